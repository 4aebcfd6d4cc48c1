//! Exact time responses by matrix-exponential stepping.
//!
//! # Method (DESIGN §3)
//! The output is the impulse response of the rational function Y(s) (see
//! [`crate::analysis::laplace`]: the forced part G(s)U(s) in lowest terms and the
//! initial-condition part P_ic(s)/D(s), each realised separately). Each strictly proper part is
//! realised — in controllable canonical form ([`crate::StateSpace::from_tf`]) when the plant came with
//! coefficients, as a cascade of real sections ([`crate::StateSpace::from_zpk`]) when it came as
//! factors — balanced ([`crate::StateSpace::balanced`]), and y(t) = C e^(At) B is marched over the
//! sorted times with
//! x ← e^(AΔt) x. One e^(AΔt) serves every step of an equally spaced grid (recognised to a few
//! ulps of t, with the marched time kept as base + k·Δt so it does not drift), so 10⁵ samples
//! cost 10⁵ small matrix-vector products. Values come back in the caller's order.
//!
//! Nothing here depends on partial fractions, so values stay accurate where residues are huge
//! and cancel (poles 4e-5 apart for ζ = 1 ± 1e-9): the error is that of the matrix exponential
//! (~1e-15 relative per step), not of the pole locations.

use serde::Serialize;

use crate::analysis::factored::Factored;
use crate::analysis::input::Input;
use crate::analysis::laplace::{Decomposition, Part};
use crate::error::{LtiError, Result};
use crate::lti::TransferFunction;
use crate::numeric::expm;

/// Samples of an output y(t), in the order of the times the caller gave.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TimeResponse {
    /// Times (s), as given (any order, each finite and ≥ 0).
    pub t: Vec<f64>,
    /// y(t). For an impulse into a proper G with D ≠ 0 the D·δ(t) term is not included.
    pub y: Vec<f64>,
    /// The limit y(∞) when it exists and is finite (e.g. the step response of a BIBO-stable
    /// G is its dc gain).
    pub final_value: Option<f64>,
}

/// Every time must be finite and ≥ 0.
pub(crate) fn check_times(t: &[f64]) -> Result<()> {
    for &x in t {
        if !x.is_finite() {
            return Err(LtiError::InvalidTime {
                value: x,
                reason: "times must be finite numbers".into(),
            });
        }
        if x < 0.0 {
            return Err(LtiError::InvalidTime {
                value: x,
                reason: "times must be ≥ 0 (the response starts at t = 0)".into(),
            });
        }
    }
    Ok(())
}

/// Exact y at the (checked) times `t` for a decomposed Y(s).
pub(crate) fn simulate(dec: &Decomposition, t: &[f64]) -> Result<Vec<f64>> {
    let mut y = vec![0.0; t.len()];
    impulse_samples(&dec.forced, t, &mut y)?;
    if let Some(ic) = &dec.ic {
        impulse_samples(ic, t, &mut y)?;
    }
    Ok(y)
}

/// Adds the impulse response of the strictly proper part of `part` at the times `t` to `out`:
/// x ← e^(Ah)·x from x(0) = B, y = C·x ([`crate::numeric::march::march`]).
fn impulse_samples(part: &Part, t: &[f64], out: &mut [f64]) -> Result<()> {
    if t.is_empty() {
        return Ok(());
    }
    let Some(ss) = part.realization()? else {
        return Ok(());
    };
    let ss = ss.balanced();
    let n = ss.order();
    let c: Vec<f64> = (0..n).map(|j| ss.c[(0, j)]).collect();
    let mut x: Vec<f64> = (0..n).map(|i| ss.b[(i, 0)]).collect();
    let mut xn = vec![0.0; n];
    crate::numeric::march::march(
        t,
        &mut x,
        |h, ti, _| {
            // row-major e^(A h)
            let e = expm(&(&ss.a * h)).map_err(|e| overflow_reason(e, part, ti))?;
            Ok((0..n * n).map(|k| e[(k / n, k % n)]).collect::<Vec<f64>>())
        },
        |phi, x, _, _| {
            for (r, v) in xn.iter_mut().enumerate() {
                let row = &phi[r * n..(r + 1) * n];
                *v = row.iter().zip(x.iter()).map(|(a, b)| a * b).sum();
            }
            std::mem::swap(x, &mut xn);
            Ok(())
        },
        |i, ti, x| {
            let yi: f64 = c.iter().zip(x).map(|(a, b)| a * b).sum();
            if !yi.is_finite() {
                let norm = x.iter().map(|v| v * v).sum::<f64>().sqrt();
                return Err(LtiError::Diverged { t: ti, norm });
            }
            out[i] += yi;
            Ok(())
        },
    )
}

/// An overflowing exponential named by its cause: the fastest-growing mode of the part.
fn overflow_reason(e: LtiError, part: &Part, t: f64) -> LtiError {
    let LtiError::Overflow { .. } = e else {
        return e;
    };
    let worst = part
        .poles
        .iter()
        .map(|p| p.value)
        .max_by(|a, b| a.re.total_cmp(&b.re));
    match worst {
        Some(p) if p.re > 0.0 => LtiError::Overflow {
            what: format!("the response at t = {t} s"),
            reason: format!(
                ": the unstable mode at s = {} grows as e^({} t) and passes it after t ≈ {} s",
                crate::fmt::fmt_root(p, 6),
                crate::fmt::fmt_sig(p.re, 6),
                crate::fmt::fmt_sig(f64::MAX.ln() / p.re, 3)
            ),
        },
        _ => e,
    }
}

/// The times t − T of the rational part (0 where t < T) and which times fall before the
/// delay (there the response of a delayed plant is exactly 0).
pub(crate) fn shift_times(t: &[f64], delay: f64) -> (Vec<f64>, Vec<bool>) {
    let before: Vec<bool> = t.iter().map(|&x| x < delay).collect();
    let shifted = t.iter().map(|&x| (x - delay).max(0.0)).collect();
    (shifted, before)
}

/// A delayed plant's responses start from rest: the dead time acts on the input, and the
/// history of an input over [−T, 0) is not an ODE initial condition.
pub(crate) fn require_no_ics_with_delay(ics: &[f64], delay: f64) -> Result<()> {
    if ics.iter().all(|&x| x == 0.0) {
        return Ok(());
    }
    Err(LtiError::invalid(format!(
        "initial conditions with a dead time e^(-{} s): a delayed plant's response is taken \
         from rest (the input's history over the delay is not an ODE initial condition)",
        crate::fmt::fmt_num(delay)
    )))
}

impl Factored {
    /// The exact response to `input` with ODE initial conditions `ics` = [y(0), y′(0), …]
    /// (input zero for t < 0; fewer than the order: the rest are 0) at the times `t`, in the
    /// caller's order. See the [module docs](self) for the method.
    ///
    /// Errors: a negative or non-finite time ([`LtiError::InvalidTime`]), an improper G
    /// ([`LtiError::Improper`]), more initial conditions than the order, values that overflow
    /// ([`LtiError::Diverged`]).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::Input;
    /// // ÿ + 2ẏ + y = 0, y(0) = 1, ẏ(0) = 0: y = (1 + t) e^(−t) (seed eq. 3.35)
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 2.0, 1.0]).unwrap();
    /// let r = g.factored().unwrap().time_response(&Input::None, &[1.0, 0.0], &[2.0, 0.0, 1.0]).unwrap();
    /// for (t, y) in r.t.iter().zip(&r.y) {
    ///     assert!((y - (1.0 + t) * (-t).exp()).abs() < 1e-15);
    /// }
    /// assert_eq!(r.final_value, Some(0.0));
    /// ```
    pub fn time_response(&self, input: &Input, ics: &[f64], t: &[f64]) -> Result<TimeResponse> {
        if let Some(dt) = self.domain().dt() {
            return crate::analysis::discrete::time_response(self, dt, input, ics, t);
        }
        check_times(t)?;
        let delay = self.delay();
        if delay > 0.0 {
            require_no_ics_with_delay(ics, delay)?;
            let rational = self.rational();
            let (shifted, before) = shift_times(t, delay);
            let mut r = rational.time_response(input, ics, &shifted)?;
            for (y, b) in r.y.iter_mut().zip(before) {
                if b {
                    *y = 0.0;
                }
            }
            r.t = t.to_vec();
            return Ok(r);
        }
        let dec = Decomposition::new(self, input, ics)?;
        let y = simulate(&dec, t)?;
        Ok(TimeResponse {
            t: t.to_vec(),
            y,
            final_value: dec.final_value(),
        })
    }

    /// Unit-step response at the times `t` (zero initial conditions).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap().factored().unwrap();
    /// let r = g.step_response(&[0.0, 1.0]).unwrap();
    /// assert!((r.y[1] - (1.0 - (-1f64).exp())).abs() < 1e-15);
    /// assert_eq!(r.final_value, Some(1.0));
    /// assert!(g.step_response(&[-1.0]).is_err());
    /// ```
    pub fn step_response(&self, t: &[f64]) -> Result<TimeResponse> {
        self.time_response(&Input::Step, &[], t)
    }

    /// Unit-impulse response at the times `t` (zero initial conditions; a D·δ(t) term of a
    /// biproper G is not included in the values).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 0.0, 1.0]).unwrap().factored().unwrap();
    /// let r = g.impulse_response(&[1.0]).unwrap();
    /// assert!((r.y[0] - 1f64.sin()).abs() < 1e-15);
    /// assert_eq!(r.final_value, None); // sin t has no limit
    /// ```
    pub fn impulse_response(&self, t: &[f64]) -> Result<TimeResponse> {
        self.time_response(&Input::Impulse, &[], t)
    }
}

impl Factored {
    /// The response to `input` (zero initial conditions) at `points` times over [0, `t_end`]
    /// for drawing it: equally spaced, except where an oscillation of the response is faster
    /// than the spacing can follow (fewer than 3 samples per period), where the times move to
    /// that oscillation's alternate crests and troughs ([`lock_to_oscillation`]). Sampled
    /// uniformly there, a resonator (Q = 5·10⁵: 6·10⁵ periods before it settles) shows a
    /// false slow wave — aliasing; sampled at its extremes it fills its envelope, as a fine
    /// sampling would, and every value drawn is still the exact y at its own time.
    ///
    /// Errors: those of [`Factored::time_response`], `points` < 2, `t_end` not > 0.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::Input;
    /// // ζ = 1e-6: over 4e6 s, 1001 samples 4000 s apart, 640 periods each
    /// let f = TransferFunction::from_descending(&[1.0], &[1.0, 2e-6, 1.0]).unwrap().factored().unwrap();
    /// let r = f.response_for_drawing(&Input::Step, 4e6, 1001).unwrap();
    /// // the samples reach the envelope 1 ± e^(−ζt) (to within the damping's shift)
    /// let (lo, hi) = r.y.iter().fold((f64::MAX, f64::MIN), |(a, b), &y| (a.min(y), b.max(y)));
    /// assert!(hi > 1.99 && lo < 0.01);
    /// assert!(r.t.windows(2).all(|w| w[0] < w[1]));
    /// ```
    pub fn response_for_drawing(
        &self,
        input: &Input,
        t_end: f64,
        points: usize,
    ) -> Result<TimeResponse> {
        if points < 2 || !(t_end.is_finite() && t_end > 0.0) {
            return Err(LtiError::invalid(format!(
                "a drawing needs at least 2 points over a positive time span (got {points} \
                 points over {t_end} s)"
            )));
        }
        let n = (points - 1) as f64;
        let uniform: Vec<f64> = (0..points).map(|i| t_end * (i as f64 / n)).collect();
        check_times(&uniform)?;
        if let Some(dt) = self.domain().dt() {
            return self.staircase(input, dt, t_end, uniform);
        }
        let delay = self.delay();
        if delay > 0.0 {
            // exactly 0 up to T (drawn as a corner at T), then the rational response shifted
            let mut r = if t_end > delay {
                self.rational()
                    .response_for_drawing(input, t_end - delay, points)?
            } else {
                TimeResponse {
                    t: Vec::new(),
                    y: Vec::new(),
                    final_value: None,
                }
            };
            let mut t = vec![0.0];
            let mut y = vec![0.0];
            for (ti, yi) in r.t.iter().zip(&r.y) {
                t.push(ti + delay);
                y.push(*yi);
            }
            if t_end <= delay {
                t.push(t_end);
                y.push(0.0);
            }
            r.t = t;
            r.y = y;
            return Ok(r);
        }
        let dec = Decomposition::new(self, input, &[])?;
        let t = match dec.closed_form() {
            Ok(parts) => lock_to_oscillation(&uniform, &parts.closed_form),
            Err(_) => uniform,
        };
        let y = simulate(&dec, &t)?;
        Ok(TimeResponse {
            t,
            y,
            final_value: dec.final_value(),
        })
    }
}

impl Factored {
    /// A discrete-time response for drawing: each sample held until the next (two points
    /// per sample, the second at the next sample's time) when there are at most as many
    /// samples as `uniform` points; otherwise the held values at the `uniform` times.
    fn staircase(
        &self,
        input: &Input,
        dt: f64,
        t_end: f64,
        uniform: Vec<f64>,
    ) -> Result<TimeResponse> {
        // (compared in floating point: t_end/T may be far beyond usize)
        if (t_end / dt).floor() + 1.0 > uniform.len() as f64 {
            return self.time_response(input, &[], &uniform);
        }
        let samples = (t_end / dt).floor() as usize;
        let k: Vec<f64> = (0..=samples).map(|k| k as f64 * dt).collect();
        let r = self.time_response(input, &[], &k)?;
        let mut t = Vec::with_capacity(2 * k.len());
        let mut y = Vec::with_capacity(2 * k.len());
        for (i, (&ti, &yi)) in k.iter().zip(&r.y).enumerate() {
            t.push(ti);
            y.push(yi);
            let next = k.get(i + 1).copied().unwrap_or(t_end);
            if next > ti {
                t.push(next);
                y.push(yi);
            }
        }
        Ok(TimeResponse {
            t,
            y,
            final_value: r.final_value,
        })
    }
}

/// Samples per period below which an oscillation is locked onto (fewer than 3 cannot show
/// it; at 2 or fewer a uniform sampling aliases it into a false slow wave).
const LOCK_SAMPLES_PER_PERIOD: f64 = 3.0;

/// Equally spaced increasing times `t` moved onto the alternate crests and troughs of the
/// fastest-dominant oscillation of `y` wherever the spacing h is more than a third of its
/// period: at each time, among the oscillatory terms A e^(σt)·cos(ωt + φ) + … with
/// 2π/ω < 3h, the one with the largest envelope there sets the extremes (ωt + φ = mπ); the
/// time moves to the nearest such instant of the parity opposite to the previous locked one,
/// by at most one period, and only if the order of the times is kept. Other times (and the
/// first and last) are left as they are.
pub fn lock_to_oscillation(t: &[f64], y: &crate::analysis::ClosedForm) -> Vec<f64> {
    use crate::analysis::ClosedFormTerm;
    use std::f64::consts::PI;
    let mut out = t.to_vec();
    if t.len() < 3 {
        return out;
    }
    let h = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    // the oscillatory terms too fast for the spacing, and their (σ, ω, φ of the leading power)
    let terms: Vec<&ClosedFormTerm> = y
        .terms()
        .iter()
        .filter(|term| match term {
            ClosedFormTerm::Oscillatory {
                omega, amplitudes, ..
            } => 2.0 * PI / omega < LOCK_SAMPLES_PER_PERIOD * h && !amplitudes.is_empty(),
            _ => false,
        })
        .collect();
    let fast: Vec<(f64, f64, f64)> = terms
        .iter()
        .filter_map(|term| match term {
            ClosedFormTerm::Oscillatory {
                sigma,
                omega,
                phases,
                ..
            } => Some((*sigma, *omega, phases.first().copied().unwrap_or(0.0))),
            _ => None,
        })
        .collect();
    if fast.is_empty() {
        return out;
    }
    let envelope = |k: usize, at: f64| terms.get(k).map_or(0.0, |term| term.envelope(at));
    let mut parity: Option<i64> = None;
    for i in 1..t.len() - 1 {
        let ti = t[i];
        let Some(k) = (0..fast.len()).max_by(|&a, &b| envelope(a, ti).total_cmp(&envelope(b, ti)))
        else {
            continue;
        };
        let (_, w, phi) = fast[k];
        let x = (w * ti + phi) / PI;
        if !x.is_finite() || x.abs() > 2f64.powi(52) {
            continue; // the phase is beyond the resolution of a double
        }
        let mut m = x.round() as i64;
        if let Some(p) = parity {
            if m.rem_euclid(2) == p {
                m += if x > m as f64 { 1 } else { -1 };
            }
        }
        let u = (m as f64 * PI - phi) / w;
        if u > out[i - 1] && u < t[i + 1] && (u - ti).abs() <= 2.0 * PI / w {
            out[i] = u;
            parity = Some(m.rem_euclid(2));
        }
    }
    out
}

impl TransferFunction {
    /// The exact response at the times `t` ([`Factored::time_response`] of the factored G).
    pub fn time_response(&self, input: &Input, ics: &[f64], t: &[f64]) -> Result<TimeResponse> {
        check_times(t)?;
        self.factored()?.time_response(input, ics, t)
    }

    /// Unit-step response at the times `t` (zero initial conditions).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap();
    /// let r = g.step_response(&[0.0, 1.0]).unwrap();
    /// assert!((r.y[1] - (1.0 - (-1f64).exp())).abs() < 1e-15);
    /// ```
    pub fn step_response(&self, t: &[f64]) -> Result<TimeResponse> {
        self.time_response(&Input::Step, &[], t)
    }

    /// Unit-impulse response at the times `t` (zero initial conditions; a D·δ(t) term of a
    /// biproper G is not included in the values).
    pub fn impulse_response(&self, t: &[f64]) -> Result<TimeResponse> {
        self.time_response(&Input::Impulse, &[], t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unsorted_and_repeated_times_keep_the_callers_order() {
        let g = TransferFunction::from_descending(&[1.0], &[1.0, 3.0, 2.0]).unwrap();
        let t = [3.0, 0.5, 0.5, 0.0, 2.0];
        let r = g.step_response(&t).unwrap();
        for (ti, yi) in t.iter().zip(&r.y) {
            let want = 0.5 - (-ti).exp() + 0.5 * (-2.0 * ti).exp();
            assert!((yi - want).abs() < 1e-15, "t = {ti}");
        }
        assert_eq!(r.t, t.to_vec());
    }

    #[test]
    fn uniform_grid_reuses_one_exponential_accurately() {
        // 10⁴ steps of 1e-3 on ẏ = −y + u: the marched time must not drift.
        let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap();
        let t: Vec<f64> = (0..=10_000).map(|k| k as f64 * 1e-3).collect();
        let r = g.impulse_response(&t).unwrap();
        let err = t
            .iter()
            .zip(&r.y)
            .map(|(t, y)| (y - (-t).exp()).abs())
            .fold(0.0, f64::max);
        assert!(err < 1e-13, "{err}");
    }

    #[test]
    fn bad_times() {
        let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap();
        for bad in [f64::NAN, f64::INFINITY, -0.1] {
            assert!(matches!(
                g.step_response(&[0.0, bad]),
                Err(LtiError::InvalidTime { .. })
            ));
        }
        assert!(g.step_response(&[]).unwrap().y.is_empty());
    }

    #[test]
    fn unstable_overflow_is_an_error() {
        let g = TransferFunction::from_descending(&[1.0], &[1.0, -10.0]).unwrap();
        assert!(g.step_response(&[1e3]).is_err());
    }
}
