//! Bode diagram: magnitude (dB) over phase (degrees) on a shared log-ω axis, with margins,
//! asymptotes and a legend for several plants.
//!
//! The data ([`series`]: one [`BodeSeries`] per plant) is laid out in two panels
//! ([`panels`]), drawn ([`diagram`]) with each series' margins marked ([`margins`]).

mod diagram;
mod margins;
mod panels;
mod series;

pub use diagram::bode_png;
pub use series::BodeSeries;
