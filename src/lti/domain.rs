//! The domain of a model: continuous time (s) or discrete time (z) with a sampling period.
//!
//! Every model type — [`TransferFunction`](crate::TransferFunction),
//! [`StateSpace`](crate::StateSpace) and the factored core
//! (`analysis::Factored`) — carries its [`Domain`], and every analysis asks
//! it instead of being copied for z: stability is decided against the imaginary axis or the
//! unit circle, the dc gain is G(0) or G(1), a frequency ω is s = jω or z = e^(jωT), a
//! response is a closed form in t or a sequence in k.

use crate::error::{LtiError, Result};
use crate::fmt::fmt_num;

/// Continuous time (the Laplace variable s) or discrete time (the z-transform) with the
/// sampling period `dt` in seconds.
///
/// ```
/// use ltikit::lti::Domain;
/// let d = Domain::discrete(0.1).unwrap();
/// assert_eq!(d.dt(), Some(0.1));
/// assert_eq!(d.variable(), "z");
/// assert_eq!(Domain::Continuous.variable(), "s");
/// assert!(Domain::discrete(0.0).is_err() && Domain::discrete(f64::NAN).is_err());
/// // models of different domains do not connect
/// assert!(d.join(Domain::Continuous, "series").is_err());
/// assert_eq!(d.join(d, "series").unwrap(), d);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Domain {
    /// Continuous time: G(s), ẋ = Ax + Bu.
    #[default]
    Continuous,
    /// Discrete time with sampling period `dt` > 0: G(z), x\[k+1\] = A x\[k\] + B u\[k\].
    Discrete {
        /// The sampling period in seconds (finite, > 0).
        dt: f64,
    },
}

impl Domain {
    /// Discrete time with sampling period `dt`. Errors unless `dt` is finite and > 0.
    pub fn discrete(dt: f64) -> Result<Domain> {
        if !dt.is_finite() || dt <= 0.0 {
            return Err(LtiError::InvalidInput(format!(
                "the sampling period dt must be a finite number > 0 (found {})",
                fmt_num(dt)
            )));
        }
        Ok(Domain::Discrete { dt })
    }

    /// From an optional sampling period: `None` is continuous time.
    pub fn from_dt(dt: Option<f64>) -> Result<Domain> {
        dt.map_or(Ok(Domain::Continuous), Domain::discrete)
    }

    /// The sampling period (`None` in continuous time).
    pub fn dt(&self) -> Option<f64> {
        match self {
            Domain::Continuous => None,
            Domain::Discrete { dt } => Some(*dt),
        }
    }

    /// True in discrete time.
    pub fn is_discrete(&self) -> bool {
        matches!(self, Domain::Discrete { .. })
    }

    /// The transform variable: "s" or "z".
    pub fn variable(&self) -> &'static str {
        if self.is_discrete() { "z" } else { "s" }
    }

    /// The domain of an interconnection of two models: theirs when equal, else an error that
    /// names the `operation` and both domains (a loop cannot mix sampling periods, nor a
    /// continuous and a discrete model).
    #[allow(clippy::float_cmp)] // equal periods are the same number
    pub fn join(self, other: Domain, operation: &str) -> Result<Domain> {
        match (self, other) {
            (Domain::Continuous, Domain::Continuous) => Ok(self),
            (Domain::Discrete { dt: a }, Domain::Discrete { dt: b }) if a == b => Ok(self),
            _ => Err(LtiError::InvalidInput(format!(
                "{operation}: cannot connect a {} model with a {} model",
                self.describe(),
                other.describe()
            ))),
        }
    }

    /// Errors in discrete time: `what` is available for continuous-time models only.
    pub fn require_continuous(&self, what: &str) -> Result<()> {
        match self {
            Domain::Continuous => Ok(()),
            Domain::Discrete { dt } => Err(LtiError::InvalidInput(format!(
                "{what} is for continuous-time models; this one is discrete (dt = {})",
                fmt_num(*dt)
            ))),
        }
    }

    /// Errors in continuous time: `what` is available for discrete-time models only.
    pub fn require_discrete(&self, what: &str) -> Result<f64> {
        match self {
            Domain::Continuous => Err(LtiError::InvalidInput(format!(
                "{what} is for discrete-time models; this one is continuous (give it a sampling period `dt`)"
            ))),
            Domain::Discrete { dt } => Ok(*dt),
        }
    }

    /// "continuous-time" or "discrete-time (dt = 0.1 s)".
    pub fn describe(&self) -> String {
        match self {
            Domain::Continuous => "continuous-time".into(),
            Domain::Discrete { dt } => format!("discrete-time (dt = {} s)", fmt_num(*dt)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_periods_are_named() {
        for dt in [0.0, -1.0, f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            let e = Domain::discrete(dt).unwrap_err().to_string();
            assert!(e.contains("sampling period"), "{e}");
        }
        let a = Domain::discrete(0.1).unwrap();
        let b = Domain::discrete(0.2).unwrap();
        let e = a.join(b, "feedback").unwrap_err().to_string();
        assert!(
            e.contains("0.1") && e.contains("0.2") && e.contains("feedback"),
            "{e}"
        );
        assert!(a.require_continuous("the Routh table").is_err());
        assert!(Domain::Continuous.require_discrete("d2c").is_err());
    }
}
