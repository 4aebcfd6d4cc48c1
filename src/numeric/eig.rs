//! Eigenvalues of a real square matrix, safely.
//!
//! nalgebra 0.35's `complex_eigenvalues()` runs an uncapped Schur iteration that never
//! terminates on the companion matrix of sⁿ ± c for even n ≥ 6 (n ≥ 4 for sⁿ + c) — the
//! controllable canonical `A` of 1/(s⁴+1) is that matrix. We therefore
//! 1. balance the matrix (`balance::balance`: Parlett–Reinsch with
//!    overflow-safe norms and capped loops — nalgebra's own balancing never returns once a
//!    squared norm overflows), which equalises row and column norms and makes the eigenvalues
//!    of badly scaled companion matrices accurate;
//! 2. scale it by an exact power of two into a range where no intermediate of the Schur
//!    iteration can overflow (entries within 2^±[`SAFE_EXP`] are left alone; otherwise the
//!    range of magnitudes is centred, keeping the largest below 2^`SAFE_EXP`), and scale the
//!    eigenvalues back — an eigenvalue beyond f64 is an error, not ∞;
//! 3. run `Schur::try_new` with an iteration cap;
//! 4. if that fails, retry once on H·M·H for a fixed Householder reflector H (an orthogonal
//!    similarity, so the eigenvalues are unchanged) which breaks the cyclic structure that
//!    stalls the unshifted-looking iteration.

use nalgebra::DMatrix;
use num_complex::Complex64;

use crate::error::{LtiError, Result};
use crate::numeric::balance::{balance, exponent_range, ldexp};

/// Iterations allowed per eigenvalue in the capped Schur iteration.
const SCHUR_ITER_PER_DIM: usize = 60;

/// Entries up to 2^`SAFE_EXP` in magnitude (and down to 2^−`SAFE_EXP`) go to the Schur
/// iteration unscaled: its squares and products of two entries stay far from overflow.
pub const SAFE_EXP: i32 = 400;

/// The power of two 2^e by which a matrix with non-zero magnitudes in [2^lo, 2^(hi+1)) is
/// divided before the eigenvalue iteration: 0 inside the safe range, otherwise the centre of
/// the range, clamped so that the largest entry ends within 2^±`SAFE_EXP`.
pub(crate) fn safe_scale_exponent(lo: i32, hi: i32) -> i32 {
    if hi <= SAFE_EXP && lo >= -SAFE_EXP {
        return 0;
    }
    let centre = (lo + hi).div_euclid(2);
    centre.clamp(hi - SAFE_EXP, hi + SAFE_EXP)
}

/// Eigenvalues of a square real matrix (any order), complex conjugate pairs exact.
///
/// Errors on a non-square matrix, non-finite entries, or (practically never) non-convergence.
///
/// ```
/// use nalgebra::DMatrix;
/// // Companion matrix of s⁴ + 1: nalgebra's own complex_eigenvalues() hangs on it.
/// let mut a = DMatrix::<f64>::zeros(4, 4);
/// a[(0, 3)] = -1.0;
/// for i in 1..4 { a[(i, i - 1)] = 1.0; }
/// let ev = ltikit::numeric::eigenvalues(&a).unwrap();
/// assert_eq!(ev.len(), 4);
/// for z in ev { assert!((z.norm() - 1.0).abs() < 1e-12); }
/// ```
pub fn eigenvalues(m: &DMatrix<f64>) -> Result<Vec<Complex64>> {
    if !m.is_square() {
        return Err(LtiError::invalid(format!(
            "eigenvalues need a square matrix, got {}×{}",
            m.nrows(),
            m.ncols()
        )));
    }
    if let Some(x) = m.iter().find(|x| !x.is_finite()) {
        return Err(LtiError::NonFinite {
            what: "a matrix entry".into(),
            value: *x,
        });
    }
    eigenvalues_checked(m.clone())
}

/// As [`eigenvalues`], for a matrix already known to be square and finite (consumed).
pub fn eigenvalues_checked(mut m: DMatrix<f64>) -> Result<Vec<Complex64>> {
    let n = m.nrows();
    match n {
        0 => return Ok(Vec::new()),
        1 => return Ok(vec![Complex64::new(m[(0, 0)], 0.0)]),
        2 => {
            if let Some(ev) = eigenvalues_2x2(m[(0, 0)], m[(0, 1)], m[(1, 0)], m[(1, 1)]) {
                return Ok(ev);
            }
        }
        _ => {}
    }
    balance(&mut m);
    let e = exponent_range(m.iter().copied()).map_or(0, |(lo, hi)| safe_scale_exponent(lo, hi));
    if e != 0 {
        m.apply(|x| *x = ldexp(*x, -e));
    }
    let ev = schur_eigenvalues(m)?;
    if e == 0 {
        return Ok(ev);
    }
    let ev: Vec<Complex64> = ev
        .into_iter()
        .map(|z| Complex64::new(ldexp(z.re, e), ldexp(z.im, e)))
        .collect();
    if let Some(z) = ev.iter().find(|z| !(z.re.is_finite() && z.im.is_finite())) {
        return Err(LtiError::NonFinite {
            what: "an eigenvalue (its magnitude is beyond the range of f64)".into(),
            value: z.norm(),
        });
    }
    Ok(ev)
}

/// Eigenvalues of [[a, b], [c, d]] from the trace and the determinant, without cancellation:
/// the larger root h ± √(h² − det) (h = tr/2) with the sign of h, the smaller one as det
/// divided by it — so [[0, 1], [−4, −1e200]] gives −1e200 and −4e-200 (a Schur iteration
/// returns 0 for the small one: its absolute error is eps·‖A‖ = 2e184). `None` when a product
/// overflows (the general path then scales).
fn eigenvalues_2x2(a: f64, b: f64, c: f64, d: f64) -> Option<Vec<Complex64>> {
    // det = ad − bc by Kahan's difference of products (exact to a few ulps).
    let w = b * c;
    let det = a.mul_add(d, -w) + (-b).mul_add(c, w);
    let h = 0.5 * a + 0.5 * d;
    if !(det.is_finite() && h.is_finite() && (a * d).is_finite()) {
        return None;
    }
    let re = |x: f64| Complex64::new(x, 0.0);
    if h == 0.0 {
        let r = (-det).abs().sqrt();
        return Some(if det <= 0.0 {
            vec![re(r), re(-r)]
        } else {
            vec![Complex64::new(0.0, r), Complex64::new(0.0, -r)]
        });
    }
    let q = 1.0 - det / h / h; // (h² − det)/h² without forming h²
    if q >= 0.0 {
        let big = h + h.signum() * h.abs() * q.sqrt();
        let small = if big == 0.0 { 0.0 } else { det / big };
        Some(vec![re(big), re(small)])
    } else {
        let im = h.abs() * (-q).sqrt();
        Some(vec![Complex64::new(h, im), Complex64::new(h, -im)])
    }
}

/// Eigenvalues from the capped real Schur iteration, with one retry after a fixed orthogonal
/// similarity.
fn schur_eigenvalues(m: DMatrix<f64>) -> Result<Vec<Complex64>> {
    let n = m.nrows();
    let cap = SCHUR_ITER_PER_DIM * n;
    if let Some(schur) = nalgebra::linalg::Schur::try_new(m.clone(), f64::EPSILON, cap) {
        return Ok(conjugate_exact(
            quasi_triangular_eigenvalues(&schur.unpack().1).into_iter(),
        ));
    }
    let h = householder(n);
    let rotated = &h * m * &h;
    if let Some(schur) = nalgebra::linalg::Schur::try_new(rotated, f64::EPSILON, cap) {
        return Ok(conjugate_exact(
            quasi_triangular_eigenvalues(&schur.unpack().1).into_iter(),
        ));
    }
    Err(LtiError::NoConvergence {
        what: format!("Schur decomposition of a {n}×{n} matrix"),
        iterations: cap,
    })
}

/// Eigenvalues of a real quasi-triangular (real Schur) matrix: 1×1 blocks are real eigenvalues,
/// 2×2 blocks give a conjugate pair — or two real eigenvalues when the block's discriminant is
/// not negative (nalgebra's own `complex_eigenvalues()` returns NaN imaginary parts for such a
/// block, which occurs for nearly double real roots).
fn quasi_triangular_eigenvalues(t: &DMatrix<f64>) -> Vec<Complex64> {
    let n = t.nrows();
    let mut out = Vec::with_capacity(n);
    let mut m = 0;
    while m < n {
        if m + 1 == n || t[(m + 1, m)] == 0.0 {
            out.push(Complex64::new(t[(m, m)], 0.0));
            m += 1;
            continue;
        }
        let (a, b, c, d) = (t[(m, m)], t[(m, m + 1)], t[(m + 1, m)], t[(m + 1, m + 1)]);
        let half_tr = 0.5 * (a + d);
        let half_diff = 0.5 * (a - d);
        let disc = half_diff * half_diff + b * c;
        if disc >= 0.0 {
            // Two real eigenvalues; the larger-magnitude one first, the other from the
            // determinant to avoid cancellation.
            let r = disc.sqrt();
            let l1 = half_tr + r.copysign(half_tr);
            let det = a * d - b * c;
            let l2 = if l1 != 0.0 { det / l1 } else { half_tr - r };
            out.push(Complex64::new(l1, 0.0));
            out.push(Complex64::new(l2, 0.0));
        } else {
            let im = (-disc).sqrt();
            out.push(Complex64::new(half_tr, im));
            out.push(Complex64::new(half_tr, -im));
        }
        m += 2;
    }
    out
}

/// A fixed, non-trivial Householder reflector H = I − 2vvᵀ/(vᵀv) (symmetric and orthogonal).
fn householder(n: usize) -> DMatrix<f64> {
    let v: Vec<f64> = (0..n)
        .map(|i| 1.0 + 0.37 * i as f64 + if i % 2 == 0 { 0.5 } else { -0.25 })
        .collect();
    let vv: f64 = v.iter().map(|x| x * x).sum();
    DMatrix::from_fn(n, n, |i, j| {
        let delta = if i == j { 1.0 } else { 0.0 };
        delta - 2.0 * v[i] * v[j] / vv
    })
}

/// Makes conjugate pairs exact: for each eigenvalue with positive imaginary part the partner
/// is replaced by its exact conjugate (the real Schur form yields them from 2×2 blocks, so
/// this only removes rounding noise in the imaginary sign bit).
fn conjugate_exact(ev: impl Iterator<Item = Complex64>) -> Vec<Complex64> {
    let mut real = Vec::new();
    let mut upper = Vec::new();
    let mut lower = Vec::new();
    for z in ev {
        if z.im == 0.0 {
            real.push(z);
        } else if z.im > 0.0 {
            upper.push(z);
        } else {
            lower.push(z);
        }
    }
    if upper.len() != lower.len() {
        // Cannot happen for a real Schur form; return the values untouched.
        let mut all = real;
        all.extend(upper);
        all.extend(lower);
        return all;
    }
    let mut out = real;
    for z in upper {
        out.push(z);
        out.push(z.conj());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn companion_monic(c: &[f64]) -> DMatrix<f64> {
        // c: descending, monic (c[0] == 1)
        let n = c.len() - 1;
        let mut a = DMatrix::zeros(n, n);
        for j in 0..n {
            a[(0, j)] = -c[j + 1];
        }
        for i in 1..n {
            a[(i, i - 1)] = 1.0;
        }
        a
    }

    /// sⁿ ± c up to n = 40: the matrices on which nalgebra's uncapped iteration hangs.
    #[test]
    fn s_to_the_n_plus_minus_c_terminates() {
        for n in 2..=40 {
            for &c in &[1.0, -1.0, 2.5, -0.3] {
                let mut coeffs = vec![0.0; n + 1];
                coeffs[0] = 1.0;
                coeffs[n] = c;
                let ev = eigenvalues(&companion_monic(&coeffs)).unwrap();
                assert_eq!(ev.len(), n);
                let r = f64::abs(c).powf(1.0 / n as f64);
                for z in &ev {
                    assert!(
                        (z.norm() - r).abs() < 1e-10 * r,
                        "n={n} c={c}: |z|={} want {r}",
                        z.norm()
                    );
                }
            }
        }
    }

    #[test]
    fn rejects_nan_and_non_square() {
        let m = DMatrix::from_row_slice(2, 2, &[1.0, f64::NAN, 0.0, 1.0]);
        assert!(eigenvalues(&m).is_err());
        let m = DMatrix::<f64>::zeros(2, 3);
        assert!(eigenvalues(&m).is_err());
        assert!(
            eigenvalues(&DMatrix::<f64>::zeros(0, 0))
                .unwrap()
                .is_empty()
        );
    }

    #[test]
    fn conjugates_are_exact() {
        let m = DMatrix::from_row_slice(3, 3, &[0.0, 1.0, 0.0, -2.0, -0.3, 0.7, 0.1, 0.0, -1.0]);
        let ev = eigenvalues(&m).unwrap();
        let ups: Vec<_> = ev.iter().filter(|z| z.im > 0.0).collect();
        for u in ups {
            assert!(ev.iter().any(|z| *z == u.conj()));
        }
    }
}
