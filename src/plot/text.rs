//! Text: the compiled-in font, the small markup (`^{…}`, `_{…}`, `s^2`), measuring and drawing.
//!
//! Text is rasterised with `ab_glyph` from Noto Sans compiled into the binary (the
//! `ttf-noto-sans` crate), with kerning, side bearings and sub-pixel pen positions: no
//! fontconfig, no system font, no display.

use std::sync::OnceLock;

use ab_glyph::{Font, FontRef, GlyphId, PxScale, ScaleFont, point};

use super::markup::rich_runs;
use super::raster::{Canvas, Color};
use crate::error::{LtiError, Result};

/// The compiled-in font, parsed once per process (`None` if it were ever rejected).
pub(super) fn font() -> Option<&'static FontRef<'static>> {
    static FONT: OnceLock<Option<FontRef<'static>>> = OnceLock::new();
    FONT.get_or_init(|| FontRef::try_from_slice(ttf_noto_sans::REGULAR).ok())
        .as_ref()
}

/// Checks that the compiled-in font can be used (every plot has text): an error names it.
pub(super) fn check_font() -> Result<()> {
    match font() {
        Some(_) => Ok(()),
        None => Err(LtiError::Plot(
            "the compiled-in font (Noto Sans) could not be loaded".into(),
        )),
    }
}

/// Horizontal text alignment relative to the anchor point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum HAlign {
    Left,
    Center,
    Right,
}

/// Vertical text alignment relative to the anchor point (capital letters define top and
/// middle; `Bottom` includes descenders).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum VAlign {
    Top,
    Middle,
    Bottom,
}

/// Capital height of Noto Sans as a fraction of the font size (the size is the ascent −
/// descent height, as in `ab_glyph::PxScale`: 1362 font units, caps 714).
const CAP: f64 = 0.524;
/// Descender depth as a fraction of the font size (293 / 1362).
const DESC: f64 = 0.215;

/// Relative size of super- and subscripts.
const SCRIPT: f64 = 0.72;
/// How far a superscript's baseline is raised, as a fraction of the font size.
const SUP_RAISE: f64 = 0.30;
/// How far a subscript's baseline is lowered, as a fraction of the font size.
const SUB_DROP: f64 = 0.12;

/// The ellipsis that ends shortened text.
const ELLIPSIS: char = '…';

#[cfg(test)]
thread_local! {
    /// Glyphs looked up (measured or drawn) on this thread, for the linearity tests.
    static GLYPH_LOOKUPS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// Counts `n` glyph lookups (tests only).
#[inline]
fn count_lookups(n: usize) {
    #[cfg(test)]
    GLYPH_LOOKUPS.with(|c| c.set(c.get() + n));
    #[cfg(not(test))]
    let _ = n;
}

/// Glyph lookups so far on this thread (tests only).
#[cfg(test)]
pub(crate) fn glyph_lookups() -> usize {
    GLYPH_LOOKUPS.with(|c| c.get())
}

/// One run of rich text measured at its size: each glyph is looked up once, and the pen
/// position after it is kept, so that any prefix's width is known without measuring again.
#[derive(Debug, Clone)]
pub(crate) struct MeasuredRun {
    /// The characters of the run.
    pub text: String,
    /// 0 normal, 1 superscript, −1 subscript.
    pub level: i8,
    /// Font size of the run (px).
    pub size: f64,
    /// The glyph of each character.
    glyphs: Vec<GlyphId>,
    /// Pen position after each character, kerning included, accumulated in `f32` exactly as
    /// the glyphs are placed when drawn.
    ends: Vec<f32>,
}

impl MeasuredRun {
    /// Measures plain `text` at font size `size`.
    fn new(text: String, level: i8, size: f64) -> MeasuredRun {
        let n = text.chars().count();
        let mut glyphs = Vec::with_capacity(n);
        let mut ends = Vec::with_capacity(n);
        if let Some(f) = font() {
            let sf = f.as_scaled(PxScale::from(size as f32));
            let mut w = 0.0f32;
            let mut prev: Option<GlyphId> = None;
            for ch in text.chars() {
                let id = sf.glyph_id(ch);
                if let Some(p) = prev {
                    w += sf.kern(p, id);
                }
                w += sf.h_advance(id);
                prev = Some(id);
                glyphs.push(id);
                ends.push(w);
            }
            count_lookups(n);
        }
        MeasuredRun {
            text,
            level,
            size,
            glyphs,
            ends,
        }
    }

    /// Width (px).
    pub fn width(&self) -> f64 {
        f64::from(self.ends.last().copied().unwrap_or(0.0))
    }

    /// The pen position after the first `k ≥ 1` characters followed by an ellipsis (`f32`, as
    /// if the ellipsis were part of this run's text).
    fn end_with_ellipsis(&self, k: usize) -> f32 {
        let Some(f) = font() else { return 0.0 };
        let sf = f.as_scaled(PxScale::from(self.size as f32));
        let id = sf.glyph_id(ELLIPSIS);
        let mut w = self.ends[k - 1];
        w += sf.kern(self.glyphs[k - 1], id);
        w + sf.h_advance(id)
    }

    /// The first `k ≥ 1` characters, with the ellipsis appended.
    fn cut_with_ellipsis(&self, k: usize) -> MeasuredRun {
        let mut text: String = self.text.chars().take(k).collect();
        text.push(ELLIPSIS);
        let mut glyphs = self.glyphs[..k].to_vec();
        let mut ends = self.ends[..k].to_vec();
        if let Some(f) = font() {
            glyphs.push(f.glyph_id(ELLIPSIS));
        }
        ends.push(self.end_with_ellipsis(k));
        MeasuredRun {
            text,
            level: self.level,
            size: self.size,
            glyphs,
            ends,
        }
    }
}

/// Rich text (see [`rich_runs`]) measured once at a font size: shortening it to a width is
/// linear in its length, however often a prefix is tried.
#[derive(Debug, Clone)]
pub(crate) struct Measured {
    /// The base font size (px).
    pub size: f64,
    pub runs: Vec<MeasuredRun>,
}

impl Measured {
    /// Parses the markup of `text` and measures every glyph at font size `size`.
    pub fn new(text: &str, size: f64) -> Measured {
        let runs = rich_runs(text)
            .into_iter()
            .map(|r| {
                let sz = if r.level == 0 { size } else { size * SCRIPT };
                MeasuredRun::new(r.text, r.level, sz)
            })
            .collect();
        Measured { size, runs }
    }

    /// Width (px).
    pub fn width(&self) -> f64 {
        self.runs.iter().map(MeasuredRun::width).sum()
    }

    /// Number of characters shown.
    pub fn chars(&self) -> usize {
        self.runs.iter().map(|r| r.ends.len()).sum()
    }

    /// The text if it fits in `avail` px, otherwise its longest prefix of at least 3
    /// characters that fits with an ellipsis appended (the shortest such prefix when none
    /// fits). Markup survives the cut: a cut inside a superscript keeps the rest of the
    /// prefix raised. One pass over the measured glyphs.
    pub fn shortened(&self, avail: f64) -> Measured {
        let n = self.chars();
        if self.width() <= avail || n <= 4 {
            return self.clone();
        }
        let ellipsis = MeasuredRun::new(ELLIPSIS.to_string(), 0, self.size);
        // Candidates: the first m characters for m = 4 … n − 2; fall back to m = 3.
        let mut best = None;
        let mut before = 0.0;
        let mut offset = 0;
        for (j, run) in self.runs.iter().enumerate() {
            for k in 1..=run.ends.len() {
                let m = offset + k;
                if m < 4 || m > n - 2 {
                    continue;
                }
                let w = if run.level == 0 {
                    before + f64::from(run.end_with_ellipsis(k))
                } else {
                    before + f64::from(run.ends[k - 1]) + ellipsis.width()
                };
                if w <= avail {
                    best = Some((j, k));
                }
            }
            before += run.width();
            offset += run.ends.len();
        }
        let (j, k) = best.unwrap_or_else(|| self.position(3));
        let mut runs: Vec<MeasuredRun> = self.runs[..j].to_vec();
        let Some(run) = self.runs.get(j) else {
            return self.clone();
        };
        if run.level == 0 {
            runs.push(run.cut_with_ellipsis(k));
        } else {
            let mut r = run.clone();
            r.text = r.text.chars().take(k).collect();
            r.glyphs.truncate(k);
            r.ends.truncate(k);
            runs.extend([r, ellipsis]);
        }
        Measured {
            size: self.size,
            runs,
        }
    }

    /// (run, characters in that run) of the m-th character (m ≥ 1).
    fn position(&self, m: usize) -> (usize, usize) {
        let mut left = m;
        for (j, r) in self.runs.iter().enumerate() {
            if left <= r.ends.len() {
                return (j, left);
            }
            left -= r.ends.len();
        }
        (self.runs.len(), 0)
    }
}

impl Canvas {
    /// Width of rich text (see [`rich_runs`]) at font size `size`.
    pub fn text_width(text: &str, size: f64) -> f64 {
        Measured::new(text, size).width()
    }

    /// Draws plain text with its baseline starting at (x, baseline). `rotate`: reading
    /// upwards, the baseline being the column x and the text starting at row `baseline`.
    fn draw_plain(
        &mut self,
        text: &str,
        x: f64,
        baseline: f64,
        size: f64,
        c: Color,
        rotate: bool,
    ) -> Result<()> {
        let f =
            font().ok_or_else(|| LtiError::Plot("the compiled-in font is unavailable".into()))?;
        let scale = PxScale::from(size as f32);
        let sf = f.as_scaled(scale);
        // Horizontal text is laid out at its real sub-pixel position; rotated text at the
        // origin and then turned by a quarter (integer pixel offsets map exactly).
        let (ox, oy) = if rotate {
            (0.0, 0.0)
        } else {
            (x as f32, baseline as f32)
        };
        let (rx, ry) = (x.round() as i64, baseline.round() as i64);
        let mut pen = ox;
        let mut prev: Option<GlyphId> = None;
        let (w, h) = (i64::from(self.w), i64::from(self.h));
        for ch in text.chars() {
            count_lookups(1);
            let id = sf.glyph_id(ch);
            if let Some(p) = prev {
                pen += sf.kern(p, id);
            }
            let glyph = id.with_scale_and_position(scale, point(pen, oy));
            pen += sf.h_advance(id);
            prev = Some(id);
            let Some(og) = f.outline_glyph(glyph) else {
                continue;
            };
            let b = og.px_bounds();
            let (bx, by) = (b.min.x as i64, b.min.y as i64);
            og.draw(|gx, gy, cov| {
                let (px, py) = if rotate {
                    (rx + by + i64::from(gy), ry - bx - i64::from(gx))
                } else {
                    (bx + i64::from(gx), by + i64::from(gy))
                };
                if px >= 0 && py >= 0 && px < w && py < h {
                    self.blend(px as usize, py as usize, c, f64::from(cov));
                }
            });
        }
        Ok(())
    }

    /// Start x and baseline y of text of `width` anchored at `at` with `align`.
    fn anchor(at: (f64, f64), width: f64, size: f64, align: (HAlign, VAlign)) -> (f64, f64) {
        let x0 = match align.0 {
            HAlign::Left => at.0,
            HAlign::Center => at.0 - width / 2.0,
            HAlign::Right => at.0 - width,
        };
        let baseline = match align.1 {
            VAlign::Top => at.1 + CAP * size,
            VAlign::Middle => at.1 + CAP * size / 2.0,
            VAlign::Bottom => at.1 - DESC * size,
        };
        (x0, baseline)
    }

    /// Draws rich text anchored at `at` with `align` (horizontal, vertical).
    pub fn text(
        &mut self,
        text: &str,
        at: (f64, f64),
        size: f64,
        c: Color,
        align: (HAlign, VAlign),
    ) -> Result<()> {
        self.draw_measured(&Measured::new(text, size), at, c, align)
    }

    /// Draws measured text anchored at `at` with `align` (horizontal, vertical).
    pub fn draw_measured(
        &mut self,
        t: &Measured,
        at: (f64, f64),
        c: Color,
        align: (HAlign, VAlign),
    ) -> Result<()> {
        let size = t.size;
        let (mut cx, baseline) = Self::anchor(at, t.width(), size, align);
        for run in &t.runs {
            let dy = match run.level {
                0 => 0.0,
                1 => -SUP_RAISE * size,
                _ => SUB_DROP * size,
            };
            self.draw_plain(&run.text, cx, baseline + dy, run.size, c, false)?;
            cx += run.width();
        }
        Ok(())
    }

    /// [`Canvas::text`] over a translucent white box, for annotations on top of curves;
    /// returns the box (x0, y0, x1, y1).
    pub fn text_on_box(
        &mut self,
        text: &str,
        at: (f64, f64),
        size: f64,
        c: Color,
        align: (HAlign, VAlign),
    ) -> Result<(f64, f64, f64, f64)> {
        let t = Measured::new(text, size);
        let width = t.width();
        let (x0, baseline) = Self::anchor(at, width, size, align);
        let m = 0.15 * size;
        let raise = if text.contains('^') {
            SUP_RAISE * size
        } else {
            0.0
        };
        let bx = (
            x0 - m,
            baseline - CAP * size - raise - m,
            x0 + width + m,
            baseline + DESC * size + 0.5 * m,
        );
        self.fill_rect(bx.0, bx.1, bx.2, bx.3, Color::WHITE, 0.85);
        self.draw_measured(&t, at, c, align)?;
        Ok(bx)
    }

    /// Draws measured text reading upwards, centred vertically at y, its caps centred on x.
    pub fn text_up(&mut self, t: &Measured, x: f64, y: f64, c: Color) -> Result<()> {
        let size = t.size;
        // Rotated (reading upwards): the baseline is a column; caps extend to its left.
        let baseline_x = x + CAP * size / 2.0;
        let mut cy = y + t.width() / 2.0;
        for run in &t.runs {
            let dx = match run.level {
                0 => 0.0,
                1 => -SUP_RAISE * size,
                _ => SUB_DROP * size,
            };
            self.draw_plain(&run.text, baseline_x + dx, cy, run.size, c, true)?;
            cy -= run.width();
        }
        Ok(())
    }
}

/// Font cap height for layout computations.
pub(crate) fn cap_height(size: f64) -> f64 {
    CAP * size
}

/// Descender depth for layout computations.
pub(crate) fn descent(size: f64) -> f64 {
    DESC * size
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_drawn() {
        let mut c = Canvas::new(80, 30);
        c.text(
            "Hg 10^{2}",
            (2.0, 15.0),
            20.0,
            Color::BLACK,
            (HAlign::Left, VAlign::Middle),
        )
        .unwrap();
        assert!(c.pixels().iter().any(|&b| b < 100));
        assert!(Canvas::text_width("10^{2}", 20.0) > Canvas::text_width("10", 20.0));
    }

    /// The shortening loop used before (quadratic: one measurement per prefix), as the
    /// reference for plain text.
    fn shorten_by_remeasuring(title: &str, size: f64, avail: f64) -> String {
        let mut text = title.to_string();
        let mut w = Canvas::text_width(&text, size);
        while w > avail && text.chars().count() > 4 {
            let n = text.chars().count();
            text = text.chars().take(n - 2).collect::<String>() + "…";
            w = Canvas::text_width(&text, size);
        }
        text
    }

    fn shown(t: &Measured) -> String {
        t.runs.iter().map(|r| r.text.as_str()).collect()
    }

    #[test]
    fn shortening_matches_the_remeasuring_loop_on_plain_text() {
        let title = "Bode diagram of G(s) = (s + 1) / (s^3 + 4 s^2 + 0.5 s + 12) with a long tail";
        let title = title.replace('^', "");
        for avail in [0.0, 30.0, 61.5, 100.0, 250.0, 400.0, 10_000.0] {
            for size in [9.0, 13.8, 23.0] {
                let fast = Measured::new(&title, size).shortened(avail);
                let slow = shorten_by_remeasuring(&title, size, avail);
                assert_eq!(shown(&fast), slow, "avail {avail}, size {size}");
                // Same width, to the bit, as measuring the shortened string again.
                assert_eq!(
                    fast.width().to_bits(),
                    Canvas::text_width(&slow, size).to_bits()
                );
                if slow.chars().count() > 4 && slow != title {
                    assert!(fast.width() <= avail);
                }
            }
        }
    }

    #[test]
    fn shortening_keeps_markup() {
        let t = Measured::new("G(s) = 1/(s^{10} + 3 s^{9} + 2 s^{8} + 1)", 20.0);
        let full = t.width();
        // Cut inside the first superscript: the kept digit stays raised, the ellipsis is not.
        let cut = (1..=t.chars())
            .map(|m| t.shortened(full * m as f64 / t.chars() as f64))
            .find(|s| s.runs.len() == 3)
            .unwrap();
        assert_eq!(cut.runs[1].level, 1);
        assert_eq!(cut.runs[2].text, "…");
        assert_eq!(cut.runs[2].level, 0);
        // Never a literal brace or caret from a cut group.
        for k in 0..=40 {
            let s = t.shortened(full * k as f64 / 40.0);
            assert!(!shown(&s).contains('{') && !shown(&s).contains('^'));
        }
    }
}
