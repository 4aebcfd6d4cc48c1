//! Frequency grids and time spans chosen automatically from the poles and zeros.
//!
//! - [`auto_frequency_grid`]: log-spaced from two decades below the smallest non-zero corner
//!   frequency to two decades above the largest (rounded out to whole decades; 0.01…100
//!   rad/s without corners), plus extra points around lightly damped pole and zero pairs and
//!   at every resonant peak, so that a ζ = 0.01 peak is drawn at its true height.
//! - [`auto_time_span`]: long enough for the slowest stable mode to settle (2 %) with a
//!   margin, five periods of undamped modes, and for unstable plants a window in which the
//!   fastest-growing mode grows by a factor 1000 (python-control #384 drew a 3e15 s window).

use serde::Serialize;

use super::factored::Factored;
use crate::error::{LtiError, Result};
use crate::fmt::fmt_root;
use crate::poly::{HalfPlane, half_plane};

/// How far the time axis of a response plot should reach, and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TimeSpan {
    /// End time (s), a "nice" number (1, 2 or 5 × 10^k).
    pub t_end: f64,
    /// What set it, in words (e.g. "2 % settling of the slowest mode s = -0.5 …").
    pub reason: String,
}

pub use crate::limits::MAX_POINTS;

/// Checks 2 ≤ `points` ≤ [`MAX_POINTS`] before anything is allocated.
///
/// ```
/// use ltikit::analysis::grid::check_points;
/// assert!(check_points(2).is_ok() && check_points(1).is_err());
/// let e = check_points(usize::MAX).unwrap_err().to_string();
/// assert!(e.starts_with("`points`: 18446744073709551615 exceeds the limit"), "{e}");
/// ```
pub fn check_points(points: usize) -> Result<()> {
    if points < 2 {
        return Err(LtiError::invalid(format!(
            "`points`: at least 2 are needed, got {points}"
        )));
    }
    crate::limits::POINTS.check_usize("`points`", points)?;
    Ok(())
}

/// A frequency grid for Bode and Nyquist plots: `points` log-spaced frequencies over the
/// corner-frequency range (two decades beyond the extreme corners, whole decades), plus
/// extra points near lightly damped pairs (ζ < 0.5: spacing ζωn/4 within ±4ζωn, then
/// coarser; undamped pairs are approached to 1e-6 relative but never hit) and every local
/// maximum of |G(jω)| exactly. Sorted and unique; its length is `points` plus the extras.
///
/// Errors: `points < 2`; root-finding failures.
///
/// ```
/// use ltikit::TransferFunction;
/// use ltikit::analysis::auto_frequency_grid;
/// // 1/(s² + 0.02 s + 1): ζ = 0.01, peak 1/(2ζ√(1−ζ²)) at ωr = √(1 − 2ζ²).
/// let g = TransferFunction::from_descending(&[1.0], &[1.0, 0.02, 1.0]).unwrap();
/// let w = auto_frequency_grid(&g.factored().unwrap(), 200).unwrap();
/// assert_eq!((w[0], *w.last().unwrap()), (0.01, 100.0));
/// let r = g.freq_response(&w).unwrap();
/// let peak = r.magnitude.iter().copied().fold(0.0, f64::max);
/// let mr = 1.0 / (2.0 * 0.01 * (1.0f64 - 1e-4).sqrt());
/// assert!((20.0 * (peak / mr).log10()).abs() < 1e-9);
/// ```
pub fn auto_frequency_grid(f: &Factored, points: usize) -> Result<Vec<f64>> {
    check_points(points)?;
    if let Some(dt) = f.domain().dt() {
        return Ok(discrete_frequency_grid(f, dt, points));
    }
    let form = f.bode();
    let (a, b) = form.decade_range();
    let (lo, hi) = (10f64.powf(a), 10f64.powf(b));
    let mut w: Vec<f64> = (0..points)
        .map(|i| 10f64.powf(a + (b - a) * i as f64 / (points - 1) as f64))
        .collect();
    // exact ends (powf of an integer exponent is exact for these, but be explicit)
    w[0] = lo;
    w[points - 1] = hi;
    for (wn, z) in form.light_pairs(0.5) {
        if z > 0.0 {
            for k in -16..=16 {
                w.push(wn * (1.0 + 0.25 * z * k as f64));
            }
            for k in [
                5.0, 6.0, 7.0, 8.0, 10.0, 12.0, 14.0, 16.0, 20.0, 24.0, 32.0, 40.0, 48.0, 64.0,
            ] {
                w.push(wn * (1.0 + k * z));
                w.push(wn * (1.0 - k * z));
            }
        } else {
            for j in 1..=6 {
                let d = 10f64.powi(-j);
                w.push(wn * (1.0 + d));
                w.push(wn * (1.0 - d));
                w.push(wn * (1.0 + 3.0 * d));
                w.push(wn * (1.0 - 3.0 * d));
            }
        }
    }
    w.extend(super::margins::local_maxima(f)?);
    w.retain(|&x| x.is_finite() && x >= lo && x <= hi);
    w.sort_by(f64::total_cmp);
    w.dedup();
    Ok(w)
}

/// A logarithmic grid for a discrete-time plant, ending exactly at the Nyquist frequency
/// π/T and starting two decades below its slowest mode (equivalent s = ln(z)/T) or three
/// below π/T; dense about the angle of every pole or zero near the unit circle.
fn discrete_frequency_grid(f: &Factored, dt: f64, points: usize) -> Vec<f64> {
    let hi = std::f64::consts::PI / dt;
    let slowest = f
        .reduced_poles()
        .iter()
        .chain(f.reduced_zeros())
        .filter_map(|r| super::discrete::equivalent_s(r.value, dt))
        .map(|s| s.norm())
        .filter(|m| *m > 0.0)
        .fold(f64::INFINITY, f64::min);
    let lo = (hi * 1e-3).min(slowest * 1e-2).max(hi * 1e-6);
    let (a, b) = (lo.log10(), hi.log10());
    let mut w: Vec<f64> = (0..points)
        .map(|i| 10f64.powf(a + (b - a) * i as f64 / (points - 1) as f64))
        .collect();
    w[0] = lo;
    w[points - 1] = hi;
    for r in f.reduced_poles().iter().chain(f.reduced_zeros()) {
        let d = (r.value.norm() - 1.0).abs();
        let angle = r.value.im.atan2(r.value.re).abs();
        if d < 0.2 && angle > 0.0 {
            for k in -24i32..=24 {
                let x = (angle + d.max(1e-9) * 0.25 * f64::from(k)) / dt;
                w.push(x);
            }
        }
    }
    w.retain(|&x| x.is_finite() && x >= lo && x <= hi);
    w.sort_by(f64::total_cmp);
    w.dedup();
    w
}

/// The end time for plotting a time response (step, impulse, initial condition) of `tf`,
/// from its reduced poles:
/// - stable modes: 1.5 × the 2 % settling time of the slowest, (ln 50 + 2(m−1))/|σ| for an
///   m-fold pole with real part σ;
/// - undamped modes ±jβ: five periods 5·2π/β of the slowest;
/// - unstable modes: the time in which the fastest-growing one grows by ×1000, ln(1000)/σ
///   (this alone sets the window: divergence dominates the picture);
/// - integrators: the window is set by the other modes; with none, by the zeros (5/|z| of
///   the slowest), or 10 s for a pure integrator chain or a static gain.
///
/// The result is rounded up to 1, 2 or 5 × 10^k.
///
/// Errors: root-finding failures; a span that overflows f64.
///
/// ```
/// use ltikit::TransferFunction;
/// use ltikit::analysis::auto_time_span;
/// // 1/(s+1): settling ln 50 ≈ 3.91 s, × 1.5 ≈ 5.87, shown up to 10 s.
/// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap();
/// assert_eq!(auto_time_span(&g.factored().unwrap()).unwrap().t_end, 10.0);
/// // an unstable pole at s = 2: e^(2t) = 1000 at t = 3.45 s, shown up to 5 s.
/// let g = TransferFunction::from_descending(&[1.0], &[1.0, -2.0]).unwrap();
/// assert_eq!(auto_time_span(&g.factored().unwrap()).unwrap().t_end, 5.0);
/// ```
pub fn auto_time_span(f: &Factored) -> Result<TimeSpan> {
    if let Some(dt) = f.domain().dt() {
        return discrete_time_span(f, dt);
    }
    let pz = f.pole_zero();
    let mut settle: Option<(f64, String)> = None;
    let mut period: Option<(f64, String)> = None;
    let mut growth: Option<(f64, String)> = None;
    for r in &pz.reduced_poles {
        let p = r.value;
        if p.im < 0.0 || (p.re == 0.0 && p.im == 0.0) {
            continue;
        }
        let m = r.multiplicity as f64;
        let name = fmt_root(p, 4);
        match half_plane(p) {
            HalfPlane::Left => {
                let t = (50f64.ln() + 2.0 * (m - 1.0)) / p.re.abs();
                if settle.as_ref().is_none_or(|(s, _)| t > *s) {
                    settle = Some((t, name));
                }
            }
            HalfPlane::Axis => {
                let t = 5.0 * std::f64::consts::TAU / p.im.abs();
                if period.as_ref().is_none_or(|(s, _)| t > *s) {
                    period = Some((t, name));
                }
            }
            HalfPlane::Right => {
                let t = 1000f64.ln() / p.re;
                if growth.as_ref().is_none_or(|(s, _)| t < *s) {
                    growth = Some((t, name));
                }
            }
        }
    }
    let (raw, reason) = if let Some((t, name)) = growth {
        (
            t,
            format!(
                "unstable pole at s = {name}: the mode grows by ×1000 in {} s",
                crate::fmt::fmt_sig(t, 3)
            ),
        )
    } else {
        let s = settle.map(|(t, name)| {
            (
                1.5 * t,
                format!(
                    "2 % settling of the slowest mode s = {name} ({} s) × 1.5",
                    crate::fmt::fmt_sig(t, 3)
                ),
            )
        });
        let p = period.map(|(t, name)| {
            (
                t,
                format!(
                    "five periods of the undamped mode s = {name} ({} s)",
                    crate::fmt::fmt_sig(t, 3)
                ),
            )
        });
        match (s, p) {
            (Some(a), Some(b)) => {
                if a.0 >= b.0 {
                    a
                } else {
                    b
                }
            }
            (Some(a), None) => a,
            (None, Some(b)) => b,
            (None, None) => {
                let slowest_zero = pz
                    .reduced_zeros
                    .iter()
                    .map(|z| z.value.norm())
                    .filter(|&x| x > 0.0)
                    .reduce(f64::min);
                match slowest_zero {
                    Some(z) => (
                        5.0 / z,
                        format!(
                            "no finite mode: five time constants of the slowest zero (|z| = {})",
                            crate::fmt::fmt_sig(z, 3)
                        ),
                    ),
                    None => (
                        10.0,
                        "no time scale in G (static gain or integrators only): default 10 s"
                            .to_string(),
                    ),
                }
            }
        }
    };
    let (raw, reason) = if f.delay() > 0.0 {
        (
            raw + f.delay(),
            format!(
                "{reason}, after the dead time {} s",
                crate::fmt::fmt_num(f.delay())
            ),
        )
    } else {
        (raw, reason)
    };
    let t_end = nice_ceil(raw);
    if !(t_end.is_finite() && t_end > 0.0) {
        return Err(LtiError::Undefined {
            what: "time span".into(),
            reason: format!("{reason}: {raw:e} s is outside the floating-point range"),
        });
    }
    Ok(TimeSpan { t_end, reason })
}

/// The span of a discrete-time plant: its modes read through the equivalent s = ln(z)/T
/// (settling ln 50/|σ|, five periods on the circle, ×1000 growth outside), at least 20
/// samples and the order plus 10 (a deadbeat or FIR plant has no mode).
fn discrete_time_span(f: &Factored, dt: f64) -> Result<TimeSpan> {
    use super::discrete::{circle_side, equivalent_s};
    let mut raw: Option<(f64, String)> = None;
    let mut growth: Option<(f64, String)> = None;
    for r in f.reduced_poles() {
        let Some(s) = equivalent_s(r.value, dt) else {
            continue;
        };
        let m = r.multiplicity as f64;
        let name = fmt_root(r.value, 4);
        let (t, why) = match circle_side(r.value) {
            HalfPlane::Left => (
                1.5 * (50f64.ln() + 2.0 * (m - 1.0)) / s.re.abs(),
                format!("2 % settling of the slowest mode z = {name} × 1.5"),
            ),
            HalfPlane::Axis if s.im.abs() > 0.0 => (
                5.0 * std::f64::consts::TAU / s.im.abs(),
                format!("five periods of the mode z = {name} on the unit circle"),
            ),
            HalfPlane::Axis => continue,
            HalfPlane::Right => {
                let t = 1000f64.ln() / s.re;
                if growth.as_ref().is_none_or(|(g, _)| t < *g) {
                    growth = Some((t, format!("unstable pole at z = {name}: ×1000")));
                }
                continue;
            }
        };
        if raw.as_ref().is_none_or(|(x, _)| t > *x) {
            raw = Some((t, why));
        }
    }
    let floor = (20.0f64).max(f.order() as f64 + 10.0) * dt;
    let (t, reason) = growth
        .or(raw)
        .unwrap_or((floor, "no decaying mode: 20 samples".into()));
    let t_end = if t < floor { floor } else { nice_ceil(t) };
    if !(t_end.is_finite() && t_end > 0.0) {
        return Err(LtiError::Undefined {
            what: "time span".into(),
            reason: format!("{reason}: {t:e} s is outside the floating-point range"),
        });
    }
    Ok(TimeSpan { t_end, reason })
}

/// `points` uniformly spaced times from 0 to [`auto_time_span`]`.t_end`.
///
/// Errors: `points < 2`, and those of [`auto_time_span`].
///
/// ```
/// use ltikit::TransferFunction;
/// use ltikit::analysis::auto_time_grid;
/// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap();
/// let t = auto_time_grid(&g.factored().unwrap(), 11).unwrap();
/// assert_eq!((t[0], t[1], t[10]), (0.0, 1.0, 10.0));
/// ```
pub fn auto_time_grid(f: &Factored, points: usize) -> Result<Vec<f64>> {
    check_points(points)?;
    let t_end = auto_time_span(f)?.t_end;
    let n = (points - 1) as f64;
    Ok((0..points).map(|i| t_end * (i as f64 / n)).collect())
}

/// Smallest number of the form 1, 2 or 5 × 10^k that is ≥ x (x > 0).
fn nice_ceil(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return x;
    }
    let k = x.log10().floor();
    let base = 10f64.powf(k);
    for m in [1.0, 2.0, 5.0, 10.0] {
        let v = m * base;
        if v >= x * (1.0 - 1e-12) {
            return v;
        }
    }
    10.0 * base
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lti::TransferFunction;

    #[test]
    fn nice_numbers() {
        assert!((nice_ceil(5.87) - 10.0).abs() < 1e-12);
        assert!((nice_ceil(3.45) - 5.0).abs() < 1e-12);
        assert!((nice_ceil(0.0123) - 0.02).abs() < 1e-15);
        assert!((nice_ceil(2.0) - 2.0).abs() < 1e-15);
        assert!((nice_ceil(101.0) - 200.0).abs() < 1e-12);
    }

    #[test]
    fn too_few_points() {
        let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0])
            .unwrap()
            .factored()
            .unwrap();
        assert!(auto_frequency_grid(&g, 1).is_err());
        assert!(auto_time_grid(&g, 0).is_err());
    }
}
