//! Options common to every plot and the limits on what a plot accepts: the image size, the
//! font and line scales, the title, and the length of any text.

use crate::error::{LtiError, Result};

/// Smallest accepted image side (px).
pub const MIN_SIDE: u32 = 100;
pub use crate::limits::{MAX_PIXELS, MAX_SIDE};
/// Longest accepted title, label, legend text or note, in characters (Unicode scalar values,
/// markup included).
///
/// Text that does not fit is shrunk or cut with an ellipsis, in time linear in its length; this
/// limit only refuses text that no accepted image could show: the widest image
/// ([`MAX_SIDE`] px) at the smallest font shows about 12 000 characters on one line. Labels
/// generated from plants of the highest order ([`crate::MAX_ORDER`]) stay below 10 000 characters.
///
/// ```
/// use ltikit::plot::{MAX_TEXT_CHARS, PlotOptions};
/// let ok = PlotOptions { title: Some("x".repeat(MAX_TEXT_CHARS)), ..Default::default() };
/// assert!(ok.validate().is_ok());
/// let long = PlotOptions { title: Some("x".repeat(MAX_TEXT_CHARS + 1)), ..Default::default() };
/// let e = long.validate().unwrap_err();
/// assert!(e.to_string().contains("MAX_TEXT_CHARS"), "{e}");
/// ```
pub const MAX_TEXT_CHARS: usize = crate::limits::MAX_TEXT_CHARS;

/// Checks that `text` (`what`, e.g. "the title") has at most [`MAX_TEXT_CHARS`] characters.
pub(crate) fn check_text(what: &str, text: &str) -> Result<()> {
    // A string of at most MAX_TEXT_CHARS bytes has at most as many characters: no count.
    if text.len() <= MAX_TEXT_CHARS {
        return Ok(());
    }
    let n = text.chars().count();
    if n > MAX_TEXT_CHARS {
        return Err(LtiError::Plot(format!(
            "{what} has {n} characters, more than the limit of {MAX_TEXT_CHARS} (MAX_TEXT_CHARS)"
        )));
    }
    Ok(())
}

/// Options common to every plot.
///
/// ```
/// use ltikit::plot::PlotOptions;
/// let o = PlotOptions { size: (800, 600), title: Some("Plant".into()), ..Default::default() };
/// assert_eq!(o.font_scale, 1.0);
/// assert!(o.validate().is_ok());
/// assert!(PlotOptions { size: (0, 600), ..Default::default() }.validate().is_err());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PlotOptions {
    /// Image size in pixels (width, height); default 1000 × 700.
    pub size: (u32, u32),
    /// Title; `None` gives each plot's default title (naming the plant), `Some("")` none.
    pub title: Option<String>,
    /// Font scale, like a dpi setting (1 = default). Fonts and line widths also grow with the
    /// image size beyond 1000 × 700.
    pub font_scale: f64,
    /// Line-width scale (1 = default).
    pub line_scale: f64,
    /// Draw grid lines.
    pub grid: bool,
}

impl Default for PlotOptions {
    fn default() -> Self {
        PlotOptions {
            size: (1000, 700),
            title: None,
            font_scale: 1.0,
            line_scale: 1.0,
            grid: true,
        }
    }
}

impl PlotOptions {
    /// Checks the size (each side in [`MIN_SIDE`]…[`MAX_SIDE`], at most [`MAX_PIXELS`]), the
    /// scales (finite, 0.25…8) and the title (at most [`MAX_TEXT_CHARS`] characters).
    pub fn validate(&self) -> Result<()> {
        let (w, h) = self.size;
        if w == 0 || h == 0 {
            return Err(LtiError::Plot(format!("`size` {w}x{h} is empty")));
        }
        if w < MIN_SIDE || h < MIN_SIDE {
            return Err(LtiError::Plot(format!(
                "`size` {w}x{h} is too small (each side at least {MIN_SIDE} px)"
            )));
        }
        // a plot error like the others, with the limit's words
        let plot = |e: LtiError| LtiError::Plot(e.to_string());
        crate::limits::SIDE
            .check("`size`", u128::from(w.max(h)))
            .map_err(plot)?;
        crate::limits::PIXELS
            .check("`size` (width × height)", u128::from(w) * u128::from(h))
            .map_err(plot)?;
        for (name, v) in [
            ("`font_scale`", self.font_scale),
            ("line scale", self.line_scale),
        ] {
            if !v.is_finite() || !(0.25..=8.0).contains(&v) {
                return Err(LtiError::Plot(format!(
                    "{name} {} is outside 0.25…8",
                    crate::error::number(v)
                )));
            }
        }
        if let Some(t) = &self.title {
            check_text("`title`", t)?;
        }
        Ok(())
    }

    /// The title to draw: the explicit one (none if empty) or `default`.
    pub(crate) fn title_or(&self, default: impl FnOnce() -> String) -> Option<String> {
        match &self.title {
            Some(t) if t.is_empty() => None,
            Some(t) => Some(t.clone()),
            None => Some(default()).filter(|t| !t.is_empty()),
        }
    }
}

/// Parses an image size written `WxH` (also `W×H` or `W,H`), e.g. for a `size` option.
///
/// ```
/// assert_eq!(ltikit::plot::parse_size("1200x800").unwrap(), (1200, 800));
/// assert!(ltikit::plot::parse_size("1200").is_err());
/// ```
pub fn parse_size(s: &str) -> Result<(u32, u32)> {
    let bad = || {
        LtiError::Plot(format!(
            "`size` '{}' is not WIDTHxHEIGHT (e.g. 1000x700)",
            crate::error::abbreviate(s)
        ))
    };
    let t = s.trim().to_ascii_lowercase().replace(['×', ','], "x");
    let (a, b) = t.split_once('x').ok_or_else(bad)?;
    let side = |x: &str| -> Result<u32> {
        let x = x.trim();
        if x.is_empty() || !x.bytes().all(|c| c.is_ascii_digit()) {
            return Err(bad());
        }
        let too_large = || {
            let l = crate::limits::SIDE;
            LtiError::Plot(format!(
                "`size`: {} exceeds the limit of {} ({})",
                crate::error::abbreviate(x),
                crate::limits::amount(l.max, l.unit),
                l.name
            ))
        };
        // more digits than any side could have: too large, not malformed
        let v = x.parse::<u128>().map_err(|_| too_large())?;
        crate::limits::SIDE
            .check("`size`", v)
            .map_err(|_| too_large())?;
        u32::try_from(v).map_err(|_| bad())
    };
    let (w, h) = (side(a)?, side(b)?);
    let o = PlotOptions {
        size: (w, h),
        ..Default::default()
    };
    o.validate()?;
    Ok((w, h))
}

/// Checks the label of series `k` (0-based) against [`MAX_TEXT_CHARS`].
pub(crate) fn check_label(k: usize, label: Option<&str>) -> Result<()> {
    match label {
        Some(l) => check_text(&format!("the label of series {}", k + 1), l),
        None => Ok(()),
    }
}
