//! Polynomials with big-integer coefficients: the working form of the exact path.
//!
//! Storage is **ascending** (constant term first) because every algorithm here walks from the
//! low end; the public [`super::ExactPoly`] speaks descending order. The zero polynomial has no
//! coefficients; otherwise the last coefficient is non-zero.

use dashu_int::ops::{BitTest, DivRem, Gcd, UnsignedAbs};
use dashu_int::{IBig, UBig};

use crate::numeric::dd::Dd;

/// A polynomial over ℤ, ascending coefficients, no trailing (leading-power) zeros.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub(crate) struct ZPoly {
    c: Vec<IBig>,
}

impl ZPoly {
    /// From ascending coefficients; high zero coefficients are dropped.
    pub fn new(mut c: Vec<IBig>) -> ZPoly {
        while c.last().is_some_and(|x| x.is_zero()) {
            c.pop();
        }
        ZPoly { c }
    }

    /// The constant 1.
    pub fn one() -> ZPoly {
        ZPoly { c: vec![IBig::ONE] }
    }

    /// The polynomial s.
    pub fn x() -> ZPoly {
        ZPoly {
            c: vec![IBig::ZERO, IBig::ONE],
        }
    }

    /// Ascending coefficients.
    pub fn coeffs(&self) -> &[IBig] {
        &self.c
    }

    /// True for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.c.is_empty()
    }

    /// Degree; 0 for constants and for the zero polynomial.
    pub fn deg(&self) -> usize {
        self.c.len().saturating_sub(1)
    }

    /// Leading coefficient (0 for the zero polynomial).
    pub fn lc(&self) -> IBig {
        self.c.last().cloned().unwrap_or(IBig::ZERO)
    }

    /// Sign of the leading coefficient (0 for the zero polynomial).
    pub fn lc_sign(&self) -> i32 {
        self.c.last().map_or(0, sign)
    }

    /// Coefficient of s^k (0 beyond the degree).
    pub fn coeff(&self, k: usize) -> IBig {
        self.c.get(k).cloned().unwrap_or(IBig::ZERO)
    }

    /// Number of bits of the largest |coefficient|.
    pub fn max_bits(&self) -> usize {
        self.c
            .iter()
            .map(|x| x.unsigned_abs().bit_len())
            .max()
            .unwrap_or(0)
    }

    /// gcd of the coefficients (0 for the zero polynomial).
    pub fn content(&self) -> UBig {
        let mut g = UBig::ZERO;
        for x in self.c.iter().filter(|x| !x.is_zero()) {
            // (dashu panics on gcd(0, 0): zero coefficients are skipped)
            g = if g.is_zero() {
                x.unsigned_abs()
            } else {
                (&g).gcd(&x.unsigned_abs())
            };
            if g.is_one() {
                break;
            }
        }
        g
    }

    /// This polynomial divided by its content, with a positive leading coefficient.
    pub fn primitive(&self) -> ZPoly {
        if self.is_zero() {
            return self.clone();
        }
        let g = IBig::from(self.content());
        let g = if self.lc_sign() < 0 { -g } else { g };
        if g.is_one() {
            return self.clone();
        }
        ZPoly {
            c: self.c.iter().map(|x| x / &g).collect(),
        }
    }

    /// Multiplies every coefficient by `k`.
    pub fn scale(&self, k: &IBig) -> ZPoly {
        ZPoly::new(self.c.iter().map(|x| x * k).collect())
    }

    /// Number of zero coefficients at the low end: the multiplicity of the root s = 0.
    pub fn low_zeros(&self) -> usize {
        self.c.iter().take_while(|x| x.is_zero()).count()
    }

    /// Divides by s^k (the low k coefficients must be zero).
    pub fn shift_down(&self, k: usize) -> ZPoly {
        ZPoly {
            c: self.c.get(k..).map(<[IBig]>::to_vec).unwrap_or_default(),
        }
    }

    /// First derivative.
    pub fn derivative(&self) -> ZPoly {
        ZPoly::new(
            self.c
                .iter()
                .enumerate()
                .skip(1)
                .map(|(i, x)| x * IBig::from(i))
                .collect(),
        )
    }

    /// Sum.
    pub fn add(&self, o: &ZPoly) -> ZPoly {
        let n = self.c.len().max(o.c.len());
        ZPoly::new(
            (0..n)
                .map(|i| match (self.c.get(i), o.c.get(i)) {
                    (Some(a), Some(b)) => a + b,
                    (Some(a), None) => a.clone(),
                    (None, Some(b)) => b.clone(),
                    (None, None) => IBig::ZERO,
                })
                .collect(),
        )
    }

    /// Negation.
    pub fn neg(&self) -> ZPoly {
        ZPoly {
            c: self.c.iter().map(|x| -x).collect(),
        }
    }

    /// Difference.
    pub fn sub(&self, o: &ZPoly) -> ZPoly {
        self.add(&o.neg())
    }

    /// Product (schoolbook).
    pub fn mul(&self, o: &ZPoly) -> ZPoly {
        if self.is_zero() || o.is_zero() {
            return ZPoly { c: Vec::new() };
        }
        let mut c = vec![IBig::ZERO; self.c.len() + o.c.len() - 1];
        for (i, a) in self.c.iter().enumerate() {
            if a.is_zero() {
                continue;
            }
            for (j, b) in o.c.iter().enumerate() {
                if !b.is_zero() {
                    c[i + j] += a * b;
                }
            }
        }
        ZPoly::new(c)
    }

    /// self^k.
    pub fn pow(&self, k: usize) -> ZPoly {
        let mut r = ZPoly::one();
        for _ in 0..k {
            r = r.mul(self);
        }
        r
    }

    /// The exact quotient self / d in ℤ\[s\], or `None` when d does not divide self there.
    pub fn div_exact(&self, d: &ZPoly) -> Option<ZPoly> {
        if d.is_zero() {
            return None;
        }
        if self.is_zero() {
            return Some(self.clone());
        }
        if self.c.len() < d.c.len() {
            return None;
        }
        let mut r = self.c.clone();
        let m = d.c.len() - 1;
        let lead = d.c.last()?;
        let mut q = vec![IBig::ZERO; r.len() - m];
        for k in (0..q.len()).rev() {
            let top = &r[k + m];
            if top.is_zero() {
                continue;
            }
            let (f, rem) = top.div_rem(lead);
            if !rem.is_zero() {
                return None;
            }
            for (j, dj) in d.c.iter().enumerate() {
                if !dj.is_zero() {
                    r[k + j] -= &f * dj;
                }
            }
            q[k] = f;
        }
        if r.iter().any(|x| !x.is_zero()) {
            return None;
        }
        Some(ZPoly::new(q))
    }

    /// Pseudo-remainder: lc(d)^(deg self − deg d + 1)·self mod d (deg self ≥ deg d).
    pub fn prem(&self, d: &ZPoly) -> ZPoly {
        let m = d.deg();
        if self.c.len() < d.c.len() {
            return self.clone();
        }
        let lead = d.lc();
        let mut r = self.c.clone();
        for top in (m..r.len()).rev() {
            let f = std::mem::replace(&mut r[top], IBig::ZERO);
            for x in r[..top].iter_mut() {
                if !x.is_zero() {
                    *x *= &lead;
                }
            }
            if f.is_zero() {
                continue;
            }
            let base = top - m;
            for (j, dj) in d.c[..m].iter().enumerate() {
                if !dj.is_zero() {
                    r[base + j] -= &f * dj;
                }
            }
        }
        r.truncate(m);
        ZPoly::new(r)
    }

    /// Even and odd parts in x = s²: self(s) = e(s²) + s·o(s²).
    pub fn even_odd(&self) -> (ZPoly, ZPoly) {
        let e = self.c.iter().step_by(2).cloned().collect();
        let o = self.c.iter().skip(1).step_by(2).cloned().collect();
        (ZPoly::new(e), ZPoly::new(o))
    }

    /// self(s²).
    pub fn of_square(&self) -> ZPoly {
        let mut c = Vec::with_capacity(2 * self.c.len());
        for (i, x) in self.c.iter().enumerate() {
            if i > 0 {
                c.push(IBig::ZERO);
            }
            c.push(x.clone());
        }
        ZPoly::new(c)
    }

    /// Sign at +∞ (leading coefficient) or −∞ (times (−1)^deg).
    pub fn sign_at_infinity(&self, positive: bool) -> i32 {
        let s = self.lc_sign();
        if positive || self.deg() % 2 == 0 {
            s
        } else {
            -s
        }
    }

    /// Sign just left of 0 (at 0⁻): the lowest non-zero coefficient times (−1)^its power.
    pub fn sign_left_of_zero(&self) -> i32 {
        match self.c.iter().position(|x| !x.is_zero()) {
            None => 0,
            Some(k) => {
                let s = sign(&self.c[k]);
                if k % 2 == 0 { s } else { -s }
            }
        }
    }

    /// Coefficients as double-doubles scaled by 2^(−shift) (the same shift for all), chosen
    /// so the largest has magnitude in [1, 2); also returns the shift.
    pub fn to_dd_scaled(&self) -> (Vec<Dd>, i64) {
        let bits = self.max_bits() as i64;
        let shift = bits - 1;
        let c = self.c.iter().map(|x| ibig_to_dd(x, shift)).collect();
        (c, shift)
    }
}

/// Sign of a big integer.
pub(crate) fn sign(x: &IBig) -> i32 {
    if x.is_zero() {
        0
    } else if *x < IBig::ZERO {
        -1
    } else {
        1
    }
}

/// x·2^(−shift) as a double-double (hi correctly rounded, lo the rounded remainder), for
/// |x|·2^(−shift) within the range of doubles.
pub(crate) fn ibig_to_dd(x: &IBig, shift: i64) -> Dd {
    if x.is_zero() {
        return Dd::ZERO;
    }
    // Keep the top 128 bits exactly: x = t·2^k + (rest), |t| < 2^128.
    let len = x.unsigned_abs().bit_len() as i64;
    let k = (len - 120).max(0);
    let t = if k > 0 { x >> k as usize } else { x.clone() };
    let t = i128::try_from(&t).unwrap_or(0);
    let hi = t as f64;
    let lo = (t - hi as i128) as f64;
    let scale = k - shift;
    Dd {
        hi: pow2_mul(hi, scale),
        lo: pow2_mul(lo, scale),
    }
}

/// x·2^e with intermediate steps that stay in range.
pub(crate) fn pow2_mul(mut x: f64, mut e: i64) -> f64 {
    let step = |k: i64| f64::from_bits(((1023 + k) as u64) << 52);
    while e > 900 {
        x *= step(900);
        e -= 900;
    }
    while e < -900 {
        x *= step(-900);
        e += 900;
    }
    x * step(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn z(c: &[i64]) -> ZPoly {
        ZPoly::new(c.iter().map(|&x| IBig::from(x)).collect())
    }

    #[test]
    fn arithmetic_and_exact_division() {
        let a = z(&[1, 1]); // 1 + s
        let b = z(&[-2, 0, 1]); // s² − 2
        let p = a.mul(&b);
        assert_eq!(p, z(&[-2, -2, 1, 1]));
        assert_eq!(p.div_exact(&a), Some(b.clone()));
        assert_eq!(p.div_exact(&z(&[1, 2])), None);
        assert_eq!(z(&[2, 4]).div_exact(&z(&[1, 2])), Some(z(&[2])));
        assert_eq!(z(&[3, 6]).div_exact(&z(&[2, 4])), None);
        assert_eq!(p.derivative(), z(&[-2, 2, 3]));
        assert_eq!(z(&[6, -4, 2]).primitive(), z(&[3, -2, 1]));
        assert_eq!(z(&[6, -4, -2]).primitive(), z(&[-3, 2, 1]));
        // prem: lc(d)^(3−1+1)·(s³ + 1) mod (2s + 1) = 8·p(−1/2) = 8·7/8 = 7
        assert_eq!(z(&[1, 0, 0, 1]).prem(&z(&[1, 2])), z(&[7]));
        let (e, o) = z(&[1, 2, 3, 4, 5]).even_odd();
        assert_eq!((e.clone(), o), (z(&[1, 3, 5]), z(&[2, 4])));
        assert_eq!(e.of_square(), z(&[1, 0, 3, 0, 5]));
        assert_eq!(z(&[0, 0, 3, 1]).low_zeros(), 2);
        assert_eq!(z(&[0, -3, 1]).sign_left_of_zero(), 1);
        assert_eq!(z(&[1, 0, -1]).sign_at_infinity(false), -1);
    }

    #[test]
    fn dd_conversion_keeps_106_bits() {
        let x = (IBig::ONE << 200usize) + IBig::from(3) * (IBig::ONE << 100usize) + IBig::ONE;
        let d = ibig_to_dd(&x, 200);
        assert!((d.hi - 1.0).abs() < 1e-300);
        assert!((d.lo - 3.0 * 2f64.powi(-100)).abs() < 1e-45);
    }
}
