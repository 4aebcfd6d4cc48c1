//! The seed's linear lattice (§2.4, eqs. 2.68–2.79): N particles of mass m joined by
//! identical linear springs, as a 2N-state model.
//!
//! With the harmonic interaction φ(r) = (αβ/2) r² the lattice equation (2.68) becomes (2.69),
//! q̈ₙ = ω0² (qₙ₊₁ − 2qₙ + qₙ₋₁) with ω0² = αβ/m, or q̈ = Ω q (2.75). ltikit adds an optional
//! damping that keeps the modes uncoupled (Rayleigh damping), a force f on particle j and the
//! displacement of particle i as the measured output:
//!
//! ```text
//! m q̈ₙ = αβ (qₙ₊₁ − 2qₙ + qₙ₋₁) − m γ q̇ₙ + m η ω0² (q̇ₙ₊₁ − 2q̇ₙ + q̇ₙ₋₁) + f δₙⱼ
//! q̈ = Ω q + (η Ω − γ I) q̇ + eⱼ f/m,     x = [q; q̇],  u = f,  y = qᵢ (or all of q)
//! ```
//!
//! γ (1/s) is a dashpot from every particle to the ground, η (s) a dashpot in parallel with
//! every spring (its coefficient is η·αβ). In the modes each of them is a plain damped
//! oscillator z̈ₖ + cₖ żₖ + ωₖ² zₖ = Tⱼₖ f/m with cₖ = γ + η ωₖ².
//!
//! **Boundaries.** `periodic`: the N-periodic lattice of eq. 2.69, particle N coupled back to
//! particle 1 (a ring). `fixed`: N moving particles between two walls, q₀ = q_{N+1} = 0.
//! The seed numbers a fixed lattice as N + 1 sites 0…N with q₀ = q_N = 0, i.e. N − 1 moving
//! particles; here N always counts the moving particles, so the state has 2N components in
//! both cases and the seed's fixed lattice of size N is ltikit's N − 1.
//!
//! **Closed forms** (derived in [`closed_form`]): the eigenvalues of A are ±j·2ω0 sin(πk/N),
//! k = 0…N−1 (periodic) and ±j·2ω0 sin(πk/(2(N+1))), k = 1…N (fixed), undamped.
//!
//! ```
//! use ltikit::lti::lattice::{Boundary, Lattice};
//! let lat = Lattice::new(128, Boundary::Periodic, 1.0).unwrap();
//! let ss = lat.state_space().unwrap();
//! assert_eq!(ss.order(), 256);
//! let modes = lat.modes().unwrap();
//! let exact = lat.frequencies_closed_form();
//! let worst = modes.omega.iter().zip(&exact).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
//! assert!(worst < 1e-12);
//! ```

pub mod closed_form;
mod modes;
mod motion;
pub mod packet;
mod params;

use std::str::FromStr;

use nalgebra::DMatrix;

use crate::error::{LtiError, Result};
use crate::lti::StateSpace;

pub use modes::{DiagonalCheck, Modes};
pub use motion::{Trajectory, modal_free_response};
pub use packet::{Envelope, Packet};
pub use params::LATTICE_PARAMS;

pub use crate::limits::MAX_PARTICLES;

/// Boundary condition of the lattice.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Boundary {
    /// N-periodic (eq. 2.69): particle N is coupled back to particle 1.
    Periodic,
    /// Fixed ends: walls at sites 0 and N + 1.
    Fixed,
}

impl Boundary {
    /// `"periodic"` or `"fixed"`.
    pub fn name(self) -> &'static str {
        match self {
            Boundary::Periodic => "periodic",
            Boundary::Fixed => "fixed",
        }
    }

    /// From the numeric parameter `periodic`: 1 → periodic, 0 → fixed.
    ///
    /// ```
    /// use ltikit::lti::lattice::Boundary;
    /// assert_eq!(Boundary::from_flag(0.0).unwrap(), Boundary::Fixed);
    /// assert!(Boundary::from_flag(0.5).is_err());
    /// ```
    #[allow(clippy::float_cmp)] // the flag is exactly 1 or 0
    pub fn from_flag(v: f64) -> Result<Boundary> {
        if v == 1.0 {
            Ok(Boundary::Periodic)
        } else if v == 0.0 {
            Ok(Boundary::Fixed)
        } else {
            Err(LtiError::InvalidParameter {
                name: "periodic".into(),
                value: v,
                reason: "the boundary flag must be 1 (periodic) or 0 (fixed)".into(),
            })
        }
    }
}

impl FromStr for Boundary {
    type Err = LtiError;

    /// `"periodic"` or `"fixed"` (case-insensitive).
    ///
    /// ```
    /// use ltikit::lti::lattice::Boundary;
    /// assert_eq!("Fixed".parse::<Boundary>().unwrap(), Boundary::Fixed);
    /// assert_eq!(
    ///     "free".parse::<Boundary>().unwrap_err().to_string(),
    ///     "unknown lattice boundary 'free' (known: periodic, fixed)"
    /// );
    /// ```
    fn from_str(s: &str) -> Result<Boundary> {
        match s.trim().to_ascii_lowercase().as_str() {
            "periodic" => Ok(Boundary::Periodic),
            "fixed" => Ok(Boundary::Fixed),
            _ => Err(LtiError::invalid(format!(
                "unknown lattice boundary '{}' (known: periodic, fixed)",
                crate::error::abbreviate(s.trim())
            ))),
        }
    }
}

/// What the model measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Output {
    /// The displacement of one particle (1-based).
    Particle(usize),
    /// All N displacements (a model with N outputs).
    All,
}

/// The linear lattice of seed §2.4 (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Lattice {
    n: usize,
    boundary: Boundary,
    w0: f64,
    mass: f64,
    gamma: f64,
    eta: f64,
    input: usize,
    output: Output,
}

fn bad(name: &str, value: f64, reason: impl Into<String>) -> LtiError {
    LtiError::InvalidParameter {
        name: name.into(),
        value,
        reason: reason.into(),
    }
}

/// An integer-valued parameter in lo..=hi.
fn integer(name: &str, v: f64, lo: usize, hi: usize, what: &str) -> Result<usize> {
    if v.is_finite() && v.fract() == 0.0 && v >= lo as f64 && v <= hi as f64 {
        Ok(v as usize)
    } else {
        Err(bad(name, v, format!("{what} must be an integer {lo}…{hi}")))
    }
}

impl Lattice {
    /// An undamped lattice of `n` particles with unit mass, the force on particle 1 and the
    /// displacement of particle 1 measured.
    ///
    /// Errors: n < 2 or above [`MAX_PARTICLES`], ω0 not positive or so large or small that
    /// ω0² is not a normal number.
    pub fn new(n: usize, boundary: Boundary, w0: f64) -> Result<Lattice> {
        integer("N", n as f64, 2, MAX_PARTICLES, "the number of particles")?;
        check_w0(w0)?;
        Ok(Lattice {
            n,
            boundary,
            w0,
            mass: 1.0,
            gamma: 0.0,
            eta: 0.0,
            input: 1,
            output: Output::Particle(1),
        })
    }

    /// Sets the particle mass m (> 0): the force f gives the acceleration f/m.
    pub fn with_mass(mut self, m: f64) -> Result<Lattice> {
        if !(m.is_finite() && m > 0.0) {
            return Err(bad("m", m, "the particle mass must be > 0 (kg)"));
        }
        self.mass = m;
        Ok(self)
    }

    /// Sets the damping: γ (1/s) to the ground, η (s) in parallel with the springs.
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice};
    /// let lat = Lattice::new(8, Boundary::Fixed, 2.0).unwrap().with_damping(0.1, 0.01).unwrap();
    /// assert!(Lattice::new(8, Boundary::Fixed, 2.0).unwrap().with_damping(-1.0, 0.0).is_err());
    /// # let _ = lat;
    /// ```
    pub fn with_damping(mut self, gamma: f64, eta: f64) -> Result<Lattice> {
        for (name, v) in [("gamma", gamma), ("eta", eta)] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(bad(name, v, "the damping must be ≥ 0"));
            }
        }
        if !(4.0 * eta * self.w0 * self.w0).is_finite() {
            return Err(bad("eta", eta, "η·ω0² overflows"));
        }
        self.gamma = gamma;
        self.eta = eta;
        Ok(self)
    }

    /// Sets the particle the force acts on (1…N).
    pub fn with_input(mut self, particle: usize) -> Result<Lattice> {
        self.input = integer(
            "input",
            particle as f64,
            1,
            self.n,
            "the particle the force acts on",
        )?;
        Ok(self)
    }

    /// Sets what is measured.
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice, Output};
    /// let lat = Lattice::new(8, Boundary::Periodic, 1.0).unwrap();
    /// assert!(lat.clone().with_output(Output::Particle(8)).is_ok());
    /// assert!(lat.with_output(Output::Particle(9)).is_err());
    /// ```
    pub fn with_output(mut self, output: Output) -> Result<Lattice> {
        if let Output::Particle(i) = output {
            integer("output", i as f64, 1, self.n, "the measured particle")?;
        }
        self.output = output;
        Ok(self)
    }

    /// Number of moving particles N.
    pub fn n(&self) -> usize {
        self.n
    }
    /// The boundary condition.
    pub fn boundary(&self) -> Boundary {
        self.boundary
    }
    /// ω0 = √(αβ/m) (rad/s).
    pub fn w0(&self) -> f64 {
        self.w0
    }
    /// Particle mass m (kg).
    pub fn mass(&self) -> f64 {
        self.mass
    }
    /// Damping to the ground γ (1/s).
    pub fn gamma(&self) -> f64 {
        self.gamma
    }
    /// Spring-parallel damping time η (s).
    pub fn eta(&self) -> f64 {
        self.eta
    }
    /// The particle the force acts on (1-based).
    pub fn input(&self) -> usize {
        self.input
    }
    /// What is measured.
    pub fn output(&self) -> Output {
        self.output
    }
    /// True when γ = η = 0.
    pub fn is_undamped(&self) -> bool {
        self.gamma == 0.0 && self.eta == 0.0
    }

    /// The boundary and the damping in words, for reports.
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice};
    /// let lat = Lattice::new(8, Boundary::Fixed, 1.0).unwrap();
    /// assert_eq!(lat.describe(), "fixed, undamped");
    /// let lat = lat.with_damping(0.005, 0.01).unwrap();
    /// assert_eq!(lat.describe(), "fixed, γ = 0.005, η = 0.01");
    /// ```
    pub fn describe(&self) -> String {
        if self.is_undamped() {
            format!("{}, undamped", self.boundary.name())
        } else {
            format!(
                "{}, γ = {}, η = {}",
                self.boundary.name(),
                crate::fmt::fmt_sig(self.gamma, 3),
                crate::fmt::fmt_sig(self.eta, 3)
            )
        }
    }

    /// The bonds as (left particle, right particle), 0-based, `None` for a wall. Periodic:
    /// N bonds (N → 1 closes the ring); fixed: N + 1 bonds (two to the walls).
    pub fn bonds(&self) -> Vec<(Option<usize>, Option<usize>)> {
        let n = self.n;
        match self.boundary {
            Boundary::Periodic => (0..n).map(|b| (Some((b + n - 1) % n), Some(b))).collect(),
            Boundary::Fixed => (0..=n)
                .map(|b| (b.checked_sub(1), (b < n).then_some(b)))
                .collect(),
        }
    }

    /// The bond-stretch matrix D (bonds × particles): r = D q, the stretch of each bond.
    /// The potential energy per unit mass is ½ω0²|Dq|², and Ω = −ω0² DᵀD.
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice};
    /// let lat = Lattice::new(3, Boundary::Fixed, 2.0).unwrap();
    /// let d = lat.bond_matrix(); // 4 bonds: wall–1, 1–2, 2–3, 3–wall
    /// assert_eq!(d.shape(), (4, 3));
    /// assert_eq!(d.transpose() * &d * (-4.0), lat.omega_matrix());
    /// ```
    pub fn bond_matrix(&self) -> DMatrix<f64> {
        let bonds = self.bonds();
        let mut d = DMatrix::zeros(bonds.len(), self.n);
        for (b, (l, r)) in bonds.into_iter().enumerate() {
            if let Some(r) = r {
                d[(b, r)] += 1.0;
            }
            if let Some(l) = l {
                d[(b, l)] -= 1.0;
            }
        }
        d
    }

    /// The stiffness pattern K = DᵀD (2 on the diagonal, −1 to each neighbour; integers, so
    /// exact), Ω = −ω0² K.
    pub fn stiffness(&self) -> DMatrix<f64> {
        let d = self.bond_matrix();
        d.transpose() * d
    }

    /// Ω of eq. 2.75 (q̈ = Ω q for the undamped lattice).
    pub fn omega_matrix(&self) -> DMatrix<f64> {
        self.stiffness() * (-self.w0 * self.w0)
    }

    /// The 2N-state model x = [q; q̇], u = force on [`Lattice::input`], y = the measured
    /// displacement(s), D = 0.
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice, Output};
    /// let lat = Lattice::new(4, Boundary::Fixed, 1.0).unwrap().with_output(Output::All).unwrap();
    /// let ss = lat.state_space().unwrap();
    /// assert_eq!((ss.order(), ss.b.ncols(), ss.c.nrows()), (8, 1, 4));
    /// ```
    pub fn state_space(&self) -> Result<StateSpace> {
        let n = self.n;
        let omega = self.omega_matrix();
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        for i in 0..n {
            a[(i, n + i)] = 1.0;
            for j in 0..n {
                a[(n + i, j)] = omega[(i, j)];
                a[(n + i, n + j)] = self.eta * omega[(i, j)];
            }
            a[(n + i, n + i)] -= self.gamma;
        }
        let mut b = DMatrix::zeros(2 * n, 1);
        b[(n + self.input - 1, 0)] = 1.0 / self.mass;
        let c = match self.output {
            Output::Particle(i) => {
                let mut c = DMatrix::zeros(1, 2 * n);
                c[(0, i - 1)] = 1.0;
                c
            }
            Output::All => {
                let mut c = DMatrix::zeros(n, 2 * n);
                for i in 0..n {
                    c[(i, i)] = 1.0;
                }
                c
            }
        };
        let p = c.nrows();
        StateSpace::new(a, b, c, DMatrix::zeros(p, 1))
    }

    /// Mode damping cₖ = γ + η ωₖ² for a mode of frequency ω (z̈ + c ż + ω² z = 0).
    pub fn mode_damping(&self, omega: f64) -> f64 {
        self.gamma + self.eta * omega * omega
    }

    /// The middle `width` particles, 0-based half-open (57…72 in the seed's 1-based count
    /// for width 16 of 128). Errors when width is 0 or exceeds N.
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice};
    /// let lat = Lattice::new(128, Boundary::Periodic, 1.0).unwrap();
    /// assert_eq!(lat.middle(16).unwrap(), 56..72);
    /// ```
    pub fn middle(&self, width: usize) -> Result<std::ops::Range<usize>> {
        if width == 0 || width > self.n {
            return Err(LtiError::invalid(format!(
                "a block of {width} particles does not fit a lattice of {}",
                self.n
            )));
        }
        let lo = (self.n - width) / 2;
        Ok(lo..lo + width)
    }
}

fn check_w0(w0: f64) -> Result<()> {
    let sq = w0 * w0;
    if !(w0.is_finite() && w0 > 0.0) {
        return Err(bad("w0", w0, "ω0 must be > 0 (rad/s)"));
    }
    if !(sq.is_normal() && (4.0 * sq).is_finite()) {
        return Err(bad("w0", w0, "ω0² must be a normal floating-point number"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // integer-valued matrices are exact
    use super::*;

    #[test]
    fn periodic_omega_is_the_seeds_circulant() {
        let lat = Lattice::new(5, Boundary::Periodic, 2.0).unwrap();
        let o = lat.omega_matrix();
        assert_eq!(o[(0, 0)], -8.0);
        assert_eq!(o[(0, 1)], 4.0);
        assert_eq!(o[(0, 4)], 4.0);
        assert_eq!(o[(2, 0)], 0.0);
        // N = 2: both neighbours of a particle are the same particle.
        let two = Lattice::new(2, Boundary::Periodic, 1.0)
            .unwrap()
            .omega_matrix();
        assert_eq!(two.as_slice(), &[-2.0, 2.0, 2.0, -2.0]);
    }

    #[test]
    fn fixed_omega_has_walls() {
        let o = Lattice::new(3, Boundary::Fixed, 1.0)
            .unwrap()
            .omega_matrix();
        assert_eq!(o[(0, 0)], -2.0);
        assert_eq!(o[(0, 2)], 0.0);
        assert_eq!(o[(2, 2)], -2.0);
    }

    #[test]
    fn state_space_structure() {
        let lat = Lattice::new(3, Boundary::Fixed, 1.0)
            .unwrap()
            .with_mass(2.0)
            .unwrap()
            .with_damping(0.5, 0.25)
            .unwrap()
            .with_input(2)
            .unwrap()
            .with_output(Output::Particle(3))
            .unwrap();
        let ss = lat.state_space().unwrap();
        assert_eq!(ss.a[(0, 3)], 1.0);
        assert_eq!(ss.a[(3, 0)], -2.0);
        assert_eq!(ss.a[(3, 3)], -0.5 - 0.5);
        assert_eq!(ss.a[(3, 4)], 0.25);
        assert_eq!(ss.b[(4, 0)], 0.5);
        assert_eq!(ss.c[(0, 2)], 1.0);
    }

    #[test]
    fn middle_block() {
        let lat = Lattice::new(128, Boundary::Periodic, 1.0).unwrap();
        assert_eq!(lat.middle(16).unwrap(), 56..72);
        assert!(lat.middle(0).is_err());
        assert!(lat.middle(129).is_err());
    }
}
