//! Norms, Gramians, Hankel singular values, balanced truncation and singular values of a
//! model (the library's `analysis::norms`), on the state-space model the command line uses:
//! a state-space model as given, otherwise the minimal realisation of the factored form.

use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use ltikit::LtiError;
use ltikit::analysis::norms::{
    GramianKind, PeakGain, ReducedOrder, balanced_truncation, gramian, h2_norm,
    hankel_singular_values, hinf_norm, linf_norm, sigma_response,
};

use crate::convert::array2;
use crate::guard;
use crate::matrix::matrix_out;
use crate::model::Model;

fn peak_dict<'py>(py: Python<'py>, n: &PeakGain) -> PyResult<Bound<'py, PyDict>> {
    let o = PyDict::new(py);
    o.set_item("norm", n.kind.symbol())?;
    o.set_item("value", n.value())?;
    o.set_item("lower", n.lower)?;
    o.set_item("upper", n.upper)?;
    o.set_item("relative_gap", n.relative_gap())?;
    o.set_item("w", n.w)?;
    o.set_item("iterations", n.iterations)?;
    o.set_item("infinite", n.infinite.clone())?;
    Ok(o)
}

/// The certified H∞ norm (`linf=True`: L∞): value, lower, upper, relative gap, peak
/// frequency w, iterations, and why it is infinite.
#[pyfunction]
#[pyo3(signature = (model, linf=false))]
pub fn peak_gain<'py>(py: Python<'py>, model: &Model, linf: bool) -> PyResult<Bound<'py, PyDict>> {
    let ss = model.norm_state_space()?;
    let n = guard(|| if linf { linf_norm(&ss) } else { hinf_norm(&ss) })?;
    peak_dict(py, &n)
}

/// The H2 norm: value, the Gramian's residual, and why it is infinite.
#[pyfunction]
pub fn norm_h2<'py>(py: Python<'py>, model: &Model) -> PyResult<Bound<'py, PyDict>> {
    let ss = model.norm_state_space()?;
    let n = guard(|| h2_norm(&ss))?;
    let o = PyDict::new(py);
    o.set_item("value", n.value)?;
    o.set_item("residual", n.residual)?;
    o.set_item("infinite", n.infinite)?;
    Ok(o)
}

/// The controllability (`"c"`) or observability (`"o"`) Gramian with its Cholesky factor and
/// residual.
#[pyfunction]
pub fn gram<'py>(py: Python<'py>, model: &Model, kind: &str) -> PyResult<Bound<'py, PyDict>> {
    let kind = match kind {
        "c" | "controllability" => GramianKind::Controllability,
        "o" | "observability" => GramianKind::Observability,
        other => {
            return Err(crate::lti_err(LtiError::invalid(format!(
                "`kind`: c (controllability) or o (observability), not '{}'",
                ltikit::error::abbreviate(other)
            ))));
        }
    };
    let ss = model.norm_state_space()?;
    let g = guard(|| gramian(&ss, kind))?;
    let o = PyDict::new(py);
    o.set_item("gramian", matrix_out(py, &g.matrix())?)?;
    o.set_item("factor", matrix_out(py, &g.factor)?)?;
    o.set_item("residual", g.residual)?;
    Ok(o)
}

/// The Hankel singular values, largest first.
#[pyfunction]
pub fn hsv(model: &Model) -> PyResult<Vec<f64>> {
    let ss = model.norm_state_space()?;
    guard(|| hankel_singular_values(&ss)).map(|h| h.values)
}

/// Balanced truncation to `order` states or to the smallest order whose bound is at most
/// `error`: the reduced model's matrices (A, B, C, D), its period, the Hankel singular
/// values, the a priori bound and the certified error ‖G − G_r‖∞.
#[pyfunction]
#[pyo3(signature = (model, order=None, error=None))]
pub fn balred<'py>(
    py: Python<'py>,
    model: &Model,
    order: Option<usize>,
    error: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let order = match (order, error) {
        (Some(k), None) => ReducedOrder::Order(k),
        (None, Some(e)) => ReducedOrder::Error(e),
        (Some(_), Some(_)) => {
            return Err(crate::lti_err(LtiError::invalid(
                "balred takes `order` or `error`, not both",
            )));
        }
        (None, None) => {
            return Err(crate::lti_err(LtiError::invalid(
                "balred needs `order` or `error`",
            )));
        }
    };
    let ss = model.norm_state_space()?;
    let r = guard(|| balanced_truncation(&ss, order))?;
    let m = &r.reduced;
    let o = PyDict::new(py);
    o.set_item(
        "reduced",
        (
            matrix_out(py, &m.a)?,
            matrix_out(py, &m.b)?,
            matrix_out(py, &m.c)?,
            matrix_out(py, &m.d)?,
        ),
    )?;
    o.set_item("dt", m.domain.dt())?;
    o.set_item("states", ss.order())?;
    o.set_item("order", m.order())?;
    o.set_item("hsv", r.hsv.clone())?;
    o.set_item("bound", r.bound)?;
    o.set_item("error", peak_dict(py, &r.error)?)?;
    o.set_item("residuals", r.residuals)?;
    Ok(o)
}

/// The singular values of G at each frequency of `w` (rad/s): one row per frequency, largest
/// first.
#[pyfunction]
pub fn sigma<'py>(
    py: Python<'py>,
    model: &Model,
    w: Vec<f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let ss = model.norm_state_space()?;
    let s = guard(|| sigma_response(&ss, &w))?;
    if s.sigma.is_empty() {
        return Ok(PyArray2::zeros(
            py,
            [0, ss.n_inputs().min(ss.n_outputs())],
            false,
        ));
    }
    array2(py, &s.sigma)
}
