//! Relative degree and the first non-zero Markov parameter of a SISO channel, and Markov
//! parameters C·A^(k−1)·B of any system.
//!
//! G(s) = D + Σₖ≥₁ C·A^(k−1)·B / sᵏ. The relative degree r is the index of the first non-zero
//! term (0 when D ≠ 0) and that term is the channel's gain in the factored form
//! G(s) = g·Π(s − zᵢ)/Π(s − pⱼ). Deciding "non-zero" from powers of A is ill-posed in floating
//! point (‖A^k‖ grows, cancellation hides structure), so [`relative_degree`] takes r as the
//! number of steps of the zero-finding reduction ([`super::zeros`]) before D becomes
//! non-singular — a rank decision with a stated tolerance on orthogonally transformed data —
//! and g as the product of the norms compressed at each step times the final D (exact up to
//! rounding in the orthogonal transformations). [`markov_parameter`] computes C·A^(k−1)·B
//! directly (by k − 1 matrix–vector block products), a cross-check.

use nalgebra::DMatrix;

use super::zeros::{Sys, default_tol, reduce, scale_system};
use crate::error::{LtiError, Result};
use crate::numeric::balance::ldexp;

/// Relative degree and gain of a SISO channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RelativeDegree {
    /// r: 0 when D ≠ 0, otherwise the first k with C·A^(k−1)·B ≠ 0 (to the tolerance);
    /// `None` when the transfer function is identically zero.
    pub r: Option<usize>,
    /// The first non-zero Markov parameter (D when r = 0; 0 when G ≡ 0).
    pub gain: f64,
}

/// Relative degree and first non-zero Markov parameter of a SISO system (1 input, 1 output),
/// see the [module docs](self); `tol` as for [`super::invariant_zeros`].
///
/// Errors: not SISO, inconsistent dimensions, non-finite entries, a gain beyond f64.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::relative_degree;
/// // G(s) = 3(s + 4)/(s³ + 2s² + 5s + 1): r = 2, gain 3.
/// let a = DMatrix::from_row_slice(3, 3, &[-2.0, -5.0, -1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
/// let b = DMatrix::from_row_slice(3, 1, &[1.0, 0.0, 0.0]);
/// let c = DMatrix::from_row_slice(1, 3, &[0.0, 3.0, 12.0]);
/// let rd = relative_degree(&a, &b, &c, &DMatrix::zeros(1, 1), None).unwrap();
/// assert_eq!(rd.r, Some(2));
/// assert!((rd.gain - 3.0).abs() < 1e-14);
/// ```
pub fn relative_degree(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    tol: Option<f64>,
) -> Result<RelativeDegree> {
    let (n, m, p) = super::checks::check_system(a, b, c, d)?;
    if m != 1 || p != 1 {
        return Err(LtiError::invalid(format!(
            "relative degree needs a single-input single-output system, got {p} outputs and {m} inputs"
        )));
    }
    let sys = Sys {
        a: a.clone(),
        b: b.clone(),
        c: c.clone(),
        d: d.clone(),
    };
    let (scaled, (ea, eb, ec)) = scale_system(&sys);
    let norm = super::norms::frobenius(
        scaled
            .a
            .iter()
            .chain(scaled.b.iter())
            .chain(scaled.c.iter())
            .chain(scaled.d.iter()),
    );
    let abs = tol.unwrap_or_else(|| default_tol(n, 1, 1)) * norm;
    let (reduced, log) = reduce(scaled, abs);
    if reduced.c.nrows() == 0 || log.dropped > 0 {
        return Ok(RelativeDegree { r: None, gain: 0.0 });
    }
    let r = log.steps.len();
    // g' = D_f·Πβ in the scaled system; g = g'·2^(eβ+eγ)·2^(eα(r−1)) (see zeros.rs).
    let mut g = reduced.d[(0, 0)];
    for &(_, _, beta) in &log.steps {
        g *= beta;
    }
    let e = i64::from(eb) + i64::from(ec) + i64::from(ea) * (r as i64 - 1);
    let e = e.clamp(-3000, 3000) as i32;
    let gain = ldexp(g, e);
    if !gain.is_finite() {
        return Err(LtiError::NonFinite {
            what: "the first non-zero Markov parameter (beyond the range of f64)".into(),
            value: gain,
        });
    }
    Ok(RelativeDegree { r: Some(r), gain })
}

/// The Markov parameter C·A^(k−1)·B (k ≥ 1), or D for k = 0.
///
/// Errors: inconsistent dimensions, non-finite entries or result.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::markov_parameter;
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -2.0, -3.0]);
/// let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
/// let c = DMatrix::from_row_slice(1, 2, &[1.0, 0.0]);
/// let d = DMatrix::zeros(1, 1);
/// assert_eq!(markov_parameter(&a, &b, &c, &d, 1).unwrap()[(0, 0)], 0.0);
/// assert_eq!(markov_parameter(&a, &b, &c, &d, 2).unwrap()[(0, 0)], 1.0);
/// ```
pub fn markov_parameter(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    k: usize,
) -> Result<DMatrix<f64>> {
    super::checks::check_system(a, b, c, d)?;
    if k == 0 {
        return Ok(d.clone());
    }
    let mut v = b.clone();
    for _ in 1..k {
        v = a * v;
    }
    let out = c * v;
    if let Some(x) = out.iter().find(|x| !x.is_finite()) {
        return Err(LtiError::NonFinite {
            what: format!("the Markov parameter C·A^{}·B", k - 1),
            value: *x,
        });
    }
    Ok(out)
}
