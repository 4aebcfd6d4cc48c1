//! Colours, line styles, markers and the size theme shared by every plot.

use super::options::PlotOptions;
use super::raster::Canvas;

pub use super::raster::Color;

/// The series colours, in order (the "tab10" palette engineers know from matplotlib).
pub const PALETTE: [Color; 10] = [
    Color(31, 119, 180),
    Color(214, 39, 40),
    Color(44, 160, 44),
    Color(255, 127, 14),
    Color(148, 103, 189),
    Color(140, 86, 75),
    Color(227, 119, 194),
    Color(127, 127, 127),
    Color(188, 189, 34),
    Color(23, 190, 207),
];

/// The colour of series number `i` (cycling through [`PALETTE`]).
///
/// ```
/// use ltikit::plot::{series_color, PALETTE};
/// assert_eq!(series_color(0), PALETTE[0]);
/// assert_eq!(series_color(10), PALETTE[0]);
/// ```
pub fn series_color(i: usize) -> Color {
    PALETTE[i % PALETTE.len()]
}

/// How a curve is stroked.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LineStyle {
    /// Continuous line.
    #[default]
    Solid,
    /// Long dashes (e.g. an unstable branch, a mirror image, an asymptote).
    Dashed,
    /// Dots.
    Dotted,
    /// Dash-dot.
    DashDot,
}

impl LineStyle {
    /// The on/off pattern in pixels for a line of width `w`.
    pub(crate) fn pattern(self, w: f64) -> Vec<f64> {
        let u = w.max(1.0);
        match self {
            LineStyle::Solid => vec![],
            LineStyle::Dashed => vec![5.0 * u, 3.5 * u],
            LineStyle::Dotted => vec![0.6 * u, 2.4 * u],
            LineStyle::DashDot => vec![5.0 * u, 2.5 * u, 0.6 * u, 2.5 * u],
        }
    }
}

/// Point markers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MarkerShape {
    /// × (a pole).
    Cross,
    /// ○ hollow circle (a zero, an unstable equilibrium).
    Circle,
    /// ● filled circle (a stable equilibrium, a data point).
    Disc,
    /// □ hollow square.
    Square,
    /// ◆ filled diamond.
    Diamond,
    /// + plus.
    Plus,
    /// ▲ filled triangle.
    Triangle,
    /// ⊗ circle with a cross (a cancelled pole-zero pair).
    CircledCross,
}

/// Sizes derived from the options: one scale for fonts and line widths.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Theme {
    /// Overall scale (1 at 1000×700 with `font_scale` 1).
    pub s: f64,
    pub tick: f64,
    pub label: f64,
    pub title: f64,
    pub note: f64,
    pub line: f64,
    pub pad: f64,
}

impl Theme {
    pub fn new(opts: &PlotOptions) -> Theme {
        let (w, h) = (f64::from(opts.size.0), f64::from(opts.size.1));
        let auto = (w / 1000.0).min(h / 700.0).clamp(0.7, 4.0);
        // Text may not eat the plot: beyond this the margins would swallow the frames.
        let room = (w / 450.0).min(h / 320.0).max(0.45);
        let s = (opts.font_scale * auto).min(room);
        let ls = auto * opts.line_scale;
        Theme {
            s,
            tick: 18.0 * s,
            label: 20.0 * s,
            title: 23.0 * s,
            note: 17.0 * s,
            line: 2.0 * ls,
            pad: 10.0 * auto.min(room),
        }
    }

    /// Axis frame and tick colour.
    pub const AXIS: Color = Color(40, 40, 40);
    /// Major grid colour.
    pub const GRID: Color = Color(215, 215, 215);
    /// Minor grid colour.
    pub const GRID_MINOR: Color = Color(236, 236, 236);
    /// Annotation colour (reference lines, notes).
    pub const NOTE: Color = Color(70, 70, 70);
}

/// Draws a marker of "radius" `r` px centred at `p`.
pub(crate) fn draw_marker(
    c: &mut Canvas,
    p: (f64, f64),
    shape: MarkerShape,
    r: f64,
    color: Color,
    lw: f64,
) {
    let (x, y) = p;
    match shape {
        MarkerShape::Cross => {
            let d = r * 0.85;
            c.stroke(&[(x - d, y - d), (x + d, y + d)], lw, color, &[]);
            c.stroke(&[(x - d, y + d), (x + d, y - d)], lw, color, &[]);
        }
        MarkerShape::Plus => {
            c.stroke(&[(x - r, y), (x + r, y)], lw, color, &[]);
            c.stroke(&[(x, y - r), (x, y + r)], lw, color, &[]);
        }
        MarkerShape::Circle => {
            c.fill_circle(p, r, Color::WHITE);
            c.ring(p, r, lw, color);
        }
        MarkerShape::Disc => c.fill_circle(p, r, color),
        MarkerShape::Square => {
            let d = r * 0.85;
            c.fill_rect(x - d, y - d, x + d, y + d, Color::WHITE, 1.0);
            c.stroke(
                &[
                    (x - d, y - d),
                    (x + d, y - d),
                    (x + d, y + d),
                    (x - d, y + d),
                    (x - d, y - d),
                ],
                lw,
                color,
                &[],
            );
        }
        MarkerShape::Diamond => {
            c.fill_polygon(
                &[(x, y - r * 1.2), (x + r, y), (x, y + r * 1.2), (x - r, y)],
                color,
                1.0,
            );
        }
        MarkerShape::CircledCross => {
            c.fill_circle(p, r, Color::WHITE);
            c.ring(p, r, lw, color);
            let d = r * 0.62;
            c.stroke(&[(x - d, y - d), (x + d, y + d)], lw, color, &[]);
            c.stroke(&[(x - d, y + d), (x + d, y - d)], lw, color, &[]);
        }
        MarkerShape::Triangle => {
            c.fill_polygon(
                &[
                    (x, y - r * 1.15),
                    (x + r, y + r * 0.7),
                    (x - r, y + r * 0.7),
                ],
                color,
                1.0,
            );
        }
    }
}

/// Draws a filled arrow head at `tip`, pointing along `dir` (pixels, need not be unit).
pub(crate) fn draw_arrow_head(
    c: &mut Canvas,
    tip: (f64, f64),
    dir: (f64, f64),
    len: f64,
    color: Color,
) {
    let n = (dir.0 * dir.0 + dir.1 * dir.1).sqrt();
    if n.is_nan() || n <= 0.0 || !n.is_finite() {
        return;
    }
    let (ux, uy) = (dir.0 / n, dir.1 / n);
    let (px, py) = (-uy, ux);
    let half = len * 0.45;
    let base = (tip.0 - ux * len, tip.1 - uy * len);
    let notch = (tip.0 - ux * len * 0.75, tip.1 - uy * len * 0.75);
    c.fill_polygon(
        &[
            tip,
            (base.0 + px * half, base.1 + py * half),
            notch,
            (base.0 - px * half, base.1 - py * half),
        ],
        color,
        1.0,
    );
}

/// Draws `n` arrow heads along pixel runs at arc-length fractions (k + ½)/n, pointing forward.
pub(crate) fn arrows_along(
    c: &mut Canvas,
    runs: &[Vec<(f64, f64)>],
    n: usize,
    len: f64,
    color: Color,
) {
    if n == 0 {
        return;
    }
    let seg_len = |a: (f64, f64), b: (f64, f64)| ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
    let total: f64 = runs
        .iter()
        .flat_map(|r| r.windows(2))
        .map(|w| seg_len(w[0], w[1]))
        .sum();
    if total < 3.0 * len {
        return;
    }
    let mut targets: Vec<f64> = (0..n)
        .map(|k| total * (k as f64 + 0.5) / n as f64)
        .collect();
    targets.reverse();
    let mut acc = 0.0;
    for run in runs {
        for w in run.windows(2) {
            let l = seg_len(w[0], w[1]);
            while let Some(&t) = targets.last() {
                if t > acc + l || l <= 0.0 {
                    break;
                }
                targets.pop();
                let f = (t - acc) / l;
                let tip = (
                    w[0].0 + (w[1].0 - w[0].0) * f,
                    w[0].1 + (w[1].1 - w[0].1) * f,
                );
                // Direction from a point a little behind, for a smooth heading on dense curves.
                let back = point_behind(run, w, f, len);
                let dir = (tip.0 - back.0, tip.1 - back.1);
                let n = (dir.0 * dir.0 + dir.1 * dir.1).sqrt();
                if n.is_nan() || n <= 0.0 {
                    continue;
                }
                // Centre the head on the curve position.
                let tip = (tip.0 + dir.0 / n * len / 2.0, tip.1 + dir.1 / n * len / 2.0);
                draw_arrow_head(c, tip, dir, len, color);
            }
            acc += l;
        }
    }
}

/// The point about `dist` px before the position `f` along segment `w` of `run` (or the run's
/// start).
fn point_behind(run: &[(f64, f64)], w: &[(f64, f64)], f: f64, dist: f64) -> (f64, f64) {
    let here = (
        w[0].0 + (w[1].0 - w[0].0) * f,
        w[0].1 + (w[1].1 - w[0].1) * f,
    );
    // Index of w[0] in run.
    let idx = run
        .windows(2)
        .position(|x| std::ptr::eq(x.as_ptr(), w.as_ptr()))
        .unwrap_or(0);
    let mut need = dist * 0.5;
    let mut cur = here;
    let mut k = idx as isize;
    while k >= 0 {
        let p = run[k as usize];
        let l = ((cur.0 - p.0).powi(2) + (cur.1 - p.1).powi(2)).sqrt();
        if l >= need {
            let g = need / l;
            return (cur.0 + (p.0 - cur.0) * g, cur.1 + (p.1 - cur.1) * g);
        }
        need -= l;
        cur = p;
        k -= 1;
    }
    cur
}
