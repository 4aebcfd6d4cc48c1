//! Modes (ωₙ, ζ, time constant per pole) and the second-order damping class.

use num_complex::Complex64;
use serde::Serialize;

use crate::analysis::factored::Factored;
use crate::poly::{HalfPlane, Poly, Root, half_plane};

/// One distinct pole seen as a mode e^{pt}.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Mode {
    /// The pole.
    pub pole: Complex64,
    /// Its multiplicity.
    pub multiplicity: usize,
    /// Natural frequency |p| (rad/s).
    pub wn: f64,
    /// Damping ratio −Re p/|p| (1 for a stable real pole, 0 on the imaginary axis, negative
    /// in the right half plane); `None` for p = 0.
    pub zeta: Option<f64>,
    /// Time constant −1/Re p (s) for Re p < 0; `None` otherwise.
    pub time_constant: Option<f64>,
}

/// The modes of a list of poles (one per distinct pole, conjugates listed separately).
///
/// ```
/// use ltikit::TransferFunction;
/// let g = TransferFunction::from_descending(&[4.0], &[1.0, 0.8, 4.0]).unwrap();
/// let m = ltikit::analysis::modes(&g.poles().unwrap());
/// assert!((m[0].wn - 2.0).abs() < 1e-15);
/// assert!((m[0].zeta.unwrap() - 0.2).abs() < 1e-15);
/// assert!((m[0].time_constant.unwrap() - 2.5).abs() < 1e-14);
/// ```
pub fn modes(poles: &[Root]) -> Vec<Mode> {
    modes_by_side(poles, half_plane)
}

/// [`modes`] with the half plane of each pole decided by `side` (the factored form's exact
/// sides where it has them: −1e-12 ± j typed as text is in the left half plane, ζ = 1e-12).
fn modes_by_side(poles: &[Root], side: impl Fn(Complex64) -> HalfPlane) -> Vec<Mode> {
    poles
        .iter()
        .map(|r| {
            let p = r.value;
            let wn = p.norm();
            let on_axis = side(p) == HalfPlane::Axis;
            let zeta = if wn == 0.0 {
                None
            } else if on_axis {
                Some(0.0)
            } else if p.im == 0.0 {
                Some(if p.re < 0.0 { 1.0 } else { -1.0 })
            } else {
                Some(-p.re / wn)
            };
            let time_constant = (p.re < 0.0 && !on_axis).then(|| -1.0 / p.re);
            Mode {
                pole: p,
                multiplicity: r.multiplicity,
                wn,
                zeta,
                time_constant,
            }
        })
        .collect()
}

/// Damping class of a second-order characteristic polynomial.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DampingClass {
    /// ζ = 0: poles ±jωₙ.
    Undamped,
    /// 0 < ζ < 1: complex poles −ζωₙ ± jω_d.
    Underdamped,
    /// ζ = 1: a double real pole at −ωₙ.
    CriticallyDamped,
    /// ζ > 1: two distinct negative real poles.
    Overdamped,
    /// ζ < 0, or real poles of opposite sign or at the origin: not a damped oscillator.
    Unstable,
}

impl DampingClass {
    /// Lower-case words: "critically damped".
    pub fn words(&self) -> &'static str {
        match self {
            DampingClass::Undamped => "undamped",
            DampingClass::Underdamped => "underdamped",
            DampingClass::CriticallyDamped => "critically damped",
            DampingClass::Overdamped => "overdamped",
            DampingClass::Unstable => "unstable",
        }
    }
}

/// ωₙ, ζ, ω_d and the class of a second-order system a s² + b s + c (seed eqs. 2.11, 3.24–3.26).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SecondOrder {
    /// The class.
    pub class: DampingClass,
    /// ωₙ = √(c/a) (rad/s); `None` when c/a ≤ 0.
    pub wn: Option<f64>,
    /// ζ = b/(2√(ac)); exactly 1 for a double root, exactly 0 for poles on the axis; `None`
    /// when c/a ≤ 0.
    pub zeta: Option<f64>,
    /// ω_d = ωₙ√(1 − ζ²) for |ζ| < 1 (rad/s).
    pub wd: Option<f64>,
}

/// The second-order data of a degree-2 characteristic polynomial with its roots (as returned
/// by [`Poly::roots`]); `None` for other degrees.
///
/// ```
/// use ltikit::{Poly, analysis::{second_order, DampingClass}};
/// let d = Poly::from_descending(&[1.0, 2.0, 1.0]).unwrap();
/// let so = second_order(&d, &d.roots().unwrap()).unwrap();
/// assert_eq!(so.class, DampingClass::CriticallyDamped);
/// assert_eq!(so.zeta, Some(1.0));
/// ```
pub fn second_order(den: &Poly, roots: &[Root]) -> Option<SecondOrder> {
    second_order_by_side(den, roots, half_plane)
}

/// [`second_order`] with the half plane of each root decided by `side`.
fn second_order_by_side(
    den: &Poly,
    roots: &[Root],
    side: impl Fn(Complex64) -> HalfPlane,
) -> Option<SecondOrder> {
    if den.degree() != 2 {
        return None;
    }
    let c = den.coeffs();
    let (a, b, k) = (c[0], c[1], c[2]);
    let ratio = k / a;
    if ratio <= 0.0 {
        return Some(SecondOrder {
            class: DampingClass::Unstable,
            wn: None,
            zeta: None,
            wd: None,
        });
    }
    let wn = ratio.sqrt();
    let double = roots.len() == 1 && roots[0].multiplicity == 2;
    let on_axis = roots
        .iter()
        .all(|r| r.value.im != 0.0 && side(r.value) == HalfPlane::Axis);
    let zeta = if double {
        if roots[0].value.re < 0.0 { 1.0 } else { -1.0 }
    } else if on_axis {
        0.0
    } else {
        b / (2.0 * a * wn)
    };
    let class = if zeta < 0.0 {
        DampingClass::Unstable
    } else if on_axis {
        DampingClass::Undamped
    } else if double {
        DampingClass::CriticallyDamped
    } else if roots.iter().all(|r| r.value.im == 0.0) {
        DampingClass::Overdamped
    } else {
        DampingClass::Underdamped
    };
    let wd = (zeta.abs() < 1.0).then(|| wn * (1.0 - zeta * zeta).sqrt());
    Some(SecondOrder {
        class,
        wn: Some(wn),
        zeta: Some(zeta),
        wd,
    })
}

impl Factored {
    /// One mode per distinct characteristic root ([`modes`]).
    pub fn modes(&self) -> Vec<Mode> {
        if let Some(dt) = self.domain().dt() {
            return crate::analysis::discrete::modes(self.poles(), dt, |p| self.side_of(p));
        }
        modes_by_side(self.poles(), |p| self.side_of(p))
    }

    /// ωₙ, ζ, ω_d and the damping class when the plant has order 2 ([`second_order`]).
    pub fn second_order(&self) -> Option<SecondOrder> {
        if self.order() != 2 || self.domain().is_discrete() {
            return None;
        }
        let den = self.characteristic_poly().ok()?;
        second_order_by_side(&den, self.poles(), |p| self.side_of(p))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn so(c: &[f64]) -> SecondOrder {
        let p = Poly::from_descending(c).unwrap();
        second_order(&p, &p.roots().unwrap()).unwrap()
    }

    #[test]
    fn seed_damping_cases() {
        // ωn = 1 and ζ = 0, 0.1, 1, 2 (seed fig. 2.3)
        assert_eq!(so(&[1.0, 0.0, 1.0]).class, DampingClass::Undamped);
        let u = so(&[1.0, 0.2, 1.0]);
        assert_eq!(u.class, DampingClass::Underdamped);
        assert!((u.wd.unwrap() - (1.0f64 - 0.01).sqrt()).abs() < 1e-15);
        assert_eq!(so(&[1.0, 2.0, 1.0]).class, DampingClass::CriticallyDamped);
        let o = so(&[1.0, 4.0, 1.0]);
        assert_eq!(o.class, DampingClass::Overdamped);
        assert_eq!(o.zeta, Some(2.0));
        assert_eq!(so(&[1.0, -0.2, 1.0]).class, DampingClass::Unstable);
        assert_eq!(so(&[1.0, 1.0, -1.0]).class, DampingClass::Unstable);
    }

    #[test]
    fn critical_damping_from_physical_parameters() {
        // M = 2, K = 3, C = 2√6: ζ = 1 exactly up to the rounding of √6.
        let c = 2.0 * 6f64.sqrt();
        let s = so(&[2.0, c, 3.0]);
        assert_eq!(s.class, DampingClass::CriticallyDamped, "{s:?}");
    }
}
