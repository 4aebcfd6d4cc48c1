//! Step metrics of a delayed closed loop (MATLAB `stepinfo` definitions, as
//! [`crate::analysis::step_info`]) on its piecewise closed form, over a finite horizon.
//!
//! # Method
//! On each interval \[kT, (k+1)T\] the response is the smooth sum of the first k pieces
//! ([`DelayedClosedForm`]); a grid of spacing min(0.2/|p|, T/16) (p the fastest pole of the
//! pieces) brackets every sign change of y′ there and Brent refines each to a critical
//! point, so y is monotone between consecutive bounds — the interval's ends, which are the
//! kinks (or jumps, for a bi-proper loop) where extrema may sit, and its critical points.
//! Level crossings on the monotone pieces are found by Brent (the searches of
//! [`crate::analysis::step_info`]); a jump across a level counts at its kink.
//!
//! # Horizon and stability
//! Nothing beyond the horizon is computed, and a finite horizon proves nothing about
//! stability: the caller declares it (`stable`), e.g. from a stability analysis of the
//! delayed loop. With `stable` the final value is y∞ = L(0)/(1 + L(0)) (1 for a loop with
//! an integrator); the peak, overshoot, undershoot and settling min/max are those of
//! \[0, t_end\], the settling and transient times the last exits within it — `None` with a
//! note when y(t_end) is still outside the band. Every result carries a note saying so.

use crate::analysis::delay::checks::check_loop;
use crate::analysis::delay::march::DelayMarch;
use crate::analysis::delay::pieces::{DelayedClosedForm, loop_powers};
use crate::analysis::delay::steps::{CLOSED_FORM_PIECES, march_pieces, probe_times};
use crate::analysis::factored::Factored;
use crate::analysis::input::Input;
use crate::analysis::step_info::search::{crossing, reach_in};
use crate::analysis::step_info::{MetricNote, StepInfo, StepInfoOptions};
use crate::error::{LtiError, Result, check_finite};
use crate::numeric::scalar::{Bracket, brent};

/// Grid steps allowed for one computation (all intervals together).
const MAX_GRID: usize = 4_000_000;
/// Grid spacing against the fastest pole: 0.2/|p| (about 31 points per period).
const GRID_FACTOR: f64 = 0.2;
/// At least this many grid steps per interval.
const MIN_STEPS_PER_INTERVAL: f64 = 16.0;

/// The arguments of the step metrics of a delayed response, checked alike for the closed form
/// and the march: valid options, a finite final value ≠ 0, a horizon in [0, `valid_until`),
/// where `holds` ("the 24 pieces hold", "the march holds") says what is valid.
fn check_metric_args(
    opts: &StepInfoOptions,
    y_inf: f64,
    horizon: f64,
    valid_until: f64,
    holds: &str,
) -> Result<()> {
    opts.validate()?;
    check_finite(|| "the final value".into(), y_inf)?;
    check_finite(|| "the horizon".into(), horizon)?;
    if y_inf == 0.0 {
        return Err(LtiError::Undefined {
            what: "step metrics".into(),
            reason: "the final value is 0".into(),
        });
    }
    if !(horizon >= 0.0 && horizon < valid_until) {
        return Err(LtiError::InvalidTime {
            value: horizon,
            reason: format!(
                "the horizon must lie in [0, {}) s, where {holds}",
                crate::fmt::fmt_sig(valid_until, 6),
            ),
        });
    }
    Ok(())
}

impl Factored {
    /// Step metrics of the closed loop of this loop L with dead time `delay` in negative
    /// unity feedback, over 0 ≤ t ≤ `horizon` (see [`crate::analysis::delay::steps_info`]);
    /// `None` when the caller says the loop is not `stable` (the final value then does not
    /// exist). The final value is L(0)/(1 + L(0)).
    ///
    /// Up to [`CLOSED_FORM_PIECES`] delays the metrics are found on the closed form when it
    /// agrees with the exact march of its pieces; otherwise (and over longer horizons, up to
    /// [`crate::analysis::delay::MAX_MARCH_INTERVALS`] delays) on the collocation march
    /// ([`DelayMarch::step_info`]).
    ///
    /// Errors: an invalid loop, delay or horizon, invalid options, a zero final value
    /// (L(0) = 0), a grid beyond 4·10⁶ steps, the limits of the march.
    ///
    /// ```
    /// use ltikit::analysis::{Factored, StepInfoOptions};
    /// use ltikit::Root;
    /// use num_complex::Complex64 as C;
    /// // L = 1/(s + 1), T = 1 (stable: |L(jω)| < 1 for ω > 0): y∞ = 1/2; y rises from t = 1.
    /// let l = Factored::from_zpk(&[], &[Root::new(C::new(-1.0, 0.0), 1)], 1.0).unwrap();
    /// let s = l.delayed_step_info(1.0, 30.0, true, &StepInfoOptions::default()).unwrap().unwrap();
    /// assert_eq!(s.steady_state, 0.5);
    /// // 10 % of 1/2 is reached on [1, 2], where y = 1 − e^(−(t−1)): t = 1 + ln(1/0.95)
    /// assert!((s.rise_start.unwrap() - (1.0 + (1.0f64 / 0.95).ln())).abs() < 1e-13);
    /// assert!(s.overshoot_percent.unwrap() > 0.0 && s.peak_time.unwrap() > 2.0);
    /// ```
    pub fn delayed_step_info(
        &self,
        delay: f64,
        horizon: f64,
        stable: bool,
        opts: &StepInfoOptions,
    ) -> Result<Option<StepInfo>> {
        opts.validate()?;
        check_loop(self, delay, &Input::Step, horizon)?;
        if !stable {
            return Ok(None);
        }
        let y_inf = match self.dc_gain() {
            None => 1.0,
            Some(l0) => l0 / (1.0 + l0),
        };
        if !y_inf.is_finite() {
            return Err(LtiError::Undefined {
                what: "the final value of the delayed closed loop".into(),
                reason: "L(0) = −1: the closed loop has a pole at s = 0".into(),
            });
        }
        // the closed form over a few delays, when it agrees with the exact march of its
        // pieces; the collocation march otherwise (and over long horizons)
        if (horizon / delay).floor() <= CLOSED_FORM_PIECES as f64 {
            let powers = loop_powers(self, delay, &Input::Step, horizon)?;
            let y = DelayedClosedForm::of_powers(&powers, delay, &Input::Step)?;
            if check_against_march(&powers, &y, horizon, y_inf, opts).is_ok() {
                return y.step_info(y_inf, horizon, opts).map(Some);
            }
        }
        let m = DelayMarch::new(self, delay, &Input::Step, horizon)?;
        m.step_info(y_inf, horizon, opts).map(Some)
    }
}

/// The metrics are found on the closed form: it must agree with the exact march of the
/// pieces ([`march_pieces`]) to a thousandth of the settling band, at both ends and the middle
/// of every interval, or the metrics are refused (the residues of k-fold poles, for large k,
/// carry more rounding than the march).
fn check_against_march(
    powers: &[Factored],
    y: &DelayedClosedForm,
    horizon: f64,
    y_inf: f64,
    opts: &StepInfoOptions,
) -> Result<()> {
    let t = probe_times(y, horizon);
    let m = march_pieces(powers, y, &Input::Step, &t)?;
    let tol = 1e-3 * opts.settling_threshold * y_inf.abs();
    let worst = t
        .iter()
        .zip(&m.y)
        .map(|(&x, v)| (x, (y.eval(x) - v).abs()))
        .fold((0.0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    if worst.1 > tol || !worst.1.is_finite() {
        return Err(LtiError::Undefined {
            what: "step metrics of the delayed loop".into(),
            reason: format!(
                "the closed form of the {} pieces differs from the exact march by {} at t = {} s \
                 (more than {}): the alternating pieces have lost their accuracy; shorten the \
                 horizon or use a Padé approximant of the delay",
                y.len(),
                crate::fmt::fmt_sig(worst.1, 3),
                crate::fmt::fmt_sig(worst.0, 6),
                crate::fmt::fmt_sig(tol, 3)
            ),
        });
    }
    Ok(())
}

impl DelayedClosedForm {
    /// Step metrics of this step response (see the [module docs](self)) against the final
    /// value `y_inf` ≠ 0 declared by the caller, over 0 ≤ t ≤ `horizon` (at most the
    /// validity of the pieces).
    ///
    /// Errors: `y_inf` zero or not finite, a horizon beyond the pieces, invalid options, a
    /// grid beyond 4·10⁶ steps.
    ///
    /// ```
    /// use ltikit::analysis::{Factored, Input, StepInfoOptions, delay::DelayedClosedForm};
    /// use ltikit::Root;
    /// use num_complex::Complex64 as C;
    /// let l = Factored::from_zpk(&[], &[Root::new(C::new(-1.0, 0.0), 1)], 0.5).unwrap();
    /// let y = DelayedClosedForm::new(&l, 0.5, &Input::Step, 20.0).unwrap();
    /// let s = y.step_info(1.0 / 3.0, 20.0, &StepInfoOptions::default()).unwrap();
    /// assert!(s.settling_time.unwrap() < 20.0);
    /// assert!(s.note("settling_time").unwrap().contains("over the horizon"));
    /// ```
    pub fn step_info(&self, y_inf: f64, horizon: f64, opts: &StepInfoOptions) -> Result<StepInfo> {
        check_metric_args(
            opts,
            y_inf,
            horizon,
            self.valid_until(),
            &format!("the {} pieces hold", self.len()),
        )?;
        let pieces = self.monotone_pieces(horizon)?;
        Ok(Measure {
            y: self,
            pieces: &pieces,
            y_inf,
            horizon,
            opts,
        }
        .compute())
    }

    /// The grid spacing: 0.2/|p| for the fastest pole of the pieces, at most T/16.
    fn spacing(&self) -> f64 {
        let rate = self
            .pieces
            .iter()
            .flat_map(|h| h.terms().iter().filter_map(|t| t.pole()))
            .map(|p| p.norm())
            .fold(0.0, f64::max);
        let cap = self.delay / MIN_STEPS_PER_INTERVAL;
        if rate > 0.0 {
            (GRID_FACTOR / rate).min(cap)
        } else {
            cap
        }
    }

    /// Every monotone piece of y on \[0, horizon\]: (interval k, a, b) with y = the sum of the
    /// first k pieces on \[a, b\], monotone there.
    fn monotone_pieces(&self, horizon: f64) -> Result<Vec<Piece>> {
        let h = self.spacing();
        let last = self.interval_of(horizon);
        let mut budget = MAX_GRID;
        let mut out = Vec::new();
        for k in 0..=last {
            let a = self.kink(k);
            let b = if k == last { horizon } else { self.kink(k + 1) };
            if k == 0 {
                // y = 0 before the first delay has elapsed
                out.push(Piece { k, a, b });
                continue;
            }
            let steps = ((b - a) / h).ceil().max(1.0);
            if steps > budget as f64 {
                return Err(LtiError::LimitExceeded {
                    field: format!(
                        "the scan of the delayed step response (interval {k} of {last}, \
                         spacing {} s)",
                        crate::fmt::fmt_sig(h, 3)
                    ),
                    value: (MAX_GRID - budget) as u128 + steps as u128,
                    max: MAX_GRID as u64,
                    unit: "grid steps".into(),
                    limit: "the step metrics' grid".into(),
                });
            }
            // steps ≤ budget ≤ MAX_GRID
            let n = steps as usize;
            budget -= n;
            let df = |t: f64| self.derivative_in(k, t);
            let mut start = a;
            let mut t0 = a;
            let mut d0 = df(a);
            for i in 1..=n {
                let t1 = if i == n {
                    b
                } else {
                    a + (b - a) * (i as f64 / n as f64)
                };
                let d1 = df(t1);
                if d0 != 0.0 && d1 != 0.0 && d0.signum() != d1.signum() {
                    let br = Bracket {
                        a: t0,
                        b: t1,
                        fa: d0,
                        fb: d1,
                    };
                    let c = brent(df, br, 1e-300)?;
                    out.push(Piece { k, a: start, b: c });
                    start = c;
                } else if d1 == 0.0 && i < n {
                    out.push(Piece { k, a: start, b: t1 });
                    start = t1;
                }
                t0 = t1;
                d0 = d1;
            }
            out.push(Piece { k, a: start, b });
        }
        Ok(out)
    }
}

/// A response measured piece by piece: the closed form (piece k = the sum of the first k
/// pieces) or the collocation march (piece k = sub-interval k).
trait Curve {
    /// y on piece k at t (smooth on the piece's closed interval).
    fn value_in(&self, k: usize, t: f64) -> f64;
    /// y(t).
    fn value_at(&self, t: f64) -> f64;
    /// The rounding or error bound of y(t).
    fn bound_at(&self, t: f64) -> f64;
}

impl Curve for DelayedClosedForm {
    fn value_in(&self, k: usize, t: f64) -> f64 {
        self.eval_in(k, t)
    }
    fn value_at(&self, t: f64) -> f64 {
        self.eval(t)
    }
    fn bound_at(&self, t: f64) -> f64 {
        self.error_bound(t)
    }
}

impl Curve for DelayMarch {
    fn value_in(&self, k: usize, t: f64) -> f64 {
        DelayMarch::value_in(self, k, t)
    }
    fn value_at(&self, t: f64) -> f64 {
        self.eval(t)
    }
    fn bound_at(&self, t: f64) -> f64 {
        self.error_at(t)
    }
}

/// Derivative samples per sub-interval of the march when its monotone pieces are searched.
const MARCH_SCAN: usize = 64;

impl DelayMarch {
    /// Step metrics of this marched step response against the final value `y_inf` ≠ 0
    /// declared by the caller, over 0 ≤ t ≤ `horizon` (within the march): each sub-interval
    /// is searched on its interpolant (the derivative's sign changes among 64 samples,
    /// refined by Brent), the kinks kT and sub-interval ends kept as candidates.
    ///
    /// Errors: `y_inf` zero or not finite, a horizon beyond the march, invalid options.
    pub fn step_info(&self, y_inf: f64, horizon: f64, opts: &StepInfoOptions) -> Result<StepInfo> {
        check_metric_args(opts, y_inf, horizon, self.valid_until(), "the march holds")?;
        let last = self.piece_of(horizon);
        let mut out = Vec::new();
        for g in 0..=last {
            let (a, b0) = self.bounds(g);
            let b = if g == last { horizon } else { b0 };
            if g < self.sub || b <= a {
                // y = 0 before the first delay has elapsed
                out.push(Piece { k: g, a, b });
                continue;
            }
            let dn = self.node_derivatives(g);
            let df = |t: f64| self.derivative_in(g, &dn, t);
            let mut start = a;
            let mut t0 = a;
            let mut d0 = df(a);
            for i in 1..=MARCH_SCAN {
                let t1 = if i == MARCH_SCAN {
                    b
                } else {
                    a + (b - a) * (i as f64 / MARCH_SCAN as f64)
                };
                let d1 = df(t1);
                if d0 != 0.0 && d1 != 0.0 && d0.signum() != d1.signum() {
                    let br = Bracket {
                        a: t0,
                        b: t1,
                        fa: d0,
                        fb: d1,
                    };
                    let c = brent(df, br, 1e-300)?;
                    out.push(Piece {
                        k: g,
                        a: start,
                        b: c,
                    });
                    start = c;
                } else if d1 == 0.0 && i < MARCH_SCAN {
                    out.push(Piece {
                        k: g,
                        a: start,
                        b: t1,
                    });
                    start = t1;
                }
                t0 = t1;
                d0 = d1;
            }
            out.push(Piece { k: g, a: start, b });
        }
        Ok(Measure {
            y: self,
            pieces: &out,
            y_inf,
            horizon,
            opts,
        }
        .compute())
    }
}

/// A monotone stretch of y: the sum of the first `k` pieces on \[a, b\].
#[derive(Debug, Clone, Copy)]
struct Piece {
    k: usize,
    a: f64,
    b: f64,
}

/// The response being measured.
struct Measure<'a, C: Curve> {
    y: &'a C,
    pieces: &'a [Piece],
    y_inf: f64,
    horizon: f64,
    opts: &'a StepInfoOptions,
}

impl<C: Curve> Measure<'_, C> {
    fn f(&self, p: &Piece, t: f64) -> f64 {
        self.y.value_in(p.k, t)
    }

    fn compute(&self) -> StepInfo {
        let scale = self.y_inf.abs();
        let mut notes = Vec::new();
        let (lo, hi) = self.opts.rise_limits;
        let rise = match (self.first_reach(lo * scale), self.first_reach(hi * scale)) {
            (Ok(Some(a)), Ok(Some(b))) => Some((a, b)),
            (Err(e), _) | (_, Err(e)) => {
                notes.push(MetricNote {
                    quantities: vec!["rise_time", "rise_start", "rise_end"],
                    reason: format!("not computed: {e}"),
                });
                None
            }
            _ => {
                notes.push(MetricNote {
                    quantities: vec!["rise_time", "rise_start", "rise_end"],
                    reason: format!(
                        "not computed: the response does not reach {} % of the final value \
                         within the horizon ({} s)",
                        hi * 100.0,
                        crate::fmt::fmt_sig(self.horizon, 6)
                    ),
                });
                None
            }
        };
        let ext = self.extremes(rise.map(|r| r.1));
        let band = self.opts.settling_threshold * scale;
        let settling = self.last_exit(band);
        let transient = if ext.max_err > 0.0 {
            self.last_exit(self.opts.settling_threshold * ext.max_err)
        } else {
            Some(0.0)
        };
        let unsettled = |q: &'static str, what: &str| MetricNote {
            quantities: vec![q],
            reason: format!(
                "not computed: y is still outside the {what} band at the end of the horizon \
                 (t = {} s)",
                crate::fmt::fmt_sig(self.horizon, 6)
            ),
        };
        if settling.is_none() {
            notes.push(unsettled("settling_time", "settling"));
        }
        if transient.is_none() {
            notes.push(unsettled("transient_time", "transient"));
        }
        notes.push(MetricNote {
            quantities: vec![
                "settling_time",
                "transient_time",
                "peak",
                "peak_time",
                "overshoot_percent",
                "undershoot_percent",
                "settling_min",
                "settling_max",
            ],
            reason: format!(
                "over the horizon [0, {}] s only (the delayed loop's response is not examined \
                 beyond it; its stability and final value {} were declared by the caller)",
                crate::fmt::fmt_sig(self.horizon, 6),
                crate::fmt::fmt_sig(self.y_inf, 6)
            ),
        });
        let overshoot = if ext.max_signed - scale <= ext.max_bound {
            0.0
        } else {
            (ext.max_signed - scale) / scale * 100.0
        };
        let undershoot = if -ext.min_signed <= ext.min_bound {
            0.0
        } else {
            -ext.min_signed / scale * 100.0
        };
        StepInfo {
            rise_time: rise.map(|(a, b)| b - a),
            settling_time: settling,
            transient_time: transient,
            settling_min: ext.settling_min,
            settling_max: ext.settling_max,
            overshoot_percent: Some(overshoot),
            undershoot_percent: Some(undershoot),
            peak: Some(ext.peak),
            peak_time: Some(ext.peak_time),
            steady_state: self.y_inf,
            rise_start: rise.map(|r| r.0),
            rise_end: rise.map(|r| r.1),
            notes,
        }
    }

    /// The first t with sgn·y(t) ≥ `level` (a jump across it counts at its kink).
    fn first_reach(&self, level: f64) -> Result<Option<f64>> {
        let sgn = self.y_inf.signum();
        for p in self.pieces {
            let g = |t: f64| sgn * self.f(p, t) - level;
            if let Some(x) = reach_in(&g, p.a, p.b)? {
                return Ok(Some(x));
            }
        }
        Ok(None)
    }

    /// The extremes over the ends of the monotone pieces (the kinks with the values on both
    /// sides, the critical points, the horizon).
    fn extremes(&self, rise_end: Option<f64>) -> Extremes {
        let sgn = self.y_inf.signum();
        let mut x = Extremes {
            peak: 0.0,
            peak_time: 0.0,
            max_signed: 0.0,
            min_signed: 0.0,
            max_bound: 0.0,
            min_bound: 0.0,
            settling_min: None,
            settling_max: None,
            max_err: self.y_inf.abs(), // |y(0) − y∞|
        };
        let mut consider = |t: f64, v: f64| {
            let bound = self.y.bound_at(t);
            if v.abs() > x.peak {
                x.peak = v.abs();
                x.peak_time = t;
            }
            if sgn * v > x.max_signed {
                x.max_signed = sgn * v;
                x.max_bound = bound;
            }
            if sgn * v < x.min_signed {
                x.min_signed = sgn * v;
                x.min_bound = bound;
            }
            if rise_end.is_some_and(|r| t >= r) {
                x.settling_min = Some(x.settling_min.map_or(v, |m: f64| m.min(v)));
                x.settling_max = Some(x.settling_max.map_or(v, |m: f64| m.max(v)));
            }
            x.max_err = x.max_err.max((v - self.y_inf).abs());
        };
        if let Some(r) = rise_end {
            consider(r, self.y.value_at(r));
        }
        for p in self.pieces {
            consider(p.a, self.f(p, p.a));
            consider(p.b, self.f(p, p.b));
        }
        x
    }

    /// The last time |y − y∞| = `band` within the horizon (0 when y never leaves the band;
    /// a jump out of the band counts at its kink); `None` when y(horizon) is outside it.
    fn last_exit(&self, band: f64) -> Option<f64> {
        let end = self.pieces.last()?;
        if (self.f(end, end.b) - self.y_inf).abs() > band {
            return None;
        }
        let mut last = 0.0f64;
        for p in self.pieces {
            if (self.f(p, p.b) - self.y_inf).abs() > band {
                last = last.max(p.b);
                continue;
            }
            for level in [self.y_inf + band, self.y_inf - band] {
                let g = |t: f64| self.f(p, t) - level;
                // a failed refinement leaves the bracket's end: the crossing lies before it
                match crossing(&g, p.a, p.b) {
                    Ok(Some(c)) => last = last.max(c),
                    Ok(None) => {}
                    Err(_) => last = last.max(p.b),
                }
            }
        }
        Some(last)
    }
}

/// The extremes over the candidate times.
struct Extremes {
    peak: f64,
    peak_time: f64,
    max_signed: f64,
    min_signed: f64,
    /// The rounding bounds of y at the times of `max_signed` and `min_signed`.
    max_bound: f64,
    min_bound: f64,
    settling_min: Option<f64>,
    settling_max: Option<f64>,
    max_err: f64,
}
