//! A small anti-aliased rasteriser over an RGB buffer: strokes, discs, rings, polygons and
//! rectangles (text is drawn by [`super::text`]).
//!
//! Geometry (strokes with round joins, dashes, discs, rings, polygons, rectangles) is drawn
//! with exact per-pixel coverage: every stroke accumulates its coverage in a mask (maximum
//! over its pieces, so dense polylines do not darken their own edges) that is composited
//! once.
//!
//! Coordinates are pixels with (0, 0) the top-left corner of the image; a pixel (i, j) covers
//! [i, i + 1) × [j, j + 1), so its centre is (i + 0.5, j + 0.5).

/// An sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Color(pub u8, pub u8, pub u8);

impl Color {
    /// Black.
    pub const BLACK: Color = Color(0, 0, 0);
    /// White.
    pub const WHITE: Color = Color(255, 255, 255);

    /// This colour mixed with white: `t = 0` is the colour, `t = 1` white.
    pub fn lighten(self, t: f64) -> Color {
        let m = |c: u8| (f64::from(c) + (255.0 - f64::from(c)) * t).round() as u8;
        Color(m(self.0), m(self.1), m(self.2))
    }
}

/// An RGB image being drawn.
pub(crate) struct Canvas {
    pub w: u32,
    pub h: u32,
    buf: Vec<u8>,
    /// Coverage of the stroke being built (max over its pieces), composited once.
    mask: Vec<f32>,
    /// Bounding box of non-zero mask entries: x0, y0, x1, y1 (inclusive-exclusive).
    dirty: Option<(usize, usize, usize, usize)>,
}

impl Canvas {
    /// A white canvas. The caller has validated the size (at most
    /// [`MAX_PIXELS`](super::options::MAX_PIXELS)).
    pub fn new(w: u32, h: u32) -> Canvas {
        let n = w as usize * h as usize;
        Canvas {
            w,
            h,
            buf: vec![255; n * 3],
            mask: vec![0.0; n],
            dirty: None,
        }
    }

    /// Paints the whole canvas white again (to draw it anew, e.g. with another layout).
    pub fn clear(&mut self) {
        self.buf.fill(255);
        self.mask.fill(0.0);
        self.dirty = None;
    }

    /// The RGB bytes, row by row.
    pub fn pixels(&self) -> &[u8] {
        &self.buf
    }

    #[inline]
    pub(super) fn blend(&mut self, x: usize, y: usize, c: Color, a: f64) {
        if a <= 0.0 {
            return;
        }
        let a = a.min(1.0);
        let i = 3 * (y * self.w as usize + x);
        let mix =
            |bg: u8, fg: u8| (f64::from(bg) + (f64::from(fg) - f64::from(bg)) * a).round() as u8;
        self.buf[i] = mix(self.buf[i], c.0);
        self.buf[i + 1] = mix(self.buf[i + 1], c.1);
        self.buf[i + 2] = mix(self.buf[i + 2], c.2);
    }

    /// Pixel index range [lo, hi) whose centres can lie within [a, b], clamped to the image.
    fn span(a: f64, b: f64, n: u32) -> (usize, usize) {
        let lo = (a - 0.5).floor().max(0.0);
        let hi = (b + 0.5).ceil().min(f64::from(n));
        if lo >= hi || lo.is_nan() || hi.is_nan() {
            return (0, 0);
        }
        (lo as usize, hi as usize)
    }

    /// Fills the rectangle [x0, x1] × [y0, y1] with `c` at opacity `alpha`, anti-aliased at
    /// fractional edges.
    pub fn fill_rect(&mut self, x0: f64, y0: f64, x1: f64, y1: f64, c: Color, alpha: f64) {
        let (xa, xb) = (x0.min(x1), x0.max(x1));
        let (ya, yb) = (y0.min(y1), y0.max(y1));
        let (i0, i1) = Self::span(xa, xb, self.w);
        let (j0, j1) = Self::span(ya, yb, self.h);
        for j in j0..j1 {
            let cy = ((yb.min(j as f64 + 1.0)) - ya.max(j as f64)).clamp(0.0, 1.0);
            if cy <= 0.0 {
                continue;
            }
            for i in i0..i1 {
                let cx = ((xb.min(i as f64 + 1.0)) - xa.max(i as f64)).clamp(0.0, 1.0);
                self.blend(i, j, c, alpha * cx * cy);
            }
        }
    }

    /// Adds the capsule of half-width `r` around segment a–b to the stroke mask.
    fn mask_segment(&mut self, a: (f64, f64), b: (f64, f64), r: f64) {
        let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        // Long segments are cut into short pieces so that each piece's bounding box is small.
        let pieces = ((len / 12.0).ceil() as usize).clamp(1, 100_000);
        for k in 0..pieces {
            let t0 = k as f64 / pieces as f64;
            let t1 = (k + 1) as f64 / pieces as f64;
            let p = (a.0 + (b.0 - a.0) * t0, a.1 + (b.1 - a.1) * t0);
            let q = (a.0 + (b.0 - a.0) * t1, a.1 + (b.1 - a.1) * t1);
            self.mask_piece(p, q, r);
        }
    }

    fn mask_piece(&mut self, a: (f64, f64), b: (f64, f64), r: f64) {
        let pad = r + 1.0;
        let (i0, i1) = Self::span(a.0.min(b.0) - pad, a.0.max(b.0) + pad, self.w);
        let (j0, j1) = Self::span(a.1.min(b.1) - pad, a.1.max(b.1) + pad, self.h);
        if i0 >= i1 || j0 >= j1 {
            return;
        }
        let d = (b.0 - a.0, b.1 - a.1);
        let dd = d.0 * d.0 + d.1 * d.1;
        let w = self.w as usize;
        for j in j0..j1 {
            let py = j as f64 + 0.5;
            for i in i0..i1 {
                let px = i as f64 + 0.5;
                let t = if dd > 0.0 {
                    (((px - a.0) * d.0 + (py - a.1) * d.1) / dd).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let ex = px - (a.0 + t * d.0);
                let ey = py - (a.1 + t * d.1);
                let dist = (ex * ex + ey * ey).sqrt();
                let cov = (r + 0.5 - dist).clamp(0.0, 1.0) as f32;
                if cov > 0.0 {
                    let m = &mut self.mask[j * w + i];
                    if cov > *m {
                        *m = cov;
                    }
                }
            }
        }
        self.dirty = Some(match self.dirty {
            None => (i0, j0, i1, j1),
            Some((x0, y0, x1, y1)) => (x0.min(i0), y0.min(j0), x1.max(i1), y1.max(j1)),
        });
    }

    /// Composites the stroke mask with colour `c` and clears it.
    fn flush_mask(&mut self, c: Color, alpha: f64) {
        if let Some((x0, y0, x1, y1)) = self.dirty.take() {
            let w = self.w as usize;
            for j in y0..y1 {
                for i in x0..x1 {
                    let m = self.mask[j * w + i];
                    if m > 0.0 {
                        self.mask[j * w + i] = 0.0;
                        self.blend(i, j, c, alpha * f64::from(m));
                    }
                }
            }
        }
    }

    /// Strokes a polyline of width `width` px with round joins. `dash` is an on/off pattern in
    /// pixels (empty: solid). Non-finite points break the line.
    pub fn stroke(&mut self, pts: &[(f64, f64)], width: f64, c: Color, dash: &[f64]) {
        self.stroke_alpha(pts, width, c, dash, 1.0);
    }

    /// [`Canvas::stroke`] with an opacity.
    pub fn stroke_alpha(
        &mut self,
        pts: &[(f64, f64)],
        width: f64,
        c: Color,
        dash: &[f64],
        alpha: f64,
    ) {
        let r = (width / 2.0).max(0.35);
        let dash_total: f64 = dash.iter().sum();
        let dashed = dash.len() >= 2 && dash_total > 0.0 && dash.iter().all(|d| *d >= 0.0);
        let ok = |p: &(f64, f64)| {
            p.0.is_finite() && p.1.is_finite() && p.0.abs() < 1e7 && p.1.abs() < 1e7
        };
        // Position in the dash pattern: element k with `left` pixels of it remaining.
        let mut k = 0;
        let mut left = dash.first().copied().unwrap_or(0.0);
        for seg in pts.windows(2) {
            let (a, b) = (seg[0], seg[1]);
            if !ok(&a) || !ok(&b) {
                continue;
            }
            if !dashed {
                self.mask_segment(a, b, r);
                continue;
            }
            let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
            let mut s = 0.0;
            while len - s > 1e-9 {
                let step = left.min(len - s);
                if k % 2 == 0 && step > 0.0 {
                    let (t0, t1) = (s / len, (s + step) / len);
                    let p = (a.0 + (b.0 - a.0) * t0, a.1 + (b.1 - a.1) * t0);
                    let q = (a.0 + (b.0 - a.0) * t1, a.1 + (b.1 - a.1) * t1);
                    self.mask_segment(p, q, r);
                }
                s += step;
                left -= step;
                if left <= 1e-9 {
                    k = (k + 1) % dash.len();
                    left = dash[k];
                }
            }
        }
        if pts.len() == 1 && ok(&pts[0]) {
            self.mask_segment(pts[0], pts[0], r);
        }
        self.flush_mask(c, alpha);
    }

    /// A filled disc.
    pub fn fill_circle(&mut self, center: (f64, f64), radius: f64, c: Color) {
        let (i0, i1) = Self::span(center.0 - radius - 1.0, center.0 + radius + 1.0, self.w);
        let (j0, j1) = Self::span(center.1 - radius - 1.0, center.1 + radius + 1.0, self.h);
        for j in j0..j1 {
            for i in i0..i1 {
                let d = ((i as f64 + 0.5 - center.0).powi(2) + (j as f64 + 0.5 - center.1).powi(2))
                    .sqrt();
                self.blend(i, j, c, (radius + 0.5 - d).clamp(0.0, 1.0));
            }
        }
    }

    /// A circle outline of line width `width`.
    pub fn ring(&mut self, center: (f64, f64), radius: f64, width: f64, c: Color) {
        let hw = width / 2.0;
        let (i0, i1) = Self::span(
            center.0 - radius - hw - 1.0,
            center.0 + radius + hw + 1.0,
            self.w,
        );
        let (j0, j1) = Self::span(
            center.1 - radius - hw - 1.0,
            center.1 + radius + hw + 1.0,
            self.h,
        );
        for j in j0..j1 {
            for i in i0..i1 {
                let d = ((i as f64 + 0.5 - center.0).powi(2) + (j as f64 + 0.5 - center.1).powi(2))
                    .sqrt();
                self.blend(i, j, c, (hw + 0.5 - (d - radius).abs()).clamp(0.0, 1.0));
            }
        }
    }

    /// Fills a (small) polygon, even-odd rule, 4×4 supersampled.
    pub fn fill_polygon(&mut self, pts: &[(f64, f64)], c: Color, alpha: f64) {
        if pts.len() < 3 || pts.iter().any(|p| !p.0.is_finite() || !p.1.is_finite()) {
            return;
        }
        let (mut xa, mut xb, mut ya, mut yb) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for p in pts {
            xa = xa.min(p.0);
            xb = xb.max(p.0);
            ya = ya.min(p.1);
            yb = yb.max(p.1);
        }
        let (i0, i1) = Self::span(xa, xb, self.w);
        let (j0, j1) = Self::span(ya, yb, self.h);
        let inside = |x: f64, y: f64| {
            let mut c = false;
            let n = pts.len();
            let mut k = n - 1;
            for m in 0..n {
                let (pi, pk) = (pts[m], pts[k]);
                if (pi.1 > y) != (pk.1 > y) && x < (pk.0 - pi.0) * (y - pi.1) / (pk.1 - pi.1) + pi.0
                {
                    c = !c;
                }
                k = m;
            }
            c
        };
        for j in j0..j1 {
            for i in i0..i1 {
                let mut hits = 0;
                for sy in 0..4 {
                    for sx in 0..4 {
                        if inside(
                            i as f64 + (sx as f64 + 0.5) / 4.0,
                            j as f64 + (sy as f64 + 0.5) / 4.0,
                        ) {
                            hits += 1;
                        }
                    }
                }
                if hits > 0 {
                    self.blend(i, j, c, alpha * f64::from(hits) / 16.0);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stroke_covers_pixels_and_dashes_leave_gaps() {
        let mut c = Canvas::new(60, 20);
        c.stroke(&[(5.0, 10.0), (55.0, 10.0)], 2.0, Color::BLACK, &[]);
        let px = |c: &Canvas, x: usize, y: usize| c.pixels()[3 * (y * 60 + x)];
        assert_eq!(px(&c, 30, 9), 0);
        assert_eq!(px(&c, 30, 14), 255);
        let mut d = Canvas::new(60, 20);
        d.stroke(&[(5.0, 10.0), (55.0, 10.0)], 2.0, Color::BLACK, &[6.0, 6.0]);
        let dark: Vec<bool> = (0..60).map(|x| px(&d, x, 9) < 128).collect();
        let n = dark.iter().filter(|&&b| b).count();
        let gaps = dark.windows(2).filter(|w| w[0] && !w[1]).count();
        assert!((20..42).contains(&n), "dark pixels {n}");
        assert!(gaps >= 3, "gaps {gaps}");
    }
}
