//! The planar double pendulum of seed example 1.1 (fig. 1.4): point masses m1, m2 on massless
//! rods L1, L2, gravity g, with optional viscous joint damping and a torque τ at the pivot.
//! Seed §2.3.3 is left blank, so the equations are derived here.
//!
//! **Derivation** (Lagrange). Angles θ₁, θ₂ of the rods from the downward vertical,
//! counter-clockwise positive; pivot at the origin, y up:
//! p₁ = L1(sin θ₁, −cos θ₁), p₂ = p₁ + L2(sin θ₂, −cos θ₂). With Δ = θ₁ − θ₂,
//!
//!   T = ½(m1 + m2) L1² θ̇₁² + ½ m2 L2² θ̇₂² + m2 L1 L2 θ̇₁θ̇₂ cos Δ,
//!   V = −(m1 + m2) g L1 cos θ₁ − m2 g L2 cos θ₂,
//!   R = ½ c1 θ̇₁² + ½ c2 (θ̇₂ − θ̇₁)²   (Rayleigh: damping c1 at the pivot, c2 at the elbow),
//!
//! and d/dt ∂L/∂θ̇ − ∂L/∂θ + ∂R/∂θ̇ = (τ, 0) give M(θ) θ̈ = r with
//!
//!   M = [[(m1 + m2) L1², m2 L1 L2 cos Δ], [m2 L1 L2 cos Δ, m2 L2²]],
//!   r₁ = τ − c1 θ̇₁ + c2 (θ̇₂ − θ̇₁) − m2 L1 L2 sin Δ θ̇₂² − (m1 + m2) g L1 sin θ₁,
//!   r₂ = −c2 (θ̇₂ − θ̇₁) + m2 L1 L2 sin Δ θ̇₁² − m2 g L2 sin θ₂,
//!
//! det M = m2 L1² L2² (m1 + m2 sin²Δ) > 0. State x = [θ₁, θ₂, θ̇₁, θ̇₂], u = \[τ\],
//! y = [θ₁, θ₂].
//!
//! **Equilibria** (θ̇ = 0, r = 0): sin θ₂ = 0 and (m1 + m2) g L1 sin θ₁ = τ — for τ = 0 the
//! four (0, 0) "down–down", (0, π), (π, 0), (π, π). Only down–down is stable; its
//! linearisation M₀ δθ̈ + K δθ = 0 (K = diag((m1 + m2) g L1, m2 g L2)) has the normal modes
//! det(K − ω² M₀) = 0, i.e. m1 L1 L2 ω⁴ − (m1 + m2) g (L1 + L2) ω² + (m1 + m2) g² = 0:
//!
//!   ω² = (m1 + m2) g / (2 m1 L1 L2) · [(L1 + L2) ± √((L1 + L2)² − 4 m1 L1 L2/(m1 + m2))]
//!
//! ((g/L)(2 ± √2) for equal masses and rods). Undamped, these are centres (not hyperbolic);
//! the energy T + V has a strict minimum there (Lagrange–Dirichlet), so down–down is
//! Lyapunov stable; the other three have a real eigenvalue pair (unstable).
//!
//! **Conserved** without damping and input: E = T + V.

use crate::error::{LtiError, Result};
use crate::lti::params::{Constraint, ModelParam, check_values, named, param};
use crate::nonlinear::system::{NonlinearSystem, Scalar, SystemInfo};

/// Parameters of `double-pendulum`: m1, m2, L1, L2, g, c1 (pivot damping), c2 (elbow
/// damping).
pub const DOUBLE_PENDULUM_PARAMS: &[ModelParam] = &[
    param(
        "m1",
        1.0,
        "kg",
        "mass m1 at the elbow",
        Constraint::Positive,
    ),
    param("m2", 1.0, "kg", "mass m2 at the tip", Constraint::Positive),
    param(
        "L1",
        1.0,
        "m",
        "length of the upper rod",
        Constraint::Positive,
    ),
    param(
        "L2",
        1.0,
        "m",
        "length of the lower rod",
        Constraint::Positive,
    ),
    param(
        "g",
        9.81,
        "m/s²",
        "gravitational acceleration",
        Constraint::Positive,
    ),
    param(
        "c1",
        0.0,
        "N·m·s/rad",
        "viscous damping at the pivot",
        Constraint::NonNegative,
    ),
    param(
        "c2",
        0.0,
        "N·m·s/rad",
        "viscous damping at the elbow",
        Constraint::NonNegative,
    ),
];

/// The double pendulum (module docs).
///
/// ```
/// use ltikit::nonlinear::{models::DoublePendulum, SystemInfo};
/// let p = DoublePendulum::default();
/// let [w1, w2] = p.normal_modes();
/// let g = 9.81f64;
/// assert!((w1 - (g * (2.0 - 2f64.sqrt())).sqrt()).abs() < 1e-14);
/// assert!((w2 - (g * (2.0 + 2f64.sqrt())).sqrt()).abs() < 1e-14);
/// assert_eq!(p.closed_form_equilibria(&[0.0]).unwrap().len(), 4);
/// assert!(DoublePendulum::from_values(&[1.0, 1.0, 0.0, 1.0, 9.81, 0.0, 0.0]).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoublePendulum {
    /// m1.
    pub m1: f64,
    /// m2.
    pub m2: f64,
    /// L1.
    pub l1: f64,
    /// L2.
    pub l2: f64,
    /// g.
    pub g: f64,
    /// Pivot damping c1.
    pub c1: f64,
    /// Elbow damping c2.
    pub c2: f64,
}

impl Default for DoublePendulum {
    fn default() -> Self {
        DoublePendulum {
            m1: 1.0,
            m2: 1.0,
            l1: 1.0,
            l2: 1.0,
            g: 9.81,
            c1: 0.0,
            c2: 0.0,
        }
    }
}

impl DoublePendulum {
    /// From values in the order of [`DOUBLE_PENDULUM_PARAMS`] (a rod of length ≤ 0 is
    /// refused: the point masses would coincide and M would be singular).
    pub fn from_values(v: &[f64]) -> Result<Self> {
        check_values(DOUBLE_PENDULUM_PARAMS, v)?;
        Ok(DoublePendulum {
            m1: v[0],
            m2: v[1],
            l1: v[2],
            l2: v[3],
            g: v[4],
            c1: v[5],
            c2: v[6],
        })
    }

    fn values(&self) -> [f64; 7] {
        [self.m1, self.m2, self.l1, self.l2, self.g, self.c1, self.c2]
    }

    /// The same pendulum without damping.
    pub fn undamped(&self) -> Self {
        DoublePendulum {
            c1: 0.0,
            c2: 0.0,
            ..*self
        }
    }

    /// The two normal-mode angular frequencies ω₁ < ω₂ of down–down (module docs); the
    /// smaller from the product ω₁²ω₂² = (m1 + m2) g²/(m1 L1 L2), free of cancellation.
    pub fn normal_modes(&self) -> [f64; 2] {
        let (m1, m2, l1, l2, g) = (self.m1, self.m2, self.l1, self.l2, self.g);
        let s = l1 + l2;
        let disc = (s * s - 4.0 * m1 * l1 * l2 / (m1 + m2)).max(0.0).sqrt();
        let big = (m1 + m2) * g / (2.0 * m1 * l1 * l2) * (s + disc);
        let product = (m1 + m2) * g * g / (m1 * l1 * l2);
        [(product / big).sqrt(), big.sqrt()]
    }

    /// Position of the tip mass m2, (x, y) with y up and the pivot at the origin.
    pub fn tip(&self, theta1: f64, theta2: f64) -> (f64, f64) {
        (
            self.l1 * theta1.sin() + self.l2 * theta2.sin(),
            -self.l1 * theta1.cos() - self.l2 * theta2.cos(),
        )
    }

    /// Energy T + V at x = [θ₁, θ₂, θ̇₁, θ̇₂].
    pub fn energy(&self, x: &[f64]) -> Result<f64> {
        if x.len() != 4 {
            return Err(LtiError::invalid(format!(
                "the double pendulum has 4 states, got {}",
                x.len()
            )));
        }
        let mut c = [0.0];
        self.undamped().conserved(x, &mut c);
        Ok(c[0])
    }
}

impl SystemInfo for DoublePendulum {
    fn nx(&self) -> usize {
        4
    }
    fn nu(&self) -> usize {
        1
    }
    fn ny(&self) -> usize {
        2
    }
    fn model_name(&self) -> String {
        "double-pendulum".into()
    }
    fn params(&self) -> Vec<(String, f64)> {
        named(DOUBLE_PENDULUM_PARAMS, &self.values())
    }
    fn state_names(&self) -> Vec<String> {
        ["theta1", "theta2", "theta1_dot", "theta2_dot"]
            .iter()
            .map(|s| s.to_string())
            .collect()
    }
    fn input_names(&self) -> Vec<String> {
        vec!["tau".into()]
    }
    fn output_names(&self) -> Vec<String> {
        vec!["theta1".into(), "theta2".into()]
    }

    /// sin θ₂ = 0, sin θ₁ = τ/((m1 + m2) g L1): four equilibria while |τ| < (m1 + m2) g L1,
    /// two at the fold, none beyond.
    fn closed_form_equilibria(&self, u: &[f64]) -> Option<Vec<Vec<f64>>> {
        let tau = u.first().copied().unwrap_or(0.0);
        let s = tau / ((self.m1 + self.m2) * self.g * self.l1);
        if s.abs() > 1.0 {
            return Some(Vec::new());
        }
        let a = s.asin();
        let b = std::f64::consts::PI - a;
        let firsts = if (b - a).abs() <= f64::EPSILON {
            vec![a]
        } else {
            vec![a, b]
        };
        let mut out = Vec::new();
        for t1 in firsts {
            for t2 in [0.0, std::f64::consts::PI] {
                out.push(vec![t1, t2, 0.0, 0.0]);
            }
        }
        Some(out)
    }

    /// Both rods horizontal, at rest: a chaotic start.
    fn default_initial_state(&self) -> Vec<f64> {
        let h = std::f64::consts::FRAC_PI_2;
        vec![h, h, 0.0, 0.0]
    }

    fn default_horizon(&self) -> f64 {
        20.0
    }

    /// The depth of the potential well, (m1 + m2) g L1 + m2 g L2.
    fn conserved_scales(&self) -> Vec<f64> {
        vec![(self.m1 + self.m2) * self.g * self.l1 + self.m2 * self.g * self.l2]
    }

    fn conserved_names(&self) -> Vec<String> {
        if self.c1 == 0.0 && self.c2 == 0.0 {
            vec!["E".into()]
        } else {
            Vec::new()
        }
    }
}

impl NonlinearSystem for DoublePendulum {
    fn f<D: Scalar>(&self, x: &[D], u: &[D], dx: &mut [D]) {
        let (m1, m2, l1, l2, g) = (self.m1, self.m2, self.l1, self.l2, self.g);
        let (t1, t2, w1, w2) = (x[0], x[1], x[2], x[3]);
        let delta = t1 - t2;
        let (sd, cd) = (delta.sin(), delta.cos());
        let a = (m1 + m2) * l1 * l1;
        let b = m2 * l1 * l2;
        let d = m2 * l2 * l2;
        let rel = w2 - w1;
        let r1 = u[0] - w1 * self.c1 + rel * self.c2
            - sd * w2 * w2 * b
            - t1.sin() * ((m1 + m2) * g * l1);
        let r2 = -(rel * self.c2) + sd * w1 * w1 * b - t2.sin() * (m2 * g * l2);
        let bc = cd * b;
        let det = -(bc * bc) + a * d;
        dx[0] = w1;
        dx[1] = w2;
        dx[2] = (r1 * d - bc * r2) / det;
        dx[3] = (r2 * a - bc * r1) / det;
    }
    fn h<D: Scalar>(&self, x: &[D], _u: &[D], y: &mut [D]) {
        y[0] = x[0];
        y[1] = x[1];
    }
    fn conserved<D: Scalar>(&self, x: &[D], c: &mut [D]) {
        let (m1, m2, l1, l2, g) = (self.m1, self.m2, self.l1, self.l2, self.g);
        let (t1, t2, w1, w2) = (x[0], x[1], x[2], x[3]);
        let kinetic = w1 * w1 * (0.5 * (m1 + m2) * l1 * l1)
            + w2 * w2 * (0.5 * m2 * l2 * l2)
            + w1 * w2 * (t1 - t2).cos() * (m2 * l1 * l2);
        let potential = -(t1.cos() * ((m1 + m2) * g * l1)) - t2.cos() * (m2 * g * l2);
        if let Some(e) = c.first_mut() {
            *e = kinetic + potential;
        }
    }
}
