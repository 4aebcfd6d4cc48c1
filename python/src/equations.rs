//! The matrix equations (the library's `numeric::linalg`): Lyapunov, Stein, Sylvester and
//! the algebraic Riccati equations, each answer X with its residual and condition estimate.

use pyo3::prelude::*;
use pyo3::types::PyDict;

use ltikit::numeric::linalg::{MatrixSolution, Riccati, care, dare, dlyap, lyap, sylvester};

use crate::guard;
use crate::matrix::{complex_out, matrix_in, matrix_out};

type Rows = Vec<Vec<f64>>;

fn solution_dict<'py>(py: Python<'py>, s: &MatrixSolution) -> PyResult<Bound<'py, PyDict>> {
    let o = PyDict::new(py);
    o.set_item("X", matrix_out(py, &s.x)?)?;
    o.set_item("residual", s.residual)?;
    o.set_item("condition", s.condition)?;
    Ok(o)
}

fn riccati_dict<'py>(py: Python<'py>, r: &Riccati) -> PyResult<Bound<'py, PyDict>> {
    let o = PyDict::new(py);
    o.set_item("X", matrix_out(py, &r.x)?)?;
    o.set_item("K", matrix_out(py, &r.gain)?)?;
    o.set_item("poles", complex_out(py, &r.closed_loop))?;
    o.set_item("residual", r.residual)?;
    o.set_item("condition", r.condition)?;
    Ok(o)
}

/// A·X + X·Aᵀ + Q = 0 (MATLAB `lyap(A, Q)`).
#[pyfunction]
pub fn solve_lyap<'py>(py: Python<'py>, a: Rows, q: Rows) -> PyResult<Bound<'py, PyDict>> {
    let s = guard(|| lyap(&matrix_in(a, "`a`")?, &matrix_in(q, "`q`")?))?;
    solution_dict(py, &s)
}

/// A·X·Aᵀ − X + Q = 0 (MATLAB `dlyap(A, Q)`).
#[pyfunction]
pub fn solve_dlyap<'py>(py: Python<'py>, a: Rows, q: Rows) -> PyResult<Bound<'py, PyDict>> {
    let s = guard(|| dlyap(&matrix_in(a, "`a`")?, &matrix_in(q, "`q`")?))?;
    solution_dict(py, &s)
}

/// A·X + X·B = C.
#[pyfunction]
pub fn solve_sylvester<'py>(
    py: Python<'py>,
    a: Rows,
    b: Rows,
    c: Rows,
) -> PyResult<Bound<'py, PyDict>> {
    let s = guard(|| {
        sylvester(
            &matrix_in(a, "`a`")?,
            &matrix_in(b, "`b`")?,
            &matrix_in(c, "`c`")?,
        )
    })?;
    solution_dict(py, &s)
}

/// The stabilising solution of the continuous (`discrete=False`) or discrete algebraic
/// Riccati equation, with the gain and the closed-loop poles.
#[pyfunction]
#[pyo3(signature = (a, b, q, r, s=None, discrete=false))]
pub fn solve_riccati<'py>(
    py: Python<'py>,
    a: Rows,
    b: Rows,
    q: Rows,
    r: Rows,
    s: Option<Rows>,
    discrete: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let sol = guard(|| {
        let (a, b) = (matrix_in(a, "`a`")?, matrix_in(b, "`b`")?);
        let (q, r) = (matrix_in(q, "`q`")?, matrix_in(r, "`r`")?);
        let s = s.map(|s| matrix_in(s, "`s`")).transpose()?;
        if discrete {
            dare(&a, &b, &q, &r, s.as_ref())
        } else {
            care(&a, &b, &q, &r, s.as_ref())
        }
    })?;
    riccati_dict(py, &sol)
}
