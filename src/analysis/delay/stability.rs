//! Stability in the delay over all T ≥ 0: the crossing frequencies, their delays and
//! directions, the count of unstable roots at any delay, the stable intervals (the method is
//! described in the [module docs](super)).

use std::f64::consts::TAU;

use serde::Serialize;

use super::parts::DelayedLoop;
use crate::analysis::factored::Factored;
use crate::error::{LtiError, Result};
use crate::fmt::fmt_num;
use crate::poly::{HalfPlane, Poly, Root, half_plane};

/// Most crossing delays merged into the stable intervals; beyond it the intervals stop at the
/// last merged delay and [`DelayStability::complete`] is false (the counts at any delay stay
/// exact: they are closed forms).
///
/// ```
/// assert_eq!(ltikit::analysis::delay::MAX_DELAY_EVENTS, 100_000);
/// ```
pub const MAX_DELAY_EVENTS: usize = 100_000;

/// Which way a pair of characteristic roots crosses the imaginary axis as the delay grows.
///
/// ```
/// use ltikit::TransferFunction;
/// use ltikit::analysis::CrossingDirection;
/// // 0.5/(s² + 0.1s + 4): the lower crossing frequency stabilizes, the upper destabilizes
/// let f = TransferFunction::from_descending(&[0.5], &[1.0, 0.1, 4.0]).unwrap().factored().unwrap();
/// let c = f.delay_stability().unwrap().crossings;
/// assert_eq!(c[0].direction, CrossingDirection::Stabilizing);
/// assert_eq!(c[1].direction, CrossingDirection::Destabilizing);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CrossingDirection {
    /// Into the right half plane (W′(ω²) > 0): two more unstable roots.
    Destabilizing,
    /// Back into the left half plane (W′(ω²) < 0): two fewer.
    Stabilizing,
    /// The roots touch the axis and turn back (W has a multiple root there): not counted.
    Tangential,
}

/// A crossing frequency ω_c and its delays T_k = (θ + 2πk)/ω_c, k = 0, 1, …
///
/// ```
/// use ltikit::TransferFunction;
/// // L = 2/(s + 1): |L(jω)| = 1 at ω = √3, θ = 2π/3, T₀ = 2π/(3√3)
/// let f = TransferFunction::from_descending(&[2.0], &[1.0, 1.0]).unwrap().factored().unwrap();
/// let c = f.delay_stability().unwrap().crossings[0];
/// assert!((c.frequency - 3f64.sqrt()).abs() < 1e-15);
/// assert!((c.delay(0) - 2.0 * std::f64::consts::PI / (3.0 * 3f64.sqrt())).abs() < 1e-15);
/// assert!((c.delay(1) - c.delay(0) - c.period()).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DelayCrossing {
    /// The crossing frequency ω_c > 0 (rad/s), where |L(jω_c)| = 1.
    pub frequency: f64,
    /// θ = arg(−L(jω_c)) in [0, 2π) (rad): exactly 0 when the pair is on the axis at T = 0.
    pub phase: f64,
    /// Which way the pair moves as the delay grows.
    pub direction: CrossingDirection,
}

impl DelayCrossing {
    /// The k-th crossing delay (θ + 2πk)/ω_c (s).
    pub fn delay(&self, k: usize) -> f64 {
        (self.phase + TAU * k as f64) / self.frequency
    }

    /// The spacing of the crossing delays, 2π/ω_c (s).
    pub fn period(&self) -> f64 {
        TAU / self.frequency
    }

    /// How many of its delays lie in (0, T) — its crossings completed as the delay grows to
    /// T (a delay of 0, θ = 0, is the pair on the axis at T = 0: it counts for T > 0 when
    /// the pair leaves to the right, never when it leaves to the left).
    fn passed(&self, t: f64) -> u64 {
        let x = t * self.frequency - self.phase;
        if x <= 0.0 {
            return 0;
        }
        let estimate = (x / TAU).ceil();
        let mut n = if estimate >= 1e15 {
            return estimate.min(u64::MAX as f64) as u64;
        } else {
            estimate as u64
        };
        while n > 0 && self.delay(n as usize - 1) >= t {
            n -= 1;
        }
        while self.delay(n as usize) < t {
            n += 1;
        }
        if self.phase == 0.0 && self.direction == CrossingDirection::Stabilizing {
            n.saturating_sub(1)
        } else {
            n
        }
    }

    /// ±2 per crossing, 0 for a tangency.
    fn step(&self) -> i64 {
        match self.direction {
            CrossingDirection::Destabilizing => 2,
            CrossingDirection::Stabilizing => -2,
            CrossingDirection::Tangential => 0,
        }
    }
}

/// A range of delays on which the closed loop is stable: open, except that `from = 0`
/// includes T = 0 when the loop is stable without delay; `to` may be ∞.
///
/// ```
/// use ltikit::TransferFunction;
/// // 0.5/(s + 1): |L(jω)| < 1 everywhere, stable for every delay
/// let f = TransferFunction::from_descending(&[0.5], &[1.0, 1.0]).unwrap().factored().unwrap();
/// let iv = f.delay_stability().unwrap().stable_intervals;
/// assert_eq!((iv[0].from, iv[0].to), (0.0, f64::INFINITY));
/// assert!(iv[0].contains(1e9));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DelayInterval {
    /// Lower end (s).
    pub from: f64,
    /// Upper end (s), ∞ when stable for every larger delay.
    pub to: f64,
}

impl DelayInterval {
    /// True when `delay` lies strictly inside (from, to) (T = 0 itself: see
    /// [`DelayStability::is_stable_at`]).
    pub fn contains(&self, delay: f64) -> bool {
        delay > self.from && delay < self.to
    }
}

/// Stability in the delay of the closed loop D(s) + N(s)·e^(−sT) for every T ≥ 0 (see the
/// [module docs](super) and [`Factored::delay_stability`]).
///
/// ```
/// use ltikit::TransferFunction;
/// // 0.5/(s² + 0.1s + 4) with a delay: stable, unstable, stable again, … (switches)
/// let f = TransferFunction::from_descending(&[0.5], &[1.0, 0.1, 4.0]).unwrap().factored().unwrap();
/// let d = f.delay_stability().unwrap();
/// assert!(d.stable_without_delay && d.stability_switches && d.complete);
/// assert!(d.stable_intervals.len() > 2);
/// assert!(d.is_stable_at(2.0).unwrap() && !d.is_stable_at(1.0).unwrap());
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DelayStability {
    /// Roots of D + N (the loop without delay) in the open right half plane.
    pub unstable_at_zero: usize,
    /// Roots of D + N on the imaginary axis (s = 0 included).
    pub axis_roots_at_zero: Vec<Root>,
    /// True when the loop without delay is asymptotically stable.
    pub stable_without_delay: bool,
    /// D(0) + N(0) = 0 (L(0) = −1): s = 0 is a characteristic root for every delay, so the
    /// loop is never asymptotically stable.
    pub root_at_origin: bool,
    /// The crossing frequencies with their delays and directions, by increasing frequency.
    pub crossings: Vec<DelayCrossing>,
    /// The delays for which the loop is stable, in increasing order (empty when never).
    pub stable_intervals: Vec<DelayInterval>,
    /// The first delay at which the loop, stable without delay, loses stability (∞ when
    /// never); `None` when it is not stable without delay.
    pub critical_delay: Option<f64>,
    /// True when the loop becomes stable again after being unstable (a stable interval that
    /// starts at a delay T > 0).
    pub stability_switches: bool,
    /// True when every crossing delay that can matter was merged; false when the merge
    /// stopped after [`MAX_DELAY_EVENTS`] delays (the intervals end at `horizon`).
    pub complete: bool,
    /// The delay up to which the crossing delays were merged: beyond it the count of unstable
    /// roots stays positive (∞ when it settles without destabilizing crossings).
    pub horizon: f64,
    /// |L(∞)| when L is bi-proper (a neutral-type equation, analysed when < 1), else `None`.
    pub neutral: Option<f64>,
    /// Modes cancelled in L: roots of the characteristic equation for every delay, outside
    /// Δ; their stability matters separately.
    pub hidden_modes: Vec<Root>,
    /// Remarks in plain words: tangencies, the root at the origin, the neutral type, hidden
    /// modes, switches, an incomplete merge.
    pub notes: Vec<String>,
}

pub(super) fn check_delay(delay: f64) -> Result<f64> {
    if !delay.is_finite() {
        return Err(LtiError::NonFinite {
            what: "`delay`".into(),
            value: delay,
        });
    }
    if delay < 0.0 {
        return Err(LtiError::invalid(format!(
            "`delay`: {} is negative (a dead time is ≥ 0)",
            fmt_num(delay)
        )));
    }
    Ok(delay)
}

impl DelayStability {
    /// The number of characteristic roots of D + N·e^(−sT) in the open right half plane at
    /// `delay` = T: the count without delay plus ±2 per crossing delay in (0, T). At a
    /// crossing delay itself the pair on the axis is not counted.
    ///
    /// Errors: a NaN, infinite or negative delay.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // 5 e^(−sT)/(s + 1): crossings at T = arccos(−1/5)/√24 + 2πk/√24
    /// let f = TransferFunction::from_descending(&[5.0], &[1.0, 1.0]).unwrap().factored().unwrap();
    /// let d = f.delay_stability().unwrap();
    /// let t0 = (-0.2f64).acos() / 24f64.sqrt();
    /// assert_eq!(d.unstable_roots_at(0.99 * t0).unwrap(), 0);
    /// assert_eq!(d.unstable_roots_at(1.01 * t0).unwrap(), 2);
    /// assert!(d.unstable_roots_at(-1.0).is_err());
    /// ```
    pub fn unstable_roots_at(&self, delay: f64) -> Result<usize> {
        let t = check_delay(delay)?;
        if t == 0.0 {
            return Ok(self.unstable_at_zero);
        }
        let mut n = self.unstable_at_zero as i128;
        for c in &self.crossings {
            n += i128::from(c.step()) * i128::from(c.passed(t));
        }
        Ok(n.clamp(0, usize::MAX as i128) as usize)
    }

    /// True when the closed loop is asymptotically stable at `delay`: no root in the open
    /// right half plane, none at the origin, and (at T = 0) none on the axis.
    ///
    /// Errors: a NaN, infinite or negative delay.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // K e^(−sT)/s: stable iff T < π/(2K)
    /// let f = TransferFunction::from_descending(&[2.0], &[1.0, 0.0]).unwrap().factored().unwrap();
    /// let d = f.delay_stability().unwrap();
    /// assert!(d.is_stable_at(0.7).unwrap() && !d.is_stable_at(0.8).unwrap());
    /// ```
    pub fn is_stable_at(&self, delay: f64) -> Result<bool> {
        let n = self.unstable_roots_at(delay)?;
        if delay == 0.0 {
            return Ok(self.stable_without_delay);
        }
        let on_axis = self
            .crossings
            .iter()
            .filter(|c| c.direction != CrossingDirection::Tangential)
            .any(|c| c.passed(delay) != c.passed(delay * (1.0 + f64::EPSILON)));
        Ok(n == 0 && !self.root_at_origin && !on_axis)
    }
}

impl Factored {
    /// Stability in the delay, for every T ≥ 0, of the closed loop of this loop L = N/D with
    /// a dead time e^(−sT) in negative unity feedback, Δ(s, T) = D(s) + N(s)·e^(−sT) (D, N
    /// from the reduced poles, zeros and gain): the unstable count without delay, the
    /// crossing frequencies with their delays and directions, the stable delay intervals, the
    /// critical delay, stability switches (see the [module docs](super)). Modes cancelled in L
    /// are outside Δ and listed in `hidden_modes`.
    ///
    /// A bi-proper L with |L(∞)| < 1 is a neutral-type equation and analysed alike (noted).
    ///
    /// Errors: a discrete-time loop; L ≡ 0; an improper L; a bi-proper L with |L(∞)| ≥ 1
    /// (roots in or approaching the right half plane for every T > 0); more than
    /// [`crate::MAX_ORDER`] reduced poles; the root finder's.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // 2 e^(−sT)/(s + 1): stable iff T < arccos(−1/2)/√3 = 2π/(3√3)
    /// let f = TransferFunction::from_descending(&[2.0], &[1.0, 1.0]).unwrap().factored().unwrap();
    /// let d = f.delay_stability().unwrap();
    /// let tc = 2.0 * std::f64::consts::PI / (3.0 * 3f64.sqrt());
    /// assert!((d.critical_delay.unwrap() - tc).abs() < 1e-15);
    /// assert_eq!(d.stable_intervals.len(), 1);
    /// ```
    pub fn delay_stability(&self) -> Result<DelayStability> {
        let l = DelayedLoop::new(self, "stability in the delay")?;
        analyse(&l)
    }
}

/// The whole analysis on checked parts.
pub(super) fn analyse(l: &DelayedLoop) -> Result<DelayStability> {
    let mut notes = Vec::new();
    if !l.hidden.is_empty() {
        let list: Vec<String> = l.hidden.iter().map(|r| format_root(r.value)).collect();
        notes.push(format!(
            "the loop cancels the modes {}: they are characteristic roots for every delay, outside D + N·e^(−sT); their stability must be judged separately",
            list.join(", ")
        ));
    }
    if let Some(c) = l.at_infinity() {
        notes.push(format!(
            "L is bi-proper: D + N·e^(−sT) is of neutral type; |L(∞)| = {} < 1, so its chains of roots stay left of Re s = ln|L(∞)|/T and the analysis holds",
            fmt_num(c.abs())
        ));
    }
    let l0 = l.at_zero();
    let root_at_origin = l0.is_finite() && (1.0 + l0).abs() <= 1e-12;
    // the loop without delay
    let mut p0 = l.undelayed_poly()?;
    if root_at_origin {
        let mut c = p0.coeffs().to_vec();
        if let Some(last) = c.last_mut() {
            *last = 0.0;
        }
        p0 = Poly::trimmed(c);
    }
    let roots0 = if p0.degree() == 0 {
        Vec::new()
    } else {
        crate::poly::roots::snap_to_axis(&p0, p0.roots()?)
    };
    let unstable_at_zero: usize = roots0
        .iter()
        .filter(|r| half_plane(r.value) == HalfPlane::Right)
        .map(|r| r.multiplicity)
        .sum();
    let axis_roots_at_zero: Vec<Root> = roots0
        .iter()
        .filter(|r| half_plane(r.value) == HalfPlane::Axis)
        .copied()
        .collect();
    if root_at_origin {
        notes.push(
            "L(0) = −1: D(0) + N(0) = 0, so s = 0 is a characteristic root for every delay (never asymptotically stable)".into(),
        );
    }
    let mut crossings = crossing_frequencies(l, l0, &mut notes)?;
    // a pair on the axis at T = 0 starts its delays at exactly 0
    for c in &mut crossings {
        if axis_roots_at_zero
            .iter()
            .any(|r| r.value.im > 0.0 && (r.value.im - c.frequency).abs() <= 1e-6 * c.frequency)
        {
            c.phase = 0.0;
        }
    }
    let stable_without_delay = unstable_at_zero == 0 && axis_roots_at_zero.is_empty();
    let mut d = DelayStability {
        unstable_at_zero,
        axis_roots_at_zero,
        stable_without_delay,
        root_at_origin,
        crossings,
        stable_intervals: Vec::new(),
        critical_delay: None,
        stability_switches: false,
        complete: true,
        horizon: f64::INFINITY,
        neutral: l.at_infinity().map(f64::abs),
        hidden_modes: l.hidden.clone(),
        notes,
    };
    intervals(&mut d);
    Ok(d)
}

fn format_root(v: num_complex::Complex64) -> String {
    if v.im == 0.0 {
        fmt_num(v.re)
    } else {
        format!(
            "{} {} {}j",
            fmt_num(v.re),
            if v.im < 0.0 { "−" } else { "+" },
            fmt_num(v.im.abs())
        )
    }
}

/// The crossing frequencies: positive roots of W(ω²), polished on the magnitude gap, with
/// their phases and directions.
fn crossing_frequencies(
    l: &DelayedLoop,
    l0: f64,
    notes: &mut Vec<String>,
) -> Result<Vec<DelayCrossing>> {
    let rho = l.frequency_scale();
    let rho2 = rho * rho;
    let mut w = l.crossing_poly(rho2)?;
    if w.is_zero() {
        return Err(LtiError::invalid(
            "stability in the delay: |D(jω)| = |N(jω)| at every frequency (W ≡ 0): every delay leaves characteristic roots on the imaginary axis",
        ));
    }
    let unit_at_zero = l0.is_finite() && (l0.abs() - 1.0).abs() <= 1e-12;
    if unit_at_zero {
        // |L(0)| = 1: x = 0 is a root of W, exactly
        let mut c = w.coeffs().to_vec();
        if let Some(last) = c.last_mut() {
            *last = 0.0;
        }
        w = Poly::trimmed(c);
        if l0 > 0.0 {
            notes.push(
                "L(0) = +1: |L(jω)| = 1 at ω = 0, where e^(−jωT) = −1/L has no solution: no root crosses there".into(),
            );
        }
    }
    if w.degree() == 0 {
        return Ok(Vec::new());
    }
    let mut out = Vec::new();
    for r in w.roots()? {
        let x = r.value.re * rho2;
        if r.value.im != 0.0 {
            if r.value.re > 0.0 && r.value.im.abs() <= 1e-8 * r.value.norm() {
                notes.push(format!(
                    "|L(jω)| comes within rounding of 1 near ω = {} rad/s without reaching it (a near tangency: a small change of the loop may add crossings there)",
                    fmt_num(x.sqrt())
                ));
            }
            continue;
        }
        if x <= 0.0 {
            continue;
        }
        let frequency = polish(l, x.sqrt());
        let (g, dg) = l.magnitude_gap(frequency);
        if g.abs() > 1e-6 {
            notes.push(format!(
                "a root of |D(jω)|² − |N(jω)|² at ω = {} rad/s does not satisfy |L(jω)| = 1 (ln|D/N| = {}); it was dropped",
                fmt_num(frequency),
                fmt_num(g)
            ));
            continue;
        }
        let direction = if r.multiplicity == 1 {
            if dg > 0.0 {
                CrossingDirection::Destabilizing
            } else if dg < 0.0 {
                CrossingDirection::Stabilizing
            } else {
                CrossingDirection::Tangential
            }
        } else {
            let above = l.magnitude_gap(frequency * (1.0 + 1e-4)).0;
            let below = l.magnitude_gap(frequency * (1.0 - 1e-4)).0;
            if r.multiplicity % 2 == 1 && above > 0.0 && below < 0.0 {
                CrossingDirection::Destabilizing
            } else if r.multiplicity % 2 == 1 && above < 0.0 && below > 0.0 {
                CrossingDirection::Stabilizing
            } else {
                CrossingDirection::Tangential
            }
        };
        if direction == CrossingDirection::Tangential {
            notes.push(format!(
                "at ω = {} rad/s |L(jω)| touches 1 without crossing (W has a {}-fold root): the roots touch the imaginary axis at the delays {} + {}·k s and turn back; not counted",
                fmt_num(frequency),
                r.multiplicity,
                fmt_num(l.phase(frequency) / frequency),
                fmt_num(TAU / frequency)
            ));
        }
        out.push(DelayCrossing {
            frequency,
            phase: l.phase(frequency),
            direction,
        });
    }
    out.sort_by(|a, b| a.frequency.total_cmp(&b.frequency));
    Ok(out)
}

/// Newton on the magnitude gap g(ω) = ln|D(jω)| − ln|N(jω)|, each step kept only when it
/// reduces |g|.
fn polish(l: &DelayedLoop, w0: f64) -> f64 {
    let mut w = w0;
    let (mut g, mut dg) = l.magnitude_gap(w);
    for _ in 0..40 {
        if g == 0.0 || dg == 0.0 || !dg.is_finite() {
            break;
        }
        let step = g / dg;
        let next = w - step;
        if next.is_nan() || next <= 0.0 || !next.is_finite() {
            break;
        }
        let (g2, dg2) = l.magnitude_gap(next);
        if g2.is_nan() || g2.abs() >= g.abs() {
            break;
        }
        w = next;
        g = g2;
        dg = dg2;
        if step.abs() <= 2.0 * f64::EPSILON * w {
            break;
        }
    }
    w
}

/// The merged crossing delays: stable intervals, critical delay, switches.
fn intervals(d: &mut DelayStability) {
    let counted: Vec<DelayCrossing> = d
        .crossings
        .iter()
        .filter(|c| c.direction != CrossingDirection::Tangential)
        .copied()
        .collect();
    let dest: Vec<&DelayCrossing> = counted
        .iter()
        .filter(|c| c.direction == CrossingDirection::Destabilizing)
        .collect();
    let stab: Vec<&DelayCrossing> = counted
        .iter()
        .filter(|c| c.direction == CrossingDirection::Stabilizing)
        .collect();
    if counted.is_empty() {
        if d.stable_without_delay {
            d.notes.push(
                "no crossing frequency: |L(jω)| ≠ 1 for every ω > 0, so the loop is stable for every delay".into(),
            );
        } else {
            d.notes.push(
                "no crossing frequency: the number of unstable roots is the same for every delay"
                    .into(),
            );
        }
    }
    // beyond T*, n0 + 2Σ_dest (T − T₀)/P − 2Σ_stab ((T − T₀)/P + 1) > 0: the count stays positive
    let rate = |cs: &[&DelayCrossing]| cs.iter().map(|c| 1.0 / c.period()).sum::<f64>();
    let offset = |cs: &[&DelayCrossing]| cs.iter().map(|c| c.phase / TAU).sum::<f64>();
    let horizon = if dest.is_empty() {
        // only stabilizing: every one of them counts until the count reaches 0
        let needed = d.unstable_at_zero.div_ceil(2) as f64;
        stab.iter()
            .map(|c| c.delay(0) + c.period() * needed)
            .fold(0.0, f64::max)
    } else {
        let slope = rate(&dest) - rate(&stab);
        if slope > 0.0 {
            let t = (offset(&dest) - offset(&stab) + stab.len() as f64
                - d.unstable_at_zero as f64 / 2.0)
                / slope;
            t.max(dest.iter().map(|c| c.delay(0)).fold(0.0, f64::max))
        } else {
            f64::INFINITY
        }
    };
    let total = |t: f64| -> f64 {
        counted
            .iter()
            .map(|c| (t * c.frequency / TAU).floor() + 1.0)
            .sum()
    };
    let mut limit = horizon;
    if total(limit).is_nan() || total(limit) > MAX_DELAY_EVENTS as f64 {
        // the latest T with at most MAX_DELAY_EVENTS delays below it
        let (mut lo, mut hi) = (0.0_f64, if limit.is_finite() { limit } else { 1.0 });
        while limit.is_infinite() && total(hi) <= MAX_DELAY_EVENTS as f64 {
            hi *= 2.0;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if total(mid) <= MAX_DELAY_EVENTS as f64 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        limit = lo;
        d.complete = false;
        d.notes.push(format!(
            "the crossing delays were merged up to T = {} s only (the limit of {} delays, MAX_DELAY_EVENTS); the stable intervals end there",
            fmt_num(limit),
            MAX_DELAY_EVENTS
        ));
    }
    d.horizon = if dest.is_empty() && d.complete {
        f64::INFINITY
    } else {
        limit
    };
    // the events in (0, limit], with those at T = 0 applied at the start
    let mut count = d.unstable_at_zero as i64;
    let mut events: Vec<(f64, i64)> = Vec::new();
    for c in &counted {
        let mut k = 0usize;
        loop {
            let t = c.delay(k);
            if t > limit {
                break;
            }
            if t == 0.0 {
                if c.direction == CrossingDirection::Destabilizing {
                    count += 2;
                }
            } else {
                events.push((t, c.step()));
            }
            k += 1;
        }
    }
    events.sort_by(|a, b| a.0.total_cmp(&b.0));
    let never = d.root_at_origin;
    let mut start: Option<f64> = (count == 0 && !never).then_some(0.0);
    let mut inconsistent = false;
    let mut i = 0;
    while i < events.len() {
        let t = events[i].0;
        // delays of different crossings that coincide exactly switch together
        while i < events.len() && events[i].0.total_cmp(&t).is_eq() {
            count += events[i].1;
            i += 1;
        }
        if count < 0 {
            inconsistent = true;
            count = 0;
        }
        match (start, count == 0 && !never) {
            (Some(from), false) => {
                d.stable_intervals.push(DelayInterval { from, to: t });
                start = None;
            }
            (None, true) => start = Some(t),
            _ => {}
        }
    }
    if let Some(from) = start {
        // stable after the last merged delay: until the next destabilizing one, if any
        let to = dest
            .iter()
            .map(|c| {
                let k = c.passed(limit.max(from)) as usize;
                let mut t = c.delay(k);
                if t <= from {
                    t = c.delay(k + 1);
                }
                t
            })
            .fold(f64::INFINITY, f64::min);
        d.stable_intervals.push(DelayInterval { from, to });
    }
    if inconsistent {
        d.notes.push(
            "the crossing directions do not add up (the count of unstable roots went below 0): the counts are not reliable for this loop".into(),
        );
    }
    d.critical_delay = if d.stable_without_delay && !never {
        Some(
            d.stable_intervals
                .first()
                .filter(|iv| iv.from == 0.0)
                .map_or(0.0, |iv| iv.to),
        )
    } else {
        None
    };
    d.stability_switches = d.stable_intervals.iter().any(|iv| iv.from > 0.0);
    if d.stability_switches {
        let list: Vec<String> = d
            .stable_intervals
            .iter()
            .map(|iv| format!("({}, {})", fmt_num(iv.from), fmt_num(iv.to)))
            .collect();
        d.notes.push(format!(
            "stability switches: the loop regains stability at larger delays; stable for T in {}",
            list.join(" ∪ ")
        ));
    }
}
