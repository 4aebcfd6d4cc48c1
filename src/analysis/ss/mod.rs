//! Analyses of state-space models as such (SISO or MIMO): time responses by exact
//! discretisation ([`time`]), the analysis of the whole model ([`report`]: eigen structure,
//! controllability, minimal realisation, zeros, dc gains, stability, modes) and the MIMO
//! frequency response ([`freq`], each channel through the factored core's one frequency
//! engine). (A SISO channel's poles, zeros and everything built on them go through the
//! factored core.)

pub(crate) mod block_march;
pub mod freq;
pub mod modal_time;
pub mod report;
pub mod time;

pub use freq::MimoFreqResponse;
pub use report::{DcGain, MAX_ANALYSIS_STATES, SsAnalysis, SsEigenvalue, SsMode, StaircaseRank};
pub use time::{Hold, InputSignal, SsTimeResponse};
