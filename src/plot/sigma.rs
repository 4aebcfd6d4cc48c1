//! The sigma plot: the singular values σ₁ ≥ σ₂ ≥ … of G(jω) in dB against ω on a log axis,
//! the certified peak marked.

use std::path::Path;

use super::options::PlotOptions;
use super::style::{MarkerShape, series_color};
use super::xy::{Curve, Marker, XyPlot, xy_png};
use crate::analysis::norms::{PeakGain, SigmaResponse};
use crate::error::Result;

/// Writes the sigma plot of `r` (one curve per singular value) with the peak of `peak`
/// marked when it is finite and inside the frequency range; `label` names the model in the
/// default title.
///
/// Errors: no positive frequency with a non-zero singular value, those of [`xy_png`].
///
/// ```no_run
/// use nalgebra::DMatrix;
/// use ltikit::StateSpace;
/// use ltikit::analysis::norms::{hinf_norm, sigma_grid, sigma_response};
/// use ltikit::plot::{PlotOptions, sigma_png};
/// let ss = StateSpace::new(
///     DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -2.0]),
///     DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 2.0]),
///     DMatrix::identity(2, 2),
///     DMatrix::zeros(2, 2),
/// ).unwrap();
/// let r = sigma_response(&ss, &sigma_grid(&ss, 400).unwrap()).unwrap();
/// let peak = hinf_norm(&ss).unwrap();
/// sigma_png("/tmp/sigma.png", &r, Some(&peak), "two lags", &PlotOptions::default()).unwrap();
/// ```
pub fn sigma_png(
    path: impl AsRef<Path>,
    r: &SigmaResponse,
    peak: Option<&PeakGain>,
    label: &str,
    opts: &PlotOptions,
) -> Result<()> {
    let k = r.sigma.first().map_or(0, Vec::len);
    let db = |x: f64| 20.0 * x.log10();
    let curves: Vec<Curve> = (0..k)
        .map(|i| {
            let pts =
                r.w.iter()
                    .zip(&r.sigma)
                    .filter(|(w, _)| **w > 0.0)
                    .map(|(&w, s)| (w, db(s[i])));
            Curve::new(pts)
                .label(format!("σ{}", i + 1))
                .color(series_color(i))
        })
        .collect();
    let (lo, hi) = (
        r.w.iter()
            .copied()
            .filter(|w| *w > 0.0)
            .fold(f64::INFINITY, f64::min),
        r.w.iter().copied().fold(0.0, f64::max),
    );
    let mut markers = Vec::new();
    let mut notes = Vec::new();
    if let Some(p) = peak.filter(|p| p.infinite.is_none() && p.lower > 0.0) {
        let text = format!(
            "peak {} ({} dB)",
            crate::fmt::fmt_sig(p.lower, 8),
            crate::fmt::fmt_sig(db(p.lower), 5)
        );
        if p.w >= lo && p.w <= hi {
            markers.push(Marker::new((p.w, db(p.lower)), MarkerShape::Disc).label(text));
        } else {
            notes.push(format!("{text} at ω = {}", crate::fmt::fmt_num(p.w)));
        }
    }
    let plot = XyPlot {
        curves,
        markers,
        x_label: "ω (rad/s)".into(),
        y_label: "singular values (dB)".into(),
        notes,
        title: format!("Singular values of {label}"),
        x_log: true,
        ..Default::default()
    };
    xy_png(path, &plot, opts)
}
