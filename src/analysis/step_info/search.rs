//! The searches behind the step metrics: the settling horizon of the transient's envelope,
//! the critical points of y on an adaptive grid, and level crossings on monotone pieces.

use super::grid;
use crate::analysis::closed_form::ClosedFormTerm;
use crate::error::{LtiError, Result};
use crate::numeric::scalar::{Bracket, brent};

/// Grid points allowed for bracketing (a guard against absurd mode spreads).
const MAX_GRID: usize = 4_000_000;
/// Points per 1/|p| of the fastest live mode: spacing 0.2/|p| (≈ 31 points per period).
const GRID_FACTOR: f64 = 0.2;
/// A mode is dead once its envelope is below this fraction of |y∞| (and decreasing).
const DEAD_REL: f64 = 1e-15;

/// The rate |p| and the time after which the envelope of a term decreases.
pub(super) fn mode_scales(t: &ClosedFormTerm) -> (f64, f64) {
    let p = t.pole().unwrap_or_default();
    let k = t.max_power() as f64;
    (p.norm(), if p.re < 0.0 { k / -p.re } else { 0.0 })
}

/// A time T after which env(t) < eps for all t ≥ T (env is a sum of decaying envelopes).
pub(super) fn horizon(
    terms: &[ClosedFormTerm],
    env: &impl Fn(f64) -> f64,
    eps: f64,
) -> Result<f64> {
    let t0 = terms.iter().map(|t| mode_scales(t).1).fold(0.0, f64::max);
    if env(t0) < eps {
        return Ok(t0);
    }
    let slowest = terms
        .iter()
        .filter_map(|t| t.pole())
        .map(|p| -p.re)
        .fold(f64::INFINITY, f64::min);
    let mut step = 1.0 / slowest;
    let mut lo = t0;
    let mut hi = t0 + step;
    let mut iterations = 0;
    while env(hi) >= eps {
        lo = hi;
        step *= 2.0;
        hi += step;
        iterations += 1;
        if iterations > 2000 || !hi.is_finite() {
            return Err(LtiError::NoConvergence {
                what: "step-response settling horizon".into(),
                iterations,
            });
        }
    }
    // env is decreasing on [t0, ∞): bisect to 1e-6 relative (keeping env(hi) < eps).
    while hi - lo > 1e-6 * hi {
        let mid = 0.5 * (lo + hi);
        if env(mid) < eps {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(hi)
}

/// Zeros of y′ on (a, b]: sign changes on an adaptive grid, refined by Brent.
///
/// The spacing at t is [`GRID_FACTOR`]/|p| for the fastest mode still alive at t (before its
/// envelope peaks, or with the envelope above [`DEAD_REL`]·`scale`); a dead mode stays dead
/// (its envelope decreases), so the fastest alive mode is tracked with one pointer. Grid values
/// of y′ come from [`grid::GridDerivative`] (exact in sign); Brent refines on the exact `df`.
pub(super) fn critical_points(
    terms: &[ClosedFormTerm],
    df: &impl Fn(f64) -> f64,
    a: f64,
    b: f64,
    scale: f64,
) -> Result<Vec<f64>> {
    let dead = DEAD_REL * scale;
    let mut grid = grid::GridDerivative::new(terms, a);
    let by_rate = grid.by_rate();
    let mut fastest = 0; // index into by_rate of the fastest mode that may be alive
    let mut out = Vec::new();
    let mut t = a;
    let mut ft = df(t);
    let mut count = 0usize;
    let xtol = 1e-15 * b.max(1e-300);
    let min_step = 4.0 * f64::EPSILON * b;
    while t < b {
        while fastest < by_rate.len() && !grid.alive(by_rate[fastest], dead) {
            fastest += 1;
        }
        let rate = by_rate.get(fastest).map_or(0.0, |&k| grid.rate(k));
        let h = if rate > 0.0 {
            (GRID_FACTOR / rate).min(b - a)
        } else {
            b - a
        }
        .max(min_step);
        let clipped = t + h > b;
        let u = if clipped { b } else { t + h };
        let fu = grid.advance(u, h, clipped, df);
        if ft != 0.0 && fu != 0.0 && ft.signum() != fu.signum() {
            let br = Bracket {
                a: t,
                b: u,
                fa: ft,
                fb: fu,
            };
            out.push(brent(df, br, xtol)?);
        } else if fu == 0.0 && u < b {
            out.push(u);
        }
        t = u;
        ft = fu;
        count += 1;
        if count > MAX_GRID {
            return Err(LtiError::NoConvergence {
                what: "step-metric bracketing grid (modes too far apart)".into(),
                iterations: count,
            });
        }
    }
    Ok(out)
}

/// The crossing of g = 0 in [a, b] when g changes sign there (g monotone on [a, b]).
pub(super) fn crossing(g: &impl Fn(f64) -> f64, a: f64, b: f64, xtol: f64) -> Result<Option<f64>> {
    let (fa, fb) = (g(a), g(b));
    if fa == 0.0 {
        return Ok(Some(a));
    }
    if fb == 0.0 {
        return Ok(Some(b));
    }
    if fa.signum() == fb.signum() {
        return Ok(None);
    }
    brent(g, Bracket { a, b, fa, fb }, xtol).map(Some)
}

/// The first t with g(t) ≥ 0, g monotone between consecutive bounds.
pub(super) fn first_reach(
    g: &impl Fn(f64) -> f64,
    bounds: &[f64],
    xtol: f64,
) -> Result<Option<f64>> {
    if g(bounds[0]) >= 0.0 {
        return Ok(Some(bounds[0]));
    }
    for w in bounds.windows(2) {
        let (fa, fb) = (g(w[0]), g(w[1]));
        if fa < 0.0 && fb >= 0.0 {
            if fb == 0.0 {
                return Ok(Some(w[1]));
            }
            return brent(
                g,
                Bracket {
                    a: w[0],
                    b: w[1],
                    fa,
                    fb,
                },
                xtol,
            )
            .map(Some);
        }
    }
    Ok(None)
}
