//! Conversions at the boundary: JSON values to Python objects, roots to numpy arrays.

use num_complex::Complex64;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde_json::Value;

use ltikit::Root;

/// A JSON value as Python: objects → dicts (keys in order), arrays → lists, numbers → int or
/// float, `null` → `None`.
pub fn to_py<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Value::Number(n) => match (n.as_i64(), n.as_f64()) {
            (Some(i), _) => i.into_pyobject(py)?.into_any(),
            (None, Some(f)) => f.into_pyobject(py)?.into_any(),
            (None, None) => py.None().into_bound(py),
        },
        Value::String(s) => s.into_pyobject(py)?.into_any(),
        Value::Array(a) => {
            let list = PyList::empty(py);
            for x in a {
                list.append(to_py(py, x)?)?;
            }
            list.into_any()
        }
        Value::Object(o) => {
            let d = PyDict::new(py);
            for (k, x) in o {
                d.set_item(k, to_py(py, x)?)?;
            }
            d.into_any()
        }
    })
}

/// A serialisable library struct as Python (through its JSON value).
pub fn ser_to_py<'py, T: serde::Serialize>(py: Python<'py>, x: &T) -> PyResult<Bound<'py, PyAny>> {
    let v = serde_json::to_value(x).map_err(crate::lti_err)?;
    to_py(py, &v)
}

/// Roots listed with repetition (the library's order: decreasing real part, then imaginary).
pub fn repeated(roots: &[Root]) -> Vec<Complex64> {
    roots
        .iter()
        .flat_map(|r| std::iter::repeat_n(r.value, r.multiplicity))
        .collect()
}

/// Roots with repetition as a complex numpy array.
pub fn roots_array<'py>(py: Python<'py>, roots: &[Root]) -> Bound<'py, PyArray1<Complex64>> {
    PyArray1::from_vec(py, repeated(roots))
}

/// Distinct roots and their multiplicities: `[(complex, int), …]`.
pub fn multiplicities(roots: &[Root]) -> Vec<(Complex64, usize)> {
    roots.iter().map(|r| (r.value, r.multiplicity)).collect()
}

/// A float vector as a numpy array.
pub fn array<'py>(py: Python<'py>, v: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, v)
}

/// A complex vector as a numpy array.
pub fn carray<'py>(py: Python<'py>, v: Vec<Complex64>) -> Bound<'py, PyArray1<Complex64>> {
    PyArray1::from_vec(py, v)
}

/// Rows of equal length as a 2-D numpy array (an empty array of shape (0, 0) for no rows).
pub fn array2<'py, T: numpy::Element + Clone>(
    py: Python<'py>,
    rows: &[Vec<T>],
) -> PyResult<Bound<'py, PyArray2<T>>> {
    PyArray2::from_vec2(py, rows).map_err(crate::lti_err)
}

/// `[re, im]` of a complex number (the JSON contract's form).
pub fn pair(z: Complex64) -> [f64; 2] {
    [z.re, z.im]
}

/// A finite number or `None` (JSON `null`), as the command line writes it.
pub fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}
