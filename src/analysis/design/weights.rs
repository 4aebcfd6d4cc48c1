//! The checks of design weights and covariances: sizes, finiteness, symmetry, positive
//! definiteness — each error names the field (`q`, `r`, `s`, `qn`, `rn`, `nn`).

use nalgebra::DMatrix;

use crate::error::{LtiError, Result};

/// `m` must be `rows × cols` and finite; `what` is the field in backquotes, `why` says where
/// the size comes from.
pub(crate) fn check_size(
    m: &DMatrix<f64>,
    rows: usize,
    cols: usize,
    what: &str,
    why: &str,
) -> Result<()> {
    if m.nrows() != rows || m.ncols() != cols {
        return Err(LtiError::invalid(format!(
            "{what} must be {rows}×{cols} ({why}), got {}×{}",
            m.nrows(),
            m.ncols()
        )));
    }
    if let Some(x) = m.iter().find(|x| !x.is_finite()) {
        return Err(LtiError::NonFinite {
            what: format!("an entry of {what}"),
            value: *x,
        });
    }
    Ok(())
}

/// `m` (square, finite) must be symmetric within 1e-12 of its largest entry.
pub(crate) fn check_symmetric(m: &DMatrix<f64>, what: &str) -> Result<()> {
    let scale = m.amax();
    let n = m.nrows();
    for i in 0..n {
        for j in 0..i {
            if (m[(i, j)] - m[(j, i)]).abs() > 1e-12 * scale {
                return Err(LtiError::invalid(format!(
                    "{what} must be symmetric: entry ({}, {}) is {} but ({}, {}) is {}",
                    i + 1,
                    j + 1,
                    m[(i, j)],
                    j + 1,
                    i + 1,
                    m[(j, i)]
                )));
            }
        }
    }
    Ok(())
}

/// `m` (square, finite, symmetric) must be positive definite (a Cholesky factor exists and
/// its smallest pivot is above 1e-14 of the largest diagonal entry, squared).
pub(crate) fn check_positive_definite(m: &DMatrix<f64>, what: &str) -> Result<()> {
    check_symmetric(m, what)?;
    let ok = m.clone().cholesky().is_some_and(|c| {
        let l = c.l();
        let dmax = l.diagonal().amax();
        l.diagonal().iter().all(|&d| d > 1e-7 * dmax)
    });
    if ok {
        Ok(())
    } else {
        Err(LtiError::invalid(format!(
            "{what} must be positive definite (symmetric with positive eigenvalues)"
        )))
    }
}

/// `m` (square, finite, symmetric) must be positive semidefinite: its smallest eigenvalue
/// not below −1e-12 of its largest magnitude.
pub(crate) fn check_positive_semidefinite(m: &DMatrix<f64>, what: &str) -> Result<()> {
    check_symmetric(m, what)?;
    let sym = (m + m.transpose()) * 0.5;
    let ev = sym.symmetric_eigenvalues();
    let scale = ev.amax();
    if ev.iter().any(|&e| e < -1e-12 * scale) {
        return Err(LtiError::invalid(format!(
            "{what} must be positive semidefinite (its smallest eigenvalue is {})",
            crate::fmt::fmt_sig(ev.min(), 3)
        )));
    }
    Ok(())
}

/// The symmetric part (m + mᵀ)/2 (removes rounding-level asymmetry).
pub(crate) fn symmetric_part(m: &DMatrix<f64>) -> DMatrix<f64> {
    (m + m.transpose()) * 0.5
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_name_the_field() {
        let m = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 3.0, 1.0]);
        let e = check_symmetric(&m, "`q`").unwrap_err().to_string();
        assert!(e.starts_with("`q` must be symmetric"), "{e}");
        let m = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 1.0]);
        assert!(check_positive_definite(&m, "`r`").is_err());
        assert!(check_positive_semidefinite(&m, "`q`").is_err());
        let m = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0]);
        assert!(check_positive_semidefinite(&m, "`q`").is_ok());
        assert!(check_positive_definite(&m, "`r`").is_err());
        let e = check_size(&m, 3, 3, "`q`", "the plant has 3 states")
            .unwrap_err()
            .to_string();
        assert_eq!(e, "`q` must be 3×3 (the plant has 3 states), got 2×2");
    }
}
