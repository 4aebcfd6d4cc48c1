//! One group of a closed form ([`ClosedFormTerm`]): δ terms, a real pole's polynomial times
//! an exponential, a conjugate pair's damped cosines — and how a pole's residues become one.

use std::f64::consts::{FRAC_PI_2, PI};

use num_complex::Complex64;
use serde::Serialize;

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

    pub(super) fn is_zero(&self) -> bool {
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

/// Phases within this of ±π/2 keep a positive amplitude: sin(ωt) prints as
/// `cos(ω t - 1.5708)`, not `-cos(ω t + 1.5708)`, whichever side of −π/2 rounding put arg r.
const PHASE_SLACK: f64 = 1e-12;

/// The real-form group of pole p (upper member or real) with residues r₁ … r_m.
pub(super) fn group_term(p: Complex64, res: &[Complex64]) -> ClosedFormTerm {
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
