//! Gain and phase margins on a Bode diagram: crossover lines, margin bars with their values,
//! and the rows listing them.

use super::panels::{Panels, Ranges, interp_log};
use super::series::{BodeSeries, name_of};
use crate::analysis::FrequencyResponse;
use crate::error::Result;
use crate::fmt::fmt_sig;
use crate::plot::legend::{Avoid, LegendEntry, Rect, box_points};
use crate::plot::raster::{Canvas, Color};
use crate::plot::style::{LineStyle, MarkerShape, Theme};
use crate::plot::text::{HAlign, VAlign};

/// Marks every series' margins in the panels and returns the rows listing them (GM, PM per
/// series; a prefix names the series when there are several). The value labels are added to
/// the points the legends of the (magnitude, phase) panels must not hide.
pub(super) fn mark_margins(
    c: &mut Canvas,
    th: &Theme,
    series: &[BodeSeries],
    colors: &[Color],
    p: &Panels,
    ranges: &Ranges,
    avoid: &mut (Avoid, Avoid),
) -> Result<Vec<LegendEntry>> {
    let mut info: Vec<LegendEntry> = Vec::new();
    let several = series.len() > 1;
    // Values next to the bars only when one series has margins (several would collide; the
    // box lists them all).
    let inline = series.iter().filter(|s| s.margins.is_some()).count() == 1;
    for (k, s) in series.iter().enumerate() {
        let Some(m) = s.margins else { continue };
        let col = colors[k];
        let prefix = if several {
            format!("{}: ", name_of(s, k))
        } else {
            String::new()
        };
        let fmt_w = |w: f64| format!("ω = {} rad/s", fmt_sig(w, 3));
        match (m.gain_margin_db, m.phase_crossover) {
            (Some(gm), Some(wpc)) if gm.is_finite() => {
                if ranges.in_range(wpc) {
                    if let Some(b) =
                        mark_gain_margin(c, th, p, s.response, (wpc, gm), (col, inline))?
                    {
                        avoid.0.extend(box_points(b));
                    }
                }
                info.push(LegendEntry::text(
                    format!("{prefix}GM = {} dB at {}", fmt_margin(gm, 4), fmt_w(wpc)),
                    col,
                ));
            }
            _ => info.push(LegendEntry::text(
                format!("{prefix}GM = ∞ (no phase crossover)"),
                col,
            )),
        }
        match (m.phase_margin_deg, m.gain_crossover) {
            (Some(pm), Some(wgc)) if pm.is_finite() => {
                if ranges.in_range(wgc) {
                    if let Some(b) =
                        mark_phase_margin(c, th, p, s.response, (wgc, pm), (col, inline))?
                    {
                        avoid.1.extend(box_points(b));
                    }
                }
                info.push(LegendEntry::text(
                    format!("{prefix}PM = {}° at {}", fmt_margin(pm, 4), fmt_w(wgc)),
                    col,
                ));
            }
            _ => info.push(LegendEntry::text(
                format!("{prefix}PM = ∞ (no gain crossover)"),
                col,
            )),
        }
    }
    Ok(info)
}

/// The phase crossover ω_pc (dotted in both panels) and the gain margin as a bar from
/// |G(jω_pc)| up to 0 dB, labelled when `inline` (the label's box is returned); `(wpc, gm)`
/// with gm in dB.
fn mark_gain_margin(
    c: &mut Canvas,
    th: &Theme,
    p: &Panels,
    r: &FrequencyResponse,
    (wpc, gm): (f64, f64),
    (col, inline): (Color, bool),
) -> Result<Option<Rect>> {
    let thin = (th.line * 0.6).max(1.0);
    let (mag, ph) = (&p.mag, &p.ph);
    mag.vline(c, wpc, thin, col, LineStyle::Dotted);
    ph.vline(c, wpc, thin, col, LineStyle::Dotted);
    mag.plot_line(
        c,
        [(wpc, -gm), (wpc, 0.0)],
        th.line * 1.4,
        col,
        LineStyle::Solid,
    );
    mag.plot_marker(c, (wpc, -gm), MarkerShape::Disc, 4.0 * th.s, col, th.line);
    if let Some(phase) = interp_log(&r.w, &r.phase_deg, wpc) {
        ph.plot_marker(c, (wpc, phase), MarkerShape::Disc, 4.0 * th.s, col, th.line);
        ph.hline(c, phase, thin, Color(120, 120, 120), LineStyle::Dashed);
    }
    let q = mag.px((wpc, -gm / 2.0));
    if !(inline && mag.contains((wpc, -gm / 2.0))) {
        return Ok(None);
    }
    let b = c.text_on_box(
        &format!("GM {} dB", fmt_margin(gm, 3)),
        (q.0 + 8.0 * th.s, q.1),
        th.note,
        col,
        (HAlign::Left, VAlign::Middle),
    )?;
    Ok(Some(b))
}

/// The gain crossover ω_gc (dotted in both panels) and the phase margin as a bar from φ(ω_gc)
/// to the −180° reference, labelled when `inline` (the label's box is returned); `(wgc, pm)`
/// with pm in degrees.
fn mark_phase_margin(
    c: &mut Canvas,
    th: &Theme,
    p: &Panels,
    r: &FrequencyResponse,
    (wgc, pm): (f64, f64),
    (col, inline): (Color, bool),
) -> Result<Option<Rect>> {
    let thin = (th.line * 0.6).max(1.0);
    let (mag, ph) = (&p.mag, &p.ph);
    mag.vline(c, wgc, thin, col, LineStyle::Dotted);
    ph.vline(c, wgc, thin, col, LineStyle::Dotted);
    mag.plot_marker(c, (wgc, 0.0), MarkerShape::Disc, 4.0 * th.s, col, th.line);
    let Some(phase) = interp_log(&r.w, &r.phase_deg, wgc) else {
        return Ok(None);
    };
    let reference = phase - pm;
    ph.hline(c, reference, thin, Color(120, 120, 120), LineStyle::Dashed);
    ph.plot_line(
        c,
        [(wgc, reference), (wgc, phase)],
        th.line * 1.4,
        col,
        LineStyle::Solid,
    );
    ph.plot_marker(c, (wgc, phase), MarkerShape::Disc, 4.0 * th.s, col, th.line);
    let mid = (wgc, reference + pm / 2.0);
    if !(inline && ph.contains(mid)) {
        return Ok(None);
    }
    let q = ph.px(mid);
    let b = c.text_on_box(
        &format!("PM {}°", fmt_margin(pm, 3)),
        (q.0 + 8.0 * th.s, q.1),
        th.note,
        col,
        (HAlign::Left, VAlign::Middle),
    )?;
    Ok(Some(b))
}

/// A margin in dB or degrees for display: rounding residue below 1e-9 shows as 0.
fn fmt_margin(x: f64, sig: usize) -> String {
    fmt_sig(if x.abs() < 1e-9 { 0.0 } else { x }, sig)
}
