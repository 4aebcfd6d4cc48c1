//! The linear-quadratic regulator: the state feedback u = −K x minimising
//! ∫ (xᵀQx + uᵀRu + 2xᵀSu) dt (continuous) or Σ (xᵀQx + uᵀRu + 2xᵀSu) (discrete), from the
//! stabilising solution X of the algebraic Riccati equation
//!
//! - continuous (CARE): AᵀX + XA − (XB + S)R⁻¹(BᵀX + Sᵀ) + Q = 0, K = R⁻¹(BᵀX + Sᵀ);
//! - discrete (DARE): AᵀXA − X − (AᵀXB + S)(R + BᵀXB)⁻¹(BᵀXA + Sᵀ) + Q = 0,
//!   K = (R + BᵀXB)⁻¹(BᵀXA + Sᵀ)
//!
//! (MATLAB's `lqr`/`dlqr`, python-control's `lqr`/`dlqr`). The plant's domain decides which.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::riccati::{Riccati, care, dare};
use super::weights::{check_positive_definite, check_size, check_symmetric, symmetric_part};
use crate::error::Result;
use crate::lti::StateSpace;

/// A linear-quadratic regulator.
#[derive(Debug, Clone)]
pub struct Lqr {
    /// K (m × n), for u = −K x.
    pub gain: DMatrix<f64>,
    /// The stabilising solution X of the Riccati equation (symmetric n × n; the optimal
    /// cost from x₀ is x₀ᵀXx₀).
    pub x: DMatrix<f64>,
    /// The eigenvalues of A − BK (in s, or in z for a discrete plant).
    pub closed_loop: Vec<Complex64>,
    /// The Riccati solver's relative residual.
    pub residual: f64,
    /// The Riccati solver's condition estimate.
    pub condition: f64,
}

impl From<Riccati> for Lqr {
    fn from(r: Riccati) -> Lqr {
        Lqr {
            gain: r.gain,
            x: r.x,
            closed_loop: r.closed_loop,
            residual: r.residual,
            condition: r.condition,
        }
    }
}

/// The LQR of a state-space plant with state weight Q (n × n, symmetric positive
/// semidefinite, or with S: Q − SR⁻¹Sᵀ so), input weight R (m × m, symmetric positive
/// definite) and an optional cross weight S (n × m); CARE for a continuous plant, DARE for a
/// discrete one.
///
/// Errors: weights of the wrong size, NaN/∞, asymmetric Q or R, R not positive definite,
/// more than [`crate::limits::MAX_DESIGN_STATES`] states,
/// and the Riccati solver's (no stabilising solution: (A, B) not stabilisable, or an
/// undetectable mode on the stability boundary).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::StateSpace;
/// use ltikit::analysis::design::lqr;
/// // the double integrator with Q = I, R = 1: K = [1, √3]
/// let ss = StateSpace::new(
///     DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]),
///     DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
///     DMatrix::from_row_slice(1, 2, &[1.0, 0.0]),
///     DMatrix::zeros(1, 1),
/// ).unwrap();
/// let d = lqr(&ss, &DMatrix::identity(2, 2), &DMatrix::identity(1, 1), None).unwrap();
/// assert!((d.gain[(0, 0)] - 1.0).abs() < 1e-12);
/// assert!((d.gain[(0, 1)] - 3f64.sqrt()).abs() < 1e-12);
/// assert!(d.closed_loop.iter().all(|p| p.re < 0.0));
/// ```
pub fn lqr(
    ss: &StateSpace,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    s: Option<&DMatrix<f64>>,
) -> Result<Lqr> {
    let (n, m) = super::place::check_pair(&ss.a, &ss.b)?;
    crate::limits::DESIGN_STATES.check("`a`", n as u128)?;
    let states = format!("the plant has {n} state{}", if n == 1 { "" } else { "s" });
    let inputs = format!("the plant has {m} input{}", if m == 1 { "" } else { "s" });
    check_size(q, n, n, "`q`", &states)?;
    check_size(r, m, m, "`r`", &inputs)?;
    check_symmetric(q, "`q`")?;
    check_positive_definite(r, "`r`")?;
    if let Some(s) = s {
        check_size(s, n, m, "`s`", &format!("{states}, {inputs}"))?;
    }
    let (q, r) = (symmetric_part(q), symmetric_part(r));
    let sol = if ss.domain.is_discrete() {
        dare(&ss.a, &ss.b, &q, &r, s)?
    } else {
        care(&ss.a, &ss.b, &q, &r, s)?
    };
    Ok(sol.into())
}
