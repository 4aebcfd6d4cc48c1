//! Exact motion of the lattice: every mode is a damped oscillator with a closed-form
//! solution (no time stepping), q = T z; energies per mode (2.78), per particle and per block.

use nalgebra::DMatrix;

use super::Lattice;
use super::modes::Modes;
use crate::error::{LtiError, Result};

pub use crate::limits::MAX_TRAJECTORY_VALUES;

/// The exact free response (z(t), ż(t)) of z̈ + c ż + ω² z = 0 from (z0, ż0), for c, ω ≥ 0
/// and t ≥ 0, in every regime (undamped, under-, critically and overdamped, ω = 0):
/// z = e^{−σt}[z0 C + (ż0 + σz0) S], ż = e^{−σt}[ż0 C − (σż0 + ω²z0) S] with σ = c/2,
/// d² = ω² − σ², C = cos(dt), S = sin(dt)/d (cosh and sinh for d² < 0, 1 and t for d² = 0).
/// The exponentials are combined so that nothing overflows, and the slow overdamped rate
/// −ω²/(σ + κ) is formed without cancellation.
///
/// ```
/// use ltikit::lti::lattice::modal_free_response;
/// let (z, v) = modal_free_response(0.0, 2.0, 1.0, 0.0, 0.25 * std::f64::consts::PI);
/// assert!(z.abs() < 1e-15 && (v + 2.0).abs() < 1e-15);      // cos 2t, −2 sin 2t
/// let (z, _) = modal_free_response(0.0, 0.0, 1.0, 3.0, 2.0);
/// assert_eq!(z, 7.0);                                        // free particle
/// ```
pub fn modal_free_response(c: f64, omega: f64, z0: f64, v0: f64, t: f64) -> (f64, f64) {
    let s = 0.5 * c;
    let d2 = (omega - s) * (omega + s);
    // (e^{−σt}C, e^{−σt}S)
    let (ec, es) = if d2 > 0.0 {
        let d = d2.sqrt();
        let e = if s == 0.0 { 1.0 } else { (-s * t).exp() };
        let (sn, cs) = (d * t).sin_cos();
        (e * cs, e * sn / d)
    } else if d2 == 0.0 {
        let e = (-s * t).exp();
        (e, e * t)
    } else {
        let k = (-d2).sqrt();
        let slow = (-(omega * omega) / (s + k) * t).exp(); // e^{(κ−σ)t}
        let fast = (-(s + k) * t).exp(); // e^{−(κ+σ)t}
        let es = if k * t < 1.0 {
            (-s * t).exp() * (k * t).sinh() / k
        } else {
            0.5 * (slow - fast) / k
        };
        (0.5 * (slow + fast), es)
    };
    (
        z0 * ec + (v0 + s * z0) * es,
        v0 * ec - (s * v0 + omega * omega * z0) * es,
    )
}

/// A sampled exact trajectory: displacements, velocities and their modal coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    /// Sample times (s).
    pub t: Vec<f64>,
    /// qₙ(tᵢ): N × samples.
    pub q: DMatrix<f64>,
    /// q̇ₙ(tᵢ): N × samples.
    pub v: DMatrix<f64>,
    /// zₖ(tᵢ) = (Tᵀq)ₖ as propagated: N × samples.
    pub z: DMatrix<f64>,
    /// żₖ(tᵢ): N × samples.
    pub zdot: DMatrix<f64>,
}

impl Lattice {
    /// The exact free motion from q(0) = `q0`, q̇(0) = `v0` at the times `t` (finite,
    /// ≥ 0, any order): z(0) = Tᵀq0, each mode by [`modal_free_response`], q = T z.
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice};
    /// let lat = Lattice::new(16, Boundary::Periodic, 1.0).unwrap();
    /// let modes = lat.modes().unwrap();
    /// let mut q0 = vec![0.0; 16];
    /// q0[7] = 1.0;
    /// let tr = lat.simulate(&modes, &q0, &[0.0; 16], &[0.0, 5.0, 10.0]).unwrap();
    /// let e = lat.total_energy(&tr);
    /// assert!((e[2] - e[0]).abs() < 1e-14 * e[0]); // undamped: energy conserved
    /// ```
    pub fn simulate(&self, modes: &Modes, q0: &[f64], v0: &[f64], t: &[f64]) -> Result<Trajectory> {
        let n = self.n();
        if modes.len() != n {
            return Err(LtiError::invalid(format!(
                "modes of a {}-particle lattice used for one of {n}",
                modes.len()
            )));
        }
        for (what, x) in [("q(0)", q0), ("q̇(0)", v0)] {
            modes.check_len(x.len())?;
            if let Some((i, v)) = x.iter().enumerate().find(|(_, v)| !v.is_finite()) {
                return Err(LtiError::NonFinite {
                    what: format!("{what} of particle {}", i + 1),
                    value: *v,
                });
            }
        }
        if let Some(&bad) = t.iter().find(|x| !(x.is_finite() && **x >= 0.0)) {
            return Err(LtiError::InvalidTime {
                value: bad,
                reason: "lattice simulation times must be finite and ≥ 0".into(),
            });
        }
        if t.is_empty() || n.saturating_mul(t.len()) > MAX_TRAJECTORY_VALUES {
            return Err(LtiError::invalid(format!(
                "a lattice trajectory needs 1…{} samples for N = {n}, got {}",
                MAX_TRAJECTORY_VALUES / n,
                t.len()
            )));
        }
        let z0 = modes.to_modal(q0)?;
        let zd0 = modes.to_modal(v0)?;
        let mut z = DMatrix::zeros(n, t.len());
        let mut zdot = DMatrix::zeros(n, t.len());
        for (i, &ti) in t.iter().enumerate() {
            for k in 0..n {
                let (a, b) =
                    modal_free_response(modes.damping[k], modes.omega[k], z0[k], zd0[k], ti);
                z[(k, i)] = a;
                zdot[(k, i)] = b;
            }
        }
        let q = &modes.t * &z;
        let v = &modes.t * &zdot;
        if let Some(x) = q.iter().chain(v.iter()).find(|x| !x.is_finite()) {
            return Err(LtiError::NonFinite {
                what: "the lattice trajectory".into(),
                value: *x,
            });
        }
        Ok(Trajectory {
            t: t.to_vec(),
            q,
            v,
            z,
            zdot,
        })
    }

    /// The energy of each particle per unit mass: ½q̇ₙ² plus half the potential energy
    /// ½ω0²r² of each bond it shares with another particle and all of a bond to a wall,
    /// so that the particle energies add up to the total energy.
    pub fn site_energies(&self, q: &[f64], v: &[f64]) -> Vec<f64> {
        let half_w2 = 0.5 * self.w0() * self.w0();
        let mut e: Vec<f64> = v.iter().map(|x| 0.5 * x * x).collect();
        if q.len() != self.n() || v.len() != self.n() {
            return e;
        }
        for (l, r) in self.bonds() {
            let at = |i: Option<usize>| i.map_or(0.0, |i| q[i]);
            let r2 = (at(r) - at(l)).powi(2);
            match (l, r) {
                (Some(a), Some(b)) => {
                    e[a] += 0.5 * half_w2 * r2;
                    e[b] += 0.5 * half_w2 * r2;
                }
                (Some(a), None) | (None, Some(a)) => e[a] += half_w2 * r2,
                (None, None) => {}
            }
        }
        e
    }

    /// The energy of the particles in `block` (0-based range) at every sample, per unit
    /// mass (seed fig. 2.18 for the middle 16).
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice, Packet};
    /// let lat = Lattice::new(64, Boundary::Periodic, 1.0).unwrap();
    /// let modes = lat.modes().unwrap();
    /// let q0 = Packet::zone_centre(8).displacements(&lat).unwrap();
    /// let tr = lat.simulate(&modes, &q0, &[0.0; 64], &[0.0, 20.0]).unwrap();
    /// let e = lat.block_energy(&tr, lat.middle(8).unwrap());
    /// assert!(e[1] < 1e-3 * e[0]); // gone at the speed of sound
    /// ```
    pub fn block_energy(&self, tr: &Trajectory, block: std::ops::Range<usize>) -> Vec<f64> {
        let block = block.start.min(self.n())..block.end.min(self.n());
        (0..tr.t.len())
            .map(|i| {
                let q: Vec<f64> = tr.q.column(i).iter().copied().collect();
                let v: Vec<f64> = tr.v.column(i).iter().copied().collect();
                self.site_energies(&q, &v)[block.clone()].iter().sum()
            })
            .collect()
    }

    /// The total energy per unit mass, ½|q̇|² + ½ω0²|Dq|², at every sample (from the
    /// displacements and velocities, independently of the modes).
    pub fn total_energy(&self, tr: &Trajectory) -> Vec<f64> {
        let d = self.bond_matrix();
        let r = &d * &tr.q;
        let w2 = self.w0() * self.w0();
        (0..tr.t.len())
            .map(|i| 0.5 * tr.v.column(i).norm_squared() + 0.5 * w2 * r.column(i).norm_squared())
            .collect()
    }
}

impl Trajectory {
    /// Hₖ(tᵢ) (2.78) from the sampled displacements and velocities projected on the modes
    /// (z = Tᵀq, ż = Tᵀq̇): N × samples.
    pub fn modal_energies(&self, modes: &Modes) -> DMatrix<f64> {
        let z = modes.t.tr_mul(&self.q);
        let zd = modes.t.tr_mul(&self.v);
        DMatrix::from_fn(z.nrows(), z.ncols(), |k, i| {
            0.5 * (zd[(k, i)] * zd[(k, i)] + (modes.omega[k] * z[(k, i)]).powi(2))
        })
    }

    /// max over modes and samples of |Hₖ(t) − Hₖ(0)|, relative to the total energy at the
    /// first sample (0 for a state at rest). For an undamped lattice every Hₖ is an invariant
    /// (eqs. 2.80–2.81), so this is the simulation's drift.
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice, Packet};
    /// let lat = Lattice::new(32, Boundary::Fixed, 1.0).unwrap();
    /// let modes = lat.modes().unwrap();
    /// let q0 = Packet::zone_edge(8).displacements(&lat).unwrap();
    /// let t: Vec<f64> = (0..100).map(|i| i as f64).collect();
    /// let tr = lat.simulate(&modes, &q0, &[0.0; 32], &t).unwrap();
    /// assert!(tr.modal_energy_drift(&modes) < 1e-14);
    /// ```
    pub fn modal_energy_drift(&self, modes: &Modes) -> f64 {
        let h = self.modal_energies(modes);
        if h.ncols() == 0 {
            return 0.0;
        }
        let total: f64 = h.column(0).sum();
        if total <= 0.0 {
            return 0.0;
        }
        let mut worst = 0.0f64;
        for i in 0..h.ncols() {
            for k in 0..h.nrows() {
                worst = worst.max((h[(k, i)] - h[(k, 0)]).abs());
            }
        }
        worst / total
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The free response satisfies z̈ + c ż + ω² z = 0 (central differences of ż) and the
    /// initial conditions, in every regime.
    #[test]
    fn free_response_solves_the_oscillator() {
        for (c, w) in [
            (0.0, 1.0),
            (0.3, 1.0),
            (2.0, 1.0),
            (5.0, 1.0),
            (1.0, 0.0),
            (0.0, 0.0),
        ] {
            let (z, v) = modal_free_response(c, w, 0.7, -0.4, 0.0);
            assert!((z - 0.7).abs() < 1e-15 && (v + 0.4).abs() < 1e-15);
            for t in [0.3, 1.7, 6.0] {
                let h = 1e-5;
                let (z, v) = modal_free_response(c, w, 0.7, -0.4, t);
                let (_, vp) = modal_free_response(c, w, 0.7, -0.4, t + h);
                let (_, vm) = modal_free_response(c, w, 0.7, -0.4, t - h);
                let acc = (vp - vm) / (2.0 * h);
                assert!((acc + c * v + w * w * z).abs() < 1e-8, "c {c} w {w} t {t}");
            }
        }
    }

    #[test]
    fn overdamped_slow_mode_does_not_cancel() {
        // c = 1e8, ω = 1: the slow rate is −1e-8 (the naive −σ + κ loses every digit).
        let (z, _) = modal_free_response(1e8, 1.0, 1.0, 0.0, 1e8);
        assert!((z - (-1.0f64).exp()).abs() < 1e-12, "{z}");
    }
}
