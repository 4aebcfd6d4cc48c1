//! Sylvester and Lyapunov equations by Bartels–Stewart on the real Schur form.
//!
//! | function | equation |
//! |---|---|
//! | [`sylvester`] | A·X + X·B = C |
//! | [`lyap`] | A·X + X·Aᵀ + Q = 0 (MATLAB `lyap`) |
//! | [`dlyap`] | A·X·Aᵀ − X + Q = 0 (MATLAB `dlyap`) |
//! | [`lyap_cholesky`], [`dlyap_cholesky`] | the same with Q = B·Bᵀ, X = L·Lᵀ (Hammarling) |
//!
//! # Method
//! A = U·T·Uᵀ (the [real Schur form](super::schur), **unbalanced** so that U is orthogonal),
//! the right-hand side transformed to Uᵀ·C·V, the quasi-triangular equation solved block by
//! block in real arithmetic (the `dtrsyl` scheme: 1×1 and 2×2 blocks, small systems by
//! Gaussian elimination with complete pivoting), and X transformed back. For the Lyapunov
//! equations one Schur form serves both sides: T·Y + Y·Tᵀ is brought to two upper
//! quasi-triangular factors by reversing the order of the columns of Y. O(n³) in all.
//!
//! # Solvability
//! The equation has a unique solution iff λᵢ(A) + μⱼ(B) ≠ 0 for all eigenvalues (continuous),
//! resp. λᵢ·λⱼ ≠ 1 (discrete). A pair with |λ + μ| ≤ 10·n·ε·(‖A‖_F + ‖B‖_F) (resp.
//! |λμ − 1| ≤ 10·n·ε·max(1, ‖A‖_F²)) is refused with [`LtiError::SingularEquation`] naming
//! the two eigenvalues.
//!
//! # What is reported
//! * `residual` = ‖A·X + X·B − C‖_F / (‖A·X‖_F + ‖X·B‖_F + ‖C‖_F) (for the Lyapunov forms
//!   the same with their terms): the backward error in the data, ~ε for a stable solve.
//! * `condition` = (‖A‖_F + ‖B‖_F)·max(‖X‖_F/‖C‖_F, 1/minᵢⱼ|λᵢ + μⱼ|) (discrete:
//!   (‖A‖_F² + 1)·max(‖X‖_F/‖Q‖_F, 1/min|λᵢλⱼ − 1|)). Both terms are lower bounds of the
//!   norm of the inverse operator, sep⁻¹, so this is a **lower bound** of the relative
//!   condition number (‖A‖ + ‖B‖)·sep⁻¹; relative error in X ≲ condition·residual when the
//!   bound is tight (it is within a small factor for normal A; for highly non-normal A sep
//!   can be far below min|λ + μ|).
//!
//! A non-symmetric Q in [`lyap`] and [`dlyap`] is accepted (the equation is a Sylvester
//! equation and has a unique solution all the same); when Q is exactly symmetric X is
//! symmetrised, (X + Xᵀ)/2, which only removes rounding.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::norms::frobenius;
use super::schur::{SchurOptions, real_schur};
use super::trsyl::{self, Equation};
use crate::error::{LtiError, Result, complex_number, number};
use crate::limits::EQUATION_STATES;

pub use super::hammarling::{CholeskySolution, dlyap_cholesky, lyap_cholesky};

/// A solution X of a linear matrix equation with its relative residual and condition
/// estimate (see the [module docs](self) for their definitions).
#[derive(Clone, Debug)]
pub struct MatrixSolution {
    /// The solution.
    pub x: DMatrix<f64>,
    /// ‖residual‖_F / (sum of the Frobenius norms of the equation's terms).
    pub residual: f64,
    /// A lower-bound estimate of the relative condition number (‖A‖ + ‖B‖)·sep⁻¹.
    pub condition: f64,
}

/// The orthogonal Schur form A = U·T·Uᵀ (no balancing): (U, T).
pub(crate) fn orthogonal_schur(a: &DMatrix<f64>) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
    let opts = SchurOptions {
        balance: false,
        want_q: true,
        want_t: true,
    };
    let s = real_schur(a, opts)?;
    let u =
        s.q.clone()
            .ok_or_else(|| LtiError::invalid("the Schur vectors were not formed"))?;
    Ok((u, s.t))
}

/// Checks a square, finite coefficient within the state limit; returns its order.
pub(crate) fn check_coefficient(a: &DMatrix<f64>, name: &str) -> Result<usize> {
    let n = super::checks::check_square(a, name)?;
    EQUATION_STATES.check_usize(&format!("`{}`", name.to_lowercase()), n)
}

/// Errors unless `m` is rows×cols with finite entries.
pub(crate) fn check_shape(m: &DMatrix<f64>, name: &str, rows: usize, cols: usize) -> Result<()> {
    if m.shape() != (rows, cols) {
        return Err(LtiError::invalid(format!(
            "{name} must be {rows}×{cols}, got {}×{}",
            m.nrows(),
            m.ncols()
        )));
    }
    super::checks::check_finite(m, name)
}

/// The closest pair to singularity: (min over pairs of |λ + μ| or |λμ − 1|, λ, μ).
fn closest_pair(
    la: &[Complex64],
    lb: &[Complex64],
    eq: Equation,
) -> Option<(f64, Complex64, Complex64)> {
    let mut best: Option<(f64, Complex64, Complex64)> = None;
    for &l in la {
        for &m in lb {
            let d = match eq {
                Equation::Continuous => (l + m).norm(),
                Equation::Discrete => (l * m - 1.0).norm(),
            };
            if best.is_none_or(|(b, _, _)| d < b) {
                best = Some((d, l, m));
            }
        }
    }
    best
}

fn show(z: Complex64) -> String {
    complex_number(z.re, z.im)
}

/// Refuses an equation with a (numerically) vanishing λ + μ (λμ − 1); returns the minimum.
fn check_solvable(
    equation: &str,
    la: &[Complex64],
    lb: &[Complex64],
    eq: Equation,
    scale: f64,
    names: (&str, &str),
) -> Result<f64> {
    let Some((d, l, m)) = closest_pair(la, lb, eq) else {
        return Ok(f64::INFINITY);
    };
    let n = la.len().max(lb.len()) as f64;
    let tol = 10.0 * n * f64::EPSILON * scale;
    if d <= tol {
        let relation = match eq {
            Equation::Continuous => format!("λ + μ = {} ≈ 0", number(d)),
            Equation::Discrete => format!("|λ·μ − 1| = {} ≈ 0", number(d)),
        };
        return Err(LtiError::SingularEquation {
            equation: equation.to_string(),
            reason: format!(
                "no unique solution: the eigenvalue λ = {} of {} and μ = {} of {} give {relation} (tolerance {})",
                show(l),
                names.0,
                show(m),
                names.1,
                number(tol)
            ),
        });
    }
    Ok(d)
}

/// Relative residual ‖Σ terms‖_F / Σ ‖term‖_F (0 when every term vanishes).
pub(crate) fn relative_residual(terms: &[&DMatrix<f64>]) -> f64 {
    let Some(first) = terms.first() else {
        return 0.0;
    };
    let mut sum = (*first).clone();
    for t in &terms[1..] {
        sum += *t;
    }
    let scale: f64 = terms.iter().map(|t| frobenius(t.iter())).sum();
    if scale == 0.0 {
        0.0
    } else {
        frobenius(sum.iter()) / scale
    }
}

/// Columns in reverse order (Y·P for the reversal P).
fn reverse_columns(m: &DMatrix<f64>) -> DMatrix<f64> {
    let n = m.ncols();
    DMatrix::from_fn(m.nrows(), n, |i, j| m[(i, n - 1 - j)])
}

/// P·Tᵀ·P: upper quasi-triangular when T is.
fn reversed_transpose(t: &DMatrix<f64>) -> DMatrix<f64> {
    let n = t.nrows();
    DMatrix::from_fn(n, n, |i, j| t[(n - 1 - j, n - 1 - i)])
}

fn is_symmetric(q: &DMatrix<f64>) -> bool {
    q == &q.transpose()
}

/// X ← (X + Xᵀ)/2, entry by entry (the Lyapunov and Riccati solutions).
pub(super) fn symmetrise(x: &mut DMatrix<f64>) {
    let n = x.nrows();
    for j in 0..n {
        for i in 0..j {
            let v = 0.5 * (x[(i, j)] + x[(j, i)]);
            x[(i, j)] = v;
            x[(j, i)] = v;
        }
    }
}

/// The condition estimate of the module docs.
fn condition(coeff: f64, x: &DMatrix<f64>, rhs: &DMatrix<f64>, min_gap: f64) -> f64 {
    let nr = frobenius(rhs.iter());
    let ratio = if nr > 0.0 {
        frobenius(x.iter()) / nr
    } else {
        0.0
    };
    coeff * ratio.max(1.0 / min_gap)
}

/// Solves the Sylvester equation A·X + X·B = C (A m×m, B n×n, C m×n).
///
/// Errors: non-square or non-finite coefficients, mismatched sizes, an order beyond
/// [`crate::limits::MAX_EQUATION_STATES`], or a singular equation (λᵢ(A) + μⱼ(B) ≈ 0, naming the two
/// eigenvalues).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::sylvester;
/// // Scalars: (−1)·x + x·(−2) = 3 ⇒ x = −1.
/// let s = sylvester(
///     &DMatrix::from_element(1, 1, -1.0),
///     &DMatrix::from_element(1, 1, -2.0),
///     &DMatrix::from_element(1, 1, 3.0),
/// ).unwrap();
/// assert!((s.x[(0, 0)] + 1.0).abs() < 1e-15);
/// assert!(s.residual < 1e-16);
/// // A and −B share the eigenvalue 1: no unique solution.
/// let a = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 2.0]);
/// let b = DMatrix::from_element(1, 1, -1.0);
/// assert!(sylvester(&a, &b, &DMatrix::zeros(2, 1)).is_err());
/// ```
pub fn sylvester(a: &DMatrix<f64>, b: &DMatrix<f64>, c: &DMatrix<f64>) -> Result<MatrixSolution> {
    let m = check_coefficient(a, "A")?;
    let n = check_coefficient(b, "B")?;
    check_shape(c, "C", m, n)?;
    let (u, ta) = orthogonal_schur(a)?;
    let (v, tb) = orthogonal_schur(b)?;
    let (na, nb) = (frobenius(a.iter()), frobenius(b.iter()));
    let la = super::schur::quasi_triangular_eigenvalues(&ta);
    let lb = super::schur::quasi_triangular_eigenvalues(&tb);
    let gap = check_solvable(
        "the Sylvester equation A·X + X·B = C",
        &la,
        &lb,
        Equation::Continuous,
        na + nb,
        ("A", "B"),
    )?;
    let mut y = u.transpose() * c * &v;
    trsyl::solve(&ta, &tb, &mut y, Equation::Continuous, tiny(na + nb));
    let x = &u * y * v.transpose();
    let residual = relative_residual(&[&(a * &x), &(&x * b), &(-c)]);
    let condition = condition(na + nb, &x, c, gap);
    Ok(MatrixSolution {
        x,
        residual,
        condition,
    })
}

/// The smallest pivot of the small systems.
fn tiny(scale: f64) -> f64 {
    (f64::EPSILON * scale).max(f64::MIN_POSITIVE)
}

/// Solves the continuous Lyapunov equation A·X + X·Aᵀ + Q = 0 (MATLAB `lyap(A, Q)`).
///
/// Errors: as [`sylvester`]; singular when λᵢ(A) + λⱼ(A) ≈ 0 (an eigenvalue on the imaginary
/// axis, or a pair symmetric about it).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::lyap;
/// // The controllability Gramian of 1/(s + 1): −2x + 1 = 0 ⇒ x = 1/2.
/// let s = lyap(&DMatrix::from_element(1, 1, -1.0), &DMatrix::from_element(1, 1, 1.0)).unwrap();
/// assert!((s.x[(0, 0)] - 0.5).abs() < 1e-16);
/// // The double integrator has λ = 0: refused.
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
/// let e = lyap(&a, &DMatrix::identity(2, 2)).unwrap_err().to_string();
/// assert!(e.contains("no unique solution"), "{e}");
/// ```
pub fn lyap(a: &DMatrix<f64>, q: &DMatrix<f64>) -> Result<MatrixSolution> {
    lyapunov(a, q, Equation::Continuous)
}

/// Solves the discrete Lyapunov (Stein) equation A·X·Aᵀ − X + Q = 0 (MATLAB `dlyap(A, Q)`).
///
/// Errors: as [`sylvester`]; singular when λᵢ(A)·λⱼ(A) ≈ 1 (an eigenvalue on the unit
/// circle, or a pair λ, 1/λ).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::dlyap;
/// // 0.25x − x + 3 = 0 ⇒ x = 4.
/// let s = dlyap(&DMatrix::from_element(1, 1, 0.5), &DMatrix::from_element(1, 1, 3.0)).unwrap();
/// assert!((s.x[(0, 0)] - 4.0).abs() < 1e-15);
/// ```
pub fn dlyap(a: &DMatrix<f64>, q: &DMatrix<f64>) -> Result<MatrixSolution> {
    lyapunov(a, q, Equation::Discrete)
}

fn lyapunov(a: &DMatrix<f64>, q: &DMatrix<f64>, eq: Equation) -> Result<MatrixSolution> {
    let n = check_coefficient(a, "A")?;
    check_shape(q, "Q", n, n)?;
    let (u, t) = orthogonal_schur(a)?;
    let na = frobenius(a.iter());
    let lambda = super::schur::quasi_triangular_eigenvalues(&t);
    let (equation, scale, coeff) = match eq {
        Equation::Continuous => (
            "the Lyapunov equation A·X + X·Aᵀ + Q = 0",
            2.0 * na,
            2.0 * na,
        ),
        Equation::Discrete => (
            "the discrete Lyapunov equation A·X·Aᵀ − X + Q = 0",
            (na * na).max(1.0),
            na * na + 1.0,
        ),
    };
    let gap = check_solvable(equation, &lambda, &lambda, eq, scale, ("A", "A"))?;
    // T·Y + Y·Tᵀ = −UᵀQU (or T·Y·Tᵀ − Y = −UᵀQU); Z = Y·P with P the reversal.
    let f = -(u.transpose() * q * &u);
    let mut z = reverse_columns(&f);
    let tb = reversed_transpose(&t);
    trsyl::solve(&t, &tb, &mut z, eq, tiny(scale));
    let y = reverse_columns(&z);
    let mut x = &u * y * u.transpose();
    if is_symmetric(q) {
        symmetrise(&mut x);
    }
    let residual = match eq {
        Equation::Continuous => {
            let ax = a * &x;
            let xat = &x * a.transpose();
            relative_residual(&[&ax, &xat, q])
        }
        Equation::Discrete => {
            let axa = a * &x * a.transpose();
            relative_residual(&[&axa, &(-&x), q])
        }
    };
    let condition = condition(coeff, &x, q, gap);
    Ok(MatrixSolution {
        x,
        residual,
        condition,
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// vec(X) from the Kronecker form: (I⊗A + Bᵀ⊗I)·vec X = vec C by an LU solve.
    fn kronecker_sylvester(a: &DMatrix<f64>, b: &DMatrix<f64>, c: &DMatrix<f64>) -> DMatrix<f64> {
        let (m, n) = (a.nrows(), b.nrows());
        let k = DMatrix::from_fn(m * n, m * n, |r, s| {
            let (i, j) = (r % m, r / m);
            let (k, l) = (s % m, s / m);
            let mut v = 0.0;
            if j == l {
                v += a[(i, k)];
            }
            if i == k {
                v += b[(l, j)];
            }
            v
        });
        let rhs = nalgebra::DVector::from_column_slice(c.as_slice());
        let x = k.lu().solve(&rhs).unwrap();
        DMatrix::from_column_slice(m, n, x.as_slice())
    }

    pub(crate) fn random(n: usize, m: usize, seed: u64) -> DMatrix<f64> {
        let mut state = seed;
        DMatrix::from_fn(n, m, |_, _| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        })
    }

    #[test]
    fn agrees_with_the_kronecker_solve() {
        for (m, n, seed) in [(1, 3, 1), (3, 2, 2), (5, 5, 3), (8, 6, 4)] {
            let a = random(m, m, seed) - DMatrix::identity(m, m) * 2.0;
            let b = random(n, n, seed + 10);
            let c = random(m, n, seed + 20);
            let s = sylvester(&a, &b, &c).unwrap();
            let k = kronecker_sylvester(&a, &b, &c);
            assert!((&s.x - &k).norm() < 1e-13 * k.norm(), "{m}×{n}");
            assert!(s.residual < 1e-15, "{}", s.residual);
            // lyap is the Sylvester equation with B = Aᵀ, C = −Q.
            let q = random(m, m, seed + 30);
            let l = lyap(&a, &q).unwrap();
            let k = kronecker_sylvester(&a, &a.transpose(), &(-&q));
            assert!((&l.x - &k).norm() < 1e-13 * k.norm(), "{m}");
        }
    }

    #[test]
    fn closed_form_2x2() {
        // A = diag(−1, −2), Q = [[1, 1], [1, 1]]: x_ij = q_ij/(−λᵢ − λⱼ) = [[1/2, 1/3], [1/3, 1/4]].
        let a = DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -2.0]);
        let q = DMatrix::from_element(2, 2, 1.0);
        let s = lyap(&a, &q).unwrap();
        let want = DMatrix::from_row_slice(2, 2, &[0.5, 1.0 / 3.0, 1.0 / 3.0, 0.25]);
        assert!((&s.x - &want).norm() < 1e-15);
        // discrete: x_ij = q_ij/(1 − λᵢλⱼ) with λ = 0.5, −0.25: [[4/3, 8/9], [8/9, 16/15]].
        let a = DMatrix::from_row_slice(2, 2, &[0.5, 0.0, 0.0, -0.25]);
        let s = dlyap(&a, &q).unwrap();
        let want = DMatrix::from_row_slice(
            2,
            2,
            &[4.0 / 3.0, 1.0 / 1.125, 1.0 / 1.125, 1.0 / (1.0 - 0.0625)],
        );
        assert!((&s.x - &want).norm() < 1e-15, "{}", s.x);
    }

    #[test]
    fn random_up_to_100_states() {
        for (n, seed) in [(30, 5), (64, 6), (100, 7)] {
            // Stable: shift the random matrix left of its spectral abscissa bound.
            let a = random(n, n, seed) - DMatrix::identity(n, n) * (n as f64).sqrt();
            let b = random(n, 3, seed + 1);
            let q = &b * b.transpose();
            let s = lyap(&a, &q).unwrap();
            assert!(s.residual < 1e-14, "n={n}: {}", s.residual);
            assert!(s.x == s.x.transpose());
            let ad = random(n, n, seed + 2) * (1.5 / (n as f64).sqrt());
            let s = dlyap(&ad, &q);
            // Not necessarily stable, but solvable with overwhelming probability.
            let s = s.unwrap();
            assert!(s.residual < 1e-14, "n={n}: {}", s.residual);
        }
    }

    #[test]
    fn singular_equations_name_the_eigenvalues() {
        let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, 0.0]);
        let e = lyap(&a, &DMatrix::identity(2, 2)).unwrap_err().to_string();
        assert!(e.contains("λ = 0 + 1j") || e.contains("λ = 0 - 1j"), "{e}");
        let e = dlyap(&DMatrix::from_element(1, 1, -1.0), &DMatrix::identity(1, 1))
            .unwrap_err()
            .to_string();
        assert!(e.contains("λ = -1 of A"), "{e}");
        assert!(lyap(&DMatrix::zeros(2, 3), &DMatrix::zeros(2, 2)).is_err());
        assert!(lyap(&DMatrix::identity(2, 2), &DMatrix::zeros(3, 3)).is_err());
        let nan = DMatrix::from_element(1, 1, f64::NAN);
        assert!(lyap(&DMatrix::identity(1, 1), &nan).is_err());
        // Empty: X is 0×0.
        assert_eq!(
            lyap(&DMatrix::zeros(0, 0), &DMatrix::zeros(0, 0))
                .unwrap()
                .x
                .len(),
            0
        );
    }

    #[test]
    fn non_symmetric_q_is_solved_as_given() {
        let a = DMatrix::from_row_slice(2, 2, &[-1.0, 2.0, 0.0, -3.0]);
        let q = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 0.0, 1.0]);
        let s = lyap(&a, &q).unwrap();
        let r = &a * &s.x + &s.x * a.transpose() + &q;
        assert!(r.norm() < 1e-15, "{}", r.norm());
    }
}
