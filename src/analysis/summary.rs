//! The complete analysis of one plant (what `ltikit analyze` reports).

use serde::Serialize;

use crate::analysis::{Mode, PoleZero, SecondOrder, Stability, StepInfo, modes, second_order};
use crate::error::Result;
use crate::lti::TransferFunction;

/// Poles and zeros, stability, modes, damping class and step metrics of a plant.
#[derive(Debug, Clone, Serialize)]
pub struct Analysis {
    /// System order (degree of the characteristic polynomial).
    pub order: usize,
    /// deg D − deg N (negative for an improper G).
    pub relative_degree: i64,
    /// Poles, zeros, cancellations and the reduced G.
    pub pole_zero: PoleZero,
    /// dc gain of the reduced G; `None` when infinite.
    pub dc_gain: Option<f64>,
    /// BIBO and internal stability with reasons.
    pub stability: Stability,
    /// One mode per distinct pole of the characteristic polynomial.
    pub modes: Vec<Mode>,
    /// ωₙ, ζ, ω_d and the damping class when the characteristic polynomial has degree 2.
    pub second_order: Option<SecondOrder>,
    /// Step metrics; `None` when the step response does not settle (or G is improper).
    pub step_info: Option<StepInfo>,
}

impl TransferFunction {
    /// Everything `ltikit analyze` reports.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let a = TransferFunction::from_descending(&[4.0], &[1.0, 0.8, 4.0]).unwrap().analyze().unwrap();
    /// assert_eq!(a.order, 2);
    /// assert!(a.stability.bibo_stable);
    /// assert_eq!(a.dc_gain, Some(1.0));
    /// let si = a.step_info.unwrap();
    /// assert!((si.overshoot_percent - 52.66).abs() < 0.01); // e^(−πζ/√(1−ζ²)), ζ = 0.2
    /// ```
    pub fn analyze(&self) -> Result<Analysis> {
        let pz = self.pole_zero()?;
        let dc_gain = crate::analysis::pz::dc_gain_of(&pz.reduced);
        let stability =
            crate::analysis::stability::stability_of(&pz.poles, &pz.reduced_poles, &pz.cancelled);
        let modes = modes(&pz.poles);
        let second_order = second_order(self.den(), &pz.poles);
        let step_info = if self.is_proper() {
            crate::analysis::step_info::step_info_with(self, &pz)?
        } else {
            None
        };
        Ok(Analysis {
            order: self.order(),
            relative_degree: self.relative_degree(),
            pole_zero: pz,
            dc_gain,
            stability,
            modes,
            second_order,
            step_info,
        })
    }
}
