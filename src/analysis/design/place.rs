//! Pole placement: the state feedback u = −K x that gives A − BK the requested eigenvalues.
//!
//! - **One input** (m = 1): Ackermann's formula K = e_nᵀ W_c⁻¹ φ(A), W_c = \[B AB … A^(n−1)B\]
//!   the controllability matrix and φ the requested characteristic polynomial. The gain is
//!   unique, but the formula solves with W_c, whose condition number grows quickly with n (it
//!   is a Krylov matrix): about log₁₀ κ(W_c) digits of K are lost. [`Placement::condition`]
//!   reports κ(W_c) (2-norm) and [`Placement::conditioning_note`] warns beyond 1e8.
//! - **Several inputs**: the robust method of Kautsky, Nichols and Van Dooren (1985, method
//!   0, as `scipy.signal.place_poles(method="KNV0")`, here with complex pairs): the freedom
//!   left by m > 1 inputs is spent on well-conditioned closed-loop eigenvectors (see
//!   `design::knv`); [`Placement::condition`] is then κ(X) of the unit eigenvector matrix, the
//!   sensitivity of the placed poles. A pole may be requested at most rank(B) times (the
//!   eigenvectors of a repeated pole must be independent).
//!
//! The algebra is the same for a discrete plant (x\[k+1\] = (A − BK) x\[k\]): the requested
//! poles are then places in z.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::knv::knv0;
use super::poles::complex_label;
use super::poles::{check_poles, match_poles};
use crate::error::{LtiError, Result};
use crate::lti::StateSpace;
use crate::numeric::linalg::controllability_staircase;

/// Which method computed the gain.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlacementMethod {
    /// Ackermann's formula (one input).
    Ackermann,
    /// Kautsky–Nichols–Van Dooren, method 0 (several inputs).
    Knv0,
}

impl PlacementMethod {
    /// "ackermann" or "knv0".
    pub fn name(self) -> &'static str {
        match self {
            PlacementMethod::Ackermann => "ackermann",
            PlacementMethod::Knv0 => "knv0",
        }
    }
}

/// A pole placement: the gain and how well it did.
#[derive(Debug, Clone)]
pub struct Placement {
    /// K (m × n), for u = −K x.
    pub gain: DMatrix<f64>,
    /// The method used.
    pub method: PlacementMethod,
    /// The requested poles (conjugate partners made exact), in the given order.
    pub requested: Vec<Complex64>,
    /// The eigenvalues of A − BK, each facing its requested pole.
    pub achieved: Vec<Complex64>,
    /// |achieved − requested| for each pole.
    pub distance: Vec<f64>,
    /// max distance / the largest requested |pole| (‖A‖_F when every requested pole is 0).
    pub relative_error: f64,
    /// Ackermann: κ₂(W_c) of the controllability matrix; KNV: κ₂(X) of the unit
    /// eigenvector matrix of A − BK.
    pub condition: f64,
    /// KNV sweeps (0 for Ackermann).
    pub iterations: usize,
}

impl Placement {
    /// A warning when the achieved poles are more than 1e-6 (relative) off, when a pole is
    /// repeated with one input (a Jordan block), or when the condition figure says digits
    /// are lost (κ > 1e8: about log₁₀ κ of the 16 digits).
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use num_complex::Complex64 as C;
    /// use ltikit::analysis::design::place_matrices;
    /// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
    /// let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
    /// let p = place_matrices(&a, &b, &[C::new(-1.0, 0.0), C::new(-2.0, 0.0)]).unwrap();
    /// assert!(p.conditioning_note().is_none());
    /// ```
    pub fn conditioning_note(&self) -> Option<String> {
        if self.relative_error.is_nan() || self.relative_error > 1e-6 {
            return Some(format!(
                "the achieved poles are {} (relative) from the requested ones: the placement \
                 is too ill-conditioned for these poles (condition number {})",
                crate::fmt::fmt_sig(self.relative_error, 2),
                crate::fmt::fmt_sig(self.condition, 3)
            ));
        }
        if self.method == PlacementMethod::Ackermann {
            let most = self
                .requested
                .iter()
                .map(|p| self.requested.iter().filter(|q| *q == p).count())
                .max()
                .unwrap_or(1);
            if most > 1 {
                return Some(format!(
                    "a pole requested {most} times with one input is a Jordan block of A - BK: \
                     its computed eigenvalues scatter by about ε^(1/{most}) relative"
                ));
            }
        }
        (self.condition > 1e8).then(|| match self.method {
            PlacementMethod::Ackermann => format!(
                "Ackermann's formula solves with the controllability matrix, condition number \
                 {}: about {:.0} of 16 digits of the gain may be lost",
                crate::fmt::fmt_sig(self.condition, 3),
                self.condition.log10().min(16.0)
            ),
            PlacementMethod::Knv0 => format!(
                "the closed-loop eigenvector matrix has condition number {}: the placed poles \
                 are sensitive to perturbations of A, B and K",
                crate::fmt::fmt_sig(self.condition, 3)
            ),
        })
    }
}

/// [`place_matrices`] on the A and B of a state-space model (continuous or discrete: the
/// poles are in s or in z).
///
/// ```
/// use nalgebra::DMatrix;
/// use num_complex::Complex64 as C;
/// use ltikit::StateSpace;
/// use ltikit::analysis::design::place;
/// // double integrator: poles −1 ± 1j need K = [2, 2]
/// let ss = StateSpace::new(
///     DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]),
///     DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
///     DMatrix::from_row_slice(1, 2, &[1.0, 0.0]),
///     DMatrix::zeros(1, 1),
/// ).unwrap();
/// let p = place(&ss, &[C::new(-1.0, 1.0), C::new(-1.0, -1.0)]).unwrap();
/// assert!((p.gain[(0, 0)] - 2.0).abs() < 1e-14 && (p.gain[(0, 1)] - 2.0).abs() < 1e-14);
/// assert!(p.relative_error < 1e-14);
/// ```
pub fn place(ss: &StateSpace, poles: &[Complex64]) -> Result<Placement> {
    place_matrices(&ss.a, &ss.b, poles)
}

/// The gain K (u = −K x) that puts the eigenvalues of A − BK at `poles`, with the achieved
/// eigenvalues and a condition figure (see the [module docs](self)).
///
/// Errors: sizes that do not match, an empty or non-finite A or B, as many poles as states
/// not given, poles not closed under conjugation, an uncontrollable pair (A, B) (the modes
/// that no input reaches are named), B of rank below its columns (several inputs), a pole
/// requested more than rank(B) times (several inputs), states beyond
/// [`crate::limits::MAX_PLACE_STATES`].
///
/// ```
/// use nalgebra::DMatrix;
/// use num_complex::Complex64 as C;
/// use ltikit::analysis::design::place_matrices;
/// let a = DMatrix::from_row_slice(3, 3, &[0.0, 1.0, 0.0, 0.0, 0.0, 1.0, -1.0, -2.0, -3.0]);
/// let b = DMatrix::from_row_slice(3, 2, &[0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
/// let poles = [C::new(-1.0, 0.0), C::new(-2.0, 1.0), C::new(-2.0, -1.0)];
/// let p = place_matrices(&a, &b, &poles).unwrap();
/// assert!(p.relative_error < 1e-12);
/// let e = place_matrices(&a, &b, &poles[..2]).unwrap_err().to_string();
/// assert!(e.contains("2 poles requested"), "{e}");
/// ```
pub fn place_matrices(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    poles: &[Complex64],
) -> Result<Placement> {
    let (n, m) = check_pair(a, b)?;
    crate::limits::PLACE_STATES.check("`a`", n as u128)?;
    let (requested, partner) = check_poles(poles, n)?;
    let stairs = controllability_staircase(a, b, &DMatrix::zeros(0, n), None, false)?;
    if stairs.dim < n {
        let modes = crate::numeric::eigenvalues(&stairs.removed_block())?;
        let mut names: Vec<String> = modes.iter().map(|z| complex_label(*z, 6)).collect();
        names.dedup();
        return Err(LtiError::invalid(format!(
            "the pair (A, B) is not controllable: {} of {n} modes cannot be moved by state \
             feedback (at {})",
            n - stairs.dim,
            names.join(", ")
        )));
    }
    let (gain, method, condition, iterations) = if m == 1 {
        let (k, cond) = ackermann(a, b, &requested)?;
        (k, PlacementMethod::Ackermann, cond, 0)
    } else {
        let rank_b = stairs.blocks.first().copied().unwrap_or(0);
        if rank_b < m {
            return Err(LtiError::invalid(format!(
                "B has rank {rank_b} but {m} columns: the inputs are not independent (drop or \
                 combine the dependent ones)"
            )));
        }
        for (i, p) in requested.iter().enumerate() {
            let count = requested.iter().filter(|q| *q == p).count();
            if count > rank_b && requested[..i].iter().all(|q| q != p) {
                return Err(LtiError::invalid(format!(
                    "`poles`: {} is requested {count} times but B has rank {rank_b}: a pole \
                     can be placed at most rank(B) times",
                    complex_label(*p, 6)
                )));
            }
        }
        let r = knv0(a, b, &requested, &partner)?;
        (r.gain, PlacementMethod::Knv0, r.condition, r.iterations)
    };
    let closed = a - b * &gain;
    let eig = crate::numeric::eigenvalues(&closed)?;
    let (achieved, distance) = match_poles(&requested, &eig);
    let scale = requested.iter().map(|z| z.norm()).fold(0.0, f64::max).max(
        if requested.iter().all(|z| z.norm() == 0.0) {
            a.norm().max(f64::MIN_POSITIVE)
        } else {
            0.0
        },
    );
    let relative_error = distance.iter().copied().fold(0.0, f64::max) / scale;
    Ok(Placement {
        gain,
        method,
        requested,
        achieved,
        distance,
        relative_error,
        condition,
        iterations,
    })
}

/// Checks A (n × n) and B (n × m): sizes, finiteness; returns (n, m).
pub(crate) fn check_pair(a: &DMatrix<f64>, b: &DMatrix<f64>) -> Result<(usize, usize)> {
    let n = a.nrows();
    if a.ncols() != n || b.nrows() != n {
        return Err(LtiError::invalid(format!(
            "inconsistent dimensions: A {}×{}, B {}×{} (A square, B with as many rows)",
            a.nrows(),
            a.ncols(),
            b.nrows(),
            b.ncols()
        )));
    }
    if n == 0 || b.ncols() == 0 {
        return Err(LtiError::invalid(
            "the plant has no states or no inputs: there is nothing to feed back",
        ));
    }
    for (mat, name) in [(a, "A"), (b, "B")] {
        if let Some(x) = mat.iter().find(|x| !x.is_finite()) {
            return Err(LtiError::NonFinite {
                what: format!("an entry of {name}"),
                value: *x,
            });
        }
    }
    Ok((n, b.ncols()))
}

/// Ackermann's formula for one input; returns K (1 × n) and κ₂(W_c).
fn ackermann(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    poles: &[Complex64],
) -> Result<(DMatrix<f64>, f64)> {
    let n = a.nrows();
    let phi = crate::poly::Poly::from_roots(poles)?;
    let coeffs = phi.coeffs(); // monic, descending, n + 1 of them
    // φ(A) by Horner
    let mut pa = DMatrix::<f64>::identity(n, n);
    for &c in &coeffs[1..] {
        pa = &pa * a;
        for i in 0..n {
            pa[(i, i)] += c;
        }
    }
    let mut w = DMatrix::<f64>::zeros(n, n);
    let mut col = b.column(0).clone_owned();
    for j in 0..n {
        w.set_column(j, &col);
        col = a * &col;
    }
    let sv = w.clone().singular_values();
    let smax = sv.max();
    let smin = sv.min();
    let condition = if smin > 0.0 {
        smax / smin
    } else {
        f64::INFINITY
    };
    let mut e = nalgebra::DVector::<f64>::zeros(n);
    e[n - 1] = 1.0;
    let v = w
        .transpose()
        .lu()
        .solve(&e)
        .ok_or_else(|| LtiError::invalid("the controllability matrix is singular"))?;
    let k = DMatrix::from_row_slice(1, n, (v.transpose() * pa).as_slice());
    if k.iter().any(|x| !x.is_finite()) {
        return Err(LtiError::invalid(
            "Ackermann's formula overflowed: the requested poles or A are too large",
        ));
    }
    Ok((k, condition))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(re: f64, im: f64) -> Complex64 {
        Complex64::new(re, im)
    }

    #[test]
    fn ackermann_third_order() {
        // A in companion form: K = desired coefficients − open-loop ones (closed form)
        let a = DMatrix::from_row_slice(3, 3, &[0.0, 1.0, 0.0, 0.0, 0.0, 1.0, -6.0, -11.0, -6.0]);
        let b = DMatrix::from_row_slice(3, 1, &[0.0, 0.0, 1.0]);
        // (s+2)(s²+2s+5) = s³ + 4s² + 9s + 10 → K = [10−6, 9−11, 4−6]
        let p = place_matrices(&a, &b, &[c(-2.0, 0.0), c(-1.0, 2.0), c(-1.0, -2.0)]).unwrap();
        let want = [4.0, -2.0, -2.0];
        for (j, w) in want.iter().enumerate() {
            assert!((p.gain[(0, j)] - w).abs() < 1e-13, "{}", p.gain);
        }
        assert_eq!(p.method, PlacementMethod::Ackermann);
        assert!(p.relative_error < 1e-13);
    }

    #[test]
    fn uncontrollable_mode_is_named() {
        let a = DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -2.0]);
        let b = DMatrix::from_row_slice(2, 1, &[1.0, 0.0]);
        let e = place_matrices(&a, &b, &[c(-3.0, 0.0), c(-4.0, 0.0)])
            .unwrap_err()
            .to_string();
        assert!(e.contains("not controllable") && e.contains("-2"), "{e}");
    }
}
