//! The seed's "van der Pol" oscillator (§2.3.2, eqs. 2.36–2.37; exercise 2.9):
//! ẋ₁ = −x₂ − x₁(x₁² + x₂² − 1), ẋ₂ = x₁ − x₂(x₁² + x₂² − 1). No input; y = x.
//!
//! In polar form ρ̇ = −ρ(ρ² − 1), φ̇ = 1: the unit circle is a stable limit cycle of period 2π,
//! and the origin — the only equilibrium (x·ẋ = −ρ²(ρ² − 1) vanishes only at ρ = 0 or on the
//! circle, where ẋ ≠ 0) — is an unstable focus with eigenvalues 1 ± j.

use crate::nonlinear::system::{NonlinearSystem, Scalar, SystemInfo};

/// The seed's van der Pol oscillator (no parameters).
///
/// ```
/// use ltikit::nonlinear::{models::VanDerPol, jacobians};
/// let j = jacobians(&VanDerPol, &[0.0, 0.0], &[]).unwrap();
/// assert_eq!(j.a.as_slice(), &[1.0, 1.0, -1.0, 1.0]); // column-major [[1, −1], [1, 1]]
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct VanDerPol;

impl SystemInfo for VanDerPol {
    fn nx(&self) -> usize {
        2
    }
    fn nu(&self) -> usize {
        0
    }
    fn ny(&self) -> usize {
        2
    }
    fn model_name(&self) -> String {
        "vanderpol".into()
    }
    fn output_names(&self) -> Vec<String> {
        self.state_names()
    }
    fn closed_form_equilibria(&self, _u: &[f64]) -> Option<Vec<Vec<f64>>> {
        Some(vec![vec![0.0, 0.0]])
    }

    /// [0.001, 0] (seed exercise 2.9: it spirals out to the limit cycle).
    fn default_initial_state(&self) -> Vec<f64> {
        vec![0.001, 0.0]
    }

    fn default_horizon(&self) -> f64 {
        20.0
    }
}

impl NonlinearSystem for VanDerPol {
    fn f<D: Scalar>(&self, x: &[D], _u: &[D], dx: &mut [D]) {
        let rho2m1 = x[0] * x[0] + x[1] * x[1] - 1.0;
        dx[0] = -x[1] - x[0] * rho2m1;
        dx[1] = x[0] - x[1] * rho2m1;
    }
    fn h<D: Scalar>(&self, x: &[D], _u: &[D], y: &mut [D]) {
        y.copy_from_slice(&x[..2]);
    }
}
