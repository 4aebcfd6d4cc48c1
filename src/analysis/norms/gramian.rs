//! Gramians and Hankel singular values of a stable state-space model.
//!
//! The controllability Gramian P solves A·P + P·Aᵀ + B·Bᵀ = 0 (A·P·Aᵀ − P + B·Bᵀ = 0 in
//! discrete time), the observability Gramian Q solves Aᵀ·Q + Q·A + Cᵀ·C = 0 (Aᵀ·Q·A − Q + Cᵀ·C
//! = 0). Both come as Cholesky factors P = L_c·L_cᵀ, Q = L_o·L_oᵀ from Hammarling's method
//! ([`crate::numeric::linalg::lyap_cholesky`]), never by factoring a formed Gramian (which
//! loses the small directions). The Hankel singular values are the singular values of
//! L_oᵀ·L_c (= √λᵢ(P·Q)).

use nalgebra::DMatrix;
use num_complex::Complex64;
use serde::Serialize;

use crate::error::{LtiError, Result};
use crate::fmt::fmt_root;
use crate::lti::StateSpace;
use crate::numeric::linalg::CholeskySolution;
use crate::numeric::linalg::hammarling::stable_or_eigenvalue;

/// The error for an eigenvalue `p` of A that is not stable by more than rounding: Re λ ≥ −τ
/// (|λ| ≥ 1 − τ in discrete time), τ = 1000·ε·max(‖A‖_F, 1) — the rule of the Lyapunov kernel,
/// which finds it on the Schur form it computes anyway. An eigenvalue within rounding of the
/// imaginary axis (a rigid-body mode computed as −1e-17) would give a Gramian of order 1e15
/// that is nothing but rounding.
fn unstable(p: Complex64, discrete: bool) -> LtiError {
    LtiError::Undefined {
        what: "a Gramian of this model".into(),
        reason: format!(
            "A must be stable, but its eigenvalue {} = {} lies {} (the model is not stable: \
             remove the mode, e.g. a rigid-body mode, or shift it)",
            if discrete { "z" } else { "s" },
            fmt_root(p, 6),
            if discrete {
                "on or outside the unit circle (within rounding)"
            } else {
                "on the imaginary axis or in the right half plane (within rounding)"
            }
        ),
    }
}

/// Which Gramian.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum GramianKind {
    /// P: A·P + P·Aᵀ + B·Bᵀ = 0.
    Controllability,
    /// Q: Aᵀ·Q + Q·A + Cᵀ·C = 0.
    Observability,
}

/// A Gramian as its Cholesky factor.
#[derive(Debug, Clone)]
pub struct Gramian {
    /// Which one.
    pub kind: GramianKind,
    /// L, lower triangular, with the Gramian = L·Lᵀ.
    pub factor: DMatrix<f64>,
    /// Relative residual of L·Lᵀ in its Lyapunov equation.
    pub residual: f64,
}

impl Gramian {
    /// The Gramian itself, L·Lᵀ.
    pub fn matrix(&self) -> DMatrix<f64> {
        &self.factor * self.factor.transpose()
    }
}

/// The controllability or observability Gramian of a stable model (continuous or discrete).
///
/// Errors: A not stable (naming the eigenvalue), more states than
/// [`crate::limits::MAX_NORM_STATES`], those of the Lyapunov solver.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::StateSpace;
/// use ltikit::analysis::norms::{GramianKind, gramian};
/// // 1/(s + 2) realised as ẋ = −2x + u, y = x: P = 1/4
/// let one = |x: f64| DMatrix::from_element(1, 1, x);
/// let ss = StateSpace::new(one(-2.0), one(1.0), one(1.0), one(0.0)).unwrap();
/// let p = gramian(&ss, GramianKind::Controllability).unwrap();
/// assert!((p.matrix()[(0, 0)] - 0.25).abs() < 1e-16 && p.residual < 1e-15);
/// ```
pub fn gramian(ss: &StateSpace, kind: GramianKind) -> Result<Gramian> {
    crate::limits::NORM_STATES.check_usize("states", ss.order())?;
    let (a, b) = match kind {
        GramianKind::Controllability => (ss.a.clone(), ss.b.clone()),
        GramianKind::Observability => (ss.a.transpose(), ss.c.transpose()),
    };
    let discrete = ss.domain.is_discrete();
    let CholeskySolution { l, residual } =
        stable_or_eigenvalue(&a, &b, discrete)?.map_err(|p| unstable(p, discrete))?;
    Ok(Gramian {
        kind,
        factor: l,
        residual,
    })
}

/// The Hankel singular values σ₁ ≥ σ₂ ≥ … ≥ σₙ ≥ 0 of a stable model with the two Gramian
/// factors they come from.
#[derive(Debug, Clone)]
pub struct HankelSingularValues {
    /// σᵢ, largest first (n of them).
    pub values: Vec<f64>,
    /// P = L_c·L_cᵀ.
    pub controllability: Gramian,
    /// Q = L_o·L_oᵀ.
    pub observability: Gramian,
}

/// The Hankel singular values (singular values of L_oᵀ·L_c; see the [module docs](self)).
///
/// Errors: as [`gramian`].
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::StateSpace;
/// use ltikit::analysis::norms::hankel_singular_values;
/// // 1/(s + a): P = 1/(2a), Q = 1/(2a), σ = 1/(2a)
/// let one = |x: f64| DMatrix::from_element(1, 1, x);
/// let ss = StateSpace::new(one(-1.0), one(1.0), one(1.0), one(0.0)).unwrap();
/// let h = hankel_singular_values(&ss).unwrap();
/// assert!((h.values[0] - 0.5).abs() < 4e-16);
/// ```
pub fn hankel_singular_values(ss: &StateSpace) -> Result<HankelSingularValues> {
    let controllability = gramian(ss, GramianKind::Controllability)?;
    let observability = gramian(ss, GramianKind::Observability)?;
    let m = observability.factor.transpose() * &controllability.factor;
    let mut values: Vec<f64> = if m.is_empty() {
        Vec::new()
    } else {
        m.svd(false, false)
            .singular_values
            .iter()
            .copied()
            .collect()
    };
    values.sort_by(|a, b| b.total_cmp(a));
    Ok(HankelSingularValues {
        values,
        controllability,
        observability,
    })
}
