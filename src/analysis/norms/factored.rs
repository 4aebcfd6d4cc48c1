//! The norms of a SISO plant in factored form: realised as the cascade of its reduced poles
//! and zeros ([`crate::StateSpace::from_zpk`]), then the state-space norm. This is how the
//! peaks of a loop's S and T (Ms, Mt) are certified.

use super::hinf::{PeakGain, hinf_norm, linf_norm};
use crate::analysis::Factored;
use crate::error::Result;
use crate::lti::StateSpace;

impl Factored {
    /// The cascade realisation ([`StateSpace::from_zpk`]) of the reduced transfer function, in
    /// the plant's domain, its dead time (which changes no gain) left out: the state-space
    /// model the norms of a SISO plant are computed on.
    ///
    /// Errors: an improper plant.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // (s + 1)/((s + 1)(s + 2)) reduces to 1/(s + 2): one state
    /// let f = TransferFunction::from_descending(&[1.0, 1.0], &[1.0, 3.0, 2.0]).unwrap().factored().unwrap();
    /// assert_eq!(f.norm_realization().unwrap().order(), 1);
    /// ```
    pub fn norm_realization(&self) -> Result<StateSpace> {
        Ok(
            StateSpace::from_zpk(self.reduced_zeros(), self.reduced_poles(), self.gain())?
                .with_domain(self.domain()),
        )
    }

    /// The certified H∞ norm of the plant ([`hinf_norm`]); a dead time changes no gain.
    ///
    /// Errors: an improper plant; those of [`hinf_norm`].
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // 1/(s² + 0.2s + 1): 1/(2ζ√(1 − ζ²)) with ζ = 0.1
    /// let f = TransferFunction::from_descending(&[1.0], &[1.0, 0.2, 1.0]).unwrap().factored().unwrap();
    /// let n = f.hinf_norm().unwrap();
    /// let exact = 1.0 / (0.2 * 0.99f64.sqrt());
    /// assert!((n.lower / exact - 1.0).abs() < 1e-13 && n.upper >= exact);
    /// ```
    pub fn hinf_norm(&self) -> Result<PeakGain> {
        hinf_norm(&self.norm_realization()?)
    }

    /// The certified L∞ norm of the plant ([`linf_norm`]).
    ///
    /// Errors: as [`Factored::hinf_norm`].
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // 1/(s − 1): peak 1 at ω = 0
    /// let f = TransferFunction::from_descending(&[1.0], &[1.0, -1.0]).unwrap().factored().unwrap();
    /// assert!(f.hinf_norm().unwrap().infinite.is_some());
    /// assert_eq!(f.linf_norm().unwrap().lower, 1.0);
    /// ```
    pub fn linf_norm(&self) -> Result<PeakGain> {
        linf_norm(&self.norm_realization()?)
    }
}
