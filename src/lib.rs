//! # ltikit
//!
//! Linear time-invariant input-output models from ODE coefficients.
//!
//! ## Conventions
//! - Polynomial coefficients are given in **descending** powers of s, as in MATLAB,
//!   python-control and ControlSystems.jl: `[1.0, 0.8, 4.0]` is s² + 0.8 s + 4.
//! - Frequencies are in rad/s, phases in degrees, magnitudes as ratios or in dB (20 log₁₀).
//! - Complex numbers in JSON are `[re, im]`; roots are listed with repetition.
#![deny(clippy::float_cmp)]
#![warn(missing_docs)]

pub mod analysis;
#[cfg(feature = "cli")]
pub mod cli;
pub mod error;
pub mod fmt;
pub mod limits;
pub mod lti;
pub mod nonlinear;
pub mod numeric;
#[cfg(feature = "plot")]
pub mod plot;
pub mod poly;

pub use error::{LtiError, Result};
pub use lti::{StateSpace, TransferFunction};
pub use poly::{MAX_ORDER, Poly, Root};

/// The README's Rust example, compiled and run as a doctest.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
