//! Heat maps: a grid of values drawn as coloured cells with a colour bar, e.g. the
//! space–time picture qₙ(t) of a lattice (seed fig. 2.17), with optional overlay curves.

use std::path::Path;

use super::axes::Axis;
use super::frame::Frame;
use super::layout::{bottom_margin, bounds, draw_title, left_margin, tick_targets, top_margin};
use super::options::PlotOptions;
use super::raster::Canvas;
use super::raster::Color;
use super::render::render;
use super::style::{Theme, series_color};
use super::text::{HAlign, Measured, VAlign, cap_height, descent};
use super::xy::Curve;
use crate::error::{LtiError, Result};

/// The largest grid accepted (cells).
pub const MAX_HEATMAP_CELLS: usize = 16_000_000;

/// How values map to colours.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ColorMap {
    /// Blue – white – red (ColorBrewer RdBu), white at the middle of the range: for signed
    /// values such as displacements; the default range is symmetric, ±max|z|.
    #[default]
    Diverging,
    /// Dark violet – green – yellow (viridis): for magnitudes such as energies; the default
    /// range is min…max.
    Sequential,
}

const RDBU: [(u8, u8, u8); 11] = [
    (5, 48, 97),
    (33, 102, 172),
    (67, 147, 195),
    (146, 197, 222),
    (209, 229, 240),
    (247, 247, 247),
    (253, 219, 199),
    (244, 165, 130),
    (214, 96, 77),
    (178, 24, 43),
    (103, 0, 31),
];

const VIRIDIS: [(u8, u8, u8); 9] = [
    (68, 1, 84),
    (71, 45, 123),
    (59, 82, 139),
    (44, 114, 142),
    (33, 145, 140),
    (40, 174, 128),
    (94, 201, 98),
    (173, 220, 48),
    (253, 231, 37),
];

impl ColorMap {
    /// The colour at `u` ∈ [0, 1] (clamped; NaN gives grey).
    ///
    /// ```
    /// use ltikit::plot::{Color, ColorMap};
    /// assert_eq!(ColorMap::Diverging.color(0.5), Color(247, 247, 247));
    /// assert_eq!(ColorMap::Sequential.color(2.0), Color(253, 231, 37));
    /// ```
    pub fn color(self, u: f64) -> Color {
        if u.is_nan() {
            return Color(190, 190, 190);
        }
        let anchors: &[(u8, u8, u8)] = match self {
            ColorMap::Diverging => &RDBU,
            ColorMap::Sequential => &VIRIDIS,
        };
        let x = u.clamp(0.0, 1.0) * (anchors.len() - 1) as f64;
        let i = (x.floor() as usize).min(anchors.len() - 2);
        let f = x - i as f64;
        let (a, b) = (anchors[i], anchors[i + 1]);
        let mix = |p: u8, q: u8| (f64::from(p) + (f64::from(q) - f64::from(p)) * f).round() as u8;
        Color(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
    }
}

/// A heat map: `rows` × `columns` values filling the rectangle `x_range` × `y_range` in
/// equal cells (row 0 at the bottom, `y_range.0`; column 0 at the left).
///
/// ```no_run
/// use ltikit::plot::{heatmap_png, HeatMap, PlotOptions};
/// // A standing wave sin(x)·cos(t) on 64 × 100 cells.
/// let (nx, nt) = (64, 100);
/// let v: Vec<f64> = (0..nt).flat_map(|r| (0..nx).map(move |c| {
///     (c as f64 * 0.1).sin() * (r as f64 * 0.1).cos() })).collect();
/// let mut h = HeatMap::new(v, nx, nt, (0.0, 6.4), (0.0, 10.0)).unwrap();
/// h.x_label = "position x (m)".into();
/// h.y_label = "time t (s)".into();
/// h.z_label = "u(x, t)".into();
/// heatmap_png(std::env::temp_dir().join("wave.png"), &h, &PlotOptions::default()).unwrap();
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct HeatMap {
    /// Values, row by row (`values[r * columns + c]`); non-finite cells are drawn grey.
    pub values: Vec<f64>,
    /// Number of cells along x.
    pub columns: usize,
    /// Number of cells along y.
    pub rows: usize,
    /// Left edge of the first column and right edge of the last.
    pub x_range: (f64, f64),
    /// Bottom edge of the first row and top edge of the last.
    pub y_range: (f64, f64),
    /// Colour scale limits; automatic when `None` (see [`ColorMap`]).
    pub z_range: Option<(f64, f64)>,
    /// The colour map.
    pub colormap: ColorMap,
    /// x-axis title.
    pub x_label: String,
    /// y-axis title.
    pub y_label: String,
    /// Colour-bar title (the quantity and its unit).
    pub z_label: String,
    /// Curves drawn over the cells (clipped), e.g. characteristic lines.
    pub curves: Vec<Curve>,
    /// Default title when [`PlotOptions::title`] is `None`.
    pub title: String,
}

impl HeatMap {
    /// A heat map of `values` (row by row) on `columns` × `rows` cells; checks the sizes and
    /// the ranges.
    ///
    /// ```
    /// use ltikit::plot::HeatMap;
    /// assert!(HeatMap::new(vec![0.0; 6], 3, 2, (0.5, 3.5), (0.0, 1.0)).is_ok());
    /// assert!(HeatMap::new(vec![0.0; 5], 3, 2, (0.5, 3.5), (0.0, 1.0)).is_err());
    /// ```
    pub fn new(
        values: Vec<f64>,
        columns: usize,
        rows: usize,
        x_range: (f64, f64),
        y_range: (f64, f64),
    ) -> Result<HeatMap> {
        let h = HeatMap {
            values,
            columns,
            rows,
            x_range,
            y_range,
            ..Default::default()
        };
        h.validate()?;
        Ok(h)
    }

    fn validate(&self) -> Result<()> {
        super::options::check_text("the x-axis title", &self.x_label)?;
        super::options::check_text("the y-axis title", &self.y_label)?;
        super::options::check_text("the colour-bar title", &self.z_label)?;
        super::options::check_text("the title", &self.title)?;
        if self.columns == 0 || self.rows == 0 {
            return Err(LtiError::Plot(format!(
                "a heat map needs at least one cell, got {}×{}",
                self.columns, self.rows
            )));
        }
        let cells = self.columns.saturating_mul(self.rows);
        if cells > MAX_HEATMAP_CELLS {
            return Err(LtiError::Plot(format!(
                "a heat map of {}×{} cells exceeds the maximum of {MAX_HEATMAP_CELLS}",
                self.columns, self.rows
            )));
        }
        if self.values.len() != cells {
            return Err(LtiError::Plot(format!(
                "a heat map of {}×{} cells needs {cells} values, got {}",
                self.columns,
                self.rows,
                self.values.len()
            )));
        }
        for (what, r) in [
            ("x", Some(self.x_range)),
            ("y", Some(self.y_range)),
            ("z", self.z_range),
        ] {
            if let Some((a, b)) = r {
                if !(a.is_finite() && b.is_finite() && a < b) {
                    return Err(LtiError::Plot(format!(
                        "heat map {what} range ({a}, {b}) must be finite and increasing"
                    )));
                }
            }
        }
        Ok(())
    }

    /// The colour-scale limits: `z_range`, or from the finite values.
    fn z_limits(&self) -> (f64, f64) {
        if let Some(r) = self.z_range {
            return r;
        }
        let (lo, hi) = bounds(self.values.iter().copied()).unwrap_or((-1.0, 1.0));
        let (lo, hi) = match self.colormap {
            ColorMap::Diverging => {
                let m = lo.abs().max(hi.abs());
                (-m, m)
            }
            ColorMap::Sequential => (lo, hi),
        };
        super::axes::widen(lo, hi)
    }
}

/// The colour bar's geometry: bar rectangle and its axis.
struct Bar {
    x0: f64,
    x1: f64,
    axis: Axis,
}

/// Width (px) needed right of the frame for the colour bar, its labels and its title.
fn bar_room(th: &Theme, axis: &Axis, titled: bool) -> f64 {
    let gap = 16.0 * th.s;
    let width = 20.0 * th.s;
    let labels = 5.0 * th.s + axis.max_label_width(th.tick);
    let title = if titled {
        8.0 * th.s + cap_height(th.label) + descent(th.label)
    } else {
        0.0
    };
    gap + width + labels + title + th.pad
}

/// Lays out the frame and the colour bar on the canvas.
fn layout(c: &Canvas, th: &Theme, h: &HeatMap, titled: bool, z: (f64, f64)) -> (Frame, Bar) {
    let (cw, ch) = (f64::from(c.w), f64::from(c.h));
    let top = top_margin(th, titled, false);
    let axes = |w: f64, hh: f64| {
        let (nx, ny) = tick_targets(w, hh, th);
        (
            Axis::linear(h.x_range.0, h.x_range.1, nx, true),
            Axis::linear(h.y_range.0, h.y_range.1, ny, true),
            // Automatic limits are rounded out to the next tick when that costs little room.
            Axis::linear(z.0, z.1, ny, h.z_range.is_some()),
        )
    };
    let (mut l, mut r, mut b) = (80.0 * th.s, 120.0 * th.s, 70.0 * th.s);
    let mut ax = axes((cw - l - r).max(10.0), (ch - top - b).max(10.0));
    for _ in 0..2 {
        l = left_margin(th, &ax.1, !h.y_label.is_empty());
        r = bar_room(th, &ax.2, !h.z_label.is_empty());
        b = bottom_margin(th, &ax.0, !h.x_label.is_empty());
        ax = axes((cw - l - r).max(10.0), (ch - top - b).max(10.0));
    }
    let x1 = (cw - r).max(l + 10.0);
    let frame = Frame {
        x0: l,
        y0: top + if ax.2.factor.is_some() { th.tick } else { 0.0 },
        x1,
        y1: (ch - b).max(top + 10.0),
        x: ax.0,
        y: ax.1,
    };
    let bx0 = x1 + 16.0 * th.s;
    let bar = Bar {
        x0: bx0,
        x1: bx0 + 20.0 * th.s,
        axis: ax.2,
    };
    (frame, bar)
}

/// Fills the frame pixel by pixel with the colour of the cell under each pixel's centre.
fn draw_cells(c: &mut Canvas, f: &Frame, h: &HeatMap, z: (f64, f64)) {
    let (xs, ys) = (
        (h.x_range.1 - h.x_range.0) / (f.x1 - f.x0),
        (h.y_range.1 - h.y_range.0) / (f.y1 - f.y0),
    );
    let (cols, rows) = (h.columns as f64, h.rows as f64);
    let mut py = f.y0.floor();
    while py < f.y1 {
        let (ya, yb) = (py.max(f.y0), (py + 1.0).min(f.y1));
        let y = h.y_range.1 - (0.5 * (ya + yb) - f.y0) * ys;
        let r = (((y - h.y_range.0) / (h.y_range.1 - h.y_range.0) * rows).floor())
            .clamp(0.0, rows - 1.0) as usize;
        let mut px = f.x0.floor();
        while px < f.x1 {
            let (xa, xb) = (px.max(f.x0), (px + 1.0).min(f.x1));
            let x = h.x_range.0 + (0.5 * (xa + xb) - f.x0) * xs;
            let col = (((x - h.x_range.0) / (h.x_range.1 - h.x_range.0) * cols).floor())
                .clamp(0.0, cols - 1.0) as usize;
            let v = h.values[r * h.columns + col];
            let u = if v.is_finite() {
                (v - z.0) / (z.1 - z.0)
            } else {
                f64::NAN
            };
            c.fill_rect(xa, ya, xb, yb, h.colormap.color(u), 1.0);
            px += 1.0;
        }
        py += 1.0;
    }
}

/// The colour bar: a strip of the map, a frame, ticks with labels, the factor and the title.
fn draw_bar(c: &mut Canvas, th: &Theme, f: &Frame, bar: &Bar, h: &HeatMap) -> Result<()> {
    let (lo, hi) = (bar.axis.lo, bar.axis.hi);
    let (y0, y1) = (f.y0, f.y1);
    let mut py = y0.floor();
    while py < y1 {
        let (ya, yb) = (py.max(y0), (py + 1.0).min(y1));
        let u = (y1 - 0.5 * (ya + yb)) / (y1 - y0);
        c.fill_rect(bar.x0, ya, bar.x1, yb, h.colormap.color(u), 1.0);
        py += 1.0;
    }
    let lw = (th.s * 1.2).max(1.0);
    c.stroke(
        &[
            (bar.x0, y0),
            (bar.x1, y0),
            (bar.x1, y1),
            (bar.x0, y1),
            (bar.x0, y0),
        ],
        lw,
        Theme::AXIS,
        &[],
    );
    let tl = 5.0 * th.s;
    for t in &bar.axis.ticks {
        let py = y1 - (t.v - lo) / (hi - lo) * (y1 - y0);
        if !(py >= y0 - 0.5 && py <= y1 + 0.5) {
            continue;
        }
        c.stroke(&[(bar.x1, py), (bar.x1 - tl, py)], lw, Theme::AXIS, &[]);
        c.stroke(&[(bar.x0, py), (bar.x0 + tl, py)], lw, Theme::AXIS, &[]);
        c.text(
            &t.label,
            (bar.x1 + 5.0 * th.s, py),
            th.tick,
            Theme::AXIS,
            (HAlign::Left, VAlign::Middle),
        )?;
    }
    if let Some(fac) = &bar.axis.factor {
        c.text(
            fac,
            (bar.x0, y0 - 5.0 * th.s),
            th.tick,
            Theme::AXIS,
            (HAlign::Left, VAlign::Bottom),
        )?;
    }
    if !h.z_label.is_empty() {
        let x = bar.x1
            + 5.0 * th.s
            + bar.axis.max_label_width(th.tick)
            + 8.0 * th.s
            + 0.5 * cap_height(th.label);
        let t = Measured::new(&h.z_label, th.label).shortened(y1 - y0);
        c.text_up(&t, x, 0.5 * (y0 + y1), Theme::AXIS)?;
    }
    Ok(())
}

/// Writes a heat map with a colour bar (see [`HeatMap`]).
///
/// Errors: inconsistent sizes or ranges, more than [`MAX_HEATMAP_CELLS`] cells, bad options, an
/// unwritable path.
pub fn heatmap_png(path: impl AsRef<Path>, h: &HeatMap, opts: &PlotOptions) -> Result<()> {
    h.validate()?;
    let z = h.z_limits();
    let title = opts.title_or(|| h.title.clone());
    render(path.as_ref(), opts, |c, th| {
        let (frame, bar) = layout(c, th, h, title.is_some(), z);
        draw_cells(c, &frame, h, (bar.axis.lo, bar.axis.hi));
        for (i, curve) in h.curves.iter().enumerate() {
            let w = th.line * if curve.width > 0.0 { curve.width } else { 1.0 };
            let color = curve.color.unwrap_or_else(|| series_color(i));
            frame.plot_line(c, curve.points.iter().copied(), w, color, curve.style);
        }
        frame.draw_axes(c, th, true, true)?;
        frame.draw_axis_titles(
            c,
            th,
            Some(h.x_label.as_str()).filter(|s| !s.is_empty()),
            Some(h.y_label.as_str()).filter(|s| !s.is_empty()),
            th.pad,
        )?;
        draw_bar(c, th, &frame, &bar, h)?;
        if let Some(t) = &title {
            draw_title(c, th, t)?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_ranges_are_checked() {
        assert!(HeatMap::new(vec![0.0; 6], 3, 2, (0.0, 1.0), (0.0, 1.0)).is_ok());
        assert!(HeatMap::new(vec![0.0; 5], 3, 2, (0.0, 1.0), (0.0, 1.0)).is_err());
        assert!(HeatMap::new(vec![], 0, 2, (0.0, 1.0), (0.0, 1.0)).is_err());
        assert!(HeatMap::new(vec![0.0; 6], 3, 2, (1.0, 1.0), (0.0, 1.0)).is_err());
        assert!(HeatMap::new(vec![0.0; 6], 3, 2, (0.0, 1.0), (0.0, f64::NAN)).is_err());
    }

    #[test]
    fn automatic_colour_limits() {
        let mut h = HeatMap::new(vec![-1.0, 3.0], 2, 1, (0.0, 1.0), (0.0, 1.0)).unwrap();
        assert_eq!(h.z_limits(), (-3.0, 3.0));
        h.colormap = ColorMap::Sequential;
        assert_eq!(h.z_limits(), (-1.0, 3.0));
        h.values = vec![2.0, 2.0];
        let (lo, hi) = h.z_limits();
        assert!(lo < 2.0 && hi > 2.0);
    }

    #[test]
    fn colour_map_ends() {
        assert_eq!(ColorMap::Diverging.color(0.0), Color(5, 48, 97));
        assert_eq!(ColorMap::Diverging.color(1.0), Color(103, 0, 31));
        assert_eq!(ColorMap::Sequential.color(f64::NAN), Color(190, 190, 190));
    }
}
