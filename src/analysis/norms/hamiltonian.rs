//! The Hamiltonian test of the H∞ iteration: for γ > σ_max(D) and A without imaginary-axis
//! eigenvalues, γ is a singular value of G(jω) exactly when jω is an eigenvalue of
//!
//! ```text
//! H(γ) = [ A + B R⁻¹ Dᵀ C        B R⁻¹ Bᵀ              ]     R = γ² I − Dᵀ D
//!        [ −Cᵀ (I + D R⁻¹ Dᵀ) C  −(A + B R⁻¹ Dᵀ C)ᵀ    ]
//! ```
//!
//! (Boyd, Balakrishnan & Kabamba 1989; Zhou, Doyle & Glover, *Robust and Optimal Control*,
//! Lemma 4.7). An eigenvalue counts as imaginary when its real part is within
//! [`IMAGINARY_TOL`]·‖H‖_F of 0; the iteration confirms each such frequency by evaluating
//! G there.

use nalgebra::DMatrix;

use crate::error::{LtiError, Result};
use crate::numeric::linalg::schur_eigenvalues;

/// Relative tolerance (to ‖H‖_F) under which an eigenvalue's real part counts as zero.
pub(crate) const IMAGINARY_TOL: f64 = 1e-8;

/// A continuous-time system (A, B, C, D) whose Hamiltonian is formed for any γ.
#[derive(Debug, Clone)]
pub(crate) struct Hamiltonian {
    pub(crate) a: DMatrix<f64>,
    pub(crate) b: DMatrix<f64>,
    pub(crate) c: DMatrix<f64>,
    pub(crate) d: DMatrix<f64>,
}

impl Hamiltonian {
    /// H(γ) (γ must exceed σ_max(D)).
    pub(crate) fn matrix(&self, gamma: f64) -> Result<DMatrix<f64>> {
        let n = self.a.nrows();
        let m = self.b.ncols();
        let p = self.c.nrows();
        let dt = self.d.transpose();
        let r = DMatrix::identity(m, m) * (gamma * gamma) - &dt * &self.d;
        let r_inv = r
            .cholesky()
            .map(|ch| ch.inverse())
            .ok_or_else(|| LtiError::Undefined {
                what: "the Hamiltonian of the H∞ test".into(),
                reason: format!(
                    "γ = {} does not exceed σ_max(D) (γ²I − DᵀD is not positive definite)",
                    crate::fmt::fmt_num(gamma)
                ),
            })?;
        let br = &self.b * &r_inv;
        let a_g = &self.a + &br * &dt * &self.c;
        let h12 = &br * self.b.transpose();
        let s = DMatrix::identity(p, p) + &self.d * &r_inv * &dt;
        let h21 = -(self.c.transpose() * s * &self.c);
        let mut h = DMatrix::zeros(2 * n, 2 * n);
        h.view_mut((0, 0), (n, n)).copy_from(&a_g);
        h.view_mut((0, n), (n, n)).copy_from(&h12);
        h.view_mut((n, 0), (n, n)).copy_from(&h21);
        h.view_mut((n, n), (n, n)).copy_from(&(-a_g.transpose()));
        Ok(h)
    }

    /// The frequencies ω ≥ 0 of the (numerically) imaginary eigenvalues jω of H(γ), sorted.
    pub(crate) fn imaginary_frequencies(&self, gamma: f64) -> Result<Vec<f64>> {
        let h = self.matrix(gamma)?;
        if !h.iter().all(|x| x.is_finite()) {
            return Err(LtiError::Overflow {
                what: "the Hamiltonian of the H∞ test".into(),
                reason: format!(" at γ = {}", crate::fmt::fmt_num(gamma)),
            });
        }
        let scale = h.norm();
        let ev = schur_eigenvalues(&h)?;
        let mut w: Vec<f64> = ev
            .iter()
            .filter(|l| l.im >= 0.0 && l.re.abs() <= IMAGINARY_TOL * scale)
            .map(|l| l.im)
            .collect();
        w.sort_by(f64::total_cmp);
        w.dedup_by(|a, b| (*a - *b).abs() <= f64::EPSILON * scale);
        Ok(w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossings_of_a_first_order_lag() {
        // G = 1/(s + 1): |G(jω)| = γ at ω = √(1/γ² − 1) for γ < 1, none for γ > 1
        let one = |x: f64| DMatrix::from_element(1, 1, x);
        let h = Hamiltonian {
            a: one(-1.0),
            b: one(1.0),
            c: one(1.0),
            d: one(0.0),
        };
        let w = h.imaginary_frequencies(0.5).unwrap();
        assert_eq!(w.len(), 1);
        assert!((w[0] - 3f64.sqrt()).abs() < 1e-14, "{w:?}");
        assert!(h.imaginary_frequencies(1.01).unwrap().is_empty());
        // with D = 0.5: G = (0.5 s + 1.5)/(s + 1), |G| from 1.5 down to 0.5; γ = 1 crosses at
        // (0.25ω² + 2.25) = ω² + 1 → ω = √(5/3)
        let h = Hamiltonian { d: one(0.5), ..h };
        let w = h.imaginary_frequencies(1.0).unwrap();
        assert!((w[0] - (5.0f64 / 3.0).sqrt()).abs() < 1e-14, "{w:?}");
        assert!(h.imaginary_frequencies(0.4).is_err());
    }
}
