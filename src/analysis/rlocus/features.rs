//! The features of a root locus, each from a polynomial: asymptotes, break points,
//! imaginary-axis crossings, departure and arrival angles.

use num_complex::Complex64;
use serde::Serialize;

use crate::error::Result;
use crate::numeric::tol::ZERO_REL_TOL;
use crate::poly::{MAX_ORDER, Poly, Root};

/// The asymptotes of the branches that go to infinity.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Asymptotes {
    /// How many branches go to infinity: deg D − deg N.
    pub count: usize,
    /// Where the asymptotes meet on the real axis: (Σ poles − Σ zeros)/(deg D − deg N).
    pub centroid: f64,
    /// Their angles in degrees, in (−180°, 180°], increasing.
    pub angles_deg: Vec<f64>,
}

/// Whether branches leave or join the real axis at a break point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum BreakKind {
    /// Branches meet on the real axis and leave it (|K| is a local maximum along the axis).
    BreakAway,
    /// Branches arrive from the complex plane and continue on the real axis (|K| is a local
    /// minimum along the axis).
    BreakIn,
    /// Branches cross through (|K| is monotonic along the axis: an inflection).
    Crossing,
}

/// A break point of the locus on the real axis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BreakPoint {
    /// Its position σ on the real axis.
    pub s: f64,
    /// The gain at which the branches meet there, −D(σ)/N(σ).
    pub gain: f64,
    /// How many branches meet (1 + the multiplicity of σ as a root of N·D′ − N′·D).
    pub branches: usize,
    /// Break-away or break-in.
    pub kind: BreakKind,
}

/// A crossing of the stability boundary: closed-loop poles at ±jω (continuous time) or at
/// z = e^(±jωT) on the unit circle (discrete time) for the gain K.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LocusCrossing {
    /// ω ≥ 0 (rad/s; in discrete time 0 ≤ ω ≤ π/T, the angle of z over T).
    pub omega: f64,
    /// The gain.
    pub gain: f64,
    /// Discrete time: the crossing point e^(jωT) on the unit circle (upper half; its conjugate
    /// too). `None` (absent from JSON) in continuous time.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub z: Option<Complex64>,
}

/// The directions in which the branches leave a pole (or arrive at a zero).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LocusAngle {
    /// The pole or zero.
    pub at: Complex64,
    /// Its multiplicity μ (μ branches leave or arrive).
    pub multiplicity: usize,
    /// The μ angles in degrees, in (−180°, 180°], increasing.
    pub angles_deg: Vec<f64>,
}

/// Splits the roots of D and N into those they share (fixed closed-loop poles, with the
/// smaller multiplicity) and the poles and zeros of G in lowest terms.
pub(super) fn cancel(poles: &[Root], zeros: &[Root]) -> (Vec<Root>, Vec<Root>, Vec<Root>) {
    let mut p: Vec<Root> = poles.to_vec();
    let mut z: Vec<Root> = zeros.to_vec();
    let mut fixed = Vec::new();
    for pi in p.iter_mut() {
        for zi in z.iter_mut() {
            if zi.multiplicity > 0 && pi.multiplicity > 0 && pi.same_as(zi.value) {
                let k = pi.multiplicity.min(zi.multiplicity);
                fixed.push(Root {
                    value: pi.value,
                    multiplicity: k,
                });
                pi.multiplicity -= k;
                zi.multiplicity -= k;
            }
        }
    }
    p.retain(|r| r.multiplicity > 0);
    z.retain(|r| r.multiplicity > 0);
    (fixed, p, z)
}

/// An angle in degrees mapped to (−180°, 180°].
fn wrap(a: f64) -> f64 {
    let r = a.rem_euclid(360.0);
    if r > 180.0 { r - 360.0 } else { r }
}

/// `count` angles (base + 360°·l)/count, wrapped and sorted.
fn spread(base: f64, count: usize) -> Vec<f64> {
    let mut v: Vec<f64> = (0..count)
        .map(|l| wrap((base + 360.0 * l as f64) / count as f64))
        .collect();
    v.sort_by(f64::total_cmp);
    v
}

/// Asymptotes from the two leading coefficients of N and D: Σp = −d₁/d₀, Σz = −n₁/n₀.
pub(super) fn asymptotes(num: &Poly, den: &Poly, base: f64) -> Option<Asymptotes> {
    let q = den.degree().checked_sub(num.degree()).filter(|q| *q > 0)?;
    let second = |p: &Poly| {
        if p.degree() == 0 {
            0.0
        } else {
            -p.coeffs()[1] / p.coeffs()[0]
        }
    };
    Some(Asymptotes {
        count: q,
        centroid: (second(den) - second(num)) / q as f64,
        angles_deg: spread(base, q),
    })
}

/// Σ multiplicity·arg(s − r) over `roots` (skipping `skip`), in degrees.
fn angle_sum(s: Complex64, roots: &[Root], skip: Option<usize>) -> f64 {
    roots
        .iter()
        .enumerate()
        .filter(|(i, _)| Some(*i) != skip)
        .map(|(_, r)| r.multiplicity as f64 * (s - r.value).arg().to_degrees())
        .sum()
}

/// Departure angles: near a pole p of multiplicity μ the angle condition
/// Σ∠(s − zᵢ) − Σ∠(s − pⱼ) = base (mod 360°) gives μ·θ = Σ∠(p − zᵢ) − Σ_{j≠p}∠(p − pⱼ) − base.
pub(super) fn departures(poles: &[Root], zeros: &[Root], base: f64) -> Vec<LocusAngle> {
    poles
        .iter()
        .enumerate()
        .filter(|(_, r)| r.value.im >= 0.0)
        .map(|(i, r)| {
            let phi = angle_sum(r.value, zeros, None) - angle_sum(r.value, poles, Some(i));
            LocusAngle {
                at: r.value,
                multiplicity: r.multiplicity,
                angles_deg: spread(phi - base, r.multiplicity),
            }
        })
        .collect()
}

/// Arrival angles: near a zero z of multiplicity ν, ν·θ = base − Σ_{i≠z}∠(z − zᵢ) + Σ∠(z − pⱼ).
pub(super) fn arrivals(poles: &[Root], zeros: &[Root], base: f64) -> Vec<LocusAngle> {
    zeros
        .iter()
        .enumerate()
        .filter(|(_, r)| r.value.im >= 0.0)
        .map(|(i, r)| {
            let psi = angle_sum(r.value, zeros, Some(i)) - angle_sum(r.value, poles, None);
            LocusAngle {
                at: r.value,
                multiplicity: r.multiplicity,
                angles_deg: spread(base - psi, r.multiplicity),
            }
        })
        .collect()
}

/// True when |p(x)| is at rounding level: ≤ [`ZERO_REL_TOL`]·Σ|aᵢ||x|ⁱ.
fn vanishes(p: &Poly, x: f64) -> bool {
    p.eval(x).abs() <= ZERO_REL_TOL * p.eval_abs(x.abs())
}

/// Real roots σ of R = N·D′ − N′·D with K = −D(σ)/N(σ) of the locus's sign (points where
/// D or N vanishes — multiple poles at K = 0, multiple zeros at K = ∞ — are not break points).
///
/// `None` when N·D′ − N′·D is of degree above [`MAX_ORDER`] (not computed).
pub(super) fn break_points(num: &Poly, den: &Poly, sign: f64) -> Result<Option<Vec<BreakPoint>>> {
    let r = &(num * &den.derivative()) + &(&num.derivative() * den).scale(-1.0);
    if r.is_zero() || r.degree() == 0 {
        return Ok(Some(Vec::new()));
    }
    if r.degree() > MAX_ORDER {
        return Ok(None);
    }
    let mut out = Vec::new();
    for root in r.roots()? {
        if root.value.im != 0.0 {
            continue;
        }
        let s = root.value.re;
        if vanishes(den, s) || vanishes(num, s) {
            continue;
        }
        let gain = -den.eval(s) / num.eval(s);
        if !(gain.is_finite() && gain * sign > 0.0) {
            continue;
        }
        let mu = root.multiplicity;
        // K′ = −R/N², so the first non-vanishing derivative of K at σ is
        // K^(μ+1)(σ) = −R^(μ)(σ)/N(σ)²: an extremum of K when μ is odd.
        let kind = if mu % 2 == 1 {
            let curvature = -r.nth_derivative(mu).eval(s);
            if curvature * gain < 0.0 {
                BreakKind::BreakAway
            } else {
                BreakKind::BreakIn
            }
        } else {
            BreakKind::Crossing
        };
        out.push(BreakPoint {
            s,
            gain,
            branches: mu + 1,
            kind,
        });
    }
    out.sort_by(|a, b| a.s.total_cmp(&b.s));
    Ok(Some(out))
}

/// The imaginary-axis crossings on this locus: K of the locus's sign, and K ≠ 0 (a pole on
/// the axis at K = 0 is an open-loop pole, not a crossing). `None` when the crossing
/// polynomial Im(D(jω)·conj N(jω)) could be of degree above [`MAX_ORDER`] (not computed).
pub(super) fn crossings(num: &Poly, den: &Poly, sign: f64) -> Result<Option<Vec<LocusCrossing>>> {
    if num.degree() + den.degree() > MAX_ORDER {
        return Ok(None);
    }
    Ok(Some(
        super::super::routh::axis_crossings(num, den)?
            .into_iter()
            .filter(|(w, k)| {
                let at_pole = {
                    let s = Complex64::new(0.0, *w);
                    den.eval_complex(s).norm() <= ZERO_REL_TOL * den.eval_abs(*w)
                };
                *k * sign > 0.0 && !at_pole
            })
            .map(|(omega, gain)| LocusCrossing {
                omega,
                gain,
                z: None,
            })
            .collect(),
    ))
}

/// The unit-circle crossings on this locus (discrete time, period `dt`): K of the locus's
/// sign, K ≠ 0 and not at an open-loop pole. `None` when the crossing polynomial could be of
/// degree above [`MAX_ORDER`].
pub(super) fn circle_crossings(
    num: &Poly,
    den: &Poly,
    sign: f64,
    dt: f64,
) -> Result<Option<Vec<LocusCrossing>>> {
    if 2 * den.degree().max(num.degree()) > MAX_ORDER {
        return Ok(None);
    }
    Ok(Some(
        crate::analysis::jury::circle_crossings(num, den)?
            .into_iter()
            .filter(|(th, k)| {
                let z = Complex64::from_polar(1.0, *th);
                let at_pole = den.eval_complex(z).norm() <= ZERO_REL_TOL * den.eval_abs(1.0);
                *k * sign > 0.0 && !at_pole
            })
            // θ = π is set exactly for z = −1 (not computed)
            .map(|(th, gain)| {
                #[allow(clippy::float_cmp)]
                let z = if th == 0.0 {
                    Complex64::new(1.0, 0.0)
                } else if th == std::f64::consts::PI {
                    Complex64::new(-1.0, 0.0)
                } else {
                    Complex64::from_polar(1.0, th)
                };
                LocusCrossing {
                    omega: th / dt,
                    gain,
                    z: Some(z),
                }
            })
            .collect(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(c: &[f64]) -> Poly {
        Poly::from_descending(c).unwrap()
    }

    #[test]
    fn break_in_between_two_zeros() {
        // (s + 2)(s + 3)/(s(s + 1)): break-away between 0 and −1, break-in between −2 and −3.
        // R = N·D′ − N′·D = (s² + 5s + 6)(2s + 1) − (2s + 5)(s² + s) = 4s² + 12s + 6 (÷2:
        // 2s² + 6s + 3), roots (−3 ± √3)/2.
        let b = break_points(&p(&[1.0, 5.0, 6.0]), &p(&[1.0, 1.0, 0.0]), 1.0)
            .unwrap()
            .unwrap();
        assert_eq!(b.len(), 2);
        let s3 = 3f64.sqrt();
        assert!((b[0].s - (-3.0 - s3) / 2.0).abs() < 1e-14);
        assert_eq!(b[0].kind, BreakKind::BreakIn);
        assert!((b[1].s - (-3.0 + s3) / 2.0).abs() < 1e-14);
        assert_eq!(b[1].kind, BreakKind::BreakAway);
    }

    #[test]
    fn departure_from_a_complex_pair() {
        // 1/((s + 1)(s² + 2s + 2)): at p = −1 + j, ∠(p + 1) = 90°, ∠(p − conj p) = 90°, so
        // θ = 180° − 90° − 90° = 0°.
        let poles = p(&[1.0, 3.0, 4.0, 2.0]).roots().unwrap();
        let d = departures(&poles, &[], 180.0);
        let top = d.iter().find(|a| a.at.im > 0.5).unwrap();
        assert!(top.angles_deg[0].abs() < 1e-12, "{:?}", top.angles_deg);
    }

    #[test]
    fn double_pole_departs_both_ways() {
        // 1/(s + 1)²: the double pole splits vertically, ±90°.
        let poles = p(&[1.0, 2.0, 1.0]).roots().unwrap();
        let d = departures(&poles, &[], 180.0);
        assert_eq!(d[0].angles_deg.len(), 2);
        assert!((d[0].angles_deg[0] + 90.0).abs() < 1e-12);
        assert!((d[0].angles_deg[1] - 90.0).abs() < 1e-12);
    }
}
