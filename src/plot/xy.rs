//! Generic x–y plots: curves with styles, markers, arrows, a legend. Time plots, phase
//! portraits and diagrams such as the MEMS pull-in curve or the pendulum's period against
//! amplitude are all built on [`xy_png`].

use std::path::Path;

use super::axes::Axis;
use super::frame::Frame;
use super::layout::{bounds, check_span, draw_title, equal_axes, layout_single, tick_targets};
use super::legend::{Corner, LegendEntry, Swatch, box_points, draw_legend, sample_run};
use super::options::{PlotOptions, check_label, check_text};
use super::raster::Canvas;
use super::raster::Color;
use super::render::render;
use super::style::{LineStyle, MarkerShape, Theme, arrows_along, series_color};
use super::text::{HAlign, VAlign};
use crate::error::{LtiError, Result};

/// One curve: points in drawing order, with its style.
///
/// ```
/// use ltikit::plot::{Curve, LineStyle};
/// let t = [0.0, 1.0, 2.0];
/// let y = [0.0, 0.5, 0.8];
/// let c = Curve::from_xy(&t, &y).unwrap().label("y(t)").style(LineStyle::Dashed);
/// assert_eq!(c.points.len(), 3);
/// assert!(Curve::from_xy(&t, &y[..2]).is_err());
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Curve {
    /// (x, y) points; non-finite points break the line.
    pub points: Vec<(f64, f64)>,
    /// Legend text (no legend entry when `None`).
    pub label: Option<String>,
    /// Line style.
    pub style: LineStyle,
    /// Colour; `None` takes the next palette colour.
    pub color: Option<Color>,
    /// Line-width factor (1 = the plot's default width).
    pub width: f64,
    /// Number of direction arrows drawn along the curve (0 = none).
    pub arrows: usize,
}

impl Curve {
    /// A solid curve through `points`.
    pub fn new(points: impl IntoIterator<Item = (f64, f64)>) -> Curve {
        Curve {
            points: points.into_iter().collect(),
            width: 1.0,
            ..Default::default()
        }
    }

    /// A curve from separate x and y slices (e.g. t and y(t)); errors if the lengths differ.
    pub fn from_xy(x: &[f64], y: &[f64]) -> Result<Curve> {
        if x.len() != y.len() {
            return Err(LtiError::Plot(format!(
                "x has {} values but y has {}",
                x.len(),
                y.len()
            )));
        }
        Ok(Curve::new(x.iter().copied().zip(y.iter().copied())))
    }

    /// Sets the legend label.
    pub fn label(mut self, label: impl Into<String>) -> Curve {
        self.label = Some(label.into());
        self
    }

    /// Sets the line style.
    pub fn style(mut self, style: LineStyle) -> Curve {
        self.style = style;
        self
    }

    /// Sets the colour.
    pub fn color(mut self, color: Color) -> Curve {
        self.color = Some(color);
        self
    }

    /// Sets the line-width factor.
    pub fn width(mut self, factor: f64) -> Curve {
        self.width = factor;
        self
    }

    /// Draws `n` direction arrows along the curve.
    pub fn arrows(mut self, n: usize) -> Curve {
        self.arrows = n;
        self
    }
}

/// A marked point with an optional text label next to it.
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    /// Position (data units).
    pub at: (f64, f64),
    /// Shape.
    pub shape: MarkerShape,
    /// Colour (black when `None`).
    pub color: Option<Color>,
    /// Text drawn to the upper right of the marker.
    pub label: Option<String>,
}

impl Marker {
    /// A marker of `shape` at `at`.
    ///
    /// ```
    /// use ltikit::plot::{Marker, MarkerShape};
    /// let m = Marker::new((1.0, 2.0), MarkerShape::Disc).label("pull-in");
    /// assert_eq!(m.label.as_deref(), Some("pull-in"));
    /// ```
    pub fn new(at: (f64, f64), shape: MarkerShape) -> Marker {
        Marker {
            at,
            shape,
            color: None,
            label: None,
        }
    }

    /// Sets the label.
    pub fn label(mut self, label: impl Into<String>) -> Marker {
        self.label = Some(label.into());
        self
    }

    /// Sets the colour.
    pub fn color(mut self, color: Color) -> Marker {
        self.color = Some(color);
        self
    }
}

/// A generic x–y plot.
///
/// ```no_run
/// use ltikit::plot::{xy_png, Curve, LineStyle, Marker, MarkerShape, PlotOptions, XyPlot};
/// // A pull-in style diagram: stable branch solid, unstable dashed, the fold marked.
/// let stable: Vec<(f64, f64)> = (0..50).map(|k| { let l = 1.0 - k as f64 / 150.0; ((l * l * (1.0 - l)).sqrt(), l) }).collect();
/// let unstable: Vec<(f64, f64)> = (0..50).map(|k| { let l = 2.0 / 3.0 - k as f64 / 75.0; ((l * l * (1.0 - l)).sqrt(), l) }).collect();
/// let plot = XyPlot {
///     curves: vec![
///         Curve::new(stable).label("stable").color(ltikit::plot::PALETTE[0]),
///         Curve::new(unstable).label("unstable").style(LineStyle::Dashed).color(ltikit::plot::PALETTE[0]),
///     ],
///     markers: vec![Marker::new(((4.0f64 / 27.0).sqrt(), 2.0 / 3.0), MarkerShape::Disc).label("pull-in")],
///     x_label: "voltage v (V)".into(),
///     y_label: "gap l (m)".into(),
///     ..Default::default()
/// };
/// xy_png("/tmp/pullin.png", &plot, &PlotOptions::default()).unwrap();
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct XyPlot {
    /// Curves, drawn in order.
    pub curves: Vec<Curve>,
    /// Marked points, drawn over the curves.
    pub markers: Vec<Marker>,
    /// x-axis title (with units).
    pub x_label: String,
    /// y-axis title (with units).
    pub y_label: String,
    /// Equal data units per pixel on both axes.
    pub equal_aspect: bool,
    /// Fixed x range; automatic when `None`.
    pub x_range: Option<(f64, f64)>,
    /// Fixed y range; automatic when `None`.
    pub y_range: Option<(f64, f64)>,
    /// Extra legend rows (text only, e.g. a note or parameter values).
    pub notes: Vec<String>,
    /// Default title when [`PlotOptions::title`] is `None`.
    pub title: String,
    /// A base-10 logarithmic x axis (decades; points with x ≤ 0 are left out), e.g. the
    /// frequency axis of a sigma plot.
    pub x_log: bool,
}

fn check_range(r: Option<(f64, f64)>, what: &str) -> Result<()> {
    if let Some((a, b)) = r {
        if !(a.is_finite() && b.is_finite() && a < b) {
            return Err(LtiError::Plot(format!(
                "{what} range ({a}, {b}) must be finite and increasing"
            )));
        }
    }
    Ok(())
}

/// Checks every text of the plot against [`MAX_TEXT_CHARS`](super::options::MAX_TEXT_CHARS).
fn check_texts(plot: &XyPlot) -> Result<()> {
    check_text("the default title", &plot.title)?;
    check_text("the x-axis title", &plot.x_label)?;
    check_text("the y-axis title", &plot.y_label)?;
    for (k, c) in plot.curves.iter().enumerate() {
        check_label(k, c.label.as_deref())?;
    }
    for (k, m) in plot.markers.iter().enumerate() {
        if let Some(l) = &m.label {
            check_text(&format!("the label of marker {}", k + 1), l)?;
        }
    }
    for (k, n) in plot.notes.iter().enumerate() {
        check_text(&format!("note {}", k + 1), n)?;
    }
    Ok(())
}

/// Writes a generic x–y plot (see [`XyPlot`]).
///
/// Errors: no curve or marker with a finite point, a bad fixed range, bad options, a title,
/// axis title, label or note longer than [`MAX_TEXT_CHARS`](super::options::MAX_TEXT_CHARS)
/// characters, an unwritable path.
pub fn xy_png(path: impl AsRef<Path>, plot: &XyPlot, opts: &PlotOptions) -> Result<()> {
    xy_png_with(path.as_ref(), plot, &[], opts)
}

/// [`xy_png`] with extra legend rows (marker swatches) after the curves.
pub(super) fn xy_png_with(
    path: &Path,
    plot: &XyPlot,
    extra: &[LegendEntry],
    opts: &PlotOptions,
) -> Result<()> {
    check_range(plot.x_range, "x")?;
    check_range(plot.y_range, "y")?;
    check_texts(plot)?;
    let all = || {
        plot.curves
            .iter()
            .flat_map(|c| c.points.iter().copied())
            .chain(plot.markers.iter().map(|m| m.at))
            .filter(|p| p.0.is_finite() && p.1.is_finite())
    };
    let xb = plot
        .x_range
        .or_else(|| bounds(all().map(|p| p.0).filter(|&x| !plot.x_log || x > 0.0)));
    let yb = plot.y_range.or_else(|| bounds(all().map(|p| p.1)));
    let (Some(xb), Some(yb)) = (xb, yb) else {
        return Err(LtiError::Plot("no finite data points to plot".into()));
    };
    let xr = if plot.x_log {
        if xb.0 <= 0.0 {
            return Err(LtiError::Plot(
                "a logarithmic x axis needs positive x values".into(),
            ));
        }
        xb
    } else {
        padded(xb, plot.x_range.is_some())
    };
    let yr = padded(yb, plot.y_range.is_some());
    check_span("x values", xr)?;
    check_span("y values", yr)?;
    let title = opts.title_or(|| plot.title.clone());
    render(path, opts, |c, th| {
        let frame = layout(c, th, plot, (xr, yr), title.is_some());
        if opts.grid {
            frame.draw_grid(c, th);
        }
        let (mut legend, mut avoid) = draw_curves(c, th, &frame, &plot.curves);
        draw_markers(c, th, &frame, &plot.markers, &mut avoid)?;
        legend.extend(extra.iter().cloned());
        for n in &plot.notes {
            legend.push(LegendEntry {
                swatch: Swatch::None,
                text: n.clone(),
                color: Theme::NOTE,
            });
        }
        frame.draw_axes(c, th, true, true)?;
        frame.draw_axis_titles(
            c,
            th,
            non_empty(&plot.x_label),
            non_empty(&plot.y_label),
            th.pad,
        )?;
        draw_legend(
            c,
            &frame,
            th,
            &legend,
            &avoid,
            &[
                Corner::TopRight,
                Corner::TopLeft,
                Corner::BottomRight,
                Corner::BottomLeft,
            ],
            &[],
        )?;
        if let Some(t) = &title {
            draw_title(c, th, t)?;
        }
        Ok(())
    })
}

/// `Some(s)` unless `s` is empty.
fn non_empty(s: &str) -> Option<&str> {
    Some(s).filter(|s| !s.is_empty())
}

/// The drawn range for data bounds `r`: automatic ranges get 3 % of room on each side, fixed
/// ones are kept.
fn padded(r: (f64, f64), fixed: bool) -> (f64, f64) {
    if fixed {
        r
    } else {
        let d = (r.1 - r.0).abs().max(f64::MIN_POSITIVE) * 0.03;
        (r.0 - d, r.1 + d)
    }
}

/// The frame for the drawn ranges `(xr, yr)`, with equal units per pixel when asked.
fn layout(
    c: &Canvas,
    th: &Theme,
    plot: &XyPlot,
    (xr, yr): ((f64, f64), (f64, f64)),
    has_title: bool,
) -> Frame {
    layout_single(
        c,
        th,
        has_title,
        !plot.x_label.is_empty(),
        !plot.y_label.is_empty(),
        |w, h| {
            if plot.equal_aspect {
                equal_axes(xr, yr, w, h, th)
            } else {
                let (nx, ny) = tick_targets(w, h, th);
                (
                    if plot.x_log {
                        Axis::log(xr.0, xr.1, nx)
                    } else {
                        Axis::linear(xr.0, xr.1, nx, plot.x_range.is_some())
                    },
                    Axis::linear(yr.0, yr.1, ny, plot.y_range.is_some()),
                )
            }
        },
    )
}

/// The curves with their arrows; returns their legend rows and the pixel points to keep
/// legends off.
fn draw_curves(
    c: &mut Canvas,
    th: &Theme,
    frame: &Frame,
    curves: &[Curve],
) -> (Vec<LegendEntry>, Vec<(f64, f64)>) {
    let mut legend = Vec::new();
    let mut avoid = Vec::new();
    let mut auto_color = 0;
    for curve in curves {
        let color = curve.color.unwrap_or_else(|| {
            auto_color += 1;
            series_color(auto_color - 1)
        });
        let w = th.line
            * if curve.width > 0.0 && curve.width.is_finite() {
                curve.width
            } else {
                1.0
            };
        let runs = frame.clip_polyline(curve.points.iter().copied());
        let pattern = curve.style.pattern(w);
        for run in &runs {
            c.stroke(run, w, color, &pattern);
            avoid.extend(sample_run(run, 6.0));
        }
        arrows_along(
            c,
            &runs,
            curve.arrows,
            11.0 * th.s.max(0.8) + 2.0 * w,
            color,
        );
        if let Some(l) = &curve.label {
            legend.push(LegendEntry::line(l.clone(), color, curve.style));
        }
    }
    (legend, avoid)
}

/// The markers, with their labels to the upper right (upper left near the right edge); adds
/// the labelled positions to `avoid`.
fn draw_markers(
    c: &mut Canvas,
    th: &Theme,
    frame: &Frame,
    markers: &[Marker],
    avoid: &mut Vec<(f64, f64)>,
) -> Result<()> {
    for m in markers {
        let color = m.color.unwrap_or(Color::BLACK);
        frame.plot_marker(c, m.at, m.shape, 6.0 * th.s, color, th.line);
        if let (Some(l), true) = (&m.label, frame.contains(m.at)) {
            let p = frame.px(m.at);
            avoid.push(p);
            let x = p.0 + 9.0 * th.s;
            let right = x + Canvas::text_width(l, th.note) < frame.x1;
            let (x, h) = if right {
                (x, HAlign::Left)
            } else {
                (p.0 - 9.0 * th.s, HAlign::Right)
            };
            let b = c.text_on_box(
                l,
                (x, p.1 - 7.0 * th.s),
                th.note,
                color,
                (h, VAlign::Bottom),
            )?;
            avoid.extend(box_points(b));
        }
    }
    Ok(())
}

/// Time plot of several series y(t) against t (s), with a legend.
///
/// ```no_run
/// use ltikit::plot::{time_plot_png, Curve, PlotOptions};
/// let t: Vec<f64> = (0..200).map(|k| k as f64 * 0.05).collect();
/// let x1: Vec<f64> = t.iter().map(|t| (-0.2 * t).exp() * t.cos()).collect();
/// let c = Curve::from_xy(&t, &x1).unwrap().label("θ(t)");
/// time_plot_png("/tmp/theta.png", &[c], "angle θ (rad)", &PlotOptions::default()).unwrap();
/// ```
pub fn time_plot_png(
    path: impl AsRef<Path>,
    series: &[Curve],
    y_label: &str,
    opts: &PlotOptions,
) -> Result<()> {
    // Time runs exactly over the data: no padding before t0 or after the end.
    let x_range = bounds(series.iter().flat_map(|c| {
        c.points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|p| p.0)
    }))
    .filter(|r| r.1 > r.0);
    let plot = XyPlot {
        curves: series.to_vec(),
        x_range,
        x_label: "Time t (s)".into(),
        y_label: y_label.into(),
        title: "Time response".into(),
        ..Default::default()
    };
    xy_png(path, &plot, opts)
}

/// An equilibrium in a phase portrait: ● when (locally asymptotically) stable, ○ otherwise.
#[derive(Debug, Clone, PartialEq)]
pub struct Equilibrium {
    /// Position in the (x, y) plane of the portrait.
    pub at: (f64, f64),
    /// Stable (filled) or not (hollow).
    pub stable: bool,
    /// Optional name drawn next to it.
    pub label: Option<String>,
}

/// A phase portrait: trajectories with direction arrows, separatrices, equilibria.
///
/// ```no_run
/// use ltikit::plot::{phase_portrait_png, Curve, Equilibrium, PhasePortrait, PlotOptions};
/// // A damped oscillator spiralling into the origin.
/// let traj: Vec<(f64, f64)> = (0..400).map(|k| { let t = k as f64 * 0.05; let e = (-0.2 * t).exp(); (e * t.cos(), -e * t.sin()) }).collect();
/// let p = PhasePortrait {
///     trajectories: vec![Curve::new(traj)],
///     equilibria: vec![Equilibrium { at: (0.0, 0.0), stable: true, label: None }],
///     x_label: "x_{1}".into(),
///     y_label: "x_{2}".into(),
///     ..Default::default()
/// };
/// phase_portrait_png("/tmp/portrait.png", &p, &PlotOptions::default()).unwrap();
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PhasePortrait {
    /// Trajectories in time order (arrows are added where a curve has none requested).
    pub trajectories: Vec<Curve>,
    /// Separatrices (drawn dashed in dark grey unless styled otherwise).
    pub separatrices: Vec<Curve>,
    /// Equilibria.
    pub equilibria: Vec<Equilibrium>,
    /// x-axis title (first state, with units).
    pub x_label: String,
    /// y-axis title (second state, with units).
    pub y_label: String,
    /// Fixed x range.
    pub x_range: Option<(f64, f64)>,
    /// Fixed y range.
    pub y_range: Option<(f64, f64)>,
    /// Equal data units per pixel on both axes.
    pub equal_aspect: bool,
}

/// Writes a phase portrait (see [`PhasePortrait`]).
pub fn phase_portrait_png(
    path: impl AsRef<Path>,
    p: &PhasePortrait,
    opts: &PlotOptions,
) -> Result<()> {
    let mut curves = Vec::new();
    for s in &p.separatrices {
        let mut s = s.clone();
        if s.color.is_none() {
            s.color = Some(Color(90, 90, 90));
        }
        if s.style == LineStyle::Solid {
            s.style = LineStyle::Dashed;
        }
        curves.push(s);
    }
    for (k, t) in p.trajectories.iter().enumerate() {
        let mut t = t.clone();
        if t.arrows == 0 {
            t.arrows = 2;
        }
        if t.color.is_none() {
            t.color = Some(series_color(k));
        }
        curves.push(t);
    }
    let mut markers = Vec::new();
    for e in &p.equilibria {
        markers.push(Marker {
            at: e.at,
            shape: if e.stable {
                MarkerShape::Disc
            } else {
                MarkerShape::Circle
            },
            color: Some(Color::BLACK),
            label: e.label.clone(),
        });
    }
    let mut extra = Vec::new();
    if p.equilibria.iter().any(|e| e.stable) {
        extra.push(LegendEntry::marker(
            "stable equilibrium",
            MarkerShape::Disc,
            Color::BLACK,
        ));
    }
    if p.equilibria.iter().any(|e| !e.stable) {
        extra.push(LegendEntry::marker(
            "unstable equilibrium",
            MarkerShape::Circle,
            Color::BLACK,
        ));
    }
    let plot = XyPlot {
        curves,
        markers,
        x_label: p.x_label.clone(),
        y_label: p.y_label.clone(),
        equal_aspect: p.equal_aspect,
        x_range: p.x_range,
        y_range: p.y_range,
        notes: Vec::new(),
        title: "Phase portrait".into(),
        x_log: false,
    };
    xy_png_with(path.as_ref(), &plot, &extra, opts)
}
