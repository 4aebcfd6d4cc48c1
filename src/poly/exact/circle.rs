//! Exact unit-circle counts: the roots of an exact polynomial strictly inside, on and outside
//! the unit circle, by the bilinear map z = (1 + w)/(1 − w) and the exact half-plane counts.
//!
//! The map sends the open unit disc onto the open left half plane, the circle onto the
//! imaginary axis (z = 1 to w = 0) and z = −1 to w = ∞. For p of degree n,
//! Q(w) = (1 − w)ⁿ·p((1 + w)/(1 − w)) = Σ pₖ (1 + w)ᵏ (1 − w)ⁿ⁻ᵏ has integer coefficients
//! when p has, its leading coefficient is (−1)ⁿ·p(−1): each root of p at z = −1 shows as a
//! degree drop (a root on the circle), never as a division by zero. Its roots in the open left
//! half plane, on the axis and in the open right half plane (`sturm.rs`, exact) are the roots
//! of p inside, on and outside the circle.

use num_complex::Complex64;

use super::budget::{beyond, check_sizes};
use super::certify::{Factor, Side, factor_roots};
use super::number::Rational;
use super::qpoly::ExactPoly;
use super::zpoly::ZPoly;
use crate::error::{LtiError, Result};

/// Roots strictly inside, on and strictly outside the unit circle, counted with multiplicity.
///
/// ```
/// use ltikit::poly::exact::ExactPoly;
/// // (z² + 1)(z − 0.5)(z − 2): two on, one inside, one outside.
/// let p = ExactPoly::parse_descending(&["1", "-2.5", "2", "-2.5", "1"]).unwrap();
/// let c = p.unit_circle_counts().unwrap();
/// assert_eq!((c.inside, c.on, c.outside), (1, 2, 1));
/// assert_eq!(c.total(), 4);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct CircleCounts {
    /// Roots with |z| < 1 (z = 0 included).
    pub inside: usize,
    /// Roots with |z| = 1.
    pub on: usize,
    /// Roots with |z| > 1.
    pub outside: usize,
}

impl CircleCounts {
    /// Total number of roots.
    pub fn total(&self) -> usize {
        self.inside + self.on + self.outside
    }

    /// These counts times `m`.
    pub fn times(&self, m: usize) -> CircleCounts {
        CircleCounts {
            inside: self.inside * m,
            on: self.on * m,
            outside: self.outside * m,
        }
    }

    /// Sum of two counts.
    pub fn plus(&self, o: &CircleCounts) -> CircleCounts {
        CircleCounts {
            inside: self.inside + o.inside,
            on: self.on + o.on,
            outside: self.outside + o.outside,
        }
    }
}

/// Where a root lies with respect to the unit circle, decided exactly.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CircleSide {
    /// |z| < 1.
    Inside,
    /// |z| = 1.
    On,
    /// |z| > 1.
    Outside,
}

/// (1 − w)ⁿ·p((1 + w)/(1 − w)) for p of degree n (ascending integer coefficients), by Horner
/// in the homogeneous pair u = 1 + w, v = 1 − w: H₀ = pₙ, Hⱼ = Hⱼ₋₁·u + pₙ₋ⱼ·vʲ.
pub(crate) fn bilinear_z(p: &ZPoly) -> ZPoly {
    if p.is_zero() {
        return p.clone();
    }
    let n = p.deg();
    let c = p.coeffs();
    let u = ZPoly::new(vec![dashu_int::IBig::ONE, dashu_int::IBig::ONE]);
    let v = ZPoly::new(vec![dashu_int::IBig::ONE, -dashu_int::IBig::ONE]);
    let mut h = ZPoly::new(vec![c[n].clone()]);
    let mut vj = ZPoly::one();
    for j in 1..=n {
        vj = vj.mul(&v);
        h = h.mul(&u).add(&vj.scale(&c[n - j]));
    }
    h
}

impl ExactPoly {
    /// The bilinear image (1 − w)ⁿ·p((1 + w)/(1 − w)) of this polynomial of degree n: its roots
    /// w = (z − 1)/(z + 1) lie in the open left half plane, on the imaginary axis or in the
    /// open right half plane exactly when the roots z of p lie inside, on or outside the unit
    /// circle; a root z = −1 drops the degree by one. Printed in the variable s.
    ///
    /// ```
    /// use ltikit::poly::exact::ExactPoly;
    /// // z − 0.5 → (1 + w) − 0.5(1 − w) = 1.5 w + 0.5: root w = −1/3 (z = 0.5 inside).
    /// let p = ExactPoly::parse_descending(&["1", "-0.5"]).unwrap();
    /// assert_eq!(p.bilinear().to_string(), "3/2 s + 1/2");
    /// // z + 1 → 2: the root z = −1 is the degree drop.
    /// assert_eq!(ExactPoly::parse_descending(&["1", "1"]).unwrap().bilinear().to_string(), "2");
    /// ```
    pub fn bilinear(&self) -> ExactPoly {
        ExactPoly::from_integer_poly(bilinear_z(self.prim()), &self.content())
    }

    /// Roots strictly inside, on and strictly outside the unit circle, with multiplicity,
    /// decided exactly (the bilinear map and the exact half-plane counts; see
    /// [`ExactPoly::bilinear`]). A polynomial of degree n has n roots; a constant none.
    ///
    /// Errors: the zero polynomial ([`LtiError::ZeroPolynomial`]), or
    /// [`LtiError::BeyondExactBudget`] when the polynomial or its bilinear image (its
    /// coefficients grow by up to n bits) exceeds the exact budget.
    ///
    /// ```
    /// use ltikit::poly::exact::ExactPoly;
    /// // z − 1.0000000001: a root just outside, decided without tolerance.
    /// let c = ExactPoly::parse_descending(&["1", "-1.0000000001"]).unwrap()
    ///     .unit_circle_counts().unwrap();
    /// assert_eq!((c.inside, c.on, c.outside), (0, 0, 1));
    /// // (z − 1)²: a double root on the circle.
    /// let c = ExactPoly::parse_descending(&["1", "-2", "1"]).unwrap()
    ///     .unit_circle_counts().unwrap();
    /// assert_eq!((c.inside, c.on, c.outside), (0, 2, 0));
    /// ```
    pub fn unit_circle_counts(&self) -> Result<CircleCounts> {
        if self.is_zero() {
            return Err(LtiError::ZeroPolynomial {
                what: "polynomial".into(),
            });
        }
        self.check_budget()?;
        let q = bilinear_z(self.prim());
        check_sizes(q.deg(), q.max_bits())?;
        let drop = self.degree() - q.deg();
        let h = ExactPoly::from_integer_poly(q, &Rational::from_integer(1));
        let h = if h.degree() == 0 {
            super::sturm::HalfPlaneCounts::default()
        } else {
            h.half_plane_counts()?
        };
        Ok(CircleCounts {
            inside: h.lhp,
            on: h.axis + drop,
            outside: h.rhp,
        })
    }
}

impl Factor {
    /// The exactly decided side of the unit circle of each root of this square-free factor,
    /// in the order of [`Factor::roots`].
    ///
    /// The bilinear image of the factor is square-free too; its roots are certified with their
    /// exact half planes (as the factor's own), mapped back by z = (1 + w)/(1 − w) and matched
    /// to the factor's roots (nearest first). Errors: [`LtiError::BeyondExactBudget`] when the
    /// image exceeds the budget, its roots cannot be separated, or the matching contradicts a
    /// root's distance from the circle (a guard).
    ///
    /// ```
    /// use ltikit::poly::exact::{CircleSide, ExactPoly, certify};
    /// // z² + 1 over (z − 2)(z − 0.5): poles outside and inside, zeros ±j on the circle.
    /// let n = ExactPoly::parse_descending(&["1", "0", "1"]).unwrap();
    /// let d = ExactPoly::parse_descending(&["1", "-2.5", "1"]).unwrap();
    /// let s = certify(&n, &d).unwrap();
    /// for f in s.factors() {
    ///     for (r, side) in f.roots.iter().zip(f.circle_sides().unwrap()) {
    ///         let want = if r.value.norm() > 1.5 { CircleSide::Outside }
    ///             else if r.value.norm() < 0.9 { CircleSide::Inside } else { CircleSide::On };
    ///         assert_eq!(side, want);
    ///     }
    /// }
    /// ```
    pub fn circle_sides(&self) -> Result<Vec<CircleSide>> {
        let p = self.poly.prim();
        if *p == ZPoly::x() {
            return Ok(vec![CircleSide::Inside]);
        }
        let q = bilinear_z(p);
        check_sizes(q.deg(), q.max_bits())?;
        // candidates: (z, side) from the certified roots of the image
        let mut cand: Vec<(Complex64, CircleSide)> = Vec::with_capacity(p.deg());
        if q.deg() < p.deg() {
            cand.push((Complex64::new(-1.0, 0.0), CircleSide::On));
        }
        let q = q.primitive();
        let k = q.low_zeros();
        if k > 0 {
            cand.push((Complex64::new(1.0, 0.0), CircleSide::On));
        }
        let rest = q.shift_down(k).primitive();
        if rest.deg() > 0 {
            let (ws, _) = factor_roots(&rest)?;
            let one = Complex64::new(1.0, 0.0);
            for w in ws {
                let side = match w.side {
                    Side::Left => CircleSide::Inside,
                    Side::Axis => CircleSide::On,
                    Side::Right => CircleSide::Outside,
                };
                cand.push(((one + w.value) / (one - w.value), side));
            }
        }
        if cand.len() != self.roots.len() {
            return Err(beyond("internal: the bilinear image lost a root"));
        }
        // nearest pairs first (relative distance)
        let mut pairs: Vec<(f64, usize, usize)> = Vec::with_capacity(cand.len().pow(2));
        for (i, r) in self.roots.iter().enumerate() {
            for (j, (z, _)) in cand.iter().enumerate() {
                let d = (r.value - z).norm() / r.value.norm().max(1.0);
                pairs.push((d, i, j));
            }
        }
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut side: Vec<Option<CircleSide>> = vec![None; self.roots.len()];
        let mut used = vec![false; cand.len()];
        for (_, i, j) in pairs {
            if side[i].is_none() && !used[j] {
                side[i] = Some(cand[j].1);
                used[j] = true;
            }
        }
        self.roots
            .iter()
            .zip(side)
            .map(|(r, s)| {
                let s = s.ok_or_else(|| beyond("internal: a root was not matched"))?;
                // guard: a root clearly off the circle must have its side
                let m = r.value.norm();
                let clear = match s {
                    CircleSide::Inside => m < 1.0 + 1e-6,
                    CircleSide::On => (m - 1.0).abs() <= 1e-6,
                    CircleSide::Outside => m > 1.0 - 1e-6,
                };
                if clear {
                    Ok(s)
                } else {
                    Err(beyond(
                        "internal: the unit-circle sides disagree with the root values",
                    ))
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(t: &[&str]) -> ExactPoly {
        ExactPoly::parse_descending(t).unwrap()
    }

    fn counts(t: &[&str]) -> (usize, usize, usize) {
        let c = p(t).unit_circle_counts().unwrap();
        (c.inside, c.on, c.outside)
    }

    #[test]
    fn simple_cases() {
        assert_eq!(counts(&["1", "0", "1"]), (0, 2, 0)); // z² + 1
        assert_eq!(counts(&["1", "-2", "1"]), (0, 2, 0)); // (z − 1)²
        assert_eq!(counts(&["1", "1"]), (0, 1, 0)); // z + 1
        assert_eq!(counts(&["2", "-1"]), (1, 0, 0)); // 2z − 1
        assert_eq!(counts(&["1", "-2"]), (0, 0, 1)); // z − 2
        assert_eq!(counts(&["1", "0", "0"]), (2, 0, 0)); // z²
        assert_eq!(counts(&["3"]), (0, 0, 0));
        assert_eq!(counts(&["1", "2", "1"]), (0, 2, 0)); // (z + 1)²: degree drop of 2
        assert_eq!(counts(&["1", "-1.000000000001"]), (0, 0, 1));
        assert_eq!(counts(&["1", "-0.999999999999"]), (1, 0, 0));
        // (z + 1)(z − 0.5)(z − 3)
        let a = &(&p(&["1", "1"]) * &p(&["1", "-0.5"])) * &p(&["1", "-3"]);
        let c = a.unit_circle_counts().unwrap();
        assert_eq!((c.inside, c.on, c.outside), (1, 1, 1));
    }

    #[test]
    fn bilinear_of_the_circle_points() {
        // z − 1 → 2w: the root z = 1 is w = 0.
        assert_eq!(p(&["1", "-1"]).bilinear().to_string(), "2 s");
    }

    #[test]
    fn sides_of_a_mixed_factor() {
        // (z − (1 − 1e-20))(z² + 1): a root inside that rounds to 1, and ±j on the circle.
        let a = &p(&["1", "-0.99999999999999999999"]) * &p(&["1", "0", "1"]);
        let s = super::super::certify(&a, &ExactPoly::one()).unwrap();
        let f = &s.factors()[0];
        let sides = f.circle_sides().unwrap();
        for (r, side) in f.roots.iter().zip(sides) {
            if r.value.im == 0.0 {
                assert_eq!(side, CircleSide::Inside, "{}", r.value);
            } else {
                assert_eq!(side, CircleSide::On, "{}", r.value);
            }
        }
    }
}
