//! Double-double ("compensated") arithmetic: a value is hi + lo with |lo| ≤ ulp(hi)/2, giving
//! ~106 bits. Used only where a residual must be computed more accurately than the data it
//! refines (iterative refinement of multiple roots); everything else stays in `f64`.

/// A double-double number hi + lo.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dd {
    /// Leading part.
    pub hi: f64,
    /// Trailing part.
    pub lo: f64,
}

/// Error-free sum: a + b = s + e exactly.
#[inline]
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// Error-free product: a·b = p + e exactly (uses a fused multiply-add).
#[inline]
pub fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let e = a.mul_add(b, -p);
    (p, e)
}

impl Dd {
    /// Zero.
    pub const ZERO: Dd = Dd { hi: 0.0, lo: 0.0 };

    /// From an `f64`.
    #[inline]
    pub fn from(x: f64) -> Dd {
        Dd { hi: x, lo: 0.0 }
    }

    /// Rounded to `f64`.
    #[inline]
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }
}

impl std::ops::Add for Dd {
    type Output = Dd;
    #[inline]
    fn add(self, o: Dd) -> Dd {
        let (s, e) = two_sum(self.hi, o.hi);
        let e = e + self.lo + o.lo;
        let (hi, lo) = two_sum(s, e);
        Dd { hi, lo }
    }
}

impl std::ops::Neg for Dd {
    type Output = Dd;
    #[inline]
    fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl std::ops::Sub for Dd {
    type Output = Dd;
    #[inline]
    fn sub(self, o: Dd) -> Dd {
        self + (-o)
    }
}

impl std::ops::Mul for Dd {
    type Output = Dd;
    #[inline]
    fn mul(self, o: Dd) -> Dd {
        let (p, e) = two_prod(self.hi, o.hi);
        let e = e + (self.hi * o.lo + self.lo * o.hi);
        let (hi, lo) = two_sum(p, e);
        Dd { hi, lo }
    }
}

/// Product of two polynomials with double-double coefficients (any consistent order).
pub fn poly_mul(a: &[Dd], b: &[Dd]) -> Vec<Dd> {
    let mut c = vec![Dd::ZERO; a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            c[i + j] = c[i + j] + *x * *y;
        }
    }
    c
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // these tests expect exact values
    use super::*;

    #[test]
    fn captures_what_f64_loses() {
        // (1 + 2^-60) - 1 is lost in f64 but kept in double-double.
        let a = Dd::from(1.0) + Dd::from(2f64.powi(-60));
        let d = a - Dd::from(1.0);
        assert_eq!(d.to_f64(), 2f64.powi(-60));
        let (p, e) = two_prod(1.0 + 2f64.powi(-30), 1.0 + 2f64.powi(-30));
        assert_eq!(e, 2f64.powi(-60));
        assert_eq!(p, 1.0 + 2f64.powi(-29));
    }
}
