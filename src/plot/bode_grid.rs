//! Bode grid of a MIMO plant: one cell per channel, rows = outputs, columns = inputs; each
//! cell a magnitude panel (dB) over a phase panel (degrees) on a log-ω axis shared by the
//! whole grid, with the magnitude and phase ranges shared too (channels compare at a glance).

use std::path::Path;

use super::axes::Axis;
use super::frame::Frame;
use super::layout::{
    bottom_margin, bounds, check_span, draw_title, left_margin, right_margin, tick_targets,
    top_margin,
};
use super::options::{PlotOptions, check_text};
use super::raster::{Canvas, Color};
use super::render::render;
use super::style::{LineStyle, Theme, series_color};
use super::text::{HAlign, Measured, VAlign, cap_height, descent};
use crate::analysis::FrequencyResponse;
use crate::error::{LtiError, Result};
use crate::fmt::fmt_sig;

/// The channels of a MIMO plant for [`bode_grid_png`].
///
/// ```
/// use ltikit::analysis::FrequencyResponse;
/// use ltikit::plot::BodeGrid;
/// let fr = FrequencyResponse { w: vec![0.1, 1.0], magnitude: vec![1.0, 0.7],
///                              magnitude_db: vec![0.0, -3.0], phase_deg: vec![-6.0, -45.0] };
/// let grid = BodeGrid {
///     inputs: vec!["u1".into()],
///     outputs: vec!["y1".into()],
///     cells: vec![(0, 0, &fr)],
///     nyquist_frequency: None,
/// };
/// assert_eq!(grid.cells.len(), 1);
/// ```
#[derive(Debug, Clone)]
pub struct BodeGrid<'a> {
    /// Input names (the columns).
    pub inputs: Vec<String>,
    /// Output names (the rows).
    pub outputs: Vec<String>,
    /// (input, output, response), 0-based; a cell not listed stays empty.
    pub cells: Vec<(usize, usize, &'a FrequencyResponse)>,
    /// π/T of a discrete plant (T its sampling period): a dash-dot line in every cell, named
    /// under the ω axis; `None` in continuous time.
    pub nyquist_frequency: Option<f64>,
}

fn check(g: &BodeGrid) -> Result<()> {
    let bad = |m: String| Err(LtiError::Plot(format!("Bode grid: {m}")));
    if g.cells.is_empty() || g.inputs.is_empty() || g.outputs.is_empty() {
        return bad("no channel given".into());
    }
    for name in g.inputs.iter().chain(&g.outputs) {
        check_text("a signal name", name)?;
    }
    if let Some(w) = g.nyquist_frequency
        && !(w.is_finite() && w > 0.0)
    {
        return bad(format!(
            "the Nyquist frequency must be finite and > 0, got {w}"
        ));
    }
    for (i, o, r) in &g.cells {
        if *i >= g.inputs.len() || *o >= g.outputs.len() {
            return bad(format!("channel {} → {} does not exist", i + 1, o + 1));
        }
        let n = r.w.len();
        if r.magnitude_db.len() != n || r.phase_deg.len() != n {
            return bad(format!("channel {} → {}: lengths differ", i + 1, o + 1));
        }
        let good = (0..n)
            .filter(|&k| {
                r.w[k] > 0.0
                    && r.w[k].is_finite()
                    && r.magnitude_db[k].is_finite()
                    && r.phase_deg[k].is_finite()
            })
            .count();
        if good < 2 {
            return bad(format!(
                "channel {} → {} has fewer than two finite points with ω > 0",
                i + 1,
                o + 1
            ));
        }
    }
    Ok(())
}

/// Writes the Bode grid of a MIMO plant: rows = outputs, columns = inputs, each cell headed
/// "input → output" with its magnitude (dB) over its phase (degrees); tick labels on the left
/// column and the bottom row only.
///
/// Errors: no channel, a channel outside the names, mismatched lengths, fewer than two finite
/// points in a cell, cells too small for the image (give a larger size), bad options, an
/// unwritable path ([`LtiError::Plot`] / [`LtiError::Io`]); no file is left behind.
///
/// ```no_run
/// use ltikit::analysis::FrequencyResponse;
/// use ltikit::plot::{BodeGrid, PlotOptions, bode_grid_png};
/// // 1/(s + 1) from its closed form, on the diagonal of a 2 × 2 grid.
/// let w: Vec<f64> = (0..=300).map(|k| 10f64.powf(-2.0 + k as f64 / 75.0)).collect();
/// let magnitude: Vec<f64> = w.iter().map(|w| 1.0 / (1.0 + w * w).sqrt()).collect();
/// let fr = FrequencyResponse {
///     magnitude_db: magnitude.iter().map(|m| 20.0 * m.log10()).collect(),
///     phase_deg: w.iter().map(|w| -w.atan().to_degrees()).collect(),
///     w,
///     magnitude,
/// };
/// let grid = BodeGrid { inputs: vec!["u1".into(), "u2".into()],
///                       outputs: vec!["y1".into(), "y2".into()],
///                       cells: vec![(0, 0, &fr), (1, 1, &fr)], nyquist_frequency: None };
/// bode_grid_png("/tmp/grid.png", &grid, &PlotOptions::default()).unwrap();
/// ```
pub fn bode_grid_png(path: impl AsRef<Path>, grid: &BodeGrid, opts: &PlotOptions) -> Result<()> {
    check(grid)?;
    let title = opts.title_or(|| {
        format!(
            "Bode diagram: {} inputs × {} outputs",
            grid.inputs.len(),
            grid.outputs.len()
        )
    });
    render(path.as_ref(), opts, |c, th| {
        draw(c, th, grid, title.as_deref())
    })
}

/// A closed interval (lo, hi).
type Span = (f64, f64);

/// The shared ranges: ω, magnitude (dB, at most 300 dB deep, padded), phase.
fn ranges(grid: &BodeGrid) -> Result<(Span, Span, Span)> {
    let pts = || {
        grid.cells.iter().flat_map(|(_, _, r)| {
            (0..r.w.len())
                .filter(|&k| r.w[k] > 0.0)
                .map(move |k| (r.w[k], r.magnitude_db[k], r.phase_deg[k]))
        })
    };
    let mut w = bounds(pts().map(|p| p.0)).unwrap_or((0.1, 10.0));
    // a discrete plant's response ends at π/T: a little room beyond it, so that its line
    // stands inside the frames (as in the single-channel Bode diagram)
    if let Some(wn) = grid.nyquist_frequency {
        w.1 = w.1.max(wn * 1.3);
    }
    let (mut lo, mut hi) = bounds(pts().map(|p| p.1)).unwrap_or((-1.0, 1.0));
    lo = lo.max(hi - 300.0);
    let pad = 0.04 * (hi - lo).max(1.0);
    lo -= pad;
    hi += pad;
    let ph = bounds(pts().map(|p| p.2)).unwrap_or((-1.0, 1.0));
    check_span("magnitudes (dB)", (lo, hi))?;
    check_span("phases (degrees)", ph)?;
    Ok((w, (lo, hi), ph))
}

/// Pixel geometry of the grid.
struct Geometry {
    left: f64,
    top: f64,
    cell_w: f64,
    cell_h: f64,
    gap_x: f64,
    gap_y: f64,
    caption: f64,
    panel_h: f64,
    inner_gap: f64,
}

fn geometry(
    c: &Canvas,
    th: &Theme,
    title: bool,
    axes: &(Axis, Axis, Axis),
    m: usize,
    p: usize,
) -> Result<Geometry> {
    let (cw, ch) = (f64::from(c.w), f64::from(c.h));
    let left = left_margin(th, &axes.1, true).max(left_margin(th, &axes.2, true));
    let right = right_margin(th, &axes.0);
    let bottom = bottom_margin(th, &axes.0, true);
    let top = top_margin(th, title, false);
    let (gap_x, gap_y) = (18.0 * th.s, 16.0 * th.s);
    let caption = cap_height(th.note) + descent(th.note) + 6.0 * th.s;
    let inner_gap = 6.0 * th.s;
    let cell_w = (cw - left - right - gap_x * (m as f64 - 1.0)) / m as f64;
    let cell_h = (ch - top - bottom - gap_y * (p as f64 - 1.0)) / p as f64;
    let panel_h = (cell_h - caption - inner_gap) / 2.0;
    if cell_w < 60.0 || panel_h < 24.0 {
        return Err(LtiError::Plot(format!(
            "Bode grid: {p} × {m} cells do not fit in {}x{} px; give a larger `size` or \
             choose a `channel`",
            c.w, c.h
        )));
    }
    Ok(Geometry {
        left,
        top,
        cell_w,
        cell_h,
        gap_x,
        gap_y,
        caption,
        panel_h,
        inner_gap,
    })
}

/// The magnitude and phase frames of the cell (input i, output o).
fn cell_frames(g: &Geometry, axes: &(Axis, Axis, Axis), i: usize, o: usize) -> (Frame, Frame) {
    let x0 = g.left + i as f64 * (g.cell_w + g.gap_x);
    let y0 = g.top + o as f64 * (g.cell_h + g.gap_y) + g.caption;
    let mag = Frame {
        x0,
        y0,
        x1: x0 + g.cell_w,
        y1: y0 + g.panel_h,
        x: axes.0.clone(),
        y: axes.1.clone(),
    };
    let y0 = y0 + g.panel_h + g.inner_gap;
    let ph = Frame {
        x0,
        y0,
        x1: x0 + g.cell_w,
        y1: y0 + g.panel_h,
        x: axes.0.clone(),
        y: axes.2.clone(),
    };
    (mag, ph)
}

fn draw(c: &mut Canvas, th: &Theme, grid: &BodeGrid, title: Option<&str>) -> Result<()> {
    let (m, p) = (grid.inputs.len(), grid.outputs.len());
    let (w, mag, ph) = ranges(grid)?;
    let make = |cell_w: f64, panel_h: f64| {
        let (nx, ny) = tick_targets(cell_w, panel_h, th);
        (
            Axis::log(w.0, w.1, nx),
            Axis::linear_from(mag.0, mag.1, ny.max(3), false, &[1.0, 2.0, 5.0, 10.0]),
            Axis::degrees(ph.0, ph.1, ny.max(3)),
        )
    };
    let guess = (
        f64::from(c.w) * 0.8 / m as f64,
        f64::from(c.h) * 0.35 / p as f64,
    );
    let mut axes = make(guess.0, guess.1);
    let g = geometry(c, th, title.is_some(), &axes, m, p)?;
    axes = make(g.cell_w, g.panel_h);
    for o in 0..p {
        for i in 0..m {
            let (fm, fp) = cell_frames(&g, &axes, i, o);
            fm.draw_grid(c, th);
            fp.draw_grid(c, th);
            let cell = grid.cells.iter().find(|(a, b, _)| *a == i && *b == o);
            if let Some((_, _, r)) = cell {
                let col = series_color(0);
                let pts = |ys: &[f64]| -> Vec<(f64, f64)> {
                    r.w.iter()
                        .zip(ys)
                        .map(|(&w, &y)| (w, if w > 0.0 { y } else { f64::NAN }))
                        .collect()
                };
                for run in fm.clip_polyline(pts(&r.magnitude_db)) {
                    c.stroke(&run, th.line, col, &[]);
                }
                for run in fp.clip_polyline(pts(&r.phase_deg)) {
                    c.stroke(&run, th.line, col, &[]);
                }
            }
            if let Some(wn) = grid.nyquist_frequency {
                let (grey, width) = (Color(90, 90, 90), (th.line * 0.8).max(1.0));
                fm.vline(c, wn, width, grey, LineStyle::DashDot);
                fp.vline(c, wn, width, grey, LineStyle::DashDot);
            }
            let (first_col, last_row) = (i == 0, o + 1 == p);
            fm.draw_axes(c, th, false, first_col)?;
            fp.draw_axes(c, th, last_row, first_col)?;
            if first_col {
                fm.draw_axis_titles(c, th, None, Some("dB"), th.pad)?;
                fp.draw_axis_titles(c, th, None, Some("deg"), th.pad)?;
            }
            if last_row {
                let title = match grid.nyquist_frequency {
                    Some(wn) => format!("ω (rad/s); dash-dot: π/T = {} rad/s", fmt_sig(wn, 3)),
                    None => "ω (rad/s)".into(),
                };
                fp.draw_axis_titles(c, th, Some(&title), None, th.pad)?;
            }
            let caption = format!("{} → {}", grid.inputs[i], grid.outputs[o]);
            let t = Measured::new(&caption, th.note).shortened(g.cell_w);
            c.draw_measured(
                &t,
                ((fm.x0 + fm.x1) / 2.0, fm.y0 - 4.0 * th.s),
                Theme::NOTE,
                (HAlign::Center, VAlign::Bottom),
            )?;
        }
    }
    if let Some(t) = title {
        draw_title(c, th, t)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn first_order() -> FrequencyResponse {
        let w: Vec<f64> = (0..=100)
            .map(|k| 10f64.powf(-2.0 + k as f64 / 25.0))
            .collect();
        let magnitude: Vec<f64> = w.iter().map(|w| 1.0 / (1.0 + w * w).sqrt()).collect();
        FrequencyResponse {
            magnitude_db: magnitude.iter().map(|m| 20.0 * m.log10()).collect(),
            phase_deg: w.iter().map(|w| -w.atan().to_degrees()).collect(),
            w,
            magnitude,
        }
    }

    #[test]
    fn a_discrete_grid_marks_and_makes_room_for_pi_over_t() {
        let fr = first_order();
        let mut grid = BodeGrid {
            inputs: vec!["u".into()],
            outputs: vec!["y".into()],
            cells: vec![(0, 0, &fr)],
            nyquist_frequency: Some(31.4),
        };
        let (w, _, _) = ranges(&grid).unwrap();
        assert!(w.1 >= 1.3 * 31.4, "{w:?}");
        let path = std::env::temp_dir().join("ltikit-bode-grid-dt-test.png");
        bode_grid_png(&path, &grid, &PlotOptions::default()).unwrap();
        assert!(path.exists());
        let _ = std::fs::remove_file(&path);
        grid.nyquist_frequency = Some(f64::NAN);
        let e = bode_grid_png(&path, &grid, &PlotOptions::default()).unwrap_err();
        assert!(e.to_string().contains("Nyquist frequency"), "{e}");
        assert!(!path.exists());
    }

    #[test]
    fn bad_grids_are_refused() {
        let fr = first_order();
        let grid = |cells| BodeGrid {
            inputs: vec!["u".into()],
            outputs: vec!["y".into()],
            cells,
            nyquist_frequency: None,
        };
        let dir = std::env::temp_dir().join("ltikit-bode-grid-test.png");
        let e = bode_grid_png(&dir, &grid(vec![]), &PlotOptions::default()).unwrap_err();
        assert!(e.to_string().contains("no channel"), "{e}");
        let e = bode_grid_png(&dir, &grid(vec![(1, 0, &fr)]), &PlotOptions::default()).unwrap_err();
        assert!(e.to_string().contains("does not exist"), "{e}");
        let many = BodeGrid {
            inputs: (0..40).map(|k| format!("u{k}")).collect(),
            outputs: vec!["y".into()],
            cells: vec![(0, 0, &fr)],
            nyquist_frequency: None,
        };
        let e = bode_grid_png(&dir, &many, &PlotOptions::default()).unwrap_err();
        assert!(e.to_string().contains("do not fit"), "{e}");
        assert!(!dir.exists());
    }
}
