//! A response in one piece: the closed form y(t) with its transient and steady-state parts,
//! and its exact values at the requested times, from one decomposition of Y(s).
//!
//! The closed form comes from the partial fractions of Y(s) ([`crate::analysis::laplace`]);
//! the values from exact matrix-exponential stepping of the same Y(s)
//! ([`crate::analysis::time`]), which stays accurate where the closed form's residues are huge
//! and cancel. Both are evaluated at the times and their largest disagreement is reported: a
//! built-in cross-check.

use serde::Serialize;

use crate::analysis::closed_form::ClosedForm;
use crate::analysis::factored::Factored;
use crate::analysis::input::Input;
use crate::analysis::laplace::{ClosedParts, Decomposition};
use crate::analysis::time::{check_times, simulate};
use crate::error::Result;
use crate::lti::TransferFunction;

/// The closed-form response, its parts and its samples.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Response {
    /// y(t) = transient + steady state.
    pub closed_form: ClosedForm,
    /// Terms of system poles (and initial conditions, and any δ term).
    pub transient: ClosedForm,
    /// Terms of input poles (including resonant ones).
    pub steady_state: ClosedForm,
    /// lim t→∞ y(t) when it exists and is finite.
    pub final_value: Option<f64>,
    /// Values at the requested times (empty when none were asked for).
    pub samples: ResponseSamples,
}

/// A response sampled at given times: exact values and the closed form side by side.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct ResponseSamples {
    /// The times, in the caller's order.
    pub t: Vec<f64>,
    /// Exact y(t) (matrix-exponential stepping); δ terms excluded.
    pub y: Vec<f64>,
    /// y(t) − steady state(t).
    pub transient: Vec<f64>,
    /// The steady-state closed form at t.
    pub steady_state: Vec<f64>,
    /// The full closed form at t.
    pub closed_form: Vec<f64>,
    /// max |closed form − y| over the times (0 for no times): the built-in cross-check.
    pub closed_form_error: f64,
    /// max |y| over the times.
    pub max_abs_y: f64,
}

impl Factored {
    /// The response to `input` with ODE initial conditions `ics` = [y(0), y′(0), …] (fewer
    /// than the order: the rest are 0): the closed form, its transient and steady-state parts
    /// (see [`crate::analysis::laplace`] for cancellations and the split), the final value,
    /// and exact values at the times `t` (any order, finite, ≥ 0) with the closed form at the
    /// same times and their largest disagreement.
    ///
    /// Errors: an improper G ([`crate::LtiError::Improper`]), more initial conditions than the
    /// order (or any, for a plant without ODE coefficients), NaN/∞ values, an invalid input
    /// parameter, a negative or non-finite time, values that overflow.
    ///
    /// A **discrete-time** plant answers in z: the closed form is the sequence y\[k\]
    /// ([`crate::analysis::SequenceForm`] inside the [`ClosedForm`], from the partial fractions
    /// of Y(z)/z; see `analysis::discrete`), `ics` are y\[−1\], y\[−2\], … of the difference
    /// equation, the inputs are sampled at t = kT, a time reads the sample at or before it,
    /// and the exact values come from the one marcher ([`Factored::time_response`]).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::Input;
    /// let f = TransferFunction::from_descending(&[1.0], &[1.0, 1.0, 1.0]).unwrap().factored().unwrap();
    /// let r = f.response(&Input::Step, &[], &[0.0, 1.0, 5.0]).unwrap();
    /// assert!(r.samples.closed_form_error < 1e-14);
    /// assert!((r.samples.steady_state[2] - 1.0).abs() < 1e-15);
    /// assert_eq!(r.steady_state.expression(), "1");
    /// ```
    pub fn response(&self, input: &Input, ics: &[f64], t: &[f64]) -> Result<Response> {
        check_times(t)?;
        if self.domain().is_discrete() {
            let parts = crate::analysis::discrete::closed_parts(self, input, ics)?;
            let y = self.time_response(input, ics, t)?.y;
            return Ok(assemble(parts, t, y));
        }
        let delay = self.delay();
        if delay > 0.0 {
            // the rational response shifted by T: closed forms f(t − T)·1(t − T)
            crate::analysis::time::require_no_ics_with_delay(ics, delay)?;
            let rational = self.rational();
            let dec = Decomposition::new(&rational, input, ics)?;
            let mut parts = dec.closed_form()?;
            parts.closed_form = parts.closed_form.with_delay(delay);
            parts.transient = parts.transient.with_delay(delay);
            parts.steady_state = parts.steady_state.with_delay(delay);
            let y = self.time_response(input, ics, t)?.y;
            return Ok(assemble(parts, t, y));
        }
        let dec = Decomposition::new(self, input, ics)?;
        let parts = dec.closed_form()?;
        let y = simulate(&dec, t)?;
        Ok(assemble(parts, t, y))
    }

    /// The closed form alone ([`Factored::response`] without samples).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::Input;
    /// // Tank (seed eqs. 3.6–3.18): h' + 0.5 h = u, h(0) = 1, step input:
    /// // h(t) = e^(−t/2) + 2 (1 − e^(−t/2)): transient −e^(−t/2), steady state 2.
    /// let f = TransferFunction::from_descending(&[1.0], &[1.0, 0.5]).unwrap().factored().unwrap();
    /// let r = f.inverse_laplace(&Input::Step, &[1.0]).unwrap();
    /// assert_eq!(r.closed_form.to_string(), "y(t) = 2 - e^(-0.5 t)");
    /// assert_eq!(r.steady_state.expression(), "2");
    /// assert_eq!(r.transient.expression(), "-e^(-0.5 t)");
    /// assert_eq!(r.final_value, Some(2.0));
    /// ```
    pub fn inverse_laplace(&self, input: &Input, ics: &[f64]) -> Result<Response> {
        self.domain().require_continuous(
            "the inverse Laplace transform (for a discrete-time plant: `inverse_z`)",
        )?;
        self.response(input, ics, &[])
    }

    /// The closed-form sequence y\[k\] of a discrete-time plant alone ([`Factored::response`]
    /// without samples): the inverse z-transform of Y(z) = G(z)U(z) + Y_ic(z), with `ics` =
    /// [y\[−1\], y\[−2\], …] of the difference equation. Errors in continuous time.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::Input;
    /// use ltikit::lti::Domain;
    /// // y[k] − 0.5 y[k−1] = 0.5 u[k−1] (G = 0.5/(z − 0.5)), y[−1] = 4, step input:
    /// // y[k] = 1 + 0.5^k (the free part 4·0.5^(k+1) = 2·0.5^k, the forced 1 − 0.5^k)
    /// let f = TransferFunction::from_descending(&[0.5], &[1.0, -0.5]).unwrap()
    ///     .with_domain(Domain::discrete(0.1).unwrap())
    ///     .factored().unwrap();
    /// let r = f.inverse_z(&Input::Step, &[4.0]).unwrap();
    /// assert_eq!(r.closed_form.to_string(), "y[k] = 1 + 0.5^k");
    /// assert_eq!(r.steady_state.expression(), "1");
    /// assert_eq!(r.transient.expression(), "0.5^k");
    /// assert_eq!(r.final_value, Some(1.0));
    /// ```
    pub fn inverse_z(&self, input: &Input, ics: &[f64]) -> Result<Response> {
        self.domain().require_discrete(
            "the inverse z-transform (for a continuous-time plant: `inverse_laplace`)",
        )?;
        self.response(input, ics, &[])
    }
}

impl TransferFunction {
    /// [`Factored::response`] of the factored G.
    pub fn response(&self, input: &Input, ics: &[f64], t: &[f64]) -> Result<Response> {
        self.factored()?.response(input, ics, t)
    }

    /// [`Factored::inverse_laplace`] of the factored G.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::Input;
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 2.0, 1.0]).unwrap();
    /// let r = g.inverse_laplace(&Input::Step, &[]).unwrap();
    /// assert_eq!(r.closed_form.to_string(), "y(t) = 1 - (1 + t) e^(-t)");
    /// ```
    pub fn inverse_laplace(&self, input: &Input, ics: &[f64]) -> Result<Response> {
        self.factored()?.inverse_laplace(input, ics)
    }
}

/// The response from its closed-form parts and the exact values `y` at the times `t`.
fn assemble(parts: ClosedParts, t: &[f64], y: Vec<f64>) -> Response {
    let closed: Vec<f64> = t.iter().map(|&x| parts.closed_form.eval(x)).collect();
    let steady: Vec<f64> = t.iter().map(|&x| parts.steady_state.eval(x)).collect();
    let transient = y.iter().zip(&steady).map(|(a, b)| a - b).collect();
    let closed_form_error = closed
        .iter()
        .zip(&y)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let max_abs_y = y.iter().map(|v| v.abs()).fold(0.0, f64::max);
    Response {
        closed_form: parts.closed_form,
        transient: parts.transient,
        steady_state: parts.steady_state,
        final_value: parts.final_value,
        samples: ResponseSamples {
            t: t.to_vec(),
            y,
            transient,
            steady_state: steady,
            closed_form: closed,
            closed_form_error,
            max_abs_y,
        },
    }
}
