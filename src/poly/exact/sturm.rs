//! Exact root counting: Sturm sequences, Cauchy indices, and the half-plane counts of
//! Routh–Hurwitz with every singular case decided exactly.
//!
//! The signed remainder sequence f₀, f₁, f₂ = −rem(f₀, f₁), … is computed as a subresultant
//! pseudo-remainder sequence over ℤ (exact divisions keep the coefficients at the size of the
//! subresultants) with the sign of each member corrected so that it is a *positive* multiple of
//! the true member. Then, for a < b not roots of f₀, V(a) − V(b) (sign variations) is the Cauchy
//! index of f₁/f₀ on (a, b) — with f₁ = f₀′ the number of distinct real roots in (a, b].
//!
//! Half planes (for a square-free b with b(0) ≠ 0): write b(s) = E(s²) + s·O(s²).
//! 1. Roots symmetric about the origin (s and −s both roots) are the roots of g(s²),
//!    g = gcd(E, O). A negative real root x of g gives the pair ±j√(−x) on the imaginary axis;
//!    any other root of g gives one root in each open half plane. So g contributes
//!    2·#{negative real roots of g} axis roots and deg g − that many in each half plane.
//! 2. c = b / g(s²) = Ẽ(s²) + s·Õ(s²) has no roots on the axis. As ω runs over ℝ the argument of
//!    c(jω) = Ẽ(−ω²) + jω·Õ(−ω²) increases by π·(n_L − n_R). Counting its crossings of multiples
//!    of π gives n_L − n_R = −2·Ind₍₋∞,₀₎(Ẽ/Õ) + J₀ + T, where the Cauchy index is in x = −ω²
//!    (ω > 0 maps onto x < 0 with the orientation reversed), J₀ = ±1 is the crossing at ω = 0
//!    and T ∈ {−1, 0, 1} the fractional turn at ω = ±∞. Degree drops in the remainder sequence
//!    (the "zero first element" of a Routh array) need no special treatment: the Cauchy index
//!    counts them correctly; the "zero row" is step 1.

use dashu_int::IBig;

use super::modular::gcd_cofactors;
use super::zpoly::{ZPoly, sign};

/// Roots in the open left half plane, on the imaginary axis and in the open right half plane,
/// counted with multiplicity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct HalfPlaneCounts {
    /// Roots with Re s < 0.
    pub lhp: usize,
    /// Roots with Re s = 0 (the root s = 0 included).
    pub axis: usize,
    /// Roots with Re s > 0.
    pub rhp: usize,
}

impl HalfPlaneCounts {
    /// Total number of roots.
    pub fn total(&self) -> usize {
        self.lhp + self.axis + self.rhp
    }

    /// These counts times `m`.
    pub fn times(&self, m: usize) -> HalfPlaneCounts {
        HalfPlaneCounts {
            lhp: self.lhp * m,
            axis: self.axis * m,
            rhp: self.rhp * m,
        }
    }

    /// Sum of two counts.
    pub fn plus(&self, o: &HalfPlaneCounts) -> HalfPlaneCounts {
        HalfPlaneCounts {
            lhp: self.lhp + o.lhp,
            axis: self.axis + o.axis,
            rhp: self.rhp + o.rhp,
        }
    }
}

/// The signed remainder sequence of (f0, f1), each member a positive multiple of the true one.
/// Ends with (a multiple of) gcd(f0, f1). `None` only if an exact division fails (a bug guard).
pub(crate) fn remainder_sequence(f0: &ZPoly, f1: &ZPoly) -> Option<Vec<ZPoly>> {
    let mut seq = vec![f0.clone()];
    if f1.is_zero() {
        return Some(seq);
    }
    seq.push(f1.clone());
    if f0.is_zero() {
        return Some(seq);
    }
    // With deg f1 > deg f0 the first remainder is f0 itself: f2 = −f0.
    let (mut prev, mut cur) = if f1.deg() > f0.deg() {
        let f2 = f0.neg();
        seq.push(f2.clone());
        (f1.clone(), f2)
    } else {
        (f0.clone(), f1.clone())
    };
    // Signs ε with (sequence member) = ε·(subresultant member).
    let (mut eps_prev, mut eps_cur) = (1i32, 1i32);
    let mut d = prev.deg() - cur.deg();
    let mut beta = if d % 2 == 0 { -IBig::ONE } else { IBig::ONE }; // (−1)^(d+1)
    let mut psi = -IBig::ONE;
    while cur.deg() > 0 {
        let r = prev.prem(&cur);
        if r.is_zero() {
            break;
        }
        let next = exact_div_scalar(&r, &beta)?;
        // −rem(F_prev, F_cur) = −ε_prev·β·next / lc(cur)^(d+1)  (rem is linear in the dividend)
        let lc_sign = cur.lc_sign();
        let lc_pow_sign = if (d + 1) % 2 == 0 { 1 } else { lc_sign };
        let eps_next = -eps_prev * sign(&beta) * lc_pow_sign;
        seq.push(if eps_next > 0 {
            next.clone()
        } else {
            next.neg()
        });
        // Subresultant recurrences: ψ ← (−lc)^d / ψ^(d−1), β ← −lc·ψ^(d′).
        let lc = cur.lc();
        let d_next = cur.deg() - next.deg();
        psi = if d == 0 {
            psi
        } else {
            let num = pow(&-lc.clone(), d);
            let den = pow(&psi, d - 1);
            exact_div(&num, &den)?
        };
        beta = -lc * pow(&psi, d_next);
        prev = cur;
        cur = next;
        eps_prev = eps_cur;
        eps_cur = eps_next;
        d = d_next;
    }
    Some(seq)
}

fn pow(x: &IBig, e: usize) -> IBig {
    x.pow(e)
}

fn exact_div(a: &IBig, b: &IBig) -> Option<IBig> {
    use dashu_int::ops::DivRem;
    let (q, r) = a.div_rem(b);
    r.is_zero().then_some(q)
}

fn exact_div_scalar(p: &ZPoly, k: &IBig) -> Option<ZPoly> {
    let mut c = Vec::with_capacity(p.coeffs().len());
    for x in p.coeffs() {
        c.push(exact_div(x, k)?);
    }
    Some(ZPoly::new(c))
}

/// Sign variations of a list of signs (zeros skipped).
fn variations(signs: impl Iterator<Item = i32>) -> usize {
    let mut last = 0;
    let mut v = 0;
    for s in signs.filter(|&s| s != 0) {
        if last != 0 && s != last {
            v += 1;
        }
        last = s;
    }
    v
}

/// Where a sequence is evaluated.
#[derive(Clone, Copy)]
enum At {
    MinusInf,
    PlusInf,
    LeftOfZero,
}

fn v_at(seq: &[ZPoly], at: At) -> usize {
    variations(seq.iter().map(|p| match at {
        At::MinusInf => p.sign_at_infinity(false),
        At::PlusInf => p.sign_at_infinity(true),
        At::LeftOfZero => p.sign_left_of_zero(),
    }))
}

/// Number of distinct real roots of a non-zero polynomial.
pub(crate) fn count_real_roots(p: &ZPoly) -> Option<usize> {
    if p.deg() == 0 {
        return Some(0);
    }
    let seq = remainder_sequence(p, &p.derivative())?;
    Some(v_at(&seq, At::MinusInf) - v_at(&seq, At::PlusInf))
}

/// Number of distinct negative real roots of a non-zero polynomial.
pub(crate) fn count_negative_roots(p: &ZPoly) -> Option<usize> {
    if p.deg() == 0 {
        return Some(0);
    }
    let seq = remainder_sequence(p, &p.derivative())?;
    Some(v_at(&seq, At::MinusInf) - v_at(&seq, At::LeftOfZero))
}

/// Half-plane counts of a square-free polynomial b with b(0) ≠ 0, and the polynomial g with
/// g(s²) the factor of b whose roots come in pairs ±s (module docs, step 1).
pub(crate) fn square_free_counts(b: &ZPoly) -> Option<(HalfPlaneCounts, ZPoly)> {
    let (e, o) = b.even_odd();
    let (g, _, _) = gcd_cofactors(&e, &o)?;
    let mut counts = HalfPlaneCounts::default();
    if g.deg() > 0 {
        let neg = count_negative_roots(&g)?;
        counts.axis = 2 * neg;
        counts.lhp = g.deg() - neg;
        counts.rhp = g.deg() - neg;
    }
    let c = if g.deg() > 0 {
        b.div_exact(&g.of_square())?
    } else {
        b.clone()
    };
    let m = c.deg();
    if m == 0 {
        return Some((counts, g));
    }
    let (e, o) = c.even_odd();
    // Õ ≠ 0: otherwise c = Ẽ(s²) and gcd(Ẽ, Õ) = Ẽ would be a constant, i.e. m = 0.
    let seq = remainder_sequence(&o, &e)?;
    let ind_x = v_at(&seq, At::MinusInf) as i64 - v_at(&seq, At::LeftOfZero) as i64;
    let k = o.low_zeros();
    let parity = if k % 2 == 0 { 1 } else { -1 };
    let j0 = i64::from(sign(&e.coeff(0)) * parity * sign(&o.coeff(k)));
    let t = if m % 2 == 0 {
        if e.sign_at_infinity(false) * o.sign_at_infinity(false) > 0 {
            -1
        } else {
            1
        }
    } else {
        0
    };
    let diff = -2 * ind_x + j0 + t; // n_L − n_R
    let m = m as i64;
    if (m + diff) % 2 != 0 || diff.abs() > m {
        return None; // cannot happen; guards the arithmetic below
    }
    counts.lhp += ((m + diff) / 2) as usize;
    counts.rhp += ((m - diff) / 2) as usize;
    Some((counts, g))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// From descending integer coefficients.
    fn zd(c: &[i64]) -> ZPoly {
        ZPoly::new(c.iter().rev().map(|&x| IBig::from(x)).collect())
    }

    fn counts(c: &[i64]) -> (usize, usize, usize) {
        let (h, _) = square_free_counts(&zd(c)).unwrap();
        (h.lhp, h.axis, h.rhp)
    }

    #[test]
    fn routh_hurwitz_singular_cases() {
        // Regular: (s + 1)(s + 2).
        assert_eq!(counts(&[1, 3, 2]), (2, 0, 0));
        // (s − 1)(s − 2).
        assert_eq!(counts(&[1, -3, 2]), (0, 0, 2));
        // s³ + s² + 2s + 8: roots −2 and 0.5 ± j1.936 (Routh: two sign changes).
        assert_eq!(counts(&[1, 1, 2, 8]), (1, 0, 2));
        // s⁵ + 2s⁴ + 2s³ + 4s² + 11s + 10: zero first element in the s³ row; 2 RHP roots
        // (Ogata, Modern Control Engineering, example of the ε method).
        assert_eq!(counts(&[1, 2, 2, 4, 11, 10]), (3, 0, 2));
        // s⁴ + s³ + 3s² + 2s + 2 = (s² + 2)(s² + s + 1): a zero row; ±j√2 on the axis.
        assert_eq!(counts(&[1, 1, 3, 2, 2]), (2, 2, 0));
        // s⁴ − 1 = (s² + 1)(s − 1)(s + 1): zero row from the first step.
        assert_eq!(counts(&[1, 0, 0, 0, -1]), (1, 2, 1));
        // s⁴ + 4 = (s² + 2s + 2)(s² − 2s + 2): roots symmetric about the origin, none on the axis.
        assert_eq!(counts(&[1, 0, 0, 0, 4]), (2, 0, 2));
        // s² + 1 and s⁴ + 3s² + 2 = (s² + 1)(s² + 2).
        assert_eq!(counts(&[1, 0, 1]), (0, 2, 0));
        assert_eq!(counts(&[1, 0, 3, 0, 2]), (0, 4, 0));
        // Odd: s³ + 1 = (s + 1)(s² − s + 1).
        assert_eq!(counts(&[1, 0, 0, 1]), (1, 0, 2));
        // s⁶ + s⁵ − 2s⁴ − 3s³ − 7s² − 4s − 4 (Routh zero row, Nise table 6.7): 1 RHP, 4 axis? —
        // it is (s − 2)(s + 1)(s² + s + 1)... checked via its factors:
        // (s² + 4)(s − 2)(s + 2)(s² + s + 1)… use an explicit product instead:
        let p = zd(&[1, 0, 4]).mul(&zd(&[1, -2])).mul(&zd(&[1, 1, 1]));
        let (h, _) = square_free_counts(&p).unwrap();
        assert_eq!((h.lhp, h.axis, h.rhp), (2, 2, 1));
    }

    #[test]
    fn near_axis_roots_are_decided_exactly() {
        // (s − 10^−20)² + 1 = s² − 2·10^−20 s + 1 + 10^−40, scaled by 10^40: RHP pair.
        let e40 = IBig::from(10u8).pow(40);
        let e20 = IBig::from(10u8).pow(20);
        let p = ZPoly::new(vec![&e40 + IBig::ONE, IBig::from(-2) * &e20, e40.clone()]);
        let (h, _) = square_free_counts(&p).unwrap();
        assert_eq!((h.lhp, h.axis, h.rhp), (0, 0, 2));
        let p = ZPoly::new(vec![&e40 + IBig::ONE, IBig::from(2) * &e20, e40]);
        let (h, _) = square_free_counts(&p).unwrap();
        assert_eq!((h.lhp, h.axis, h.rhp), (2, 0, 0));
    }

    #[test]
    fn sturm_counts_real_roots() {
        // (s − 1)(s + 2)(s² + 1)(s + 3): three real roots, two negative.
        let p = zd(&[1, -1])
            .mul(&zd(&[1, 2]))
            .mul(&zd(&[1, 0, 1]))
            .mul(&zd(&[1, 3]));
        assert_eq!(count_real_roots(&p), Some(3));
        assert_eq!(count_negative_roots(&p), Some(2));
        // Two roots 10^−12 apart: (s − 1)(s − 1 − 10^−12), scaled.
        let e12 = IBig::from(10u8).pow(12);
        let a = ZPoly::new(vec![-e12.clone(), e12.clone()]);
        let b = ZPoly::new(vec![-(&e12 + IBig::ONE), e12]);
        assert_eq!(count_real_roots(&a.mul(&b)), Some(2));
    }
}
