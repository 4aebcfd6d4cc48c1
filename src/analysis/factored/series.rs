//! Products of many complex factors without overflow, and truncated power series of products
//! of factors — the arithmetic that lets a factored plant be evaluated and expanded without
//! ever forming its coefficients.

use num_complex::Complex64;

use crate::poly::Root;

/// A complex number kept as mantissa·2^exp, so that products of hundreds of factors neither
/// overflow nor underflow (the exponent is exact; the mantissa keeps |m| in [2^-256, 2^256]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ScaledProduct {
    mant: Complex64,
    exp: i64,
}

const RESCALE_HI: f64 = 1.157_920_892_373_162e77; // 2^256
const RESCALE_LO: f64 = 8.636_168_555_094_445e-78; // 2^-256

impl ScaledProduct {
    /// The value `v` (exactly).
    pub(crate) fn new(v: Complex64) -> ScaledProduct {
        let mut p = ScaledProduct { mant: v, exp: 0 };
        p.rescale();
        p
    }

    fn rescale(&mut self) {
        let m = self.mant.re.abs().max(self.mant.im.abs());
        if m == 0.0 || !m.is_finite() {
            return;
        }
        if !(RESCALE_LO..=RESCALE_HI).contains(&m) {
            // frexp: m = f·2^e with f in [0.5, 1)
            let e = m.log2().floor() as i64;
            let s = pow2(-e);
            self.mant = Complex64::new(self.mant.re * s, self.mant.im * s);
            self.exp += e;
        }
    }

    /// `v` as (mantissa, exponent) with the larger component of the mantissa in [0.5, 1).
    fn split(v: Complex64) -> (Complex64, i64) {
        let m = v.re.abs().max(v.im.abs());
        match crate::numeric::balance::exponent(m) {
            Some(e) => {
                let e = i64::from(e) + 1;
                let s = pow2(-e);
                (Complex64::new(v.re * s, v.im * s), e)
            }
            None => (v, 0),
        }
    }

    /// Multiplies by `v` (any finite size: the factor's exponent is taken out first).
    pub(crate) fn mul(&mut self, v: Complex64) {
        let (m, e) = Self::split(v);
        self.mant *= m;
        self.exp += e;
        self.rescale();
    }

    /// Divides by `v` (Smith's division on the factor's mantissa).
    pub(crate) fn div(&mut self, v: Complex64) {
        let (m, e) = Self::split(v);
        self.mant = crate::numeric::complex::div(self.mant, m);
        self.exp -= e;
        self.rescale();
    }

    /// Multiplies by `v^k`.
    pub(crate) fn mul_pow(&mut self, v: Complex64, k: usize) {
        for _ in 0..k {
            self.mul(v);
        }
    }

    /// Divides by `v^k`.
    pub(crate) fn div_pow(&mut self, v: Complex64, k: usize) {
        for _ in 0..k {
            self.div(v);
        }
    }

    /// The value as a plain complex number (±∞ or 0 when out of range).
    pub(crate) fn value(&self) -> Complex64 {
        if self.mant.re == 0.0 && self.mant.im == 0.0 {
            return self.mant;
        }
        let e = self.exp.clamp(-3000, 3000);
        // apply in two halves so that an in-range result is not lost to an intermediate
        let half = e / 2;
        let s1 = pow2(half);
        let s2 = pow2(e - half);
        Complex64::new(self.mant.re * s1 * s2, self.mant.im * s1 * s2)
    }
}

/// 2^e as f64 for |e| ≤ 1500 (0 or ∞ beyond the range of f64).
fn pow2(e: i64) -> f64 {
    if e > 1023 {
        return if e > 2000 {
            f64::INFINITY
        } else {
            2f64.powi(1023) * 2f64.powi((e - 1023) as i32)
        };
    }
    if e < -1022 {
        return if e < -2100 {
            0.0
        } else {
            2f64.powi(-1022) * 2f64.powi((e + 1022) as i32)
        };
    }
    2f64.powi(e as i32)
}

/// k·Π(s − zᵢ)^mᵢ / Π(s − pⱼ)^mⱼ at `s`, the factors multiplied and divided alternately so
/// that the running value stays near the size of the result.
pub(crate) fn eval_factors(gain: f64, zeros: &[Root], poles: &[Root], s: Complex64) -> Complex64 {
    let mut acc = ScaledProduct::new(Complex64::new(gain, 0.0));
    let mut zs = zeros
        .iter()
        .flat_map(|r| std::iter::repeat_n(r.value, r.multiplicity));
    let mut ps = poles
        .iter()
        .flat_map(|r| std::iter::repeat_n(r.value, r.multiplicity));
    loop {
        let z = zs.next();
        let p = ps.next();
        if z.is_none() && p.is_none() {
            break;
        }
        if let Some(z) = z {
            acc.mul(s - z);
        }
        if let Some(p) = p {
            acc.div(s - p);
        }
    }
    acc.value()
}

/// The first `m` Taylor coefficients at h = 0 of Π(1 + h/aᵢ)^(±kᵢ) (exponent +k for the
/// entries of `up`, −k for those of `down`), each aᵢ ≠ 0.
pub(crate) fn normalised_series(
    up: &[(Complex64, usize)],
    down: &[(Complex64, usize)],
    m: usize,
) -> Vec<Complex64> {
    let zero = Complex64::new(0.0, 0.0);
    let mut out = vec![zero; m];
    if m == 0 {
        return out;
    }
    out[0] = Complex64::new(1.0, 0.0);
    if m == 1 {
        return out;
    }
    let mut factor = vec![zero; m];
    let mut apply = |a: Complex64, k: usize, sign: f64, out: &mut Vec<Complex64>| {
        // (1 + x)^(sign·k), x = h/a: binomial coefficients C(sign·k, l) x^l
        let x = crate::numeric::complex::recip(a);
        let kk = sign * k as f64;
        let mut coef = Complex64::new(1.0, 0.0);
        for (l, f) in factor.iter_mut().enumerate() {
            *f = coef;
            coef = coef * x * ((kk - l as f64) / (l + 1) as f64);
        }
        *out = series_mul(out, &factor);
    };
    for &(a, k) in up {
        apply(a, k, 1.0, &mut out);
    }
    for &(a, k) in down {
        apply(a, k, -1.0, &mut out);
    }
    out
}

/// Product of two power series truncated to the length of `a`.
pub(crate) fn series_mul(a: &[Complex64], b: &[Complex64]) -> Vec<Complex64> {
    let m = a.len();
    (0..m)
        .map(|k| (0..=k).map(|j| a[j] * b[k - j]).sum())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::Complex64 as C;

    #[test]
    fn products_far_beyond_the_range_of_f64() {
        // Π_{k<400} 1e3 / Π_{k<400} 1e3 = 1, with intermediates up to 1e1200.
        let mut p = ScaledProduct::new(C::new(1.0, 0.0));
        p.mul_pow(C::new(1e3, 0.0), 400);
        p.div_pow(C::new(0.0, 1e3), 400);
        let v = p.value();
        assert!((v - C::new(1.0, 0.0)).norm() < 1e-12, "{v}"); // j^400 = 1
        let mut p = ScaledProduct::new(C::new(2.0, 0.0));
        p.mul_pow(C::new(1e-200, 0.0), 2);
        assert_eq!(p.value(), C::new(0.0, 0.0)); // 2e-400 underflows at the end only
    }

    #[test]
    fn factors_beyond_1e154_are_not_lost() {
        // 1/((s + 1e200)(s + 1e-200)) at s = 0: 1/(1e200·1e-200) = 1
        let p = [
            Root::new(C::new(-1e200, 0.0), 1),
            Root::new(C::new(-1e-200, 0.0), 1),
        ];
        let v = eval_factors(1.0, &[], &p, C::new(0.0, 0.0));
        assert!((v - C::new(1.0, 0.0)).norm() < 1e-15, "{v}");
        // the series of (1 + h/1e200)^(−1): 1, −1e-200
        let s = normalised_series(&[], &[(C::new(1e200, 0.0), 1)], 2);
        assert_eq!(s[1], C::new(-1e-200, 0.0));
    }

    #[test]
    fn factor_evaluation_matches_the_polynomial() {
        // 3 (s + 1)² / ((s + 2)(s² + 2s + 5)) at s = 0.5 + 1j
        let z = [Root::new(C::new(-1.0, 0.0), 2)];
        let p = [
            Root::new(C::new(-1.0, 2.0), 1),
            Root::new(C::new(-1.0, -2.0), 1),
            Root::new(C::new(-2.0, 0.0), 1),
        ];
        let s = C::new(0.5, 1.0);
        let want = 3.0 * (s + 1.0).powu(2) / ((s + 2.0) * (s * s + 2.0 * s + 5.0));
        assert!((eval_factors(3.0, &z, &p, s) - want).norm() < 1e-15);
    }

    #[test]
    fn binomial_series() {
        // (1 + h/2)^2 (1 + h)^(-1) = (1 + h + h²/4)(1 − h + h² − h³) = 1 + 0h + h²/4 − h³/4 …
        let s = normalised_series(&[(C::new(2.0, 0.0), 2)], &[(C::new(1.0, 0.0), 1)], 4);
        let want = [1.0, 0.0, 0.25, -0.25];
        for (a, b) in s.iter().zip(want) {
            assert!((a.re - b).abs() < 1e-15 && a.im == 0.0, "{s:?}");
        }
    }
}
