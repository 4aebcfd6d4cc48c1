//! Step (and impulse, ramp) response plots with the step metrics annotated.

use std::path::Path;

use super::axes::Axis;
use super::frame::Frame;
use super::layout::{bounds, check_span, draw_title, layout_single_above, tick_targets};
use super::legend::{
    Avoid, Corner, Fitted, LegendEntry, Rect, box_points, clear_spot, draw_fitted, sample_run,
};
use super::options::{PlotOptions, check_label};
use super::raster::Canvas;
use super::raster::Color;
use super::render::render;
use super::style::{LineStyle, MarkerShape, Theme, series_color};
use super::text::{HAlign, VAlign};
use crate::analysis::{Input, StepInfo, TimeResponse};
use crate::error::{LtiError, Result};
use crate::fmt::{fmt_opt, fmt_sig};

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

/// y at time `t` by linear interpolation of the samples; at a time sampled exactly, its last
/// sample (a staircase — a discrete-time response — has two there: the value held until t and
/// the value from t on, which is the response at t).
#[allow(clippy::float_cmp)] // the metric times are the sample times, bit for bit
fn y_at(r: &TimeResponse, t: f64) -> Option<f64> {
    if let Some(i) = r.t.iter().rposition(|&x| x == t) {
        return Some(r.y[i]);
    }
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
        draw(c, th, series, opts, title.as_deref()).map(|_| ())
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
        let (Some(rise_start), Some(rise_end)) = (i.rise_start, i.rise_end) else {
            return Ok(());
        };
        for (t, y) in [(rise_start, 0.1 * yss), (rise_end, 0.9 * yss)] {
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
        if self.inline && frame.contains((rise_start, yr)) && frame.contains((rise_end, yr)) {
            let (p, q) = (frame.px((rise_start, yr)), frame.px((rise_end, yr)));
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
        let (Some(overshoot), Some(peak_time)) = (i.overshoot_percent, i.peak_time) else {
            return Ok(());
        };
        if overshoot <= 0.0 || overshoot.is_nan() {
            return Ok(());
        }
        let Some(yp) = y_at(r, peak_time) else {
            return Ok(());
        };
        frame.plot_line(
            c,
            [(frame.x.lo, yp), (peak_time, yp)],
            self.thin,
            col,
            LineStyle::Dotted,
        );
        frame.plot_marker(c, (peak_time, yp), MarkerShape::Disc, self.ms, col, th.line);
        if self.inline && frame.contains((peak_time, yp)) {
            let p = frame.px((peak_time, yp));
            let text = format!("overshoot {} %", fmt_sig(overshoot, 3));
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
        let Some(ts) = i.settling_time else {
            return Ok(());
        };
        let Some(ys) = y_at(r, ts) else {
            return Ok(());
        };
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

/// The curves with the step-metric marks, each in its line style; returns the pixel points to
/// keep legends off (the curves and the inline labels).
fn draw_curves(
    c: &mut Canvas,
    th: &Theme,
    frame: &Frame,
    series: &[StepSeries],
    styles: &[LineStyle],
) -> Result<Avoid> {
    let mut avoid = Vec::new();
    for (k, s) in series.iter().enumerate() {
        let col = color_of(series, k);
        let r = s.response;
        let runs = frame.clip_polyline(r.t.iter().copied().zip(r.y.iter().copied()));
        let dash = styles[k].pattern(th.line);
        for run in &runs {
            c.stroke(run, th.line, col, &dash);
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

/// The largest vertical distance in pixels between two curves over their common samples
/// (each one's samples against the other interpolated linearly, in one merged pass); ∞ when
/// their time spans differ or one is not finite where the other is.
fn pixel_gap(a: &TimeResponse, b: &TimeResponse, frame: &Frame) -> f64 {
    let span = |r: &TimeResponse| (r.t.first().copied(), r.t.last().copied());
    let (Some(a0), Some(a1)) = span(a) else {
        return f64::INFINITY;
    };
    let (Some(b0), Some(b1)) = span(b) else {
        return f64::INFINITY;
    };
    let tol = 1e-9 * (a1 - a0).abs().max(f64::MIN_POSITIVE);
    if (a0 - b0).abs() > tol || (a1 - b1).abs() > tol {
        return f64::INFINITY;
    }
    let one_way = |p: &TimeResponse, q: &TimeResponse| {
        let mut worst = 0.0f64;
        let mut j = 0;
        for (&t, &y) in p.t.iter().zip(&p.y) {
            while j + 2 < q.t.len() && q.t[j + 1] < t {
                j += 1;
            }
            let (t0, t1) = (q.t[j], q.t[(j + 1).min(q.t.len() - 1)]);
            let (y0, y1) = (q.y[j], q.y[(j + 1).min(q.y.len() - 1)]);
            let v = if t1 > t0 {
                y0 + (y1 - y0) * ((t - t0) / (t1 - t0)).clamp(0.0, 1.0)
            } else {
                y0
            };
            let d = (frame.px((t, y)).1 - frame.px((t, v)).1).abs();
            if !(d.is_finite() || (y.is_nan() && v.is_nan())) {
                return f64::INFINITY;
            }
            if d.is_finite() {
                worst = worst.max(d);
            }
        }
        worst
    };
    one_way(a, b).max(one_way(b, a))
}

/// For each series, the first earlier series whose curve it would be drawn on (within half a
/// line width at every sample over the same time span), if any.
fn coincident(series: &[StepSeries], frame: &Frame, th: &Theme) -> Vec<Option<usize>> {
    let tol = (0.5 * th.line).max(0.75);
    let mut out: Vec<Option<usize>> = vec![None; series.len()];
    for k in 1..series.len() {
        out[k] = (0..k).find(|&j| {
            out[j].is_none() && pixel_gap(series[j].response, series[k].response, frame) <= tol
        });
    }
    out
}

/// The line style of each series: solid, and for a curve drawn on an earlier one dashed
/// (then dotted, dash-dotted) so that the one beneath shows through the gaps.
fn line_styles(coincide: &[Option<usize>]) -> Vec<LineStyle> {
    const ON_TOP: [LineStyle; 3] = [LineStyle::Dashed, LineStyle::Dotted, LineStyle::DashDot];
    let mut count = vec![0usize; coincide.len()];
    coincide
        .iter()
        .map(|c| match c {
            Some(j) => {
                count[*j] += 1;
                ON_TOP[(count[*j] - 1) % ON_TOP.len()]
            }
            None => LineStyle::Solid,
        })
        .collect()
}

/// Whether the samples move monotonically towards the final value `yss` (never back by more
/// than rounding: 1e-9·|y∞| from one sample to the next).
fn monotone(r: &TimeResponse, yss: f64) -> bool {
    let slack = 1e-9 * yss.abs();
    let sign = yss.signum();
    r.y.windows(2)
        .all(|w| !(w[0].is_finite() && w[1].is_finite()) || sign * (w[1] - w[0]) >= -slack)
}

/// The metric rows of one series (without its name): a note when unstable, then the step
/// metrics or the final value.
fn metric_rows(s: &StepSeries) -> Vec<(String, Color)> {
    let mut rows = Vec::new();
    if s.unstable {
        rows.push(("unstable: response diverges".to_string(), Color(200, 0, 0)));
    }
    if let Some(i) = step_info(s) {
        rows.push((
            format!(
                "rise time {} s, settling time {} s (2 %)",
                fmt_opt(i.rise_time, 3),
                fmt_opt(i.settling_time, 3)
            ),
            Color::BLACK,
        ));
        // Without overshoot the peak |y∞| is only approached (peak_time = ∞); whether the
        // response gets there monotonically is read off the samples drawn.
        let peak = match i.peak_time {
            Some(tp) if tp.is_finite() => format!(
                "overshoot {} %, peak {} at {} s",
                fmt_opt(i.overshoot_percent, 3),
                fmt_opt(i.peak, 4),
                fmt_sig(tp, 3)
            ),
            None => "peak and overshoot not computed".to_string(),
            Some(_) if monotone(s.response, i.steady_state) => {
                "no overshoot (monotone)".to_string()
            }
            Some(_) if i.steady_state < 0.0 => {
                "no overshoot (stays above the final value)".to_string()
            }
            Some(_) => "no overshoot (stays below the final value)".to_string(),
        };
        rows.push((
            format!("{peak}, final value {}", fmt_sig(i.steady_state, 4)),
            Color::BLACK,
        ));
    } else if let Some(f) = s.response.final_value {
        if !s.unstable {
            rows.push((format!("final value {}", fmt_sig(f, 4)), Color::BLACK));
        }
    }
    rows
}

/// Rows of a box in groups that stay together when the box is split into columns.
type Groups = Vec<Vec<LegendEntry>>;

/// The information rows, one group per series: its metric rows, prefixed with its name when
/// there are several; coincident series with the same rows share them ("u1 → y2, u2 → y1: …").
fn info_rows(series: &[StepSeries], coincide: &[Option<usize>]) -> Groups {
    let mut out: Groups = Vec::new();
    let several = series.len() > 1;
    let mut done = vec![false; series.len()];
    for k in 0..series.len() {
        if done[k] {
            continue;
        }
        let rows = metric_rows(&series[k]);
        // the later series drawn on this one with the very same rows
        let same: Vec<usize> = (k + 1..series.len())
            .filter(|&j| coincide[j] == Some(k) && metric_rows(&series[j]) == rows)
            .collect();
        let mut names = vec![name_of(&series[k], k)];
        for &j in &same {
            done[j] = true;
            names.push(name_of(&series[j], j));
        }
        let prefix = if several {
            format!("{}: ", names.join(", "))
        } else {
            String::new()
        };
        let col = color_of(series, k);
        let group: Vec<LegendEntry> = rows
            .into_iter()
            .map(|(text, c)| {
                let c = if c == Color::BLACK { col } else { c };
                LegendEntry::text(format!("{prefix}{text}"), c)
            })
            .collect();
        if !group.is_empty() {
            out.push(group);
        }
    }
    out
}

/// The plant legend (only for several plants; the input is named when the inputs differ, and
/// a curve drawn on an earlier one says so).
fn legend_rows(
    series: &[StepSeries],
    coincide: &[Option<usize>],
    styles: &[LineStyle],
) -> Vec<LegendEntry> {
    if series.len() < 2 {
        return Vec::new();
    }
    let mixed = series.iter().any(|o| o.input != series[0].input);
    series
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let mut name = name_of(s, k);
            if mixed {
                name = format!("{name} ({})", s.input.title().to_lowercase());
            }
            if let Some(j) = coincide[k] {
                name = format!("{name} (coincides with {})", name_of(&series[j], j));
            }
            LegendEntry::line(name, color_of(series, k), styles[k])
        })
        .collect()
}

/// Grid, bands, the curves with their marks, axes and axis titles; returns the points the
/// boxes must not hide.
fn draw_chart(
    c: &mut Canvas,
    th: &Theme,
    frame: &Frame,
    series: &[StepSeries],
    styles: &[LineStyle],
    grid: bool,
) -> Result<Avoid> {
    draw_background(c, th, frame, series, grid);
    let avoid = draw_curves(c, th, frame, series, styles)?;
    frame.draw_axes(c, th, true, true)?;
    let y_title = match &series[0].input {
        Input::Step => "Step response y(t)",
        Input::Impulse => "Impulse response y(t)",
        Input::Ramp => "Ramp response y(t)",
        _ => "Output y(t)",
    };
    frame.draw_axis_titles(c, th, Some("Time t (s)"), Some(y_title), th.pad)?;
    Ok(avoid)
}

/// The boxes (legend, metrics) inside the frame where each hides none of the points `avoid`
/// and shows all its rows; `None` when one of them has no such place.
fn inside(
    frame: &Frame,
    th: &Theme,
    boxes: &[Groups],
    avoid: &[(f64, f64)],
) -> Option<Vec<(Fitted, Rect)>> {
    let order = [
        Corner::BottomRight,
        Corner::TopRight,
        Corner::TopLeft,
        Corner::BottomLeft,
    ];
    let mut placed: Vec<(Fitted, Rect)> = Vec::new();
    for rows in boxes.iter().map(|b| b.concat()).filter(|b| !b.is_empty()) {
        let fit = Fitted::new(frame, th, &rows).filter(|f| !f.cut)?;
        let taken: Vec<Rect> = placed.iter().map(|p| p.1).collect();
        let at = clear_spot(frame, th, (fit.w, fit.h), avoid, &order, &taken)?;
        placed.push((fit, at));
    }
    Some(placed)
}

/// Boxes in a strip under the chart (below the x-axis title), side by side: each box split
/// into columns of at most R rows (its groups kept whole), R as small as keeps the strip
/// within the canvas width; the strip is at most 45 % of the canvas height (beyond it rows
/// are summarised as "… and n more").
struct Strip {
    boxes: Vec<Fitted>,
}

impl Strip {
    fn new(c: &Canvas, th: &Theme, boxes: &[Groups]) -> Strip {
        let (cw, ch) = (f64::from(c.w), f64::from(c.h));
        let gap = 8.0 * th.s;
        let (width, budget) = (cw - 2.0 * th.pad, 0.45 * ch);
        let boxes: Vec<&Groups> = boxes.iter().filter(|b| !b.is_empty()).collect();
        // each box's groups packed in order into columns of at most `most` rows (a longer
        // group gets a column of its own)
        let columns = |most: usize| -> Vec<Fitted> {
            let mut out = Vec::new();
            for b in &boxes {
                let mut col: Vec<LegendEntry> = Vec::new();
                for g in b.iter() {
                    if !col.is_empty() && col.len() + g.len() > most {
                        out.extend(Fitted::within(th, &col, (width, budget)));
                        col.clear();
                    }
                    col.extend(g.iter().cloned());
                }
                if !col.is_empty() {
                    out.extend(Fitted::within(th, &col, (width, budget)));
                }
            }
            out
        };
        let total = |cols: &[Fitted]| cols.iter().map(|f| f.w + gap).sum::<f64>() - gap;
        let rows = |b: &Groups| b.iter().map(Vec::len).sum::<usize>();
        let longest = boxes.iter().map(|b| rows(b)).max().unwrap_or(1);
        (1..=longest)
            .map(columns)
            .find(|cols| total(cols) <= width && cols.iter().all(|f| !f.cut))
            .map(|boxes| Strip { boxes })
            .unwrap_or_else(|| {
                // too wide even one column a box: one above the other, sharing the height
                let n = boxes.len().max(1) as f64;
                let share = (budget - gap * (n - 1.0)) / n;
                Strip {
                    boxes: boxes
                        .iter()
                        .filter_map(|b| Fitted::within(th, &b.concat(), (width, share)))
                        .collect(),
                }
            })
    }

    /// Whether the boxes stand side by side (else one above the other).
    fn side_by_side(&self, th: &Theme, cw: f64) -> bool {
        let gap = 8.0 * th.s;
        self.boxes.iter().map(|f| f.w + gap).sum::<f64>() - gap <= cw - 2.0 * th.pad
    }

    /// Height of the strip with the gap above it.
    fn height(&self, th: &Theme, cw: f64) -> f64 {
        let gap = 8.0 * th.s;
        let hs = self.boxes.iter().map(|f| f.h);
        gap + if self.side_by_side(th, cw) {
            hs.fold(0.0, f64::max)
        } else {
            hs.map(|h| h + gap).sum::<f64>() - gap
        }
    }

    /// Draws the boxes at the bottom of the canvas, from the frame's left edge when they fit
    /// there.
    fn draw(&self, c: &mut Canvas, th: &Theme, frame: &Frame) -> Result<Vec<Rect>> {
        let (cw, ch) = (f64::from(c.w), f64::from(c.h));
        let gap = 8.0 * th.s;
        let side_by_side = self.side_by_side(th, cw);
        let top = ch - th.pad - (self.height(th, cw) - gap);
        let widest = if side_by_side {
            self.boxes.iter().map(|f| f.w + gap).sum::<f64>() - gap
        } else {
            self.boxes.iter().map(|f| f.w).fold(0.0, f64::max)
        };
        let x0 = if frame.x0 + widest <= cw - th.pad {
            frame.x0
        } else {
            th.pad
        };
        let (mut x, mut y) = (x0, top);
        let mut rects = Vec::new();
        for f in &self.boxes {
            draw_fitted(c, th, f, (x, y))?;
            rects.push((x, y, x + f.w, y + f.h));
            if side_by_side {
                x += f.w + gap;
            } else {
                y += f.h + gap;
            }
        }
        Ok(rects)
    }
}

/// Draws the picture; returns the chart's frame and the boxes drawn (legend, metrics): inside
/// the frame where they hide no curve, else in a strip under the chart.
fn draw(
    c: &mut Canvas,
    th: &Theme,
    series: &[StepSeries],
    opts: &PlotOptions,
    title: Option<&str>,
) -> Result<(Frame, Vec<Rect>)> {
    let ((t0, t1), (ylo, yhi)) = data_ranges(series)?;
    let axes = |w: f64, h: f64| {
        let (nx, ny) = tick_targets(w, h, th);
        (
            Axis::linear(t0, t1, nx, true),
            Axis::linear(ylo, yhi, ny, false),
        )
    };
    let titles = (title.is_some(), true, true);
    let frame = layout_single_above(c, th, titles, 0.0, axes);
    let coincide = coincident(series, &frame, th);
    let styles = line_styles(&coincide);
    let boxes: [Groups; 2] = [
        legend_rows(series, &coincide, &styles)
            .into_iter()
            .map(|r| vec![r])
            .collect(),
        info_rows(series, &coincide),
    ];
    let avoid = draw_chart(c, th, &frame, series, &styles, opts.grid)?;
    let drawn = match inside(&frame, th, &boxes, &avoid) {
        Some(placed) => {
            for (fit, at) in &placed {
                draw_fitted(c, th, fit, (at.0, at.1))?;
            }
            (frame, placed.into_iter().map(|p| p.1).collect())
        }
        None => {
            // Every place inside would hide a curve: the boxes go under the chart.
            let strip = Strip::new(c, th, &boxes);
            c.clear();
            let reserve = strip.height(th, f64::from(c.w));
            let frame = layout_single_above(c, th, titles, reserve, axes);
            draw_chart(c, th, &frame, series, &styles, opts.grid)?;
            let rects = strip.draw(c, th, &frame)?;
            (frame, rects)
        }
    };
    if let Some(t) = title {
        draw_title(c, th, t)?;
    }
    Ok(drawn)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::Factored;
    use crate::lti::TransferFunction;

    fn factored(num: &[f64], den: &[f64]) -> Factored {
        TransferFunction::from_descending(num, den)
            .unwrap()
            .factored()
            .unwrap()
    }

    /// The step response on 0…t_end (1001 samples) and the step metrics.
    fn step(g: &Factored, t_end: f64) -> (TimeResponse, StepInfo) {
        let t: Vec<f64> = (0..=1000).map(|k| t_end * k as f64 / 1000.0).collect();
        (
            g.step_response(&t).unwrap(),
            g.step_info().unwrap().unwrap(),
        )
    }

    /// Draws `series` on a 1000 × 700 canvas; the frame and the boxes drawn.
    fn drawn(series: &[StepSeries]) -> (Frame, Vec<Rect>) {
        let opts = PlotOptions::default();
        let mut c = Canvas::new(1000, 700);
        let th = Theme::new(&opts);
        draw(&mut c, &th, series, &opts, Some("t")).unwrap()
    }

    /// Curve points (every 2 px) inside a box drawn, over all series.
    fn hidden_points(series: &[StepSeries], frame: &Frame, boxes: &[Rect]) -> usize {
        let mut n = 0;
        for s in series {
            let r = s.response;
            for run in frame.clip_polyline(r.t.iter().copied().zip(r.y.iter().copied())) {
                n += sample_run(&run, 2.0)
                    .iter()
                    .filter(|p| {
                        boxes
                            .iter()
                            .any(|b| p.0 > b.0 && p.0 < b.2 && p.1 > b.1 && p.1 < b.3)
                    })
                    .count();
            }
        }
        n
    }

    /// The channels of the two tanks of the README, A = [[−1, 0.5], [0.5, −2]], B = C = I:
    /// (sI − A)⁻¹ = [[s + 2, 0.5], [0.5, s + 1]]/(s² + 3s + 1.75), so G12 = G21.
    fn tanks() -> Vec<(TimeResponse, StepInfo)> {
        let den = [1.0, 3.0, 1.75];
        [[1.0, 2.0], [0.0, 0.5], [0.0, 0.5], [1.0, 1.0]]
            .iter()
            .map(|num| step(&factored(num, &den), 10.0))
            .collect()
    }

    #[test]
    fn identical_channels_are_told_apart_and_share_their_metrics() {
        let data = tanks();
        let names = ["u1 → y1", "u1 → y2", "u2 → y1", "u2 → y2"];
        let series: Vec<StepSeries> = data
            .iter()
            .zip(names)
            .map(|((r, i), n)| StepSeries::new(r).label(n).info(i))
            .collect();
        let (frame, _) = drawn(&series);
        let th = Theme::new(&PlotOptions::default());
        let coincide = coincident(&series, &frame, &th);
        assert_eq!(coincide, vec![None, None, Some(1), None]);
        let styles = line_styles(&coincide);
        assert_eq!(styles[2], LineStyle::Dashed);
        assert!(
            styles
                .iter()
                .enumerate()
                .all(|(k, s)| k == 2 || *s == LineStyle::Solid)
        );
        let legend = legend_rows(&series, &coincide, &styles);
        assert_eq!(legend[2].text, "u2 → y1 (coincides with u1 → y2)");
        // 3 groups of metrics, two rows each; the coincident pair shares its rows
        let info = info_rows(&series, &coincide);
        assert_eq!(info.len(), 3);
        let info = info.concat();
        assert_eq!(info.len(), 6);
        assert!(
            info[2].text.starts_with("u1 → y2, u2 → y1: rise time"),
            "{}",
            info[2].text
        );
    }

    #[test]
    fn boxes_hide_no_curve() {
        // The README's two tanks: room inside the frame.
        let data = tanks();
        let names = [
            "inflow 1 [m^3/s] → level 1 [m]",
            "inflow 1 [m^3/s] → level 2 [m]",
            "inflow 2 [m^3/s] → level 1 [m]",
            "inflow 2 [m^3/s] → level 2 [m]",
        ];
        let series: Vec<StepSeries> = data
            .iter()
            .zip(names)
            .map(|((r, i), n)| StepSeries::new(r).label(n).info(i))
            .collect();
        let (frame, boxes) = drawn(&series);
        assert_eq!(boxes.len(), 2);
        assert_eq!(hidden_points(&series, &frame, &boxes), 0);
        // Twelve lags 1/(τs + 1) with τ = 0.5…6 fill the frame: the boxes go under it.
        let data: Vec<(TimeResponse, StepInfo)> = (1..=12)
            .map(|k| step(&factored(&[1.0], &[0.5 * k as f64, 1.0]), 20.0))
            .collect();
        let names: Vec<String> = (1..=12)
            .map(|k| format!("τ = {} s", 0.5 * k as f64))
            .collect();
        let series: Vec<StepSeries> = data
            .iter()
            .zip(&names)
            .map(|((r, i), n)| StepSeries::new(r).label(n).info(i))
            .collect();
        let (frame, boxes) = drawn(&series);
        assert!(!boxes.is_empty());
        for b in &boxes {
            assert!(
                b.1 > frame.y1 && b.3 <= 700.0,
                "{b:?} vs frame bottom {}",
                frame.y1
            );
        }
        assert_eq!(hidden_points(&series, &frame, &boxes), 0);
    }

    #[test]
    fn no_overshoot_says_whether_the_approach_is_monotone() {
        // 1/(s + 1): monotone.
        let (r, i) = step(&factored(&[1.0], &[1.0, 1.0]), 10.0);
        let rows = metric_rows(&StepSeries::new(&r).info(&i));
        assert!(rows[1].0.starts_with("no overshoot (monotone)"), "{rows:?}");
        // The README's PID loop on the spring–mass–damper, T = (260 s² + 1005 s + 500) /
        // (5 s⁴ + 502 s³ + 480 s² + 3005 s + 500) (tests/closed_loop.rs, from sympy): no
        // overshoot, but it oscillates on its way up.
        let g = factored(&[260.0, 1005.0, 500.0], &[5.0, 502.0, 480.0, 3005.0, 500.0]);
        let (r, i) = step(&g, 50.0);
        assert!(i.peak_time.is_some_and(f64::is_infinite));
        assert!(
            r.y.windows(2).any(|w| w[1] < w[0] - 1e-3),
            "it goes down somewhere"
        );
        let rows = metric_rows(&StepSeries::new(&r).info(&i));
        assert!(
            rows[1]
                .0
                .starts_with("no overshoot (stays below the final value)"),
            "{rows:?}"
        );
        // and in the sign of a negative final value: −1/(s + 1) is monotone too
        let (r, i) = step(&factored(&[-1.0], &[1.0, 1.0]), 10.0);
        assert!(monotone(&r, i.steady_state));
    }
}
