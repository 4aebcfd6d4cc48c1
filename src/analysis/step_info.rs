//! Step-response metrics with MATLAB `stepinfo` definitions, computed exactly on the closed
//! form by root-finding.
//!
//! (Implementation in progress — the data type below is the interface.)

use serde::Serialize;

/// Step metrics (DESIGN §1.3). Times in seconds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StepInfo {
    /// Time from 10 % to 90 % of the final value.
    pub rise_time: f64,
    /// Last time |y − y∞| equals 2 % of |y∞|.
    pub settling_time: f64,
    /// (max y − y∞)/|y∞|·100, at least 0.
    pub overshoot_percent: f64,
    /// max |y|.
    pub peak: f64,
    /// First time the peak is reached.
    pub peak_time: f64,
    /// y∞ (the dc gain).
    pub steady_state: f64,
    /// When y first reaches 10 % of y∞ (start of the rise).
    pub rise_start: f64,
    /// When y first reaches 90 % of y∞ (end of the rise).
    pub rise_end: f64,
}
