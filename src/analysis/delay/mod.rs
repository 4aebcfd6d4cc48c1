//! Loops with a dead time: stability in the delay of D(s) + N(s)·e^(−sT), the closed loop of
//! a rational loop L = N/D with a delay T in negative unity feedback.
//!
//! | you want | call |
//! |---|---|
//! | for which delays the loop is stable (crossing frequencies, directions, intervals, critical delay) | [`Factored::delay_stability`](crate::analysis::Factored::delay_stability) |
//! | the unstable roots at one delay | [`DelayStability::unstable_roots_at`], [`DelayStability::is_stable_at`] |
//! | the rightmost characteristic roots at one delay | [`Factored::closed_loop_delay_roots`](crate::analysis::Factored::closed_loop_delay_roots) |
//! | an independent count by the delayed Nyquist criterion | [`Factored::delayed_nyquist_count`](crate::analysis::Factored::delayed_nyquist_count) |
//!
//! The delay is an argument here; nothing is stored on the loop.

mod pade;
mod parts;
mod roots;
mod stability;
mod winding;

pub use roots::{CharacteristicRoot, DelayRoots};
pub use stability::{
    CrossingDirection, DelayCrossing, DelayInterval, DelayStability, MAX_DELAY_EVENTS,
};
