//! Frequency response G(jω): magnitude, dB and continuous phase.
//!
//! (Implementation in progress — the data types below are the interface the plot module and
//! the CLI read.)

use serde::Serialize;

/// G(jω) sampled at the frequencies `w` (rad/s). All vectors have the same length.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrequencyResponse {
    /// Frequencies (rad/s), as requested.
    pub w: Vec<f64>,
    /// |G(jω)|.
    pub magnitude: Vec<f64>,
    /// 20·log₁₀|G(jω)| (dB); −∞ at an exact zero on the axis.
    pub magnitude_db: Vec<f64>,
    /// Phase in degrees, continuous in ω (DESIGN §1.3).
    pub phase_deg: Vec<f64>,
}
