//! Rendering a plot: the options checked, a white canvas of their size, the theme, the
//! plot's drawing, and the PNG written atomically.

use std::path::Path;

use super::options::PlotOptions;
use super::raster::Canvas;
use super::style::Theme;
use super::text::check_font;
use crate::error::Result;

/// Renders with `draw` and writes the PNG atomically.
pub(crate) fn render(
    path: &Path,
    opts: &PlotOptions,
    draw: impl FnOnce(&mut Canvas, &Theme) -> Result<()>,
) -> Result<()> {
    opts.validate()?;
    check_font()?;
    let mut canvas = Canvas::new(opts.size.0, opts.size.1);
    let theme = Theme::new(opts);
    draw(&mut canvas, &theme)?;
    super::output::write_png(&canvas, path)
}
