//! Analyses of transfer functions: poles and zeros, stability, modes, partial fractions and
//! closed-form responses, exact time responses, step metrics, frequency response, margins.

pub mod modes;
pub mod pz;
pub mod stability;

pub use modes::{DampingClass, Mode, SecondOrder, modes, second_order};
pub use pz::PoleZero;
pub use stability::{HalfPlane, Stability, StabilityClass, half_plane};
