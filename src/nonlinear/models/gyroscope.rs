//! The gimbal gyroscope of seed §1.5.6 (eqs. 1.103–1.106) and exercise 2.14: an axi-symmetric
//! disc (moments Il = I1 = I2 about a diameter, Iz = I3 about its axis) in an outer gimbal
//! (angle θ₁ about the fixed e₃ axis) and an inner gimbal (angle θ₂ about the outer gimbal's
//! b₁ axis), spinning (angle θ₃) about the inner gimbal's c₃ axis — the 3-1-3 Euler angles of
//! eq. 1.106. Gimbal inertia neglected; inputs are the torques u₁, u₂, u₃ about the outer
//! gimbal axis, the inner gimbal axis and the spin axis; outputs the gimbal angles θ₁, θ₂.
//!
//! **Equations.** The seed writes Euler's equations in the disc frame (1.103–1.105),
//! the body rates through the Euler angles (1.93–1.95) and the disc torque as T = M(θ) u;
//! that M is exactly J(θ)⁻ᵀ for Ω = J(θ)θ̇ (virtual work: T·Ω = u·θ̇). The same dynamics in
//! the Euler angles themselves, from the Lagrangian
//! L = ½ Il (θ̇₂² + θ̇₁² sin²θ₂) + ½ Iz Ω₃², Ω₃ = θ̇₁ cos θ₂ + θ̇₃, with generalised forces u:
//!
//!   Il sin²θ₂ θ̈₁ = u₁ − u₃ cos θ₂ − 2 Il θ̇₁θ̇₂ sin θ₂ cos θ₂ + Iz Ω₃ θ̇₂ sin θ₂,
//!   Il θ̈₂       = u₂ + Il θ̇₁² sin θ₂ cos θ₂ − Iz Ω₃ θ̇₁ sin θ₂,
//!   Iz Ω̇₃       = u₃   (eq. 1.105).
//!
//! θ₃ is cyclic (nothing depends on it for an axi-symmetric disc), so the state is
//! x = [θ₁, θ₂, θ̇₁, θ̇₂, Ω₃] and **steady spin** (θ̇₁ = θ̇₂ = 0, Ω₃ = ω) is an equilibrium
//! for every θ₁ and every θ₂ away from gimbal lock (sin θ₂ = 0, where the equations are
//! singular — the seed's remark after eq. 1.107); the model's domain ends there.
//! [`GyroscopeDiscFrame`] is the seed's own six-state form, kept for the cross-check.
//!
//! **Linearisation** at θ₂ = π/2 with ν = Iz ω/Il (the nutation frequency):
//! δθ̈₁ = ν δθ̇₂ + δu₁/Il, δθ̈₂ = −ν δθ̇₁ + δu₂/Il, δΩ̇₃ = δu₃/Iz; eigenvalues 0, 0, 0, ±jν;
//! G₁₁ = G₂₂ = 1/(Il(s² + ν²)), G₂₁ = −G₁₂ = −ν/(Il s(s² + ν²)): a constant torque about the
//! outer gimbal axis turns the *inner* gimbal at the mean rate −u₁/(Iz ω) (precession),
//! exercise 2.14's second claim; its first is that steady spin is an equilibrium.
//!
//! **Conserved** (zero input): E = ½ Il (θ̇₂² + θ̇₁² sin²θ₂) + ½ Iz Ω₃², the momentum of
//! the cyclic θ₁, p₁ = Il θ̇₁ sin²θ₂ + Iz Ω₃ cos θ₂, and p₃ = Iz Ω₃.

use crate::error::Result;
use crate::lti::params::{Constraint, ModelParam, check_values, named, param};
use crate::nonlinear::system::{NonlinearSystem, Scalar, SystemInfo};

/// Parameters of `gyroscope`: I1 (= Il), I3 (= Iz) and the spin w of the steady state.
pub const GYROSCOPE_PARAMS: &[ModelParam] = &[
    param(
        "I1",
        0.5,
        "kg·m²",
        "moment of inertia Il = I1 = I2 of the disc about a diameter",
        Constraint::Positive,
    ),
    param(
        "I3",
        1.0,
        "kg·m²",
        "moment of inertia Iz = I3 of the disc about its axis",
        Constraint::Positive,
    ),
    param(
        "w",
        20.0,
        "rad/s",
        "spin Ω3 of the steady state",
        Constraint::Any,
    ),
];

/// The gimbal gyroscope in Euler angles (module docs).
///
/// ```
/// use ltikit::nonlinear::{models::Gyroscope, linearize, EquilibriumSearch};
/// let g = Gyroscope::default();
/// let lin = linearize(&g, None, &EquilibriumSearch::default()).unwrap();
/// let e = &lin.equilibria[0];
/// let nu = g.nutation_frequency();
/// assert!(e.eigenvalues.iter().any(|z| (z.im - nu).abs() < 1e-12 * nu));
/// assert_eq!(e.channels.len(), 6); // 3 inputs × 2 outputs
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gyroscope {
    /// Il = I1 = I2.
    pub i1: f64,
    /// Iz = I3.
    pub i3: f64,
    /// Spin ω of the steady state.
    pub w: f64,
}

impl Default for Gyroscope {
    fn default() -> Self {
        Gyroscope {
            i1: 0.5,
            i3: 1.0,
            w: 20.0,
        }
    }
}

impl Gyroscope {
    /// From values in the order of [`GYROSCOPE_PARAMS`] (triangle inequality Iz ≤ 2 Il).
    pub fn from_values(v: &[f64]) -> Result<Self> {
        check_values(GYROSCOPE_PARAMS, v)?;
        super::rigid_body::check_inertias(&[v[0], v[0], v[1]])?;
        Ok(Gyroscope {
            i1: v[0],
            i3: v[1],
            w: v[2],
        })
    }

    /// The nutation frequency ν = Iz ω / Il of the linearisation at θ₂ = π/2.
    pub fn nutation_frequency(&self) -> f64 {
        self.i3 * self.w / self.i1
    }

    /// The linearisation's transfer function from torque `input` to gimbal angle `output`
    /// (0-based: u₁, u₂, u₃ → θ₁, θ₂) at `s`, in closed form (module docs):
    /// G₁₁ = G₂₂ = 1/(Il(s² + ν²)), G₂₁ = −G₁₂ = −ν/(Il s(s² + ν²)), and 0 from u₃.
    ///
    /// ```
    /// use ltikit::nonlinear::models::Gyroscope;
    /// use num_complex::Complex64;
    /// let g = Gyroscope::default(); // Il = 0.5, ν = 40 rad/s
    /// let s = Complex64::new(0.0, 10.0);
    /// let g11 = g.channel_closed_form(0, 0, s); // 1/(0.5·(1600 − 100))
    /// assert!((g11 - Complex64::new(1.0 / 750.0, 0.0)).norm() < 1e-18);
    /// assert_eq!(g.channel_closed_form(2, 1, s), Complex64::new(0.0, 0.0));
    /// ```
    pub fn channel_closed_form(
        &self,
        input: usize,
        output: usize,
        s: num_complex::Complex64,
    ) -> num_complex::Complex64 {
        let nu = self.nutation_frequency();
        let d = s * s + nu * nu;
        match (input, output) {
            (0, 0) | (1, 1) => 1.0 / (self.i1 * d),
            (0, 1) => -nu / (self.i1 * s * d),
            (1, 0) => nu / (self.i1 * s * d),
            _ => num_complex::Complex64::new(0.0, 0.0),
        }
    }

    /// The mean rate −u₁/(Iz ω) at which a constant torque `u1` about the outer gimbal axis
    /// turns the inner gimbal (precession; module docs).
    pub fn precession_rate(&self, u1: f64) -> f64 {
        -u1 / (self.i3 * self.w)
    }

    /// The linearisation's gimbal angles [δθ₁, δθ₂] at time `t` after a constant torque `u1`
    /// about the outer gimbal axis is applied from steady spin (the step responses of
    /// G₁₁ = 1/(Il(s² + ν²)) and G₂₁ = −ν/(Il s(s² + ν²)), module docs):
    /// δθ₁ = u₁/(Il ν²)·(1 − cos νt), δθ₂ = −u₁/(Il ν)·(t − sin(νt)/ν) — nutation loops of
    /// size u₁/(Il ν²) riding on the precession.
    ///
    /// ```
    /// use ltikit::nonlinear::models::Gyroscope;
    /// let g = Gyroscope::default();
    /// let period = 2.0 * std::f64::consts::PI / g.nutation_frequency();
    /// let [d1, d2] = g.outer_torque_response(0.2, period);
    /// assert!(d1.abs() < 1e-15); // back on the axis after a full nutation loop
    /// assert!((d2 - g.precession_rate(0.2) * period).abs() < 1e-15);
    /// ```
    pub fn outer_torque_response(&self, u1: f64, t: f64) -> [f64; 2] {
        let nu = self.nutation_frequency();
        [
            u1 / (self.i1 * nu * nu) * (1.0 - (nu * t).cos()),
            -u1 / (self.i1 * nu) * (t - (nu * t).sin() / nu),
        ]
    }

    /// The steady spin [θ₁, θ₂, θ̇₁, θ̇₂, Ω₃] = [0, π/2, 0, 0, ω].
    pub fn steady_spin(&self) -> [f64; 5] {
        [0.0, std::f64::consts::FRAC_PI_2, 0.0, 0.0, self.w]
    }

    /// The spin axis c₃ in the fixed frame e: R₃(θ₁)R₁(θ₂)e₃ = (sin θ₁ sin θ₂, −cos θ₁ sin θ₂,
    /// cos θ₂), with the elementary rotations R₁, R₃ of seed §1.5.4.
    pub fn spin_axis(theta1: f64, theta2: f64) -> [f64; 3] {
        let (s1, c1) = theta1.sin_cos();
        let (s2, c2) = theta2.sin_cos();
        [s1 * s2, -c1 * s2, c2]
    }
}

impl SystemInfo for Gyroscope {
    fn nx(&self) -> usize {
        5
    }
    fn nu(&self) -> usize {
        3
    }
    fn ny(&self) -> usize {
        2
    }
    fn model_name(&self) -> String {
        "gyroscope".into()
    }
    fn params(&self) -> Vec<(String, f64)> {
        named(GYROSCOPE_PARAMS, &[self.i1, self.i3, self.w])
    }
    fn state_names(&self) -> Vec<String> {
        ["theta1", "theta2", "theta1_dot", "theta2_dot", "Omega3"]
            .iter()
            .map(|s| s.to_string())
            .collect()
    }
    fn input_names(&self) -> Vec<String> {
        vec!["u1".into(), "u2".into(), "u3".into()]
    }
    fn output_names(&self) -> Vec<String> {
        vec!["theta1".into(), "theta2".into()]
    }

    /// One representative of the steady spins: θ₁ = 0, θ₂ = π/2 (for zero input; a torque
    /// u₁ or u₂ has no equilibrium — it makes the gimbals precess — and u₃ spins the disc up).
    fn closed_form_equilibria(&self, u: &[f64]) -> Option<Vec<Vec<f64>>> {
        if u.iter().any(|v| *v != 0.0) {
            return Some(Vec::new());
        }
        Some(vec![self.steady_spin().to_vec()])
    }

    /// Away from gimbal lock, |sin θ₂| > 1e-9.
    fn in_domain(&self, x: &[f64]) -> bool {
        x[1].sin().abs() > 1e-9
    }

    fn domain_note(&self) -> Option<String> {
        Some("gimbal lock: sin θ2 = 0".into())
    }

    /// Steady spin with the outer gimbal knocked: θ̇₁(0) = 1 rad/s (nutation about the spin).
    fn default_initial_state(&self) -> Vec<f64> {
        vec![0.0, std::f64::consts::FRAC_PI_2, 1.0, 0.0, self.w]
    }

    fn default_horizon(&self) -> f64 {
        2.0
    }

    fn conserved_names(&self) -> Vec<String> {
        vec!["E".into(), "p1".into(), "p3".into()]
    }

    /// E: ½ Iz ω²; p₁ and p₃: Iz |ω| (p₁ vanishes at θ₂ = π/2).
    fn conserved_scales(&self) -> Vec<f64> {
        let p = self.i3 * self.w.abs();
        vec![0.5 * p * self.w.abs(), p, p]
    }

    fn equilibria_note(&self) -> Option<String> {
        Some(format!(
            "steady spin Ω3 = {} rad/s is an equilibrium for every θ1 and every θ2 away from \
             gimbal lock (sin θ2 = 0); listed: θ1 = 0, θ2 = π/2",
            self.w
        ))
    }
}

impl NonlinearSystem for Gyroscope {
    fn f<D: Scalar>(&self, x: &[D], u: &[D], dx: &mut [D]) {
        let (il, iz) = (self.i1, self.i3);
        let (s2, c2) = (x[1].sin(), x[1].cos());
        let (d1, d2, w3) = (x[2], x[3], x[4]);
        dx[0] = d1;
        dx[1] = d2;
        dx[2] = (u[0] - u[2] * c2 - d1 * d2 * s2 * c2 * (2.0 * il) + w3 * d2 * s2 * iz)
            / (s2 * s2 * il);
        dx[3] = (u[1] + d1 * d1 * s2 * c2 * il - w3 * d1 * s2 * iz) / il;
        dx[4] = u[2] / iz;
    }
    fn h<D: Scalar>(&self, x: &[D], _u: &[D], y: &mut [D]) {
        y[0] = x[0];
        y[1] = x[1];
    }
    fn conserved<D: Scalar>(&self, x: &[D], c: &mut [D]) {
        let (il, iz) = (self.i1, self.i3);
        let (s2, c2) = (x[1].sin(), x[1].cos());
        let (d1, d2, w3) = (x[2], x[3], x[4]);
        c[0] = (d2 * d2 * il + d1 * d1 * s2 * s2 * il + w3 * w3 * iz) * 0.5;
        c[1] = d1 * s2 * s2 * il + w3 * c2 * iz;
        c[2] = w3 * iz;
    }
}

/// The seed's own form of the gyroscope: x = [θ₁, θ₂, θ₃, Ω₁, Ω₂, Ω₃] with Euler's equations
/// in the disc frame (eqs. 1.103–1.105), the Euler-angle rates from eqs. 1.93–1.95 inverted
/// (θ̇₁ = (Ω₁ sin θ₃ + Ω₂ cos θ₃)/sin θ₂, θ̇₂ = Ω₁ cos θ₃ − Ω₂ sin θ₃,
/// θ̇₃ = Ω₃ − θ̇₁ cos θ₂) and the disc torque T = M(θ) u of §1.5.6. Same inputs and outputs
/// as [`Gyroscope`]; used to cross-check it (not in the registry: steady spin is not an
/// equilibrium here, θ₃ turns).
///
/// ```
/// use ltikit::nonlinear::{derivative, models::{Gyroscope, GyroscopeDiscFrame}};
/// let g = Gyroscope::default();
/// let d = GyroscopeDiscFrame(g);
/// // Steady spin: only θ₃ moves, at the spin rate.
/// let dx = derivative(&d, &[0.0, 1.0, 0.3, 0.0, 0.0, 20.0], &[0.0; 3]).unwrap();
/// assert_eq!(&dx[..2], &[0.0, 0.0]);
/// assert!((dx[2] - 20.0).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GyroscopeDiscFrame(pub Gyroscope);

impl SystemInfo for GyroscopeDiscFrame {
    fn nx(&self) -> usize {
        6
    }
    fn nu(&self) -> usize {
        3
    }
    fn ny(&self) -> usize {
        2
    }
    fn model_name(&self) -> String {
        "gyroscope (disc frame, seed eqs. 1.103–1.106)".into()
    }
    fn in_domain(&self, x: &[f64]) -> bool {
        x[1].sin().abs() > 1e-9
    }
    fn domain_note(&self) -> Option<String> {
        Some("gimbal lock: sin θ2 = 0".into())
    }
}

impl NonlinearSystem for GyroscopeDiscFrame {
    fn f<D: Scalar>(&self, x: &[D], u: &[D], dx: &mut [D]) {
        let (il, iz) = (self.0.i1, self.0.i3);
        let (s2, c2) = (x[1].sin(), x[1].cos());
        let (s3, c3) = (x[2].sin(), x[2].cos());
        let (o1, o2, o3) = (x[3], x[4], x[5]);
        let cot2 = c2 / s2;
        // Euler-angle rates (eqs. 1.93–1.95 inverted).
        let d1 = (o1 * s3 + o2 * c3) / s2;
        dx[0] = d1;
        dx[1] = o1 * c3 - o2 * s3;
        dx[2] = o3 - d1 * c2;
        // The disc torque T = M(θ) u (§1.5.6).
        let t1 = u[0] * s3 / s2 + u[1] * c3 - u[2] * s3 * cot2;
        let t2 = u[0] * c3 / s2 - u[1] * s3 - u[2] * c3 * cot2;
        let t3 = u[2];
        // Euler's equations (1.103–1.105).
        dx[3] = (o2 * o3 * (il - iz) + t1) / il;
        dx[4] = (o3 * o1 * (iz - il) + t2) / il;
        dx[5] = t3 / iz;
    }
    fn h<D: Scalar>(&self, x: &[D], _u: &[D], y: &mut [D]) {
        y[0] = x[0];
        y[1] = x[1];
    }
}
