//! The complete analysis of one plant (what `ltikit analyze` reports).

use serde::Serialize;

use crate::analysis::{
    Factored, Mode, NEAR_PAIR_REL, NearPair, PoleZero, SecondOrder, Stability, StepInfo,
    StructurePath,
};
use crate::error::Result;
use crate::lti::TransferFunction;

/// Poles and zeros, stability, modes, damping class and step metrics of a plant.
#[derive(Debug, Clone, Serialize)]
pub struct Analysis {
    /// The sampling period of a discrete-time plant (`None`: continuous time).
    pub dt: Option<f64>,
    /// System order (degree of the characteristic polynomial).
    pub order: usize,
    /// deg D − deg N (negative for an improper G); `None` for G ≡ 0.
    pub relative_degree: Option<i64>,
    /// Poles, zeros, cancellations and the reduced G.
    pub pole_zero: PoleZero,
    /// Zeros within a relative [`NEAR_PAIR_REL`] of a pole that do not cancel it (closest
    /// first); `minreal` cancels them on request.
    pub near_cancellations: Vec<NearPair>,
    /// dc gain of the reduced G; `None` when infinite.
    pub dc_gain: Option<f64>,
    /// BIBO and internal stability with reasons.
    pub stability: Stability,
    /// One mode per distinct pole of the characteristic polynomial.
    pub modes: Vec<Mode>,
    /// ωₙ, ζ, ω_d and the damping class when the characteristic polynomial has degree 2.
    pub second_order: Option<SecondOrder>,
    /// Step metrics; `None` when the step response does not settle, settles to 0, G is
    /// improper, or the metrics could not be computed — [`Analysis::step_info_note`] says
    /// which. A metric that alone could not be computed is `None` inside with its note.
    pub step_info: Option<StepInfo>,
    /// Why there are no step metrics (set exactly when `step_info` is `None`).
    pub step_info_note: Option<String>,
    /// Which path decided the structure (exact for coefficients typed as text).
    pub structure: StructurePath,
    /// The same in one line, with the reason when exact input went the numerical way.
    pub structure_note: String,
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
    /// assert!((si.overshoot_percent.unwrap() - 52.66).abs() < 0.01); // e^(−πζ/√(1−ζ²)), ζ = 0.2
    /// ```
    pub fn analyze(&self) -> Result<Analysis> {
        self.factored()?.analyze()
    }
}

impl Factored {
    /// Everything `ltikit analyze` reports, on this factorisation.
    pub fn analyze(&self) -> Result<Analysis> {
        let (step_info, step_info_note) = self.step_info_or_note();
        Ok(Analysis {
            dt: self.domain().dt(),
            order: self.order(),
            relative_degree: self.relative_degree(),
            pole_zero: self.pole_zero().clone(),
            near_cancellations: self.near_cancellations(NEAR_PAIR_REL),
            dc_gain: self.dc_gain(),
            stability: self.stability(),
            modes: self.modes(),
            second_order: self.second_order(),
            step_info,
            step_info_note,
            structure: self.structure_path(),
            structure_note: self.structure_note(),
        })
    }

    /// The step metrics, or why there are none: a failure here is reported in its place and
    /// does not take the rest of the analysis down.
    fn step_info_or_note(&self) -> (Option<StepInfo>, Option<String>) {
        if !self.is_proper() {
            return (
                None,
                Some("no step metrics: G is improper (its step response has impulses)".into()),
            );
        }
        match self.step_info() {
            Ok(Some(si)) => (Some(si), None),
            Ok(None) => (None, Some(self.why_no_step_info())),
            Err(e) => (None, Some(format!("no step metrics: not computed: {e}"))),
        }
    }

    /// Why a proper G has no step metrics (it does not settle, or settles to 0).
    fn why_no_step_info(&self) -> String {
        match self.dc_gain() {
            _ if self.has_unstable_pole() => format!(
                "does not settle (no step metrics: a pole of the reduced G is not {})",
                if self.domain().is_discrete() {
                    "strictly inside the unit circle"
                } else {
                    "in the open left half plane"
                }
            ),
            Some(0.0) => "settles to 0 (no step metrics: rise time, overshoot and \
                 settling are relative to a non-zero final value)"
                .into(),
            _ => "does not settle (no step metrics: infinite dc gain)".into(),
        }
    }
}
