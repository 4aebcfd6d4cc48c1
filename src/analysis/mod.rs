//! Analyses of transfer functions: poles and zeros, stability, modes, partial fractions and
//! closed-form responses, exact time responses, step metrics, frequency response, margins.

pub mod asymptotes;
pub mod closed_form;
pub mod freq;
pub mod grid;
pub mod input;
pub mod laplace;
pub mod margins;
pub mod modes;
pub mod nyquist;
pub mod pfe;
pub mod pz;
pub mod stability;
pub mod step_info;
pub mod summary;
pub mod time;

pub use asymptotes::{BodeAsymptotes, CornerFrequency, bode_asymptotes};
pub use closed_form::{ClosedForm, ClosedFormTerm};
pub use freq::FrequencyResponse;
pub use grid::{TimeSpan, auto_frequency_grid, auto_time_grid, auto_time_span};
pub use input::Input;
pub use laplace::{Response, ResponseSamples};
pub use margins::{GainCrossing, Margins, PhaseCrossing};
pub use modes::{DampingClass, Mode, SecondOrder, modes, second_order};
pub use nyquist::{ContourPart, NyquistContour, NyquistPoint, nyquist_contour};
pub use pfe::{PartialFractions, PfTerm, partial_fractions};
pub use pz::PoleZero;
pub use stability::{HalfPlane, Stability, StabilityClass, half_plane};
pub use step_info::StepInfo;
pub use summary::Analysis;
pub use time::TimeResponse;
