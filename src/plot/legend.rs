//! Legend and information boxes, placed in the frame corner that hides the least of the curves.

use super::frame::Frame;
use super::raster::Canvas;
use super::raster::Color;
use super::style::{LineStyle, MarkerShape, Theme, draw_marker};
use super::text::{HAlign, Measured, VAlign};
use crate::error::Result;

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

/// A box (x0, y0, x1, y1) in pixels.
pub(crate) type Rect = (f64, f64, f64, f64);

/// Pixel points that a legend should not hide (samples of the curves, annotation boxes).
pub(crate) type Avoid = Vec<(f64, f64)>;

/// A legend fitted to its frame: the rows shown (text measured, and shortened with an
/// ellipsis where wider than the frame), and the box size.
pub(crate) struct Fitted {
    rows: Vec<(Swatch, Measured, Color)>,
    /// Box width and height.
    pub w: f64,
    pub h: f64,
    /// Whether rows were left out ("… and n more") for want of height.
    pub cut: bool,
    /// Swatch width (0 when no row has one), horizontal padding, row height.
    swatch: f64,
    padx: f64,
    row: f64,
}

impl Fitted {
    /// Measures the rows once and fits them into `frame` (inside its 8 px margins): rows too
    /// wide are cut, and when there are more rows than fit, the last row shown says how many
    /// are left out. `None` when not even two rows fit (and there is more than one).
    pub(crate) fn new(frame: &Frame, th: &Theme, entries: &[LegendEntry]) -> Option<Fitted> {
        let m = 8.0 * th.s;
        Fitted::within(
            th,
            entries,
            (frame.x1 - frame.x0 - 2.0 * m, frame.y1 - frame.y0 - 2.0 * m),
        )
    }

    /// [`Fitted::new`] for a box of at most `max_w` × `max_h` px anywhere on the canvas.
    pub(crate) fn within(
        th: &Theme,
        entries: &[LegendEntry],
        (max_w, max_h): (f64, f64),
    ) -> Option<Fitted> {
        let size = th.note;
        let row = 1.45 * size;
        let swatch = if entries.iter().any(|e| !matches!(e.swatch, Swatch::None)) {
            34.0 * th.s
        } else {
            0.0
        };
        let padx = 8.0 * th.s;
        let gap = if swatch > 0.0 { 6.0 * th.s } else { 0.0 };
        let max_text = max_w - (padx + swatch + gap + padx);
        let max_rows = ((max_h - 0.5 * size) / row).floor();
        let max_rows = if max_rows.is_finite() && max_rows > 0.0 {
            max_rows as usize
        } else {
            0
        };
        let shown = if entries.len() <= max_rows {
            entries.len()
        } else if max_rows >= 2 {
            max_rows - 1
        } else {
            return None;
        };
        let fit = |text: &str| Measured::new(text, size).shortened(max_text);
        let mut rows: Vec<(Swatch, Measured, Color)> = entries[..shown]
            .iter()
            .map(|e| (e.swatch.clone(), fit(&e.text), e.color))
            .collect();
        if shown < entries.len() {
            let more = format!("… and {} more", entries.len() - shown);
            rows.push((Swatch::None, fit(&more), Theme::NOTE));
        }
        let text_w = rows.iter().map(|r| r.1.width()).fold(0.0, f64::max);
        let w = padx + swatch + gap + text_w + padx;
        let h = row * rows.len() as f64 + 0.5 * size;
        Some(Fitted {
            cut: shown < entries.len(),
            rows,
            w,
            h,
            swatch,
            padx,
            row,
        })
    }
}

/// The position of a `bw` × `bh` box in `frame`: the first preferred corner hiding the fewest
/// of the points `avoid` without overlapping a `taken` box; if every corner hides something,
/// the middles of the edges are tried as well.
fn place(
    frame: &Frame,
    th: &Theme,
    (bw, bh): (f64, f64),
    avoid: &[(f64, f64)],
    prefer: &[Corner],
    taken: &[Rect],
) -> Rect {
    let m = 8.0 * th.s;
    let at_corner = |corner: Corner| -> Rect {
        let (x, y) = match corner {
            Corner::TopRight => (frame.x1 - m - bw, frame.y0 + m),
            Corner::TopLeft => (frame.x0 + m, frame.y0 + m),
            Corner::BottomRight => (frame.x1 - m - bw, frame.y1 - m - bh),
            Corner::BottomLeft => (frame.x0 + m, frame.y1 - m - bh),
        };
        (x, y, x + bw, y + bh)
    };
    let score = |b: Rect| {
        hidden(b, avoid)
            + if taken.iter().any(|t| overlaps(b, *t)) {
                1_000_000
            } else {
                0
            }
    };
    let prefer = if prefer.is_empty() {
        &[Corner::TopRight][..]
    } else {
        prefer
    };
    let mut best = at_corner(prefer[0]);
    let mut best_score = usize::MAX;
    let mut consider = |b: Rect| {
        let sc = score(b);
        if sc < best_score {
            best_score = sc;
            best = b;
        }
        best_score
    };
    let mut last = usize::MAX;
    for &corner in prefer {
        last = consider(at_corner(corner));
    }
    if last > 0 {
        let cx = (frame.x0 + frame.x1 - bw) / 2.0;
        let cy = (frame.y0 + frame.y1 - bh) / 2.0;
        for (x, y) in [
            (cx, frame.y0 + m),
            (cx, frame.y1 - m - bh),
            (frame.x0 + m, cy),
            (frame.x1 - m - bw, cy),
        ] {
            consider((x, y, x + bw, y + bh));
        }
    }
    best
}

/// Draws a legend box inside `frame` in the corner (from `prefer`) that hides the fewest of the
/// pixel points `avoid`; returns the box drawn (x0, y0, x1, y1). The box always fits the frame:
/// rows wider than the frame are cut with an ellipsis, rows beyond its height are summarised
/// as "… and n more" (no box at all when the frame cannot hold two rows).
pub(crate) fn draw_legend(
    c: &mut Canvas,
    frame: &Frame,
    th: &Theme,
    entries: &[LegendEntry],
    avoid: &[(f64, f64)],
    prefer: &[Corner],
    taken: &[Rect],
) -> Result<Option<Rect>> {
    if entries.is_empty() {
        return Ok(None);
    }
    let Some(fit) = Fitted::new(frame, th, entries) else {
        return Ok(None);
    };
    let best = place(frame, th, (fit.w, fit.h), avoid, prefer, taken);
    draw_fitted(c, th, &fit, (best.0, best.1))?;
    Ok(Some(best))
}

/// A place in `frame` for a `bw` × `bh` box that hides none of the points `avoid` and overlaps
/// no `taken` box: the preferred corners in order, then the middles of the edges, then a grid
/// of positions across the frame. `None` when every one hides something.
pub(crate) fn clear_spot(
    frame: &Frame,
    th: &Theme,
    (bw, bh): (f64, f64),
    avoid: &[(f64, f64)],
    prefer: &[Corner],
    taken: &[Rect],
) -> Option<Rect> {
    let m = 8.0 * th.s;
    let (x0, x1) = (frame.x0 + m, frame.x1 - m - bw);
    let (y0, y1) = (frame.y0 + m, frame.y1 - m - bh);
    if x1 < x0 || y1 < y0 {
        return None;
    }
    let corner = |c: &Corner| match c {
        Corner::TopRight => (x1, y0),
        Corner::TopLeft => (x0, y0),
        Corner::BottomRight => (x1, y1),
        Corner::BottomLeft => (x0, y1),
    };
    const STEPS: usize = 8;
    let at = |lo: f64, hi: f64, k: usize| lo + (hi - lo) * k as f64 / STEPS as f64;
    let (xm, ym) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    prefer
        .iter()
        .map(corner)
        .chain([(xm, y0), (xm, y1), (x0, ym), (x1, ym)])
        .chain((0..=STEPS).flat_map(|j| (0..=STEPS).map(move |i| (at(x0, x1, i), at(y0, y1, j)))))
        .map(|(x, y)| (x, y, x + bw, y + bh))
        .find(|&b| hidden(b, avoid) == 0 && !taken.iter().any(|t| overlaps(b, *t)))
}

/// How many of the points `avoid` a box hides (with a 4 px margin).
fn hidden(b: Rect, avoid: &[(f64, f64)]) -> usize {
    avoid
        .iter()
        .filter(|p| p.0 >= b.0 - 4.0 && p.0 <= b.2 + 4.0 && p.1 >= b.1 - 4.0 && p.1 <= b.3 + 4.0)
        .count()
}

/// Whether two boxes overlap.
fn overlaps(a: Rect, b: Rect) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}

/// Draws a fitted box with its top-left corner at `(x0, y0)`: a white, lightly framed box and
/// its rows.
pub(crate) fn draw_fitted(
    c: &mut Canvas,
    th: &Theme,
    fit: &Fitted,
    (x0, y0): (f64, f64),
) -> Result<()> {
    let (x1, y1) = (x0 + fit.w, y0 + fit.h);
    c.fill_rect(x0, y0, x1, y1, Color::WHITE, 0.9);
    c.stroke(
        &[(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)],
        th.s.max(1.0),
        Color(190, 190, 190),
        &[],
    );
    let size = th.note;
    let sw = fit.swatch;
    for (k, (swatch, text, color)) in fit.rows.iter().enumerate() {
        let cy = y0 + 0.25 * size + fit.row * (k as f64 + 0.5);
        let mut tx = x0 + fit.padx;
        draw_swatch(c, th, swatch, (tx, cy), sw);
        if sw > 0.0 {
            tx += sw + 6.0 * th.s;
        }
        c.draw_measured(text, (tx, cy), *color, (HAlign::Left, VAlign::Middle))?;
    }
    Ok(())
}

/// Draws a row's swatch of width `sw` starting at `(x, cy)` (vertically centred on cy).
fn draw_swatch(c: &mut Canvas, th: &Theme, swatch: &Swatch, (tx, cy): (f64, f64), sw: f64) {
    let size = th.note;
    match *swatch {
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
}

/// Corners, edge midpoints and centre of a box: what a legend must not cover of an annotation.
pub(crate) fn box_points(r: Rect) -> [(f64, f64); 9] {
    let (xm, ym) = ((r.0 + r.2) / 2.0, (r.1 + r.3) / 2.0);
    [
        (r.0, r.1),
        (xm, r.1),
        (r.2, r.1),
        (r.0, ym),
        (xm, ym),
        (r.2, ym),
        (r.0, r.3),
        (xm, r.3),
        (r.2, r.3),
    ]
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
