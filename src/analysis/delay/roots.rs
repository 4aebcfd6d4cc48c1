//! The rightmost characteristic roots of D(s) + N(s)·e^(−sT) at one delay: Newton on the
//! exact equation from the roots of a Padé approximant (and from the crossing frequencies and
//! the roots without delay), each root reported with its relative residual, and the count of
//! unstable roots found checked against the count from the crossing delays.

use num_complex::Complex64;
use serde::Serialize;

use super::parts::DelayedLoop;
use super::stability::{analyse, check_delay};
use crate::analysis::factored::Factored;
use crate::error::{LtiError, Result};
use crate::limits::MAX_ORDER;
use crate::lti::delay::pade_coefficients;
use crate::poly::{HalfPlane, Poly, half_plane, same_root};

/// Highest order of the Padé approximant whose roots start the search.
const MAX_PADE: usize = 96;

/// A characteristic root of D(s) + N(s)·e^(−sT) with the quality of its value.
///
/// ```
/// use ltikit::TransferFunction;
/// // 1/s with T = 0: the root −1 (the residual is the rounding of e^(−jπ) in the evaluation)
/// let f = TransferFunction::from_descending(&[1.0], &[1.0, 0.0]).unwrap().factored().unwrap();
/// let r = f.closed_loop_delay_roots(0.0, 1).unwrap().roots[0];
/// assert_eq!(r.value.re, -1.0);
/// assert!(r.relative_residual < 1e-16);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CharacteristicRoot {
    /// The root s.
    pub value: Complex64,
    /// |D(s) + N(s)e^(−sT)| / (|D(s)| + |N(s)e^(−sT)|): 0 at an exact root, about the
    /// rounding of the evaluation at a computed one.
    pub relative_residual: f64,
}

/// The rightmost characteristic roots at one delay (see [`Factored::closed_loop_delay_roots`]).
///
/// ```
/// use ltikit::TransferFunction;
/// // 1/s with T = 2 > π/2: one unstable pair, found
/// let f = TransferFunction::from_descending(&[1.0], &[1.0, 0.0]).unwrap().factored().unwrap();
/// let r = f.closed_loop_delay_roots(2.0, 2).unwrap();
/// assert_eq!((r.unstable_found, r.unstable_expected), (2, 2));
/// assert!(r.agrees && r.note.is_none());
/// assert_eq!(r.roots[0].value, r.roots[1].value.conj());
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DelayRoots {
    /// The delay T (s).
    pub delay: f64,
    /// The rightmost roots found, by decreasing real part then decreasing imaginary part
    /// (conjugate pairs adjacent), at most the number asked for.
    pub roots: Vec<CharacteristicRoot>,
    /// Roots found in the open right half plane (all found, not only those listed).
    pub unstable_found: usize,
    /// Roots in the open right half plane by the crossing delays
    /// ([`super::DelayStability::unstable_roots_at`]).
    pub unstable_expected: usize,
    /// True when the two counts agree; when false the search missed unstable roots (or the
    /// delay sits on a crossing) and `note` says so.
    pub agrees: bool,
    /// Why the counts differ, when they do.
    pub note: Option<String>,
}

impl Factored {
    /// The `count` rightmost roots of the closed loop D(s) + N(s)·e^(−sT) of this loop
    /// L = N/D with the dead time `delay` = T in negative unity feedback. Starting points:
    /// the roots of D·Q + N·P for the [n/n] Padé approximant P/Q of e^(−sT) (n grows from
    /// 8 while unstable roots are missing), the crossing frequencies, the roots at T = 0;
    /// each is refined by Newton on ln(−L(s)e^(−sT)) = 0 (zero where Δ is, evaluated from
    /// the factors), duplicates merged. The number of unstable roots found is compared with
    /// [`super::DelayStability::unstable_roots_at`] (`agrees`).
    ///
    /// Errors: a NaN, infinite or negative delay; `count` = 0; those of
    /// [`Factored::delay_stability`].
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // s + 1 + 2e^(−2s) = 0: s = −1 + W_k(−4e²)/2 (Lambert W); the rightmost pair from
    /// // mpmath's lambertw: 0.108834997795856 ± 1.165617222109161j, unstable (T > 1.209)
    /// let f = TransferFunction::from_descending(&[2.0], &[1.0, 1.0]).unwrap().factored().unwrap();
    /// let r = f.closed_loop_delay_roots(2.0, 4).unwrap();
    /// assert!(r.agrees && r.unstable_found == 2);
    /// let s = r.roots[0].value;
    /// assert!((s.re - 0.108834997795856).abs() < 1e-13 && (s.im - 1.165617222109161).abs() < 1e-13);
    /// assert!(r.roots[0].relative_residual < 1e-14);
    /// ```
    pub fn closed_loop_delay_roots(&self, delay: f64, count: usize) -> Result<DelayRoots> {
        let t = check_delay(delay)?;
        if count == 0 {
            return Err(LtiError::invalid(
                "`count`: 0 roots asked for (ask for at least 1)",
            ));
        }
        let l = DelayedLoop::new(self, "the characteristic roots with a delay")?;
        let stability = analyse(&l)?;
        let expected = stability.unstable_roots_at(t)?;
        let mut base: Vec<Complex64> = stability
            .crossings
            .iter()
            .map(|c| Complex64::new(0.0, c.frequency))
            .collect();
        let p0 = l.undelayed_poly()?;
        if p0.degree() > 0 {
            base.extend(crate::poly::roots::flatten(&p0.roots()?));
        }
        let top = 1.5
            * stability
                .crossings
                .iter()
                .map(|c| c.frequency)
                .fold(l.frequency_scale(), f64::max);
        base.extend(chain_starts(&l, t, top));
        let room = MAX_ORDER.saturating_sub(l.poles.len()).clamp(2, MAX_PADE);
        let mut n = expected.saturating_add(8).min(room);
        loop {
            let mut starts = base.clone();
            starts.extend(pade_starts(&l, t, n)?);
            let origin = stability.root_at_origin.then(|| l.frequency_scale());
            let found = refine_all(&l, t, &starts, origin);
            let unstable = found
                .iter()
                .filter(|r| half_plane(r.value) == HalfPlane::Right)
                .count();
            let enough = unstable >= expected && found.len() >= count;
            if enough || n >= room {
                let agrees = unstable == expected;
                let note = (!agrees).then(|| {
                    format!(
                        "{unstable} roots found in the right half plane, {expected} expected from the crossing delays: {}",
                        if unstable < expected {
                            "the search from Padé starting points missed some (or T is at a crossing delay)"
                        } else {
                            "the crossing count is short (or T is at a crossing delay)"
                        }
                    )
                });
                let roots = found.into_iter().take(count).collect();
                return Ok(DelayRoots {
                    delay: t,
                    roots,
                    unstable_found: unstable,
                    unstable_expected: expected,
                    agrees,
                    note,
                });
            }
            n = (2 * n).min(room);
        }
    }
}

/// The roots of D·Q + N·P in s for the [n/n] Padé approximant, computed in u = sT:
/// Π(u − pT)·Q(u) + k·T^(deg D − deg N)·Π(u − zT)·P(u) (at T = 0: D + N).
fn pade_starts(l: &DelayedLoop, t: f64, n: usize) -> Result<Vec<Complex64>> {
    let poly = if t == 0.0 {
        l.undelayed_poly()?
    } else {
        let scaled = |r: &[Complex64]| -> Vec<Complex64> { r.iter().map(|&v| v * t).collect() };
        let d = Poly::from_roots(&scaled(&l.poles))?;
        let shift = l.poles.len() as f64 - l.zeros.len() as f64;
        let k = l.gain.signum() * (l.gain.abs().ln() + shift * t.ln()).exp();
        if !k.is_finite() || k == 0.0 {
            return Ok(Vec::new());
        }
        let nk = Poly::from_roots(&scaled(&l.zeros))?.scale(k);
        let (p, q) = pade_coefficients(1.0, n);
        let p = Poly::trimmed(p);
        let q = Poly::trimmed(q);
        &(&d * &q) + &(&nk * &p)
    };
    if poly.degree() == 0 || poly.coeffs().iter().any(|c| !c.is_finite()) {
        return Ok(Vec::new());
    }
    let Ok(roots) = poly.roots() else {
        return Ok(Vec::new());
    };
    let scale = if t == 0.0 { 1.0 } else { 1.0 / t };
    Ok(crate::poly::roots::flatten(&roots)
        .into_iter()
        .map(|u| u * scale)
        .collect())
}

/// Starting points for long delays: along the axis the roots of 1 + L(s)e^(−sT) lie near
/// s = ln|L(jω)|/T + jω where ωT − arg(−L(jω)) is a multiple of 2π (|e^(−sT)| = 1/|L|, and
/// the phase condition); one per multiple up to the frequency `top`.
fn chain_starts(l: &DelayedLoop, t: f64, top: f64) -> Vec<Complex64> {
    if t == 0.0 || top.is_nan() || top <= 0.0 || !top.is_finite() {
        return Vec::new();
    }
    let tau = std::f64::consts::TAU;
    let steps = (top * t / (std::f64::consts::PI / 4.0))
        .ceil()
        .clamp(1.0, MAX_CHAIN_STEPS);
    let h = top / steps;
    let wrapped = |w: f64| (w * t - l.phase(w)).rem_euclid(tau);
    let mut out = Vec::new();
    let mut prev = wrapped(0.5 * h);
    for i in 1..steps as usize {
        let w = (i as f64 + 0.5) * h;
        let r = wrapped(w);
        if r < prev - std::f64::consts::PI {
            let a = w - h + h * (tau - prev) / (r + tau - prev);
            let sigma = l.log_loop(Complex64::new(0.0, a)).re / t;
            if sigma.is_finite() {
                out.push(Complex64::new(sigma, a));
            }
        }
        prev = r;
    }
    out
}

/// Most grid steps of [`chain_starts`].
const MAX_CHAIN_STEPS: f64 = 200_000.0;

/// Newton from every starting point in the closed upper half plane; converged roots merged
/// (within 1e-8 relative), sorted, conjugates added. With a root at the origin (L(0) = −1;
/// `origin` holds the loop's frequency scale) a root within 1e-13 of the scale is that root,
/// exactly 0 (elsewhere tiny roots are genuine: a long delay has roots about 2π/T apart).
fn refine_all(
    l: &DelayedLoop,
    t: f64,
    starts: &[Complex64],
    origin: Option<f64>,
) -> Vec<CharacteristicRoot> {
    let mut found: Vec<CharacteristicRoot> = Vec::new();
    for &s0 in starts.iter().filter(|s| s.im >= 0.0) {
        let Some(mut r) = newton(l, t, s0) else {
            continue;
        };
        if r.value.im < 0.0 {
            r.value = r.value.conj();
        }
        if r.value.im != 0.0 && r.value.im.abs() <= 1e-10 * r.value.norm() {
            // a real root reached from off the axis: refined along the axis
            match newton(l, t, Complex64::new(r.value.re, 0.0)) {
                Some(q) if q.value.im == 0.0 => r = q,
                _ => {}
            }
        }
        if origin.is_some_and(|scale| r.value.norm() <= 1e-13 * scale) {
            // the root at the origin (L(0) = −1), exactly
            r = CharacteristicRoot {
                value: Complex64::new(0.0, 0.0),
                relative_residual: residual(l, t, Complex64::new(0.0, 0.0)),
            };
        }
        found.push(r);
    }
    // merge duplicates: sorted by imaginary part, each compared with its neighbours
    found.sort_by(|a, b| a.value.im.total_cmp(&b.value.im));
    let mut upper: Vec<CharacteristicRoot> = Vec::new();
    for r in found {
        let window = 1e-8 * r.value.norm();
        let twin = upper
            .iter_mut()
            .rev()
            .take_while(|q| r.value.im - q.value.im <= window)
            .find(|q| same_root(q.value, r.value));
        match twin {
            Some(q) => {
                if r.relative_residual < q.relative_residual {
                    *q = r;
                }
            }
            None => upper.push(r),
        }
    }
    upper.sort_by(|a, b| {
        b.value
            .re
            .total_cmp(&a.value.re)
            .then(b.value.im.total_cmp(&a.value.im))
    });
    let mut out = Vec::with_capacity(2 * upper.len());
    for r in upper {
        out.push(r);
        if r.value.im > 0.0 {
            out.push(CharacteristicRoot {
                value: r.value.conj(),
                relative_residual: r.relative_residual,
            });
        }
    }
    out
}

/// ln G(s) for G = L(s)·e^(−sT), and the relative residual |1 + G|/(1 + |G|).
fn residual(l: &DelayedLoop, t: f64, s: Complex64) -> f64 {
    let g = (l.log_loop(s) - s * t).exp();
    let r = (Complex64::new(1.0, 0.0) + g).norm() / (1.0 + g.norm());
    if r.is_finite() { r } else { f64::INFINITY }
}

/// Newton on φ(s) = Ln(−L(s)e^(−sT)) (principal branch), φ′ = L′/L − T, from `s0`; the
/// best point by residual, when it is a root (residual ≤ 1e-10).
fn newton(l: &DelayedLoop, t: f64, s0: Complex64) -> Option<CharacteristicRoot> {
    let pi = std::f64::consts::PI;
    let mut s = s0;
    if l.poles.iter().chain(&l.zeros).any(|&p| p == s) {
        s += Complex64::new(1e-9 * s.norm().max(1e-300), 1e-9 * s.norm().max(1e-300));
    }
    let mut best: Option<CharacteristicRoot> = None;
    let mut small_steps = 0;
    for _ in 0..100 {
        let lg = l.log_loop(s) - s * t;
        if !(lg.re.is_finite() && lg.im.is_finite()) {
            break;
        }
        let phi = Complex64::new(lg.re, (lg.im + 2.0 * pi).rem_euclid(2.0 * pi) - pi);
        let dphi = l.log_slope(s) - t;
        let step = phi / dphi;
        if !(step.re.is_finite() && step.im.is_finite()) {
            break;
        }
        let r = residual(l, t, s);
        if best.is_none_or(|b| r < b.relative_residual) {
            best = Some(CharacteristicRoot {
                value: s,
                relative_residual: r,
            });
        }
        s -= step;
        if step.norm() <= 4.0 * f64::EPSILON * s.norm() {
            small_steps += 1;
            if small_steps >= 2 {
                break;
            }
        }
    }
    let r = residual(l, t, s);
    if s.re.is_finite() && s.im.is_finite() && best.is_none_or(|b| r < b.relative_residual) {
        best = Some(CharacteristicRoot {
            value: s,
            relative_residual: r,
        });
    }
    best.filter(|b| b.relative_residual <= 1e-10)
}
