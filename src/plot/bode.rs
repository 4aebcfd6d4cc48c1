//! Bode diagram: magnitude (dB) over phase (degrees) on a shared log-ω axis, with margins,
//! asymptotes and a legend for several plants.

use std::path::Path;

use super::axes::Axis;
use super::bode_margins::mark_margins;
use super::frame::Frame;
use super::layout::{
    bottom_margin, bounds, check_span, draw_title, left_margin, right_margin, tick_targets,
    top_margin,
};
use super::legend::{Corner, LegendEntry, draw_legend, sample_run};
use super::raster::Canvas;
use super::style::{LineStyle, Theme, series_color};
use super::{Color, PlotOptions, check_label, render};
use crate::analysis::{BodeAsymptotes, FrequencyResponse, Margins};
use crate::error::{LtiError, Result};

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
}

/// Linear interpolation of `ys` at `w` on log ω.
pub(super) fn interp_log(ws: &[f64], ys: &[f64], w: f64) -> Option<f64> {
    let x = w.log10();
    let k = ws.windows(2).position(|p| p[0] <= w && w <= p[1])?;
    let (a, b) = (ws[k].log10(), ws[k + 1].log10());
    let (ya, yb) = (ys[k], ys[k + 1]);
    if !(ya.is_finite() && yb.is_finite()) {
        return None;
    }
    Some(if b > a {
        ya + (yb - ya) * (x - a) / (b - a)
    } else {
        ya
    })
}

fn check(series: &[BodeSeries]) -> Result<()> {
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
    }
    Ok(())
}

/// Writes a Bode diagram of one or more plants.
///
/// The magnitude panel (dB) sits over the phase panel (degrees, ticks at multiples of 45° or
/// 90°); the shared ω axis (rad/s) is logarithmic with decade grid lines labelled 10^k. With
/// margins, the gain crossover ω_gc and phase crossover ω_pc are drawn as vertical lines, the
/// gain margin as a bar from |G(jω_pc)| up to 0 dB and the phase margin as a bar from φ(ω_gc)
/// to the −180° reference, with the values listed. Asymptotes are drawn dashed. Points that
/// are not finite (−∞ dB at a zero on the axis) break the curve.
///
/// Errors: no series, mismatched lengths, fewer than two finite points, bad options, a title
/// or label longer than [`MAX_TEXT_CHARS`](super::MAX_TEXT_CHARS) characters, an unwritable
/// path ([`LtiError::Plot`] / [`LtiError::Io`]); no file is left behind.
///
/// ```no_run
/// use ltikit::analysis::FrequencyResponse;
/// use ltikit::plot::{bode_png, BodeSeries, PlotOptions};
/// // 1/(s + 1) from its closed form.
/// let w: Vec<f64> = (0..=300).map(|k| 10f64.powf(-2.0 + k as f64 / 75.0)).collect();
/// let magnitude: Vec<f64> = w.iter().map(|w| 1.0 / (1.0 + w * w).sqrt()).collect();
/// let fr = FrequencyResponse {
///     magnitude_db: magnitude.iter().map(|m| 20.0 * m.log10()).collect(),
///     phase_deg: w.iter().map(|w| -w.atan().to_degrees()).collect(),
///     w,
///     magnitude,
/// };
/// bode_png("/tmp/bode.png", &[BodeSeries::new(&fr).label("1/(s + 1)")], &PlotOptions::default()).unwrap();
/// ```
pub fn bode_png(path: impl AsRef<Path>, series: &[BodeSeries], opts: &PlotOptions) -> Result<()> {
    check(series)?;
    let title = opts.title_or(|| match (series.len(), series[0].label) {
        (1, Some(l)) => format!("Bode diagram of G(s) = {l}"),
        _ => "Bode diagram".into(),
    });
    render(path.as_ref(), opts, |c, th| {
        draw(c, th, series, opts, title.as_deref())
    })
}

/// The colour of series `k`: its own, or the palette's.
fn color_of(series: &[BodeSeries], k: usize) -> Color {
    series[k].color.unwrap_or_else(|| series_color(k))
}

/// The name of series `k` in legends: its label or "G1", "G2", ….
pub(super) fn name_of(s: &BodeSeries, k: usize) -> String {
    s.label
        .map(str::to_string)
        .unwrap_or_else(|| format!("G{}", k + 1))
}

/// The data ranges of a Bode diagram.
#[derive(Debug, Clone, Copy)]
pub(super) struct Ranges {
    /// ω range (positive frequencies).
    pub w: (f64, f64),
    /// Magnitude range (dB), padded.
    pub mag: (f64, f64),
    /// Phase range (degrees).
    pub phase: (f64, f64),
}

impl Ranges {
    /// Whether ω lies inside the drawn frequency range.
    pub fn in_range(&self, w: f64) -> bool {
        w >= self.w.0 && w <= self.w.1
    }
}

/// Data ranges, including the margin bars and the asymptotes inside the ω range.
fn data_ranges(series: &[BodeSeries]) -> Result<Ranges> {
    let finite_w = |s: &BodeSeries| {
        s.response
            .w
            .iter()
            .copied()
            .filter(|w| *w > 0.0)
            .collect::<Vec<_>>()
    };
    let w = bounds(series.iter().flat_map(finite_w)).unwrap_or((0.1, 10.0));
    let in_range = |x: f64| x >= w.0 && x <= w.1;
    let mut mags: Vec<f64> = Vec::new();
    let mut phases: Vec<f64> = Vec::new();
    for s in series {
        let r = s.response;
        for i in 0..r.w.len() {
            if r.w[i] > 0.0 {
                mags.push(r.magnitude_db[i]);
                phases.push(r.phase_deg[i]);
            }
        }
        if let Some(m) = s.margins {
            if let (Some(w), Some(gm)) = (m.phase_crossover, m.gain_margin_db) {
                if in_range(w) && gm.is_finite() {
                    mags.extend([0.0, -gm]);
                }
            }
            if let (Some(w), Some(pm)) = (m.gain_crossover, m.phase_margin_deg) {
                if let Some(p) = interp_log(&r.w, &r.phase_deg, w).filter(|_| in_range(w)) {
                    phases.extend([p, p - pm]);
                    mags.push(0.0);
                }
            }
        }
        if let Some(a) = s.asymptotes {
            mags.extend(a.magnitude_db.iter().filter(|p| in_range(p.0)).map(|p| p.1));
            phases.extend(a.phase_deg.iter().filter(|p| in_range(p.0)).map(|p| p.1));
        }
    }
    let (mut mlo, mut mhi) = bounds(mags.iter().copied()).unwrap_or((-1.0, 1.0));
    // A notch at a zero on the axis would squash everything else: show at most 300 dB.
    mlo = mlo.max(mhi - 300.0);
    // A little room so that the curve does not run along the frame.
    let pad = 0.04 * (mhi - mlo).max(1.0);
    mlo -= pad;
    mhi += pad;
    let phase = bounds(phases.iter().copied()).unwrap_or((-1.0, 1.0));
    check_span("magnitudes (dB)", (mlo, mhi))?;
    check_span("phases (degrees)", phase)?;
    Ok(Ranges {
        w,
        mag: (mlo, mhi),
        phase,
    })
}

/// The magnitude panel over the phase panel, sharing the ω axis.
pub(super) struct Panels {
    pub mag: Frame,
    pub ph: Frame,
}

/// Layout: title, magnitude panel, small gap, phase panel, x labels.
fn layout_panels(c: &Canvas, th: &Theme, has_title: bool, r: &Ranges) -> Panels {
    let (cw, ch) = (f64::from(c.w), f64::from(c.h));
    let gap = 14.0 * th.s;
    let db_mults = [1.0, 2.0, 5.0, 10.0];
    let make = |w: f64, h_panel: f64| {
        let (nx, ny) = tick_targets(w, h_panel, th);
        let x = Axis::log(r.w.0, r.w.1, nx);
        let mag = Axis::linear_from(r.mag.0, r.mag.1, ny.max(3), false, &db_mults);
        let ph = Axis::degrees(r.phase.0, r.phase.1, ny.max(3));
        (x, mag, ph)
    };
    let top = top_margin(th, has_title, false);
    let mut axes = make(cw * 0.8, ch * 0.35);
    let mut frame = (0.0, 0.0, 0.0, 0.0);
    for _ in 0..2 {
        let l = left_margin(th, &axes.1, true).max(left_margin(th, &axes.2, true));
        let r = right_margin(th, &axes.0);
        let b = bottom_margin(th, &axes.0, true);
        let w = (cw - l - r).max(10.0);
        let h = ((ch - top - b - gap) / 2.0).max(10.0);
        frame = (l, w, h, b);
        axes = make(w, h);
    }
    let (l, w, h, _) = frame;
    let (x_axis, mag_axis, ph_axis) = axes;
    Panels {
        mag: Frame {
            x0: l,
            y0: top,
            x1: l + w,
            y1: top + h,
            x: x_axis.clone(),
            y: mag_axis,
        },
        ph: Frame {
            x0: l,
            y0: top + h + gap,
            x1: l + w,
            y1: top + 2.0 * h + gap,
            x: x_axis,
            y: ph_axis,
        },
    }
}

/// Grids and the 0 dB line.
fn draw_background(c: &mut Canvas, th: &Theme, p: &Panels, grid: bool) {
    if grid {
        p.mag.draw_grid(c, th);
        p.ph.draw_grid(c, th);
    }
    if p.mag.y.lo < 0.0 && p.mag.y.hi > 0.0 {
        let thin = (th.line * 0.6).max(1.0);
        p.mag
            .hline(c, 0.0, thin, Color(120, 120, 120), LineStyle::Solid);
    }
}

/// Asymptotes, dashed and lighter, under the curves.
fn draw_asymptotes(c: &mut Canvas, th: &Theme, series: &[BodeSeries], p: &Panels) {
    for (k, s) in series.iter().enumerate() {
        if let Some(a) = s.asymptotes {
            let col = color_of(series, k).lighten(0.25);
            p.mag.plot_line(
                c,
                a.magnitude_db.iter().copied(),
                th.line * 0.8,
                col,
                LineStyle::Dashed,
            );
            p.ph.plot_line(
                c,
                a.phase_deg.iter().copied(),
                th.line * 0.8,
                col,
                LineStyle::Dashed,
            );
        }
    }
}

/// The points (ω, y) with y = NaN (a break in the curve) where ω ≤ 0.
fn positive_w<'a>(w: &'a [f64], ys: &'a [f64]) -> impl Iterator<Item = (f64, f64)> + 'a {
    w.iter()
        .zip(ys)
        .map(|(&w, &y)| (w, if w > 0.0 { y } else { f64::NAN }))
}

/// Pixel points that legends should not hide.
pub(super) type Avoid = Vec<(f64, f64)>;

/// The magnitude and phase curves; returns the pixel points to keep legends off (magnitude,
/// phase).
fn draw_curves(c: &mut Canvas, th: &Theme, series: &[BodeSeries], p: &Panels) -> (Avoid, Avoid) {
    let mut avoid_mag = Vec::new();
    let mut avoid_ph = Vec::new();
    for (k, s) in series.iter().enumerate() {
        let r = s.response;
        for run in p.mag.clip_polyline(positive_w(&r.w, &r.magnitude_db)) {
            c.stroke(&run, th.line, color_of(series, k), &[]);
            avoid_mag.extend(sample_run(&run, 6.0));
        }
        for run in p.ph.clip_polyline(positive_w(&r.w, &r.phase_deg)) {
            c.stroke(&run, th.line, color_of(series, k), &[]);
            avoid_ph.extend(sample_run(&run, 6.0));
        }
    }
    (avoid_mag, avoid_ph)
}

/// Axis frames, ticks and titles of both panels.
fn draw_axes(c: &mut Canvas, th: &Theme, p: &Panels) -> Result<()> {
    p.mag.draw_axes(c, th, false, true)?;
    p.ph.draw_axes(c, th, true, true)?;
    p.mag
        .draw_axis_titles(c, th, None, Some("Magnitude (dB)"), th.pad)?;
    p.ph.draw_axis_titles(
        c,
        th,
        Some("Frequency ω (rad/s)"),
        Some("Phase (deg)"),
        th.pad,
    )
}

/// Legend (plants, asymptotes) in the magnitude panel; margin values in the phase panel.
fn draw_legends(
    c: &mut Canvas,
    th: &Theme,
    series: &[BodeSeries],
    p: &Panels,
    avoid: &(Avoid, Avoid),
    info: &[LegendEntry],
) -> Result<()> {
    let mut legend: Vec<LegendEntry> = Vec::new();
    if series.len() > 1 || series[0].asymptotes.is_some() {
        for (k, s) in series.iter().enumerate() {
            legend.push(LegendEntry::line(
                name_of(s, k),
                color_of(series, k),
                LineStyle::Solid,
            ));
        }
    }
    if series.iter().any(|s| s.asymptotes.is_some()) {
        legend.push(LegendEntry::line(
            "asymptotes",
            Color(110, 110, 110),
            LineStyle::Dashed,
        ));
    }
    let corners = [
        Corner::TopRight,
        Corner::BottomLeft,
        Corner::TopLeft,
        Corner::BottomRight,
    ];
    draw_legend(c, &p.mag, th, &legend, &avoid.0, &corners, &[])?;
    draw_legend(
        c,
        &p.ph,
        th,
        info,
        &avoid.1,
        &[
            Corner::BottomLeft,
            Corner::TopRight,
            Corner::BottomRight,
            Corner::TopLeft,
        ],
        &[],
    )?;
    Ok(())
}

fn draw(
    c: &mut Canvas,
    th: &Theme,
    series: &[BodeSeries],
    opts: &PlotOptions,
    title: Option<&str>,
) -> Result<()> {
    let ranges = data_ranges(series)?;
    let panels = layout_panels(c, th, title.is_some(), &ranges);
    draw_background(c, th, &panels, opts.grid);
    draw_asymptotes(c, th, series, &panels);
    let mut avoid = draw_curves(c, th, series, &panels);
    let colors: Vec<Color> = (0..series.len()).map(|k| color_of(series, k)).collect();
    let info = mark_margins(c, th, series, &colors, &panels, &ranges, &mut avoid)?;
    draw_axes(c, th, &panels)?;
    draw_legends(c, th, series, &panels, &avoid, &info)?;
    if let Some(t) = title {
        draw_title(c, th, t)?;
    }
    Ok(())
}
