//! Minimum-norm least-squares solutions by the SVD, with an iteration cap and exact scaling.
//!
//! nalgebra's `svd` iterates without a bound on hostile input; `min_norm_solve` scales A and
//! b by powers of two (exact) so that their largest entries are about 1, and calls `try_svd`
//! with [`MAX_SVD_ITER`] iterations: no convergence is `None`, never a hang.

use nalgebra::{DMatrix, DVector};

use crate::numeric::tol::EPS;

/// Iteration cap of the SVD (nalgebra counts implicit QR sweeps; a well-posed n ≤ 2048 problem
/// needs a few per singular value).
pub const MAX_SVD_ITER: usize = 10_000;

/// The power of two 2^k nearest 1/max|x|, or 1 for a zero or non-finite maximum.
fn pow2_scale(max_abs: f64) -> f64 {
    if max_abs > 0.0 && max_abs.is_finite() {
        let e = max_abs.log2().round().clamp(-1000.0, 1000.0) as i32;
        2f64.powi(-e)
    } else {
        1.0
    }
}

/// The minimum-norm least-squares solution of A x = b, singular values below
/// `rel_tol`·σ_max treated as zero; `None` when the SVD does not converge within
/// [`MAX_SVD_ITER`] iterations or the solution is not finite.
pub(crate) fn min_norm_solve(
    a: &DMatrix<f64>,
    b: &DVector<f64>,
    rel_tol: f64,
) -> Option<DVector<f64>> {
    if a.iter().chain(b.iter()).any(|v| !v.is_finite()) {
        return None;
    }
    let sa = pow2_scale(a.amax());
    let sb = pow2_scale(b.amax());
    let svd = (a * sa).try_svd(true, true, EPS, MAX_SVD_ITER)?;
    let tol = rel_tol * svd.singular_values.max().max(f64::MIN_POSITIVE);
    // A x = b ⇔ (sa A)(x sb / sa) = sb b.
    let y = svd.solve(&(b * sb), tol).ok()?;
    let x = y * (sa / sb);
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
mod tests {
    /// `min_norm_solve` on a worked example (an internal kernel: a unit test, not a doctest).
    #[test]
    #[allow(clippy::float_cmp)] // exact values are meant
    fn min_norm_solve_example() {
        use crate::numeric::lstsq::min_norm_solve;
        use nalgebra::{DMatrix, DVector};
        // Singular A: x + y = 2 twice → the minimum-norm solution (1, 1).
        let a = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0]);
        let x = min_norm_solve(&a, &DVector::from_vec(vec![2.0, 2.0]), 1e-12).unwrap();
        assert!((x[0] - 1.0).abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14);
        // Entries near the overflow threshold are scaled first.
        let big = DMatrix::from_row_slice(2, 2, &[1e300, 0.0, 0.0, 1e-300]);
        let x = min_norm_solve(&big, &DVector::from_vec(vec![1e300, 0.0]), 1e-12).unwrap();
        assert!((x[0] - 1.0).abs() < 1e-14);
    }
}
