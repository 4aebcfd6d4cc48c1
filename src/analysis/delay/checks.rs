//! The argument checks of the delayed closed loop, shared by the method of steps
//! ([`super::steps`]) and the collocation march ([`super::march`]) — a leaf both import.

use crate::analysis::factored::Factored;
use crate::analysis::input::Input;
use crate::error::{LtiError, Result, check_finite};

/// The checks shared by the closed form and the march: a continuous, proper loop, a delay
/// > 0, a finite horizon ≥ 0, a valid input.
pub(crate) fn check_loop(l: &Factored, delay: f64, input: &Input, horizon: f64) -> Result<()> {
    l.domain().require_continuous(
        "the delayed closed loop by the method of steps (a sampled loop's delay is a power of z)",
    )?;
    check_delay(delay)?;
    check_finite(|| "the horizon".into(), horizon)?;
    if horizon < 0.0 {
        return Err(LtiError::InvalidTime {
            value: horizon,
            reason: "the horizon must be ≥ 0".into(),
        });
    }
    input.validate()?;
    l.require_proper("the delayed closed loop", false)
}

/// The delay must be a finite number > 0.
pub(crate) fn check_delay(delay: f64) -> Result<()> {
    check_finite(|| "the delay".into(), delay)?;
    if delay <= 0.0 {
        return Err(LtiError::InvalidParameter {
            name: "delay".into(),
            value: delay,
            reason: "a dead time must be > 0 (without delay the closed loop is rational: \
                     `Factored::feedback`)"
                .into(),
        });
    }
    Ok(())
}
