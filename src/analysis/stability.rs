//! BIBO and internal stability, with the reason in words.
//!
//! **BIBO stable** ⇔ every pole of G in lowest terms has Re p < 0 (seed Theorem 3.1, which
//! holds for the reduced form). **Internally stable** ⇔ every root of the characteristic
//! polynomial (the denominator as given) has Re p < 0. A root within a relative 1e-9 of the
//! imaginary axis is *on* it: s² + 1 is never called stable because Re p came out −4e-16.
//! Simple imaginary-axis poles make a system marginally stable; repeated ones unstable.

use num_complex::Complex64;
use serde::Serialize;

use crate::analysis::factored::Factored;
use crate::error::Result;
use crate::fmt::fmt_root;
use crate::lti::TransferFunction;
use crate::poly::Root;
pub use crate::poly::{HalfPlane, half_plane};

/// Stability class of a set of roots.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StabilityClass {
    /// All roots in the open left half plane.
    Stable,
    /// No right-half-plane roots; simple roots on the imaginary axis.
    MarginallyStable,
    /// A right-half-plane root or a repeated imaginary-axis root.
    Unstable,
}

/// Stability verdicts with reasons.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Stability {
    /// BIBO stable (poles of the reduced transfer function).
    pub bibo_stable: bool,
    /// Class of the reduced transfer function's poles.
    pub bibo: StabilityClass,
    /// Why, for the reduced transfer function.
    pub bibo_reason: String,
    /// Internally stable (roots of the characteristic polynomial).
    pub internally_stable: bool,
    /// Class of the characteristic roots.
    pub internal: StabilityClass,
    /// Why, for the characteristic polynomial.
    pub internal_reason: String,
    /// One sentence covering both (they differ only when an unstable root cancels).
    pub reason: String,
}

/// Classifies a set of roots and says why.
pub fn classify(roots: &[Root]) -> (StabilityClass, String) {
    classify_by(roots, &half_plane, Plane::S)
}

/// [`classify`] in continuous or discrete time (against the unit circle when `discrete`).
pub(crate) fn classify_in(roots: &[Root], discrete: bool) -> (StabilityClass, String) {
    if discrete {
        classify_by(roots, &crate::analysis::discrete::circle_side, Plane::Z)
    } else {
        classify(roots)
    }
}

/// The stability region's words: the s-plane (left half plane) or the z-plane (unit disc).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Plane {
    S,
    Z,
}

impl Plane {
    fn var(self) -> &'static str {
        match self {
            Plane::S => "s",
            Plane::Z => "z",
        }
    }
    fn outside(self) -> &'static str {
        match self {
            Plane::S => "in the right half plane",
            Plane::Z => "outside the unit circle",
        }
    }
    fn boundary(self) -> &'static str {
        match self {
            Plane::S => "on the imaginary axis",
            Plane::Z => "on the unit circle",
        }
    }
    fn boundary_short(self) -> &'static str {
        match self {
            Plane::S => "imaginary-axis",
            Plane::Z => "unit-circle",
        }
    }
    fn inside(self) -> &'static str {
        match self {
            Plane::S => "all poles in the open left half plane",
            Plane::Z => "all poles strictly inside the unit circle",
        }
    }
}

/// As [`classify`], with the half plane of each root decided by `side` (exactly, on the exact
/// path).
fn classify_by(
    roots: &[Root],
    side: &dyn Fn(Complex64) -> HalfPlane,
    plane: Plane,
) -> (StabilityClass, String) {
    if roots.is_empty() {
        return (StabilityClass::Stable, "no poles".into());
    }
    let rhp: Vec<&Root> = roots
        .iter()
        .filter(|r| side(r.value) == HalfPlane::Right && r.value.im >= 0.0)
        .collect();
    let worse = |r: &Root| match plane {
        Plane::S => r.value.re,
        Plane::Z => r.value.norm(),
    };
    if let Some(worst) = rhp.iter().max_by(|a, b| worse(a).total_cmp(&worse(b))) {
        let more = if rhp.len() > 1 {
            format!(" (and {} more)", rhp.len() - 1)
        } else {
            String::new()
        };
        let mult = if worst.multiplicity > 1 {
            format!(" of multiplicity {}", worst.multiplicity)
        } else {
            String::new()
        };
        return (
            StabilityClass::Unstable,
            format!(
                "pole at {} = {}{mult} {}{more}",
                plane.var(),
                fmt_root(worst.value, 3),
                plane.outside()
            ),
        );
    }
    let axis: Vec<&Root> = roots
        .iter()
        .filter(|r| side(r.value) == HalfPlane::Axis && r.value.im >= 0.0)
        .collect();
    // distinct poles once each, as printed (±1j and ±1.000000001j both read "±1j")
    let axis_list = |rs: &[&Root]| {
        let mut seen: Vec<String> = Vec::new();
        for r in rs {
            let t = match plane {
                Plane::S => fmt_root(Complex64::new(0.0, r.value.im), 3),
                Plane::Z => fmt_root(r.value, 3),
            };
            if !seen.contains(&t) {
                seen.push(t);
            }
        }
        seen.join(", ")
    };
    let repeated: Vec<&Root> = axis
        .iter()
        .copied()
        .filter(|r| r.multiplicity > 1)
        .collect();
    if !repeated.is_empty() {
        let m = repeated.iter().map(|r| r.multiplicity).max().unwrap_or(2);
        return (
            StabilityClass::Unstable,
            format!(
                "repeated {} poles at {} = {} (multiplicity {m}): unstable",
                plane.boundary_short(),
                plane.var(),
                axis_list(&repeated)
            ),
        );
    }
    if !axis.is_empty() {
        return (
            StabilityClass::MarginallyStable,
            format!(
                "simple poles {} at {} = {}: marginally stable",
                plane.boundary(),
                plane.var(),
                axis_list(&axis)
            ),
        );
    }
    (StabilityClass::Stable, plane.inside().into())
}

impl TransferFunction {
    /// BIBO stability of the reduced transfer function and internal stability of the
    /// characteristic polynomial.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // (s − 1)/((s − 1)(s + 2)): BIBO stable, internally unstable.
    /// let g = TransferFunction::from_descending(&[1.0, -1.0], &[1.0, 1.0, -2.0]).unwrap();
    /// let st = g.bibo_stability().unwrap();
    /// assert!(st.bibo_stable && !st.internally_stable);
    /// // s² + 1 in the denominator: marginally stable, not BIBO stable.
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 0.0, 1.0]).unwrap();
    /// let st = g.bibo_stability().unwrap();
    /// assert!(!st.bibo_stable);
    /// assert_eq!(st.bibo_reason, "simple poles on the imaginary axis at s = ±1j: marginally stable");
    /// ```
    pub fn bibo_stability(&self) -> Result<Stability> {
        Ok(self.factored()?.stability())
    }
}

impl Factored {
    /// BIBO stability of the reduced transfer function and internal stability of the
    /// characteristic roots, with the reasons.
    ///
    /// On the exact path (coefficients typed as text) the half planes — for a discrete plant
    /// the sides of the unit circle — come from the exact counts, with no tolerance about the
    /// axis or the circle, and every reason ends "(decided exactly)".
    pub fn stability(&self) -> Stability {
        let pz = self.pole_zero();
        let plane = if self.domain().is_discrete() {
            Plane::Z
        } else {
            Plane::S
        };
        let mut st = stability_by(
            &pz.poles,
            &pz.reduced_poles,
            &pz.cancelled,
            &|v| self.side_of(v),
            plane,
        );
        if !self.decided_exactly() {
            return st;
        }
        for r in [&mut st.bibo_reason, &mut st.internal_reason, &mut st.reason] {
            r.push_str(" (decided exactly)");
        }
        st
    }
}

/// Stability from the characteristic roots, the reduced poles and the cancelled roots.
pub fn stability_of(poles: &[Root], reduced_poles: &[Root], cancelled: &[Root]) -> Stability {
    stability_by(poles, reduced_poles, cancelled, &half_plane, Plane::S)
}

fn stability_by(
    poles: &[Root],
    reduced_poles: &[Root],
    cancelled: &[Root],
    side: &dyn Fn(Complex64) -> HalfPlane,
    plane: Plane,
) -> Stability {
    let (bibo, bibo_reason) = classify_by(reduced_poles, side, plane);
    let (internal, internal_reason) = classify_by(poles, side, plane);
    let reason = if bibo == internal {
        bibo_reason.clone()
    } else {
        let (_, cancelled_reason) = classify_by(cancelled, side, plane);
        format!(
            "BIBO {}: {bibo_reason}; internally {}: cancelled {}",
            if bibo == StabilityClass::Stable {
                "stable"
            } else {
                "not stable"
            },
            match internal {
                StabilityClass::Stable => "stable",
                StabilityClass::MarginallyStable => "marginally stable",
                StabilityClass::Unstable => "unstable",
            },
            cancelled_reason
        )
    };
    Stability {
        bibo_stable: bibo == StabilityClass::Stable,
        bibo,
        bibo_reason,
        internally_stable: internal == StabilityClass::Stable,
        internal,
        internal_reason,
        reason,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn st(num: &[f64], den: &[f64]) -> Stability {
        TransferFunction::from_descending(num, den)
            .unwrap()
            .bibo_stability()
            .unwrap()
    }

    #[test]
    fn seed_section_3_5_examples() {
        // (s−1)/((s+1)(s+2)(s+7)) is BIBO stable.
        assert!(st(&[1.0, -1.0], &[1.0, 10.0, 23.0, 14.0]).bibo_stable);
        // (s−1)/((s+1)(s−2)(s+7)) is not.
        let s = st(&[1.0, -1.0], &[1.0, 6.0, -9.0, -14.0]);
        assert!(!s.bibo_stable);
        assert_eq!(s.bibo, StabilityClass::Unstable);
        assert_eq!(s.bibo_reason, "pole at s = 2 in the right half plane");
        // (s+1)/(s(s+1)(s+2)): the pole at 0 remains after cancelling s+1.
        let s = st(&[1.0, 1.0], &[1.0, 3.0, 2.0, 0.0]);
        assert_eq!(s.bibo, StabilityClass::MarginallyStable);
        // 1/(s²+1)
        assert!(!st(&[1.0], &[1.0, 0.0, 1.0]).bibo_stable);
    }

    #[test]
    fn repeated_axis_poles_are_unstable() {
        let s = st(&[1.0], &[1.0, 0.0, 2.0, 0.0, 1.0]);
        assert_eq!(s.bibo, StabilityClass::Unstable);
        assert!(s.bibo_reason.contains("repeated"), "{}", s.bibo_reason);
        let s = st(&[1.0], &[1.0, 0.0, 0.0]);
        assert_eq!(s.bibo, StabilityClass::Unstable);
    }

    #[test]
    fn right_half_plane_pair_reason() {
        // (s − 0.25)² + 1.75 = s² − 0.5 s + 1.8125: poles 0.25 ± 1.32j
        let s = st(&[1.0], &[1.0, -0.5, 1.8125]);
        assert_eq!(
            s.bibo_reason,
            "pole at s = 0.25 ± 1.32j in the right half plane"
        );
    }

    #[test]
    fn hidden_unstable_mode() {
        let s = st(&[1.0, -1.0], &[1.0, 1.0, -2.0]);
        assert!(s.bibo_stable);
        assert!(!s.internally_stable);
        assert!(s.reason.contains("cancelled pole at s = 1"), "{}", s.reason);
    }
}
