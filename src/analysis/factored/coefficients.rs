//! A plant given by the coefficients of its ODE: factored by the roots of its numerator and
//! denominator (the numerical path; coefficients that arrived as text take the exact path,
//! `exact.rs`, first).

use super::decision::Decision;
use super::form::{Factored, assemble};
use super::pole_zero::PoleZero;
use super::source::Source;
use crate::error::Result;
use crate::lti::TransferFunction;
use crate::poly::Poly;

impl TransferFunction {
    /// The factored form of G: roots of the numerator and denominator with exact
    /// multiplicities, the cancelled common roots and the reduced form. Every analysis method
    /// of [`TransferFunction`] calls this first; call it once yourself to run several
    /// analyses on one factorisation.
    ///
    /// Errors: the root finder's ([`crate::Poly::roots`]).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // s / (s (s + 1)): the pole at 0 cancels, the reduced G is 1/(s + 1).
    /// let g = TransferFunction::from_descending(&[1.0, 0.0], &[1.0, 1.0, 0.0]).unwrap();
    /// let f = g.factored().unwrap();
    /// assert_eq!(f.pole_zero().cancelled.len(), 1);
    /// assert_eq!(f.reduced_tf().unwrap().den().coeffs(), &[1.0, 1.0]);
    /// assert_eq!(f.pole_zero().zeros_at_infinity, Some(1));
    /// ```
    pub fn factored(&self) -> Result<Factored> {
        Factored::from_tf(self)?.with_delay(self.delay())
    }

    /// Poles, zeros, cancelled common roots and the reduced root lists
    /// ([`Factored::pole_zero`] of [`TransferFunction::factored`]).
    ///
    /// A numerator root and a denominator root cancel when they are the same root
    /// ([`crate::poly::same_root`]: 1e-8 relative; exactly for roots at s = 0).
    pub fn pole_zero(&self) -> Result<PoleZero> {
        Ok(self.factored()?.into_pole_zero())
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
        Ok(self.factored()?.dc_gain())
    }
}

impl Factored {
    /// Factors a transfer function given by its coefficients: the roots of the numerator and
    /// the denominator with exact multiplicities, the common roots that cancel, the reduced
    /// form (the same as [`TransferFunction::factored`]).
    ///
    /// Errors: the root finder's ([`crate::Poly::roots`]).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::Factored;
    /// // (s + 1)/((s + 1)(s + 2)): the pole −1 cancels.
    /// let g = TransferFunction::from_descending(&[1.0, 1.0], &[1.0, 3.0, 2.0]).unwrap();
    /// let f = Factored::from_tf(&g).unwrap();
    /// assert_eq!(f.poles().len(), 2);
    /// assert_eq!(f.reduced_poles().len(), 1);
    /// assert!((f.dc_gain().unwrap() - 0.5).abs() < 1e-15);
    /// ```
    pub fn from_tf(tf: &TransferFunction) -> Result<Factored> {
        Factored::from_tf_deciding(tf, Decision::default())
    }

    /// [`Factored::from_tf`] with the structure decision recorded (a numerical fallback of
    /// exact input says why).
    pub(super) fn from_tf_deciding(tf: &TransferFunction, decision: Decision) -> Result<Factored> {
        let zero = tf.num().is_zero();
        // a root within its error bound of the imaginary axis is put on it (printed and used
        // as ±jβ: nothing more is known of it)
        // (in z the imaginary axis means nothing: no snapping)
        let snap = |p: &Poly, r| {
            if tf.domain().is_discrete() {
                r
            } else {
                crate::poly::roots::snap_to_axis(p, r)
            }
        };
        let poles = snap(tf.den(), tf.den().roots()?);
        let zeros = if zero {
            Vec::new()
        } else {
            snap(tf.num(), tf.num().roots()?)
        };
        let pz = PoleZero::new(poles, zeros, zero);
        let source = coefficient_source(tf.clone(), &pz)?;
        Ok(
            assemble(pz, if zero { 0.0 } else { tf.gain() }, source, decision)
                .with_domain(tf.domain()),
        )
    }
}

/// The source of a plant given by the coefficients `tf`, with roots `pz`: the coefficients as
/// given and in lowest terms (divided by the cancelled common factor).
pub(super) fn coefficient_source(tf: TransferFunction, pz: &PoleZero) -> Result<Source> {
    let reduced = if pz.cancelled.is_empty() {
        tf.clone()
    } else {
        let common = Poly::from_root_list(&pz.cancelled)?;
        let (num, _) = tf.num().div_rem(&common)?;
        let (den, _) = tf.den().div_rem(&common)?;
        TransferFunction::new(num, den)?.with_domain(tf.domain())
    };
    Ok(Source::coefficients_of(tf, reduced))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_transfer_function() {
        let g = TransferFunction::from_descending(&[0.0], &[1.0, 1.0]).unwrap();
        let f = g.factored().unwrap();
        assert!(f.is_zero());
        assert_eq!(f.relative_degree(), None);
        assert_eq!(f.dc_gain(), Some(0.0));
        assert!(f.require_proper("x", true).is_ok());
    }
}
