//! Exact time responses (zero-order-hold stepping with the matrix exponential).
//!
//! (Implementation in progress — the data type below is the interface.)

use serde::Serialize;

/// Samples of an output y(t). `t` is increasing and starts at or after 0.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TimeResponse {
    /// Times (s).
    pub t: Vec<f64>,
    /// y(t). For an impulse into a proper G with D ≠ 0 the D·δ(t) term is not included.
    pub y: Vec<f64>,
    /// The limit y(∞) when it exists and is finite (e.g. the step response of a BIBO-stable
    /// G is its dc gain).
    pub final_value: Option<f64>,
}
