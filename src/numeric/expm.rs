//! Matrix exponential.
//!
//! nalgebra's `exp()` (scaling and squaring with a Padé approximant) is accurate to
//! 1e-16…1e-13 on rotations, Jordan blocks and stiff cases; this wrapper only adds the checks
//! that keep bad input from reaching it (non-square, non-finite, empty).

use nalgebra::DMatrix;

use crate::error::{LtiError, Result};

/// e^M for a square, finite matrix.
///
/// ```
/// use nalgebra::DMatrix;
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, 0.0]);
/// let e = ltikit::numeric::expm(&(a * std::f64::consts::FRAC_PI_2)).unwrap();
/// assert!((e[(0, 1)] - 1.0).abs() < 1e-14);
/// ```
pub fn expm(m: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    if !m.is_square() {
        return Err(LtiError::invalid(format!(
            "matrix exponential needs a square matrix, got {}×{}",
            m.nrows(),
            m.ncols()
        )));
    }
    if m.nrows() == 0 {
        return Ok(m.clone());
    }
    if let Some(x) = m.iter().find(|x| !x.is_finite()) {
        return Err(LtiError::NonFinite {
            what: "a matrix entry".into(),
            value: *x,
        });
    }
    let e = m.exp();
    if let Some(x) = e.iter().find(|x| !x.is_finite()) {
        return Err(LtiError::NonFinite {
            what: "the matrix exponential (overflow: the time span is too long for this unstable system)".into(),
            value: *x,
        });
    }
    Ok(e)
}
