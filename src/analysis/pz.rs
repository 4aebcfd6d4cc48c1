//! Poles, zeros, cancellations and the reduced (lowest-terms) transfer function.

use num_complex::Complex64;
use serde::Serialize;

use crate::error::Result;
use crate::lti::TransferFunction;
use crate::numeric::tol::CANCEL_REL_TOL;
use crate::poly::{Poly, Root};

/// Everything about the roots of a transfer function.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PoleZero {
    /// Roots of the denominator as given (the characteristic polynomial), with multiplicities.
    pub poles: Vec<Root>,
    /// Finite zeros: roots of the numerator as given.
    pub zeros: Vec<Root>,
    /// Common roots of numerator and denominator (with the multiplicity that cancels).
    pub cancelled: Vec<Root>,
    /// Poles of the reduced transfer function.
    pub reduced_poles: Vec<Root>,
    /// Zeros of the reduced transfer function.
    pub reduced_zeros: Vec<Root>,
    /// Number of zeros at infinity: deg D − deg N (0 for an improper or zero G).
    pub zeros_at_infinity: usize,
    /// G in lowest terms.
    #[serde(skip)]
    pub reduced: TransferFunction,
}

/// Two roots are the same when they agree to [`CANCEL_REL_TOL`] relative to their size.
fn same_root(a: Complex64, b: Complex64) -> bool {
    let scale = a.norm().max(b.norm());
    (a - b).norm() <= CANCEL_REL_TOL * scale
}

impl TransferFunction {
    /// Poles, zeros, cancelled common roots and the reduced transfer function.
    ///
    /// A numerator root and a denominator root cancel when they agree to 1e-8 relative
    /// (exactly for roots at s = 0). The reduced G is obtained by dividing both polynomials by
    /// the common factor (built from the cancelled poles), which keeps the original
    /// coefficients' information.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // s / (s (s + 1)): the pole at 0 cancels, the reduced G is 1/(s + 1).
    /// let g = TransferFunction::from_descending(&[1.0, 0.0], &[1.0, 1.0, 0.0]).unwrap();
    /// let pz = g.pole_zero().unwrap();
    /// assert_eq!(pz.cancelled.len(), 1);
    /// assert_eq!(pz.reduced.den().coeffs(), &[1.0, 1.0]);
    /// assert_eq!(pz.zeros_at_infinity, 1);
    /// ```
    pub fn pole_zero(&self) -> Result<PoleZero> {
        let poles = self.poles()?;
        let zeros = self.zeros()?;
        let mut zero_left: Vec<Root> = zeros.clone();
        let mut cancelled = Vec::new();
        let mut pole_left = Vec::new();
        for p in &poles {
            let mut m = p.multiplicity;
            if let Some(z) = zero_left
                .iter_mut()
                .find(|z| z.multiplicity > 0 && same_root(z.value, p.value))
            {
                let k = m.min(z.multiplicity);
                z.multiplicity -= k;
                m -= k;
                cancelled.push(Root {
                    value: p.value,
                    multiplicity: k,
                });
            }
            if m > 0 {
                pole_left.push(Root {
                    value: p.value,
                    multiplicity: m,
                });
            }
        }
        zero_left.retain(|z| z.multiplicity > 0);
        let reduced = if cancelled.is_empty() {
            self.clone()
        } else {
            let common = Poly::from_root_list(&cancelled)?;
            let (num, _) = self.num().div_rem(&common)?;
            let (den, _) = self.den().div_rem(&common)?;
            TransferFunction::new(num, den)?
        };
        let zeros_at_infinity = if self.num().is_zero() {
            0
        } else {
            self.relative_degree().max(0) as usize
        };
        Ok(PoleZero {
            poles,
            zeros,
            cancelled,
            reduced_poles: pole_left,
            reduced_zeros: zero_left,
            zeros_at_infinity,
            reduced,
        })
    }

    /// dc gain lim s→0 of the reduced G: `None` when infinite (a pole at s = 0 remains).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let g = TransferFunction::from_descending(&[1.0, 0.0], &[1.0, 1.0, 0.0]).unwrap();
    /// assert_eq!(g.dc_gain().unwrap(), Some(1.0)); // s/(s(s+1)) → 1
    /// let i = TransferFunction::from_descending(&[1.0], &[1.0, 0.0]).unwrap();
    /// assert_eq!(i.dc_gain().unwrap(), None);       // 1/s
    /// ```
    pub fn dc_gain(&self) -> Result<Option<f64>> {
        Ok(dc_gain_of(&self.pole_zero()?.reduced))
    }
}

/// dc gain of a transfer function already in lowest terms.
pub(crate) fn dc_gain_of(reduced: &TransferFunction) -> Option<f64> {
    let n0 = reduced.num().coeff(0);
    let d0 = reduced.den().coeff(0);
    if d0 == 0.0 {
        // A pole at the origin remains (exactly: zero roots are deflated exactly), unless the
        // numerator is zero too, which cannot happen in lowest terms except for G = 0.
        if reduced.num().is_zero() {
            Some(0.0)
        } else {
            None
        }
    } else {
        Some(n0 / d0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_cancellation_keeps_polynomials() {
        let g = TransferFunction::from_descending(&[1.0, 3.0], &[1.0, 3.0, 2.0]).unwrap();
        let pz = g.pole_zero().unwrap();
        assert!(pz.cancelled.is_empty());
        assert_eq!(pz.reduced, g);
        assert_eq!(pz.reduced_poles.len(), 2);
    }

    #[test]
    fn partial_cancellation_of_a_double_pole() {
        // (s+1) / (s+1)^2 (s+2)
        let g = TransferFunction::from_descending(&[1.0, 1.0], &[1.0, 4.0, 5.0, 2.0]).unwrap();
        let pz = g.pole_zero().unwrap();
        assert_eq!(pz.cancelled.len(), 1);
        assert_eq!(pz.cancelled[0].multiplicity, 1);
        assert_eq!(pz.reduced.order(), 2);
        let c = pz.reduced.den().coeffs();
        assert!((c[1] - 3.0).abs() < 1e-14 && (c[2] - 2.0).abs() < 1e-14);
        assert_eq!(pz.reduced.num().degree(), 0);
    }

    #[test]
    fn dc_gain_cases() {
        let g = TransferFunction::from_descending(&[0.0], &[1.0, 1.0]).unwrap();
        assert_eq!(g.dc_gain().unwrap(), Some(0.0));
        let g = TransferFunction::from_descending(&[3.0], &[2.0, 1.0]).unwrap();
        assert_eq!(g.dc_gain().unwrap(), Some(3.0));
        let g = TransferFunction::from_descending(&[1.0, 0.0, 0.0], &[1.0, 0.0, 0.0]).unwrap();
        assert_eq!(g.dc_gain().unwrap(), Some(1.0));
    }
}
