//! A certificate that the step response is monotone, from the poles and zeros alone.
//!
//! G(s) = k·Π(s − zᵢ)/Π(s − pⱼ) with every pole and zero real and negative. A factor
//! (s − z)/(s − p) with z ≤ p < 0 is 1 + (p − z)/(s − p): its impulse response δ + (p − z)e^(pt)
//! is a non-negative measure; a lone pole's 1/(s − p) has e^(pt) > 0; a repeated one
//! t^(m−1)e^(pt)/(m − 1)! > 0. When the zeros can be paired with distinct poles that way, the
//! impulse response is k times a convolution of non-negative measures, at least one of them a
//! positive function (a strictly proper G keeps a lone pole): y′ = g has the sign of k on
//! t > 0, and y has no critical point there. The pairing exists iff, with both lists sorted
//! from the right, the i-th zero lies at or left of the i-th pole (Hall's condition for
//! intervals).
//!
//! The step metrics' scan for critical points is then unnecessary: y is one monotone piece.
//! The certificate is decided on the same roots the closed form is built from, so a pair that
//! is equal only to rounding changes y′ only at the rounding level of its residues.

use crate::poly::Root;

/// True when the step response of k·Π(s − z)/Π(s − p) is strictly monotone on t > 0 by the
/// pairing argument of the module docs (every root real, every pole negative, each zero
/// paired with a distinct pole at or right of it, and a pole left unpaired).
pub(super) fn monotone_step(poles: &[Root], zeros: &[Root]) -> bool {
    let real_desc = |roots: &[Root]| -> Option<Vec<f64>> {
        let mut v = Vec::new();
        for r in roots {
            if r.value.im != 0.0 || !r.value.re.is_finite() {
                return None;
            }
            v.extend(std::iter::repeat_n(r.value.re, r.multiplicity));
        }
        v.sort_by(|a, b| b.total_cmp(a));
        Some(v)
    };
    let (Some(p), Some(z)) = (real_desc(poles), real_desc(zeros)) else {
        return false;
    };
    p.len() > z.len()
        && p.first().is_some_and(|&right| right < 0.0)
        && z.iter().zip(&p).all(|(zi, pi)| zi <= pi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::Complex64;

    fn roots(v: &[f64]) -> Vec<Root> {
        v.iter()
            .map(|&x| Root::new(Complex64::new(x, 0.0), 1))
            .collect()
    }

    #[test]
    fn pairs_decide() {
        // 1/((s+1)(s+2)): lone poles
        assert!(monotone_step(&roots(&[-1.0, -2.0]), &[]));
        // (s+3)/((s+1)(s+2)): the zero −3 pairs with −2 (or −1)
        assert!(monotone_step(&roots(&[-1.0, -2.0]), &roots(&[-3.0])));
        // (s+1.5)/((s+1)(s+2)): −1.5 pairs with −1
        assert!(monotone_step(&roots(&[-1.0, -2.0]), &roots(&[-1.5])));
        // (s+0.5)/((s+1)(s+2)): a zero right of every pole: overshoot possible
        assert!(!monotone_step(&roots(&[-1.0, -2.0]), &roots(&[-0.5])));
        // a right-half-plane zero (undershoot)
        assert!(!monotone_step(&roots(&[-1.0, -2.0]), &roots(&[1.0])));
        // biproper: no lone pole left
        assert!(!monotone_step(&roots(&[-1.0]), &roots(&[-2.0])));
        // complex poles
        let pair = [
            Root::new(Complex64::new(-1.0, 1.0), 1),
            Root::new(Complex64::new(-1.0, -1.0), 1),
        ];
        assert!(!monotone_step(&pair, &[]));
        // a repeated pole counts twice: (s+3)(s+4)/(s+1)^2(s+5) pairs −3 ≤ −1, −4 ≤ −1 and
        // leaves −5
        let rep = [
            Root::new(Complex64::new(-1.0, 0.0), 2),
            Root::new(Complex64::new(-5.0, 0.0), 1),
        ];
        assert!(monotone_step(&rep, &roots(&[-3.0, -4.0])));
        // (s+3)(s+0.5)/((s+1)^2(s+5)): 0.5 cannot pair
        assert!(!monotone_step(&rep, &roots(&[-3.0, -0.5])));
        // an integrator is not a decaying pole
        assert!(!monotone_step(&roots(&[0.0, -1.0]), &[]));
    }
}
