//! Controller and estimator design on a model: `lqr`, `lqe`, `lqg`, `place` (the library's
//! `analysis::design`), answers as dicts of numpy arrays.

use nalgebra::DMatrix;
use num_complex::Complex64;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use ltikit::LtiError;
use ltikit::analysis::design::{Kalman, Lqr, NoiseInput, lqe, lqg, lqr, place};
use ltikit::lti::StateSpace;

use crate::guard;
use crate::matrix::{complex_out, matrix_in, matrix_out, weight_in};
use crate::model::Model;

/// "care" or "dare": the Riccati equation of the model's domain.
fn equation(ss: &StateSpace) -> &'static str {
    if ss.domain.is_discrete() {
        "dare"
    } else {
        "care"
    }
}

/// Where the process noise enters (`None`: decided by the size of Qn).
fn noise_of(noise: Option<&str>) -> ltikit::Result<Option<NoiseInput>> {
    // the library's message names the command line's field, `noise_input`
    noise
        .map(|text| {
            NoiseInput::parse(text).map_err(|_| {
                LtiError::invalid(format!(
                    "`noise` '{}': write states (G = I) or inputs (G = B)",
                    ltikit::error::abbreviate(text)
                ))
            })
        })
        .transpose()
}

/// Qn with one number standing for a multiple of the identity of the size `noise` needs.
fn process_noise(
    rows: Vec<Vec<f64>>,
    ss: &StateSpace,
    noise: Option<NoiseInput>,
) -> ltikit::Result<DMatrix<f64>> {
    let k = match noise {
        Some(NoiseInput::States) => ss.order(),
        Some(NoiseInput::Inputs) => ss.b.ncols(),
        None => 1,
    };
    weight_in(rows, "`qn`", k)
}

fn regulator_dict<'py>(py: Python<'py>, ss: &StateSpace, d: &Lqr) -> PyResult<Bound<'py, PyDict>> {
    let o = PyDict::new(py);
    o.set_item("equation", equation(ss))?;
    o.set_item("K", matrix_out(py, &d.gain)?)?;
    o.set_item("X", matrix_out(py, &d.x)?)?;
    o.set_item("poles", complex_out(py, &d.closed_loop))?;
    o.set_item("residual", d.residual)?;
    o.set_item("condition", d.condition)?;
    Ok(o)
}

fn estimator_dict<'py>(
    py: Python<'py>,
    ss: &StateSpace,
    k: &Kalman,
) -> PyResult<Bound<'py, PyDict>> {
    let o = PyDict::new(py);
    o.set_item("equation", equation(ss))?;
    o.set_item("L", matrix_out(py, &k.gain)?)?;
    o.set_item("P", matrix_out(py, &k.p)?)?;
    o.set_item("poles", complex_out(py, &k.estimator_poles))?;
    o.set_item("noise", k.noise_input.name())?;
    o.set_item("residual", k.residual)?;
    o.set_item("condition", k.condition)?;
    Ok(o)
}

/// The LQR of `model` (state weight Q, input weight R, optional cross weight S; one number
/// stands for that multiple of the identity): K, X, the closed-loop poles, the residual.
#[pyfunction]
#[pyo3(signature = (model, q, r, s=None))]
pub fn design_lqr<'py>(
    py: Python<'py>,
    model: &Model,
    q: Vec<Vec<f64>>,
    r: Vec<Vec<f64>>,
    s: Option<Vec<Vec<f64>>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (ss, d) = guard(|| {
        let ss = model.design_state_space("lqr")?;
        let q = weight_in(q, "`q`", ss.order())?;
        let r = weight_in(r, "`r`", ss.b.ncols())?;
        let s = s.map(|s| matrix_in(s, "`s`")).transpose()?;
        let d = lqr(&ss, &q, &r, s.as_ref())?;
        Ok((ss, d))
    })?;
    regulator_dict(py, &ss, &d)
}

/// The Kalman estimator gain of `model` (process noise Qn, measurement noise Rn, optional
/// cross covariance Nn; `noise` "states" or "inputs", `None` decided by the size of Qn).
#[pyfunction]
#[pyo3(signature = (model, qn, rn, nn=None, noise=None))]
pub fn design_lqe<'py>(
    py: Python<'py>,
    model: &Model,
    qn: Vec<Vec<f64>>,
    rn: Vec<Vec<f64>>,
    nn: Option<Vec<Vec<f64>>>,
    noise: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let (ss, k) = guard(|| {
        let ss = model.design_state_space("lqe")?;
        let noise = noise_of(noise)?;
        let qn = process_noise(qn, &ss, noise)?;
        let rn = weight_in(rn, "`rn`", ss.c.nrows())?;
        let nn = nn.map(|n| matrix_in(n, "`nn`")).transpose()?;
        let k = lqe(&ss, &qn, &rn, nn.as_ref(), noise)?;
        Ok((ss, k))
    })?;
    estimator_dict(py, &ss, &k)
}

/// The LQG controller of `model`: the regulator, the estimator, and the controller from y
/// to −u as the rows of its matrices (A, B, C, D) with its sampling period.
#[pyfunction]
#[pyo3(signature = (model, q, r, qn, rn, noise=None))]
pub fn design_lqg<'py>(
    py: Python<'py>,
    model: &Model,
    q: Vec<Vec<f64>>,
    r: Vec<Vec<f64>>,
    qn: Vec<Vec<f64>>,
    rn: Vec<Vec<f64>>,
    noise: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let (ss, d) = guard(|| {
        let ss = model.design_state_space("lqg")?;
        let noise = noise_of(noise)?;
        let q = weight_in(q, "`q`", ss.order())?;
        let r = weight_in(r, "`r`", ss.b.ncols())?;
        let qn = process_noise(qn, &ss, noise)?;
        let rn = weight_in(rn, "`rn`", ss.c.nrows())?;
        let d = lqg(&ss, &q, &r, &qn, &rn, noise)?;
        Ok((ss, d))
    })?;
    let o = PyDict::new(py);
    o.set_item("regulator", regulator_dict(py, &ss, &d.regulator)?)?;
    o.set_item("estimator", estimator_dict(py, &ss, &d.estimator)?)?;
    let c = &d.controller;
    o.set_item(
        "controller",
        (
            matrix_out(py, &c.a)?,
            matrix_out(py, &c.b)?,
            matrix_out(py, &c.c)?,
            matrix_out(py, &c.d)?,
        ),
    )?;
    o.set_item("dt", c.domain.dt())?;
    Ok(o)
}

/// The state feedback K (u = −K x) placing the eigenvalues of A − BK at `poles`: K, the
/// method, the requested and achieved poles, their distances, the relative error and the
/// condition figure.
#[pyfunction]
pub fn design_place<'py>(
    py: Python<'py>,
    model: &Model,
    poles: Vec<Complex64>,
) -> PyResult<Bound<'py, PyDict>> {
    let p = guard(|| {
        let ss = model.design_state_space("place")?;
        place(&ss, &poles)
    })?;
    let o = PyDict::new(py);
    o.set_item("K", matrix_out(py, &p.gain)?)?;
    o.set_item("method", p.method.name())?;
    o.set_item("requested", complex_out(py, &p.requested))?;
    o.set_item("poles", complex_out(py, &p.achieved))?;
    o.set_item("distance", p.distance.clone())?;
    o.set_item("relative_error", p.relative_error)?;
    o.set_item("condition", p.condition)?;
    o.set_item("iterations", p.iterations)?;
    o.set_item("note", p.conditioning_note())?;
    Ok(o)
}
