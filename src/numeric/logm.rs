//! The principal real matrix logarithm, by inverse scaling and squaring (Kenney & Laub 1989;
//! Higham, "Functions of Matrices", 2008, §11.5).
//!
//! # Method
//! 1. **Square roots** until ‖X − I‖₁ ≤ ½: X ← X^(1/2) by the coupled Denman–Beavers iteration
//!    Y ← (Y + Z⁻¹)/2, Z ← (Z + Y⁻¹)/2 (Y → X^(1/2), Z → X^(−1/2); numerically stable, and it
//!    stays real for a real X), k times.
//! 2. **Padé approximant** of log(I + E), E = X − I, in its partial-fraction form: the
//!    m-point Gauss–Legendre rule on log(I + E) = ∫₀¹ E (I + tE)⁻¹ dt is the [m/m] Padé
//!    approximant (Dieci, Morini & Papini 1996). With m = 16 and ‖E‖₁ ≤ ½ its error is below
//!    the unit roundoff (Higham 2001, Table 2.1: θ₁₆ = 0.72).
//! 3. log A = 2ᵏ · log X.
//!
//! The principal logarithm of a real matrix is real when no eigenvalue lies on the closed
//! negative real axis; such an eigenvalue is an error naming it ([`LtiError::Undefined`]).
//! Used by the ZOH `d2c` (`StateSpace::d2c` in the lti layer), which reports the same condition as
//! a pole without a preimage.

use nalgebra::DMatrix;
use num_complex::Complex64;

use crate::error::{LtiError, Result};

/// Largest number of square roots (|log λ| ≤ 2^60 · ½ for every eigenvalue then; a finite
/// matrix with no eigenvalue on the closed negative axis needs far fewer).
const MAX_SQUARE_ROOTS: u32 = 60;

/// Iteration cap of one Denman–Beavers square root.
const MAX_DB_ITER: usize = 100;

/// Number of Gauss–Legendre points (the degree of the Padé approximant).
const PADE_POINTS: usize = 16;

/// The principal logarithm of a real square matrix (see the [module docs](self)).
///
/// Errors: not square, a NaN/∞ entry, an eigenvalue on the closed negative real axis (named),
/// a square root that does not converge.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::{expm, logm};
/// // a rotation by 1 rad, scaled by e^(−0.5): log = [[−0.5, 1], [−1, −0.5]]
/// let l = DMatrix::from_row_slice(2, 2, &[-0.5, 1.0, -1.0, -0.5]);
/// let back = logm(&expm(&l).unwrap()).unwrap();
/// assert!((back - &l).abs().max() < 1e-15);
/// assert!(logm(&DMatrix::from_row_slice(1, 1, &[-0.5])).is_err());
/// ```
pub fn logm(a: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let n = a.nrows();
    if a.ncols() != n {
        return Err(LtiError::invalid(format!(
            "the matrix logarithm needs a square matrix, got {}×{}",
            a.nrows(),
            a.ncols()
        )));
    }
    if let Some(x) = a.iter().find(|x| !x.is_finite()) {
        return Err(LtiError::NonFinite {
            what: "an entry of the matrix whose logarithm is taken".into(),
            value: *x,
        });
    }
    if n == 0 {
        return Ok(a.clone());
    }
    if let Some(l) = negative_real_eigenvalue(a)? {
        return Err(LtiError::Undefined {
            what: "the real matrix logarithm".into(),
            reason: format!(
                "the eigenvalue {} lies on the closed negative real axis",
                crate::error::number(l.re)
            ),
        });
    }
    let id = DMatrix::<f64>::identity(n, n);
    let mut x = a.clone();
    let mut k = 0u32;
    while (&x - &id).abs().column_sum().max() > 0.5 {
        if k == MAX_SQUARE_ROOTS {
            return Err(LtiError::NoConvergence {
                what: "the square roots of the matrix logarithm".into(),
                iterations: k as usize,
            });
        }
        x = sqrtm(&x)?;
        k += 1;
    }
    let e = &x - &id;
    let (nodes, weights) = gauss_legendre(PADE_POINTS);
    let mut log = DMatrix::<f64>::zeros(n, n);
    for (t, w) in nodes.iter().zip(&weights) {
        let m = &id + &e * *t;
        let solved = m.lu().solve(&e).ok_or_else(|| LtiError::NoConvergence {
            what: "the Padé approximant of the matrix logarithm (a singular factor)".into(),
            iterations: 0,
        })?;
        log += solved * *w;
    }
    Ok(log * 2f64.powi(k as i32))
}

/// An eigenvalue of `a` on the closed negative real axis (a real eigenvalue ≤ 0, or one
/// within rounding of 0), if any.
pub(crate) fn negative_real_eigenvalue(a: &DMatrix<f64>) -> Result<Option<Complex64>> {
    let scale = a.abs().column_sum().max().max(f64::MIN_POSITIVE);
    let tiny = 8.0 * (a.nrows() as f64) * f64::EPSILON * scale;
    Ok(crate::numeric::eigenvalues(a)?
        .into_iter()
        .find(|l| (l.im == 0.0 && l.re <= 0.0) || l.norm() <= tiny))
}

/// The principal square root by the coupled Denman–Beavers iteration.
fn sqrtm(x: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let n = x.nrows();
    let singular = || LtiError::NoConvergence {
        what: "the square root of the matrix logarithm (a singular iterate)".into(),
        iterations: 0,
    };
    let mut y = x.clone();
    let mut z = DMatrix::<f64>::identity(n, n);
    let mut settled = 0;
    for _ in 0..MAX_DB_ITER {
        let yi = y.clone().try_inverse().ok_or_else(singular)?;
        let zi = z.clone().try_inverse().ok_or_else(singular)?;
        let y_next = (&y + zi) * 0.5;
        let z_next = (&z + yi) * 0.5;
        let change = (&y_next - &y).abs().column_sum().max();
        let size = y_next.abs().column_sum().max();
        y = y_next;
        z = z_next;
        if !size.is_finite() {
            return Err(singular());
        }
        // quadratic convergence: one more step after the change reaches rounding level
        if change <= 4.0 * (n as f64) * f64::EPSILON * size {
            settled += 1;
            if settled == 2 {
                return Ok(y);
            }
        }
    }
    Err(LtiError::NoConvergence {
        what: "the Denman–Beavers square root".into(),
        iterations: MAX_DB_ITER,
    })
}

/// The m-point Gauss–Legendre rule on [0, 1]: nodes and weights (Newton on Pₘ).
fn gauss_legendre(m: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = Vec::with_capacity(m);
    let mut weights = Vec::with_capacity(m);
    for i in 0..m {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (m as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // P_m(x) and P_m'(x) by the three-term recurrence
            let (mut p0, mut p1) = (1.0, x);
            for j in 2..=m {
                let jf = j as f64;
                let p2 = ((2.0 * jf - 1.0) * x * p1 - (jf - 1.0) * p0) / jf;
                p0 = p1;
                p1 = p2;
            }
            dp = m as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() <= 1e-17 {
                break;
            }
        }
        nodes.push(0.5 * (1.0 - x));
        weights.push(1.0 / ((1.0 - x * x) * dp * dp));
    }
    (nodes, weights)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_polynomials() {
        let (t, w) = gauss_legendre(PADE_POINTS);
        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        // ∫₀¹ t^k dt = 1/(k + 1), exact up to degree 2m − 1
        for k in [1, 5, 17, 31] {
            let q: f64 = t.iter().zip(&w).map(|(t, w)| w * t.powi(k)).sum();
            assert!((q - 1.0 / f64::from(k + 1)).abs() < 1e-15, "{k}");
        }
    }

    #[test]
    fn logarithm_of_exponentials() {
        for m in [
            DMatrix::from_row_slice(2, 2, &[-3.0, 1.0, 0.0, -3.0]),
            DMatrix::from_row_slice(3, 3, &[-1.0, 2.0, 0.0, -2.0, -1.0, 1.0, 0.5, 0.0, -3.0]),
            DMatrix::from_row_slice(2, 2, &[0.0, 3.0, -3.0, 0.0]),
            DMatrix::from_row_slice(1, 1, &[-25.0]),
        ] {
            let back = logm(&crate::numeric::expm(&m).unwrap()).unwrap();
            let err = (&back - &m).abs().max() / m.abs().max();
            assert!(err < 1e-13, "{err}\n{m}");
        }
    }

    #[test]
    fn negative_axis_is_refused() {
        let a = DMatrix::from_row_slice(2, 2, &[-0.5, 0.0, 0.0, 0.7]);
        let e = logm(&a).unwrap_err().to_string();
        assert!(e.contains("-0.5"), "{e}");
        assert!(logm(&DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0])).is_err());
    }
}
