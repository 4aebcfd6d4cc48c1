//! Nyquist diagram: G along the D contour (or, for a discrete plant, along the unit circle
//! z = e^(jωT)), with direction arrows, the −1 point and the encirclement count.

use std::path::Path;

use super::frame::Frame;
use super::layout::{bounds, check_span, draw_title, equal_axes, layout_single};
use super::legend::{Corner, LegendEntry, box_points, draw_legend, sample_run};
use super::options::{PlotOptions, check_label};
use super::raster::Canvas;
use super::raster::Color;
use super::render::render;
use super::style::{LineStyle, MarkerShape, Theme, arrows_along, series_color};
use super::text::{HAlign, VAlign};
use crate::analysis::NyquistContour;
use crate::error::{LtiError, Result};
use crate::fmt::fmt_sig;

/// One plant on a Nyquist diagram.
///
/// ```
/// use ltikit::TransferFunction;
/// use ltikit::plot::NyquistSeries;
/// let g = TransferFunction::from_descending(&[1.0], &[1.0, 2.0, 1.0]).unwrap();
/// let n = g.nyquist().unwrap();
/// let s = NyquistSeries::new(&n).label("1/(s + 1)^2");
/// assert!(s.color.is_none());
/// ```
#[derive(Debug, Clone, Copy)]
pub struct NyquistSeries<'a> {
    /// The contour computed by [`crate::analysis::nyquist_contour`].
    pub contour: &'a NyquistContour,
    /// Legend text.
    pub label: Option<&'a str>,
    /// Colour; `None` takes the palette colour of the series' position.
    pub color: Option<Color>,
}

impl<'a> NyquistSeries<'a> {
    /// A series for `contour`.
    pub fn new(contour: &'a NyquistContour) -> Self {
        NyquistSeries {
            contour,
            label: None,
            color: None,
        }
    }

    /// Sets the legend label.
    pub fn label(mut self, label: &'a str) -> Self {
        self.label = Some(label);
        self
    }

    /// Sets the colour.
    pub fn color(mut self, color: Color) -> Self {
        self.color = Some(color);
        self
    }
}

/// How a stretch of the curve is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Style {
    /// ω ≥ 0 (solid) or the mirror image ω < 0 (dashed).
    positive: bool,
    /// Beyond the display radius: drawn on the circle of that radius (dotted).
    scaled: bool,
}

/// A stretch of the displayed curve drawn in one style.
type Run = (Style, Vec<(f64, f64)>);

/// Splits the contour into runs of one style, mapping |G| > r onto the circle of radius r.
fn runs(contour: &NyquistContour, radius: Option<f64>) -> Vec<Run> {
    let mut out: Vec<Run> = Vec::new();
    for p in &contour.points {
        let g = p.g;
        if !(g.re.is_finite() && g.im.is_finite()) {
            continue;
        }
        let (shown, scaled) = match radius {
            Some(r) if g.norm() > r => (g * (r / g.norm()), true),
            _ => (g, false),
        };
        let style = Style {
            positive: p.s.im >= 0.0,
            scaled,
        };
        let pt = (shown.re, shown.im);
        match out.last_mut() {
            Some((s, run)) if *s == style => run.push(pt),
            Some((_, run)) => {
                let last = *run.last().unwrap_or(&pt);
                out.push((style, vec![last, pt]));
            }
            None => out.push((style, vec![pt])),
        }
    }
    out
}

/// Writes a Nyquist diagram of one or more plants: G(jω) for ω from −∞ to +∞ (ω > 0 solid,
/// the mirror image ω < 0 dashed) with direction arrows, the −1 point, the unit circle, and
/// the indentations around imaginary-axis poles. Where the curve heads to infinity near such
/// poles, |G| beyond the contour's display radius is drawn on that circle (dotted), so the
/// arcs at infinity keep their direction. The encirclement count N, the open-loop RHP poles P
/// and Z = N + P are listed.
///
/// Errors: no series, a series without finite points, bad options, a title or label longer
/// than [`MAX_TEXT_CHARS`](super::options::MAX_TEXT_CHARS) characters, an unwritable path; no file is
/// left behind.
///
/// ```no_run
/// use ltikit::TransferFunction;
/// use ltikit::plot::{nyquist_png, NyquistSeries, PlotOptions};
/// let g = TransferFunction::from_descending(&[2.0], &[1.0, 3.0, 2.0, 0.0]).unwrap();
/// let n = g.nyquist().unwrap();
/// nyquist_png("/tmp/nyquist.png", &[NyquistSeries::new(&n).label("2/(s(s+1)(s+2))")], &PlotOptions::default()).unwrap();
/// ```
pub fn nyquist_png(
    path: impl AsRef<Path>,
    series: &[NyquistSeries],
    opts: &PlotOptions,
) -> Result<()> {
    if series.is_empty() {
        return Err(LtiError::Plot("Nyquist plot: no contour given".into()));
    }
    for (k, s) in series.iter().enumerate() {
        check_label(k, s.label)?;
        if !s
            .contour
            .points
            .iter()
            .any(|p| p.g.re.is_finite() && p.g.im.is_finite())
        {
            return Err(LtiError::Plot(format!(
                "Nyquist plot: series {} has no finite point",
                k + 1
            )));
        }
    }
    let title = opts.title_or(|| match (series.len(), series[0].label) {
        (1, Some(l)) => format!(
            "Nyquist diagram of G({}) = {l}",
            if series[0].contour.dt.is_some() {
                "z"
            } else {
                "s"
            }
        ),
        _ => "Nyquist diagram".into(),
    });
    render(path.as_ref(), opts, |c, th| {
        draw(c, th, series, opts, title.as_deref())
    })
}

/// The colour of series `k`: its own, or the palette's.
fn color_of(series: &[NyquistSeries], k: usize) -> Color {
    series[k].color.unwrap_or_else(|| series_color(k))
}

/// Equal-aspect axes around every displayed point, −1 and the origin.
fn layout(c: &Canvas, th: &Theme, all_runs: &[Vec<Run>], has_title: bool) -> Result<Frame> {
    let pts = || {
        all_runs
            .iter()
            .flatten()
            .flat_map(|(_, r)| r.iter().copied())
            .chain([(-1.0, 0.0), (0.0, 0.0)])
    };
    let (xlo, xhi) = bounds(pts().map(|p| p.0)).unwrap_or((-1.0, 1.0));
    let (ylo, yhi) = bounds(pts().map(|p| p.1)).unwrap_or((-1.0, 1.0));
    let pad = 0.08 * (xhi - xlo).max(yhi - ylo).max(1e-9);
    let (xr, yr) = ((xlo - pad, xhi + pad), (ylo - pad, yhi + pad));
    check_span("real parts", xr)?;
    check_span("imaginary parts", yr)?;
    Ok(layout_single(c, th, has_title, true, true, |w, h| {
        equal_axes(xr, yr, w, h, th)
    }))
}

/// Grid, the axes through the origin, the unit circle and the display-radius circle.
fn draw_background(c: &mut Canvas, th: &Theme, frame: &Frame, grid: bool, radius: Option<f64>) {
    if grid {
        frame.draw_grid(c, th);
    }
    let thin = (th.line * 0.6).max(1.0);
    frame.vline(c, 0.0, thin, Color(120, 120, 120), LineStyle::Solid);
    frame.hline(c, 0.0, thin, Color(120, 120, 120), LineStyle::Solid);
    let circle = |r: f64| {
        (0..=180).map(move |i| {
            let a = std::f64::consts::TAU * i as f64 / 180.0;
            (r * a.cos(), r * a.sin())
        })
    };
    frame.plot_line(
        c,
        circle(1.0),
        thin,
        Color(150, 150, 150),
        LineStyle::Dotted,
    );
    if let Some(r) = radius {
        frame.plot_line(c, circle(r), thin, Color(200, 200, 200), LineStyle::Solid);
    }
}

/// The curves (ω > 0 solid, ω < 0 dashed, beyond the display radius dotted) with direction
/// arrows; returns the pixel points to keep legends off.
fn draw_curves(
    c: &mut Canvas,
    th: &Theme,
    frame: &Frame,
    all_runs: &[Vec<Run>],
    colors: &[Color],
) -> Vec<(f64, f64)> {
    let mut avoid = Vec::new();
    let arrow = 12.0 * th.s.max(0.8);
    for (rs, &col) in all_runs.iter().zip(colors) {
        let mut pos = Vec::new();
        let mut neg = Vec::new();
        let mut far = Vec::new();
        for (style, run) in rs {
            let line = match (style.scaled, style.positive) {
                (true, _) => LineStyle::Dotted,
                (false, true) => LineStyle::Solid,
                (false, false) => LineStyle::Dashed,
            };
            let px = frame.clip_polyline(run.iter().copied());
            for r in &px {
                c.stroke(r, th.line, col, &line.pattern(th.line));
                avoid.extend(sample_run(r, 6.0));
            }
            match (style.scaled, style.positive) {
                (true, _) => far.push(px),
                (false, true) => pos.extend(px),
                (false, false) => neg.extend(px),
            }
        }
        arrows_along(c, &pos, 2, arrow, col);
        arrows_along(c, &neg, 2, arrow, col);
        for f in &far {
            arrows_along(c, f, 1, arrow, col);
        }
    }
    avoid
}

/// The critical point −1, marked and labelled; adds the mark and its label to `avoid`.
fn draw_critical_point(
    c: &mut Canvas,
    th: &Theme,
    frame: &Frame,
    avoid: &mut Vec<(f64, f64)>,
) -> Result<()> {
    frame.plot_marker(
        c,
        (-1.0, 0.0),
        MarkerShape::Plus,
        7.0 * th.s,
        Color(200, 0, 0),
        th.line * 1.2,
    );
    if frame.contains((-1.0, 0.0)) {
        let p = frame.px((-1.0, 0.0));
        avoid.push(p);
        let b = c.text_on_box(
            "−1",
            (p.0 - 6.0 * th.s, p.1 + 8.0 * th.s),
            th.note,
            Color(200, 0, 0),
            (HAlign::Right, VAlign::Top),
        )?;
        avoid.extend(box_points(b));
    }
    Ok(())
}

/// Which contour the series were computed on: all continuous (the D contour), all discrete
/// (the unit circle), or a mixture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    S,
    Z,
    Mixed,
}

fn kind_of(series: &[NyquistSeries]) -> Kind {
    let discrete = series.iter().filter(|s| s.contour.dt.is_some()).count();
    match discrete {
        0 => Kind::S,
        n if n == series.len() => Kind::Z,
        _ => Kind::Mixed,
    }
}

/// The legend: line styles (one plant) or plants, the verdict N, P, Z of each, and the
/// display-radius note.
fn legend_rows(series: &[NyquistSeries], radius: Option<f64>) -> Vec<LegendEntry> {
    let several = series.len() > 1;
    let kind = kind_of(series);
    let (pos, neg) = match kind {
        Kind::Z => ("0 ≤ ω ≤ π/T", "−π/T ≤ ω < 0 (mirror)"),
        _ => ("ω > 0", "ω < 0 (mirror)"),
    };
    let mut legend = Vec::new();
    for (k, s) in series.iter().enumerate() {
        let name = s
            .label
            .map(str::to_string)
            .unwrap_or_else(|| format!("G{}", k + 1));
        if several {
            legend.push(LegendEntry::line(
                format!("{name} ({pos})"),
                color_of(series, k),
                LineStyle::Solid,
            ));
        }
        let n = s.contour;
        let prefix = if several {
            format!("{name}: ")
        } else {
            String::new()
        };
        // where P and Z are counted: the right half plane, or outside the unit circle
        let region = if n.dt.is_some() {
            " (outside |z| = 1)"
        } else {
            ""
        };
        let verdict = match (n.encirclements, n.closed_loop_rhp_poles) {
            (Some(nn), Some(z)) => format!(
                "{prefix}N = {nn}, P = {}{region} → Z = N + P = {z}{}",
                n.open_loop_rhp_poles,
                if z == 0 {
                    " (closed loop stable)"
                } else {
                    " (closed loop unstable)"
                }
            ),
            _ => format!("{prefix}the curve passes through −1: N undefined"),
        };
        legend.push(LegendEntry::text(verdict, color_of(series, k)));
    }
    if !several {
        let col = color_of(series, 0);
        legend.insert(0, LegendEntry::line(pos, col, LineStyle::Solid));
        legend.insert(1, LegendEntry::line(neg, col, LineStyle::Dashed));
    }
    if let Some(r) = radius {
        legend.push(LegendEntry::line(
            format!("|G| > {} drawn at radius {}", fmt_sig(r, 3), fmt_sig(r, 3)),
            Color(110, 110, 110),
            LineStyle::Dotted,
        ));
    }
    legend
}

fn draw(
    c: &mut Canvas,
    th: &Theme,
    series: &[NyquistSeries],
    opts: &PlotOptions,
    title: Option<&str>,
) -> Result<()> {
    let radius = series
        .iter()
        .filter_map(|s| s.contour.display_radius)
        .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.max(r))));
    let all_runs: Vec<Vec<Run>> = series.iter().map(|s| runs(s.contour, radius)).collect();
    let frame = layout(c, th, &all_runs, title.is_some())?;
    draw_background(c, th, &frame, opts.grid, radius);
    let colors: Vec<Color> = (0..series.len()).map(|k| color_of(series, k)).collect();
    let mut avoid = draw_curves(c, th, &frame, &all_runs, &colors);
    draw_critical_point(c, th, &frame, &mut avoid)?;
    frame.draw_axes(c, th, true, true)?;
    let (re, im) = match kind_of(series) {
        Kind::S => ("Real axis Re G(jω)", "Imaginary axis Im G(jω)"),
        Kind::Z => ("Real axis Re G(e^(jωT))", "Imaginary axis Im G(e^(jωT))"),
        Kind::Mixed => ("Real axis Re G", "Imaginary axis Im G"),
    };
    frame.draw_axis_titles(c, th, Some(re), Some(im), th.pad)?;
    draw_legend(
        c,
        &frame,
        th,
        &legend_rows(series, radius),
        &avoid,
        &[
            Corner::TopRight,
            Corner::TopLeft,
            Corner::BottomRight,
            Corner::BottomLeft,
        ],
        &[],
    )?;
    if let Some(t) = title {
        draw_title(c, th, t)?;
    }
    Ok(())
}
