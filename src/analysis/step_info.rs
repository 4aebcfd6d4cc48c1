//! Step-response metrics with MATLAB `stepinfo` definitions, computed exactly on the closed
//! form by root-finding.
//!
//! # Definitions (DESIGN §1.3; y∞ the dc gain, s = sign y∞)
//! - rise time: from the first time s·y reaches 10 % of |y∞| to the first time it reaches 90 %;
//! - settling time: the last time |y − y∞| = 2 %·|y∞| (0 if y never leaves the band);
//! - overshoot: (max s·y − |y∞|)/|y∞|·100, at least 0;
//! - peak: max |y| over t ≥ 0, peak time its first instant.
//!
//! # Method
//! y(t) = y∞ + Σ terms is the closed form of the step response
//! ([`TransferFunction::inverse_laplace`]). The envelope E(t) = Σ|cₖ|tᵏe^(σt) of the transient
//! bounds |y − y∞| and decreases after max(k/|σ|); bisection on it gives a horizon T after
//! which |y − y∞| < 2 %·|y∞|, so nothing about rise and settling happens later. On [0, T] a
//! grid whose local spacing is 0.2/|p| for the fastest mode still alive (envelope above
//! 1e-15·|y∞|) brackets every sign change of y′(t) (closed-form derivative); Brent's method
//! refines each to a critical point. Between consecutive critical points y is monotone, so each
//! level (10 %, 90 %, y∞ ± 2 %) is crossed at most once there, and Brent finds the crossing to
//! ~1e-14 relative. Peaks are the critical points; if the largest of them does not exceed
//! |y∞|, the search is extended until the envelope cannot lift |y| above the best value found.
//! The result is exact to the evaluation accuracy of the closed form, not to a grid.
//!
//! A monotone response never attains its supremum |y∞|: then `peak` = |y∞| and `peak_time` =
//! +∞ (serialised as `null` in JSON).

use num_complex::Complex64;
use serde::Serialize;

use crate::analysis::closed_form::{ClosedForm, ClosedFormTerm};
use crate::analysis::input::Input;
use crate::analysis::laplace::decompose_with;
use crate::analysis::pz::{PoleZero, dc_gain_of};
use crate::analysis::stability::{HalfPlane, half_plane};
use crate::error::{LtiError, Result};
use crate::lti::TransferFunction;
use crate::numeric::scalar::{Bracket, brent};
use crate::poly::Poly;

mod grid;

/// Step metrics (DESIGN §1.3). Times in seconds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StepInfo {
    /// Time from 10 % to 90 % of the final value.
    pub rise_time: f64,
    /// Last time |y − y∞| equals 2 % of |y∞| (0 when the response never leaves the band).
    pub settling_time: f64,
    /// (max y − y∞)/|y∞|·100, at least 0 (with y and y∞ taken in the sign of y∞).
    pub overshoot_percent: f64,
    /// max |y| (its supremum |y∞| for a response that approaches y∞ from below).
    pub peak: f64,
    /// First time the peak is reached; +∞ when it is only approached as t → ∞ (monotone
    /// responses), which serialises as `null`.
    pub peak_time: f64,
    /// y∞ (the dc gain).
    pub steady_state: f64,
    /// When y first reaches 10 % of y∞ (start of the rise).
    pub rise_start: f64,
    /// When y first reaches 90 % of y∞ (end of the rise).
    pub rise_end: f64,
}

/// Grid points allowed for bracketing (a guard against absurd mode spreads).
const MAX_GRID: usize = 4_000_000;
/// Points per 1/|p| of the fastest live mode: spacing 0.2/|p| (≈ 31 points per period).
const GRID_FACTOR: f64 = 0.2;
/// A mode is dead once its envelope is below this fraction of |y∞| (and decreasing).
const DEAD_REL: f64 = 1e-15;
/// Overshoot smaller than this fraction of |y∞| is not searched for beyond the settling horizon.
const PEAK_REL: f64 = 1e-12;

impl TransferFunction {
    /// Step metrics of G (MATLAB `stepinfo` definitions, see the [module docs](self)), exact
    /// to ~1e-12 relative; `None` when the step response does not settle: G (in lowest terms)
    /// not BIBO stable, or a zero or infinite dc gain.
    ///
    /// Errors: an improper G.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // ζ = 0.5, ωₙ = 1: overshoot e^(−πζ/√(1−ζ²)) = 16.3 %, peak at π/ω_d.
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0, 1.0]).unwrap();
    /// let s = g.step_info().unwrap().unwrap();
    /// let wd = 0.75f64.sqrt();
    /// assert!((s.overshoot_percent - 100.0 * (-0.5 * std::f64::consts::PI / wd).exp()).abs() < 1e-10);
    /// assert!((s.peak_time - std::f64::consts::PI / wd).abs() < 1e-10);
    /// // An integrator never settles.
    /// let i = TransferFunction::from_descending(&[1.0], &[1.0, 0.0]).unwrap();
    /// assert!(i.step_info().unwrap().is_none());
    /// ```
    pub fn step_info(&self) -> Result<Option<StepInfo>> {
        self.require_proper("step metrics", false)?;
        step_info_with(self, &self.pole_zero()?)
    }
}

/// [`TransferFunction::step_info`] of a proper `g` whose pole/zero analysis `pz` is at hand
/// (`analyze` has it: the roots are not found again).
pub(crate) fn step_info_with(g: &TransferFunction, pz: &PoleZero) -> Result<Option<StepInfo>> {
    if pz
        .reduced_poles
        .iter()
        .any(|p| half_plane(p.value) != HalfPlane::Left)
    {
        return Ok(None);
    }
    let y_inf = match dc_gain_of(&pz.reduced) {
        Some(k) if k != 0.0 && k.is_finite() => k,
        _ => return Ok(None),
    };
    // zero initial conditions: no initial-condition polynomial
    let y = decompose_with(g, pz, &Input::Step, Poly::zero())?
        .response()?
        .closed_form;
    step_info_of(&y, y_inf).map(Some)
}

/// Step metrics of a closed-form step response `y` with final value `y_inf` ≠ 0, whose terms
/// other than the constant all decay (Re p < 0) — e.g. a step response with initial
/// conditions, which [`TransferFunction::step_info`] does not cover.
///
/// Errors: `y_inf` zero or not finite, a term that does not decay.
///
/// ```
/// use ltikit::TransferFunction;
/// use ltikit::analysis::{Input, step_info::step_info_of};
/// // Tank 1/(2s + 0.5) filled by a unit step from h(0) = 1: h = 2 − e^(−t/4).
/// let g = TransferFunction::from_descending(&[1.0], &[2.0, 0.5]).unwrap();
/// let h = g.inverse_laplace(&Input::Step, &[1.0]).unwrap().closed_form;
/// let s = step_info_of(&h, 2.0).unwrap();
/// assert_eq!(s.rise_start, 0.0); // already at 50 %
/// assert!((s.settling_time - 4.0 * 25f64.ln()).abs() < 1e-12); // e^(−t/4) = 0.04
/// ```
pub fn step_info_of(y: &ClosedForm, y_inf: f64) -> Result<StepInfo> {
    if y_inf == 0.0 || !y_inf.is_finite() {
        return Err(LtiError::Undefined {
            what: "step metrics".into(),
            reason: format!("the final value is {y_inf}"),
        });
    }
    let transient: Vec<ClosedFormTerm> = y
        .terms()
        .iter()
        .filter(|t| !matches!(t.pole(), Some(p) if p == Complex64::new(0.0, 0.0)))
        .filter(|t| !matches!(t, ClosedFormTerm::Impulse { .. }))
        .cloned()
        .collect();
    if let Some(p) = transient
        .iter()
        .filter_map(|t| t.pole())
        .find(|p| p.re >= 0.0)
    {
        return Err(LtiError::Undefined {
            what: "step metrics".into(),
            reason: format!("the step response has a mode at s = {p} that does not decay"),
        });
    }
    let scale = y_inf.abs();
    let sgn = y_inf.signum();
    let env = |t: f64| transient.iter().map(|x| x.envelope(t)).sum::<f64>();
    let f = |t: f64| y.eval(t);
    let df = |t: f64| y.eval_derivative(t);

    // Phase 1: [0, T_settle].
    let t_settle = horizon(&transient, &env, 0.02 * scale)?;
    let mut bounds = vec![0.0];
    bounds.extend(critical_points(&transient, &df, 0.0, t_settle, scale)?);
    bounds.push(t_settle);
    let xtol = 1e-15 * t_settle.max(1e-300);

    // Rise: first reach of 10 % and 90 %.
    let reach = |level: f64| -> Result<f64> {
        let g = |t: f64| sgn * f(t) - level * scale;
        first_reach(&g, &bounds, xtol)?.ok_or_else(|| LtiError::NoConvergence {
            what: format!(
                "search for the {}% level of the step response",
                level * 100.0
            ),
            iterations: bounds.len(),
        })
    };
    let rise_start = reach(0.1)?;
    let rise_end = reach(0.9)?;

    // Settling: last crossing of y∞ ± 2 %.
    let band = 0.02 * scale;
    let mut settling_time = 0.0;
    'outer: for w in bounds.windows(2).rev() {
        let mut best: Option<f64> = None;
        for level in [y_inf + band, y_inf - band] {
            let g = |t: f64| f(t) - level;
            if let Some(x) = crossing(&g, w[0], w[1], xtol)? {
                best = Some(best.map_or(x, |b: f64| b.max(x)));
            }
        }
        if let Some(x) = best {
            settling_time = x;
            break 'outer;
        }
    }

    // Peaks: t = 0 and the critical points, extended until nothing later can be higher.
    let mut candidates: Vec<f64> = bounds[..bounds.len() - 1].to_vec();
    let best_abs = candidates.iter().map(|&t| f(t).abs()).fold(0.0, f64::max);
    let margin = (best_abs - scale).max(PEAK_REL * scale);
    let t_peak = horizon(&transient, &env, margin)?;
    if t_peak > t_settle {
        candidates.extend(critical_points(&transient, &df, t_settle, t_peak, scale)?);
    }
    let mut peak = scale;
    let mut peak_time = f64::INFINITY;
    let mut max_signed = f64::NEG_INFINITY;
    for &t in &candidates {
        let v = f(t);
        if v.abs() > peak || (peak_time.is_infinite() && v.abs() >= peak) {
            peak = v.abs();
            peak_time = t;
        }
        max_signed = max_signed.max(sgn * v);
    }
    let overshoot_percent = ((max_signed - scale) / scale * 100.0).max(0.0);

    Ok(StepInfo {
        rise_time: rise_end - rise_start,
        settling_time,
        overshoot_percent,
        peak,
        peak_time,
        steady_state: y_inf,
        rise_start,
        rise_end,
    })
}

/// The rate |p| and the time after which the envelope of a term decreases.
fn mode_scales(t: &ClosedFormTerm) -> (f64, f64) {
    let p = t.pole().unwrap_or_default();
    let k = t.max_power() as f64;
    (p.norm(), if p.re < 0.0 { k / -p.re } else { 0.0 })
}

/// A time T after which env(t) < eps for all t ≥ T (env is a sum of decaying envelopes).
fn horizon(terms: &[ClosedFormTerm], env: &impl Fn(f64) -> f64, eps: f64) -> Result<f64> {
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
fn critical_points(
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
fn crossing(g: &impl Fn(f64) -> f64, a: f64, b: f64, xtol: f64) -> Result<Option<f64>> {
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
fn first_reach(g: &impl Fn(f64) -> f64, bounds: &[f64], xtol: f64) -> Result<Option<f64>> {
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

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact values are meant: 0 before t = 0, exact dc gains
mod tests {
    use super::*;

    fn info(n: &[f64], d: &[f64]) -> Option<StepInfo> {
        TransferFunction::from_descending(n, d)
            .unwrap()
            .step_info()
            .unwrap()
    }

    #[test]
    fn first_order_is_exact() {
        // 1/(s + 1): y = 1 − e^(−t); 10 % at ln(10/9), 90 % at ln 10, 2 % at ln 50.
        let s = info(&[1.0], &[1.0, 1.0]).unwrap();
        assert!((s.rise_start - (10.0f64 / 9.0).ln()).abs() < 1e-14);
        assert!((s.rise_end - 10f64.ln()).abs() < 1e-14);
        assert!((s.settling_time - 50f64.ln()).abs() < 1e-14);
        assert_eq!(s.overshoot_percent, 0.0);
        assert_eq!(s.peak, 1.0);
        assert!(s.peak_time.is_infinite());
        assert_eq!(
            serde_json::to_value(s).unwrap()["peak_time"],
            serde_json::Value::Null
        );
    }

    #[test]
    fn negative_gain_and_biproper() {
        // −2/(s + 1): same times as 1/(s + 1), y∞ = −2, peak |y| = 2.
        let s = info(&[-2.0], &[1.0, 1.0]).unwrap();
        assert!((s.rise_end - 10f64.ln()).abs() < 1e-14);
        assert_eq!(s.steady_state, -2.0);
        assert_eq!(s.overshoot_percent, 0.0);
        // (s + 2)/(s + 1): y = 2 − e^(−t) starts at 1 ≥ 90 % of 2? no: 1 < 1.8.
        let s = info(&[1.0, 2.0], &[1.0, 1.0]).unwrap();
        assert_eq!(s.rise_start, 0.0);
        assert!((s.rise_end - 5f64.ln()).abs() < 1e-14); // 2 − e^(−t) = 1.8
        // (3s + 1)/(s + 1): starts at 3, decays to 1: peak 3 at t = 0, overshoot 200 %.
        let s = info(&[3.0, 1.0], &[1.0, 1.0]).unwrap();
        assert_eq!(s.peak_time, 0.0);
        assert!((s.peak - 3.0).abs() < 1e-15);
        assert!((s.overshoot_percent - 200.0).abs() < 1e-12);
        assert!((s.settling_time - 100f64.ln()).abs() < 1e-13); // 1 + 2e^(−t) = 1.02
    }

    #[test]
    fn does_not_settle() {
        assert!(info(&[1.0], &[1.0, 0.0, 1.0]).is_none()); // undamped
        assert!(info(&[1.0], &[1.0, -1.0]).is_none()); // unstable
        assert!(info(&[1.0, 0.0], &[1.0, 1.0]).is_none()); // zero dc gain
        assert!(info(&[0.0], &[1.0, 1.0]).is_none()); // G = 0
        // A cancelled unstable pole does not matter (BIBO on the reduced form).
        assert!(info(&[1.0, -1.0], &[1.0, 1.0, -2.0]).is_some());
    }

    #[test]
    fn improper_is_an_error() {
        let g = TransferFunction::from_descending(&[1.0, 0.0, 0.0], &[1.0, 1.0]).unwrap();
        assert!(g.step_info().is_err());
    }
}
