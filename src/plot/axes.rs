//! Axes: tick choice (1-2-2.5-5 steps, multiples of 45°/90° for phase, decades for log ω),
//! tick labels, the plot frame, data → pixel mapping with clipping, grid, legend.

use super::raster::{Canvas, HAlign, VAlign, cap_height, descent};
use super::style::{LineStyle, MarkerShape, Theme, draw_marker};
use crate::error::Result;
use crate::plot::Color;

/// Linear or base-10 logarithmic axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Scale {
    Linear,
    Log10,
}

/// A labelled tick.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Tick {
    pub v: f64,
    pub label: String,
}

/// One axis: range, scale, ticks.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Axis {
    pub lo: f64,
    pub hi: f64,
    pub scale: Scale,
    pub ticks: Vec<Tick>,
    pub minor: Vec<f64>,
    /// Common factor of the tick labels, e.g. "×10^{-6}".
    pub factor: Option<String>,
}

/// Replaces an ASCII minus with the typographic one and removes "−0".
pub(crate) fn typographic(s: String) -> String {
    let t = s.replace('-', "−");
    if t.trim_start_matches('−')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        t.trim_start_matches('−').to_string()
    } else {
        t
    }
}

/// Number of decimals needed to print multiples of `step` exactly (up to 10).
fn decimals_for(step: f64) -> usize {
    (0..=10)
        .find(|&d| {
            let x = step * 10f64.powi(d as i32);
            (x - x.round()).abs() < 1e-6 * x.abs().max(1.0)
        })
        .unwrap_or(10)
}

/// A "nice" step (1, 2, 2.5, 5 × 10^k) giving at most `max_ticks` intervals over `span`.
pub(crate) fn nice_step(span: f64, max_ticks: usize) -> f64 {
    nice_step_from(span, max_ticks, &[1.0, 2.0, 2.5, 5.0, 10.0])
}

/// The smallest step m × 10^k (m from `mults`, ascending, ending with 10) giving at most
/// `max_ticks` intervals over `span`.
pub(crate) fn nice_step_from(span: f64, max_ticks: usize, mults: &[f64]) -> f64 {
    let raw = span / max_ticks.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    for &m in mults {
        if m * mag >= raw * (1.0 - 1e-9) {
            return m * mag;
        }
    }
    10.0 * mag
}

/// Widens a degenerate range [v, v].
pub(crate) fn widen(lo: f64, hi: f64) -> (f64, f64) {
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
    let size = lo.abs().max(hi.abs());
    if hi - lo > 1e-9 * size && hi - lo > 1e-300 {
        (lo, hi)
    } else if size > 0.0 {
        (lo - 0.1 * size, hi + 0.1 * size)
    } else {
        (-1.0, 1.0)
    }
}

impl Axis {
    /// Axis coordinate of a data value (log10 on a log axis; NaN for v ≤ 0 there).
    pub fn t(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Linear => v,
            Scale::Log10 => {
                if v > 0.0 {
                    v.log10()
                } else {
                    f64::NAN
                }
            }
        }
    }

    /// A linear axis over [lo, hi] with at most `max_ticks` intervals; `tight` keeps the limits,
    /// otherwise they are rounded outwards to ticks.
    pub fn linear(lo: f64, hi: f64, max_ticks: usize, tight: bool) -> Axis {
        Self::linear_from(lo, hi, max_ticks, tight, &[1.0, 2.0, 2.5, 5.0, 10.0])
    }

    /// [`Axis::linear`] with steps m × 10^k for m in `mults` (e.g. no 2.5 for decibels).
    pub fn linear_from(lo: f64, hi: f64, max_ticks: usize, tight: bool, mults: &[f64]) -> Axis {
        let (lo, hi) = widen(lo, hi);
        let step = nice_step_from(hi - lo, max_ticks, mults);
        let (lo, hi) = if tight {
            (lo, hi)
        } else {
            // Round a limit out to the next tick only when that costs little room.
            let span = hi - lo;
            let rlo = (lo / step + 1e-9).floor() * step;
            let rhi = (hi / step - 1e-9).ceil() * step;
            (
                if lo - rlo <= 0.06 * span { rlo } else { lo },
                if rhi - hi <= 0.06 * span { rhi } else { hi },
            )
        };
        Self::with_step(lo, hi, step)
    }

    /// A linear axis over [lo, hi] with ticks at the multiples of `step` inside it.
    pub fn with_step(lo: f64, hi: f64, step: f64) -> Axis {
        let amax = lo.abs().max(hi.abs());
        let exp = if amax >= 1e5 || (amax > 0.0 && amax < 1e-2) {
            let e = amax.log10().floor() as i32;
            3 * e.div_euclid(3)
        } else {
            0
        };
        let unit = 10f64.powi(exp);
        let d = decimals_for(step / unit);
        let k0 = (lo / step - 1e-9).ceil() as i64;
        let k1 = (hi / step + 1e-9).floor() as i64;
        let ticks = (k0..=k1.min(k0 + 200))
            .map(|k| {
                let v = k as f64 * step;
                Tick {
                    v,
                    label: typographic(format!("{:.*}", d, v / unit)),
                }
            })
            .collect();
        Axis {
            lo,
            hi,
            scale: Scale::Linear,
            ticks,
            minor: vec![],
            factor: (exp != 0).then(|| format!("×10^{{{exp}}}")),
        }
    }

    /// A phase axis in degrees: limits rounded out to, and ticks at, multiples of 45°, 90°,
    /// 180° or 360° (at most `max_ticks` intervals).
    pub fn degrees(lo: f64, hi: f64, max_ticks: usize) -> Axis {
        // Absurd ranges (a corrupt phase) get a plain linear axis.
        if !(hi - lo).is_finite() || hi - lo > 2880.0 * max_ticks.max(1) as f64 {
            return Self::linear(lo, hi, max_ticks, false);
        }
        let (lo, hi) = if hi - lo < 1e-6 {
            (lo - 1.0, hi + 1.0)
        } else {
            (lo, hi)
        };
        // A little room so that a curve at a multiple of the step does not sit on the frame.
        let pad = 0.02 * (hi - lo).max(45.0);
        let (lo, hi) = (lo - pad, hi + pad);
        let mut step = 45.0;
        for s in [45.0, 90.0, 180.0, 360.0, 720.0, 1440.0, 2880.0] {
            step = s;
            let n = ((hi / s - 1e-9).ceil() - (lo / s + 1e-9).floor()) as usize;
            if n <= max_ticks {
                break;
            }
        }
        // Limits at multiples of half the tick step (45° when ticks are every 90°).
        let unit = if step > 45.0 { step / 2.0 } else { step };
        let lo = (lo / unit + 1e-9).floor() * unit;
        let hi = (hi / unit - 1e-9).ceil() * unit;
        let mut a = Self::with_step(lo, hi, step);
        // Half-steps as minor grid lines (every 45° when labelled every 90°).
        if step > 45.0 {
            let half = step / 2.0;
            let k0 = (lo / half).round() as i64;
            let k1 = (hi / half).round() as i64;
            a.minor = (k0..=k1.min(k0 + 400))
                .filter(|k| k % 2 != 0)
                .map(|k| k as f64 * half)
                .collect();
        }
        a
    }

    /// A log axis over [lo, hi] (both > 0): ticks at decades labelled 10^k, minor grid at
    /// 2…9 × 10^k; over less than about a decade, ticks at 1, 2, 5 × 10^k with plain labels.
    pub fn log(lo: f64, hi: f64, max_ticks: usize) -> Axis {
        let (mut lo, mut hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        if lo.is_nan() || lo <= 0.0 || !hi.is_finite() {
            lo = 0.1;
            hi = 10.0;
        }
        if hi / lo < 1.0 + 1e-9 {
            lo /= 2.0;
            hi *= 2.0;
        }
        let (tlo, thi) = (lo.log10(), hi.log10());
        let d0 = (tlo - 1e-9).floor() as i64;
        let d1 = (thi + 1e-9).ceil() as i64;
        let within = |v: f64| v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9);
        let decades: Vec<i64> = (d0..=d1)
            .filter(|&k| within(10f64.powi(k as i32)))
            .collect();
        let mut ticks = Vec::new();
        let mut minor = Vec::new();
        if decades.len() >= 2 {
            let every = decades.len().div_ceil(max_ticks.max(1)).max(1) as i64;
            for &k in &decades {
                let v = 10f64.powi(k as i32);
                if k.rem_euclid(every) == 0 {
                    ticks.push(Tick {
                        v,
                        label: format!("10^{{{k}}}"),
                    });
                } else {
                    minor.push(v);
                }
            }
            if every == 1 && decades.len() <= 14 {
                for k in d0..=d1 {
                    for m in 2..=9 {
                        let v = f64::from(m) * 10f64.powi(k as i32);
                        if within(v) {
                            minor.push(v);
                        }
                    }
                }
            }
        } else {
            for mults in [
                &[1.0, 2.0, 5.0][..],
                &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0][..],
            ] {
                ticks.clear();
                minor.clear();
                for k in d0..=d1 {
                    let p = 10f64.powi(k as i32);
                    for m in 1..=9 {
                        let v = f64::from(m) * p;
                        if !within(v) {
                            continue;
                        }
                        if mults.contains(&f64::from(m)) {
                            ticks.push(Tick {
                                v,
                                label: typographic(crate::poly::fmt_sig(v, 3)),
                            });
                        } else {
                            minor.push(v);
                        }
                    }
                }
                if ticks.len() >= 3 {
                    break;
                }
            }
        }
        Axis {
            lo,
            hi,
            scale: Scale::Log10,
            ticks,
            minor,
            factor: None,
        }
    }

    /// Widest tick label (px) at font size `size`.
    pub fn max_label_width(&self, size: f64) -> f64 {
        self.ticks
            .iter()
            .map(|t| Canvas::text_width(&t.label, size))
            .fold(0.0, f64::max)
    }

    fn has_superscripts(&self) -> bool {
        self.ticks.iter().any(|t| t.label.contains('^'))
    }
}

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
                let h = tick_label_height(&self.x, th);
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

    /// Axis titles: x below the tick labels, y rotated left of them.
    pub fn draw_axis_titles(
        &self,
        c: &mut Canvas,
        th: &Theme,
        x_title: Option<&str>,
        y_title: Option<&str>,
        left_edge: f64,
    ) -> Result<()> {
        if let Some(t) = x_title {
            let h = tick_label_height(&self.x, th);
            let y = self.y1 + 5.0 * th.s + h + 8.0 * th.s;
            c.text(
                t,
                ((self.x0 + self.x1) / 2.0, y),
                th.label,
                Theme::AXIS,
                (HAlign::Center, VAlign::Top),
            )?;
        }
        if let Some(t) = y_title {
            let x = left_edge + cap_height(th.label) / 2.0 + 0.1 * th.label;
            c.text_up(t, x, (self.y0 + self.y1) / 2.0, th.label, Theme::AXIS)?;
        }
        Ok(())
    }
}

/// Height of a row of x tick labels (with room for superscripts).
pub(crate) fn tick_label_height(a: &Axis, th: &Theme) -> f64 {
    let base = cap_height(th.tick) + descent(th.tick);
    if a.has_superscripts() {
        base + 0.3 * th.tick
    } else {
        base
    }
}

/// Space (px) to the left of a frame for the y tick labels and the rotated y title.
pub(crate) fn left_margin(th: &Theme, y: &Axis, has_title: bool) -> f64 {
    let labels = y.max_label_width(th.tick) + 5.0 * th.s;
    let title = if has_title {
        cap_height(th.label) + descent(th.label) + 0.4 * th.label
    } else {
        0.0
    };
    th.pad + title + labels + 4.0 * th.s
}

/// Space (px) below a frame for x tick labels and the x title.
pub(crate) fn bottom_margin(th: &Theme, x: &Axis, has_title: bool) -> f64 {
    let labels =
        5.0 * th.s + tick_label_height(x, th) + if x.factor.is_some() { th.tick } else { 0.0 };
    let title = if has_title {
        8.0 * th.s + cap_height(th.label) + descent(th.label)
    } else {
        0.0
    };
    labels + title + th.pad
}

/// Space (px) above the top frame for the title.
pub(crate) fn top_margin(th: &Theme, has_title: bool, y_factor: bool) -> f64 {
    let t = if has_title {
        cap_height(th.title) + descent(th.title) + 0.6 * th.title
    } else {
        0.0
    };
    let f = if y_factor { th.tick } else { 0.0 };
    th.pad + t + f.max(if has_title { 0.0 } else { 6.0 * th.s })
}

/// Space (px) to the right of a frame: half of the last x tick label may stick out.
pub(crate) fn right_margin(th: &Theme, x: &Axis) -> f64 {
    let last = x
        .ticks
        .last()
        .map(|t| Canvas::text_width(&t.label, th.tick) / 2.0)
        .unwrap_or(0.0);
    (last + 4.0 * th.s).max(th.pad * 2.0)
}

/// Draws the title centred at the top, shrinking it (down to 60 %) or cutting it to fit.
pub(crate) fn draw_title(c: &mut Canvas, th: &Theme, title: &str) -> Result<()> {
    let avail = f64::from(c.w) - 2.0 * th.pad;
    let mut size = th.title;
    let mut text = title.to_string();
    let mut w = Canvas::text_width(&text, size);
    if w > avail {
        size = (th.title * avail / w).max(th.title * 0.6);
        w = Canvas::text_width(&text, size);
        while w > avail && text.chars().count() > 4 {
            let n = text.chars().count();
            text = text.chars().take(n - 2).collect::<String>() + "…";
            w = Canvas::text_width(&text, size);
        }
    }
    c.text(
        &text,
        (f64::from(c.w) / 2.0, th.pad + 0.2 * th.title),
        size,
        Color::BLACK,
        (HAlign::Center, VAlign::Top),
    )
}

/// A legend or information row: optional swatch, then text.
#[derive(Debug, Clone)]
pub(crate) enum Swatch {
    None,
    Line { color: Color, style: LineStyle },
    Marker { shape: MarkerShape, color: Color },
    Patch { color: Color, alpha: f64 },
}

/// One row of a legend box.
#[derive(Debug, Clone)]
pub(crate) struct LegendEntry {
    pub swatch: Swatch,
    pub text: String,
    pub color: Color,
}

impl LegendEntry {
    pub fn line(text: impl Into<String>, color: Color, style: LineStyle) -> Self {
        LegendEntry {
            swatch: Swatch::Line { color, style },
            text: text.into(),
            color: Color::BLACK,
        }
    }
    pub fn marker(text: impl Into<String>, shape: MarkerShape, color: Color) -> Self {
        LegendEntry {
            swatch: Swatch::Marker { shape, color },
            text: text.into(),
            color: Color::BLACK,
        }
    }
    pub fn text(text: impl Into<String>, color: Color) -> Self {
        LegendEntry {
            swatch: Swatch::None,
            text: text.into(),
            color,
        }
    }
}

/// Where a box goes inside a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Corner {
    TopRight,
    TopLeft,
    BottomRight,
    BottomLeft,
}

/// Draws a legend box inside `frame` in the corner (from `prefer`) that hides the fewest of the
/// pixel points `avoid`; returns the box drawn (x0, y0, x1, y1).
pub(crate) fn draw_legend(
    c: &mut Canvas,
    frame: &Frame,
    th: &Theme,
    entries: &[LegendEntry],
    avoid: &[(f64, f64)],
    prefer: &[Corner],
    taken: &[(f64, f64, f64, f64)],
) -> Result<Option<(f64, f64, f64, f64)>> {
    if entries.is_empty() {
        return Ok(None);
    }
    let size = th.note;
    let row = 1.45 * size;
    let sw = if entries.iter().any(|e| !matches!(e.swatch, Swatch::None)) {
        34.0 * th.s
    } else {
        0.0
    };
    let text_w = entries
        .iter()
        .map(|e| Canvas::text_width(&e.text, size))
        .fold(0.0, f64::max);
    let padx = 8.0 * th.s;
    let bw = padx + sw + if sw > 0.0 { 6.0 * th.s } else { 0.0 } + text_w + padx;
    let bh = row * entries.len() as f64 + 0.5 * size;
    let m = 8.0 * th.s;
    let place = |corner: Corner| -> (f64, f64, f64, f64) {
        let (x, y) = match corner {
            Corner::TopRight => (frame.x1 - m - bw, frame.y0 + m),
            Corner::TopLeft => (frame.x0 + m, frame.y0 + m),
            Corner::BottomRight => (frame.x1 - m - bw, frame.y1 - m - bh),
            Corner::BottomLeft => (frame.x0 + m, frame.y1 - m - bh),
        };
        (x, y, x + bw, y + bh)
    };
    let overlaps = |a: (f64, f64, f64, f64), b: &(f64, f64, f64, f64)| {
        a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
    };
    let prefer = if prefer.is_empty() {
        &[Corner::TopRight][..]
    } else {
        prefer
    };
    let mut best = place(prefer[0]);
    let mut best_score = usize::MAX;
    for &corner in prefer {
        let b = place(corner);
        let mut score = avoid
            .iter()
            .filter(|p| {
                p.0 >= b.0 - 4.0 && p.0 <= b.2 + 4.0 && p.1 >= b.1 - 4.0 && p.1 <= b.3 + 4.0
            })
            .count();
        if taken.iter().any(|t| overlaps(b, t)) {
            score += 1_000_000;
        }
        if score < best_score {
            best_score = score;
            best = b;
        }
    }
    if best_score > 0 {
        // Every preferred corner hides something: try the middles of the edges as well.
        let cx = (frame.x0 + frame.x1 - bw) / 2.0;
        let cy = (frame.y0 + frame.y1 - bh) / 2.0;
        for (x, y) in [
            (cx, frame.y0 + m),
            (cx, frame.y1 - m - bh),
            (frame.x0 + m, cy),
            (frame.x1 - m - bw, cy),
        ] {
            let b = (x, y, x + bw, y + bh);
            let score = avoid
                .iter()
                .filter(|p| {
                    p.0 >= b.0 - 4.0 && p.0 <= b.2 + 4.0 && p.1 >= b.1 - 4.0 && p.1 <= b.3 + 4.0
                })
                .count()
                + if taken.iter().any(|t| overlaps(b, t)) {
                    1_000_000
                } else {
                    0
                };
            if score < best_score {
                best_score = score;
                best = b;
            }
        }
    }
    let (x0, y0, x1, y1) = best;
    c.fill_rect(x0, y0, x1, y1, Color::WHITE, 0.9);
    c.stroke(
        &[(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)],
        th.s.max(1.0),
        Color(190, 190, 190),
        &[],
    );
    for (k, e) in entries.iter().enumerate() {
        let cy = y0 + 0.25 * size + row * (k as f64 + 0.5);
        let mut tx = x0 + padx;
        match e.swatch {
            Swatch::None => {}
            Swatch::Line { color, style } => {
                c.stroke(
                    &[(tx, cy), (tx + sw, cy)],
                    th.line,
                    color,
                    &style.pattern(th.line),
                );
            }
            Swatch::Marker { shape, color } => {
                draw_marker(c, (tx + sw / 2.0, cy), shape, 5.5 * th.s, color, th.line);
            }
            Swatch::Patch { color, alpha } => {
                c.fill_rect(
                    tx,
                    cy - 0.35 * size,
                    tx + sw,
                    cy + 0.35 * size,
                    color,
                    alpha,
                );
            }
        }
        if sw > 0.0 {
            tx += sw + 6.0 * th.s;
        }
        c.text(
            &e.text,
            (tx, cy),
            size,
            e.color,
            (HAlign::Left, VAlign::Middle),
        )?;
    }
    Ok(Some(best))
}

/// Tick-count targets (x, y) for a plot area of w × h px.
pub(crate) fn tick_targets(w: f64, h: f64, th: &Theme) -> (usize, usize) {
    (
        ((w / (95.0 * th.s)) as usize).clamp(2, 12),
        ((h / (60.0 * th.s)) as usize).clamp(2, 10),
    )
}

/// Lays out one frame filling the canvas below the title. `axes(w, h)` builds the axes for a
/// plot area of w × h px (called a few times while the margins settle).
pub(crate) fn layout_single(
    c: &Canvas,
    th: &Theme,
    title: bool,
    x_title: bool,
    y_title: bool,
    axes: impl Fn(f64, f64) -> (Axis, Axis),
) -> Frame {
    let (cw, ch) = (f64::from(c.w), f64::from(c.h));
    let (mut l, mut r, mut t, mut b) = (
        80.0 * th.s,
        20.0 * th.s,
        top_margin(th, title, false),
        70.0 * th.s,
    );
    let mut ax = axes((cw - l - r).max(10.0), (ch - t - b).max(10.0));
    for _ in 0..2 {
        l = left_margin(th, &ax.1, y_title);
        r = right_margin(th, &ax.0);
        t = top_margin(th, title, ax.1.factor.is_some());
        b = bottom_margin(th, &ax.0, x_title);
        ax = axes((cw - l - r).max(10.0), (ch - t - b).max(10.0));
    }
    Frame {
        x0: l,
        y0: t,
        x1: (cw - r).max(l + 10.0),
        y1: (ch - b).max(t + 10.0),
        x: ax.0,
        y: ax.1,
    }
}

/// Axes with equal data units per pixel on x and y (for the complex plane): the ranges are
/// widened about their centres to fill a w × h area, and both axes share one tick step.
pub(crate) fn equal_axes(
    xr: (f64, f64),
    yr: (f64, f64),
    w: f64,
    h: f64,
    th: &Theme,
) -> (Axis, Axis) {
    let (xlo, xhi) = widen(xr.0, xr.1);
    let (ylo, yhi) = widen(yr.0, yr.1);
    let u = ((xhi - xlo) / w).max((yhi - ylo) / h);
    let (cx, cy) = ((xlo + xhi) / 2.0, (ylo + yhi) / 2.0);
    let (nx, ny) = tick_targets(w, h, th);
    let step = nice_step(u * w, nx).max(nice_step(u * h, ny));
    (
        Axis::with_step(cx - u * w / 2.0, cx + u * w / 2.0, step),
        Axis::with_step(cy - u * h / 2.0, cy + u * h / 2.0, step),
    )
}

/// Bounds (lo, hi) of the finite values, or `None`.
pub(crate) fn bounds(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for v in values {
        if v.is_finite() {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// Points every `step` px along a pixel polyline (for keeping legends off the curves).
pub(crate) fn sample_run(run: &[(f64, f64)], step: f64) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for w in run.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        let n = ((len / step).ceil() as usize).clamp(1, 10_000);
        for k in 0..n {
            let t = k as f64 / n as f64;
            out.push((a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t));
        }
    }
    out.extend(run.last().copied());
    out
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
                super::style::draw_arrow_head(c, tip, dir, len, color);
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps() {
        assert!((nice_step(10.0, 5) - 2.0).abs() < 1e-12);
        assert!((nice_step(1.0, 4) - 0.25).abs() < 1e-12);
        assert!((nice_step(7.3, 8) - 1.0).abs() < 1e-12);
        // −0.13 rounds out to the tick −0.2 (cheap), 1.07 stays (1.2 would waste 11 %).
        let a = Axis::linear(-0.13, 1.07, 6, false);
        assert!((a.lo + 0.2).abs() < 1e-12 && (a.hi - 1.07).abs() < 1e-12);
        let labels: Vec<&str> = a.ticks.iter().map(|t| t.label.as_str()).collect();
        assert_eq!(labels, ["−0.2", "0.0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
        let a = Axis::linear(0.0, 0.97, 5, false);
        assert!((a.hi - 1.0).abs() < 1e-12);
    }

    #[test]
    fn factor_for_tiny_values() {
        let a = Axis::linear(0.0, 3.2e-6, 5, false);
        assert_eq!(a.factor.as_deref(), Some("×10^{-6}"));
        assert_eq!(a.ticks.last().unwrap().label, "3");
        assert!((a.hi - 3.2e-6).abs() < 1e-18);
    }

    #[test]
    fn phase_ticks_are_multiples_of_45_or_90() {
        let a = Axis::degrees(-270.0, -270.0, 8);
        assert!(a.ticks.iter().any(|t| (t.v + 270.0).abs() < 1e-9));
        let a = Axis::degrees(-180.0, 0.0, 8);
        assert!(a.ticks.iter().all(|t| (t.v / 45.0).fract().abs() < 1e-12));
        let a = Axis::degrees(-1000.0, 0.0, 8);
        assert!(a.ticks.iter().all(|t| (t.v / 90.0).fract().abs() < 1e-12));
        assert!(a.ticks.len() <= 9);
    }

    #[test]
    fn log_ticks_at_decades() {
        let a = Axis::log(0.01, 100.0, 10);
        let labels: Vec<&str> = a.ticks.iter().map(|t| t.label.as_str()).collect();
        assert_eq!(labels, ["10^{-2}", "10^{-1}", "10^{0}", "10^{1}", "10^{2}"]);
        assert_eq!(a.minor.len(), 4 * 8);
        let a = Axis::log(2.0, 9.0, 10);
        assert!(a.ticks.len() >= 3);
    }

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
