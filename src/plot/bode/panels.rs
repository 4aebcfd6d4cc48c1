//! The geometry of a Bode diagram: the data ranges (curves, margin bars and asymptotes) and
//! the magnitude panel over the phase panel on a shared log-ω axis; values read off a curve
//! by interpolation on log ω.

use super::series::BodeSeries;
use crate::error::Result;
use crate::plot::axes::Axis;
use crate::plot::frame::Frame;
use crate::plot::layout::{
    bottom_margin, bounds, check_span, left_margin, right_margin, tick_targets, top_margin,
};
use crate::plot::raster::Canvas;
use crate::plot::style::Theme;

/// Linear interpolation of `ys` at `w` on log ω.
pub(super) fn interp_log(ws: &[f64], ys: &[f64], w: f64) -> Option<f64> {
    let x = w.log10();
    let k = ws.windows(2).position(|p| p[0] <= w && w <= p[1])?;
    let (a, b) = (ws[k].log10(), ws[k + 1].log10());
    let (ya, yb) = (ys[k], ys[k + 1]);
    if !(ya.is_finite() && yb.is_finite()) {
        return None;
    }
    Some(if b > a {
        ya + (yb - ya) * (x - a) / (b - a)
    } else {
        ya
    })
}

/// The data ranges of a Bode diagram.
#[derive(Debug, Clone, Copy)]
pub(super) struct Ranges {
    /// ω range (positive frequencies).
    pub w: (f64, f64),
    /// Magnitude range (dB), padded.
    pub mag: (f64, f64),
    /// Phase range (degrees).
    pub phase: (f64, f64),
}

impl Ranges {
    /// Whether ω lies inside the drawn frequency range.
    pub fn in_range(&self, w: f64) -> bool {
        w >= self.w.0 && w <= self.w.1
    }
}

/// How far the ω axis reaches beyond the highest Nyquist frequency (a factor).
const NYQUIST_ROOM: f64 = 1.3;

/// The distinct Nyquist frequencies π/T of the series, ascending.
pub(super) fn nyquist_frequencies(series: &[BodeSeries]) -> Vec<f64> {
    let mut v: Vec<f64> = series.iter().filter_map(|s| s.nyquist_frequency).collect();
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * b.abs());
    v
}

/// The largest magnitude span drawn (dB).
const MAX_DB_SPAN: f64 = 300.0;

/// The window [lo, lo + `span`] over the finite `values` that holds the most of them (the
/// highest among equals), as (lo, hi) with hi the largest value inside.
fn densest_window(values: &[f64], span: f64) -> Option<(f64, f64)> {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    v.sort_by(f64::total_cmp);
    let mut best: Option<(usize, usize)> = None; // (count, start index)
    let mut j = 0;
    for i in 0..v.len() {
        while j < v.len() && v[j] <= v[i] + span {
            j += 1;
        }
        if best.is_none_or(|(c, _)| j - i >= c) {
            best = Some((j - i, i));
        }
    }
    let (count, i) = best?;
    Some((v[i], v[i + count - 1]))
}

/// Data ranges, including the margin bars and the asymptotes inside the ω range.
pub(super) fn data_ranges(series: &[BodeSeries]) -> Result<Ranges> {
    let finite_w = |s: &BodeSeries| {
        s.response
            .w
            .iter()
            .copied()
            .filter(|w| *w > 0.0)
            .collect::<Vec<_>>()
    };
    let mut w = bounds(series.iter().flat_map(finite_w)).unwrap_or((0.1, 10.0));
    // The response of a discrete plant ends at π/T: a little room beyond it, so that its
    // marker stands inside the frame.
    if let Some(wn) = nyquist_frequencies(series).last() {
        w.1 = w.1.max(wn * NYQUIST_ROOM);
    }
    let in_range = |x: f64| x >= w.0 && x <= w.1;
    let mut mags: Vec<f64> = Vec::new();
    let mut phases: Vec<f64> = Vec::new();
    for s in series {
        let r = s.response;
        for i in 0..r.w.len() {
            if r.w[i] > 0.0 {
                mags.push(r.magnitude_db[i]);
                phases.push(r.phase_deg[i]);
            }
        }
        if let Some(m) = s.margins {
            if let (Some(w), Some(gm)) = (m.phase_crossover, m.gain_margin_db) {
                if in_range(w) && gm.is_finite() {
                    mags.extend([0.0, -gm]);
                }
            }
            if let (Some(w), Some(pm)) = (m.gain_crossover, m.phase_margin_deg) {
                if let Some(p) = interp_log(&r.w, &r.phase_deg, w).filter(|_| in_range(w)) {
                    phases.extend([p, p - pm]);
                    mags.push(0.0);
                }
            }
        }
        if let Some(a) = s.asymptotes {
            mags.extend(a.magnitude_db.iter().filter(|p| in_range(p.0)).map(|p| p.1));
            phases.extend(a.phase_deg.iter().filter(|p| in_range(p.0)).map(|p| p.1));
        }
    }
    let (mut mlo, mut mhi) = bounds(mags.iter().copied()).unwrap_or((-1.0, 1.0));
    // A notch at a zero on the axis, or the 400 dB peak of a pair 1e-20 from it, would squash
    // everything else: show at most 300 dB, the window that holds the most samples (the
    // highest such window: peaks matter more than notches).
    if mhi - mlo > MAX_DB_SPAN {
        (mlo, mhi) = densest_window(&mags, MAX_DB_SPAN).unwrap_or((mhi - MAX_DB_SPAN, mhi));
    }
    // A little room so that the curve does not run along the frame.
    let pad = 0.04 * (mhi - mlo).max(1.0);
    mlo -= pad;
    mhi += pad;
    let phase = bounds(phases.iter().copied()).unwrap_or((-1.0, 1.0));
    check_span("magnitudes (dB)", (mlo, mhi))?;
    check_span("phases (degrees)", phase)?;
    Ok(Ranges {
        w,
        mag: (mlo, mhi),
        phase,
    })
}

/// The magnitude panel over the phase panel, sharing the ω axis.
pub(super) struct Panels {
    pub mag: Frame,
    pub ph: Frame,
}

/// Layout: title, magnitude panel, small gap, phase panel, x labels.
pub(super) fn layout_panels(c: &Canvas, th: &Theme, has_title: bool, r: &Ranges) -> Panels {
    let (cw, ch) = (f64::from(c.w), f64::from(c.h));
    let gap = 14.0 * th.s;
    let db_mults = [1.0, 2.0, 5.0, 10.0];
    let make = |w: f64, h_panel: f64| {
        let (nx, ny) = tick_targets(w, h_panel, th);
        let x = Axis::log(r.w.0, r.w.1, nx);
        let mag = Axis::linear_from(r.mag.0, r.mag.1, ny.max(3), false, &db_mults);
        let ph = Axis::degrees(r.phase.0, r.phase.1, ny.max(3));
        (x, mag, ph)
    };
    let top = top_margin(th, has_title, false);
    let mut axes = make(cw * 0.8, ch * 0.35);
    let mut frame = (0.0, 0.0, 0.0, 0.0);
    for _ in 0..2 {
        let l = left_margin(th, &axes.1, true).max(left_margin(th, &axes.2, true));
        let r = right_margin(th, &axes.0);
        let b = bottom_margin(th, &axes.0, true);
        let w = (cw - l - r).max(10.0);
        let h = ((ch - top - b - gap) / 2.0).max(10.0);
        frame = (l, w, h, b);
        axes = make(w, h);
    }
    let (l, w, h, _) = frame;
    let (x_axis, mag_axis, ph_axis) = axes;
    Panels {
        mag: Frame {
            x0: l,
            y0: top,
            x1: l + w,
            y1: top + h,
            x: x_axis.clone(),
            y: mag_axis,
        },
        ph: Frame {
            x0: l,
            y0: top + h + gap,
            x1: l + w,
            y1: top + 2.0 * h + gap,
            x: x_axis,
            y: ph_axis,
        },
    }
}
