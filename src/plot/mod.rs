//! Headless PNG plots: Bode, step (and impulse/ramp) responses, pole-zero map, Nyquist, and
//! generic x–y plots (time plots, phase portraits, bifurcation-style diagrams).
//!
//! Every function here only **reads** data computed elsewhere ([`FrequencyResponse`],
//! [`Margins`], [`TimeResponse`], [`StepInfo`], [`PoleZero`], [`NyquistContour`],
//! [`BodeAsymptotes`], plain point lists) and writes one PNG:
//!
//! - no display, no fontconfig, no system package: the font (Noto Sans) is compiled in and
//!   rasterised with `ab_glyph`; lines, markers and fills are drawn with anti-aliasing into an
//!   RGB buffer and clipped to the plot frame;
//! - text that does not fit is shrunk (the title, down to 60 %) or cut with an ellipsis
//!   (titles, axis titles, legend rows; legends with more rows than fit end with "… and n
//!   more"), in time linear in its length; text longer than [`MAX_TEXT_CHARS`] is an error;
//! - the file is written atomically (a temporary file in the same directory, then a rename),
//!   so an error never leaves a partial file behind;
//! - errors are [`LtiError::Plot`] (bad options, no data, text too long, data spanning more
//!   than f64 can subtract) or [`LtiError::Io`] (unwritable path).
//!
//! Conventions: frequencies in rad/s on a log axis labelled in decades, magnitudes in dB,
//! phases in degrees with ticks at multiples of 45° or 90°, times in seconds. Text accepts a
//! small markup: `^{…}` superscript, `_{…}` subscript, and `^` followed by a number (`s^2`).
//!
//! [`FrequencyResponse`]: crate::analysis::FrequencyResponse
//! [`Margins`]: crate::analysis::Margins
//! [`TimeResponse`]: crate::analysis::TimeResponse
//! [`StepInfo`]: crate::analysis::StepInfo
//! [`PoleZero`]: crate::analysis::PoleZero
//! [`NyquistContour`]: crate::analysis::NyquistContour
//! [`BodeAsymptotes`]: crate::analysis::BodeAsymptotes
//! [`LtiError::Plot`]: crate::error::LtiError::Plot
//! [`LtiError::Io`]: crate::error::LtiError::Io

mod axes;
mod bode;
mod bode_grid;
mod frame;
mod heatmap;
mod layout;
mod legend;
mod markup;
mod nyquist;
mod options;
pub(crate) mod output;
mod projection;
mod pzmap;
mod raster;
mod render;
mod rlocus;
mod sigma;
mod step;
mod style;
mod text;
mod xy;

pub use bode::{BodeSeries, bode_png};
pub use bode_grid::{BodeGrid, bode_grid_png};
pub use heatmap::{ColorMap, HeatMap, MAX_HEATMAP_CELLS, heatmap_png};
pub use nyquist::{NyquistSeries, nyquist_png};
pub use options::{MAX_PIXELS, MAX_SIDE, MAX_TEXT_CHARS, MIN_SIDE, PlotOptions, parse_size};
pub use projection::{Curve3, Point3, SpherePlot, View, sphere_png};
pub use pzmap::{PzMap, pzmap_png};
pub use rlocus::{RootLocusPlot, rlocus_png};
pub use sigma::sigma_png;
pub use step::{StepSeries, step_png};
pub use style::{Color, LineStyle, MarkerShape, PALETTE, series_color};
pub use xy::{
    Curve, Equilibrium, Marker, PhasePortrait, XyPlot, phase_portrait_png, time_plot_png, xy_png,
};
