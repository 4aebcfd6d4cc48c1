//! [`ExactPoly`]: a polynomial with exact rational coefficients (descending at the interface).

use std::fmt;

use dashu_int::IBig;

use super::budget::{beyond, check_sizes};
use super::number::{Rational, ratio_to_f64};
use super::sqfree::square_free;
use super::sturm::{HalfPlaneCounts, count_real_roots, square_free_counts};
use super::zpoly::ZPoly;
use crate::error::{LtiError, Result};
use crate::poly::Poly;

/// A polynomial in s with exact rational coefficients, given in **descending** powers like
/// [`Poly`]. Stored as a rational scale times a primitive integer polynomial with a positive
/// leading coefficient, which is the form every exact algorithm works on.
///
/// ```
/// use ltikit::poly::exact::ExactPoly;
/// // s⁴ + 2.00000002 s² + 1.00000002 = (s² + 1)(s² + 1.00000002): exact, no rounding.
/// let p = ExactPoly::parse_descending(&["1", "0", "2.00000002", "0", "1.00000002"]).unwrap();
/// assert_eq!(p.degree(), 4);
/// let q = ExactPoly::parse_descending(&["1", "0", "1"]).unwrap();
/// let (quot, rem) = p.div_rem(&q).unwrap();
/// assert!(rem.is_zero());
/// assert_eq!(quot.to_string(), "s^2 + 50000001/50000000");
/// // Exact stability counts: four simple roots on the imaginary axis.
/// let h = p.half_plane_counts().unwrap();
/// assert_eq!((h.lhp, h.axis, h.rhp), (0, 4, 0));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExactPoly {
    /// Rational scale (0 for the zero polynomial).
    scale: Rational,
    /// Primitive, positive leading coefficient (the zero polynomial for 0).
    prim: ZPoly,
}

impl ExactPoly {
    /// Reads coefficients in descending powers from the tokens exactly as typed (decimals,
    /// exponents, fractions; see [`Rational::parse`]). Leading zeros are dropped.
    ///
    /// Errors: no tokens ([`LtiError::EmptyPolynomial`]) or a malformed token
    /// ([`LtiError::BadNumber`] naming it).
    ///
    /// ```
    /// use ltikit::poly::exact::ExactPoly;
    /// let p = ExactPoly::parse_descending(&["0", "1", "0.2", "1/100"]).unwrap();
    /// assert_eq!(p.to_string(), "s^2 + 1/5 s + 1/100"); // (s + 0.1)², exactly
    /// assert!(ExactPoly::parse_descending(&["1", "1/0"]).is_err());
    /// ```
    pub fn parse_descending<S: AsRef<str>>(tokens: &[S]) -> Result<ExactPoly> {
        ExactPoly::parse_descending_named(tokens, "polynomial")
    }

    /// As [`ExactPoly::parse_descending`], naming the polynomial in errors
    /// ("coefficient 2 of the denominator").
    pub fn parse_descending_named<S: AsRef<str>>(tokens: &[S], what: &str) -> Result<ExactPoly> {
        let c = tokens
            .iter()
            .enumerate()
            .map(|(i, t)| {
                Rational::parse_named(t.as_ref(), &format!("coefficient {i} of the {what}"))
            })
            .collect::<Result<Vec<_>>>()?;
        if c.is_empty() {
            return Err(LtiError::EmptyPolynomial { what: what.into() });
        }
        ExactPoly::from_rationals(&c)
    }

    /// From exact coefficients in descending powers. Errors on an empty slice.
    pub fn from_rationals(c: &[Rational]) -> Result<ExactPoly> {
        if c.is_empty() {
            return Err(LtiError::EmptyPolynomial {
                what: "polynomial".into(),
            });
        }
        // Common denominator L: L·c_i are integers.
        let mut l = dashu_int::UBig::ONE;
        for x in c {
            let d = x.denom();
            if !d.is_one() {
                let g = dashu_int::ops::Gcd::gcd(&l, d);
                l = &l / g * d;
            }
        }
        let li = IBig::from(l.clone());
        let ints: Vec<IBig> = c
            .iter()
            .rev()
            .map(|x| x.numer() * (&li / IBig::from(x.denom().clone())))
            .collect();
        Ok(ExactPoly::from_integer_poly(
            ZPoly::new(ints),
            &Rational::from_parts(IBig::ONE, li),
        ))
    }

    /// The exact values of f64 coefficients (descending): `0.1` is the double nearest 1/10,
    /// not 1/10. Errors on NaN/infinite values or an empty slice.
    pub fn from_f64_descending(c: &[f64]) -> Result<ExactPoly> {
        let r = c
            .iter()
            .map(|&x| Rational::from_f64(x))
            .collect::<Result<Vec<_>>>()?;
        ExactPoly::from_rationals(&r)
    }

    /// scale·p for an integer polynomial p.
    pub(crate) fn from_integer_poly(p: ZPoly, scale: &Rational) -> ExactPoly {
        if p.is_zero() || scale.is_zero() {
            return ExactPoly::zero();
        }
        let prim = p.primitive();
        // p = k·prim with k = lc(p)/lc(prim), an integer.
        let k = p.lc() / prim.lc();
        let s = Rational::from_parts(scale.numer() * k, IBig::from(scale.denom().clone()));
        ExactPoly { scale: s, prim }
    }

    /// The zero polynomial.
    pub fn zero() -> ExactPoly {
        ExactPoly {
            scale: Rational::from_integer(0),
            prim: ZPoly::new(Vec::new()),
        }
    }

    /// True for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.prim.is_zero()
    }

    /// Degree (0 for constants and for the zero polynomial).
    pub fn degree(&self) -> usize {
        self.prim.deg()
    }

    /// Coefficients in descending powers.
    pub fn coeffs(&self) -> Vec<Rational> {
        if self.is_zero() {
            return vec![Rational::from_integer(0)];
        }
        let n = IBig::from(self.scale.denom().clone());
        self.prim
            .coeffs()
            .iter()
            .rev()
            .map(|c| Rational::from_parts(c * self.scale.numer(), n.clone()))
            .collect()
    }

    /// Leading coefficient (0 for the zero polynomial).
    pub fn leading(&self) -> Rational {
        Rational::from_parts(
            self.prim.lc() * self.scale.numer(),
            IBig::from(self.scale.denom().clone()),
        )
    }

    /// The content: the rational c with self = c·(primitive integer polynomial with a positive
    /// leading coefficient). 0 for the zero polynomial.
    pub fn content(&self) -> Rational {
        self.scale.clone()
    }

    /// The primitive integer polynomial with a positive leading coefficient that is a rational
    /// multiple of self (zero for zero).
    pub fn primitive_part(&self) -> ExactPoly {
        ExactPoly {
            scale: if self.is_zero() {
                Rational::from_integer(0)
            } else {
                Rational::from_integer(1)
            },
            prim: self.prim.clone(),
        }
    }

    pub(crate) fn prim(&self) -> &ZPoly {
        &self.prim
    }

    /// Degree and coefficient size within the exact path's budget (errors with
    /// [`LtiError::BeyondExactBudget`](crate::LtiError::BeyondExactBudget) naming the size
    /// that is not).
    pub(crate) fn check_budget(&self) -> Result<()> {
        check_sizes(self.degree(), self.prim().max_bits())
    }

    /// The polynomial with each coefficient rounded to the nearest double (for the numerical
    /// steps). Errors when a coefficient overflows the doubles.
    ///
    /// ```
    /// use ltikit::poly::exact::ExactPoly;
    /// let p = ExactPoly::parse_descending(&["1", "1/3"]).unwrap();
    /// assert_eq!(p.to_poly().unwrap().coeffs(), &[1.0, 1.0 / 3.0]);
    /// ```
    pub fn to_poly(&self) -> Result<Poly> {
        let c: Vec<f64> = self
            .coeffs()
            .iter()
            .map(|x| ratio_to_f64(x.numer(), x.denom()))
            .collect();
        Poly::from_descending(&c)
    }

    /// First derivative.
    pub fn derivative(&self) -> ExactPoly {
        ExactPoly::from_integer_poly(self.prim.derivative(), &self.scale)
    }

    /// Exact division over ℚ: self = q·d + r with deg r < deg d. Errors when d is zero.
    pub fn div_rem(&self, d: &ExactPoly) -> Result<(ExactPoly, ExactPoly)> {
        if d.is_zero() {
            return Err(LtiError::ZeroPolynomial {
                what: "divisor".into(),
            });
        }
        if self.degree() < d.degree() || self.is_zero() {
            return Ok((ExactPoly::zero(), self.clone()));
        }
        // lc(D)^k·A = Q·D + R over ℤ (pseudo-division), so A/D = Q/lc^k, R/lc^k.
        let (a, b) = (&self.prim, &d.prim);
        let k = a.deg() - b.deg() + 1;
        let lk = b.lc().pow(k);
        let r = a.prem(b);
        // Q = (lc^k·A − R)/B exactly.
        let q = a
            .scale(&lk)
            .sub(&r)
            .div_exact(b)
            .ok_or_else(|| LtiError::invalid("internal: inexact pseudo-division"))?;
        let sa = &self.scale;
        let qs = Rational::from_parts(
            sa.numer() * IBig::from(d.scale.denom().clone()),
            IBig::from(sa.denom().clone()) * d.scale.numer() * &lk,
        );
        let rs = Rational::from_parts(sa.numer().clone(), IBig::from(sa.denom().clone()) * lk);
        Ok((
            ExactPoly::from_integer_poly(q, &qs),
            ExactPoly::from_integer_poly(r, &rs),
        ))
    }

    /// Greatest common divisor, as a primitive integer polynomial with a positive leading
    /// coefficient (gcd(0, 0) = 0). Modular algorithm with a certifying trial division.
    ///
    /// ```
    /// use ltikit::poly::exact::ExactPoly;
    /// let a = ExactPoly::parse_descending(&["1", "0.4", "0.03"]).unwrap(); // (s+0.1)(s+0.3)
    /// let b = ExactPoly::parse_descending(&["1", "0.8", "0.07"]).unwrap(); // (s+0.1)(s+0.7)
    /// assert_eq!(a.gcd(&b).unwrap().to_string(), "10 s + 1");
    /// ```
    pub fn gcd(&self, o: &ExactPoly) -> Result<ExactPoly> {
        if self.is_zero() && o.is_zero() {
            return Ok(ExactPoly::zero());
        }
        self.check_budget()?;
        o.check_budget()?;
        let (g, _, _) = super::modular::gcd_cofactors(&self.prim, &o.prim)
            .ok_or_else(|| beyond("the gcd's coefficients exceed the modular prime table"))?;
        Ok(ExactPoly::from_integer_poly(g, &Rational::from_integer(1)))
    }

    /// Square-free factorisation (Yun): self = c·Π fᵢ^i with fᵢ square-free, pairwise coprime,
    /// primitive with positive leading coefficients; returns the (fᵢ, i) with i increasing
    /// (c = [`ExactPoly::content`]). Roots at s = 0 are included (as the factor s).
    ///
    /// ```
    /// use ltikit::poly::exact::ExactPoly;
    /// // (s + 3)²(s + 3.5)·s = s⁴ + 9.5 s³ + 30 s² + 31.5 s
    /// let p = ExactPoly::parse_descending(&["1", "9.5", "30", "31.5", "0"]).unwrap();
    /// let f = p.square_free().unwrap();
    /// let shown: Vec<(String, usize)> = f.iter().map(|(q, i)| (q.to_string(), *i)).collect();
    /// assert_eq!(shown, [("2 s^2 + 7 s".to_string(), 1), ("s + 3".to_string(), 2)]);
    /// ```
    pub fn square_free(&self) -> Result<Vec<(ExactPoly, usize)>> {
        if self.degree() == 0 {
            return Ok(Vec::new());
        }
        self.check_budget()?;
        let f = square_free(&self.prim)
            .ok_or_else(|| beyond("a gcd's coefficients exceed the modular prime table"))?;
        Ok(f.into_iter()
            .map(|(p, i)| {
                (
                    ExactPoly::from_integer_poly(p, &Rational::from_integer(1)),
                    i,
                )
            })
            .collect())
    }

    /// Exact multiplicity of the root s = 0.
    pub fn zero_root_multiplicity(&self) -> usize {
        if self.is_zero() {
            0
        } else {
            self.prim.low_zeros()
        }
    }

    /// Number of distinct real roots (Sturm's theorem, exact).
    pub fn count_distinct_real_roots(&self) -> Result<usize> {
        if self.is_zero() {
            return Err(LtiError::ZeroPolynomial {
                what: "polynomial".into(),
            });
        }
        self.check_budget()?;
        count_real_roots(&self.prim).ok_or_else(|| beyond("internal: inexact subresultant"))
    }

    /// Roots in the open left half plane, on the imaginary axis and in the open right half
    /// plane, with multiplicity, decided exactly (Routh–Hurwitz through Cauchy indices, see
    /// the [module docs](crate::poly::exact)). Errors on the zero polynomial.
    ///
    /// ```
    /// use ltikit::poly::exact::ExactPoly;
    /// // s⁵ + 2s⁴ + 2s³ + 4s² + 11s + 10: a zero first element in the Routh array.
    /// let p = ExactPoly::parse_descending(&["1", "2", "2", "4", "11", "10"]).unwrap();
    /// let h = p.half_plane_counts().unwrap();
    /// assert_eq!((h.lhp, h.axis, h.rhp), (3, 0, 2));
    /// ```
    pub fn half_plane_counts(&self) -> Result<HalfPlaneCounts> {
        if self.is_zero() {
            return Err(LtiError::ZeroPolynomial {
                what: "polynomial".into(),
            });
        }
        self.check_budget()?;
        let k = self.prim.low_zeros();
        let mut total = HalfPlaneCounts {
            axis: k,
            ..HalfPlaneCounts::default()
        };
        let rest = self.prim.shift_down(k);
        if rest.deg() == 0 {
            return Ok(total);
        }
        let sf = square_free(&rest)
            .ok_or_else(|| beyond("a gcd's coefficients exceed the modular prime table"))?;
        for (f, i) in sf {
            let (h, _) =
                square_free_counts(&f).ok_or_else(|| beyond("internal: inexact subresultant"))?;
            total = total.plus(&h.times(i));
        }
        Ok(total)
    }
}

impl std::ops::Add for &ExactPoly {
    type Output = ExactPoly;
    fn add(self, o: &ExactPoly) -> ExactPoly {
        if self.is_zero() {
            return o.clone();
        }
        if o.is_zero() {
            return self.clone();
        }
        // a/b·P + c/d·Q = (a·d·P + c·b·Q)/(b·d)
        let (a, b) = (self.scale.numer(), IBig::from(self.scale.denom().clone()));
        let (c, d) = (o.scale.numer(), IBig::from(o.scale.denom().clone()));
        let p = self.prim.scale(&(a * &d)).add(&o.prim.scale(&(c * &b)));
        ExactPoly::from_integer_poly(p, &Rational::from_parts(IBig::ONE, b * d))
    }
}

impl std::ops::Neg for &ExactPoly {
    type Output = ExactPoly;
    fn neg(self) -> ExactPoly {
        ExactPoly::from_integer_poly(self.prim.neg(), &self.scale)
    }
}

impl std::ops::Sub for &ExactPoly {
    type Output = ExactPoly;
    fn sub(self, o: &ExactPoly) -> ExactPoly {
        self + &(-o)
    }
}

impl std::ops::Mul for &ExactPoly {
    type Output = ExactPoly;
    fn mul(self, o: &ExactPoly) -> ExactPoly {
        let s = Rational::from_parts(
            self.scale.numer() * o.scale.numer(),
            IBig::from(self.scale.denom() * o.scale.denom()),
        );
        ExactPoly::from_integer_poly(self.prim.mul(&o.prim), &s)
    }
}

impl fmt::Display for ExactPoly {
    /// Descending powers with exact coefficients: `s^2 + 1/5 s + 1/100`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let c = self.coeffs();
        let n = c.len() - 1;
        let mut first = true;
        for (i, x) in c.iter().enumerate() {
            let k = n - i;
            if x.is_zero() && n != 0 {
                continue;
            }
            let neg = x.signum() < 0;
            let mag = if neg {
                Rational::from_parts(-x.numer().clone(), IBig::from(x.denom().clone()))
            } else {
                x.clone()
            };
            if first {
                if neg {
                    f.write_str("-")?;
                }
            } else {
                f.write_str(if neg { " - " } else { " + " })?;
            }
            first = false;
            let one = mag == Rational::from_integer(1);
            match k {
                0 => write!(f, "{mag}")?,
                _ => {
                    if !one {
                        write!(f, "{mag} ")?;
                    }
                    if k == 1 {
                        f.write_str("s")?;
                    } else {
                        write!(f, "s^{k}")?;
                    }
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(t: &[&str]) -> ExactPoly {
        ExactPoly::parse_descending(t).unwrap()
    }

    #[test]
    fn arithmetic_is_exact() {
        let a = p(&["1", "0.1"]);
        let b = p(&["1", "0.3"]);
        assert_eq!(&a * &b, p(&["1", "0.4", "0.03"]));
        assert_eq!(&(&a * &b) - &(&a * &a), p(&["0.2", "0.02"]));
        assert_eq!(&a + &(-&a), ExactPoly::zero());
        assert_eq!(p(&["3", "2", "1"]).derivative(), p(&["6", "2"]));
        let (q, r) = p(&["1", "0", "0", "2"]).div_rem(&p(&["2", "1"])).unwrap();
        assert_eq!(q, p(&["1/2", "-1/4", "1/8"]));
        assert_eq!(r, p(&["15/8"]));
        assert_eq!(p(&["0", "0"]).to_string(), "0");
        assert_eq!(p(&["-2", "0", "-1/3"]).to_string(), "-2 s^2 - 1/3");
        assert_eq!(p(&["-4", "6"]).content(), Rational::from_integer(-2));
        assert_eq!(p(&["1", "2", "0", "0"]).zero_root_multiplicity(), 2);
    }

    #[test]
    fn f64_input_means_the_binary_value() {
        // The f64 0.1 is not 1/10: (s + 0.1)² typed as f64 is not a perfect square exactly.
        let f = ExactPoly::from_f64_descending(&[1.0, 0.2, 0.01]).unwrap();
        assert_eq!(f.square_free().unwrap().len(), 1);
        assert_eq!(f.square_free().unwrap()[0].1, 1);
        let t = p(&["1", "0.2", "0.01"]);
        assert_eq!(t.square_free().unwrap()[0].1, 2);
    }
}
