//! Step (and impulse, ramp) response plots with the step metrics annotated.

use std::path::Path;

use super::axes::Axis;
use super::frame::Frame;
use super::layout::{bounds, check_span, draw_title, layout_single, tick_targets};
use super::legend::{Avoid, Corner, LegendEntry, Rect, box_points, draw_legend, sample_run};
use super::options::{PlotOptions, check_label};
use super::raster::Canvas;
use super::raster::Color;
use super::render::render;
use super::style::{LineStyle, MarkerShape, Theme, series_color};
use super::text::{HAlign, VAlign};
use crate::analysis::{Input, StepInfo, TimeResponse};
use crate::error::{LtiError, Result};
use crate::fmt::fmt_sig;

/// One response on a step-response plot.
///
/// ```
/// use ltikit::analysis::TimeResponse;
/// use ltikit::analysis::Input;
/// use ltikit::plot::StepSeries;
/// let r = TimeResponse { t: vec![0.0, 1.0], y: vec![0.0, 0.63], final_value: Some(1.0) };
/// let s = StepSeries::new(&r).label("1/(s + 1)").input(Input::Step);
/// assert!(!s.unstable);
/// ```
#[derive(Debug, Clone)]
pub struct StepSeries<'a> {
    /// The samples y(t) and the final value.
    pub response: &'a TimeResponse,
    /// Legend text.
    pub label: Option<&'a str>,
    /// Step metrics to annotate (rise time, settling time and band, peak, overshoot).
    pub info: Option<&'a StepInfo>,
    /// The input (step, impulse, ramp, …).
    pub input: Input,
    /// The plant is unstable: a note "unstable: response diverges" is drawn.
    pub unstable: bool,
    /// Colour; `None` takes the palette colour of the series' position.
    pub color: Option<Color>,
}

impl<'a> StepSeries<'a> {
    /// A step response without annotations.
    pub fn new(response: &'a TimeResponse) -> Self {
        StepSeries {
            response,
            label: None,
            info: None,
            input: Input::Step,
            unstable: false,
            color: None,
        }
    }

    /// Sets the legend label.
    pub fn label(mut self, label: &'a str) -> Self {
        self.label = Some(label);
        self
    }

    /// Annotates these step metrics.
    pub fn info(mut self, info: &'a StepInfo) -> Self {
        self.info = Some(info);
        self
    }

    /// Sets the input kind.
    pub fn input(mut self, input: Input) -> Self {
        self.input = input;
        self
    }

    /// Marks the response as diverging (unstable plant).
    pub fn unstable(mut self, unstable: bool) -> Self {
        self.unstable = unstable;
        self
    }

    /// Sets the colour.
    pub fn color(mut self, color: Color) -> Self {
        self.color = Some(color);
        self
    }
}

/// y at time `t` by linear interpolation of the samples.
fn y_at(r: &TimeResponse, t: f64) -> Option<f64> {
    let k = r.t.windows(2).position(|p| p[0] <= t && t <= p[1])?;
    let (t0, t1) = (r.t[k], r.t[k + 1]);
    let (y0, y1) = (r.y[k], r.y[k + 1]);
    Some(if t1 > t0 {
        y0 + (y1 - y0) * (t - t0) / (t1 - t0)
    } else {
        y0
    })
}

/// An annotation right of pixel point `p` (left of it when it would leave the frame); returns
/// its box.
fn label(
    c: &mut Canvas,
    frame: &Frame,
    th: &Theme,
    text: &str,
    p: (f64, f64),
    col: Color,
) -> Result<Rect> {
    let gap = 7.0 * th.s;
    let w = Canvas::text_width(text, th.note);
    let (x, h) = if p.0 + gap + w < frame.x1 - 2.0 {
        (p.0 + gap, HAlign::Left)
    } else {
        (p.0 - gap, HAlign::Right)
    };
    c.text_on_box(text, (x, p.1), th.note, col, (h, VAlign::Middle))
}

fn check(series: &[StepSeries]) -> Result<()> {
    if series.is_empty() {
        return Err(LtiError::Plot("response plot: no response given".into()));
    }
    for (k, s) in series.iter().enumerate() {
        check_label(k, s.label)?;
        let r = s.response;
        if r.t.len() != r.y.len() {
            return Err(LtiError::Plot(format!(
                "response plot: series {}: {} times but {} values",
                k + 1,
                r.t.len(),
                r.y.len()
            )));
        }
        let good =
            r.t.iter()
                .zip(&r.y)
                .filter(|(t, y)| t.is_finite() && y.is_finite())
                .count();
        if good < 2 {
            return Err(LtiError::Plot(format!(
                "response plot: series {} has fewer than two finite samples",
                k + 1
            )));
        }
    }
    Ok(())
}

/// Writes a time-response plot of one or more plants: step responses annotated with their
/// [`StepInfo`] (final value, ±2 % settling band, rise time 10 %→90 %, peak and overshoot,
/// settling time), or impulse/ramp responses labelled by their input. An unstable series gets
/// the note "unstable: response diverges"; its curve is drawn over the window given (the
/// y-axis follows the data).
///
/// Errors: no series, mismatched lengths, fewer than two finite samples, bad options, a title,
/// label or input name longer than [`MAX_TEXT_CHARS`](super::options::MAX_TEXT_CHARS) characters, an
/// unwritable path; no file is left behind.
///
/// ```no_run
/// use ltikit::TransferFunction;
/// use ltikit::plot::{step_png, PlotOptions, StepSeries};
/// // First-order lag 1/(s + 1): y = 1 − e^(−t).
/// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap().factored().unwrap();
/// let t: Vec<f64> = (0..=500).map(|k| k as f64 * 0.01).collect();
/// let r = g.step_response(&t).unwrap();
/// let info = g.step_info().unwrap().unwrap();
/// step_png("/tmp/step.png", &[StepSeries::new(&r).label("1/(s + 1)").info(&info)], &PlotOptions::default()).unwrap();
/// ```
pub fn step_png(path: impl AsRef<Path>, series: &[StepSeries], opts: &PlotOptions) -> Result<()> {
    check(series)?;
    let kind = {
        let first = series[0].input.title();
        if series.iter().all(|s| s.input.title() == first) {
            first
        } else {
            "Time".into()
        }
    };
    let title = opts.title_or(|| match (series.len(), series[0].label) {
        (1, Some(l)) => format!("{kind} response of G(s) = {l}"),
        _ => format!("{kind} response"),
    });
    render(path.as_ref(), opts, |c, th| {
        draw(c, th, series, opts, title.as_deref())
    })
}

/// The colour of series `k`: its own, or the palette's.
fn color_of(series: &[StepSeries], k: usize) -> Color {
    series[k].color.unwrap_or_else(|| series_color(k))
}

/// The name of series `k` in legends: its label or "G1", "G2", ….
fn name_of(s: &StepSeries, k: usize) -> String {
    s.label
        .map(str::to_string)
        .unwrap_or_else(|| format!("G{}", k + 1))
}

/// The step metrics of a series, if it is a step response that has them.
fn step_info<'a>(s: &StepSeries<'a>) -> Option<&'a StepInfo> {
    match (s.info, &s.input) {
        (Some(i), Input::Step) => Some(i),
        _ => None,
    }
}

/// The time range (from 0 at the latest) and the padded y range: the data, 0, the final values
/// and settling bands, the peaks.
fn data_ranges(series: &[StepSeries]) -> Result<((f64, f64), (f64, f64))> {
    let (t0, t1) =
        bounds(series.iter().flat_map(|s| s.response.t.iter().copied())).unwrap_or((0.0, 1.0));
    let t0 = t0.min(0.0);
    let mut ys: Vec<f64> = vec![0.0];
    for s in series {
        ys.extend(s.response.y.iter().copied());
        if let Some(f) = s.response.final_value {
            ys.push(f);
        }
        if let Some(i) = step_info(s) {
            ys.extend([i.steady_state * 1.02, i.steady_state * 0.98]);
        }
    }
    let (ylo, yhi) = bounds(ys).unwrap_or((-1.0, 1.0));
    let pad = 0.04 * (yhi - ylo).max(f64::MIN_POSITIVE);
    let y = (if ylo < 0.0 { ylo - pad } else { ylo }, yhi + pad);
    check_span("times", (t0, t1))?;
    check_span("values", y)?;
    Ok(((t0, t1), y))
}

/// Grid, the y = 0 line, and under the curves the settling bands and final values.
fn draw_background(c: &mut Canvas, th: &Theme, frame: &Frame, series: &[StepSeries], grid: bool) {
    if grid {
        frame.draw_grid(c, th);
    }
    let thin = (th.line * 0.6).max(1.0);
    if frame.y.lo < 0.0 && frame.y.hi > 0.0 {
        frame.hline(c, 0.0, thin, Color(120, 120, 120), LineStyle::Solid);
    }
    for (k, s) in series.iter().enumerate() {
        let col = color_of(series, k);
        if let Some(i) = step_info(s) {
            let (a, b) = (
                i.steady_state - 0.02 * i.steady_state.abs(),
                i.steady_state + 0.02 * i.steady_state.abs(),
            );
            let p = frame.px((frame.x.lo, a.max(frame.y.lo).min(frame.y.hi)));
            let q = frame.px((frame.x.hi, b.max(frame.y.lo).min(frame.y.hi)));
            c.fill_rect(p.0, p.1, q.0, q.1, col, 0.10);
        }
        if let Some(f) = s.response.final_value {
            frame.hline(c, f, thin, col.lighten(0.2), LineStyle::Dashed);
        }
    }
}

/// Drawing context for the step-metric marks of one series.
struct Marks<'a> {
    frame: &'a Frame,
    th: &'a Theme,
    col: Color,
    /// Marker size and thin line width.
    ms: f64,
    thin: f64,
    /// Inline labels (only for a single plant: several would collide; the box lists all).
    inline: bool,
}

impl Marks<'_> {
    /// Rise: 10 % and 90 % points with drop lines to the time axis, and the t_r arrow.
    fn rise(&self, c: &mut Canvas, i: &StepInfo, avoid: &mut Avoid) -> Result<()> {
        let (frame, th, col) = (self.frame, self.th, self.col);
        let yss = i.steady_state;
        for (t, y) in [(i.rise_start, 0.1 * yss), (i.rise_end, 0.9 * yss)] {
            frame.plot_line(
                c,
                [(t, frame.y.lo.max(0.0f64.min(frame.y.hi))), (t, y)],
                self.thin,
                col,
                LineStyle::Dotted,
            );
            frame.plot_marker(c, (t, y), MarkerShape::Disc, self.ms, col, th.line);
        }
        let yr = 0.5 * yss;
        if self.inline && frame.contains((i.rise_start, yr)) && frame.contains((i.rise_end, yr)) {
            let (p, q) = (frame.px((i.rise_start, yr)), frame.px((i.rise_end, yr)));
            c.stroke(&[p, q], self.thin, col, &[]);
            if q.0 - p.0 > 14.0 * th.s {
                let len = 6.0 * th.s;
                super::style::draw_arrow_head(c, p, (-1.0, 0.0), len, col);
                super::style::draw_arrow_head(c, q, (1.0, 0.0), len, col);
            }
            avoid.extend(box_points(label(c, frame, th, "t_{r}", q, col)?));
        }
        Ok(())
    }

    /// Peak and overshoot.
    fn peak(
        &self,
        c: &mut Canvas,
        r: &TimeResponse,
        i: &StepInfo,
        avoid: &mut Avoid,
    ) -> Result<()> {
        let (frame, th, col) = (self.frame, self.th, self.col);
        if i.overshoot_percent <= 0.0 || i.overshoot_percent.is_nan() {
            return Ok(());
        }
        let Some(yp) = y_at(r, i.peak_time) else {
            return Ok(());
        };
        frame.plot_line(
            c,
            [(frame.x.lo, yp), (i.peak_time, yp)],
            self.thin,
            col,
            LineStyle::Dotted,
        );
        frame.plot_marker(
            c,
            (i.peak_time, yp),
            MarkerShape::Disc,
            self.ms,
            col,
            th.line,
        );
        if self.inline && frame.contains((i.peak_time, yp)) {
            let p = frame.px((i.peak_time, yp));
            let text = format!("overshoot {} %", fmt_sig(i.overshoot_percent, 3));
            let bx = label(c, frame, th, &text, (p.0, p.1 - 12.0 * th.s), col)?;
            avoid.extend(box_points(bx));
        }
        Ok(())
    }

    /// Settling time: a drop line from y(t_s) to the time axis.
    fn settling(
        &self,
        c: &mut Canvas,
        r: &TimeResponse,
        i: &StepInfo,
        avoid: &mut Avoid,
    ) -> Result<()> {
        let (frame, th, col) = (self.frame, self.th, self.col);
        let base_y = frame.y.lo.max(0.0f64.min(frame.y.hi));
        let Some(ys) = y_at(r, i.settling_time) else {
            return Ok(());
        };
        let ts = i.settling_time;
        frame.plot_line(
            c,
            [(ts, base_y), (ts, ys)],
            self.thin,
            col,
            LineStyle::Dotted,
        );
        frame.plot_marker(c, (ts, ys), MarkerShape::Disc, self.ms, col, th.line);
        if self.inline && frame.contains((ts, base_y)) {
            let p = frame.px((ts, base_y));
            let bx = label(c, frame, th, "t_{s}", (p.0, p.1 - 12.0 * th.s), col)?;
            avoid.extend(box_points(bx));
        }
        Ok(())
    }
}

/// The curves with the step-metric marks; returns the pixel points to keep legends off (the
/// curves and the inline labels).
fn draw_curves(c: &mut Canvas, th: &Theme, frame: &Frame, series: &[StepSeries]) -> Result<Avoid> {
    let mut avoid = Vec::new();
    for (k, s) in series.iter().enumerate() {
        let col = color_of(series, k);
        let r = s.response;
        let runs = frame.clip_polyline(r.t.iter().copied().zip(r.y.iter().copied()));
        for run in &runs {
            c.stroke(run, th.line, col, &[]);
            avoid.extend(sample_run(run, 6.0));
        }
        if let Some(i) = step_info(s) {
            let marks = Marks {
                frame,
                th,
                col,
                ms: 4.5 * th.s,
                thin: (th.line * 0.6).max(1.0),
                inline: series.len() == 1,
            };
            marks.rise(c, i, &mut avoid)?;
            marks.peak(c, r, i, &mut avoid)?;
            marks.settling(c, r, i, &mut avoid)?;
        }
    }
    Ok(avoid)
}

/// The information rows: per series, a note when unstable, then the step metrics or the final
/// value (prefixed with the series' name when there are several).
fn info_rows(series: &[StepSeries]) -> Vec<LegendEntry> {
    let mut rows: Vec<LegendEntry> = Vec::new();
    for (k, s) in series.iter().enumerate() {
        let col = color_of(series, k);
        let prefix = if series.len() > 1 {
            format!("{}: ", name_of(s, k))
        } else {
            String::new()
        };
        if s.unstable {
            rows.push(LegendEntry::text(
                format!("{prefix}unstable: response diverges"),
                Color(200, 0, 0),
            ));
        }
        if let Some(i) = step_info(s) {
            rows.push(LegendEntry::text(
                format!(
                    "{prefix}rise time {} s, settling time {} s (2 %)",
                    fmt_sig(i.rise_time, 3),
                    fmt_sig(i.settling_time, 3)
                ),
                col,
            ));
            // A monotone response approaches its peak |y∞| only as t → ∞ (peak_time = ∞).
            let peak = if i.peak_time.is_finite() {
                format!(
                    "overshoot {} %, peak {} at {} s",
                    fmt_sig(i.overshoot_percent, 3),
                    fmt_sig(i.peak, 4),
                    fmt_sig(i.peak_time, 3)
                )
            } else {
                "no overshoot (monotone)".to_string()
            };
            rows.push(LegendEntry::text(
                format!("{prefix}{peak}, final value {}", fmt_sig(i.steady_state, 4)),
                col,
            ));
        } else if let Some(f) = s.response.final_value {
            if !s.unstable {
                rows.push(LegendEntry::text(
                    format!("{prefix}final value {}", fmt_sig(f, 4)),
                    col,
                ));
            }
        }
    }
    rows
}

/// The plant legend (only for several plants; the input is named when the inputs differ).
fn legend_rows(series: &[StepSeries]) -> Vec<LegendEntry> {
    if series.len() < 2 {
        return Vec::new();
    }
    let mixed = series.iter().any(|o| o.input != series[0].input);
    series
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let name = name_of(s, k);
            let name = if mixed {
                format!("{name} ({})", s.input.title().to_lowercase())
            } else {
                name
            };
            LegendEntry::line(name, color_of(series, k), LineStyle::Solid)
        })
        .collect()
}

fn draw(
    c: &mut Canvas,
    th: &Theme,
    series: &[StepSeries],
    opts: &PlotOptions,
    title: Option<&str>,
) -> Result<()> {
    let ((t0, t1), (ylo, yhi)) = data_ranges(series)?;
    let frame = layout_single(c, th, title.is_some(), true, true, |w, h| {
        let (nx, ny) = tick_targets(w, h, th);
        (
            Axis::linear(t0, t1, nx, true),
            Axis::linear(ylo, yhi, ny, false),
        )
    });
    draw_background(c, th, &frame, series, opts.grid);
    let avoid = draw_curves(c, th, &frame, series)?;
    frame.draw_axes(c, th, true, true)?;
    let y_title = match &series[0].input {
        Input::Step => "Step response y(t)",
        Input::Impulse => "Impulse response y(t)",
        Input::Ramp => "Ramp response y(t)",
        _ => "Output y(t)",
    };
    frame.draw_axis_titles(c, th, Some("Time t (s)"), Some(y_title), th.pad)?;
    let order = [
        Corner::BottomRight,
        Corner::TopRight,
        Corner::TopLeft,
        Corner::BottomLeft,
    ];
    let placed = draw_legend(c, &frame, th, &legend_rows(series), &avoid, &order, &[])?;
    let taken: Vec<_> = placed.into_iter().collect();
    draw_legend(c, &frame, th, &info_rows(series), &avoid, &order, &taken)?;
    if let Some(t) = title {
        draw_title(c, th, t)?;
    }
    Ok(())
}
