//! The exact path into the factored core: a plant whose coefficients arrived as text is
//! factored from its certified structure ([`crate::poly::exact::certify`]) — exact
//! multiplicities, exact cancellations, roots from the square-free factors, and the half plane
//! of every root decided by rational arithmetic. When the input is beyond the exact budget
//! the numerical path factors it and the factored form says why.

use num_complex::Complex64;

use super::decision::{Decision, StructurePath};
use super::form::{Factored, assemble};
use super::pole_zero::PoleZero;
use super::source::Source;
use crate::error::{LtiError, Result};
use crate::lti::TransferFunction;
use crate::poly::exact::{CircleSide, ExactPoly, Side, Structure, certify};
use crate::poly::{HalfPlane, half_plane};

impl Factored {
    /// A plant from exact coefficients (descending powers), factored on the exact path:
    /// multiplicities, cancellations and stability are decided without tolerance. Beyond the
    /// exact budget the numerical path factors it ([`Factored::exact_fallback`] says why).
    ///
    /// Errors: those of [`TransferFunction::new`] for the rounded coefficients (an all-zero
    /// denominator, an order above [`crate::MAX_ORDER`], coefficients that overflow f64).
    ///
    /// ```
    /// use ltikit::analysis::{Factored, StructurePath};
    /// use ltikit::poly::exact::ExactPoly;
    /// // poles ±j and ±j(1 + 1e-8): four simple poles on the axis, marginally stable.
    /// let num = ExactPoly::parse_descending(&["1"]).unwrap();
    /// let den = ExactPoly::parse_descending(&["1", "0", "2.00000002", "0", "1.00000002"]).unwrap();
    /// let f = Factored::from_exact(&num, &den).unwrap();
    /// assert_eq!(f.structure_path(), StructurePath::Exact);
    /// assert_eq!(f.poles().len(), 4);
    /// assert!(f.stability().reason.contains("marginally stable (decided exactly)"));
    /// ```
    pub fn from_exact(num: &ExactPoly, den: &ExactPoly) -> Result<Factored> {
        let tf = TransferFunction::new(num.to_poly()?, den.to_poly()?)?;
        Factored::from_exact_tf(&tf, num, den)
    }

    /// As [`Factored::from_exact`] for a transfer function whose exact coefficients are
    /// `num`/`den` (`tf` is their rounding, validated).
    pub(crate) fn from_exact_tf(
        tf: &TransferFunction,
        num: &ExactPoly,
        den: &ExactPoly,
    ) -> Result<Factored> {
        let built = certify(num, den).and_then(|s| Factored::from_structure(tf, &s));
        match built {
            Ok(f) => Ok(f),
            Err(e) => Factored::numerical_fallback(tf, &e),
        }
    }

    /// The numerical path for exact input that the exact path could not take.
    pub(crate) fn numerical_fallback(tf: &TransferFunction, why: &LtiError) -> Result<Factored> {
        let reason = match why {
            LtiError::BeyondExactBudget { reason } => reason.clone(),
            other => other.to_string(),
        };
        Factored::from_tf_deciding(tf, Decision::fallback(reason))
    }

    fn from_structure(tf: &TransferFunction, s: &Structure) -> Result<Factored> {
        let zero = tf.num().is_zero();
        let discrete = tf.domain().is_discrete();
        let mut sides = Vec::new();
        for f in s.factors() {
            if discrete {
                // the unit circle, in the words of the half plane (as `circle_side`)
                for (r, c) in f.roots.iter().zip(f.circle_sides()?) {
                    let side = match c {
                        CircleSide::Inside => HalfPlane::Left,
                        CircleSide::On => HalfPlane::Axis,
                        CircleSide::Outside => HalfPlane::Right,
                    };
                    sides.push((r.value, side));
                }
                continue;
            }
            for r in &f.roots {
                let side = match r.side {
                    Side::Left => HalfPlane::Left,
                    Side::Axis => HalfPlane::Axis,
                    Side::Right => HalfPlane::Right,
                };
                sides.push((r.value, side));
            }
        }
        // Distinct exact roots closer than double precision separates would become one
        // double: the analyses downstream need distinct values.
        for (i, (a, _)) in sides.iter().enumerate() {
            if sides[i + 1..].iter().any(|(b, _)| b == a) {
                return Err(LtiError::BeyondExactBudget {
                    reason: format!(
                        "two distinct roots round to the same double ({} {:+}j)",
                        a.re, a.im
                    ),
                });
            }
        }
        let zeros = if zero { Vec::new() } else { s.zeros() };
        let pz = PoleZero::from_parts(
            s.poles(),
            zeros,
            s.cancelled(),
            s.reduced_poles(),
            s.reduced_zeros(),
            zero,
        );
        let reduced = if pz.cancelled.is_empty() {
            tf.clone()
        } else {
            TransferFunction::new(
                s.reduced_numerator().to_poly()?,
                s.reduced_denominator().to_poly()?,
            )?
            .with_domain(tf.domain())
        };
        Ok(assemble(
            pz,
            if zero { 0.0 } else { tf.gain() },
            Source::coefficients_of(tf.clone(), reduced),
            Decision::exact(sides),
        )
        .with_domain(tf.domain()))
    }

    /// Which path decided the structure: [`StructurePath::Exact`] for coefficients that
    /// arrived as text (or through [`Factored::from_exact`]) within the exact budget,
    /// [`StructurePath::Numerical`] otherwise.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::StructurePath;
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 0.2, 0.01]).unwrap();
    /// assert_eq!(g.factored().unwrap().structure_path(), StructurePath::Numerical);
    /// ```
    pub fn structure_path(&self) -> StructurePath {
        if self.decision().sides.is_some() {
            StructurePath::Exact
        } else {
            StructurePath::Numerical
        }
    }

    /// Why exact input was factored numerically (beyond the exact budget: degree, digits,
    /// roots closer than the refinement separates); `None` when the exact path decided or the
    /// input was plain f64.
    pub fn exact_fallback(&self) -> Option<&str> {
        self.decision().fallback.as_deref()
    }

    /// One line saying which path decided the structure.
    ///
    /// ```
    /// use ltikit::lti::Plant;
    /// let p = Plant::from_text(None, "1 0.2 0.01").unwrap();
    /// let line = p.factored().unwrap().structure_note();
    /// assert_eq!(line, "exact (certified by rational arithmetic on the coefficients as typed)");
    /// ```
    pub fn structure_note(&self) -> String {
        if let Source::StateSpace(ss) = self.source() {
            return ss.note.clone();
        }
        match (self.structure_path(), &self.decision().fallback) {
            (StructurePath::Exact, _) => {
                "exact (certified by rational arithmetic on the coefficients as typed)".into()
            }
            (StructurePath::Numerical, Some(why)) => {
                format!("numerical (the exact path was not taken: {why})")
            }
            (StructurePath::Numerical, None) => {
                "numerical (floating-point root finder; f64 input)".into()
            }
        }
    }

    /// The half plane of a root of this plant — for a discrete plant the side of the unit
    /// circle (`Left` inside, `Axis` on, `Right` outside): decided exactly on the exact path,
    /// else by [`half_plane`] or [`circle_side`](crate::analysis::discrete::circle_side) (a
    /// relative tolerance about the axis or the circle).
    pub(crate) fn side_of(&self, v: Complex64) -> HalfPlane {
        let exact = self
            .decision()
            .sides
            .as_ref()
            .and_then(|s| s.iter().find(|(r, _)| *r == v).map(|(_, h)| *h));
        match exact {
            Some(h) => h,
            None if self.domain().is_discrete() => crate::analysis::discrete::circle_side(v),
            None => half_plane(v),
        }
    }

    /// True when the structure (and the side of every root: of the imaginary axis, or of the
    /// unit circle for a discrete plant) was decided exactly.
    pub(crate) fn decided_exactly(&self) -> bool {
        self.decision().sides.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::poly::Root;

    fn exact(num: &[&str], den: &[&str]) -> Factored {
        let n = ExactPoly::parse_descending(num).unwrap();
        let d = ExactPoly::parse_descending(den).unwrap();
        Factored::from_exact(&n, &d).unwrap()
    }

    #[test]
    fn exact_cancellation_with_decimals() {
        // (s + 0.1)(s + 0.3) / ((s + 0.1)(s + 0.7)), expanded by hand: 0.4 = 0.1 + 0.3,
        // 0.03 = 0.1·0.3, 0.8 = 0.1 + 0.7, 0.07 = 0.1·0.7.
        let f = exact(&["1", "0.4", "0.03"], &["1", "0.8", "0.07"]);
        assert_eq!(f.structure_path(), StructurePath::Exact);
        assert_eq!(
            f.pole_zero().cancelled,
            vec![Root::new(Complex64::new(-0.1, 0.0), 1)]
        );
        assert_eq!(
            f.reduced_poles(),
            &[Root::new(Complex64::new(-0.7, 0.0), 1)]
        );
        assert_eq!(f.reduced_tf().unwrap().den().coeffs(), &[1.0, 0.7]);
        assert_eq!(f.exact_fallback(), None);
    }

    #[test]
    fn root_just_right_of_the_axis_is_unstable() {
        // (s − 1e-20)(s + 1): s² + (1 − 1e-20) s − 1e-20.
        let f = exact(&["1"], &["1", "0.99999999999999999999", "-1e-20"]);
        let st = f.stability();
        assert!(!st.bibo_stable, "{}", st.reason);
        assert!(st.reason.contains("right half plane"), "{}", st.reason);
        assert!(st.reason.contains("decided exactly"), "{}", st.reason);
    }

    #[test]
    fn beyond_the_budget_falls_back() {
        // 5000-bit coefficient: above MAX_EXACT_BITS.
        let big = format!("1e{}", 999);
        let n = ExactPoly::parse_descending(&["1"]).unwrap();
        let d = ExactPoly::parse_descending(&["1", &big, "1e-999", "1"]).unwrap();
        let tf = TransferFunction::from_descending(&[1.0], &[1.0, 1e300, 1.0, 1.0]).unwrap();
        let f = Factored::from_exact_tf(&tf, &n, &d).unwrap();
        assert_eq!(f.structure_path(), StructurePath::Numerical);
        assert!(f.exact_fallback().is_some());
        assert!(f.structure_note().starts_with("numerical (the exact path"));
    }
}
