//! The exact path's budget: beyond these sizes it is not taken, and the numerical path runs
//! and says why.

use crate::error::{LtiError, Result};

/// Highest degree the exact path takes.
pub const MAX_EXACT_DEGREE: usize = 100;

/// Largest coefficient (in bits) of the primitive integer form of an exact polynomial: about
/// 1200 decimal digits.
pub const MAX_EXACT_BITS: usize = 4096;

/// Largest product degree × coefficient bits: the subresultant, Sturm and certification
/// steps grow with both (a degree-49 polynomial of 2000-bit coefficients — decimals spanning
/// 1e±300 — took 11.5 s; degree 20 at 2000 bits 0.05 s). Beyond it the numerical path runs
/// and says so.
pub const MAX_EXACT_WORK: usize = 40_000;

/// The budget error.
pub(crate) fn beyond(reason: impl Into<String>) -> LtiError {
    LtiError::BeyondExactBudget {
        reason: reason.into(),
    }
}

/// A polynomial of degree `degree` whose primitive integer form has coefficients of at most
/// `bits` bits is within the budget (see [`super::qpoly::ExactPoly::check_budget`]).
pub(crate) fn check_sizes(degree: usize, bits: usize) -> Result<()> {
    if degree > MAX_EXACT_DEGREE {
        return Err(beyond(format!(
            "degree {degree} exceeds {MAX_EXACT_DEGREE}"
        )));
    }
    if bits > MAX_EXACT_BITS {
        return Err(beyond(format!(
            "coefficients of {bits} bits exceed {MAX_EXACT_BITS} bits"
        )));
    }
    if degree.saturating_mul(bits) > MAX_EXACT_WORK {
        return Err(beyond(format!(
            "degree {degree} × {bits}-bit coefficients exceeds {MAX_EXACT_WORK}"
        )));
    }
    Ok(())
}
