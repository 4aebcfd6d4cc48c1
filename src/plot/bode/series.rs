//! The data of a Bode diagram: one [`BodeSeries`] per plant (response, label, margins,
//! asymptotes, colour), its checks, and each series' colour and legend name.

use crate::analysis::{BodeAsymptotes, FrequencyResponse, Margins};
use crate::error::{LtiError, Result};
use crate::plot::options::check_label;
use crate::plot::raster::Color;
use crate::plot::style::series_color;

/// One plant on a Bode diagram.
///
/// ```
/// use ltikit::analysis::FrequencyResponse;
/// use ltikit::plot::BodeSeries;
/// let fr = FrequencyResponse { w: vec![0.1, 1.0], magnitude: vec![1.0, 0.7], magnitude_db: vec![0.0, -3.0], phase_deg: vec![-6.0, -45.0] };
/// let s = BodeSeries::new(&fr).label("1/(s + 1)");
/// assert_eq!(s.label.as_deref(), Some("1/(s + 1)"));
/// ```
#[derive(Debug, Clone, Copy)]
pub struct BodeSeries<'a> {
    /// The frequency response (ω, dB, phase).
    pub response: &'a FrequencyResponse,
    /// Legend text (the transfer function, a name).
    pub label: Option<&'a str>,
    /// Margins to mark: crossover lines and values.
    pub margins: Option<&'a Margins>,
    /// Straight-line asymptotes to draw dashed.
    pub asymptotes: Option<&'a BodeAsymptotes>,
    /// Colour; `None` takes the palette colour of the series' position.
    pub color: Option<Color>,
    /// The Nyquist frequency π/T of a discrete-time plant (rad/s): marked by a vertical line
    /// labelled "π/T", where the response ends. `None` for a continuous plant.
    pub nyquist_frequency: Option<f64>,
}

impl<'a> BodeSeries<'a> {
    /// A series with only the response.
    pub fn new(response: &'a FrequencyResponse) -> Self {
        BodeSeries {
            response,
            label: None,
            margins: None,
            asymptotes: None,
            color: None,
            nyquist_frequency: None,
        }
    }

    /// Sets the legend label.
    pub fn label(mut self, label: &'a str) -> Self {
        self.label = Some(label);
        self
    }

    /// Marks these margins.
    pub fn margins(mut self, margins: &'a Margins) -> Self {
        self.margins = Some(margins);
        self
    }

    /// Draws these asymptotes.
    pub fn asymptotes(mut self, asymptotes: &'a BodeAsymptotes) -> Self {
        self.asymptotes = Some(asymptotes);
        self
    }

    /// Sets the colour.
    pub fn color(mut self, color: Color) -> Self {
        self.color = Some(color);
        self
    }

    /// Marks the Nyquist frequency π/T of a discrete-time plant with period `dt`.
    ///
    /// ```
    /// use ltikit::analysis::FrequencyResponse;
    /// use ltikit::plot::BodeSeries;
    /// let fr = FrequencyResponse { w: vec![0.1, 1.0], magnitude: vec![1.0, 0.7], magnitude_db: vec![0.0, -3.0], phase_deg: vec![-6.0, -45.0] };
    /// let s = BodeSeries::new(&fr).sampling_period(0.1);
    /// assert!((s.nyquist_frequency.unwrap() - std::f64::consts::PI / 0.1).abs() < 1e-12);
    /// ```
    pub fn sampling_period(mut self, dt: f64) -> Self {
        self.nyquist_frequency = Some(std::f64::consts::PI / dt);
        self
    }
}

/// The colour of series `k`: its own, or the palette's.
pub(super) fn color_of(series: &[BodeSeries], k: usize) -> Color {
    series[k].color.unwrap_or_else(|| series_color(k))
}

/// The name of series `k` in legends: its label or "G1", "G2", ….
pub(super) fn name_of(s: &BodeSeries, k: usize) -> String {
    s.label
        .map(str::to_string)
        .unwrap_or_else(|| format!("G{}", k + 1))
}

/// Checks the series of a Bode diagram: at least one, matching lengths, two finite points
/// with ω > 0 each, labels within [`MAX_TEXT_CHARS`](crate::plot::MAX_TEXT_CHARS).
pub(super) fn check(series: &[BodeSeries]) -> Result<()> {
    if series.is_empty() {
        return Err(LtiError::Plot(
            "Bode plot: no frequency response given".into(),
        ));
    }
    for (k, s) in series.iter().enumerate() {
        check_label(k, s.label)?;
        let r = s.response;
        let n = r.w.len();
        if r.magnitude_db.len() != n || r.phase_deg.len() != n {
            return Err(LtiError::Plot(format!(
                "Bode plot: series {}: {} frequencies but {} magnitudes and {} phases",
                k + 1,
                n,
                r.magnitude_db.len(),
                r.phase_deg.len()
            )));
        }
        let good = (0..n)
            .filter(|&i| {
                r.w[i] > 0.0
                    && r.w[i].is_finite()
                    && r.magnitude_db[i].is_finite()
                    && r.phase_deg[i].is_finite()
            })
            .count();
        if good < 2 {
            return Err(LtiError::Plot(format!(
                "Bode plot: series {} has fewer than two finite points with ω > 0",
                k + 1
            )));
        }
        if let Some(w) = s.nyquist_frequency
            && !(w.is_finite() && w > 0.0)
        {
            return Err(LtiError::Plot(format!(
                "Bode plot: series {}: the Nyquist frequency must be finite and > 0",
                k + 1
            )));
        }
    }
    Ok(())
}
