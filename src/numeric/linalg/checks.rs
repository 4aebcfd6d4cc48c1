//! The argument checks of the kernels: a square matrix, finite entries, the dimensions of a
//! system (A, B, C, D). Each error names the matrix and, for a bad entry, its row and column.

use nalgebra::DMatrix;
use num_complex::Complex64;

use crate::error::{LtiError, Result};

/// The test "not stable by more than rounding" for the eigenvalues of `a`: Re λ ≥ −τ
/// (|λ| ≥ 1 − τ in discrete time), τ = 1000·ε·max(‖A‖_F, 1). An eigenvalue within rounding
/// of the boundary (a rigid-body mode computed as −1e-17) would give a Lyapunov solution of
/// order 1e15 that is nothing but rounding. One rule for the Gramians and their kernel.
pub(crate) fn unstable_within_rounding(
    a: &DMatrix<f64>,
    discrete: bool,
) -> impl Fn(Complex64) -> bool + use<> {
    let tol = 1e3 * f64::EPSILON * a.norm().max(1.0);
    move |z: Complex64| {
        if discrete {
            z.norm() >= 1.0 - tol
        } else {
            z.re >= -tol
        }
    }
}

/// Errors unless `a` is square with finite entries; returns its order.
pub(crate) fn check_square(a: &DMatrix<f64>, what: &str) -> Result<usize> {
    if !a.is_square() {
        return Err(LtiError::invalid(format!(
            "{what} must be square, got {}×{}",
            a.nrows(),
            a.ncols()
        )));
    }
    check_finite(a, what)?;
    Ok(a.nrows())
}

/// Errors unless `b` (the input matrix of an equation with an n×n A) has n rows, finite
/// entries and at most [`crate::limits::SIGNALS`] columns; returns its column count.
pub(crate) fn check_input_matrix(b: &DMatrix<f64>, n: usize) -> Result<usize> {
    if b.nrows() != n {
        return Err(LtiError::invalid(format!(
            "B must have {n} rows to match A ({n}×{n}), got {}×{}",
            b.nrows(),
            b.ncols()
        )));
    }
    check_finite(b, "B")?;
    crate::limits::SIGNALS.check_usize("`b`", b.ncols())
}

/// Errors at the first NaN or infinite entry (named by its row and column).
pub(crate) fn check_finite(a: &DMatrix<f64>, what: &str) -> Result<()> {
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            let x = a[(i, j)];
            if !x.is_finite() {
                return Err(LtiError::NonFinite {
                    what: format!("entry ({}, {}) of {what}", i + 1, j + 1),
                    value: x,
                });
            }
        }
    }
    Ok(())
}

/// Errors unless (A, B, C, D) have consistent dimensions (n×n, n×m, p×n, p×m) and finite
/// entries; returns (n, m, p).
pub(crate) fn check_system(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
) -> Result<(usize, usize, usize)> {
    let n = check_square(a, "A")?;
    let (m, p) = (b.ncols(), c.nrows());
    let bad = |what: &str, got: (usize, usize), want: (usize, usize)| {
        LtiError::invalid(format!(
            "{what} must be {}×{} to match A ({n}×{n}), B and C, got {}×{}",
            want.0, want.1, got.0, got.1
        ))
    };
    if b.nrows() != n {
        return Err(bad("B", b.shape(), (n, m)));
    }
    if c.ncols() != n {
        return Err(bad("C", c.shape(), (p, n)));
    }
    if d.shape() != (p, m) {
        return Err(bad("D", d.shape(), (p, m)));
    }
    check_finite(b, "B")?;
    check_finite(c, "C")?;
    check_finite(d, "D")?;
    Ok((n, m, p))
}
