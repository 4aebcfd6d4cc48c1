//! `ltikit._core`: the Rust half of the Python package `ltikit` (PyO3, numpy).
//!
//! The package's public face is the Python module `ltikit` (`python/ltikit/__init__.py`), which
//! checks and converts the arguments (lists, numpy arrays) and wraps the answers; this module
//! holds one model type, [`model::Model`], whose methods call the library's public API — the
//! same functions the command line calls — and hand back numbers, numpy arrays and plain dicts.
//! Nothing here computes an analysis of its own.
//!
//! Errors: every `ltikit::LtiError` becomes `ltikit.LtiError` (a `ValueError`) carrying the
//! library's one-line message; a Rust panic is caught at the boundary ([`guard`]) and becomes
//! the same exception, so the interpreter never crashes.

use std::panic::{AssertUnwindSafe, catch_unwind};

use pyo3::prelude::*;

mod analyze;
mod batch;
mod convert;
mod design;
mod equations;
mod matrix;
mod mimo;
mod model;
mod norms;
mod tables;

pyo3::create_exception!(
    _core,
    LtiError,
    pyo3::exceptions::PyValueError,
    "An input ltikit cannot take or a quantity it cannot compute: one line naming the problem \
     (the command line's message)."
);

/// The library's error as `ltikit.LtiError` with its one-line message.
pub(crate) fn lti_err(e: impl std::fmt::Display) -> PyErr {
    LtiError::new_err(one_line(&e.to_string()))
}

/// A message on one line (a library message is one line already; this is the guard).
fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Runs `f`, turning the library's error into `LtiError` and a panic into `LtiError` too
/// ("internal error: …"), never unwinding into Python.
pub(crate) fn guard<T>(f: impl FnOnce() -> ltikit::Result<T>) -> PyResult<T> {
    attempt(f).map_err(LtiError::new_err)
}

/// Runs `f`: its value, or the one-line message of its error or of its panic.
pub(crate) fn attempt<T>(f: impl FnOnce() -> ltikit::Result<T>) -> Result<T, String> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(v)) => Ok(v),
        Ok(Err(e)) => Err(one_line(&e.to_string())),
        Err(payload) => Err(format!(
            "internal error (please report it): {}",
            panic_text(&payload)
        )),
    }
}

/// The text of a panic's payload.
pub(crate) fn panic_text(payload: &Box<dyn std::any::Any + Send>) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .map_or_else(|| "a panic".into(), |s| one_line(&s))
}

/// The extension module.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("LtiError", m.py().get_type::<LtiError>())?;
    m.add_class::<model::Model>()?;
    m.add_function(wrap_pyfunction!(batch::batch, m)?)?;
    m.add_function(wrap_pyfunction!(model::model_names, m)?)?;
    m.add_function(wrap_pyfunction!(panic_for_test, m)?)?;
    m.add_function(wrap_pyfunction!(check_points, m)?)?;
    m.add_function(wrap_pyfunction!(check_order, m)?)?;
    m.add_function(wrap_pyfunction!(design::design_lqr, m)?)?;
    m.add_function(wrap_pyfunction!(design::design_lqe, m)?)?;
    m.add_function(wrap_pyfunction!(design::design_lqg, m)?)?;
    m.add_function(wrap_pyfunction!(design::design_place, m)?)?;
    m.add_function(wrap_pyfunction!(norms::peak_gain, m)?)?;
    m.add_function(wrap_pyfunction!(norms::norm_h2, m)?)?;
    m.add_function(wrap_pyfunction!(norms::gram, m)?)?;
    m.add_function(wrap_pyfunction!(norms::hsv, m)?)?;
    m.add_function(wrap_pyfunction!(norms::balred, m)?)?;
    m.add_function(wrap_pyfunction!(norms::sigma, m)?)?;
    m.add_function(wrap_pyfunction!(equations::solve_lyap, m)?)?;
    m.add_function(wrap_pyfunction!(equations::solve_dlyap, m)?)?;
    m.add_function(wrap_pyfunction!(equations::solve_sylvester, m)?)?;
    m.add_function(wrap_pyfunction!(equations::solve_riccati, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("MAX_ORDER", ltikit::MAX_ORDER)?;
    Ok(())
}

/// The library's limit on sample points (`MAX_POINTS`) for the field `what` (`` `t` ``):
/// checked before a long array is converted.
#[pyfunction]
fn check_points(what: &str, n: usize) -> PyResult<()> {
    guard(|| ltikit::limits::POINTS.check_usize(what, n).map(|_| ()))
}

/// The library's limit on the number of coefficients of a polynomial (`MAX_ORDER` + 1).
#[pyfunction]
fn check_order(what: &str, n: usize) -> PyResult<()> {
    if n > ltikit::MAX_ORDER + 1 {
        return Err(LtiError::new_err(format!(
            "{what}: {n} coefficients exceed the supported maximum order {}",
            ltikit::MAX_ORDER
        )));
    }
    Ok(())
}

/// Panics on purpose (the tests check that a panic becomes `LtiError`, not a crash).
#[pyfunction]
fn panic_for_test() -> PyResult<()> {
    guard(|| -> ltikit::Result<()> { panic!("a deliberate panic") })
}
