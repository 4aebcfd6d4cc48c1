//! dare's first solution: the structure-preserving doubling algorithm.

use nalgebra::DMatrix;

use super::{Data, Kind, symmetrise};
use crate::error::{LtiError, Result};
use crate::numeric::linalg::norms::frobenius;

/// The most doubling steps (quadratic convergence: ρ(A_cl)^(2^k); 60 steps cover spectral
/// radii up to 1 − 1e-16).
const MAX_DOUBLING: usize = 60;

/// The structure-preserving doubling algorithm for the discrete equation (module docs).
pub(super) fn doubling(d: &Data) -> Result<DMatrix<f64>> {
    let n = d.a.nrows();
    let mut ak = d.at.clone();
    let mut gk = d.g.clone();
    let mut hk = d.qt.clone();
    let id = DMatrix::<f64>::identity(n, n);
    for _ in 0..MAX_DOUBLING {
        let w = &id + &gk * &hk;
        let lu = w.lu();
        let (Some(v1), Some(v2)) = (lu.solve(&ak), lu.solve(&gk)) else {
            return Err(LtiError::SingularEquation {
                equation: Kind::Discrete.equation().into(),
                reason: "no stabilising solution found: I + G·H became singular in the doubling (is [Q S; Sᵀ R] indefinite?)"
                    .into(),
            });
        };
        let a_next = &ak * &v1;
        let mut g_next = &gk + &ak * v2 * ak.transpose();
        let mut h_next = &hk + ak.transpose() * &hk * &v1;
        symmetrise(&mut g_next);
        symmetrise(&mut h_next);
        if h_next.iter().chain(g_next.iter()).any(|v| !v.is_finite()) {
            break;
        }
        let change = frobenius((&h_next - &hk).iter());
        let size = frobenius(h_next.iter());
        ak = a_next;
        gk = g_next;
        hk = h_next;
        if change <= f64::EPSILON * size || frobenius(ak.iter()) <= f64::EPSILON {
            return Ok(hk);
        }
    }
    Err(LtiError::SingularEquation {
        equation: Kind::Discrete.equation().into(),
        reason: format!(
            "no stabilising solution: the doubling did not converge in {MAX_DOUBLING} steps (the symplectic pencil has eigenvalues on or extremely close to the unit circle)"
        ),
    })
}
