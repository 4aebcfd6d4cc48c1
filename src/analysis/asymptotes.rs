//! Bode straight-line asymptotes of magnitude and phase, from poles, zeros and gain.
//!
//! Write G(s) = k · Π(s − zᵢ) / Π(s − pⱼ) (k = b_m/a_n, roots as given, with multiplicity).
//!
//! **Magnitude.** Each factor (s − r) is replaced by its low-frequency value |r| below its
//! corner ω = |r| and by ω above it (a conjugate pair gives |r|² and ω², the textbook
//! second-order asymptote); roots at s = 0 give ω throughout. So
//! `|G|_asym(ω) = |k| · Π max(ω, |zᵢ|) / Π max(ω, |pⱼ|)`, a polyline in (log ω, dB) with
//! slope changes of ±20 dB/decade per root at its corner. It is exact far from every corner.
//!
//! **Phase.** It starts at the phase of the low-frequency asymptote, 90°·(zeros − poles at the
//! origin), minus 180° when the low-frequency gain k·Π(−zᵢ)/Π(−pⱼ) over the non-zero roots is
//! negative: the branch convention of [`crate::analysis::FrequencyResponse`] (DESIGN §1.3).
//! Each non-zero root then adds its total phase change Δ: +90° for a left-half-plane zero,
//! −90° for a right-half-plane zero, −90° for a left-half-plane pole, +90° for a
//! right-half-plane pole (roots on the imaginary axis count as left-half-plane: the limit of
//! vanishing damping). The change is spread linearly in log ω over
//! - a real root: one decade either side of the corner, [ω_c/10, 10 ω_c] (the textbook rule);
//! - a complex root of damping ζ = |Re r|/|r|: [ω_n·10^(−ζ), ω_n·10^ζ], which is the decade rule
//!   at ζ = 1 (a double real root) and tends to a step at ω_n as ζ → 0 (exactly a step for a
//!   root on the imaginary axis).

use serde::Serialize;

use crate::analysis::factored::Factored;
use crate::analysis::stability::{HalfPlane, half_plane};
use crate::error::{LtiError, Result, check_finite};
use crate::lti::TransferFunction;
use crate::poly::Root;

/// A corner (break) frequency of the asymptotes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CornerFrequency {
    /// Corner frequency |r| (rad/s).
    pub w: f64,
    /// Change of the magnitude slope there, in units of 20 dB/decade (+m for an m-fold zero,
    /// −m for an m-fold pole; a conjugate pair is listed once per root).
    pub slope_change: i32,
    /// Damping ratio |Re r|/|r| of the root (1 for a real root).
    pub zeta: f64,
}

/// Straight-line Bode asymptotes over a frequency range.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BodeAsymptotes {
    /// Vertices (ω rad/s, dB) of the magnitude asymptote, by increasing ω; straight between
    /// vertices on a log-ω axis.
    pub magnitude_db: Vec<(f64, f64)>,
    /// Vertices (ω rad/s, degrees) of the phase asymptote; a step appears as two vertices at
    /// the same ω.
    pub phase_deg: Vec<(f64, f64)>,
    /// Corner frequencies of the non-zero roots, by increasing ω (all of them, also those
    /// outside the range).
    pub corners: Vec<CornerFrequency>,
}

/// One non-zero root as seen by the asymptotes.
#[derive(Debug, Clone, Copy)]
struct Factor {
    /// |r|.
    w: f64,
    /// +1 zero, −1 pole, times multiplicity.
    order: i32,
    /// log10 of the start and end of the phase transition.
    a: f64,
    b: f64,
    /// Total phase change (degrees).
    delta: f64,
    /// Damping ratio of the root.
    zeta: f64,
}

/// The straight-line asymptotes of G = gain · Π(s − z)/Π(s − p) over [w_min, w_max].
///
/// Errors: a zero gain (the magnitude is −∞ dB), non-finite values, w_min ≤ 0 or
/// w_max ≤ w_min.
///
/// ```
/// use ltikit::analysis::asymptotes::bode_asymptotes;
/// use ltikit::TransferFunction;
/// // 10 / (s + 10): 0 dB up to 10 rad/s, then −20 dB/decade; phase 0 → −90° over 1…100 rad/s.
/// let g = TransferFunction::from_descending(&[10.0], &[1.0, 10.0]).unwrap();
/// let a = bode_asymptotes(&g.zeros().unwrap(), &g.poles().unwrap(), g.gain(), 0.1, 1000.0).unwrap();
/// assert_eq!(a.magnitude_db.len(), 3);
/// assert!((a.magnitude_db[1].0 - 10.0).abs() < 1e-12 && a.magnitude_db[1].1.abs() < 1e-12);
/// assert!((a.magnitude_db[2].1 + 40.0).abs() < 1e-12); // 1000 rad/s: two decades past the corner
/// assert!((a.phase_deg.last().unwrap().1 + 90.0).abs() < 1e-12);
/// ```
pub fn bode_asymptotes(
    zeros: &[Root],
    poles: &[Root],
    gain: f64,
    w_min: f64,
    w_max: f64,
) -> Result<BodeAsymptotes> {
    check_finite(|| "the gain".into(), gain)?;
    check_finite(|| "the lowest frequency".into(), w_min)?;
    check_finite(|| "the highest frequency".into(), w_max)?;
    if gain == 0.0 {
        return Err(LtiError::Undefined {
            what: "Bode asymptotes".into(),
            reason: "the transfer function is zero (magnitude −∞ dB)".into(),
        });
    }
    if w_min <= 0.0 || w_max <= w_min {
        return Err(LtiError::invalid(format!(
            "the frequency range [{w_min}, {w_max}] must satisfy 0 < w_min < w_max"
        )));
    }
    let (factors, origin, negative) = asymptote_factors(zeros, poles, gain < 0.0)?;
    let phase0 = 90.0 * f64::from(origin) - if negative { 180.0 } else { 0.0 };
    let (lo, hi) = (w_min.log10(), w_max.log10());
    let mut corners: Vec<CornerFrequency> = factors
        .iter()
        .map(|f| CornerFrequency {
            w: f.w,
            slope_change: f.order,
            zeta: f.zeta,
        })
        .collect();
    corners.sort_by(|a, b| a.w.total_cmp(&b.w));
    Ok(BodeAsymptotes {
        magnitude_db: magnitude_polyline(&factors, gain, origin, lo, hi),
        phase_deg: phase_polyline(&factors, phase0, lo, hi),
        corners,
    })
}

/// The straight-line factors of the non-zero roots, the order at s = 0 (zeros − poles) and
/// whether the low-frequency gain is negative.
fn asymptote_factors(
    zeros: &[Root],
    poles: &[Root],
    mut negative: bool,
) -> Result<(Vec<Factor>, i32, bool)> {
    let mut origin = 0i32;
    let mut factors = Vec::new();
    for (roots, sign) in [(zeros, 1i32), (poles, -1i32)] {
        for r in roots {
            let v = r.value;
            check_finite(|| "a root".into(), v.re)?;
            check_finite(|| "a root".into(), v.im)?;
            let m = r.multiplicity as i32;
            let w = v.norm();
            if w == 0.0 {
                origin += sign * m;
                continue;
            }
            // Real roots contribute −r (sign flips when r > 0); pairs contribute |r|² > 0.
            if v.im == 0.0 && v.re > 0.0 && m % 2 == 1 {
                negative = !negative;
            }
            let hp = half_plane(v);
            let zeta = if v.im == 0.0 { 1.0 } else { (v.re / w).abs() };
            let (a, b) = if hp == HalfPlane::Axis {
                (w.log10(), w.log10())
            } else if v.im == 0.0 {
                (w.log10() - 1.0, w.log10() + 1.0)
            } else {
                (w.log10() - zeta, w.log10() + zeta)
            };
            let side = if hp == HalfPlane::Right { -1.0 } else { 1.0 };
            factors.push(Factor {
                w,
                order: sign * m,
                a,
                b,
                delta: 90.0 * f64::from(sign * m) * side,
                zeta,
            });
        }
    }
    Ok((factors, origin, negative))
}

/// Sorted, unique log-frequencies: the ends and the given breakpoints inside (lo, hi).
fn breakpoints(xs: impl Iterator<Item = f64>, lo: f64, hi: f64) -> Vec<f64> {
    let mut out: Vec<f64> = xs.filter(|&x| x > lo && x < hi).collect();
    out.push(lo);
    out.push(hi);
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

/// The magnitude asymptote (ω, dB) at the ends and the corners inside [10^lo, 10^hi].
fn magnitude_polyline(
    factors: &[Factor],
    gain: f64,
    origin: i32,
    lo: f64,
    hi: f64,
) -> Vec<(f64, f64)> {
    let mag_db = |w: f64| {
        let lw = w.log10();
        let mut l = gain.abs().log10() + f64::from(origin) * lw;
        for f in factors {
            l += f64::from(f.order) * lw.max(f.w.log10());
        }
        20.0 * l
    };
    breakpoints(factors.iter().map(|f| f.w.log10()), lo, hi)
        .iter()
        .map(|&x| {
            let w = 10f64.powf(x);
            (w, mag_db(w))
        })
        .collect()
}

/// The phase asymptote (ω, degrees): ramps over each factor's decade (or ζ-wide band), steps
/// at imaginary-axis roots (both limits listed).
fn phase_polyline(factors: &[Factor], phase0: f64, lo: f64, hi: f64) -> Vec<(f64, f64)> {
    // Phase at log-frequency x; `right` chooses the right-hand limit at a step.
    let phase = |x: f64, right: bool| {
        let mut p = phase0;
        for f in factors {
            let frac = if f.b > f.a {
                ((x - f.a) / (f.b - f.a)).clamp(0.0, 1.0)
            } else if x > f.a || (right && x >= f.a) {
                1.0
            } else {
                0.0
            };
            p += f.delta * frac;
        }
        p
    };
    let ph_x = breakpoints(factors.iter().flat_map(|f| [f.a, f.b]), lo, hi);
    let mut phase_deg = Vec::with_capacity(2 * ph_x.len());
    for (i, &x) in ph_x.iter().enumerate() {
        let w = 10f64.powf(x);
        let (l, r) = (phase(x, false), phase(x, true));
        if i > 0 {
            phase_deg.push((w, l));
        }
        if i == 0 || (r - l).abs() > 1e-12 {
            phase_deg.push((w, r));
        }
    }
    phase_deg
}

impl TransferFunction {
    /// Straight-line Bode asymptotes over [w_min, w_max] (see [`bode_asymptotes`]), from the
    /// reduced poles and zeros and the gain b_m/a_n ([`Factored::bode_asymptotes`]).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // 1/s³: −60 dB/decade through 0 dB at 1 rad/s, phase −270° everywhere.
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 0.0, 0.0, 0.0]).unwrap();
    /// let a = g.bode_asymptotes(0.1, 10.0).unwrap();
    /// assert!((a.magnitude_db[0].1 - 60.0).abs() < 1e-9);
    /// assert!(a.phase_deg.iter().all(|p| (p.1 + 270.0).abs() < 1e-12));
    /// ```
    pub fn bode_asymptotes(&self, w_min: f64, w_max: f64) -> Result<BodeAsymptotes> {
        self.factored()?.bode_asymptotes(w_min, w_max)
    }
}

impl Factored {
    /// Straight-line Bode asymptotes of G in lowest terms over [w_min, w_max]
    /// ([`bode_asymptotes`]).
    pub fn bode_asymptotes(&self, w_min: f64, w_max: f64) -> Result<BodeAsymptotes> {
        self.domain()
            .require_continuous("straight-line Bode asymptotes")?;
        bode_asymptotes(
            self.reduced_zeros(),
            self.reduced_poles(),
            self.gain(),
            w_min,
            w_max,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tf(num: &[f64], den: &[f64]) -> TransferFunction {
        TransferFunction::from_descending(num, den).unwrap()
    }

    /// Piecewise-linear interpolation of a polyline in log ω (left limit at steps).
    fn at(poly: &[(f64, f64)], w: f64) -> f64 {
        let x = w.log10();
        for s in poly.windows(2) {
            let (a, b) = (s[0].0.log10(), s[1].0.log10());
            if x >= a && x <= b && b > a {
                return s[0].1 + (s[1].1 - s[0].1) * (x - a) / (b - a);
            }
        }
        poly.last().unwrap().1
    }

    #[test]
    fn first_order_lag() {
        // 1/(s+1): 0 dB, −20 dB/dec after 1 rad/s; phase 0 below 0.1, −45° at 1, −90° above 10.
        let a = tf(&[1.0], &[1.0, 1.0])
            .bode_asymptotes(0.01, 100.0)
            .unwrap();
        assert!(at(&a.magnitude_db, 0.5).abs() < 1e-12);
        assert!((at(&a.magnitude_db, 100.0) + 40.0).abs() < 1e-12);
        assert!(at(&a.phase_deg, 0.05).abs() < 1e-12);
        assert!((at(&a.phase_deg, 1.0) + 45.0).abs() < 1e-12);
        assert!((at(&a.phase_deg, 50.0) + 90.0).abs() < 1e-12);
        assert_eq!(a.corners.len(), 1);
        assert_eq!(a.corners[0].slope_change, -1);
    }

    #[test]
    fn branch_conventions() {
        // Integrator −90°, 1/s³ −270°, negative gain −180°, RHP zero (1 − s)/(s + 1) from 0 to −180°.
        let a = tf(&[1.0], &[1.0, 0.0]).bode_asymptotes(0.1, 10.0).unwrap();
        assert!(a.phase_deg.iter().all(|p| (p.1 + 90.0).abs() < 1e-12));
        let a = tf(&[-2.0], &[1.0, 1.0]).bode_asymptotes(1e-3, 1e3).unwrap();
        assert!((a.phase_deg[0].1 + 180.0).abs() < 1e-12);
        assert!((a.phase_deg.last().unwrap().1 + 270.0).abs() < 1e-12);
        let a = tf(&[-1.0, 1.0], &[1.0, 1.0])
            .bode_asymptotes(1e-3, 1e3)
            .unwrap();
        assert!(a.phase_deg[0].1.abs() < 1e-12);
        assert!((a.phase_deg.last().unwrap().1 + 180.0).abs() < 1e-12);
        // Unstable 1/(s − 1): G(0) = −1 → starts at −180°, ends at −90°.
        let a = tf(&[1.0], &[1.0, -1.0]).bode_asymptotes(1e-3, 1e3).unwrap();
        assert!((a.phase_deg[0].1 + 180.0).abs() < 1e-12);
        assert!((a.phase_deg.last().unwrap().1 + 90.0).abs() < 1e-12);
    }

    #[test]
    fn second_order_and_undamped_step() {
        // 4/(s² + 0.8 s + 4): ωn = 2, ζ = 0.2 → 0 dB then −40 dB/dec, phase over 2·10^(±0.2).
        let a = tf(&[4.0], &[1.0, 0.8, 4.0])
            .bode_asymptotes(0.01, 100.0)
            .unwrap();
        assert!(at(&a.magnitude_db, 1.0).abs() < 1e-9);
        assert!((at(&a.magnitude_db, 20.0) + 40.0).abs() < 1e-9);
        assert!((at(&a.phase_deg, 2.0) + 90.0).abs() < 1e-9);
        assert!(at(&a.phase_deg, 2.0 * 10f64.powf(-0.2) * 0.999).abs() < 1e-9);
        // 1/(s² + 1): a −180° step at ω = 1 (two vertices at the same ω).
        let a = tf(&[1.0], &[1.0, 0.0, 1.0])
            .bode_asymptotes(0.1, 10.0)
            .unwrap();
        let step: Vec<_> = a
            .phase_deg
            .iter()
            .filter(|p| (p.0 - 1.0).abs() < 1e-12)
            .collect();
        assert_eq!(step.len(), 2);
        assert!(step[0].1.abs() < 1e-12 && (step[1].1 + 180.0).abs() < 1e-12);
    }

    #[test]
    fn agrees_with_exact_response_far_from_corners() {
        // (s + 10) / (s (s + 1)(s + 100)): |G| and phase far below/above every corner.
        let g = tf(&[1.0, 10.0], &[1.0, 101.0, 100.0, 0.0]);
        let a = g.bode_asymptotes(1e-4, 1e6).unwrap();
        for w in [1e-4, 1e6] {
            let exact = g.eval(num_complex::Complex64::new(0.0, w));
            let db = 20.0 * exact.norm().log10();
            assert!((at(&a.magnitude_db, w) - db).abs() < 1e-3, "ω = {w}");
        }
        assert!((a.phase_deg[0].1 + 90.0).abs() < 1e-12);
        assert!((a.phase_deg.last().unwrap().1 + 180.0).abs() < 1e-12);
    }

    #[test]
    fn rejects_bad_ranges_and_zero() {
        let g = tf(&[1.0], &[1.0, 1.0]);
        assert!(g.bode_asymptotes(0.0, 1.0).is_err());
        assert!(g.bode_asymptotes(2.0, 1.0).is_err());
        assert!(g.bode_asymptotes(f64::NAN, 1.0).is_err());
        assert!(tf(&[0.0], &[1.0, 1.0]).bode_asymptotes(0.1, 1.0).is_err());
    }

    mod property {
        use super::*;
        use num_complex::Complex64;
        use proptest::prelude::*;

        /// Exact magnitude (dB) and phase (DESIGN §1.3 branch) of k·Π(s − z)/Π(s − p) at jω,
        /// all roots non-zero: φ = φ₀ + Σ arg(1 − jω/z) − Σ arg(1 − jω/p).
        fn exact(k: f64, zeros: &[f64], poles: &[f64], w: f64) -> (f64, f64) {
            let s = Complex64::new(0.0, w);
            let mut g = Complex64::new(k, 0.0);
            let mut k0 = k;
            let mut ph = 0.0;
            for &z in zeros {
                g *= s - z;
                k0 *= -z;
                ph += (Complex64::new(1.0, 0.0) - s / z).arg().to_degrees();
            }
            for &p in poles {
                g /= s - p;
                k0 /= -p;
                ph -= (Complex64::new(1.0, 0.0) - s / p).arg().to_degrees();
            }
            let ph0 = if k0 < 0.0 { -180.0 } else { 0.0 };
            (20.0 * g.norm().log10(), ph0 + ph)
        }

        fn root() -> impl Strategy<Value = f64> {
            (0.01f64..100.0, any::<bool>(), 0.0f64..1.0)
                .prop_map(|(m, rhp, _)| if rhp { m } else { -m })
        }

        proptest! {
            #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]
            #[test]
            fn asymptotes_are_exact_far_from_the_corners(
                zeros in prop::collection::vec(root(), 0..4),
                poles in prop::collection::vec(root(), 1..6),
                k in prop_oneof![0.01f64..100.0, -100.0f64..-0.01],
            ) {
                let as_roots = |v: &[f64]| v.iter().map(|&r| Root { value: Complex64::new(r, 0.0), multiplicity: 1 }).collect::<Vec<_>>();
                let lo = zeros.iter().chain(&poles).map(|r| r.abs()).fold(f64::INFINITY, f64::min) * 1e-4;
                let hi = zeros.iter().chain(&poles).map(|r| r.abs()).fold(0.0, f64::max) * 1e4;
                let a = bode_asymptotes(&as_roots(&zeros), &as_roots(&poles), k, lo, hi).unwrap();
                for (w, m_asym, p_asym) in [
                    (lo, a.magnitude_db[0].1, a.phase_deg[0].1),
                    (hi, a.magnitude_db.last().unwrap().1, a.phase_deg.last().unwrap().1),
                ] {
                    let (m, p) = exact(k, &zeros, &poles, w);
                    prop_assert!((m - m_asym).abs() < 0.01, "ω = {}: {} vs {} dB", w, m, m_asym);
                    prop_assert!((p - p_asym).abs() < 0.5, "ω = {}: {} vs {} deg", w, p, p_asym);
                }
            }
        }
    }
}
