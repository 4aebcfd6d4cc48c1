//! Drawing the Bode diagram: grids, asymptotes, the curves, the margins, axes, legends and
//! the title, in that order.

use std::path::Path;

use super::margins::mark_margins;
use super::panels::{Panels, data_ranges, layout_panels, nyquist_frequencies};
use super::series::{BodeSeries, check, color_of, name_of};
use crate::error::Result;
use crate::fmt::fmt_sig;
use crate::plot::layout::draw_title;
use crate::plot::legend::{Avoid, Corner, LegendEntry, box_points, draw_legend, sample_run};
use crate::plot::options::PlotOptions;
use crate::plot::raster::{Canvas, Color};
use crate::plot::render::render;
use crate::plot::style::{LineStyle, Theme};
use crate::plot::text::{HAlign, VAlign};

/// Writes a Bode diagram of one or more plants.
///
/// The magnitude panel (dB) sits over the phase panel (degrees, ticks at multiples of 45° or
/// 90°); the shared ω axis (rad/s) is logarithmic with decade grid lines labelled 10^k. With
/// margins, the gain crossover ω_gc and phase crossover ω_pc are drawn as vertical lines, the
/// gain margin as a bar from |G(jω_pc)| up to 0 dB and the phase margin as a bar from φ(ω_gc)
/// to the −180° reference, with the values listed. For a discrete plant (a series with a
/// Nyquist frequency) the ω axis reaches a little beyond π/T, where the response ends, and a
/// dash-dotted vertical line labelled "π/T = … rad/s" marks it. Asymptotes are drawn dashed. Points that
/// are not finite (−∞ dB at a zero on the axis) break the curve.
///
/// Errors: no series, mismatched lengths, fewer than two finite points, bad options, a title
/// or label longer than [`MAX_TEXT_CHARS`](crate::plot::MAX_TEXT_CHARS) characters, an unwritable
/// path ([`LtiError::Plot`](crate::error::LtiError::Plot) /
/// [`LtiError::Io`](crate::error::LtiError::Io)); no file is left behind.
///
/// ```no_run
/// use ltikit::analysis::FrequencyResponse;
/// use ltikit::plot::{bode_png, BodeSeries, PlotOptions};
/// // 1/(s + 1) from its closed form.
/// let w: Vec<f64> = (0..=300).map(|k| 10f64.powf(-2.0 + k as f64 / 75.0)).collect();
/// let magnitude: Vec<f64> = w.iter().map(|w| 1.0 / (1.0 + w * w).sqrt()).collect();
/// let fr = FrequencyResponse {
///     magnitude_db: magnitude.iter().map(|m| 20.0 * m.log10()).collect(),
///     phase_deg: w.iter().map(|w| -w.atan().to_degrees()).collect(),
///     w,
///     magnitude,
/// };
/// bode_png("/tmp/bode.png", &[BodeSeries::new(&fr).label("1/(s + 1)")], &PlotOptions::default()).unwrap();
/// ```
pub fn bode_png(path: impl AsRef<Path>, series: &[BodeSeries], opts: &PlotOptions) -> Result<()> {
    check(series)?;
    let title = opts.title_or(|| match (series.len(), series[0].label) {
        (1, Some(l)) => format!(
            "Bode diagram of G({}) = {l}",
            if series[0].nyquist_frequency.is_some() {
                "z"
            } else {
                "s"
            }
        ),
        _ => "Bode diagram".into(),
    });
    render(path.as_ref(), opts, |c, th| {
        draw(c, th, series, opts, title.as_deref())
    })
}

/// Grids and the 0 dB line.
fn draw_background(c: &mut Canvas, th: &Theme, p: &Panels, grid: bool) {
    if grid {
        p.mag.draw_grid(c, th);
        p.ph.draw_grid(c, th);
    }
    if p.mag.y.lo < 0.0 && p.mag.y.hi > 0.0 {
        let thin = (th.line * 0.6).max(1.0);
        p.mag
            .hline(c, 0.0, thin, Color(120, 120, 120), LineStyle::Solid);
    }
}

/// Asymptotes, dashed and lighter, under the curves.
fn draw_asymptotes(c: &mut Canvas, th: &Theme, series: &[BodeSeries], p: &Panels) {
    for (k, s) in series.iter().enumerate() {
        if let Some(a) = s.asymptotes {
            let col = color_of(series, k).lighten(0.25);
            p.mag.plot_line(
                c,
                a.magnitude_db.iter().copied(),
                th.line * 0.8,
                col,
                LineStyle::Dashed,
            );
            p.ph.plot_line(
                c,
                a.phase_deg.iter().copied(),
                th.line * 0.8,
                col,
                LineStyle::Dashed,
            );
        }
    }
}

/// The points (ω, y) with y = NaN (a break in the curve) where ω ≤ 0.
fn positive_w<'a>(w: &'a [f64], ys: &'a [f64]) -> impl Iterator<Item = (f64, f64)> + 'a {
    w.iter()
        .zip(ys)
        .map(|(&w, &y)| (w, if w > 0.0 { y } else { f64::NAN }))
}

/// The magnitude and phase curves; returns the pixel points to keep legends off (magnitude,
/// phase).
fn draw_curves(c: &mut Canvas, th: &Theme, series: &[BodeSeries], p: &Panels) -> (Avoid, Avoid) {
    let mut avoid_mag = Vec::new();
    let mut avoid_ph = Vec::new();
    for (k, s) in series.iter().enumerate() {
        let r = s.response;
        for run in p.mag.clip_polyline(positive_w(&r.w, &r.magnitude_db)) {
            c.stroke(&run, th.line, color_of(series, k), &[]);
            avoid_mag.extend(sample_run(&run, 6.0));
        }
        for run in p.ph.clip_polyline(positive_w(&r.w, &r.phase_deg)) {
            c.stroke(&run, th.line, color_of(series, k), &[]);
            avoid_ph.extend(sample_run(&run, 6.0));
        }
    }
    (avoid_mag, avoid_ph)
}

/// The Nyquist frequency π/T of each discrete series: a vertical line through both panels,
/// labelled at the top of the magnitude panel (the label is kept clear of the legend).
fn mark_nyquist_frequencies(
    c: &mut Canvas,
    th: &Theme,
    series: &[BodeSeries],
    p: &Panels,
    avoid: &mut (Avoid, Avoid),
) -> Result<()> {
    let col = Color(90, 90, 90);
    let width = (th.line * 0.8).max(1.0);
    for (i, wn) in nyquist_frequencies(series).into_iter().enumerate() {
        p.mag.vline(c, wn, width, col, LineStyle::DashDot);
        p.ph.vline(c, wn, width, col, LineStyle::DashDot);
        let text = format!("π/T = {} rad/s", fmt_sig(wn, 3));
        let (top, bottom) = (p.mag.y.hi, p.mag.y.lo);
        if !p.mag.contains((wn, top)) {
            continue;
        }
        // at the top of the panel, or at its bottom when fewer curve points lie there
        let width = Canvas::text_width(&text, th.note);
        let height = 1.3 * th.note;
        let x = p.mag.px((wn, top)).0 - 4.0 * th.s;
        let step = (6.0 + 18.0 * i as f64) * th.s;
        let y_top = p.mag.px((wn, top)).1 + step;
        let y_bottom = p.mag.px((wn, bottom)).1 - step;
        let hits = |y0: f64| {
            avoid
                .0
                .iter()
                .filter(|q| q.0 >= x - width && q.0 <= x && q.1 >= y0 && q.1 <= y0 + height)
                .count()
        };
        let (at, valign) = if hits(y_top) <= hits(y_bottom - height) {
            ((x, y_top), VAlign::Top)
        } else {
            ((x, y_bottom), VAlign::Bottom)
        };
        let b = c.text_on_box(&text, at, th.note, col, (HAlign::Right, valign))?;
        avoid.0.extend(box_points(b));
    }
    Ok(())
}

/// Axis frames, ticks and titles of both panels.
fn draw_axes(c: &mut Canvas, th: &Theme, p: &Panels) -> Result<()> {
    p.mag.draw_axes(c, th, false, true)?;
    p.ph.draw_axes(c, th, true, true)?;
    p.mag
        .draw_axis_titles(c, th, None, Some("Magnitude (dB)"), th.pad)?;
    p.ph.draw_axis_titles(
        c,
        th,
        Some("Frequency ω (rad/s)"),
        Some("Phase (deg)"),
        th.pad,
    )
}

/// Legend (plants, asymptotes) in the magnitude panel; margin values in the phase panel.
fn draw_legends(
    c: &mut Canvas,
    th: &Theme,
    series: &[BodeSeries],
    p: &Panels,
    avoid: &(Avoid, Avoid),
    info: &[LegendEntry],
) -> Result<()> {
    let mut legend: Vec<LegendEntry> = Vec::new();
    if series.len() > 1 || series[0].asymptotes.is_some() {
        for (k, s) in series.iter().enumerate() {
            legend.push(LegendEntry::line(
                name_of(s, k),
                color_of(series, k),
                LineStyle::Solid,
            ));
        }
    }
    if series.iter().any(|s| s.asymptotes.is_some()) {
        legend.push(LegendEntry::line(
            "asymptotes",
            Color(110, 110, 110),
            LineStyle::Dashed,
        ));
    }
    let corners = [
        Corner::TopRight,
        Corner::BottomLeft,
        Corner::TopLeft,
        Corner::BottomRight,
    ];
    draw_legend(c, &p.mag, th, &legend, &avoid.0, &corners, &[])?;
    draw_legend(
        c,
        &p.ph,
        th,
        info,
        &avoid.1,
        &[
            Corner::BottomLeft,
            Corner::TopRight,
            Corner::BottomRight,
            Corner::TopLeft,
        ],
        &[],
    )?;
    Ok(())
}

fn draw(
    c: &mut Canvas,
    th: &Theme,
    series: &[BodeSeries],
    opts: &PlotOptions,
    title: Option<&str>,
) -> Result<()> {
    let ranges = data_ranges(series)?;
    let panels = layout_panels(c, th, title.is_some(), &ranges);
    draw_background(c, th, &panels, opts.grid);
    draw_asymptotes(c, th, series, &panels);
    let mut avoid = draw_curves(c, th, series, &panels);
    let colors: Vec<Color> = (0..series.len()).map(|k| color_of(series, k)).collect();
    let info = mark_margins(c, th, series, &colors, &panels, &ranges, &mut avoid)?;
    mark_nyquist_frequencies(c, th, series, &panels, &mut avoid)?;
    draw_axes(c, th, &panels)?;
    draw_legends(c, th, series, &panels, &avoid, &info)?;
    if let Some(t) = title {
        draw_title(c, th, t)?;
    }
    Ok(())
}
