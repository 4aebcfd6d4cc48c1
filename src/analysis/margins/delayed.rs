//! Phase crossings of a loop with a dead time: ψ(ω) = φ(ω) − ωT crosses −180° (mod 360°)
//! infinitely often, since −ωT decreases without bound. They are listed in order up to a
//! frequency that covers the plotted range and the first turns of the delay; the result says
//! how far ([`Margins::crossings_listed_to`](super::Margins::crossings_listed_to)).
//!
//! The search grid is the factored form's sampling grid (dense at lightly damped pairs)
//! merged with a linear grid on which ωT advances by π/8, so each interval holds at most one
//! crossing of the delay's own turning; each sign change of ψ − level is polished by Brent's
//! method on the exact phase.

use std::f64::consts::{PI, TAU};

use super::crossing::PhaseCrossing;
use crate::analysis::factored::BodeForm;
use crate::numeric::scalar::{Bracket, brent};

/// Most phase crossings listed for a delayed loop.
pub(crate) const MAX_LISTED: usize = 50;
/// Most points of the search grid (the listing stops earlier for very long delays).
const MAX_GRID: usize = 40_000;

/// The phase crossings ω > 0 of G(jω)e^(−jωT), in order, and the frequency up to which they
/// are complete: the larger of the plotted range's end `w_plot` and three turns of the delay
/// (6π/T), shortened when the grid or [`MAX_LISTED`] runs out.
pub(crate) fn phase_crossings(
    form: &BodeForm,
    delay: f64,
    w_plot: f64,
    singular: &[f64],
) -> (Vec<PhaseCrossing>, f64) {
    let step = PI / (8.0 * delay);
    let mut w_end = w_plot.max(6.0 * PI / delay);
    if w_end / step > MAX_GRID as f64 {
        w_end = step * MAX_GRID as f64;
    }
    let mut grid: Vec<f64> = form
        .sampling_grid(200)
        .into_iter()
        .filter(|&x| x > 0.0 && x < w_end)
        .collect();
    let n = (w_end / step).ceil() as usize;
    grid.extend((1..=n).map(|k| (k as f64 * step).min(w_end)));
    grid.sort_by(f64::total_cmp);
    grid.dedup();
    let psi = |x: f64| form.eval(x).phase_rad() - x * delay;
    let mut out: Vec<PhaseCrossing> = Vec::new();
    let mut prev: Option<(f64, f64)> = None;
    for &x in &grid {
        if singular.iter().any(|&b| (x - b).abs() <= 1e-8 * b) {
            prev = None;
            continue;
        }
        let e = form.eval(x);
        if !(e.mant > 0.0 && e.mant.is_finite()) {
            prev = None;
            continue;
        }
        let p = e.phase_rad() - x * delay;
        if let Some((xa, pa)) = prev {
            // levels −π − 2πk between pa and p
            let (lo, hi) = (pa.min(p), pa.max(p));
            let mut level = PI * (2.0 * ((lo - PI) / TAU).ceil() + 1.0);
            while level <= hi {
                let f = |t: f64| psi(t) - level;
                let (fa, fb) = (pa - level, p - level);
                let root = if fa == 0.0 {
                    Some(xa)
                } else if fb == 0.0 {
                    Some(x)
                } else if fa.signum() != fb.signum() {
                    brent(
                        f,
                        Bracket {
                            a: xa,
                            b: x,
                            fa,
                            fb,
                        },
                        0.0,
                    )
                    .ok()
                } else {
                    None
                };
                if let Some(w) = root
                    && out.last().is_none_or(|c| w > c.w * (1.0 + 1e-12))
                {
                    let e = form.eval(w);
                    out.push(PhaseCrossing {
                        w,
                        gain_margin: (-e.ln_mag()).exp(),
                        gain_margin_db: -e.db(),
                    });
                    if out.len() == MAX_LISTED {
                        return (out, w);
                    }
                }
                level += TAU;
            }
        }
        prev = Some((x, p));
    }
    (out, w_end)
}
