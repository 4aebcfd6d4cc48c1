//! Gain and phase margins, bandwidth and resonance, found by root-finding on the analytic
//! G(jω).
//!
//! (Implementation in progress — the data types below are the interface.)

use serde::Serialize;

/// A frequency where |G(jω)| = 1, with the phase margin there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GainCrossing {
    /// Gain-crossover frequency (rad/s).
    pub w: f64,
    /// 180° + φ(ω), the phase margin at this crossing (degrees).
    pub phase_margin_deg: f64,
}

/// A frequency where φ(ω) = −180° (mod 360°), with the gain margin there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhaseCrossing {
    /// Phase-crossover frequency (rad/s).
    pub w: f64,
    /// 1/|G(jω)| (ratio).
    pub gain_margin: f64,
    /// −20·log₁₀|G(jω)| (dB).
    pub gain_margin_db: f64,
}

/// Stability margins, bandwidth and resonant peak. `None` means "infinite" for margins (no
/// crossing) and "not defined" for bandwidth and resonance.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Margins {
    /// Smallest gain margin over all phase crossings (ratio); `None` = infinite.
    pub gain_margin: Option<f64>,
    /// The same in dB.
    pub gain_margin_db: Option<f64>,
    /// Phase-crossover frequency of that gain margin (rad/s).
    pub phase_crossover: Option<f64>,
    /// Smallest phase margin over all gain crossings (degrees); `None` = infinite.
    pub phase_margin_deg: Option<f64>,
    /// Gain-crossover frequency of that phase margin (rad/s).
    pub gain_crossover: Option<f64>,
    /// Every gain crossing, by increasing ω.
    pub gain_crossings: Vec<GainCrossing>,
    /// Every phase crossing, by increasing ω.
    pub phase_crossings: Vec<PhaseCrossing>,
    /// First ω where |G| falls 3 dB below the dc gain (rad/s); `None` when the dc gain is 0 or
    /// infinite or |G| never falls that far.
    pub bandwidth: Option<f64>,
    /// Resonant peak M_r = max|G(jω)| / |G(0)| when the maximum is at ω > 0 (ratio).
    pub resonant_peak: Option<f64>,
    /// Resonant frequency ω_r (rad/s).
    pub resonant_frequency: Option<f64>,
}
