//! Partial fractions G(s) = Σ rₖ/(s − pₖ)^k + direct polynomial.
//!
//! # Method (DESIGN §3)
//! For each distinct pole p of multiplicity m (exact multiplicities from [`Poly::roots`]) the
//! residues r₁ … r_m are the first m Taylor coefficients at p of N(s)/D_p(s), where D_p is the
//! denominator without (s − p)^m:
//!
//! N(p + h)/D(p + h) = h^(−m) · Σⱼ cⱼ hʲ,  cⱼ = residue of 1/(s − p)^(m − j).
//!
//! N is Taylor-shifted to p by repeated synthetic division ([`Poly::taylor_at`]). The series of
//! 1/D_p(p + h) is taken from the factored denominator, lead · Π_{q ≠ p} (p − q + h)^(m_q), as
//! a product of binomial series. In exact arithmetic this is the same as shifting the
//! coefficients of D and dropping the first m Taylor coefficients; in floating point it keeps
//! the expansion *consistent with the poles that are used*: the partial fractions are exactly
//! those of N/(lead·Π(s − q)^(m_q)), so the residues of two poles 5e-4 apart (≈ ±1000) cancel
//! as they must. Shifting the coefficients of D instead evaluates D's Taylor coefficients at a
//! pole that is off by ~1e-13, which gives such residues relative errors of ~1e-9; measured on
//! (s + 0.5)/((s + 1)(s + 1.0005)(s + 2)) that recomposes G only to 5e-8 relative (1e-3 once a
//! factor s² + s + 3 is added), against 3e-13 (4e-11) here — and 1e-16 relative to the size of
//! the terms, which is all the rounding of the residues themselves allows where they cancel.
//! There is no linear solve and no clustering tolerance: poles are as distinct as
//! [`Poly::roots`] says they are.
//!
//! Conjugate pairs: the residues of the lower member are the exact conjugates of the upper
//! member's; the residues of real poles are exactly real.

use num_complex::Complex64;
use serde::Serialize;

use crate::analysis::factored::series::{normalised_series, series_mul};
use crate::analysis::factored::{Factored, ScaledProduct};
use crate::error::{LtiError, Result};
use crate::lti::TransferFunction;
use crate::poly::{Poly, Root};

/// One term residue/(s − pole)^power.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PfTerm {
    /// The pole (serialised as `[re, im]`).
    pub pole: Complex64,
    /// The power k ≥ 1 of (s − pole).
    pub power: usize,
    /// The coefficient (serialised as `[re, im]`).
    pub residue: Complex64,
}

/// A partial-fraction expansion: G(s) = Σ residue/(s − pole)^power + direct polynomial.
///
/// Terms are grouped by pole (poles in the order of [`Poly::roots`]: decreasing real part, a
/// conjugate pair as +, −), powers ascending within a pole, every power from 1 to the
/// multiplicity listed (a coefficient may be 0). Serialises to the JSON contract
/// `{"terms": [{"pole": [re, im], "power": k, "residue": [re, im]}], "direct": [c…]}`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PartialFractions {
    /// The fractions.
    pub terms: Vec<PfTerm>,
    /// The polynomial part in **descending** powers; empty for a strictly proper G.
    pub direct: Vec<f64>,
}

impl PartialFractions {
    /// The terms grouped by pole (exact equality), in order of first appearance, the residue
    /// of 1/(s − p)^j at index j − 1; a conjugate pair by its upper member only. The closed
    /// forms in t and in k are built from these groups.
    pub(crate) fn by_pole(&self) -> Vec<(Complex64, Vec<Complex64>)> {
        let mut groups: Vec<(Complex64, Vec<Complex64>)> = Vec::new();
        for t in &self.terms {
            if t.pole.im < 0.0 {
                continue;
            }
            let k = match groups.iter().position(|(p, _)| *p == t.pole) {
                Some(k) => k,
                None => {
                    groups.push((t.pole, Vec::new()));
                    groups.len() - 1
                }
            };
            let g = &mut groups[k].1;
            if g.len() < t.power {
                g.resize(t.power, Complex64::new(0.0, 0.0));
            }
            g[t.power - 1] += t.residue;
        }
        groups
    }
}

impl PartialFractions {
    /// Value of the expansion at s (a pole gives an infinite or NaN value).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use num_complex::Complex64;
    /// let g = TransferFunction::from_descending(&[1.0, 3.0], &[1.0, 3.0, 2.0]).unwrap();
    /// let pf = g.partial_fractions().unwrap();
    /// let s = Complex64::new(0.3, 2.0);
    /// assert!((pf.eval(s) - g.eval(s)).norm() < 1e-15);
    /// ```
    pub fn eval(&self, s: Complex64) -> Complex64 {
        let mut acc = Complex64::new(0.0, 0.0);
        for t in &self.terms {
            acc += t.residue / (s - t.pole).powu(t.power as u32);
        }
        let mut d = Complex64::new(0.0, 0.0);
        for &c in &self.direct {
            d = d * s + c;
        }
        acc + d
    }

    /// The direct polynomial as a [`Poly`] (the zero polynomial when there is none).
    pub fn direct_poly(&self) -> Poly {
        if self.direct.is_empty() {
            Poly::zero()
        } else {
            Poly::trimmed(self.direct.clone())
        }
    }
}

/// Partial fractions of any rational N/D (proper or not, no cancellation performed: a common
/// root of N and D gets residues at rounding level).
///
/// Errors: D is the zero polynomial, NaN/∞ in the result (overflowing residues), and the
/// errors of [`Poly::roots`].
///
/// ```
/// use ltikit::{Poly, analysis::pfe::partial_fractions};
/// // (s² + 1)/(s + 1)² = 1 + (−2)/(s + 1) + 2/(s + 1)²
/// let n = Poly::from_descending(&[1.0, 0.0, 1.0]).unwrap();
/// let d = Poly::from_descending(&[1.0, 2.0, 1.0]).unwrap();
/// let pf = partial_fractions(&n, &d).unwrap();
/// assert_eq!(pf.direct, vec![1.0]);
/// assert_eq!(pf.terms.len(), 2);
/// assert_eq!((pf.terms[0].power, pf.terms[0].residue.re), (1, -2.0));
/// assert_eq!((pf.terms[1].power, pf.terms[1].residue.re), (2, 2.0));
/// ```
pub fn partial_fractions(num: &Poly, den: &Poly) -> Result<PartialFractions> {
    if den.is_zero() {
        return Err(LtiError::ZeroPolynomial {
            what: "denominator".into(),
        });
    }
    let roots = den.roots()?;
    partial_fractions_with_poles(num, den, &roots)
}

/// Partial fractions of N/D when the roots of D are already known (`poles` must be the roots
/// of `den` with multiplicities, conjugate pairs exact).
pub(crate) fn partial_fractions_with_poles(
    num: &Poly,
    den: &Poly,
    poles: &[Root],
) -> Result<PartialFractions> {
    let direct = if num.degree() >= den.degree() && !num.is_zero() {
        let (q, _) = num.div_rem(den)?;
        if q.is_zero() {
            Vec::new()
        } else {
            q.coeffs().to_vec()
        }
    } else {
        Vec::new()
    };
    let terms = principal_parts(num, den.leading(), poles)?;
    Ok(PartialFractions { terms, direct })
}

/// The principal parts of N/(lead·Π(s − p)^m) at every pole: terms grouped by pole, powers
/// 1..=m ascending. An empty list for N = 0.
pub(crate) fn principal_parts(num: &Poly, lead: f64, poles: &[Root]) -> Result<Vec<PfTerm>> {
    if num.is_zero() {
        return Ok(Vec::new());
    }
    principal_parts_with(poles, |i| laurent_head(num, lead, poles, i))
}

/// The principal parts of gain·Π(s − z)^k / Π(s − p)^m (a monic denominator) at every pole,
/// from the factors alone: the Laurent head at p is S·Π(1 + h/(p − z))^k·Π(1 + h/(p − q))^(−m)
/// with the scalar S = gain·Π(p − z)^k/Π(p − q)^m kept in scaled form, so hundreds of
/// factors neither overflow nor underflow.
pub(crate) fn principal_parts_factored(
    gain: f64,
    zeros: &[Root],
    poles: &[Root],
) -> Result<Vec<PfTerm>> {
    if gain == 0.0 {
        return Ok(Vec::new());
    }
    principal_parts_with(poles, |i| {
        let p = poles[i].value;
        let m = poles[i].multiplicity;
        let mut scalar = ScaledProduct::new(Complex64::new(gain, 0.0));
        let mut up = Vec::with_capacity(zeros.len());
        let mut down = Vec::with_capacity(poles.len());
        for z in zeros {
            let a = p - z.value;
            scalar.mul_pow(a, z.multiplicity);
            up.push((a, z.multiplicity));
        }
        for (j, q) in poles.iter().enumerate() {
            if j != i && q.multiplicity > 0 {
                let a = p - q.value;
                scalar.div_pow(a, q.multiplicity);
                down.push((a, q.multiplicity));
            }
        }
        let s = scalar.value();
        let c: Vec<Complex64> = normalised_series(&up, &down, m)
            .into_iter()
            .map(|x| x * s)
            .collect();
        check_residues(&c, p, m)?;
        Ok(c)
    })
}

/// Shared bookkeeping of the principal parts: `head(i)` gives c₀ … c_{m−1}, the Taylor
/// coefficients of (s − pᵢ)^m·G at pᵢ; conjugate pairs get exactly conjugate residues and
/// real poles exactly real ones.
fn principal_parts_with(
    poles: &[Root],
    head: impl Fn(usize) -> Result<Vec<Complex64>>,
) -> Result<Vec<PfTerm>> {
    let mut terms = Vec::new();
    for (i, p) in poles.iter().enumerate() {
        let m = p.multiplicity;
        if m == 0 {
            continue;
        }
        if p.value.im < 0.0 {
            // The conjugate partner (listed among the poles) is handled by the upper member;
            // if the caller's list lacks it, compute directly.
            if let Some(upper) = terms_of_upper(&terms, p.value.conj(), m) {
                terms.extend(upper);
                continue;
            }
        }
        let c = head(i)?;
        let real = p.value.im == 0.0;
        for (j, cj) in c.iter().enumerate().rev() {
            let residue = if real {
                Complex64::new(cj.re, 0.0)
            } else {
                *cj
            };
            terms.push(PfTerm {
                pole: p.value,
                power: m - j,
                residue,
            });
        }
    }
    Ok(terms)
}

/// The polynomial part of gain·Π(s − z)^k/Π(s − p)^m (descending; empty when strictly
/// proper), from its Laurent expansion at infinity:
/// gain·s^d·Π(1 − z/s)^k/Π(1 − p/s)^m, d = deg N − deg D.
pub(crate) fn direct_factored(gain: f64, zeros: &[Root], poles: &[Root]) -> Vec<f64> {
    let nz: usize = zeros.iter().map(|r| r.multiplicity).sum();
    let np: usize = poles.iter().map(|r| r.multiplicity).sum();
    if gain == 0.0 || nz < np {
        return Vec::new();
    }
    let d = nz - np;
    // (1 − r x) = (1 + x/a) with a = −1/r
    let term = |r: &Root| {
        (!r.is_origin()).then(|| (-crate::numeric::complex::recip(r.value), r.multiplicity))
    };
    let up: Vec<(Complex64, usize)> = zeros.iter().filter_map(term).collect();
    let down: Vec<(Complex64, usize)> = poles.iter().filter_map(term).collect();
    normalised_series(&up, &down, d + 1)
        .into_iter()
        .map(|c| gain * c.re)
        .collect()
}

/// Conjugates of the already computed terms of `upper` (power ascending), if present.
fn terms_of_upper(terms: &[PfTerm], upper: Complex64, m: usize) -> Option<Vec<PfTerm>> {
    let found: Vec<PfTerm> = terms
        .iter()
        .filter(|t| t.pole == upper)
        .map(|t| PfTerm {
            pole: upper.conj(),
            power: t.power,
            residue: t.residue.conj(),
        })
        .collect();
    (found.len() == m).then_some(found)
}

/// c₀ … c_{m−1}: the Taylor coefficients at p = poles\[i\] of N(s)/D_p(s), with
/// D_p(s) = lead · Π_{j ≠ i} (s − q_j)^(m_j).
fn laurent_head(num: &Poly, lead: f64, poles: &[Root], i: usize) -> Result<Vec<Complex64>> {
    let p = poles[i].value;
    let m = poles[i].multiplicity;
    // 1/D_p(p + h) = S·Π(1 + h/a)^(−k), a = p − q, S = Π a^(−k)/lead kept in scaled form
    let mut scalar = ScaledProduct::new(Complex64::new(1.0 / lead, 0.0));
    let mut down = Vec::with_capacity(poles.len());
    for (j, q) in poles.iter().enumerate() {
        if j == i || q.multiplicity == 0 {
            continue;
        }
        let a = p - q.value;
        scalar.div_pow(a, q.multiplicity);
        down.push((a, q.multiplicity));
    }
    let inv = normalised_series(&[], &down, m);
    let n = num.taylor_at(p, m);
    let c: Vec<Complex64> = series_mul(&n, &inv)
        .into_iter()
        .map(|x| {
            let mut v = scalar;
            v.mul(x);
            v.value()
        })
        .collect();
    check_residues(&c, p, m)?;
    Ok(c)
}

/// Errors when a residue is not finite (poles too close or too far apart to represent).
fn check_residues(c: &[Complex64], p: Complex64, m: usize) -> Result<()> {
    for (j, x) in c.iter().enumerate() {
        if !(x.re.is_finite() && x.im.is_finite()) {
            return Err(LtiError::NonFinite {
                what: format!(
                    "the residue of power {} at the pole {} + {}j (the poles are too close or too far apart to represent)",
                    m - j,
                    p.re,
                    p.im
                ),
                value: if x.re.is_finite() { x.im } else { x.re },
            });
        }
    }
    Ok(())
}

impl TransferFunction {
    /// Partial fractions of G in lowest terms (cancelled pole/zero pairs removed first, see
    /// [`TransferFunction::pole_zero`]), with the poles exactly as `pole_zero` reports them.
    /// Works for improper G too (the direct polynomial then has degree ≥ 1).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // 1/(s (s + 1)²) = 1/s − 1/(s + 1) − 1/(s + 1)²
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 2.0, 1.0, 0.0]).unwrap();
    /// let pf = g.partial_fractions().unwrap();
    /// let got: Vec<(f64, usize, f64)> =
    ///     pf.terms.iter().map(|t| (t.pole.re, t.power, t.residue.re)).collect();
    /// assert_eq!(got, vec![(0.0, 1, 1.0), (-1.0, 1, -1.0), (-1.0, 2, -1.0)]);
    /// assert!(pf.direct.is_empty());
    /// ```
    pub fn partial_fractions(&self) -> Result<PartialFractions> {
        self.factored()?.partial_fractions()
    }
}

impl Factored {
    /// Partial fractions of G in lowest terms, with the reduced poles of the factored form.
    /// From coefficients the numerator's Taylor coefficients come from the reduced
    /// coefficients; from factors everything comes from the factors.
    ///
    /// ```
    /// use ltikit::analysis::Factored;
    /// use ltikit::Root;
    /// use num_complex::Complex64 as C;
    /// // 1/(s + 1)^12: one term of power 12 with residue 1, exactly.
    /// let f = Factored::from_zpk(&[], &[Root::new(C::new(-1.0, 0.0), 12)], 1.0).unwrap();
    /// let pf = f.partial_fractions().unwrap();
    /// assert_eq!(pf.terms.len(), 12);
    /// assert_eq!(pf.terms[11].residue, C::new(1.0, 0.0));
    /// assert!(pf.terms[..11].iter().all(|t| t.residue == C::new(0.0, 0.0)));
    /// ```
    pub fn partial_fractions(&self) -> Result<PartialFractions> {
        match self.source().coefficients() {
            Some(c) => {
                partial_fractions_with_poles(c.reduced.num(), c.reduced.den(), self.reduced_poles())
            }
            None => Ok(PartialFractions {
                terms: principal_parts_factored(
                    self.gain(),
                    self.reduced_zeros(),
                    self.reduced_poles(),
                )?,
                direct: direct_factored(self.gain(), self.reduced_zeros(), self.reduced_poles()),
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(re: f64, im: f64) -> Complex64 {
        Complex64::new(re, im)
    }

    #[test]
    fn simple_real_poles() {
        // (s + 3)/((s + 1)(s + 2)) = 2/(s + 1) − 1/(s + 2)
        let n = Poly::from_descending(&[1.0, 3.0]).unwrap();
        let d = Poly::from_descending(&[1.0, 3.0, 2.0]).unwrap();
        let pf = partial_fractions(&n, &d).unwrap();
        assert_eq!(pf.terms.len(), 2);
        assert!((pf.terms[0].residue - c(2.0, 0.0)).norm() < 1e-15);
        assert!((pf.terms[1].residue - c(-1.0, 0.0)).norm() < 1e-15);
        assert!(pf.direct.is_empty());
    }

    #[test]
    fn conjugate_pair_residues_are_exact_conjugates() {
        // 1/(s² + 2s + 5): poles −1 ± 2j, residues ∓j/4
        let n = Poly::constant(1.0);
        let d = Poly::from_descending(&[1.0, 2.0, 5.0]).unwrap();
        let pf = partial_fractions(&n, &d).unwrap();
        assert_eq!(pf.terms.len(), 2);
        let (a, b) = (pf.terms[0], pf.terms[1]);
        assert_eq!(a.pole, b.pole.conj());
        assert_eq!(a.residue, b.residue.conj());
        assert!((a.residue - c(0.0, -0.25)).norm() < 1e-16);
    }

    #[test]
    fn improper_gets_direct_polynomial() {
        // (s³ + 2)/(s + 1) = s² − s + 1 + 1/(s + 1)
        let n = Poly::from_descending(&[1.0, 0.0, 0.0, 2.0]).unwrap();
        let d = Poly::from_descending(&[1.0, 1.0]).unwrap();
        let pf = partial_fractions(&n, &d).unwrap();
        assert_eq!(pf.direct, vec![1.0, -1.0, 1.0]);
        assert!((pf.terms[0].residue - c(1.0, 0.0)).norm() < 1e-15);
    }

    #[test]
    fn zero_numerator_and_constant_denominator() {
        let pf =
            partial_fractions(&Poly::zero(), &Poly::from_descending(&[1.0, 1.0]).unwrap()).unwrap();
        assert!(pf.terms.is_empty() && pf.direct.is_empty());
        let pf = partial_fractions(&Poly::constant(3.0), &Poly::constant(2.0)).unwrap();
        assert!(pf.terms.is_empty());
        assert_eq!(pf.direct, vec![1.5]);
        assert!(partial_fractions(&Poly::constant(1.0), &Poly::zero()).is_err());
    }

    #[test]
    fn tf_method_uses_reduced_form() {
        // (s + 1)/((s + 1)(s + 2)) → 1/(s + 2): one term.
        let g = TransferFunction::from_descending(&[1.0, 1.0], &[1.0, 3.0, 2.0]).unwrap();
        let pf = g.partial_fractions().unwrap();
        assert_eq!(pf.terms.len(), 1);
        assert!((pf.terms[0].pole - c(-2.0, 0.0)).norm() < 1e-14);
        assert!((pf.terms[0].residue - c(1.0, 0.0)).norm() < 1e-14);
    }

    #[test]
    fn json_shape() {
        let g = TransferFunction::from_descending(&[1.0, 0.0], &[1.0, 1.0]).unwrap();
        let pf = g.partial_fractions().unwrap();
        let j = serde_json::to_string(&pf).unwrap();
        assert_eq!(
            j,
            r#"{"terms":[{"pole":[-1.0,0.0],"power":1,"residue":[-1.0,0.0]}],"direct":[1.0]}"#
        );
    }
}
