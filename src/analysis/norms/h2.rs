//! The H2 norm from the controllability Gramian's Cholesky factor: ‖G‖₂ = ‖C·L_c‖_F in
//! continuous time (infinite when D ≠ 0: the impulse response has a Dirac part), and
//! √(‖C·L_c‖_F² + ‖D‖_F²) in discrete time. An unstable model (or a pole on the imaginary
//! axis or unit circle) has an infinite H2 norm, as python-control's `norm(sys, 2)` says.

use serde::Serialize;

use super::gramian::{GramianKind, gramian};
use crate::error::Result;
use crate::fmt::fmt_root;
use crate::lti::StateSpace;
use crate::numeric::linalg::schur_eigenvalues;

/// The H2 norm of a model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct H2Norm {
    /// ‖G‖₂ (∞ when infinite).
    pub value: f64,
    /// Relative residual of the Gramian it comes from (0 without states).
    pub residual: f64,
    /// Why the norm is infinite (None when finite).
    pub infinite: Option<String>,
}

/// The H2 norm (see the [module docs](self)).
///
/// Errors: more states than [`crate::limits::MAX_NORM_STATES`]; the solvers'.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::StateSpace;
/// use ltikit::analysis::norms::h2_norm;
/// // 1/(s + a): ‖G‖₂ = 1/√(2a)
/// let one = |x: f64| DMatrix::from_element(1, 1, x);
/// let ss = StateSpace::new(one(-3.0), one(1.0), one(1.0), one(0.0)).unwrap();
/// assert!((h2_norm(&ss).unwrap().value - 1.0 / 6f64.sqrt()).abs() < 1e-16);
/// let with_d = StateSpace::new(one(-3.0), one(1.0), one(1.0), one(0.5)).unwrap();
/// assert!(h2_norm(&with_d).unwrap().infinite.unwrap().contains("D"));
/// ```
pub fn h2_norm(ss: &StateSpace) -> Result<H2Norm> {
    crate::limits::NORM_STATES.check_usize("states", ss.order())?;
    let discrete = ss.domain.is_discrete();
    let infinite = |why: String| H2Norm {
        value: f64::INFINITY,
        residual: 0.0,
        infinite: Some(why),
    };
    if ss.order() > 0 {
        let var = if discrete { "z" } else { "s" };
        if let Some(p) = schur_eigenvalues(&ss.a)?.into_iter().find(|p| {
            if discrete {
                p.norm() >= 1.0
            } else {
                p.re >= 0.0
            }
        }) {
            return Ok(infinite(format!(
                "the model is not stable (eigenvalue {var} = {} of A {})",
                fmt_root(p, 6),
                if discrete {
                    "on or outside the unit circle"
                } else {
                    "in the closed right half plane"
                }
            )));
        }
    }
    let d2 = ss.d.norm_squared();
    if !discrete && d2 > 0.0 {
        return Ok(infinite(
            "the feedthrough D is not zero (the impulse response has a Dirac part)".into(),
        ));
    }
    if ss.order() == 0 {
        return Ok(H2Norm {
            value: d2.sqrt(),
            residual: 0.0,
            infinite: None,
        });
    }
    let p = gramian(ss, GramianKind::Controllability)?;
    let cl = &ss.c * &p.factor;
    Ok(H2Norm {
        value: (cl.norm_squared() + d2).sqrt(),
        residual: p.residual,
        infinite: None,
    })
}
