//! Page layout: margins from the tick labels and titles, single frames, equal-aspect axes,
//! the title.

use super::axes::{Axis, nice_step, widen};
use super::frame::Frame;
use super::raster::Canvas;
use super::raster::Color;
use super::style::Theme;
use super::text::{HAlign, Measured, VAlign, cap_height, descent};
use crate::error::{LtiError, Result};

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
        5.0 * th.s + x.label_row_height(th.tick) + if x.factor.is_some() { th.tick } else { 0.0 };
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

/// Draws the title centred at the top, shrinking it (down to 60 %) or cutting it to fit. The
/// text is measured twice (at the full and at the reduced size) and cut in one pass over the
/// measured glyphs: linear in its length.
pub(crate) fn draw_title(c: &mut Canvas, th: &Theme, title: &str) -> Result<()> {
    let avail = f64::from(c.w) - 2.0 * th.pad;
    let mut text = Measured::new(title, th.title);
    let w = text.width();
    if w > avail {
        let size = (th.title * avail / w).max(th.title * 0.6);
        text = Measured::new(title, size).shortened(avail);
    }
    c.draw_measured(
        &text,
        (f64::from(c.w) / 2.0, th.pad + 0.2 * th.title),
        Color::BLACK,
        (HAlign::Center, VAlign::Top),
    )
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
    layout_single_above(c, th, (title, x_title, y_title), 0.0, axes)
}

/// [`layout_single`] leaving a strip of `reserve` px free at the bottom of the canvas (under
/// the x tick labels and title), e.g. for boxes that would hide the data inside the frame;
/// `titles` says whether there is a title, an x title and a y title.
pub(crate) fn layout_single_above(
    c: &Canvas,
    th: &Theme,
    (title, x_title, y_title): (bool, bool, bool),
    reserve: f64,
    axes: impl Fn(f64, f64) -> (Axis, Axis),
) -> Frame {
    let cw = f64::from(c.w);
    let ch = (f64::from(c.h) - reserve.max(0.0)).max(0.0);
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

/// Checks that a padded data range (lo, hi) of `what` can be drawn: pixel positions are
/// computed from differences of data values, and tick limits are rounded out by up to a step,
/// so the span and the limits plus twice the span must stay finite. Data that spans most of
/// the f64 range (e.g. from −1e308 to 1e308) is refused with a clear message instead of being
/// drawn as garbage.
pub(crate) fn check_span(what: &str, (lo, hi): (f64, f64)) -> Result<()> {
    let span = hi - lo;
    let fits = |v: f64| (v.abs() + 2.0 * span).is_finite();
    if span.is_finite() && fits(lo) && fits(hi) {
        Ok(())
    } else {
        Err(LtiError::Plot(format!(
            "{what} from {lo:e} to {hi:e} span a range too wide to draw in f64 (plot scaled values)"
        )))
    }
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

#[cfg(test)]
mod tests {
    use super::super::options::PlotOptions;
    use super::super::text::glyph_lookups;
    use super::*;

    /// Glyph lookups (measuring and drawing) to lay out and draw a title of `n` characters.
    fn lookups_for_title(n: usize) -> usize {
        let mut c = Canvas::new(1000, 700);
        let th = Theme::new(&PlotOptions::default());
        let title: String = "ab c".chars().cycle().take(n).collect();
        let before = glyph_lookups();
        draw_title(&mut c, &th, &title).unwrap();
        glyph_lookups() - before
    }

    #[test]
    fn title_layout_is_linear_in_its_length() {
        // A long title is measured at the full size and at the reduced size, then cut in one
        // pass: about 2 lookups per character, plus the few glyphs drawn. The loop used
        // before measured every prefix again (≈ n²/2 lookups: 1.3e8 for 16 000 characters).
        for n in [1_000, 4_000, 16_000] {
            let k = lookups_for_title(n);
            assert!(k <= 2 * n + 400, "{n} characters: {k} glyph lookups");
        }
        // A title that fits is measured and drawn once each.
        assert_eq!(lookups_for_title(40), 2 * 40);
    }
}
