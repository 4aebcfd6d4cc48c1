//! The linear-quadratic-Gaussian controller: an LQR on the estimate of a Kalman filter, as
//! one state-space model from the measurement y to the control u.
//!
//! ```text
//! x̂' = (A − BK − LC + LDK) x̂ + L y,    u = −K x̂
//! ```
//!
//! **Sign convention: negative feedback.** [`Lqg::controller`] is the model
//! H = (A − BK − LC + LDK, L, K, 0), so that u = −H y: it is the controller C of the usual
//! loop u = C·(r − y) (unity negative feedback, `--controller`), and
//! `plant.feedback(&lqg.controller, -1.0)` is the closed loop. By the separation principle
//! its eigenvalues are those of A − BK and of A − LC. A discrete plant gets the predictor
//! form (x̂\[k+1\] = … , the Kalman predictor gain of [`super::kalman`]).

use nalgebra::DMatrix;

use super::kalman::{Kalman, NoiseInput, lqe};
use super::lqr::{Lqr, lqr};
use crate::error::Result;
use crate::lti::StateSpace;

/// An LQG design: the regulator, the estimator and the controller they make.
#[derive(Debug, Clone)]
pub struct Lqg {
    /// The state feedback (K, X, eig(A − BK)).
    pub regulator: Lqr,
    /// The estimator (L, P, eig(A − LC)).
    pub estimator: Kalman,
    /// The controller H from y to −u (n states, p inputs, m outputs), in the plant's domain.
    pub controller: StateSpace,
}

/// The LQG controller of a plant: [`lqr()`] with weights Q, R and [`lqe`] with covariances Qn,
/// Rn (no cross terms), joined as an observer-based compensator (see the
/// [module docs](self)).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::StateSpace;
/// use ltikit::analysis::design::{NoiseInput, lqg};
/// let ss = StateSpace::new(
///     DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]),
///     DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
///     DMatrix::from_row_slice(1, 2, &[1.0, 0.0]),
///     DMatrix::zeros(1, 1),
/// ).unwrap();
/// let id = |k| DMatrix::<f64>::identity(k, k);
/// let d = lqg(&ss, &id(2), &id(1), &id(1), &id(1), Some(NoiseInput::Inputs)).unwrap();
/// // the closed loop has the regulator's and the estimator's poles
/// let cl = ss.feedback(&d.controller, -1.0).unwrap();
/// let ev = ltikit::numeric::eigenvalues(&cl.a).unwrap();
/// assert_eq!(ev.len(), 4);
/// assert!(ev.iter().all(|z| z.re < 0.0));
/// ```
pub fn lqg(
    ss: &StateSpace,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    qn: &DMatrix<f64>,
    rn: &DMatrix<f64>,
    noise: Option<NoiseInput>,
) -> Result<Lqg> {
    let regulator = lqr(ss, q, r, None)?;
    let estimator = lqe(ss, qn, rn, None, noise)?;
    let controller = compensator(ss, &regulator.gain, &estimator.gain)?;
    Ok(Lqg {
        regulator,
        estimator,
        controller,
    })
}

/// The observer-based compensator (A − BK − LC + LDK, L, K, 0) in the plant's domain.
pub fn compensator(ss: &StateSpace, k: &DMatrix<f64>, l: &DMatrix<f64>) -> Result<StateSpace> {
    let a = &ss.a - &ss.b * k - l * &ss.c + l * &ss.d * k;
    let d = DMatrix::zeros(k.nrows(), l.ncols());
    Ok(StateSpace::new(a, l.clone(), k.clone(), d)?.with_domain(ss.domain))
}
