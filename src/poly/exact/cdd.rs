//! Complex double-double arithmetic (~106-bit real and imaginary parts) for refining roots
//! against the exact coefficients.

use num_complex::Complex64;

use crate::numeric::dd::{Dd, two_prod, two_sum};

/// a / b in double-double (three correction steps; relative error ~2^−104).
pub(crate) fn dd_div(a: Dd, b: Dd) -> Dd {
    let q1 = a.hi / b.hi;
    let r = a - mul_f64(b, q1);
    let q2 = r.hi / b.hi;
    let r = r - mul_f64(b, q2);
    let q3 = r.hi / b.hi;
    let (s, e) = two_sum(q1, q2);
    let (hi, lo) = two_sum(s, e + q3);
    Dd { hi, lo }
}

/// a·x for a double-double a and a double x.
pub(crate) fn mul_f64(a: Dd, x: f64) -> Dd {
    let (p, e) = two_prod(a.hi, x);
    let (hi, lo) = two_sum(p, e + a.lo * x);
    Dd { hi, lo }
}

/// √a for a ≥ 0 (one Newton correction on the double square root).
pub(crate) fn dd_sqrt(a: Dd) -> Dd {
    if a.hi <= 0.0 {
        return Dd::ZERO;
    }
    let x = a.hi.sqrt();
    let (p, e) = two_prod(x, x);
    let r = (a.hi - p - e + a.lo) / (2.0 * x);
    let (hi, lo) = two_sum(x, r);
    Dd { hi, lo }
}

/// A complex number with double-double parts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Cdd {
    pub re: Dd,
    pub im: Dd,
}

impl Cdd {
    pub const ZERO: Cdd = Cdd {
        re: Dd::ZERO,
        im: Dd::ZERO,
    };

    pub fn from_c64(z: Complex64) -> Cdd {
        Cdd {
            re: Dd::from(z.re),
            im: Dd::from(z.im),
        }
    }

    pub fn from_dd(re: Dd) -> Cdd {
        Cdd { re, im: Dd::ZERO }
    }

    /// Rounded to a complex double.
    pub fn to_c64(self) -> Complex64 {
        Complex64::new(self.re.to_f64(), self.im.to_f64())
    }

    pub fn conj(self) -> Cdd {
        Cdd {
            re: self.re,
            im: -self.im,
        }
    }

    /// |z|² in double-double.
    pub fn norm_sqr(self) -> Dd {
        self.re * self.re + self.im * self.im
    }

    /// |z| as a double (relative error ≤ 2^−50).
    pub fn abs(self) -> f64 {
        self.to_c64().norm()
    }

    pub fn inv(self) -> Cdd {
        let n = self.norm_sqr();
        Cdd {
            re: dd_div(self.re, n),
            im: dd_div(-self.im, n),
        }
    }

    /// Multiplies both parts by 2^k (exact while in range).
    pub fn scale_pow2(self, k: i64) -> Cdd {
        let f = |d: Dd| Dd {
            hi: super::zpoly::pow2_mul(d.hi, k),
            lo: super::zpoly::pow2_mul(d.lo, k),
        };
        Cdd {
            re: f(self.re),
            im: f(self.im),
        }
    }

    /// Principal square root.
    pub fn sqrt(self) -> Cdd {
        // √z = (√((|z| + x)/2), sign(y)·√((|z| − x)/2)), using the larger part to avoid
        // cancellation.
        let r = dd_sqrt(self.norm_sqr());
        let x = self.re;
        if x.hi >= 0.0 {
            let a = dd_sqrt(mul_f64(r + x, 0.5));
            if a.hi == 0.0 {
                return Cdd::ZERO;
            }
            let b = dd_div(self.im, mul_f64(a, 2.0));
            Cdd { re: a, im: b }
        } else {
            let mut b = dd_sqrt(mul_f64(r - x, 0.5));
            if self.im.hi < 0.0 {
                b = -b;
            }
            let a = dd_div(self.im, mul_f64(b, 2.0));
            Cdd { re: a, im: b }
        }
    }
}

impl std::ops::Add for Cdd {
    type Output = Cdd;
    fn add(self, o: Cdd) -> Cdd {
        Cdd {
            re: self.re + o.re,
            im: self.im + o.im,
        }
    }
}

impl std::ops::Sub for Cdd {
    type Output = Cdd;
    fn sub(self, o: Cdd) -> Cdd {
        Cdd {
            re: self.re - o.re,
            im: self.im - o.im,
        }
    }
}

impl std::ops::Mul for Cdd {
    type Output = Cdd;
    fn mul(self, o: Cdd) -> Cdd {
        Cdd {
            re: self.re * o.re - self.im * o.im,
            im: self.re * o.im + self.im * o.re,
        }
    }
}

impl std::ops::Div for Cdd {
    type Output = Cdd;
    #[allow(clippy::suspicious_arithmetic_impl)] // a / b = a · b⁻¹
    fn div(self, o: Cdd) -> Cdd {
        self * o.inv()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn division_and_square_root_keep_double_double_accuracy() {
        let third = dd_div(Dd::from(1.0), Dd::from(3.0));
        let back = mul_f64(third, 3.0) - Dd::from(1.0);
        assert!(back.to_f64().abs() < 1e-31);
        let two = dd_sqrt(Dd::from(2.0));
        let sq = two * two - Dd::from(2.0);
        assert!(sq.to_f64().abs() < 1e-31);
        let z = Cdd::from_c64(Complex64::new(-3.0, 4.0)).sqrt(); // 1 + 2j
        let d = z - Cdd::from_c64(Complex64::new(1.0, 2.0));
        assert!(d.abs() < 1e-30);
        let w = Cdd::from_c64(Complex64::new(-4.0, -0.0)).sqrt();
        assert!(w.re.to_f64().abs() < 1e-300);
    }
}
