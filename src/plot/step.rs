//! Step (and impulse, ramp) response plots with the step metrics annotated.

use std::path::Path;

use super::axes::Axis;
use super::frame::Frame;
use super::layout::{bounds, draw_title, layout_single, tick_targets};
use super::legend::{Corner, LegendEntry, draw_legend, sample_run};
use super::raster::{Canvas, HAlign, VAlign};
use super::style::{LineStyle, MarkerShape, Theme, series_color};
use super::{Color, PlotOptions, render};
use crate::analysis::{StepInfo, TimeResponse};
use crate::error::{LtiError, Result};
use crate::poly::fmt_sig;

/// The input that produced a response (for titles and labels).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum InputKind {
    /// Unit step.
    #[default]
    Step,
    /// Unit impulse.
    Impulse,
    /// Unit ramp.
    Ramp,
    /// Anything else, named (e.g. "sin(2t)").
    Other(String),
}

impl InputKind {
    fn name(&self) -> String {
        match self {
            InputKind::Step => "Step".into(),
            InputKind::Impulse => "Impulse".into(),
            InputKind::Ramp => "Ramp".into(),
            InputKind::Other(s) => s.clone(),
        }
    }
}

/// One response on a step-response plot.
///
/// ```
/// use ltikit::analysis::TimeResponse;
/// use ltikit::plot::{InputKind, StepSeries};
/// let r = TimeResponse { t: vec![0.0, 1.0], y: vec![0.0, 0.63], final_value: Some(1.0) };
/// let s = StepSeries::new(&r).label("1/(s + 1)").input(InputKind::Step);
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
    pub input: InputKind,
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
            input: InputKind::Step,
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
    pub fn input(mut self, input: InputKind) -> Self {
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

/// An annotation right of pixel point `p` (left of it when it would leave the frame).
fn label(
    c: &mut Canvas,
    frame: &Frame,
    th: &Theme,
    text: &str,
    p: (f64, f64),
    col: Color,
) -> Result<()> {
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
/// Errors: no series, mismatched lengths, fewer than two finite samples, bad options, an
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
        let first = series[0].input.name();
        if series.iter().all(|s| s.input.name() == first) {
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

fn draw(
    c: &mut Canvas,
    th: &Theme,
    series: &[StepSeries],
    opts: &PlotOptions,
    title: Option<&str>,
) -> Result<()> {
    let color_of = |k: usize| series[k].color.unwrap_or_else(|| series_color(k));
    let (t0, t1) =
        bounds(series.iter().flat_map(|s| s.response.t.iter().copied())).unwrap_or((0.0, 1.0));
    let t0 = t0.min(0.0);
    // y range: the data, 0, the final values and settling bands, the peaks.
    let mut ys: Vec<f64> = vec![0.0];
    for s in series {
        ys.extend(s.response.y.iter().copied());
        if let Some(f) = s.response.final_value {
            ys.push(f);
        }
        if let (Some(i), InputKind::Step) = (s.info, &s.input) {
            ys.extend([i.steady_state * 1.02, i.steady_state * 0.98]);
        }
    }
    let (ylo, yhi) = bounds(ys).unwrap_or((-1.0, 1.0));
    let pad = 0.04 * (yhi - ylo).max(1e-300);
    let (ylo, yhi) = (if ylo < 0.0 { ylo - pad } else { ylo }, yhi + pad);
    let frame = layout_single(c, th, title.is_some(), true, true, |w, h| {
        let (nx, ny) = tick_targets(w, h, th);
        (
            Axis::linear(t0, t1, nx, true),
            Axis::linear(ylo, yhi, ny, false),
        )
    });
    if opts.grid {
        frame.draw_grid(c, th);
    }
    if frame.y.lo < 0.0 && frame.y.hi > 0.0 {
        frame.hline(
            c,
            0.0,
            (th.line * 0.6).max(1.0),
            Color(120, 120, 120),
            LineStyle::Solid,
        );
    }
    let thin = (th.line * 0.6).max(1.0);
    let several = series.len() > 1;
    let mut info_rows: Vec<LegendEntry> = Vec::new();
    let mut avoid = Vec::new();

    // Settling bands and final values under the curves.
    for (k, s) in series.iter().enumerate() {
        let col = color_of(k);
        if let (Some(i), InputKind::Step) = (s.info, &s.input) {
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

    for (k, s) in series.iter().enumerate() {
        let col = color_of(k);
        let r = s.response;
        let runs = frame.clip_polyline(r.t.iter().copied().zip(r.y.iter().copied()));
        for run in &runs {
            c.stroke(run, th.line, col, &[]);
            avoid.extend(sample_run(run, 6.0));
        }
        let prefix = if several {
            format!(
                "{}: ",
                s.label
                    .map(str::to_string)
                    .unwrap_or_else(|| format!("G{}", k + 1))
            )
        } else {
            String::new()
        };
        if s.unstable {
            info_rows.push(LegendEntry::text(
                format!("{prefix}unstable: response diverges"),
                Color(200, 0, 0),
            ));
        }
        if let (Some(i), InputKind::Step) = (s.info, &s.input) {
            let ms = 4.5 * th.s;
            let yss = i.steady_state;
            // Rise: 10 % and 90 % points with drop lines to the time axis.
            for (t, y) in [(i.rise_start, 0.1 * yss), (i.rise_end, 0.9 * yss)] {
                frame.plot_line(
                    c,
                    [(t, frame.y.lo.max(0.0f64.min(frame.y.hi))), (t, y)],
                    thin,
                    col,
                    LineStyle::Dotted,
                );
                frame.plot_marker(c, (t, y), MarkerShape::Disc, ms, col, th.line);
            }
            // Inline labels only for a single plant (several would collide; the box lists all).
            let inline = !several;
            let yr = 0.5 * yss;
            if inline && frame.contains((i.rise_start, yr)) && frame.contains((i.rise_end, yr)) {
                let (p, q) = (frame.px((i.rise_start, yr)), frame.px((i.rise_end, yr)));
                c.stroke(&[p, q], thin, col, &[]);
                if q.0 - p.0 > 14.0 * th.s {
                    let len = 6.0 * th.s;
                    super::style::draw_arrow_head(c, p, (-1.0, 0.0), len, col);
                    super::style::draw_arrow_head(c, q, (1.0, 0.0), len, col);
                }
                label(c, &frame, th, "t_{r}", q, col)?;
            }
            // Peak and overshoot.
            if i.overshoot_percent > 0.0 {
                if let Some(yp) = y_at(r, i.peak_time) {
                    frame.plot_line(
                        c,
                        [(frame.x.lo, yp), (i.peak_time, yp)],
                        thin,
                        col,
                        LineStyle::Dotted,
                    );
                    frame.plot_marker(c, (i.peak_time, yp), MarkerShape::Disc, ms, col, th.line);
                    if inline && frame.contains((i.peak_time, yp)) {
                        let p = frame.px((i.peak_time, yp));
                        let text = format!("overshoot {} %", fmt_sig(i.overshoot_percent, 3));
                        label(c, &frame, th, &text, (p.0, p.1 - 12.0 * th.s), col)?;
                    }
                }
            }
            // Settling time.
            let base_y = frame.y.lo.max(0.0f64.min(frame.y.hi));
            if let Some(ys) = y_at(r, i.settling_time) {
                frame.plot_line(
                    c,
                    [(i.settling_time, base_y), (i.settling_time, ys)],
                    thin,
                    col,
                    LineStyle::Dotted,
                );
                frame.plot_marker(
                    c,
                    (i.settling_time, ys),
                    MarkerShape::Disc,
                    ms,
                    col,
                    th.line,
                );
                if inline && frame.contains((i.settling_time, base_y)) {
                    let p = frame.px((i.settling_time, base_y));
                    label(c, &frame, th, "t_{s}", (p.0, p.1 - 12.0 * th.s), col)?;
                }
            }
            info_rows.push(LegendEntry::text(
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
            info_rows.push(LegendEntry::text(
                format!("{prefix}{peak}, final value {}", fmt_sig(yss, 4)),
                col,
            ));
        } else if let Some(f) = s.response.final_value {
            if !s.unstable {
                info_rows.push(LegendEntry::text(
                    format!("{prefix}final value {}", fmt_sig(f, 4)),
                    col,
                ));
            }
        }
    }

    frame.draw_axes(c, th, true, true)?;
    let y_title = match &series[0].input {
        InputKind::Step => "Step response y(t)",
        InputKind::Impulse => "Impulse response y(t)",
        InputKind::Ramp => "Ramp response y(t)",
        InputKind::Other(_) => "Output y(t)",
    };
    frame.draw_axis_titles(c, th, Some("Time t (s)"), Some(y_title), th.pad)?;
    let mut legend = Vec::new();
    if several {
        for (k, s) in series.iter().enumerate() {
            let name = s
                .label
                .map(str::to_string)
                .unwrap_or_else(|| format!("G{}", k + 1));
            let name = if series.iter().any(|o| o.input != s.input) {
                format!("{name} ({})", s.input.name().to_lowercase())
            } else {
                name
            };
            legend.push(LegendEntry::line(name, color_of(k), LineStyle::Solid));
        }
    }
    let order = [
        Corner::BottomRight,
        Corner::TopRight,
        Corner::TopLeft,
        Corner::BottomLeft,
    ];
    let placed = draw_legend(c, &frame, th, &legend, &avoid, &order, &[])?;
    let taken: Vec<_> = placed.into_iter().collect();
    draw_legend(c, &frame, th, &info_rows, &avoid, &order, &taken)?;
    if let Some(t) = title {
        draw_title(c, th, t)?;
    }
    Ok(())
}
