//! The gain of a state-space model at one frequency, σ_max(G(jω)) (σ_max(G(e^(jωT))) in
//! discrete time), evaluated accurately on the Hessenberg form of A
//! ([`HessenbergResponse`]): the lower bounds of the H∞ iteration and the points of a sigma
//! plot.

use nalgebra::DMatrix;
use num_complex::Complex64;

use crate::error::Result;
use crate::lti::StateSpace;
use crate::numeric::linalg::HessenbergResponse;

/// G(s) of a model, ready for evaluation at any point of its frequency axis.
#[derive(Debug, Clone)]
pub(crate) struct GainEvaluator {
    response: Option<HessenbergResponse>,
    d: DMatrix<f64>,
    dt: Option<f64>,
}

impl GainEvaluator {
    /// Reduces the model once.
    pub(crate) fn new(ss: &StateSpace) -> Result<GainEvaluator> {
        let response = if ss.order() == 0 {
            None
        } else {
            Some(HessenbergResponse::new(&ss.a, &ss.b, &ss.c, &ss.d)?)
        };
        Ok(GainEvaluator {
            response,
            d: ss.d.clone(),
            dt: ss.domain.dt(),
        })
    }

    /// G at the frequency ω (rad/s): s = jω, or z = e^(jωT). ω = ∞ (continuous) is D.
    pub(crate) fn matrix(&self, w: f64) -> DMatrix<Complex64> {
        let point = match self.dt {
            Some(dt) => Complex64::from_polar(1.0, w * dt),
            None if w.is_infinite() => return self.d.map(|x| Complex64::new(x, 0.0)),
            None => Complex64::new(0.0, w),
        };
        match &self.response {
            Some(r) => r.eval(point),
            None => self.d.map(|x| Complex64::new(x, 0.0)),
        }
    }

    /// The singular values of G at ω, largest first.
    pub(crate) fn singular_values(&self, w: f64) -> Vec<f64> {
        singular_values(&self.matrix(w))
    }

    /// σ_max(G) at ω.
    pub(crate) fn sigma_max(&self, w: f64) -> f64 {
        let g = self.matrix(w);
        if g.len() == 1 {
            return g[(0, 0)].norm();
        }
        singular_values(&g).first().copied().unwrap_or(0.0)
    }
}

/// Singular values of a complex matrix, largest first (|g| for 1×1).
pub(crate) fn singular_values(g: &DMatrix<Complex64>) -> Vec<f64> {
    if g.is_empty() {
        return Vec::new();
    }
    if g.len() == 1 {
        return vec![g[(0, 0)].norm()];
    }
    let mut s: Vec<f64> = g
        .clone()
        .svd(false, false)
        .singular_values
        .iter()
        .copied()
        .collect();
    s.sort_by(|a, b| b.total_cmp(a));
    s
}

/// σ_max of a real matrix (0 for an empty one).
pub(crate) fn sigma_max_real(m: &DMatrix<f64>) -> f64 {
    if m.is_empty() {
        return 0.0;
    }
    m.clone()
        .svd(false, false)
        .singular_values
        .iter()
        .copied()
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn siso_gain_and_mimo_singular_values() {
        // G(s) = 1/(s + 1): |G(j)| = 1/√2
        let ss = StateSpace::new(
            DMatrix::from_element(1, 1, -1.0),
            DMatrix::from_element(1, 1, 1.0),
            DMatrix::from_element(1, 1, 1.0),
            DMatrix::zeros(1, 1),
        )
        .unwrap();
        let g = GainEvaluator::new(&ss).unwrap();
        assert!((g.sigma_max(1.0) - 0.5f64.sqrt()).abs() < 1e-16);
        assert!(g.sigma_max(f64::INFINITY).abs() < f64::MIN_POSITIVE);
        // diag(3, 4) as a static 2×2 gain: singular values 4, 3
        let m =
            DMatrix::from_row_slice(2, 2, &[3.0, 0.0, 0.0, -4.0]).map(|x| Complex64::new(x, 0.0));
        assert_eq!(singular_values(&m), vec![4.0, 3.0]);
    }
}
