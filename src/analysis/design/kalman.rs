//! The Kalman filter gain (linear-quadratic estimator) of a plant with process noise w and
//! measurement noise v:
//!
//! ```text
//! ẋ = A x + B u + G w,   y = C x + D u + v,   E{wwᵀ} = Qn, E{vvᵀ} = Rn, E{wvᵀ} = Nn
//! ```
//!
//! The estimator x̂' = A x̂ + B u + L (y − C x̂ − D u) has the error dynamics A − LC. The
//! process noise enters either **on every state** (G = I, Qn n × n) or **through the inputs**
//! (G = B, Qn m × m): the size of Qn says which, and when n = m the caller must say
//! ([`NoiseInput`]). L comes from the dual Riccati equation (A ↦ Aᵀ, B ↦ Cᵀ, Q ↦ GQnGᵀ,
//! R ↦ Rn, S ↦ GNn):
//!
//! - continuous: AP + PAᵀ − (PCᵀ + GNn)Rn⁻¹(CP + NnᵀGᵀ) + GQnGᵀ = 0, L = (PCᵀ + GNn)Rn⁻¹
//!   (MATLAB `lqe`, python-control `lqe`), P the steady error covariance;
//! - discrete: the dual DARE and the **predictor** gain L = (APCᵀ + GNn)(Rn + CPCᵀ)⁻¹ for
//!   x̂\[k+1\] = A x̂\[k\] + B u\[k\] + L (y\[k\] − C x̂\[k\] − D u\[k\]), P the one-step
//!   prediction error covariance (the gain of MATLAB's `kalman` in its predictor form; the
//!   filter gain is M = PCᵀ(Rn + CPCᵀ)⁻¹ and L = AM when Nn = 0).

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::riccati::{care, dare};
use super::weights::{
    check_positive_definite, check_positive_semidefinite, check_size, symmetric_part,
};
use crate::error::{LtiError, Result};
use crate::lti::StateSpace;

/// Where the process noise enters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoiseInput {
    /// On every state: G = I, Qn is n × n.
    States,
    /// Through the plant's inputs: G = B, Qn is m × m.
    Inputs,
}

impl NoiseInput {
    /// "states" or "inputs".
    pub fn name(self) -> &'static str {
        match self {
            NoiseInput::States => "states",
            NoiseInput::Inputs => "inputs",
        }
    }

    /// Reads "states" or "inputs".
    ///
    /// ```
    /// use ltikit::analysis::design::NoiseInput;
    /// assert_eq!(NoiseInput::parse("inputs").unwrap(), NoiseInput::Inputs);
    /// assert!(NoiseInput::parse("both").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<NoiseInput> {
        match text.trim().to_ascii_lowercase().as_str() {
            "states" | "state" => Ok(NoiseInput::States),
            "inputs" | "input" => Ok(NoiseInput::Inputs),
            _ => Err(LtiError::invalid(format!(
                "`noise_input` '{}': write states (G = I) or inputs (G = B)",
                crate::error::abbreviate(text)
            ))),
        }
    }
}

/// A Kalman estimator.
#[derive(Debug, Clone)]
pub struct Kalman {
    /// L (n × p).
    pub gain: DMatrix<f64>,
    /// The steady error covariance P (n × n; discrete: of the one-step prediction).
    pub p: DMatrix<f64>,
    /// The eigenvalues of A − LC.
    pub estimator_poles: Vec<Complex64>,
    /// Where the process noise was taken to enter.
    pub noise_input: NoiseInput,
    /// The Riccati solver's relative residual.
    pub residual: f64,
    /// The Riccati solver's condition estimate.
    pub condition: f64,
}

/// The Kalman gain of a plant for process noise covariance `qn` (n × n on every state, or
/// m × m through the inputs), measurement noise covariance `rn` (p × p, positive definite)
/// and an optional cross covariance `nn` (rows as Qn, p columns). `noise` says where the
/// process noise enters; `None` decides by the size of Qn (and is an error when n = m).
///
/// Errors: sizes, NaN/∞, Qn not positive semidefinite, Rn not positive definite, an
/// ambiguous noise input, more than [`crate::limits::MAX_DESIGN_STATES`] states, no
/// stabilising solution ((A, C) not detectable).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::StateSpace;
/// use ltikit::analysis::design::{NoiseInput, lqe};
/// // ẋ = −x + w, y = x + v, Qn = 1, Rn = 1: P² + 2P − 1 = 0, L = P = √2 − 1
/// let one = DMatrix::from_element(1, 1, 1.0);
/// let ss = StateSpace::new(-one.clone(), one.clone(), one.clone(), one.scale(0.0)).unwrap();
/// let k = lqe(&ss, &one, &one, None, Some(NoiseInput::States)).unwrap();
/// assert!((k.gain[(0, 0)] - (2f64.sqrt() - 1.0)).abs() < 1e-12);
/// ```
pub fn lqe(
    ss: &StateSpace,
    qn: &DMatrix<f64>,
    rn: &DMatrix<f64>,
    nn: Option<&DMatrix<f64>>,
    noise: Option<NoiseInput>,
) -> Result<Kalman> {
    let (n, m) = super::place::check_pair(&ss.a, &ss.b)?;
    crate::limits::DESIGN_STATES.check("`a`", n as u128)?;
    let p = ss.c.nrows();
    if p == 0 {
        return Err(LtiError::invalid(
            "the plant has no outputs: there is nothing to estimate from",
        ));
    }
    let noise_input = noise_input_of(qn, n, m, noise)?;
    let (k, g) = match noise_input {
        NoiseInput::States => (n, DMatrix::<f64>::identity(n, n)),
        NoiseInput::Inputs => (m, ss.b.clone()),
    };
    let why = match noise_input {
        NoiseInput::States => format!("noise on each of the {n} states"),
        NoiseInput::Inputs => format!("noise through the {m} inputs"),
    };
    check_size(qn, k, k, "`qn`", &why)?;
    check_size(rn, p, p, "`rn`", &format!("the plant has {p} outputs"))?;
    check_positive_semidefinite(qn, "`qn`")?;
    check_positive_definite(rn, "`rn`")?;
    let s = match nn {
        Some(nn) => {
            check_size(nn, k, p, "`nn`", &format!("{why}, {p} outputs"))?;
            Some(&g * nn)
        }
        None => None,
    };
    let q = symmetric_part(&(&g * symmetric_part(qn) * g.transpose()));
    let r = symmetric_part(rn);
    let (at, ct) = (ss.a.transpose(), ss.c.transpose());
    let sol = if ss.domain.is_discrete() {
        dare(&at, &ct, &q, &r, s.as_ref())
    } else {
        care(&at, &ct, &q, &r, s.as_ref())
    }
    .map_err(dual_error)?;
    Ok(Kalman {
        gain: sol.gain.transpose(),
        p: sol.x,
        estimator_poles: sol.closed_loop,
        noise_input,
        residual: sol.residual,
        condition: sol.condition,
    })
}

/// The solver's error in the terms of the estimator: its (A, B) is the plant's (Aᵀ, Cᵀ), so
/// "not stabilisable" means (A, C) is not detectable.
fn dual_error(e: LtiError) -> LtiError {
    match e {
        LtiError::SingularEquation { equation, reason } => LtiError::SingularEquation {
            equation: format!("{equation} of the estimator (the dual: Aᵀ, Cᵀ)"),
            reason: reason
                .replace("(A, B) is not stabilisable", "(A, C) is not detectable")
                .replace("uncontrollable mode", "unobservable mode"),
        },
        other => other,
    }
}

/// Where the noise enters: as told (the size of Qn must then agree; a 1 × 1 Qn stands for
/// that multiple of the identity only through [`expand_scalar`]), or by the size of Qn.
fn noise_input_of(
    qn: &DMatrix<f64>,
    n: usize,
    m: usize,
    told: Option<NoiseInput>,
) -> Result<NoiseInput> {
    if let Some(t) = told {
        return Ok(t);
    }
    let size = qn.nrows();
    if n == m {
        return Err(LtiError::invalid(format!(
            "the plant has as many inputs as states ({n}): say where the process noise enters \
             (`noise_input` states: G = I, or inputs: G = B)"
        )));
    }
    match (size == n, size == m) {
        (true, true) => unreachable_sizes(),
        (true, false) => Ok(NoiseInput::States),
        (false, true) => Ok(NoiseInput::Inputs),
        (false, false) => Err(LtiError::invalid(format!(
            "`qn` must be {n}×{n} (noise on every state) or {m}×{m} (noise through the \
             inputs), got {}×{}",
            qn.nrows(),
            qn.ncols()
        ))),
    }
}

/// n ≠ m was checked: Qn cannot have both sizes.
fn unreachable_sizes() -> Result<NoiseInput> {
    Err(LtiError::invalid(
        "`qn`: the plant has as many inputs as states",
    ))
}

/// A 1 × 1 matrix c made c·I of size k (a weight given as one number); any other matrix as
/// it is.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::analysis::design::kalman::expand_scalar;
/// let q = expand_scalar(DMatrix::from_element(1, 1, 2.0), 3);
/// assert_eq!(q, DMatrix::identity(3, 3) * 2.0);
/// ```
pub fn expand_scalar(m: DMatrix<f64>, k: usize) -> DMatrix<f64> {
    if m.nrows() == 1 && m.ncols() == 1 && k > 1 {
        DMatrix::identity(k, k) * m[(0, 0)]
    } else {
        m
    }
}
