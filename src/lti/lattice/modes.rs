//! The modal decomposition of §2.4.1.2 computed numerically: T from the symmetric
//! eigenproblem of Ω, modes sorted by increasing frequency, and the checks that T is
//! orthogonal and TᵀΩT = diag(−ωₖ²).

use nalgebra::{DMatrix, DVector, SymmetricEigen};
use num_complex::Complex64;
use std::f64::consts::PI;

use super::closed_form::oscillator_roots;
use super::{Boundary, Lattice};
use crate::error::{LtiError, Result};

/// The lattice's modes, in order of increasing frequency.
#[derive(Debug, Clone, PartialEq)]
pub struct Modes {
    /// The modal matrix T (N × N, orthogonal): column k is the shape of mode k, q = T z.
    pub t: DMatrix<f64>,
    /// ωₖ (rad/s) = ω0·‖D tₖ‖, the square root of the Rayleigh quotient −tₖᵀΩtₖ evaluated
    /// through the bond stretches D tₖ (see [`Lattice::modes`]).
    pub omega: Vec<f64>,
    /// ωₖ² = −λₖ(Ω) as the symmetric eigensolver returned it.
    pub omega_sq: Vec<f64>,
    /// Mode damping cₖ = γ + ηωₖ² (1/s).
    pub damping: Vec<f64>,
    /// The wave number |k|a (rad, 0…π) of each mode shape: the peak of its discrete Fourier
    /// transform (periodic) or sine transform (fixed).
    pub wavenumber: Vec<f64>,
}

/// How well T diagonalises Ω (all relative to ω0², except the orthogonality).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiagonalCheck {
    /// max |(TᵀΩT)ᵢⱼ| over i ≠ j, divided by ω0².
    pub off_diagonal: f64,
    /// max |(TᵀΩT)ₖₖ + ωₖ²| against the closed-form ωₖ², divided by ω0².
    pub diagonal: f64,
    /// max |(TᵀT − I)ᵢⱼ|.
    pub orthogonality: f64,
    /// The largest increase of (TᵀΩT)ₖₖ from one mode to the next, divided by ω0²: ≤ 0
    /// when −(TᵀΩT)ₖₖ = ωₖ² is non-decreasing; positive only by rounding inside a degenerate
    /// pair.
    pub order_violation: f64,
}

impl Lattice {
    /// The modes from the symmetric eigenproblem of K = DᵀD = −Ω/ω0² (nalgebra
    /// `SymmetricEigen`: Householder tridiagonalisation and implicit QR), sorted by
    /// increasing frequency.
    ///
    /// The frequencies are taken as ωₖ = ω0‖D tₖ‖ rather than ω0√λₖ(K): the eigenvalue
    /// carries an absolute error of order eps·‖K‖, which the square root turns into ~1e-8·ω0
    /// for the rigid mode of the periodic lattice (ω = 0), whereas D tₖ is a difference of
    /// neighbouring entries of an accurate eigenvector and keeps ω = 0 at the rounding level.
    ///
    /// Errors: the eigensolver does not converge within 100 N sweeps.
    pub fn modes(&self) -> Result<Modes> {
        let n = self.n();
        let d = self.bond_matrix();
        let k = d.transpose() * &d;
        let eig = SymmetricEigen::try_new(k, f64::EPSILON, 100 * n).ok_or_else(|| {
            LtiError::NoConvergence {
                what: "the symmetric eigensolver of the lattice".into(),
                iterations: 100 * n,
            }
        })?;
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
        let mut t = DMatrix::zeros(n, n);
        for (col, &src) in order.iter().enumerate() {
            let mut v = eig.eigenvectors.column(src).into_owned();
            // A deterministic sign: the largest entry (first of equals) positive.
            let imax = v.iamax();
            if v[imax] < 0.0 {
                v.neg_mut();
            }
            t.set_column(col, &v);
        }
        let w0 = self.w0();
        let stretches = &d * &t;
        let omega: Vec<f64> = (0..n).map(|c| w0 * stretches.column(c).norm()).collect();
        let omega_sq = order
            .iter()
            .map(|&i| w0 * w0 * eig.eigenvalues[i])
            .collect();
        let damping = omega.iter().map(|&w| self.mode_damping(w)).collect();
        let wavenumber = (0..n)
            .map(|c| shape_wavenumber(self.boundary(), t.column(c).as_slice()))
            .collect();
        Ok(Modes {
            t,
            omega,
            omega_sq,
            damping,
            wavenumber,
        })
    }
}

/// The |k|a (0…π) at which a mode shape's transform peaks: DFT over the ring (periodic,
/// k and −k folded together), sine transform for fixed ends.
fn shape_wavenumber(boundary: Boundary, v: &[f64]) -> f64 {
    let n = v.len();
    let nf = n as f64;
    let mut best = (0.0, -1.0);
    match boundary {
        Boundary::Periodic => {
            let table: Vec<(f64, f64)> = (0..n)
                .map(|m| (2.0 * PI * m as f64 / nf).sin_cos())
                .collect();
            for p in 0..=n / 2 {
                let (mut re, mut im) = (0.0, 0.0);
                for (i, x) in v.iter().enumerate() {
                    let (s, c) = table[(p * (i + 1)) % n];
                    re += x * c;
                    im -= x * s;
                }
                let power = re * re + im * im;
                if power > best.1 {
                    best = (2.0 * PI * p as f64 / nf, power);
                }
            }
        }
        Boundary::Fixed => {
            let m = 2 * (n + 1);
            let table: Vec<f64> = (0..m).map(|j| (PI * j as f64 / (nf + 1.0)).sin()).collect();
            for k in 1..=n {
                let s: f64 = v
                    .iter()
                    .enumerate()
                    .map(|(i, x)| x * table[(k * (i + 1)) % m])
                    .sum();
                if s * s > best.1 {
                    best = (PI * k as f64 / (nf + 1.0), s * s);
                }
            }
        }
    }
    best.0
}

impl Modes {
    /// Number of modes N.
    pub fn len(&self) -> usize {
        self.omega.len()
    }

    /// Always false (a lattice has at least two modes); for clippy's `len` convention.
    pub fn is_empty(&self) -> bool {
        self.omega.is_empty()
    }

    /// The 2N eigenvalues of A, two per mode (roots of s² + cₖ s + ωₖ²).
    pub fn eigenvalues(&self) -> Vec<Complex64> {
        self.omega
            .iter()
            .zip(&self.damping)
            .flat_map(|(&w, &c)| oscillator_roots(c, w))
            .collect()
    }

    /// TᵀΩT against diag(−ωₖ²) with the closed-form frequencies of `lattice` (the lattice
    /// these modes were computed for).
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice};
    /// let lat = Lattice::new(32, Boundary::Periodic, 1.0).unwrap();
    /// let c = lat.modes().unwrap().diagonal_check(&lat).unwrap();
    /// assert!(c.off_diagonal < 1e-13 && c.diagonal < 1e-13 && c.orthogonality < 1e-13);
    /// assert!(c.order_violation < 1e-14);
    /// ```
    pub fn diagonal_check(&self, lattice: &Lattice) -> Result<DiagonalCheck> {
        let n = lattice.n();
        if self.t.nrows() != n || self.t.ncols() != n {
            return Err(LtiError::invalid(format!(
                "modes of a {}-particle lattice checked against one of {n}",
                self.t.nrows()
            )));
        }
        let w2 = lattice.w0() * lattice.w0();
        let dm = self.t.transpose() * lattice.omega_matrix() * &self.t;
        let gram = self.t.transpose() * &self.t;
        let exact = lattice.frequencies_closed_form();
        let (mut off, mut orth, mut diag, mut viol) = (0.0f64, 0.0f64, 0.0f64, f64::NEG_INFINITY);
        for i in 0..n {
            for j in 0..n {
                let g = gram[(i, j)] - if i == j { 1.0 } else { 0.0 };
                orth = orth.max(g.abs());
                if i != j {
                    off = off.max(dm[(i, j)].abs() / w2);
                }
            }
            diag = diag.max((dm[(i, i)] + exact[i] * exact[i]).abs() / w2);
            if i > 0 {
                viol = viol.max((dm[(i, i)] - dm[(i - 1, i - 1)]) / w2);
            }
        }
        Ok(DiagonalCheck {
            off_diagonal: off,
            diagonal: diag,
            orthogonality: orth,
            order_violation: viol,
        })
    }

    /// Modal coordinates z = Tᵀq (and ż = Tᵀq̇ alike).
    pub fn to_modal(&self, q: &[f64]) -> Result<DVector<f64>> {
        self.check_len(q.len())?;
        Ok(self.t.tr_mul(&DVector::from_column_slice(q)))
    }

    /// The modal energies Hₖ = ½(żₖ² + ωₖ²zₖ²) (2.78) of the state (q, q̇), per unit mass.
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice};
    /// let lat = Lattice::new(8, Boundary::Fixed, 1.0).unwrap();
    /// let modes = lat.modes().unwrap();
    /// let q: Vec<f64> = modes.t.column(2).iter().copied().collect(); // mode 3 alone
    /// let h = modes.energies(&q, &[0.0; 8]).unwrap();
    /// assert!((h[2] - 0.5 * modes.omega[2].powi(2)).abs() < 1e-15);
    /// assert!(h.iter().enumerate().all(|(k, e)| k == 2 || *e < 1e-30));
    /// ```
    pub fn energies(&self, q: &[f64], v: &[f64]) -> Result<Vec<f64>> {
        let z = self.to_modal(q)?;
        let zd = self.to_modal(v)?;
        Ok((0..self.len())
            .map(|k| 0.5 * (zd[k] * zd[k] + (self.omega[k] * z[k]).powi(2)))
            .collect())
    }

    pub(super) fn check_len(&self, len: usize) -> Result<()> {
        if len == self.len() {
            Ok(())
        } else {
            Err(LtiError::invalid(format!(
                "a lattice state needs {} values per vector, got {len}",
                self.len()
            )))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rigid_mode_frequency_is_at_rounding_level() {
        let lat = Lattice::new(64, Boundary::Periodic, 1.0).unwrap();
        let m = lat.modes().unwrap();
        assert!(m.omega[0] < 1e-14, "{}", m.omega[0]);
        assert!(m.wavenumber[0] == 0.0);
        assert!((m.wavenumber[63] - PI).abs() < 1e-15);
    }
}
