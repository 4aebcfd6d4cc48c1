//! Square-root balanced truncation (Laub 1987; Tombs & Postlethwaite 1987): with the Gramian
//! factors P = L_c·L_cᵀ, Q = L_o·L_oᵀ and the SVD L_oᵀ·L_c = U·Σ·Vᵀ, the projections
//! T_l = Σ_k^(−1/2)·U_kᵀ·L_oᵀ and T_r = L_c·V_k·Σ_k^(−1/2) give the reduced model
//! (T_l·A·T_r, T_l·B, C·T_r, D) of order k — the balanced realisation truncated, without ever
//! forming it. The a priori bound ‖G − G_r‖∞ ≤ 2·Σ_{i>k} σᵢ (Glover 1984; Enns 1984; the same
//! in discrete time) is reported beside the measured error, the certified H∞ norm of G − G_r
//! ([`super::hinf_norm`]).

use nalgebra::DMatrix;

use super::gramian::{HankelSingularValues, hankel_singular_values};
use super::hinf::{PeakGain, hinf_norm};
use crate::error::{LtiError, Result};
use crate::lti::StateSpace;

/// What the reduced order is chosen by.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ReducedOrder {
    /// Exactly this order.
    Order(usize),
    /// The smallest order whose bound 2·Σ_{i>k} σᵢ is at most this.
    Error(f64),
}

/// A balanced truncation with its bound and measured error.
#[derive(Debug, Clone)]
pub struct BalancedTruncation {
    /// The reduced model (order k, same domain, D kept).
    pub reduced: StateSpace,
    /// The Hankel singular values of the full model, largest first.
    pub hsv: Vec<f64>,
    /// The a priori bound 2·Σ_{i>k} σᵢ.
    pub bound: f64,
    /// The certified ‖G − G_r‖∞.
    pub error: PeakGain,
    /// Relative residuals of the controllability and observability Gramians.
    pub residuals: (f64, f64),
}

/// Balanced truncation of a stable model to an order or an error bound (see the
/// [module docs](self)).
///
/// Errors: A not stable (naming the eigenvalue); an order above the number of states or of
/// non-zero Hankel singular values (the model's minimal order); a negative or non-finite
/// error; those of the solvers.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::StateSpace;
/// use ltikit::analysis::norms::{ReducedOrder, balanced_truncation};
/// // 1/(s + 1) + 0.01/(s + 10): dropping the fast mode
/// let ss = StateSpace::new(
///     DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -10.0]),
///     DMatrix::from_row_slice(2, 1, &[1.0, 0.1]),
///     DMatrix::from_row_slice(1, 2, &[1.0, 0.1]),
///     DMatrix::zeros(1, 1),
/// ).unwrap();
/// let r = balanced_truncation(&ss, ReducedOrder::Order(1)).unwrap();
/// assert_eq!(r.reduced.order(), 1);
/// // the measured error (a certified interval) against the bound 2σ₂
/// assert!(r.error.lower <= r.bound * (1.0 + 1e-12) && r.bound < 1e-3);
/// ```
pub fn balanced_truncation(ss: &StateSpace, order: ReducedOrder) -> Result<BalancedTruncation> {
    let h = hankel_singular_values(ss)?;
    let n = ss.order();
    let tail = |k: usize| 2.0 * h.values[k.min(n)..].iter().sum::<f64>();
    let top = h.values.first().copied().unwrap_or(0.0);
    let rank = h
        .values
        .iter()
        .take_while(|&&s| s > top * f64::EPSILON * n.max(1) as f64)
        .count();
    let k = match order {
        ReducedOrder::Order(k) => {
            if k > n {
                return Err(LtiError::invalid(format!(
                    "the reduced order {k} exceeds the model's {n} states"
                )));
            }
            if k > rank {
                return Err(LtiError::invalid(format!(
                    "the reduced order {k} exceeds the {rank} non-zero Hankel singular values \
                     (the model's minimal order): choose k ≤ {rank}"
                )));
            }
            k
        }
        ReducedOrder::Error(e) => {
            if !(e.is_finite() && e >= 0.0) {
                return Err(LtiError::InvalidParameter {
                    name: "error".into(),
                    value: e,
                    reason: "the error bound must be a finite number ≥ 0".into(),
                });
            }
            (0..=rank).find(|&k| tail(k) <= e).unwrap_or(rank)
        }
    };
    let reduced = project(ss, &h, k)?;
    let error = hinf_norm(&difference(ss, &reduced)?)?;
    Ok(BalancedTruncation {
        reduced,
        bound: tail(k),
        hsv: h.values,
        error,
        residuals: (h.controllability.residual, h.observability.residual),
    })
}

/// The order-k projection of the square-root method.
fn project(ss: &StateSpace, h: &HankelSingularValues, k: usize) -> Result<StateSpace> {
    let lc = &h.controllability.factor;
    let lo = &h.observability.factor;
    let (n, m, p) = (ss.order(), ss.n_inputs(), ss.n_outputs());
    let (tl, tr) = if k == 0 {
        (DMatrix::zeros(0, n), DMatrix::zeros(n, 0))
    } else {
        let svd = (lo.transpose() * lc).svd(true, true);
        let (Some(u), Some(vt)) = (svd.u, svd.v_t) else {
            return Err(LtiError::invalid("the SVD of L_oᵀ·L_c failed"));
        };
        // nalgebra's singular values are not sorted: order them
        let mut idx: Vec<usize> = (0..svd.singular_values.len()).collect();
        idx.sort_by(|&i, &j| svd.singular_values[j].total_cmp(&svd.singular_values[i]));
        let idx = &idx[..k];
        let scale: Vec<f64> = idx
            .iter()
            .map(|&i| 1.0 / svd.singular_values[i].sqrt())
            .collect();
        let uk = DMatrix::from_fn(n, k, |r, c| u[(r, idx[c])] * scale[c]);
        let vk = DMatrix::from_fn(n, k, |r, c| vt[(idx[c], r)] * scale[c]);
        (uk.transpose() * lo.transpose(), lc * vk)
    };
    let a = &tl * &ss.a * &tr;
    let b = if k == 0 {
        DMatrix::zeros(0, m)
    } else {
        &tl * &ss.b
    };
    let c = if k == 0 {
        DMatrix::zeros(p, 0)
    } else {
        &ss.c * &tr
    };
    Ok(StateSpace::new(a, b, c, ss.d.clone())?.with_domain(ss.domain))
}

/// G − G_r as one state-space model: (diag(A, A_r), [B; B_r], [C, −C_r], D − D_r).
fn difference(g: &StateSpace, r: &StateSpace) -> Result<StateSpace> {
    let (n, k) = (g.order(), r.order());
    let (m, p) = (g.n_inputs(), g.n_outputs());
    let mut a = DMatrix::zeros(n + k, n + k);
    a.view_mut((0, 0), (n, n)).copy_from(&g.a);
    a.view_mut((n, n), (k, k)).copy_from(&r.a);
    let mut b = DMatrix::zeros(n + k, m);
    b.view_mut((0, 0), (n, m)).copy_from(&g.b);
    b.view_mut((n, 0), (k, m)).copy_from(&r.b);
    let mut c = DMatrix::zeros(p, n + k);
    c.view_mut((0, 0), (p, n)).copy_from(&g.c);
    c.view_mut((0, n), (p, k)).copy_from(&(-&r.c));
    Ok(StateSpace::new(a, b, c, &g.d - &r.d)?.with_domain(g.domain))
}
