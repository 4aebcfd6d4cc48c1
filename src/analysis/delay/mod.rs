//! Loops with a dead time: stability in the delay of D(s) + N(s)·e^(−sT), the closed loop of
//! a rational loop L = N/D with a delay T in negative unity feedback, and its exact time
//! responses by the method of steps ([`steps`]) with their step metrics ([`steps_info`]).
//!
//! | you want | call |
//! |---|---|
//! | for which delays the loop is stable (crossing frequencies, directions, intervals, critical delay) | [`Factored::delay_stability`](crate::analysis::Factored::delay_stability) |
//! | the unstable roots at one delay | [`DelayStability::unstable_roots_at`], [`DelayStability::is_stable_at`] |
//! | the rightmost characteristic roots at one delay | [`Factored::closed_loop_delay_roots`](crate::analysis::Factored::closed_loop_delay_roots) |
//! | an independent count by the delayed Nyquist criterion | [`Factored::delayed_nyquist_count`](crate::analysis::Factored::delayed_nyquist_count) |
//! | the closed-loop response, exact (method of steps) | [`Factored::delayed_feedback_response`](crate::analysis::Factored::delayed_feedback_response) |
//! | its step metrics over a horizon | [`Factored::delayed_step_info`](crate::analysis::Factored::delayed_step_info) |
//! | the response over many delays (a delay short against the dynamics) | the same calls: beyond [`CLOSED_FORM_PIECES`] delays they march the delay equation ([`march`], [`DelayMarch`]) |
//!
//! The delay is an argument here; nothing is stored on the loop. D and N are the reduced
//! poles (D monic) and the reduced zeros with the gain of the factored loop; modes cancelled
//! in L are outside Δ and reported (`hidden_modes`).
//!
//! # How
//! The number of characteristic roots in the open right half plane changes only when a pair
//! crosses the imaginary axis at ±jω_c. There |D(jω_c)| = |N(jω_c)|: ω_c² is a positive root
//! of W(x) = |D(jω)|² − |N(jω)|² (x = ω², a polynomial from the factors, each root polished
//! on ln|D(jω)| − ln|N(jω)|), and e^(−jω_c·T) = −D(jω_c)/N(jω_c) fixes the delays
//! T_k = (θ + 2πk)/ω_c, θ = arg(−L(jω_c)) ∈ [0, 2π). The pair moves right as T grows where
//! W′(ω_c²) > 0 and left where W′ < 0 (Cooke & van den Driessche, 1986: sign Re ds/dT =
//! sign W′); a multiple root of W is a tangency, reported and not counted. The count at T is
//! the count of D + N at T = 0 plus ±2 per crossing delay passed.
//!
//! A bi-proper L makes Δ of neutral type: analysed when |L(∞)| < 1, refused when ≥ 1 (then
//! roots lie in, or approach, the right half plane for every T > 0).

mod checks;
pub mod march;
mod parts;
mod pieces;
mod roots;
mod stability;
pub mod steps;
pub mod steps_info;
mod winding;

pub use march::{DelayMarch, MAX_MARCH_INTERVALS, MAX_MARCH_NODES};
pub use roots::{CharacteristicRoot, DelayRoots};
pub use stability::{
    CrossingDirection, DelayCrossing, DelayInterval, DelayStability, MAX_DELAY_EVENTS,
};
pub use steps::{
    CLOSED_FORM_PIECES, CROSS_CHECK_PIECES, DelayMethod, DelayedClosedForm, DelayedResponse,
    MAX_DELAY_PIECES,
};
