//! The rigid pendulum of seed §2.3.1 (eq. 2.15): a bar of mass M and length L swinging about
//! its end, viscous friction torque C θ̇, driven by a torque τ.
//!
//! θ̈ = −(3C/(M L²)) θ̇ − (3g/(2L)) sin θ + 3τ/(M L²);  x = [θ, θ̇], u = \[τ\], y = θ.
//!
//! Equilibria for a constant torque τ: sin θ̄ = 2τ/(M g L), θ̇ = 0 — for τ = 0 the hanging
//! θ̄ = 0 and the upright θ̄ = π (all others differ by 2π). Linearisation (seed eq. 2.18):
//! A = [[0, 1], [−(3g/(2L)) cos θ̄, −3C/(M L²)]], B = [0, 3/(M L²)]ᵀ.

use crate::error::Result;
use crate::lti::params::{Constraint, ModelParam, check_values, named, param};
use crate::nonlinear::system::{NonlinearSystem, Scalar, SystemInfo};

/// Parameters of `pendulum`: M, L, C, g.
pub const PENDULUM_PARAMS: &[ModelParam] = &[
    param("M", 1.0, "kg", "mass of the bar", Constraint::Positive),
    param("L", 1.0, "m", "length of the bar", Constraint::Positive),
    param(
        "C",
        0.5,
        "N·m·s/rad",
        "viscous friction torque constant",
        Constraint::NonNegative,
    ),
    param(
        "g",
        9.81,
        "m/s²",
        "gravitational acceleration",
        Constraint::Positive,
    ),
];

/// The pendulum of seed eq. 2.15.
///
/// ```
/// use ltikit::nonlinear::{models::Pendulum, SystemInfo};
/// let p = Pendulum::new(1.0, 1.0, 0.5, 9.81).unwrap();
/// assert!((p.omega() - (1.5f64 * 9.81).sqrt()).abs() < 1e-15);
/// assert_eq!(p.closed_form_equilibria(&[0.0]).unwrap().len(), 2);
/// assert!(Pendulum::new(1.0, 0.0, 0.5, 9.81).is_err()); // L ≤ 0
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pendulum {
    /// Mass M (kg).
    pub m: f64,
    /// Length L (m).
    pub l: f64,
    /// Friction constant C (N·m·s/rad).
    pub c: f64,
    /// Gravity g (m/s²).
    pub g: f64,
}

impl Default for Pendulum {
    fn default() -> Self {
        Pendulum {
            m: 1.0,
            l: 1.0,
            c: 0.5,
            g: 9.81,
        }
    }
}

impl Pendulum {
    /// Validated constructor (M, L, g > 0, C ≥ 0).
    pub fn new(m: f64, l: f64, c: f64, g: f64) -> Result<Self> {
        Self::from_values(&[m, l, c, g])
    }

    /// From values in the order of [`PENDULUM_PARAMS`].
    pub fn from_values(v: &[f64]) -> Result<Self> {
        check_values(PENDULUM_PARAMS, v)?;
        Ok(Pendulum {
            m: v[0],
            l: v[1],
            c: v[2],
            g: v[3],
        })
    }

    /// Small-oscillation angular frequency ω = √(3g/(2L)) (seed eq. 2.19).
    pub fn omega(&self) -> f64 {
        (3.0 * self.g / (2.0 * self.l)).sqrt()
    }

    /// The coefficient 3C/(M L²) of θ̇.
    pub fn damping(&self) -> f64 {
        3.0 * self.c / (self.m * self.l * self.l)
    }

    /// The input gain 3/(M L²).
    pub fn input_gain(&self) -> f64 {
        3.0 / (self.m * self.l * self.l)
    }
}

impl SystemInfo for Pendulum {
    fn nx(&self) -> usize {
        2
    }
    fn nu(&self) -> usize {
        1
    }
    fn ny(&self) -> usize {
        1
    }
    fn model_name(&self) -> String {
        "pendulum".into()
    }
    fn params(&self) -> Vec<(String, f64)> {
        named(PENDULUM_PARAMS, &[self.m, self.l, self.c, self.g])
    }
    fn state_names(&self) -> Vec<String> {
        vec!["theta".into(), "theta_dot".into()]
    }
    fn input_names(&self) -> Vec<String> {
        vec!["tau".into()]
    }
    fn output_names(&self) -> Vec<String> {
        vec!["theta".into()]
    }

    /// sin θ̄ = 2τ/(M g L): two equilibria in [−π/2, 3π/2) when |2τ/(MgL)| < 1 (θ̄ = 0 and π
    /// for τ = 0), one at the fold |2τ/(MgL)| = 1, none beyond.
    fn closed_form_equilibria(&self, u: &[f64]) -> Option<Vec<Vec<f64>>> {
        let s = 2.0 * u.first().copied().unwrap_or(0.0) / (self.m * self.g * self.l);
        if s.abs() > 1.0 {
            return Some(Vec::new());
        }
        let a = s.asin();
        let b = std::f64::consts::PI - a;
        if (b - a).abs() <= f64::EPSILON {
            return Some(vec![vec![a, 0.0]]);
        }
        Some(vec![vec![a, 0.0], vec![b, 0.0]])
    }

    /// Released at rest from θ = 1 rad.
    fn default_initial_state(&self) -> Vec<f64> {
        vec![1.0, 0.0]
    }

    /// Without friction (C = 0) the energy ½θ̇² + ω²(1 − cos θ), ω² = 3g/(2L), is conserved.
    fn conserved_names(&self) -> Vec<String> {
        if self.c == 0.0 {
            vec!["E".into()]
        } else {
            Vec::new()
        }
    }

    /// The height of the potential barrier, 2ω².
    fn conserved_scales(&self) -> Vec<f64> {
        vec![2.0 * self.omega() * self.omega()]
    }
}

impl NonlinearSystem for Pendulum {
    fn f<D: Scalar>(&self, x: &[D], u: &[D], dx: &mut [D]) {
        let w2 = 3.0 * self.g / (2.0 * self.l);
        dx[0] = x[1];
        dx[1] = -(x[1] * self.damping()) - x[0].sin() * w2 + u[0] * self.input_gain();
    }
    fn h<D: Scalar>(&self, x: &[D], _u: &[D], y: &mut [D]) {
        y[0] = x[0];
    }
    fn conserved<D: Scalar>(&self, x: &[D], c: &mut [D]) {
        if let Some(e) = c.first_mut() {
            let w2 = 3.0 * self.g / (2.0 * self.l);
            *e = x[1] * x[1] * 0.5 - (x[0].cos() - 1.0) * w2;
        }
    }
}
