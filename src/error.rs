//! The one error type of the library.
//!
//! Every fallible public function returns [`Result<T>`]. Variants carry the offending numbers so
//! that the message names the problem ("coefficient 2 of the denominator is NaN", "order 300
//! exceeds the supported maximum 200"). The binary wraps these in `anyhow` for context; the
//! library never panics on user-reachable input.

use thiserror::Error;

/// Result alias used throughout the crate.
pub type Result<T> = std::result::Result<T, LtiError>;

/// Everything that can go wrong in ltikit.
///
/// ```
/// use ltikit::{LtiError, TransferFunction};
/// let err = TransferFunction::from_descending(&[1.0], &[0.0, 0.0]).unwrap_err();
/// assert!(matches!(err, LtiError::ZeroPolynomial { .. }));
/// assert_eq!(err.to_string(), "the denominator is the zero polynomial");
/// ```
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum LtiError {
    /// A coefficient, parameter or time value is NaN or infinite.
    #[error("{what} is {value} (must be a finite number)")]
    NonFinite {
        /// Which quantity, e.g. "coefficient 2 of the denominator".
        what: String,
        /// The offending value.
        value: f64,
    },
    /// A polynomial was given with no coefficients.
    #[error("the {what} has no coefficients")]
    EmptyPolynomial {
        /// "numerator", "denominator", …
        what: String,
    },
    /// A polynomial that must not vanish is identically zero.
    #[error("the {what} is the zero polynomial")]
    ZeroPolynomial {
        /// "numerator", "denominator", …
        what: String,
    },
    /// The order is beyond what the root finder supports.
    #[error("order {order} exceeds the supported maximum {max}")]
    OrderTooHigh {
        /// Requested order.
        order: usize,
        /// Supported maximum (the polynomial limit `MAX_ORDER`, or the factored limit).
        max: usize,
    },
    /// The coefficients span a range that overflows once the polynomial is made monic.
    #[error(
        "the {what} cannot be scaled: coefficient ratio {ratio:e} overflows (leading coefficient {leading:e})"
    )]
    BadScaling {
        /// "numerator", "denominator", …
        what: String,
        /// The ratio that overflowed.
        ratio: f64,
        /// The leading coefficient.
        leading: f64,
    },
    /// An operation needs a proper (or strictly proper) transfer function.
    #[error(
        "{operation} needs a {required} transfer function, but the numerator degree {num_degree} exceeds {limit} (denominator degree {den_degree})"
    )]
    Improper {
        /// What was attempted ("step response", "state-space realisation", …).
        operation: String,
        /// "proper" or "strictly proper".
        required: String,
        /// Degree of the numerator.
        num_degree: usize,
        /// Degree of the denominator.
        den_degree: usize,
        /// The largest numerator degree allowed.
        limit: usize,
    },
    /// A parameter is outside its valid range.
    #[error(
        "parameter {} = {} is invalid: {reason}",
        abbreviate(.name),
        number(*.value)
    )]
    InvalidParameter {
        /// Parameter name.
        name: String,
        /// Its value.
        value: f64,
        /// Why it is rejected.
        reason: String,
    },
    /// An argument has the wrong shape or content (dimensions, empty lists, …).
    #[error("{0}")]
    InvalidInput(String),
    /// A named model does not exist (the name is shown abbreviated, as every echoed text).
    #[error("unknown model '{}' (known: {known})", abbreviate(.name))]
    UnknownModel {
        /// The requested name.
        name: String,
        /// Comma-separated list of known names.
        known: String,
    },
    /// A model has no parameter of this name.
    #[error(
        "model '{}' has no parameter '{}' (parameters: {known})",
        abbreviate(.model),
        abbreviate(.name)
    )]
    UnknownParameter {
        /// Model name.
        model: String,
        /// Requested parameter.
        name: String,
        /// Comma-separated list of known parameters.
        known: String,
    },
    /// A time value is outside the valid range (negative, or not increasing).
    #[error("time {} is invalid: {reason}", number(*.value))]
    InvalidTime {
        /// The time.
        value: f64,
        /// Why.
        reason: String,
    },
    /// An iterative algorithm did not converge.
    #[error("{what} did not converge after {iterations} iterations")]
    NoConvergence {
        /// Which algorithm.
        what: String,
        /// Iterations spent.
        iterations: usize,
    },
    /// A quantity is not defined for this system (e.g. step metrics of an unstable plant).
    #[error("{what} is undefined: {reason}")]
    Undefined {
        /// The quantity.
        what: String,
        /// Why.
        reason: String,
    },
    /// A simulation left the finite numbers.
    #[error("simulation diverged at t = {t} (|x| = {norm:e})")]
    Diverged {
        /// Time at which the state became too large or non-finite.
        t: f64,
        /// Size of the state then.
        norm: f64,
    },
    /// A simulation needed more steps than allowed.
    #[error("simulation stopped after {steps} steps at t = {t} (step limit reached)")]
    StepLimit {
        /// Steps taken.
        steps: usize,
        /// Time reached.
        t: f64,
    },
    /// Reading or writing a file failed.
    #[error("{}: {message}", abbreviate(.path))]
    Io {
        /// The file.
        path: String,
        /// The operating system's or parser's message.
        message: String,
    },
    /// A plant file or a batch line does not hold a valid plant record: where (the file, the
    /// line and column, or a batch line's column) and what, in plain words, naming the key.
    #[error("{}{message}", if .location.is_empty() { String::new() } else { format!("{location}: ") })]
    BadRecord {
        /// "plant.toml, line 3, column 7" (file names abbreviated); empty when unknown.
        location: String,
        /// What is wrong ("`den` must be a list of numbers or a string of numbers (found
        /// true)").
        message: String,
    },
    /// A plot could not be drawn.
    #[error("plot: {0}")]
    Plot(String),
    /// A result exceeds the largest f64 (≈ 1.8e308).
    #[error("{what} overflows the largest floating-point number (≈ 1.8e308){reason}")]
    Overflow {
        /// What overflows ("the matrix exponential", "the response at t = 2 s").
        what: String,
        /// Why, when known (", the unstable mode at s = 3 grows as e^(3t)"), with a leading
        /// separator, or empty.
        reason: String,
    },
    /// Exact input is too large or too ill-separated for the exact path (degree, coefficient
    /// size, or roots closer than its refinement separates); the caller falls back to the
    /// numerical path.
    #[error("beyond the exact budget: {reason}")]
    BeyondExactBudget {
        /// Which limit was hit, with the numbers.
        reason: String,
    },
    /// A size the user controls exceeds its limit ([`crate::limits`]); checked before
    /// anything is allocated.
    #[error("{field}: {value} exceeds the limit of {} ({limit})", crate::fmt::amount(*.max, .unit))]
    LimitExceeded {
        /// The field, in backquotes (`` `points` ``), or the product that is limited.
        field: String,
        /// The requested size.
        value: u128,
        /// The limit.
        max: u64,
        /// What is counted ("sample points", "px a side").
        unit: String,
        /// The limit's name in [`crate::limits::LIMITS`] (`MAX_POINTS`).
        limit: String,
    },
    /// A discrete-time pole has no continuous-time preimage under a conversion (`d2c`): e^(sT)
    /// is never 0 nor a negative real number (ZOH), and no finite s maps to z = −1 (Tustin).
    #[error(
        "{method}: the pole z = {} has no continuous-time preimage ({reason})",
        complex_number(*.re, *.im)
    )]
    NoPreimage {
        /// The conversion ("d2c (zoh)").
        method: String,
        /// Real part of the pole.
        re: f64,
        /// Imaginary part of the pole.
        im: f64,
        /// Why ("e^(sT) is never 0 nor a negative real number").
        reason: String,
    },
    /// A linear matrix equation (Sylvester, Lyapunov) is singular, or a Riccati equation has
    /// no stabilising solution: the equation and why, naming the eigenvalues responsible.
    #[error("{equation}: {reason}")]
    SingularEquation {
        /// The equation ("the Lyapunov equation A·X + X·Aᵀ + Q = 0").
        equation: String,
        /// Why, with the numbers.
        reason: String,
    },
    /// A number (or a list, or a `NAME=VALUE` pair) could not be read from text.
    #[error("{what}: '{token}' {reason}")]
    BadNumber {
        /// Where it was read: the field in backquotes (`` `den` ``, `` `param` K ``), or a
        /// description ("coefficient 2 of the numerator").
        what: String,
        /// The offending text, abbreviated to [`TOKEN_SHOWN`] characters.
        token: String,
        /// Why ("is not a number", …).
        reason: String,
    },
}

/// A number as an error message shows it: as Rust prints it (`0.4`, `-1`, `NaN`), or in
/// exponent form when that is shorter than 300 digits of `1e300`.
///
/// ```
/// use ltikit::error::number;
/// assert_eq!(number(0.4), "0.4");
/// assert_eq!(number(1e300), "1e300");
/// assert_eq!(number(-2.5e-200), "-2.5e-200");
/// ```
pub fn number(x: f64) -> String {
    let plain = x.to_string();
    if plain.len() > 24 {
        format!("{x:e}")
    } else {
        plain
    }
}

/// A complex number as an error message shows it: `-0.5`, `0.3 + 0.4j`, `-1 - 2j`.
///
/// ```
/// use ltikit::error::complex_number;
/// assert_eq!(complex_number(-0.5, 0.0), "-0.5");
/// assert_eq!(complex_number(0.3, -0.4), "0.3 - 0.4j");
/// assert_eq!(complex_number(-0.0, 0.0), "0");
/// ```
pub fn complex_number(re: f64, im: f64) -> String {
    // a zero's sign is rounding, not information
    let re = if re == 0.0 { 0.0 } else { re };
    if im == 0.0 {
        return number(re);
    }
    let sign = if im < 0.0 { "-" } else { "+" };
    format!("{} {sign} {}j", number(re), number(im.abs()))
}

/// The number of characters of an offending input token shown in an error message.
pub const TOKEN_SHOWN: usize = 80;

/// `text` cut to [`TOKEN_SHOWN`] characters (with "…" and the full length when cut), so an
/// error never echoes a huge input.
///
/// ```
/// use ltikit::error::abbreviate;
/// assert_eq!(abbreviate("1e5x"), "1e5x");
/// let long = "9".repeat(1000);
/// let a = abbreviate(&long);
/// assert!(a.starts_with("9999") && a.ends_with("(1000 characters)"));
/// assert!(a.chars().count() < 110);
/// ```
pub fn abbreviate(text: &str) -> String {
    let n = text.chars().count();
    if n <= TOKEN_SHOWN {
        return text.to_string();
    }
    let head: String = text.chars().take(TOKEN_SHOWN).collect();
    format!("{head}… ({n} characters)")
}

impl LtiError {
    /// Shorthand for [`LtiError::InvalidInput`].
    pub fn invalid(msg: impl Into<String>) -> Self {
        LtiError::InvalidInput(msg.into())
    }

    /// Shorthand for [`LtiError::BadNumber`] (the token is abbreviated).
    pub fn bad_number(what: impl Into<String>, token: &str, reason: impl Into<String>) -> Self {
        LtiError::BadNumber {
            what: what.into(),
            token: abbreviate(token),
            reason: reason.into(),
        }
    }
}

/// Checks that `value` is finite, naming it `what` in the error.
pub(crate) fn check_finite(what: impl FnOnce() -> String, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(LtiError::NonFinite {
            what: what(),
            value,
        })
    }
}
