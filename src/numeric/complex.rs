//! Complex division without spurious overflow or underflow.
//!
//! num-complex divides by |b|² = re² + im², which overflows for |b| ≳ 1e154 (1/(1e200) comes
//! out as 0) and underflows for |b| ≲ 1e-154. These use Smith's algorithm (scaled by the
//! larger component of b), as LAPACK's `zladiv` does, and are exact to a few ulps for every
//! finite b ≠ 0 whose result is representable.

use num_complex::Complex64;

/// a / b (Smith's algorithm).
pub fn div(a: Complex64, b: Complex64) -> Complex64 {
    if b.im == 0.0 {
        return Complex64::new(a.re / b.re, a.im / b.re);
    }
    if b.re == 0.0 {
        return Complex64::new(a.im / b.im, -a.re / b.im);
    }
    if b.re.abs() >= b.im.abs() {
        let r = b.im / b.re;
        let d = b.re + b.im * r;
        Complex64::new((a.re + a.im * r) / d, (a.im - a.re * r) / d)
    } else {
        let r = b.re / b.im;
        let d = b.re * r + b.im;
        Complex64::new((a.re * r + a.im) / d, (a.im * r - a.re) / d)
    }
}

/// 1 / b (Smith's algorithm).
pub fn recip(b: Complex64) -> Complex64 {
    div(Complex64::new(1.0, 0.0), b)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `div` on a worked example (an internal kernel: a unit test, not a doctest).
    #[test]
    #[allow(clippy::float_cmp)] // exact values are meant
    fn div_example() {
        use crate::numeric::complex::div;
        use num_complex::Complex64 as C;
        let q = div(C::new(1.0, 0.0), C::new(1e200, 0.0));
        assert_eq!(q, C::new(1e-200, 0.0)); // num-complex gives 0
        let q = div(C::new(3e300, 4e300), C::new(0.0, 1e300));
        assert!((q - C::new(4.0, -3.0)).norm() < 1e-15);
    }

    #[test]
    fn agrees_with_plain_division_in_range_and_survives_outside() {
        let cases = [
            (Complex64::new(1.0, 2.0), Complex64::new(3.0, -4.0)),
            (Complex64::new(-0.5, 0.25), Complex64::new(1e-3, 7.0)),
            (Complex64::new(2.0, 0.0), Complex64::new(0.0, -8.0)),
        ];
        for (a, b) in cases {
            assert!((div(a, b) - a / b).norm() <= 4.0 * f64::EPSILON * (a / b).norm());
        }
        let big = Complex64::new(3e250, -4e250);
        let q = recip(big); // (3 + 4j)/(25e250)
        assert!((q - Complex64::new(3.0 / 25.0 * 1e-250, 4.0 / 25.0 * 1e-250)).norm() < 1e-265);
        let tiny = Complex64::new(1e-250, 1e-250);
        assert!((recip(tiny) - Complex64::new(0.5e250, -0.5e250)).norm() < 1e235);
    }
}
