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
use crate::analysis::factored::Factored;
use crate::analysis::input::Input;
use crate::analysis::laplace::Decomposition;
use crate::error::{LtiError, Result};
use crate::lti::TransferFunction;

mod grid;
mod search;

use search::{critical_points, crossing, first_reach, horizon};

/// Thresholds of the step metrics (MATLAB `stepinfo` options, with its defaults).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StepInfoOptions {
    /// The settling band as a fraction of |y∞| (`SettlingTimeThreshold`, default 0.02); the
    /// transient time uses the same fraction of the largest error.
    pub settling_threshold: f64,
    /// The rise from `rise_limits.0`·y∞ to `rise_limits.1`·y∞ (`RiseTimeLimits`, default
    /// (0.1, 0.9)).
    pub rise_limits: (f64, f64),
}

impl Default for StepInfoOptions {
    fn default() -> Self {
        StepInfoOptions {
            settling_threshold: 0.02,
            rise_limits: (0.1, 0.9),
        }
    }
}

impl StepInfoOptions {
    /// Checks 0 < settling threshold < 1 and 0 ≤ low < high ≤ 1.
    ///
    /// ```
    /// use ltikit::analysis::StepInfoOptions;
    /// assert!(StepInfoOptions::default().validate().is_ok());
    /// let bad = StepInfoOptions { rise_limits: (0.9, 0.1), ..Default::default() };
    /// assert!(bad.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<()> {
        let st = self.settling_threshold;
        if !(st > 0.0 && st < 1.0) {
            return Err(LtiError::InvalidParameter {
                name: "settling threshold".into(),
                value: st,
                reason: "must lie strictly between 0 and 1 (0.02 is a 2 % band)".into(),
            });
        }
        let (lo, hi) = self.rise_limits;
        if !(lo >= 0.0 && hi <= 1.0 && lo < hi) {
            return Err(LtiError::InvalidParameter {
                name: "rise-time limits".into(),
                value: if lo >= 0.0 && lo < hi { hi } else { lo },
                reason: format!("need 0 ≤ low < high ≤ 1, got ({lo}, {hi})"),
            });
        }
        Ok(())
    }
}

/// Step metrics (DESIGN §1.3, MATLAB `stepinfo`). Times in seconds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StepInfo {
    /// Time from the low to the high rise limit (10 % to 90 % of the final value).
    pub rise_time: f64,
    /// Last time |y − y∞| equals the settling band (2 % of |y∞|; 0 when the response never
    /// leaves the band).
    pub settling_time: f64,
    /// Last time |y − y∞| equals the settling fraction (2 %) of its largest value over t ≥ 0
    /// (MATLAB's `TransientTime`; the settling time when the error is largest at t = 0).
    pub transient_time: f64,
    /// min y(t) once the response has risen (t ≥ the end of the rise).
    pub settling_min: f64,
    /// max y(t) once the response has risen (its supremum y∞ when only approached).
    pub settling_max: f64,
    /// (max y − y∞)/|y∞|·100, at least 0 (with y and y∞ taken in the sign of y∞).
    pub overshoot_percent: f64,
    /// How far y goes the wrong way: max(0, −min y)/|y∞|·100 (in the sign of y∞).
    pub undershoot_percent: f64,
    /// max |y| (its supremum |y∞| for a response that approaches y∞ from below).
    pub peak: f64,
    /// First time the peak is reached; +∞ when it is only approached as t → ∞ (monotone
    /// responses), which serialises as `null`.
    pub peak_time: f64,
    /// y∞ (the dc gain).
    pub steady_state: f64,
    /// When y first reaches the low rise limit (start of the rise).
    pub rise_start: f64,
    /// When y first reaches the high rise limit (end of the rise).
    pub rise_end: f64,
}

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
        self.factored()?.step_info()
    }
}

impl Factored {
    /// Step metrics with MATLAB's default thresholds ([`TransferFunction::step_info`]).
    pub fn step_info(&self) -> Result<Option<StepInfo>> {
        self.step_info_for(&StepInfoOptions::default())
    }

    /// Step metrics with the given thresholds; `None` when the step response does not
    /// settle.
    ///
    /// Errors: an improper G, invalid options.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::StepInfoOptions;
    /// // 1/(s + 1): y = 1 − e^(−t) is within 0.5 % of 1 from t = ln 200 on.
    /// let f = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap().factored().unwrap();
    /// let o = StepInfoOptions { settling_threshold: 0.005, ..Default::default() };
    /// let s = f.step_info_for(&o).unwrap().unwrap();
    /// assert!((s.settling_time - 200f64.ln()).abs() < 1e-13);
    /// ```
    pub fn step_info_for(&self, opts: &StepInfoOptions) -> Result<Option<StepInfo>> {
        opts.validate()?;
        self.require_proper("step metrics", false)?;
        if self.has_unstable_pole() {
            return Ok(None);
        }
        let y_inf = match self.dc_gain() {
            Some(k) if k != 0.0 && k.is_finite() => k,
            _ => return Ok(None),
        };
        // zero initial conditions
        let y = Decomposition::new(self, &Input::Step, &[])?
            .closed_form()?
            .closed_form;
        step_info_of(&y, y_inf, opts).map(Some)
    }
}

/// Step metrics of a closed-form step response `y` with final value `y_inf` ≠ 0, whose terms
/// other than the constant all decay (Re p < 0) — e.g. a step response with initial
/// conditions, which [`TransferFunction::step_info`] does not cover.
///
/// Errors: `y_inf` zero or not finite, a term that does not decay, invalid options.
///
/// ```
/// use ltikit::TransferFunction;
/// use ltikit::analysis::{Input, StepInfoOptions, step_info::step_info_of};
/// // Tank 1/(2s + 0.5) filled by a unit step from h(0) = 1: h = 2 − e^(−t/4).
/// let g = TransferFunction::from_descending(&[1.0], &[2.0, 0.5]).unwrap();
/// let h = g.inverse_laplace(&Input::Step, &[1.0]).unwrap().closed_form;
/// let s = step_info_of(&h, 2.0, &StepInfoOptions::default()).unwrap();
/// assert_eq!(s.rise_start, 0.0); // already at 50 %
/// assert!((s.settling_time - 4.0 * 25f64.ln()).abs() < 1e-12); // e^(−t/4) = 0.04
/// ```
pub fn step_info_of(y: &ClosedForm, y_inf: f64, opts: &StepInfoOptions) -> Result<StepInfo> {
    opts.validate()?;
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
    Metrics {
        y,
        transient: &transient,
        y_inf,
        opts,
    }
    .compute()
}

/// The closed form being measured.
struct Metrics<'a> {
    y: &'a ClosedForm,
    transient: &'a [ClosedFormTerm],
    y_inf: f64,
    opts: &'a StepInfoOptions,
}

impl Metrics<'_> {
    fn f(&self, t: f64) -> f64 {
        self.y.eval(t)
    }

    fn env(&self, t: f64) -> f64 {
        self.transient.iter().map(|x| x.envelope(t)).sum::<f64>()
    }

    fn horizon(&self, eps: f64) -> Result<f64> {
        horizon(self.transient, &|t| self.env(t), eps)
    }

    fn critical_points(&self, a: f64, b: f64) -> Result<Vec<f64>> {
        critical_points(
            self.transient,
            &|t| self.y.eval_derivative(t),
            a,
            b,
            self.y_inf.abs(),
        )
    }

    fn compute(&self) -> Result<StepInfo> {
        let scale = self.y_inf.abs();
        let sgn = self.y_inf.signum();
        let band = self.opts.settling_threshold * scale;

        // [0, T]: y is monotone between consecutive bounds.
        let t_settle = self.horizon(band)?;
        let mut bounds = vec![0.0];
        bounds.extend(self.critical_points(0.0, t_settle)?);
        bounds.push(t_settle);
        let xtol = 1e-15 * t_settle.max(1e-300);

        // Rise: first reach of the two limits.
        let reach = |level: f64| -> Result<f64> {
            let g = |t: f64| sgn * self.f(t) - level * scale;
            first_reach(&g, &bounds, xtol)?.ok_or_else(|| LtiError::NoConvergence {
                what: format!(
                    "search for the {}% level of the step response",
                    level * 100.0
                ),
                iterations: bounds.len(),
            })
        };
        let (lo, hi) = self.opts.rise_limits;
        let rise_start = reach(lo)?;
        let rise_end = reach(hi)?;
        let settling_time = self.last_exit(&bounds, band, xtol)?;

        // Extremes: t = 0, the critical points, the end of the rise, extended until nothing
        // later can beat them.
        let mut candidates: Vec<f64> = bounds[..bounds.len() - 1].to_vec();
        candidates.push(rise_end);
        let best_abs = candidates
            .iter()
            .map(|&t| self.f(t).abs())
            .fold(0.0, f64::max);
        let dip = (1.0 - hi) * scale;
        let margin = (best_abs - scale)
            .max(PEAK_REL * scale)
            .min(dip.max(PEAK_REL * scale));
        let t_far = self.horizon(margin)?;
        if t_far > t_settle {
            candidates.extend(self.critical_points(t_settle, t_far)?);
        }
        let ext = Extremes::of(self, &candidates, rise_end);

        // Transient time: the band is the threshold times the largest error.
        let max_err = candidates
            .iter()
            .map(|&t| (self.f(t) - self.y_inf).abs())
            .fold(0.0, f64::max);
        let transient_time = if max_err > 0.0 {
            self.last_exit(&bounds, self.opts.settling_threshold * max_err, xtol)?
        } else {
            0.0
        };

        Ok(StepInfo {
            rise_time: rise_end - rise_start,
            settling_time,
            transient_time,
            settling_min: ext.settling_min,
            settling_max: ext.settling_max,
            overshoot_percent: ((ext.max_signed - scale) / scale * 100.0).max(0.0),
            undershoot_percent: (-ext.min_signed / scale * 100.0).max(0.0),
            peak: ext.peak,
            peak_time: ext.peak_time,
            steady_state: self.y_inf,
            rise_start,
            rise_end,
        })
    }

    /// The last crossing of y∞ ± `band` (0 when y never leaves the band), searching the
    /// monotone pieces between `bounds` from the last one back.
    fn last_exit(&self, bounds: &[f64], band: f64, xtol: f64) -> Result<f64> {
        for w in bounds.windows(2).rev() {
            let mut best: Option<f64> = None;
            for level in [self.y_inf + band, self.y_inf - band] {
                let g = |t: f64| self.f(t) - level;
                if let Some(x) = crossing(&g, w[0], w[1], xtol)? {
                    best = Some(best.map_or(x, |b: f64| b.max(x)));
                }
            }
            if let Some(x) = best {
                return Ok(x);
            }
        }
        Ok(0.0)
    }
}

/// Peak and the extremes of y over the candidate times.
struct Extremes {
    peak: f64,
    peak_time: f64,
    max_signed: f64,
    min_signed: f64,
    settling_min: f64,
    settling_max: f64,
}

impl Extremes {
    fn of(m: &Metrics<'_>, candidates: &[f64], rise_end: f64) -> Extremes {
        let scale = m.y_inf.abs();
        let sgn = m.y_inf.signum();
        let mut e = Extremes {
            peak: scale,
            peak_time: f64::INFINITY,
            max_signed: f64::NEG_INFINITY,
            min_signed: f64::INFINITY,
            // the limit y∞ is approached after any candidate
            settling_min: m.y_inf,
            settling_max: m.y_inf,
        };
        for &t in candidates {
            let v = m.f(t);
            if v.abs() > e.peak || (e.peak_time.is_infinite() && v.abs() >= e.peak) {
                e.peak = v.abs();
                e.peak_time = t;
            }
            e.max_signed = e.max_signed.max(sgn * v);
            e.min_signed = e.min_signed.min(sgn * v);
            if t >= rise_end {
                e.settling_min = e.settling_min.min(v);
                e.settling_max = e.settling_max.max(v);
            }
        }
        e
    }
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
