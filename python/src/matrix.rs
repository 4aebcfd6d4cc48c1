//! Matrices at the boundary: rows of numbers in, numpy 2-D arrays out.

use nalgebra::DMatrix;
use num_complex::Complex64;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;

/// Rows of numbers as a matrix (ragged rows are an error naming the matrix `what`).
pub fn matrix_in(rows: Vec<Vec<f64>>, what: &str) -> ltikit::Result<DMatrix<f64>> {
    ltikit::lti::plant::matrix_of_rows(rows, what)
}

/// Rows of numbers as a matrix, one number standing for that multiple of the k × k identity
/// (as the command line reads a weight).
pub fn weight_in(rows: Vec<Vec<f64>>, what: &str, k: usize) -> ltikit::Result<DMatrix<f64>> {
    Ok(ltikit::analysis::design::kalman::expand_scalar(
        matrix_in(rows, what)?,
        k,
    ))
}

/// A matrix as a numpy 2-D array (of its shape, empty ones included).
pub fn matrix_out<'py>(py: Python<'py>, m: &DMatrix<f64>) -> PyResult<Bound<'py, PyArray2<f64>>> {
    // nalgebra stores by columns: the transpose's storage is the rows in order
    let data: Vec<f64> = m.transpose().as_slice().to_vec();
    PyArray1::from_vec(py, data).reshape([m.nrows(), m.ncols()])
}

/// Complex numbers as a numpy array.
pub fn complex_out<'py>(py: Python<'py>, v: &[Complex64]) -> Bound<'py, PyArray1<Complex64>> {
    PyArray1::from_vec(py, v.to_vec())
}
