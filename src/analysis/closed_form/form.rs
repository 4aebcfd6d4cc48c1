//! The closed form itself: a sum of [`ClosedFormTerm`]s, from a partial-fraction expansion,
//! evaluated with its derivative and envelope (see the [module docs](super)).

use num_complex::Complex64;
use serde::Serialize;

use super::sequence::SequenceForm;
use super::term::{ClosedFormTerm, group_term};
use crate::analysis::pfe::PartialFractions;

/// A closed-form time function: a sum of [`ClosedFormTerm`]s — or, for a discrete-time
/// plant, a closed-form sequence y\[k\] ([`SequenceForm`], [`ClosedForm::sequence`]), which
/// every method then answers for: [`ClosedForm::eval`] reads the sample at or before t and
/// the text says `y[k] = …`.
///
/// ```
/// use ltikit::TransferFunction;
/// use ltikit::analysis::{ClosedForm, Input};
/// // Step response of 1/(s² + s + 1) (ζ = 0.5, ωₙ = 1)
/// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0, 1.0]).unwrap();
/// let y: ClosedForm = g.inverse_laplace(&Input::Step, &[]).unwrap().closed_form;
/// assert_eq!(y.to_string(), "y(t) = 1 - 1.1547 e^(-0.5 t) cos(0.866025 t - 0.523599)");
/// assert!((y.eval(0.0)).abs() < 1e-15);
/// assert!((y.eval(40.0) - 1.0).abs() < 1e-8);
/// ```
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct ClosedForm {
    pub(super) terms: Vec<ClosedFormTerm>,
    /// The sequence of a discrete-time response (then `terms` is empty).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) sequence: Option<SequenceForm>,
    /// Dead time T (s): the function is the terms at t − T, and 0 before T.
    #[serde(skip_serializing_if = "is_no_delay")]
    pub(super) delay: f64,
}

fn is_no_delay(t: &f64) -> bool {
    *t == 0.0
}

impl ClosedForm {
    /// From terms (groups whose coefficients are all exactly zero are dropped).
    pub fn new(terms: Vec<ClosedFormTerm>) -> ClosedForm {
        ClosedForm {
            terms: terms.into_iter().filter(|t| !t.is_zero()).collect(),
            sequence: None,
            delay: 0.0,
        }
    }

    /// A closed-form sequence y\[k\] of a discrete-time response as a closed form.
    ///
    /// ```
    /// use ltikit::analysis::{ClosedForm, SequenceForm, SequenceTerm};
    /// let y = ClosedForm::from_sequence(SequenceForm::new(0.5, vec![SequenceTerm::Real {
    ///     pole: 0.5,
    ///     coefficients: vec![2.0],
    /// }]));
    /// assert_eq!(y.to_string(), "y[k] = 2·0.5^k");
    /// assert_eq!(y.eval(1.2), 0.5); // t = 1.2 s reads k = 2
    /// assert!(y.terms().is_empty() && y.sequence().is_some());
    /// ```
    pub fn from_sequence(sequence: SequenceForm) -> ClosedForm {
        ClosedForm {
            terms: Vec::new(),
            sequence: Some(sequence),
            delay: 0.0,
        }
    }

    /// The same function delayed by `delay` seconds: f(t − T)·1(t − T) (a sequence is not
    /// delayed here: a discrete delay is part of its rational model).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::Input;
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap();
    /// let y = g.inverse_laplace(&Input::Step, &[]).unwrap().closed_form.with_delay(2.0);
    /// assert_eq!(y.to_string(), "y(t) = f(t - 2)·1(t - 2), f(t) = 1 - e^(-t)");
    /// assert_eq!(y.eval(1.5), 0.0);
    /// assert!((y.eval(3.0) - (1.0 - (-1f64).exp())).abs() < 1e-15);
    /// ```
    pub fn with_delay(mut self, delay: f64) -> ClosedForm {
        if self.sequence.is_none() {
            self.delay = delay;
        }
        self
    }

    /// The dead time T of a delayed closed form (0 for none).
    pub fn delay(&self) -> f64 {
        self.delay
    }

    /// The closed-form sequence of a discrete-time response (`None` in continuous time).
    pub fn sequence(&self) -> Option<&SequenceForm> {
        self.sequence.as_ref()
    }

    /// The inverse Laplace transform of a partial-fraction expansion. Terms of the same pole
    /// are grouped; for a conjugate pair only the upper member's residues are used (they are
    /// exact conjugates, see [`crate::analysis::pfe`]).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::ClosedForm;
    /// // 1/(s + 1)² ↔ t e^(−t)
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 2.0, 1.0]).unwrap();
    /// let h = ClosedForm::from_partial_fractions(&g.partial_fractions().unwrap());
    /// assert_eq!(h.expression(), "t e^(-t)");
    /// assert!((h.eval(2.0) - 2.0 * (-2f64).exp()).abs() < 1e-16);
    /// ```
    pub fn from_partial_fractions(pf: &PartialFractions) -> ClosedForm {
        let mut terms = Vec::new();
        let nd = pf.direct.len();
        for (i, &c) in pf.direct.iter().enumerate().rev() {
            terms.push(ClosedFormTerm::Impulse {
                derivative: nd - 1 - i,
                coefficient: c,
            });
        }
        let groups = pf.by_pole();
        for (p, res) in groups {
            terms.push(group_term(p, &res));
        }
        ClosedForm::new(terms)
    }

    /// The terms of a continuous-time closed form (empty for a sequence: see
    /// [`ClosedForm::sequence`]).
    pub fn terms(&self) -> &[ClosedFormTerm] {
        &self.terms
    }

    /// True when the function is identically zero.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty() && self.sequence.as_ref().is_none_or(SequenceForm::is_zero)
    }

    /// y(t) for t ≥ 0, δ terms excluded (at t = 0 this is y(0⁺)); 0 for t < 0; NaN for NaN.
    /// For a sequence: the sample y\[k\] at or before t ([`SequenceForm::eval_at`], δ terms
    /// included: they are samples).
    pub fn eval(&self, t: f64) -> f64 {
        if let Some(s) = &self.sequence {
            return s.eval_at(t);
        }
        let t = t - self.delay;
        if t < 0.0 {
            return 0.0;
        }
        self.terms.iter().map(|x| x.eval(t)).sum()
    }

    /// y′(t) for t ≥ 0 (the smooth part; δ terms excluded); NaN for a sequence, which has no
    /// derivative.
    pub fn eval_derivative(&self, t: f64) -> f64 {
        if self.sequence.is_some() {
            return f64::NAN;
        }
        let t = t - self.delay;
        if t < 0.0 {
            return 0.0;
        }
        self.terms.iter().map(|x| x.eval_derivative(t)).sum()
    }

    /// Σ over terms of their envelopes Σ|cₖ|tᵏe^(σt): a bound on |y(t)| and the scale of the
    /// rounding error of [`ClosedForm::eval`] (≈ a few eps times this); for a sequence the
    /// envelope of the sample at or before t.
    pub fn envelope(&self, t: f64) -> f64 {
        if let Some(s) = &self.sequence {
            return if t < 0.0 {
                0.0
            } else {
                s.envelope(super::sequence::sample_of(t, s.dt))
            };
        }
        let t = t - self.delay;
        if t < 0.0 {
            return 0.0;
        }
        self.terms.iter().map(|x| x.envelope(t)).sum()
    }

    /// The terms for which `keep(pole)` holds (δ terms are kept when `keep_impulses`).
    pub(crate) fn filtered(
        &self,
        keep: impl Fn(Complex64) -> bool,
        keep_impulses: bool,
    ) -> ClosedForm {
        if let Some(s) = &self.sequence {
            return ClosedForm::from_sequence(s.filtered(keep, keep_impulses));
        }
        ClosedForm {
            sequence: None,
            delay: self.delay,
            terms: self
                .terms
                .iter()
                .filter(|t| t.pole().map_or(keep_impulses, &keep))
                .cloned()
                .collect(),
        }
    }
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact values are meant: 0 before t = 0, exact dc gains
mod tests {
    use super::*;
    use crate::analysis::pfe::PfTerm;

    fn pf(terms: &[(Complex64, usize, Complex64)], direct: &[f64]) -> PartialFractions {
        PartialFractions {
            terms: terms
                .iter()
                .map(|&(pole, power, residue)| PfTerm {
                    pole,
                    power,
                    residue,
                })
                .collect(),
            direct: direct.to_vec(),
        }
    }
    fn c(re: f64, im: f64) -> Complex64 {
        Complex64::new(re, im)
    }

    #[test]
    fn critically_damped_grouping() {
        // 1/s − 1/(s+1) − 1/(s+1)²  ↔  1 − (1 + t) e^(−t)
        let p = pf(
            &[
                (c(0.0, 0.0), 1, c(1.0, 0.0)),
                (c(-1.0, 0.0), 1, c(-1.0, 0.0)),
                (c(-1.0, 0.0), 2, c(-1.0, 0.0)),
            ],
            &[],
        );
        let y = ClosedForm::from_partial_fractions(&p);
        assert_eq!(y.to_string(), "y(t) = 1 - (1 + t) e^(-t)");
        let t: f64 = 0.7;
        assert!((y.eval(t) - (1.0 - (1.0 + t) * (-t).exp())).abs() < 1e-16);
        assert!((y.eval_derivative(t) - t * (-t).exp()).abs() < 1e-16);
    }

    #[test]
    fn oscillatory_and_impulse_terms() {
        // 2 δ(t) + δ'(t) and the pair −1 ± 2j with residues ∓0.25j: 0.5 e^(−t) sin(2t)
        let p = pf(
            &[
                (c(-1.0, 2.0), 1, c(0.0, -0.25)),
                (c(-1.0, -2.0), 1, c(0.0, 0.25)),
            ],
            &[1.0, 2.0],
        );
        let y = ClosedForm::from_partial_fractions(&p);
        assert_eq!(
            y.expression(),
            "2 δ(t) + δ'(t) + 0.5 e^(-t) cos(2 t - 1.5708)"
        );
        let t: f64 = 1.3;
        let want = 0.5 * (-t).exp() * (2.0 * t).sin();
        assert!((y.eval(t) - want).abs() < 1e-16);
        let dwant = 0.5 * (-t).exp() * (2.0 * (2.0 * t).cos() - (2.0 * t).sin());
        assert!((y.eval_derivative(t) - dwant).abs() < 1e-15);
    }

    #[test]
    fn repeated_pair_and_envelope() {
        // residues at −0.5 ± j: power 1: 1, power 2: j  → 2 e^(−t/2) (cos t − t sin t)
        let p = pf(
            &[
                (c(-0.5, 1.0), 1, c(1.0, 0.0)),
                (c(-0.5, 1.0), 2, c(0.0, 1.0)),
                (c(-0.5, -1.0), 1, c(1.0, 0.0)),
                (c(-0.5, -1.0), 2, c(0.0, -1.0)),
            ],
            &[],
        );
        let y = ClosedForm::from_partial_fractions(&p);
        assert_eq!(
            y.expression(),
            "e^(-0.5 t) (2 cos(t) + 2 t cos(t + 1.5708))"
        );
        let t: f64 = 2.2;
        let want = 2.0 * (-0.5 * t).exp() * (t.cos() - t * t.sin());
        assert!((y.eval(t) - want).abs() < 1e-15);
        assert!(y.envelope(t) >= want.abs());
        let h = 1e-6;
        let fd = (y.eval(t + h) - y.eval(t - h)) / (2.0 * h);
        assert!((y.eval_derivative(t) - fd).abs() < 1e-8);
    }

    #[test]
    fn empty_and_negative_time() {
        let y = ClosedForm::default();
        assert_eq!(y.to_string(), "y(t) = 0");
        let p = pf(&[(c(-1.0, 0.0), 1, c(3.0, 0.0))], &[]);
        let y = ClosedForm::from_partial_fractions(&p);
        assert_eq!(y.eval(-1.0), 0.0);
        assert_eq!(y.expression(), "3 e^(-t)");
        assert!(y.eval(f64::NAN).is_nan());
    }
}
