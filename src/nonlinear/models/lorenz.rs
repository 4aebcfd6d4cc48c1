//! The Lorenz weather model of seed §2.3.4 (eqs. 2.38–2.40):
//! ẋ₁ = σ(x₂ − x₁), ẋ₂ = r x₁ − x₂ − x₁x₃, ẋ₃ = x₁x₂ − b x₃. No input; y = x.
//!
//! Equilibria: the origin, and for r > 1 also C± = (±√(b(r−1)), ±√(b(r−1)), r−1). At the
//! origin the eigenvalues are −b and (−(σ+1) ± √((σ+1)² + 4σ(r−1)))/2.

use crate::error::Result;
use crate::lti::params::{Constraint, ModelParam, check_values, named, param};
use crate::nonlinear::system::{NonlinearSystem, Scalar, SystemInfo};

/// Parameters of `lorenz`: sigma, r, b (10, 28, 8/3 as in seed fig. 2.9).
pub const LORENZ_PARAMS: &[ModelParam] = &[
    param("sigma", 10.0, "1", "Prandtl number σ", Constraint::Positive),
    param(
        "r",
        28.0,
        "1",
        "Rayleigh number ratio r",
        Constraint::NonNegative,
    ),
    param(
        "b",
        8.0 / 3.0,
        "1",
        "geometric factor b",
        Constraint::Positive,
    ),
];

/// The Lorenz system.
///
/// ```
/// use ltikit::nonlinear::{models::Lorenz, SystemInfo};
/// let l = Lorenz::default();
/// let eq = l.closed_form_equilibria(&[]).unwrap();
/// assert_eq!(eq.len(), 3);
/// assert!((eq[1][2] - 27.0).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lorenz {
    /// σ.
    pub sigma: f64,
    /// r.
    pub r: f64,
    /// b.
    pub b: f64,
}

impl Default for Lorenz {
    fn default() -> Self {
        Lorenz {
            sigma: 10.0,
            r: 28.0,
            b: 8.0 / 3.0,
        }
    }
}

impl Lorenz {
    /// From values in the order of [`LORENZ_PARAMS`].
    pub fn from_values(v: &[f64]) -> Result<Self> {
        check_values(LORENZ_PARAMS, v)?;
        Ok(Lorenz {
            sigma: v[0],
            r: v[1],
            b: v[2],
        })
    }
}

impl SystemInfo for Lorenz {
    fn nx(&self) -> usize {
        3
    }
    fn nu(&self) -> usize {
        0
    }
    fn ny(&self) -> usize {
        3
    }
    fn model_name(&self) -> String {
        "lorenz".into()
    }
    fn params(&self) -> Vec<(String, f64)> {
        named(LORENZ_PARAMS, &[self.sigma, self.r, self.b])
    }
    fn output_names(&self) -> Vec<String> {
        self.state_names()
    }
    fn closed_form_equilibria(&self, _u: &[f64]) -> Option<Vec<Vec<f64>>> {
        let mut eq = vec![vec![0.0; 3]];
        if self.r > 1.0 {
            let s = (self.b * (self.r - 1.0)).sqrt();
            eq.push(vec![s, s, self.r - 1.0]);
            eq.push(vec![-s, -s, self.r - 1.0]);
        }
        Some(eq)
    }

    /// [1, 0, 0] (seed fig. 2.9).
    fn default_initial_state(&self) -> Vec<f64> {
        vec![1.0, 0.0, 0.0]
    }

    /// 50 s (seed fig. 2.9).
    fn default_horizon(&self) -> f64 {
        50.0
    }
}

impl NonlinearSystem for Lorenz {
    fn f<D: Scalar>(&self, x: &[D], _u: &[D], dx: &mut [D]) {
        dx[0] = (x[1] - x[0]) * self.sigma;
        dx[1] = x[0] * self.r - x[1] - x[0] * x[2];
        dx[2] = x[0] * x[1] - x[2] * self.b;
    }
    fn h<D: Scalar>(&self, x: &[D], _u: &[D], y: &mut [D]) {
        y.copy_from_slice(&x[..3]);
    }
}
