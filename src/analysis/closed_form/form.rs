//! Closed-form time functions in real form: the inverse Laplace transform of a partial-fraction
//! expansion.
//!
//! A term r/(s − p)^k is r·t^(k−1)/(k−1)!·e^(pt). Terms are grouped by pole:
//! - the direct polynomial Σ cₖ sᵏ gives cₖ·δ^(k)(t);
//! - a real pole p of multiplicity m gives (c₀ + c₁t + … + c_{m−1}t^(m−1))·e^(pt);
//! - a conjugate pair σ ± jω gives e^(σt)·Σₖ Aₖ tᵏ cos(ωt + φₖ) (seed eq. 3.33), with
//!   Aₖ = 2|r_{k+1}|/k! and φₖ = arg r_{k+1}, normalised to φₖ ∈ [−π/2, π/2] by moving the sign
//!   into Aₖ (at ±π/2 the amplitude stays positive), so a step response reads
//!   `1 - 1.1547 e^(-0.5 t) cos(0.866025 t - 0.523599)` and sin t reads `cos(t - 1.5708)`.
//!
//! [`ClosedForm::eval`] is the smooth part for t ≥ 0 (δ terms excluded; 0 for t < 0: every
//! term carries 1(t)).

mod text;

use std::f64::consts::{FRAC_PI_2, PI};

use num_complex::Complex64;
use serde::Serialize;

use crate::analysis::pfe::PartialFractions;

/// One group of a closed form.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum ClosedFormTerm {
    /// coefficient·δ^(derivative)(t).
    Impulse {
        /// Order of the derivative of δ (0 for δ itself).
        derivative: usize,
        /// Its weight.
        coefficient: f64,
    },
    /// (c₀ + c₁ t + c₂ t² + …)·e^(pole·t) for a real pole.
    Real {
        /// The pole.
        pole: f64,
        /// c₀, c₁, … (ascending powers of t).
        coefficients: Vec<f64>,
    },
    /// e^(σt)·Σₖ Aₖ tᵏ cos(ωt + φₖ) for the conjugate pair σ ± jω (ω > 0).
    Oscillatory {
        /// Real part σ of the pair.
        sigma: f64,
        /// Imaginary part ω > 0 of the upper member.
        omega: f64,
        /// A₀, A₁, … (signed; ascending powers of t).
        amplitudes: Vec<f64>,
        /// φ₀, φ₁, … in [−π/2, π/2] (rad).
        phases: Vec<f64>,
    },
}

impl ClosedFormTerm {
    /// Value at t ≥ 0 (0 for δ terms).
    pub fn eval(&self, t: f64) -> f64 {
        match self {
            ClosedFormTerm::Impulse { .. } => 0.0,
            ClosedFormTerm::Real { pole, coefficients } => {
                horner(coefficients, t) * exp_or_one(*pole, t)
            }
            ClosedFormTerm::Oscillatory {
                sigma,
                omega,
                amplitudes,
                phases,
            } => {
                let mut acc = 0.0;
                let mut tk = 1.0;
                for (a, ph) in amplitudes.iter().zip(phases) {
                    acc += a * tk * (omega * t + ph).cos();
                    tk *= t;
                }
                acc * exp_or_one(*sigma, t)
            }
        }
    }

    /// Time derivative at t ≥ 0 (0 for δ terms).
    pub fn eval_derivative(&self, t: f64) -> f64 {
        match self {
            ClosedFormTerm::Impulse { .. } => 0.0,
            ClosedFormTerm::Real { pole, coefficients } => {
                // d/dt Σ c_k t^k e^{pt} = e^{pt} Σ (k c_k t^{k−1} + p c_k t^k)
                let mut acc = 0.0;
                let mut tk = 1.0; // t^k
                let mut tkm1 = 0.0; // t^{k−1}
                for (k, c) in coefficients.iter().enumerate() {
                    acc += c * (k as f64 * tkm1 + pole * tk);
                    tkm1 = tk;
                    tk *= t;
                }
                acc * exp_or_one(*pole, t)
            }
            ClosedFormTerm::Oscillatory {
                sigma,
                omega,
                amplitudes,
                phases,
            } => {
                let mut acc = 0.0;
                let mut tk = 1.0;
                let mut tkm1 = 0.0;
                for (k, (a, ph)) in amplitudes.iter().zip(phases).enumerate() {
                    let th = omega * t + ph;
                    acc += a * ((k as f64 * tkm1 + sigma * tk) * th.cos() - omega * tk * th.sin());
                    tkm1 = tk;
                    tk *= t;
                }
                acc * exp_or_one(*sigma, t)
            }
        }
    }

    /// A bound on |term(t)|: Σ|cₖ|tᵏe^(σt) (0 for δ terms).
    pub fn envelope(&self, t: f64) -> f64 {
        match self {
            ClosedFormTerm::Impulse { .. } => 0.0,
            ClosedFormTerm::Real { pole, coefficients } => {
                abs_horner(coefficients, t) * exp_or_one(*pole, t)
            }
            ClosedFormTerm::Oscillatory {
                sigma, amplitudes, ..
            } => abs_horner(amplitudes, t) * exp_or_one(*sigma, t),
        }
    }

    /// The pole of the group (upper member for a pair); `None` for δ terms.
    pub fn pole(&self) -> Option<Complex64> {
        match self {
            ClosedFormTerm::Impulse { .. } => None,
            ClosedFormTerm::Real { pole, .. } => Some(Complex64::new(*pole, 0.0)),
            ClosedFormTerm::Oscillatory { sigma, omega, .. } => {
                Some(Complex64::new(*sigma, *omega))
            }
        }
    }

    /// Highest power of t present (multiplicity − 1); 0 for δ terms.
    pub fn max_power(&self) -> usize {
        match self {
            ClosedFormTerm::Impulse { .. } => 0,
            ClosedFormTerm::Real { coefficients, .. } => coefficients.len().saturating_sub(1),
            ClosedFormTerm::Oscillatory { amplitudes, .. } => amplitudes.len().saturating_sub(1),
        }
    }

    fn is_zero(&self) -> bool {
        match self {
            ClosedFormTerm::Impulse { coefficient, .. } => *coefficient == 0.0,
            ClosedFormTerm::Real { coefficients, .. } => coefficients.iter().all(|c| *c == 0.0),
            ClosedFormTerm::Oscillatory { amplitudes, .. } => amplitudes.iter().all(|c| *c == 0.0),
        }
    }
}

fn exp_or_one(rate: f64, t: f64) -> f64 {
    if rate == 0.0 { 1.0 } else { (rate * t).exp() }
}

/// Σ cₖ tᵏ with coefficients ascending.
fn horner(c: &[f64], t: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &x| acc * t + x)
}

fn abs_horner(c: &[f64], t: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &x| acc * t.abs() + x.abs())
}

/// A closed-form time function: a sum of [`ClosedFormTerm`]s.
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
    terms: Vec<ClosedFormTerm>,
}

impl ClosedForm {
    /// From terms (groups whose coefficients are all exactly zero are dropped).
    pub fn new(terms: Vec<ClosedFormTerm>) -> ClosedForm {
        ClosedForm {
            terms: terms.into_iter().filter(|t| !t.is_zero()).collect(),
        }
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
        // Group by pole (exact equality), in order of first appearance.
        let mut groups: Vec<(Complex64, Vec<Complex64>)> = Vec::new();
        for t in &pf.terms {
            if t.pole.im < 0.0 {
                continue;
            }
            let g = match groups.iter_mut().position(|(p, _)| *p == t.pole) {
                Some(k) => &mut groups[k].1,
                None => {
                    groups.push((t.pole, Vec::new()));
                    &mut groups.last_mut().expect("ok: just pushed").1
                }
            };
            if g.len() < t.power {
                g.resize(t.power, Complex64::new(0.0, 0.0));
            }
            g[t.power - 1] += t.residue;
        }
        for (p, res) in groups {
            terms.push(group_term(p, &res));
        }
        ClosedForm::new(terms)
    }

    /// The terms.
    pub fn terms(&self) -> &[ClosedFormTerm] {
        &self.terms
    }

    /// True when the function is identically zero.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// y(t) for t ≥ 0, δ terms excluded (at t = 0 this is y(0⁺)); 0 for t < 0; NaN for NaN.
    pub fn eval(&self, t: f64) -> f64 {
        if t < 0.0 {
            return 0.0;
        }
        self.terms.iter().map(|x| x.eval(t)).sum()
    }

    /// y′(t) for t ≥ 0 (the smooth part; δ terms excluded).
    pub fn eval_derivative(&self, t: f64) -> f64 {
        if t < 0.0 {
            return 0.0;
        }
        self.terms.iter().map(|x| x.eval_derivative(t)).sum()
    }

    /// Σ over terms of their envelopes Σ|cₖ|tᵏe^(σt): a bound on |y(t)| and the scale of the
    /// rounding error of [`ClosedForm::eval`] (≈ a few eps times this).
    pub fn envelope(&self, t: f64) -> f64 {
        self.terms.iter().map(|x| x.envelope(t)).sum()
    }

    /// The terms for which `keep(pole)` holds (δ terms are kept when `keep_impulses`).
    pub(crate) fn filtered(
        &self,
        keep: impl Fn(Complex64) -> bool,
        keep_impulses: bool,
    ) -> ClosedForm {
        ClosedForm {
            terms: self
                .terms
                .iter()
                .filter(|t| t.pole().map_or(keep_impulses, &keep))
                .cloned()
                .collect(),
        }
    }
}

/// Phases within this of ±π/2 keep a positive amplitude: sin(ωt) prints as
/// `cos(ω t - 1.5708)`, not `-cos(ω t + 1.5708)`, whichever side of −π/2 rounding put arg r.
const PHASE_SLACK: f64 = 1e-12;

/// The real-form group of pole p (upper member or real) with residues r₁ … r_m.
fn group_term(p: Complex64, res: &[Complex64]) -> ClosedFormTerm {
    let mut fact = 1.0;
    if p.im == 0.0 {
        let coefficients = res
            .iter()
            .enumerate()
            .map(|(k, r)| {
                if k > 0 {
                    fact *= k as f64;
                }
                r.re / fact
            })
            .collect();
        return ClosedFormTerm::Real {
            pole: p.re,
            coefficients,
        };
    }
    let mut amplitudes = Vec::with_capacity(res.len());
    let mut phases = Vec::with_capacity(res.len());
    for (k, r) in res.iter().enumerate() {
        if k > 0 {
            fact *= k as f64;
        }
        let mut a = 2.0 * r.norm() / fact;
        let mut ph = if a == 0.0 { 0.0 } else { r.arg() };
        if ph > FRAC_PI_2 + PHASE_SLACK {
            ph -= PI;
            a = -a;
        } else if ph < -FRAC_PI_2 - PHASE_SLACK {
            ph += PI;
            a = -a;
        }
        amplitudes.push(a);
        phases.push(ph);
    }
    ClosedFormTerm::Oscillatory {
        sigma: p.re,
        omega: p.im,
        amplitudes,
        phases,
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
