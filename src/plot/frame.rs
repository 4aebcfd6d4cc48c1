//! The plot frame: data → pixel mapping, clipping (Liang–Barsky), grid, ticks, axis titles.

use super::axes::Axis;
use super::raster::Canvas;
use super::raster::Color;
use super::style::{LineStyle, MarkerShape, Theme, draw_marker};
use super::text::{HAlign, Measured, VAlign, cap_height};
use crate::error::Result;

/// Liang–Barsky: clips segment a–b to the rectangle; returns the parameters [t0, t1].
fn clip(a: (f64, f64), b: (f64, f64), r: (f64, f64, f64, f64)) -> Option<(f64, f64)> {
    let (xmin, xmax, ymin, ymax) = r;
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let mut t0: f64 = 0.0;
    let mut t1: f64 = 1.0;
    for (p, q) in [
        (-dx, a.0 - xmin),
        (dx, xmax - a.0),
        (-dy, a.1 - ymin),
        (dy, ymax - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
            if t0 > t1 {
                return None;
            }
        }
    }
    Some((t0, t1))
}

/// The plot rectangle (pixels) with its two axes.
#[derive(Debug, Clone)]
pub(crate) struct Frame {
    pub x0: f64,
    pub y0: f64,
    pub x1: f64,
    pub y1: f64,
    pub x: Axis,
    pub y: Axis,
}

impl Frame {
    /// Pixel position of axis coordinates.
    pub fn px_t(&self, tx: f64, ty: f64) -> (f64, f64) {
        let (ax, bx) = (self.x.t(self.x.lo), self.x.t(self.x.hi));
        let (ay, by) = (self.y.t(self.y.lo), self.y.t(self.y.hi));
        (
            self.x0 + (tx - ax) / (bx - ax) * (self.x1 - self.x0),
            self.y1 - (ty - ay) / (by - ay) * (self.y1 - self.y0),
        )
    }

    /// Pixel position of a data point (may lie outside the frame; NaN if not on the scale).
    pub fn px(&self, p: (f64, f64)) -> (f64, f64) {
        self.px_t(self.x.t(p.0), self.y.t(p.1))
    }

    /// Whether a data point is inside the frame.
    pub fn contains(&self, p: (f64, f64)) -> bool {
        let (tx, ty) = (self.x.t(p.0), self.y.t(p.1));
        let (ax, bx) = (self.x.t(self.x.lo), self.x.t(self.x.hi));
        let (ay, by) = (self.y.t(self.y.lo), self.y.t(self.y.hi));
        tx >= ax.min(bx) && tx <= ax.max(bx) && ty >= ay.min(by) && ty <= ay.max(by)
    }

    /// Clips a data polyline to the frame: pixel runs (non-finite points break the line).
    pub fn clip_polyline(&self, pts: impl IntoIterator<Item = (f64, f64)>) -> Vec<Vec<(f64, f64)>> {
        let (ax, bx) = (self.x.t(self.x.lo), self.x.t(self.x.hi));
        let (ay, by) = (self.y.t(self.y.lo), self.y.t(self.y.hi));
        // A hair outside the frame so that lines on the border are kept.
        let ex = (bx - ax).abs() * 1e-6;
        let ey = (by - ay).abs() * 1e-6;
        let rect = (
            ax.min(bx) - ex,
            ax.max(bx) + ex,
            ay.min(by) - ey,
            ay.max(by) + ey,
        );
        let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
        let mut cur: Vec<(f64, f64)> = Vec::new();
        let mut prev: Option<(f64, f64)> = None;
        let close = |cur: &mut Vec<(f64, f64)>, runs: &mut Vec<Vec<(f64, f64)>>| {
            if !cur.is_empty() {
                runs.push(std::mem::take(cur));
            }
        };
        for p in pts {
            let q = (self.x.t(p.0), self.y.t(p.1));
            if !(q.0.is_finite() && q.1.is_finite()) {
                close(&mut cur, &mut runs);
                prev = None;
                continue;
            }
            if let Some(a) = prev {
                match clip(a, q, rect) {
                    Some((t0, t1)) => {
                        let pa = (a.0 + (q.0 - a.0) * t0, a.1 + (q.1 - a.1) * t0);
                        let pb = (a.0 + (q.0 - a.0) * t1, a.1 + (q.1 - a.1) * t1);
                        if t0 > 0.0 || cur.is_empty() {
                            close(&mut cur, &mut runs);
                            cur.push(self.px_t(pa.0, pa.1));
                        }
                        cur.push(self.px_t(pb.0, pb.1));
                        if t1 < 1.0 {
                            close(&mut cur, &mut runs);
                        }
                    }
                    None => close(&mut cur, &mut runs),
                }
            } else if q.0 >= rect.0 && q.0 <= rect.1 && q.1 >= rect.2 && q.1 <= rect.3 {
                cur.push(self.px_t(q.0, q.1));
            }
            prev = Some(q);
        }
        close(&mut cur, &mut runs);
        runs
    }

    /// Strokes a data polyline clipped to the frame.
    pub fn plot_line(
        &self,
        c: &mut Canvas,
        pts: impl IntoIterator<Item = (f64, f64)>,
        width: f64,
        color: Color,
        style: LineStyle,
    ) {
        let pattern = style.pattern(width);
        for run in self.clip_polyline(pts) {
            c.stroke(&run, width, color, &pattern);
        }
    }

    /// Draws a marker at a data point if it is inside the frame.
    pub fn plot_marker(
        &self,
        c: &mut Canvas,
        p: (f64, f64),
        shape: MarkerShape,
        r: f64,
        color: Color,
        lw: f64,
    ) {
        if self.contains(p) {
            draw_marker(c, self.px(p), shape, r, color, lw);
        }
    }

    /// Vertical line at data x across the frame.
    pub fn vline(&self, c: &mut Canvas, x: f64, width: f64, color: Color, style: LineStyle) {
        self.plot_line(c, [(x, self.y.lo), (x, self.y.hi)], width, color, style);
    }

    /// Horizontal line at data y across the frame.
    pub fn hline(&self, c: &mut Canvas, y: f64, width: f64, color: Color, style: LineStyle) {
        self.plot_line(c, [(self.x.lo, y), (self.x.hi, y)], width, color, style);
    }

    /// Grid lines (minor, then major).
    pub fn draw_grid(&self, c: &mut Canvas, th: &Theme) {
        let w = (th.s * 1.0).max(1.0);
        for &v in &self.x.minor {
            self.vline(c, v, w, Theme::GRID_MINOR, LineStyle::Solid);
        }
        for &v in &self.y.minor {
            self.hline(c, v, w, Theme::GRID_MINOR, LineStyle::Solid);
        }
        for t in &self.x.ticks {
            self.vline(c, t.v, w, Theme::GRID, LineStyle::Solid);
        }
        for t in &self.y.ticks {
            self.hline(c, t.v, w, Theme::GRID, LineStyle::Solid);
        }
    }

    /// Frame box, tick marks and (optionally) tick labels.
    pub fn draw_axes(
        &self,
        c: &mut Canvas,
        th: &Theme,
        x_labels: bool,
        y_labels: bool,
    ) -> Result<()> {
        let lw = (th.s * 1.2).max(1.0);
        let (x0, y0, x1, y1) = (self.x0, self.y0, self.x1, self.y1);
        c.stroke(
            &[(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)],
            lw,
            Theme::AXIS,
            &[],
        );
        let tl = 6.0 * th.s;
        let gap = 5.0 * th.s;
        for t in &self.x.ticks {
            let (px, _) = self.px((t.v, self.y.lo));
            if !px.is_finite() || px < x0 - 0.5 || px > x1 + 0.5 {
                continue;
            }
            c.stroke(&[(px, y1), (px, y1 - tl)], lw, Theme::AXIS, &[]);
            c.stroke(&[(px, y0), (px, y0 + tl)], lw, Theme::AXIS, &[]);
            if x_labels {
                let extra = if self.x.has_superscripts() {
                    0.3 * th.tick
                } else {
                    0.0
                };
                c.text(
                    &t.label,
                    (px, y1 + gap + extra),
                    th.tick,
                    Theme::AXIS,
                    (HAlign::Center, VAlign::Top),
                )?;
            }
        }
        for t in &self.y.ticks {
            let (_, py) = self.px((self.x.lo, t.v));
            if !py.is_finite() || py < y0 - 0.5 || py > y1 + 0.5 {
                continue;
            }
            c.stroke(&[(x0, py), (x0 + tl, py)], lw, Theme::AXIS, &[]);
            c.stroke(&[(x1, py), (x1 - tl, py)], lw, Theme::AXIS, &[]);
            if y_labels {
                c.text(
                    &t.label,
                    (x0 - gap, py),
                    th.tick,
                    Theme::AXIS,
                    (HAlign::Right, VAlign::Middle),
                )?;
            }
        }
        if y_labels {
            if let Some(f) = &self.y.factor {
                c.text(
                    f,
                    (x0, y0 - gap),
                    th.tick,
                    Theme::AXIS,
                    (HAlign::Left, VAlign::Bottom),
                )?;
            }
        }
        if x_labels {
            if let Some(f) = &self.x.factor {
                let h = self.x.label_row_height(th.tick);
                c.text(
                    f,
                    (x1, y1 + gap + h + gap),
                    th.tick,
                    Theme::AXIS,
                    (HAlign::Right, VAlign::Top),
                )?;
            }
        }
        Ok(())
    }

    /// Axis titles: x below the tick labels, y rotated left of them; each is cut with an
    /// ellipsis where longer than its side of the frame.
    pub fn draw_axis_titles(
        &self,
        c: &mut Canvas,
        th: &Theme,
        x_title: Option<&str>,
        y_title: Option<&str>,
        left_edge: f64,
    ) -> Result<()> {
        if let Some(t) = x_title {
            let h = self.x.label_row_height(th.tick);
            let y = self.y1 + 5.0 * th.s + h + 8.0 * th.s;
            let t = Measured::new(t, th.label).shortened(self.x1 - self.x0);
            c.draw_measured(
                &t,
                ((self.x0 + self.x1) / 2.0, y),
                Theme::AXIS,
                (HAlign::Center, VAlign::Top),
            )?;
        }
        if let Some(t) = y_title {
            let x = left_edge + cap_height(th.label) / 2.0 + 0.1 * th.label;
            let t = Measured::new(t, th.label).shortened(self.y1 - self.y0);
            c.text_up(&t, x, (self.y0 + self.y1) / 2.0, Theme::AXIS)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_splits_runs() {
        let f = Frame {
            x0: 0.0,
            y0: 0.0,
            x1: 100.0,
            y1: 100.0,
            x: Axis::with_step(0.0, 1.0, 0.5),
            y: Axis::with_step(0.0, 1.0, 0.5),
        };
        let runs = f.clip_polyline([
            (0.5, 0.5),
            (0.5, 2.0),
            (0.6, 2.0),
            (0.6, 0.5),
            (f64::NAN, 0.0),
            (0.1, 0.1),
            (0.2, 0.2),
        ]);
        assert_eq!(runs.len(), 3);
        assert!((runs[0][1].1 - 0.0).abs() < 1e-3); // clipped at the top edge (pixel y = 0)
    }
}
