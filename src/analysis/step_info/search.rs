//! The searches behind the step metrics: the horizon of the transient's envelope, a lazy scan
//! of y's monotone pieces from any time on, and level crossings on monotone pieces.
//!
//! Nothing here marches over the whole response: every scan starts where its quantity can be
//! (t = 0 for first reaches and extremes, just before an envelope horizon for last exits)
//! and stops as soon as the envelope proves that nothing later matters. A lightly damped
//! response (ζ = 1e-12: 10¹¹ periods before it settles) costs a few periods of grid per
//! quantity, not all of them.

use super::grid::{GridDerivative, mode_scales};
use crate::analysis::closed_form::ClosedFormTerm;
use crate::error::{LtiError, Result};
use crate::numeric::scalar::{Bracket, brent};

/// Grid steps allowed for all the scans of one step-metric computation (a guard against
/// responses whose envelope bound is loose over very many periods).
pub(super) const MAX_GRID: usize = 4_000_000;
/// Points per 1/|p| of the fastest live mode: spacing 0.2/|p| (≈ 31 points per period).
const GRID_FACTOR: f64 = 0.2;
/// Brent's absolute tolerance: negligible, so every root comes to ~4 ulps of itself
/// however wide its bracket (a 10 % reach at 2e-10 s inside a piece of 1e8 s).
const XTOL: f64 = 1e-300;
/// A mode is dead once its envelope is below this fraction of |y∞| (and decreasing).
const DEAD_REL: f64 = 1e-15;

/// A time T after which env(t) < eps for all t ≥ T (env is a sum of decaying envelopes),
/// found to a few ulps of T; `None` when no finite time has env < eps (eps ≤ 0, or
/// a horizon beyond the largest double).
pub(super) fn horizon(
    terms: &[ClosedFormTerm],
    env: &impl Fn(f64) -> f64,
    eps: f64,
) -> Option<f64> {
    let t0 = envelope_peak(terms);
    if env(t0) < eps {
        return Some(t0);
    }
    if eps.is_nan() || eps <= 0.0 {
        return None;
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
        if iterations > 2100 || !hi.is_finite() {
            return None;
        }
    }
    Some(shrink(env, eps, lo, hi))
}

/// The bracket [lo, hi] of env = eps (env(lo) ≥ eps > env(hi), env decreasing) narrowed until
/// lo and hi are adjacent doubles; returns hi.
///
/// ln env is close to linear in t past the envelope's peak (a sum of decaying exponentials is
/// dominated by its slowest term), so regula falsi on ln env − ln eps (Illinois variant: the
/// end that stays is halved in weight) lands within a few ulps in a handful of evaluations
/// where bisection takes ~60; when two steps have not halved the bracket the next one
/// bisects, so the worst case stays within three times bisection's count. The answer is
/// bisection's: the first double at which env < eps (env decreasing).
fn shrink(env: &impl Fn(f64) -> f64, eps: f64, mut lo: f64, mut hi: f64) -> f64 {
    let log_eps = eps.ln();
    let mut f_lo = env(lo).ln() - log_eps;
    let mut f_hi = env(hi).ln() - log_eps;
    let mut kept_lo = false; // the last step kept lo (moved hi)
    let mut kept_hi = false;
    // the bracket's width one and two steps ago: bisect when two steps did not halve it
    let (mut one_ago, mut two_ago) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..4400 {
        let width = hi - lo;
        let interpolate =
            width <= 0.5 * two_ago && f_lo.is_finite() && f_hi.is_finite() && f_lo > f_hi;
        (two_ago, one_ago) = (one_ago, width);
        let mut mid = if interpolate {
            lo + width * (f_lo / (f_lo - f_hi))
        } else {
            0.5 * (lo + hi)
        };
        if !(mid > lo && mid < hi) {
            // the interpolation fell on an end (the crossing is within an ulp of it): the
            // neighbour on the inside, or the midpoint
            mid = if f_lo.abs() < f_hi.abs() {
                f64::from_bits(lo.to_bits() + 1)
            } else {
                f64::from_bits(hi.to_bits() - 1)
            };
            if !(mid > lo && mid < hi) {
                mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
            }
        }
        let e = env(mid);
        let f_mid = e.ln() - log_eps;
        if e < eps {
            hi = mid;
            f_hi = f_mid;
            if kept_lo {
                f_lo *= 0.5;
            }
            (kept_lo, kept_hi) = (true, false);
        } else {
            lo = mid;
            f_lo = f_mid;
            if kept_hi {
                f_hi *= 0.5;
            }
            (kept_lo, kept_hi) = (false, true);
        }
    }
    hi
}

/// The time after which every term's envelope Σ|cₖ|tᵏe^(σt) decreases: max k/|σ|.
pub(super) fn envelope_peak(terms: &[ClosedFormTerm]) -> f64 {
    terms.iter().map(|t| mode_scales(t).1).fold(0.0, f64::max)
}

/// Grid steps left for the scans of one computation.
pub(super) struct Budget {
    left: usize,
}

impl Budget {
    pub(super) fn new() -> Budget {
        Budget { left: MAX_GRID }
    }

    fn take(&mut self, at: f64, rate: f64) -> Result<()> {
        if self.left == 0 {
            return Err(LtiError::NoConvergence {
                what: format!(
                    "the scan of the step response (a mode of rate {} rad/s still alive at \
                     t = {} s after {MAX_GRID} grid steps)",
                    crate::fmt::fmt_sig(rate, 3),
                    crate::fmt::fmt_sig(at, 4)
                ),
                iterations: MAX_GRID,
            });
        }
        self.left -= 1;
        Ok(())
    }
}

/// A forward scan of y′ from a start time: each [`Scanner::next_bound`] returns the next
/// critical point of y (a zero of y′, refined by Brent) or the given limit, so y is
/// monotone between consecutive bounds.
///
/// The grid spacing at t is [`GRID_FACTOR`]/|p| for the fastest mode still alive at t
/// (before its envelope peaks, or with the envelope above [`DEAD_REL`]·`scale`); a dead
/// mode stays dead (its envelope decreases), so the fastest alive mode is tracked with one
/// pointer. Grid values of y′ come from [`GridDerivative`] (exact in sign); Brent refines on
/// the exact `df`.
pub(super) struct Scanner<'a, F: Fn(f64) -> f64> {
    df: &'a F,
    grid: GridDerivative,
    by_rate: Vec<usize>,
    fastest: usize,
    dead: f64,
    t: f64,
    ft: f64,
    /// y is known monotone: the next bound is always the limit.
    monotone: bool,
}

impl<'a, F: Fn(f64) -> f64> Scanner<'a, F> {
    /// A scan from `a` of the derivative `df` of a response with transient `terms` and
    /// final value of size `scale`.
    pub(super) fn new(terms: &[ClosedFormTerm], df: &'a F, a: f64, scale: f64) -> Self {
        let grid = GridDerivative::new(terms, a);
        let by_rate = grid.by_rate();
        Scanner {
            df,
            grid,
            by_rate,
            fastest: 0,
            dead: DEAD_REL * scale,
            t: a,
            ft: df(a),
            monotone: false,
        }
    }

    /// The same scan for a y known to be monotone on t > 0 when `yes`
    /// ([`super::monotone`]): [`Scanner::next_bound`] returns its limit at once.
    pub(super) fn monotone(mut self, yes: bool) -> Self {
        self.monotone = yes;
        self
    }

    /// The current time of the scan.
    pub(super) fn time(&self) -> f64 {
        self.t
    }

    /// The grid spacing the scan would use now (`None` when no mode is alive: y is constant
    /// to within [`DEAD_REL`] of the final value from here on).
    pub(super) fn spacing(&mut self) -> Option<f64> {
        while self.fastest < self.by_rate.len()
            && !self.grid.alive(self.by_rate[self.fastest], self.dead)
        {
            self.fastest += 1;
        }
        let rate = self
            .by_rate
            .get(self.fastest)
            .map_or(0.0, |&k| self.grid.rate(k));
        (rate > 0.0).then(|| GRID_FACTOR / rate)
    }

    /// The next bound after the current time: the first critical point in (t, `limit`), or
    /// `limit` itself. Requires `limit` > the current time.
    pub(super) fn next_bound(&mut self, limit: f64, budget: &mut Budget) -> Result<f64> {
        let df = self.df;
        if self.monotone && self.t < limit {
            self.t = limit;
            self.ft = df(limit);
            return Ok(limit);
        }
        while self.t < limit {
            let spacing = self.spacing();
            budget.take(self.t, spacing.map_or(0.0, |h| GRID_FACTOR / h))?;
            // at least a few ulps of t, so the scan advances where the spacing is below
            // the resolution of t
            let min_step = 4.0 * f64::EPSILON * self.t.abs();
            let h = spacing.unwrap_or(limit - self.t).max(min_step);
            let clipped = self.t + h >= limit;
            let u = if clipped { limit } else { self.t + h };
            let fu = self.grid.advance(u, h, clipped, df);
            let (t, ft) = (self.t, self.ft);
            self.t = u;
            self.ft = fu;
            if ft != 0.0 && fu != 0.0 && ft.signum() != fu.signum() {
                let br = Bracket {
                    a: t,
                    b: u,
                    fa: ft,
                    fb: fu,
                };
                // c lies in [t, u]: a zero-length piece at an end is harmless
                return brent(df, br, XTOL);
            } else if fu == 0.0 && u < limit {
                return Ok(u);
            }
        }
        Ok(limit)
    }
}

/// The crossing of g = 0 in [a, b] when g changes sign there (g monotone on [a, b]).
pub(crate) fn crossing(g: &impl Fn(f64) -> f64, a: f64, b: f64) -> Result<Option<f64>> {
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
    brent(g, Bracket { a, b, fa, fb }, XTOL).map(Some)
}

/// The first t with g(t) ≥ 0 on the monotone piece [a, b] (g(a) < 0 assumed), if any.
pub(crate) fn reach_in(g: &impl Fn(f64) -> f64, a: f64, b: f64) -> Result<Option<f64>> {
    let (fa, fb) = (g(a), g(b));
    if fa >= 0.0 {
        return Ok(Some(a));
    }
    if fb < 0.0 {
        return Ok(None);
    }
    if fb == 0.0 {
        return Ok(Some(b));
    }
    brent(g, Bracket { a, b, fa, fb }, XTOL).map(Some)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    /// Bisection to adjacent doubles (what `shrink` replaced), for reference.
    fn bisect(env: &impl Fn(f64) -> f64, eps: f64, mut lo: f64, mut hi: f64) -> f64 {
        loop {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                return hi;
            }
            if env(mid) < eps {
                hi = mid;
            } else {
                lo = mid;
            }
        }
    }

    #[test]
    fn shrink_gives_bisections_answer_in_fewer_evaluations() {
        let calls = Cell::new(0usize);
        // sums of decaying envelopes |c|·t^k·e^(σt) as the step metrics see them
        let cases: [&[(f64, i32, f64)]; 4] = [
            &[(1.0, 0, -1.0)],
            &[(2.0, 0, -0.1), (5.0, 0, -10.0), (0.3, 1, -2.0)],
            &[(1e-3, 3, -1e-6), (1.0, 0, -1e3)],
            &[(4.0, 0, -0.25), (4.0, 0, -0.2500001)],
        ];
        let mut total = 0;
        for terms in cases {
            let env = |t: f64| {
                calls.set(calls.get() + 1);
                terms
                    .iter()
                    .map(|&(c, k, s)| c * t.powi(k) * (s * t).exp())
                    .sum::<f64>()
            };
            for eps in [1e-1, 2e-2, 1e-9, 1e-15] {
                // a bracket as horizon builds it: env(lo) ≥ eps > env(hi)
                let (mut lo, mut hi) = (10.0, 20.0);
                while env(lo) < eps {
                    lo *= 0.5;
                }
                while env(hi) >= eps {
                    hi *= 2.0;
                }
                let reference = bisect(&env, eps, lo, hi);
                calls.set(0);
                let got = shrink(&env, eps, lo, hi);
                assert_eq!(
                    got.to_bits(),
                    reference.to_bits(),
                    "eps {eps}, terms {terms:?}"
                );
                assert!(env(got) < eps && env(f64::from_bits(got.to_bits() - 1)) >= eps);
                total += calls.get();
            }
        }
        // 16 brackets: bisection takes ~55–64 evaluations each, this ~8
        assert!(total <= 16 * 12, "{total} evaluations");
    }
}
