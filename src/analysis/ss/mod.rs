//! Analyses of state-space models as such (SISO or MIMO): time responses by exact
//! discretisation. (A SISO channel's poles, zeros and everything built on them go through the
//! factored core.)

pub mod time;

pub use time::{Hold, InputSignal, SsTimeResponse};
