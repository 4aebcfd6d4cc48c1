//! Dead time e^(−sT) in a loop: exact closed-loop time responses by the method of steps
//! ([`steps`]) and their step metrics ([`steps_info`]).

pub mod steps;
pub mod steps_info;

pub use steps::{DelayedClosedForm, DelayedResponse, MAX_DELAY_PIECES};
