//! Analyses of SISO plants on their factored form: poles and zeros, stability, modes, partial
//! fractions and closed-form responses, exact time responses, step metrics, frequency
//! response, margins, Nyquist, asymptotes and automatic grids.
//!
//! A plant is factored once ([`Factored`], from [`crate::TransferFunction::factored`] or
//! [`Factored::from_zpk`]); every analysis is a method of the factored form, and the
//! [`crate::TransferFunction`] methods of the same names factor first.
//!
//! # Where to start
//! | you have | you want | call |
//! |---|---|---|
//! | coefficients, a plant file, a model | the factored form | [`crate::TransferFunction::factored`], [`crate::Plant::factored`], [`Factored::from_zpk`], [`Factored::from_state_space`] |
//! | a factored plant | the whole report (poles, zeros, stability, modes, step metrics) | [`Factored::analyze`] |
//! | | frequency response, margins, Nyquist, Bode asymptotes | [`Factored::freq_response`], [`Factored::margins`], [`Factored::nyquist`], [`Factored::bode_asymptotes`] |
//! | | time responses, closed forms | [`Factored::step_response`], [`Factored::response`], [`Factored::partial_fractions`] |
//! | | closed loops, root locus | [`ClosedLoop::new`], [`Factored::feedback`], [`Factored::root_locus`] |
//! | | stability with a dead time in the loop, roots at a delay | [`Factored::delay_stability`], [`Factored::closed_loop_delay_roots`] |
//! | a state-space model | its whole analysis (eigen structure, minimal realisation, zeros) | [`crate::StateSpace::analysis`] |
//! | | MIMO responses | [`crate::StateSpace::step_response_from`], [`crate::StateSpace::freq_response_mimo`] |
//! | a polynomial in z, a sampled loop | Jury table, exact unit-circle counts, stable gains | [`jury()`], [`jury_exact`], [`discrete_stable_gains`] |
//!
//! The numerical kernels underneath (`crate::numeric`) are building blocks; an analysis needs
//! none of them directly.

pub mod asymptotes;
pub mod closed_form;
pub mod closed_loop;
pub mod delay;
pub mod design;
pub mod discrete;
pub mod factored;
pub mod freq;
pub mod grid;
pub mod input;
pub mod jury;
pub mod laplace;
pub mod margins;
pub mod modes;
pub mod norms;
pub mod nyquist;
pub mod pfe;
pub mod point;
pub mod response;
pub mod rlocus;
pub mod routh;
pub mod ss;
pub mod stability;
pub mod step_info;
pub mod summary;
pub mod time;

pub use asymptotes::{BodeAsymptotes, CornerFrequency, bode_asymptotes};
pub use closed_form::{ClosedForm, ClosedFormTerm, SequenceForm, SequenceTerm};
pub use closed_loop::{ClosedLoop, InternalStability, LoopSystem, Peak, Robustness};
pub use delay::{
    CharacteristicRoot, CrossingDirection, DelayCrossing, DelayInterval, DelayRoots,
    DelayStability, DelayedClosedForm, DelayedResponse, MAX_DELAY_PIECES,
};
pub use factored::{
    Factored, Feedback, MAX_FACTORED_ORDER, NEAR_PAIR_REL, NearPair, PoleZero, StructurePath,
    factorizations_on_this_thread,
};
pub use freq::FrequencyResponse;
pub use grid::{TimeSpan, auto_frequency_grid, auto_time_grid, auto_time_span};
pub use input::Input;
pub use jury::{JuryTable, circle_crossings, discrete_stable_gains, jury, jury_exact};
pub use margins::{GainCrossing, Margins, PhaseCrossing};
pub use modes::{DampingClass, Mode, SecondOrder, modes, second_order};
pub use nyquist::{ContourPart, NyquistContour, NyquistPoint, nyquist_contour};
pub use pfe::{PartialFractions, PfTerm, partial_fractions};
pub use response::{Response, ResponseSamples};
pub use rlocus::{RootLocus, RootLocusOptions, root_locus};
pub use routh::{RouthEvent, RouthTable, axis_crossings, routh, stable_gains};
pub use ss::{DcGain, Hold, InputSignal, MimoFreqResponse, SsAnalysis, SsTimeResponse};
pub use stability::{HalfPlane, Stability, StabilityClass, half_plane};
pub use step_info::{MetricNote, StepInfo, StepInfoOptions};
pub use summary::Analysis;
pub use time::TimeResponse;
