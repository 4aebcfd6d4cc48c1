//! The low-frequency asymptote K·s^k of a factored plant's reduced G: the dc gain, and the
//! start of the Bode form.

use num_complex::Complex64;

use super::series::ScaledProduct;
use crate::poly::Root;

/// The low-frequency asymptote K·s^k of the reduced G: K = sign·e^(ln_abs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LowFrequency {
    /// Sign of K (±1).
    pub sign: f64,
    /// ln|K|.
    pub ln_abs: f64,
    /// k: zeros at s = 0 minus poles at s = 0.
    pub int_order: i32,
    /// K itself when it is a normal f64 (NaN otherwise).
    pub k: f64,
}

impl LowFrequency {
    /// The asymptote of a G finite at s = 0 with value `k`.
    pub(crate) fn of_value(k: f64) -> LowFrequency {
        LowFrequency {
            sign: if k < 0.0 { -1.0 } else { 1.0 },
            ln_abs: k.abs().ln(),
            int_order: 0,
            k,
        }
    }

    /// K as an f64 (from the logarithm when the direct ratio under- or overflowed).
    pub fn value(&self) -> f64 {
        if self.k.is_finite() && self.k != 0.0 {
            self.k
        } else {
            self.sign * self.ln_abs.exp()
        }
    }

    /// The asymptote of k·Π(s − zᵢ)/Π(s − pⱼ) from the (reduced) factors, in scaled form.
    pub(super) fn from_factors(gain: f64, zeros: &[Root], poles: &[Root]) -> LowFrequency {
        let mut acc = ScaledProduct::new(Complex64::new(gain, 0.0));
        let mut int_order = 0i32;
        let mut ln_abs = gain.abs().ln();
        for z in zeros {
            if z.is_origin() {
                int_order += z.multiplicity as i32;
            } else {
                acc.mul_pow(-z.value, z.multiplicity);
                ln_abs += z.multiplicity as f64 * z.value.norm().ln();
            }
        }
        for p in poles {
            if p.is_origin() {
                int_order -= p.multiplicity as i32;
            } else {
                acc.div_pow(-p.value, p.multiplicity);
                ln_abs -= p.multiplicity as f64 * p.value.norm().ln();
            }
        }
        let k = acc.value().re;
        let sign =
            if gain < 0.0 { -1.0 } else { 1.0 } * real_root_sign(zeros) * real_root_sign(poles);
        LowFrequency {
            sign,
            ln_abs,
            int_order,
            k,
        }
    }
}

/// Sign of Π(−r)^m over the non-zero roots (conjugate pairs contribute |r|² > 0).
fn real_root_sign(roots: &[Root]) -> f64 {
    let negative = roots
        .iter()
        .filter(|r| r.is_real() && r.value.re > 0.0 && r.multiplicity % 2 == 1)
        .count();
    if negative % 2 == 1 { -1.0 } else { 1.0 }
}
