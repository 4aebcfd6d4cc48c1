//! The input of a simulation: a vector signal built on the standard test inputs of the linear
//! analysis ([`crate::analysis::Input`]), so that one input enum serves the closed forms, the
//! nonlinear simulations and the plots.
//!
//! u(t) = `before` for t < `start`, and `before + (after − before)·s(t − start)` from then on,
//! where s is a standard signal: a step jumps to `after` (exactly), a ramp grows by
//! `after − before` per second, `sin:W` oscillates about `before` with amplitude
//! `after − before`, and so on. A constant input is a step with `before = after`.

use serde::Serialize;

use crate::analysis::Input;
use crate::error::{LtiError, Result, check_finite};
use crate::nonlinear::system::check_len;

/// The input signal of a simulation (see the module docs).
///
/// ```
/// use ltikit::analysis::Input;
/// use ltikit::nonlinear::InputSignal;
/// let u = InputSignal::shaped(vec![1.0], vec![3.0], Input::Ramp, 2.0);
/// let mut v = [0.0];
/// u.eval(1.0, &mut v);
/// assert_eq!(v[0], 1.0);
/// u.eval(2.5, &mut v);
/// assert_eq!(v[0], 2.0); // 1 + 2·0.5
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InputSignal {
    /// u(t) before `start`.
    pub before: Vec<f64>,
    /// The value a unit step would reach: the signal is `before + (after − before)·s`.
    pub after: Vec<f64>,
    /// The standard signal s (step, ramp, exp, sin, cos, none; an impulse cannot be
    /// simulated).
    pub shape: Input,
    /// When s starts.
    pub start: f64,
}

impl InputSignal {
    /// u(t) = u for all t.
    pub fn constant(u: Vec<f64>) -> InputSignal {
        InputSignal {
            before: u.clone(),
            after: u,
            shape: Input::Step,
            start: 0.0,
        }
    }

    /// No input (for autonomous models).
    pub fn none() -> InputSignal {
        InputSignal::constant(Vec::new())
    }

    /// u(t) = `before` for t < `t_step`, `after` from then on.
    pub fn step(t_step: f64, before: Vec<f64>, after: Vec<f64>) -> InputSignal {
        InputSignal {
            before,
            after,
            shape: Input::Step,
            start: t_step,
        }
    }

    /// `before` until `start`, then `before + (after − before)·shape(t − start)`.
    pub fn shaped(before: Vec<f64>, after: Vec<f64>, shape: Input, start: f64) -> InputSignal {
        InputSignal {
            before,
            after,
            shape,
            start,
        }
    }

    /// u(t) into `out` (length = number of inputs).
    pub fn eval(&self, t: f64, out: &mut [f64]) {
        if t < self.start {
            out.copy_from_slice(&self.before);
            return;
        }
        match self.shape {
            Input::Step => out.copy_from_slice(&self.after),
            Input::None | Input::Impulse => out.copy_from_slice(&self.before),
            shape => {
                let s = shape.eval(t - self.start);
                for ((o, b), a) in out.iter_mut().zip(&self.before).zip(&self.after) {
                    *o = b + (a - b) * s;
                }
            }
        }
    }

    /// u(t) as a new vector.
    pub fn at(&self, t: f64) -> Vec<f64> {
        let mut u = vec![0.0; self.before.len()];
        self.eval(t, &mut u);
        u
    }

    /// True when the input is zero at every time (the condition for conservation).
    pub fn is_zero(&self) -> bool {
        let zero = |v: &[f64]| v.iter().all(|x| *x == 0.0);
        zero(&self.before) && (zero(&self.after) || self.shape == Input::None)
    }

    /// True when u is constant on [0, ∞).
    pub fn is_constant(&self) -> bool {
        self.before == self.after || self.shape == Input::None
    }

    /// Errors unless both vectors have `nu` finite components, the start time is finite and the
    /// shape can be simulated.
    pub(crate) fn check(&self, nu: usize) -> Result<()> {
        for (what, u) in [
            ("input", &self.before),
            ("input after the start", &self.after),
        ] {
            check_len(what, u.len(), nu)?;
            for (i, &v) in u.iter().enumerate() {
                check_finite(|| format!("component {} of the {what}", i + 1), v)?;
            }
        }
        check_finite(|| "the start time of the input".into(), self.start)?;
        if self.shape == Input::Impulse && !self.is_constant() {
            return Err(LtiError::invalid(
                "an impulse cannot be simulated by integration: use a short pulse (a step up \
                 and a step down) or an initial state",
            ));
        }
        Ok(())
    }
}
