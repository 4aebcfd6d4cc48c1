//! The integrator's options (`odeset` in MATLAB) and their checks.

use serde::Serialize;

use crate::error::{LtiError, Result};
use crate::numeric::tol::EPS;

/// Smallest relative tolerance accepted (100·eps, as MATLAB's `ode45` clamps it).
pub const MIN_RTOL: f64 = 100.0 * EPS;

/// Options of the integrator (`odeset` in MATLAB). Build with `..Default::default()`.
///
/// ```
/// use ltikit::numeric::rk45::Rk45Options;
/// let o = Rk45Options { rtol: 1e-6, ..Default::default() };
/// assert!(o.validate().is_ok());
/// assert!(Rk45Options { rtol: -1.0, ..o }.validate().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Rk45Options {
    /// Relative tolerance (default 1e-9; at least [`MIN_RTOL`]).
    pub rtol: f64,
    /// Absolute tolerance (default 1e-12; ≥ 0).
    pub atol: f64,
    /// Maximum number of attempted steps, accepted plus rejected (default 1 000 000).
    pub max_steps: usize,
    /// First step size; `None` chooses it from the derivatives (Hairer's `hinit`).
    pub initial_step: Option<f64>,
    /// Largest step size; `None` means unlimited.
    pub max_step: Option<f64>,
}

impl Default for Rk45Options {
    fn default() -> Self {
        Rk45Options {
            rtol: 1e-9,
            atol: 1e-12,
            max_steps: 1_000_000,
            initial_step: None,
            max_step: None,
        }
    }
}

impl Rk45Options {
    /// Checks every option, naming the first bad one.
    pub fn validate(&self) -> Result<()> {
        let bad = |name: &str, value: f64, reason: &str| {
            Err(LtiError::InvalidParameter {
                name: name.into(),
                value,
                reason: reason.into(),
            })
        };
        if !(self.rtol.is_finite() && self.rtol >= MIN_RTOL && self.rtol < 1.0) {
            return bad(
                "rtol",
                self.rtol,
                "the relative tolerance must lie in [2.2e-14, 1)",
            );
        }
        if !(self.atol.is_finite() && self.atol >= 0.0) {
            return bad(
                "atol",
                self.atol,
                "the absolute tolerance must be finite and ≥ 0",
            );
        }
        if self.max_steps == 0 {
            return bad("max_steps", 0.0, "at least one step must be allowed");
        }
        if let Some(h) = self.initial_step.filter(|h| !(h.is_finite() && *h > 0.0)) {
            return bad("initial_step", h, "the initial step must be finite and > 0");
        }
        if let Some(h) = self.max_step.filter(|h| !(h.is_finite() && *h > 0.0)) {
            return bad("max_step", h, "the maximum step must be finite and > 0");
        }
        Ok(())
    }
}
