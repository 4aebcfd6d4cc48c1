//! Closed forms of the linear lattice: dispersion law, mode frequencies and wave numbers,
//! the eigenvalues of A, the modal matrix T of §2.4.1.2, and the force → displacement
//! transfer function as a modal sum.
//!
//! **Periodic** (N particles on a ring, eq. 2.69). qₙ = e^{jnθ} satisfies qₙ₊N = qₙ for
//! θ = 2πp/N, p = 0…N−1, and ω0²(qₙ₊₁ − 2qₙ + qₙ₋₁) = ω0²(2cos θ − 2)qₙ = −4ω0² sin²(θ/2) qₙ,
//! so Ω has the eigenvalues −ωₚ² with ωₚ = 2ω0 |sin(πp/N)| — the dispersion law (2.71)
//! ω(k) = 2ω0 sin(ka/2) sampled at ka = 2πp/N. Ordered by frequency, the modes are
//! p = 0 (the rigid translation, ω = 0), the degenerate pairs p and N − p (wave number
//! |k|a = 2πp/N, a left- and a right-running wave, or a sine and a cosine standing wave) for
//! 1 ≤ p < N/2, and for even N the zone edge p = N/2 (ω = 2ω0, qₙ ∝ (−1)ⁿ). The eigenvalues of
//! A are ±j·2ω0 sin(πp/N): a pair ±jω of multiplicity 2 (semisimple) for every degenerate
//! pair, and for p = 0 the eigenvalue 0 with algebraic multiplicity 2 but one eigenvector
//! (q = q0 + v0 t: a 2×2 Jordan block) — unless γ > 0 splits it into 0 and −γ.
//!
//! **Fixed ends** (walls at sites 0 and N + 1). qₙ = sin(nθ) vanishes at n = 0 and, for
//! θ = πk/(N + 1), at n = N + 1; the same computation gives ωₖ = 2ω0 sin(πk/(2(N + 1))),
//! k = 1…N: N distinct frequencies, none zero, standing waves of wave number ka = πk/(N + 1).
//!
//! **Damping** cₖ = γ + ηωₖ² turns each ±jωₖ into the roots of s² + cₖ s + ωₖ².
//!
//! **Zeros of a fixed-end channel** (force on particle j, displacement of particle i; lo, hi
//! the smaller and the larger of the two). With Ω = −ω0²K, K = tridiag(−1, 2, −1), every
//! factor of the damped lattice is s²I + s(γI + ηω0²K) + ω0²K = (1 + ηs)(wI + ω0²K) with
//! w = (s² + γs)/(1 + ηs), so G(s) = H(w)/(m(1 + ηs)) where H(w) = eᵢᵀ(wI + ω0²K)⁻¹eⱼ is the
//! undamped channel with s² replaced by w. The cofactor of the tridiagonal wI + ω0²K is
//! det(wI + ω0²K_(lo−1))·det(wI + ω0²K_(N−hi))·(ω0²)^(hi−lo) (the blocks before lo and after
//! hi; the bonds between contribute the power of ω0²), so H has the zeros
//! w = −4ω0² sin²(πl/(2 lo)), l = 1…lo−1, and w = −4ω0² sin²(πl/(2(N − hi + 1))),
//! l = 1…N−hi, over the poles w = −ωₖ², and the gain (ω0²)^(hi−lo). A value of a block is a
//! mode value exactly when the mode has a node at lo (at hi): sin(πk·lo/(N + 1)) = 0 ⇔
//! k/(N + 1) = l/lo. Such a mode is not in the channel, and it cancels one copy of its value
//! from the zeros — a mode with nodes at both particles leaves one copy. H then has
//! relative degree ρ = hi − lo + 1 in w. In s each factor w − a is
//! (s² + (γ − ηa)s − a)/(1 + ηs): G has two zeros per zero of H, ρ − 1 zeros at −1/η
//! (η > 0), relative degree ρ + 1 (2ρ without η) and the gain (ω0²)^(hi−lo)·η^(ρ−1)/m.

use nalgebra::DMatrix;
use num_complex::Complex64;
use std::f64::consts::PI;

use super::{Boundary, Lattice, Output};
use crate::error::{LtiError, Result};

/// The dispersion law (2.71): ω(k) = 2ω0 |sin(ka/2)| for the wave number times the lattice
/// spacing, `ka` (rad).
///
/// ```
/// use ltikit::lti::lattice::closed_form::dispersion;
/// assert!((dispersion(1.0, std::f64::consts::PI) - 2.0).abs() < 1e-15); // zone edge
/// assert!((dispersion(3.0, 1e-6) - 3e-6).abs() < 1e-18); // sound speed a·ω0 at the centre
/// ```
pub fn dispersion(w0: f64, ka: f64) -> f64 {
    2.0 * w0 * (0.5 * ka).sin().abs()
}

/// The group velocity dω/dk = aω0 cos(ka/2) (seed §2.4.1.1) in lattice spacings per second.
///
/// ```
/// use ltikit::lti::lattice::closed_form::group_velocity;
/// assert!(group_velocity(1.0, std::f64::consts::PI).abs() < 1e-16); // zone-edge phonons stand
/// ```
pub fn group_velocity(w0: f64, ka: f64) -> f64 {
    w0 * (0.5 * ka).cos()
}

/// The two roots of s² + c s + ω² (c, ω ≥ 0), without cancellation: complex conjugates for
/// c < 2ω (the one with positive imaginary part first), otherwise real, the larger magnitude
/// first.
///
/// ```
/// use ltikit::lti::lattice::closed_form::oscillator_roots;
/// let [a, b] = oscillator_roots(1.2, 1.0); // s² + 1.2s + 1: −0.6 ± 0.8j
/// assert!((a.re + 0.6).abs() < 1e-15 && (a.im - 0.8).abs() < 1e-15 && b == a.conj());
/// let [f, s] = oscillator_roots(1e9, 1.0); // slow root −1e-9 without cancellation
/// assert!((s.re + 1e-9).abs() < 1e-24 && (f.re + 1e9).abs() < 1.0);
/// ```
pub fn oscillator_roots(c: f64, omega: f64) -> [Complex64; 2] {
    let h = 0.5 * c;
    if h < omega {
        let wd = ((omega - h) * (omega + h)).sqrt();
        [Complex64::new(-h, wd), Complex64::new(-h, -wd)]
    } else {
        let big = -h - ((h - omega) * (h + omega)).sqrt();
        let small = if big == 0.0 { 0.0 } else { omega * omega / big };
        [Complex64::new(big, 0.0), Complex64::new(small, 0.0)]
    }
}

impl Lattice {
    /// The folded mode index p of each mode in order of increasing frequency: 0, 1, 1, 2, 2,
    /// …, (N/2 for even N) when periodic; 1, 2, …, N when fixed.
    fn mode_indices(&self) -> Vec<usize> {
        let n = self.n();
        match self.boundary() {
            Boundary::Periodic => {
                let mut p: Vec<usize> = (0..n).map(|j| j.min(n - j)).collect();
                p.sort_unstable();
                p
            }
            Boundary::Fixed => (1..=n).collect(),
        }
    }

    /// The wave number ka (rad, in [0, π]) of each mode in order of increasing frequency:
    /// 2πp/N (periodic; each degenerate pair twice) or πk/(N + 1) (fixed).
    pub fn wavenumbers_closed_form(&self) -> Vec<f64> {
        let n = self.n() as f64;
        self.mode_indices()
            .into_iter()
            .map(|p| match self.boundary() {
                Boundary::Periodic => 2.0 * PI * p as f64 / n,
                Boundary::Fixed => PI * p as f64 / (n + 1.0),
            })
            .collect()
    }

    /// The N mode frequencies ωₖ in increasing order: 2ω0 sin(πp/N) (periodic) or
    /// 2ω0 sin(πk/(2(N + 1))) (fixed).
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice};
    /// let w = Lattice::new(4, Boundary::Periodic, 1.0).unwrap().frequencies_closed_form();
    /// let r = std::f64::consts::SQRT_2;
    /// assert!(w.iter().zip([0.0, r, r, 2.0]).all(|(a, b)| (a - b).abs() < 1e-15));
    /// ```
    pub fn frequencies_closed_form(&self) -> Vec<f64> {
        let n = self.n() as f64;
        self.mode_indices()
            .into_iter()
            .map(|p| {
                let x = match self.boundary() {
                    Boundary::Periodic => PI * p as f64 / n,
                    Boundary::Fixed => PI * p as f64 / (2.0 * (n + 1.0)),
                };
                2.0 * self.w0() * x.sin()
            })
            .collect()
    }

    /// The 2N eigenvalues of A, mode by mode in order of increasing frequency (each mode's
    /// two roots of s² + cₖ s + ωₖ², see [`oscillator_roots`]).
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice};
    /// let ev = Lattice::new(6, Boundary::Periodic, 1.0).unwrap().eigenvalues_closed_form();
    /// assert_eq!(ev.len(), 12);
    /// assert_eq!((ev[0].norm(), ev[1].norm()), (0.0, 0.0)); // the rigid mode's double 0
    /// assert!((ev[2].im - 1.0).abs() < 1e-15 && (ev[4].im - 1.0).abs() < 1e-15); // a pair
    /// ```
    pub fn eigenvalues_closed_form(&self) -> Vec<Complex64> {
        self.frequencies_closed_form()
            .into_iter()
            .flat_map(|w| oscillator_roots(self.mode_damping(w), w))
            .collect()
    }

    /// The modal matrix T of §2.4.1.2 (orthogonal; column k is mode k, in order of
    /// increasing frequency). Periodic, as the seed writes it: 1/√N; then for each pair
    /// √(2/N) sin(2πpn/N) and √(2/N) cos(2πpn/N); for even N last (−1)ⁿ/√N (n = 1…N).
    /// Fixed: √(2/(N + 1)) sin(πkn/(N + 1)).
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice};
    /// let lat = Lattice::new(8, Boundary::Periodic, 1.0).unwrap();
    /// let t = lat.modal_matrix_closed_form();
    /// let d = t.transpose() * lat.omega_matrix() * &t; // diag(−ωₖ²), increasing ωₖ
    /// assert!((d[(7, 7)] + 4.0).abs() < 1e-14 && d[(2, 3)].abs() < 1e-14);
    /// ```
    pub fn modal_matrix_closed_form(&self) -> DMatrix<f64> {
        let n = self.n();
        let nf = n as f64;
        let mut t = DMatrix::zeros(n, n);
        match self.boundary() {
            Boundary::Periodic => {
                let pairs = (n - 1) / 2;
                for row in 0..n {
                    t[(row, 0)] = 1.0 / nf.sqrt();
                    for p in 1..=pairs {
                        let th = 2.0 * PI * ((p * (row + 1)) % n) as f64 / nf;
                        t[(row, 2 * p - 1)] = (2.0 / nf).sqrt() * th.sin();
                        t[(row, 2 * p)] = (2.0 / nf).sqrt() * th.cos();
                    }
                    if n % 2 == 0 {
                        t[(row, n - 1)] = if (row + 1) % 2 == 0 { 1.0 } else { -1.0 } / nf.sqrt();
                    }
                }
            }
            Boundary::Fixed => {
                let s = (2.0 / (nf + 1.0)).sqrt();
                for row in 0..n {
                    for k in 0..n {
                        // sin(πkn/(N+1)) with the argument reduced exactly modulo 2(N+1).
                        let m = ((k + 1) * (row + 1)) % (2 * (n + 1));
                        t[(row, k)] = s * (PI * m as f64 / (nf + 1.0)).sin();
                    }
                }
            }
        }
        t
    }

    /// The transfer function from a force on particle `j` to the displacement of particle
    /// `i` (both 1-based) as a sum over the distinct mode frequencies, with the modal weights
    /// in closed form (see [`ModalSum`]).
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice};
    /// use num_complex::Complex64;
    /// let lat = Lattice::new(4, Boundary::Fixed, 1.0).unwrap();
    /// // Static compliance of the fixed chain: (K⁻¹)ᵢⱼ = i(N+1−j)/(N+1) for i ≤ j.
    /// let g = lat.modal_sum(1, 3).unwrap().eval(Complex64::new(0.0, 0.0));
    /// assert!((g.re - 2.0 / 5.0).abs() < 1e-15);
    /// ```
    pub fn modal_sum(&self, i: usize, j: usize) -> Result<ModalSum> {
        let n = self.n();
        for (name, v) in [("output", i), ("input", j)] {
            if v == 0 || v > n {
                return Err(LtiError::invalid(format!(
                    "lattice channel: {name} particle {v} is not one of 1…{n}"
                )));
            }
        }
        let nf = n as f64;
        let (mut weight, mut omega, mut damping) = (Vec::new(), Vec::new(), Vec::new());
        let mut push = |w: f64, p: f64| {
            let om = 2.0 * self.w0() * p.sin();
            weight.push(w / self.mass());
            omega.push(om);
            damping.push(self.mode_damping(om));
        };
        match self.boundary() {
            Boundary::Periodic => {
                // Σ over the pair p, N − p of Tᵢₖ Tⱼₖ = (2/N) cos(2πp(i − j)/N); exactly zero
                // when 4p·d ≡ N (mod 2N).
                let d = i.abs_diff(j);
                for p in 0..=n / 2 {
                    let mult = if p == 0 || 2 * p == n { 1.0 } else { 2.0 };
                    let c = if (4 * p * d) % (2 * n) == n {
                        0.0
                    } else {
                        (2.0 * PI * ((p * d) % n) as f64 / nf).cos()
                    };
                    push(mult * c / nf, PI * p as f64 / nf);
                }
            }
            Boundary::Fixed => {
                let s = |k: usize, x: usize| {
                    if (k * x) % (n + 1) == 0 {
                        0.0
                    } else {
                        (PI * ((k * x) % (2 * (n + 1))) as f64 / (nf + 1.0)).sin()
                    }
                };
                for k in 1..=n {
                    push(
                        2.0 / (nf + 1.0) * s(k, i) * s(k, j),
                        PI * k as f64 / (2.0 * (nf + 1.0)),
                    );
                }
            }
        }
        Ok(ModalSum {
            weight,
            omega,
            damping,
        })
    }
}

/// A lattice channel as a modal sum G(s) = Σₖ wₖ / (s² + cₖ s + ωₖ²) over distinct mode
/// frequencies ωₖ (a reference for frequency responses and for the minimal realisation).
#[derive(Debug, Clone, PartialEq)]
pub struct ModalSum {
    /// Weights wₖ (1/kg); exactly zero for a mode the channel cannot see (a node of the mode
    /// shape at the input or at the output particle).
    pub weight: Vec<f64>,
    /// The distinct mode frequencies ωₖ (rad/s), increasing.
    pub omega: Vec<f64>,
    /// Mode damping cₖ = γ + ηωₖ² (1/s).
    pub damping: Vec<f64>,
}

impl ModalSum {
    /// G(s).
    pub fn eval(&self, s: Complex64) -> Complex64 {
        let s2 = s * s;
        self.weight
            .iter()
            .zip(self.omega.iter().zip(&self.damping))
            .filter(|(w, _)| **w != 0.0)
            .map(|(w, (om, c))| *w / (s2 + s * *c + om * om))
            .sum()
    }

    /// The order of a minimal realisation: two states per mode with a non-zero weight
    /// (exact for distinct poles, i.e. when no two overdamped modes share a real pole).
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice};
    /// // Driven and measured at the centre of 7 fixed particles: the antisymmetric modes
    /// // (k = 2, 4, 6) have a node there and drop out.
    /// let lat = Lattice::new(7, Boundary::Fixed, 1.0).unwrap();
    /// assert_eq!(lat.modal_sum(4, 4).unwrap().minimal_order(), 8);
    /// ```
    pub fn minimal_order(&self) -> usize {
        2 * self.weight.iter().filter(|w| **w != 0.0).count()
    }

    /// The poles of G in lowest terms (the roots of s² + cₖ s + ωₖ² of every visible mode).
    pub fn poles(&self) -> Vec<Complex64> {
        self.weight
            .iter()
            .zip(self.omega.iter().zip(&self.damping))
            .filter(|(w, _)| **w != 0.0)
            .flat_map(|(_, (om, c))| oscillator_roots(*c, *om))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn oscillator_roots_cover_all_regimes() {
        let [a, b] = oscillator_roots(0.0, 2.0);
        assert_eq!((a.re, a.im, b.im), (0.0, 2.0, -2.0));
        let [a, b] = oscillator_roots(4.0, 2.0);
        assert!((a.re + 2.0).abs() < 1e-7 && (b.re + 2.0).abs() < 1e-7);
        let [a, b] = oscillator_roots(1e8, 1.0);
        assert!((b.re + 1e-8).abs() < 1e-22 && (a.re + 1e8).abs() < 1e-6);
        assert_eq!(oscillator_roots(0.0, 0.0), [Complex64::new(0.0, 0.0); 2]);
        let [a, b] = oscillator_roots(3.0, 0.0);
        assert_eq!((a.re, b.re), (-3.0, 0.0));
    }

    #[test]
    fn collocated_periodic_channel_sees_one_mode_per_frequency() {
        let lat = Lattice::new(128, Boundary::Periodic, 1.0).unwrap();
        assert_eq!(lat.modal_sum(1, 1).unwrap().minimal_order(), 130);
        // d = 32 = N/4: cos(2πp/4) vanishes for odd p.
        assert_eq!(lat.modal_sum(1, 33).unwrap().minimal_order(), 2 * 33);
    }
}

/// The zeros of a fixed-end lattice channel in closed form ([`Lattice::channel_zeros_closed_form`],
/// derived in the [module docs](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelZeros {
    /// The zeros of the undamped channel H(w) in w (w = s² without damping), after the
    /// values shared with a mode not in the channel cancel; increasing.
    pub w_zeros: Vec<f64>,
    /// H's relative degree in w, ρ = |i − j| + 1.
    pub w_relative_degree: usize,
    /// The zeros of G(s) other than −1/η: the two roots of s² + (γ − ηw)s − w for each zero
    /// w of H.
    pub zeros: Vec<Complex64>,
    /// The multiplicity of the zero at −1/η: ρ − 1 with η > 0, else 0.
    pub eta_zero_multiplicity: usize,
    /// G's relative degree: ρ + 1 with η > 0, 2ρ without.
    pub relative_degree: usize,
    /// G's gain, the ratio of the leading coefficients: (ω0²)^(ρ−1)·η^(ρ−1)/m with η > 0,
    /// (ω0²)^(ρ−1)/m without.
    pub gain: f64,
}

impl Lattice {
    /// The zeros, relative degree and gain of the force → displacement channel of a lattice
    /// with fixed ends in closed form (the cofactor of the tridiagonal stiffness; Rayleigh
    /// damping maps them through w = (s² + γs)/(1 + ηs); see the [module docs](self)).
    ///
    /// Errors: periodic boundaries (the ring has no tridiagonal cofactor), all particles as
    /// the output, and γη = 1 (then every factor has the root −1/η and the forms degenerate).
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice, Output};
    /// // 5 fixed particles, force on 2, displacement of 4: each one-particle block (before 2,
    /// // after 4) gives the value −4 sin²(π/4) = −2, which is also the mode k = 3 (ω² = 2,
    /// // nodes at both particles): it cancels one copy, so H(w) = (w + 2)/Π(w + ωₖ²) over
    /// // the other four modes, ρ = 3.
    /// let lat = Lattice::new(5, Boundary::Fixed, 1.0).unwrap()
    ///     .with_input(2).unwrap().with_output(Output::Particle(4)).unwrap();
    /// let z = lat.channel_zeros_closed_form().unwrap();
    /// assert_eq!(z.w_relative_degree, 3);
    /// assert_eq!(z.w_zeros.len(), 1);
    /// assert!((z.w_zeros[0] + 2.0).abs() < 1e-15);
    /// assert_eq!((z.relative_degree, z.gain), (6, 1.0)); // undamped: 2ρ, (ω0²)²/m
    /// assert!(z.zeros.iter().all(|s| s.re == 0.0)); // ±j√2
    /// ```
    pub fn channel_zeros_closed_form(&self) -> Result<ChannelZeros> {
        let bad = |why: &str| Err(LtiError::invalid(format!("lattice channel zeros: {why}")));
        if self.boundary() != Boundary::Fixed {
            return bad("closed form for fixed ends only (the ring has no tridiagonal cofactor)");
        }
        let Output::Particle(out) = self.output() else {
            return bad("the output is every particle; choose one");
        };
        let (gamma, eta) = (self.gamma(), self.eta());
        if (1.0 - gamma * eta).abs() <= 1e-12 {
            return bad("γη = 1: every factor has the root −1/η");
        }
        let n = self.n();
        let (lo, hi) = (self.input().min(out), self.input().max(out));
        let w0sq = self.w0() * self.w0();
        // values −4ω0² sin²(πa/b) kept as the fraction a/b (of π/2), compared exactly
        let value =
            |a: usize, b: usize| -4.0 * w0sq * (PI * a as f64 / (2.0 * b as f64)).sin().powi(2);
        let mut blocks: Vec<(usize, usize)> = (1..lo).map(|l| (l, lo)).collect();
        blocks.extend((1..=n - hi).map(|l| (l, n - hi + 1)));
        // a mode k (value k/(N + 1)) equal to a block value cancels one copy of it
        let mut cancelled = vec![false; n + 1];
        let mut kept: Vec<f64> = Vec::new();
        for (a, b) in blocks {
            let mode = ((a * (n + 1)) % b == 0).then(|| a * (n + 1) / b);
            match mode {
                Some(k) if k <= n && !cancelled[k] => cancelled[k] = true,
                _ => kept.push(value(a, b)),
            }
        }
        kept.sort_by(f64::total_cmp);
        let rho = hi - lo + 1;
        let zeros = kept
            .iter()
            .flat_map(|&w| oscillator_roots(gamma - eta * w, (-w).sqrt()))
            .collect();
        let base = w0sq.powi((rho - 1) as i32) / self.mass();
        let (eta_zero_multiplicity, relative_degree, gain) = if eta > 0.0 {
            (rho - 1, rho + 1, base * eta.powi((rho - 1) as i32))
        } else {
            (0, 2 * rho, base)
        };
        Ok(ChannelZeros {
            w_zeros: kept,
            w_relative_degree: rho,
            zeros,
            eta_zero_multiplicity,
            relative_degree,
            gain,
        })
    }
}
