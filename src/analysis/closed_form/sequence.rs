//! Closed-form sequences y\[k\] in real form: the inverse z-transform of a partial-fraction
//! expansion of Y(z)/z.
//!
//! A term c/(z − p)^j of Y(z)/z is c·z/(z − p)^j in Y(z), whose inverse transform is
//! c·C(k, j−1)·p^(k−j+1) (k ≥ 0; zero for k < j − 1, where the binomial vanishes); at p = 0 it
//! is c·z^(1−j), the delayed unit sample c·δ\[k − (j−1)\]. The binomials are expanded in powers
//! of k (C(k, m) = k(k−1)…(k−m+1)/m!), so a pole of multiplicity m gives p^k times a
//! polynomial of degree m − 1 in k:
//! - a real pole p: (c₀ + c₁k + …)·p^k, written `0.5^k`, `(-0.5)^k`, and a polynomial in k
//!   alone at p = 1;
//! - a conjugate pair ρe^(±jθ): ρ^k·Σᵢ Aᵢ kⁱ cos(θk + φᵢ), with the phases in [−π/2, π/2] as
//!   in continuous time (the sign moved into Aᵢ);
//! - a pole at z = 0: Σ cₘ δ\[k − m\] (a finite impulse response).

use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt;

use num_complex::Complex64;
use serde::Serialize;

use super::words::{cos_of, product, signed_sum, var_power};
use crate::analysis::pfe::PartialFractions;
use crate::fmt::fmt_num;

/// One group of a closed-form sequence.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SequenceTerm {
    /// coefficient·δ\[k − delay\] (from a pole at z = 0).
    Delta {
        /// The delay m ≥ 0 in samples.
        delay: usize,
        /// Its weight.
        coefficient: f64,
    },
    /// (c₀ + c₁ k + c₂ k² + …)·p^k for a real pole p ≠ 0.
    Real {
        /// The pole p.
        pole: f64,
        /// c₀, c₁, … (ascending powers of k).
        coefficients: Vec<f64>,
    },
    /// ρ^k·Σᵢ Aᵢ kⁱ cos(θk + φᵢ) for the conjugate pair ρe^(±jθ), 0 < θ < π.
    Oscillatory {
        /// The upper member ρe^(jθ) (serialised as `[re, im]`).
        pole: Complex64,
        /// A₀, A₁, … (signed; ascending powers of k).
        amplitudes: Vec<f64>,
        /// φ₀, φ₁, … in [−π/2, π/2] (rad).
        phases: Vec<f64>,
    },
}

/// p^k for a real p and a sample index k (exact sign; |p|^k by `powf`, exactly 1 for p = 1).
#[allow(clippy::float_cmp)] // the pole z = 1 (a step's) is exact
fn real_power(p: f64, k: u64) -> f64 {
    if p == 1.0 {
        return 1.0;
    }
    let m = p.abs().powf(k as f64);
    if p < 0.0 && k & 1 == 1 { -m } else { m }
}

/// Σ cᵢ kⁱ with coefficients ascending.
fn horner(c: &[f64], k: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &x| acc * k + x)
}

impl SequenceTerm {
    /// The value at the sample k ≥ 0.
    pub fn eval(&self, k: u64) -> f64 {
        let kf = k as f64;
        match self {
            SequenceTerm::Delta { delay, coefficient } => {
                if k == *delay as u64 {
                    *coefficient
                } else {
                    0.0
                }
            }
            SequenceTerm::Real { pole, coefficients } => {
                horner(coefficients, kf) * real_power(*pole, k)
            }
            SequenceTerm::Oscillatory {
                pole,
                amplitudes,
                phases,
            } => {
                let (rho, theta) = (pole.norm(), pole.arg());
                let mut acc = 0.0;
                let mut kk = 1.0;
                for (a, ph) in amplitudes.iter().zip(phases) {
                    acc += a * kk * (theta * kf + ph).cos();
                    kk *= kf;
                }
                acc * real_power(rho, k)
            }
        }
    }

    /// A bound on |term\[k\]|: Σ|cᵢ|kⁱ|p|^k (|c| for a δ term at its delay).
    pub fn envelope(&self, k: u64) -> f64 {
        let kf = k as f64;
        let abs_horner = |c: &[f64]| c.iter().rev().fold(0.0, |acc, &x| acc * kf + x.abs());
        match self {
            SequenceTerm::Delta { .. } => self.eval(k).abs(),
            SequenceTerm::Real { pole, coefficients } => {
                abs_horner(coefficients) * real_power(pole.abs(), k)
            }
            SequenceTerm::Oscillatory {
                pole, amplitudes, ..
            } => abs_horner(amplitudes) * real_power(pole.norm(), k),
        }
    }

    /// The pole of the group (upper member for a pair); `None` for δ terms.
    pub fn pole(&self) -> Option<Complex64> {
        match self {
            SequenceTerm::Delta { .. } => None,
            SequenceTerm::Real { pole, .. } => Some(Complex64::new(*pole, 0.0)),
            SequenceTerm::Oscillatory { pole, .. } => Some(*pole),
        }
    }

    fn coefficients(&self) -> &[f64] {
        match self {
            SequenceTerm::Delta { coefficient, .. } => std::slice::from_ref(coefficient),
            SequenceTerm::Real { coefficients, .. } => coefficients,
            SequenceTerm::Oscillatory { amplitudes, .. } => amplitudes,
        }
    }

    fn is_zero(&self) -> bool {
        self.coefficients().iter().all(|c| *c == 0.0)
    }
}

/// A closed-form sequence y\[k\], k = 0, 1, 2, … at t = kT: a sum of [`SequenceTerm`]s (see
/// the module docs of `analysis::closed_form`).
///
/// ```
/// use ltikit::TransferFunction;
/// use ltikit::analysis::Input;
/// use ltikit::lti::Domain;
/// // G(z) = 0.5/(z − 0.5), T = 0.1 s: the step response is y[k] = 1 − 0.5^k
/// let g = TransferFunction::from_descending(&[0.5], &[1.0, -0.5]).unwrap()
///     .with_domain(Domain::discrete(0.1).unwrap());
/// let r = g.factored().unwrap().inverse_z(&Input::Step, &[]).unwrap();
/// let y = r.closed_form.sequence().unwrap();
/// assert_eq!(y.to_string(), "y[k] = 1 - 0.5^k");
/// assert_eq!(y.eval(3), 1.0 - 0.125);
/// assert_eq!(y.eval_at(0.35), 1.0 - 0.125); // t = 0.35 s reads the sample k = 3
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SequenceForm {
    /// The sampling period T in seconds (y\[k\] is the value at t = kT).
    pub dt: f64,
    pub(super) terms: Vec<SequenceTerm>,
}

/// Phases within this of ±π/2 keep a positive amplitude (as in continuous time).
const PHASE_SLACK: f64 = 1e-12;

impl SequenceForm {
    /// From terms (terms whose coefficients are all exactly zero are dropped).
    pub fn new(dt: f64, terms: Vec<SequenceTerm>) -> SequenceForm {
        SequenceForm {
            dt,
            terms: terms.into_iter().filter(|t| !t.is_zero()).collect(),
        }
    }

    /// The inverse z-transform of z·E(z), where `pf` is the partial-fraction expansion E(z) of
    /// Y(z)/z (strictly proper: a direct part would make y non-causal and is ignored). Terms
    /// of the same pole are grouped; for a conjugate pair only the upper member's residues are
    /// used (they are exact conjugates, see [`crate::analysis::pfe`]).
    ///
    /// ```
    /// use ltikit::analysis::SequenceForm;
    /// use ltikit::analysis::pfe::partial_fractions;
    /// use ltikit::Poly;
    /// // Y(z)/z = 1/(z − 0.5)²  ↔  y[k] = k·0.5^(k−1) = 2 k 0.5^k
    /// let e = partial_fractions(&Poly::constant(1.0), &Poly::from_descending(&[1.0, -1.0, 0.25]).unwrap()).unwrap();
    /// let y = SequenceForm::from_partial_fractions(&e, 1.0);
    /// assert_eq!(y.expression(), "2 k·0.5^k");
    /// assert!((y.eval(4) - 4.0 * 0.5f64.powi(3)).abs() < 1e-15);
    /// ```
    pub fn from_partial_fractions(pf: &PartialFractions, dt: f64) -> SequenceForm {
        let groups = pf.by_pole();
        let mut terms = Vec::new();
        for (p, res) in groups {
            if p == Complex64::new(0.0, 0.0) {
                // c/z^j ↔ c δ[k − (j − 1)]
                for (j, c) in res.iter().enumerate() {
                    terms.push(SequenceTerm::Delta {
                        delay: j,
                        coefficient: c.re,
                    });
                }
            } else {
                terms.push(power_group(p, &res));
            }
        }
        // δ terms first (in order of delay), then the poles as the expansion lists them
        terms.sort_by_key(|t| match t {
            SequenceTerm::Delta { delay, .. } => (0, *delay),
            _ => (1, 0),
        });
        SequenceForm::new(dt, terms)
    }

    /// The terms.
    pub fn terms(&self) -> &[SequenceTerm] {
        &self.terms
    }

    /// True when the sequence is identically zero.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// y\[k\].
    pub fn eval(&self, k: u64) -> f64 {
        self.terms.iter().map(|x| x.eval(k)).sum()
    }

    /// The sample a time t reads: y\[k\] for the last kT at or before t (the value held); 0 for
    /// t < 0, NaN for NaN.
    pub fn eval_at(&self, t: f64) -> f64 {
        if t.is_nan() {
            return f64::NAN;
        }
        if t < 0.0 {
            return 0.0;
        }
        self.eval(sample_of(t, self.dt))
    }

    /// The sample index k a time t ≥ 0 reads: the last kT at or before t (a time within
    /// rounding of a sample reads that sample).
    ///
    /// ```
    /// use ltikit::analysis::SequenceForm;
    /// let y = SequenceForm::new(0.1, vec![]);
    /// assert_eq!((y.sample(0.3), y.sample(0.29), y.sample(0.0)), (3, 2, 0));
    /// ```
    pub fn sample(&self, t: f64) -> u64 {
        sample_of(t, self.dt)
    }

    /// Σ over terms of their envelopes: a bound on |y\[k\]| and the scale of the rounding error
    /// of [`SequenceForm::eval`].
    pub fn envelope(&self, k: u64) -> f64 {
        self.terms.iter().map(|x| x.envelope(k)).sum()
    }

    /// The terms for which `keep(pole)` holds (δ terms are kept when `keep_deltas`).
    pub(crate) fn filtered(&self, keep: impl Fn(Complex64) -> bool, keep_deltas: bool) -> Self {
        SequenceForm {
            dt: self.dt,
            terms: self
                .terms
                .iter()
                .filter(|t| t.pole().map_or(keep_deltas, &keep))
                .cloned()
                .collect(),
        }
    }

    /// The right-hand side as text, e.g. `1 - 0.5^k`, `2 k·0.5^k`, `4 δ[k] - (4 - 4 k)·0.5^k`,
    /// `0.9^k (cos(0.5 k) + 0.2 k cos(0.5 k - 1.5708))`; `0` when empty.
    pub fn expression(&self) -> String {
        let scale = self
            .terms
            .iter()
            .flat_map(|t| t.coefficients().iter().map(|c| c.abs()))
            .fold(0.0, f64::max);
        // coefficients at rounding level relative to the largest one are not shown
        let noise = 8.0 * f64::EPSILON * scale;
        let pieces: Vec<(bool, String)> =
            self.terms.iter().flat_map(|t| pieces(t, noise)).collect();
        if pieces.is_empty() {
            return "0".into();
        }
        signed_sum(pieces)
    }

    /// `lhs = expression`, e.g. `formula("y_ss[k]")`.
    pub fn formula(&self, lhs: &str) -> String {
        format!("{lhs} = {}", self.expression())
    }
}

/// The sample a time reads, as a float: the last sample at or before t ≥ 0 (t/T rounded
/// down, with 4 ulps of slack so that k·T computed in floating point reads sample k). The one
/// rule of every discrete-time response: the closed form, the marched sequence, the
/// state-space march.
pub(crate) fn sample_floor(t: f64, dt: f64) -> f64 {
    (t / dt * (1.0 + 4.0 * f64::EPSILON)).floor()
}

/// [`sample_floor`] as an index (saturates at 2^64).
pub(crate) fn sample_of(t: f64, dt: f64) -> u64 {
    sample_floor(t, dt) as u64
}

impl fmt::Display for SequenceForm {
    /// `y[k] = …` (see [`SequenceForm::expression`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.formula("y[k]"))
    }
}

/// The real-form group of the pole p ≠ 0 (upper member or real) with the coefficients
/// c₁ … c_m of 1/(z − p)ʲ in Y(z)/z: p^k·Σᵢ bᵢ kⁱ with
/// Σᵢ bᵢ kⁱ = Σₘ c_{m+1} p^(−m) C(k, m).
fn power_group(p: Complex64, res: &[Complex64]) -> SequenceTerm {
    let m = res.len();
    let mut b = vec![Complex64::new(0.0, 0.0); m];
    // falling factorial k(k−1)…(k−j+1)/j! in ascending powers of k, and p^(−j)
    let mut fall = vec![1.0];
    let mut inv_p = Complex64::new(1.0, 0.0);
    for (j, c) in res.iter().enumerate() {
        if j > 0 {
            // × (k − (j − 1))/j
            let shift = (j - 1) as f64;
            let mut next = vec![0.0; fall.len() + 1];
            for (i, &f) in fall.iter().enumerate() {
                next[i + 1] += f / j as f64;
                next[i] -= f * shift / j as f64;
            }
            fall = next;
            inv_p /= p;
        }
        let w = c * inv_p;
        for (i, &f) in fall.iter().enumerate() {
            b[i] += w * f;
        }
    }
    if p.im == 0.0 {
        return SequenceTerm::Real {
            pole: p.re,
            coefficients: b.iter().map(|x| x.re).collect(),
        };
    }
    let mut amplitudes = Vec::with_capacity(m);
    let mut phases = Vec::with_capacity(m);
    for x in &b {
        let mut a = 2.0 * x.norm();
        let mut ph = if a == 0.0 { 0.0 } else { x.arg() };
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
    SequenceTerm::Oscillatory {
        pole: p,
        amplitudes,
        phases,
    }
}

/// `0.5^k`, `(-0.5)^k`; empty for 1.
fn power_factor(base: f64) -> String {
    match fmt_num(base).as_str() {
        "1" => String::new(),
        b if base < 0.0 => format!("({b})^k"),
        b => format!("{b}^k"),
    }
}

/// `lead·base^k`, or `base^k` alone when the lead is 1 (empty `base`: the lead alone).
fn times_power(lead: String, base: &str) -> String {
    match (lead.as_str(), base.is_empty()) {
        (_, true) => lead,
        ("1", false) => base.to_string(),
        (_, false) => format!("{lead}·{base}"),
    }
}

/// Signed text pieces of one group; coefficients with |c| ≤ noise are left out. A power
/// factor ρ^k is joined to what precedes it by `·` (`2·0.5^k`, `(1 - k)·0.5^k`).
fn pieces(t: &SequenceTerm, noise: f64) -> Vec<(bool, String)> {
    match t {
        SequenceTerm::Delta { delay, coefficient } => {
            if coefficient.abs() <= noise {
                return vec![];
            }
            let d = match delay {
                0 => "δ[k]".to_string(),
                m => format!("δ[k-{m}]"),
            };
            vec![(*coefficient < 0.0, product(coefficient.abs(), &[d]))]
        }
        SequenceTerm::Real { pole, coefficients } => {
            let nz: Vec<(usize, f64)> = coefficients
                .iter()
                .copied()
                .enumerate()
                .filter(|(_, c)| c.abs() > noise)
                .collect();
            let e = power_factor(*pole);
            if e.is_empty() || nz.len() <= 1 {
                return nz
                    .iter()
                    .map(|&(i, c)| {
                        let lead = product(c.abs(), &[var_power("k", i)]);
                        (c < 0.0, times_power(lead, &e))
                    })
                    .collect();
            }
            let neg = nz[0].1 < 0.0;
            let inner = signed_sum(
                nz.iter()
                    .map(|&(i, c)| {
                        let c = if neg { -c } else { c };
                        (c < 0.0, product(c.abs(), &[var_power("k", i)]))
                    })
                    .collect(),
            );
            vec![(neg, format!("({inner})·{e}"))]
        }
        SequenceTerm::Oscillatory {
            pole,
            amplitudes,
            phases,
        } => {
            let theta = pole.arg();
            let nz: Vec<(usize, f64, f64)> = amplitudes
                .iter()
                .zip(phases)
                .enumerate()
                .filter(|(_, (a, _))| a.abs() > noise)
                .map(|(i, (a, p))| (i, *a, *p))
                .collect();
            let e = power_factor(pole.norm());
            if e.is_empty() || nz.len() <= 1 {
                return nz
                    .iter()
                    .map(|&(i, a, p)| {
                        let lead = product(a.abs(), &[var_power("k", i)]);
                        let body = format!("{} {}", times_power(lead, &e), cos_of(theta, p, "k"));
                        (
                            a < 0.0,
                            body.strip_prefix("1 ").unwrap_or(&body).to_string(),
                        )
                    })
                    .collect();
            }
            let neg = nz[0].1 < 0.0;
            let inner = signed_sum(
                nz.iter()
                    .map(|&(i, a, p)| {
                        let a = if neg { -a } else { a };
                        (
                            a < 0.0,
                            product(a.abs(), &[var_power("k", i), cos_of(theta, p, "k")]),
                        )
                    })
                    .collect(),
            );
            vec![(neg, format!("{e} ({inner})"))]
        }
    }
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact values are meant: 0 before k = 0
mod tests {
    use super::*;
    use crate::analysis::pfe::PfTerm;

    fn c(re: f64, im: f64) -> Complex64 {
        Complex64::new(re, im)
    }

    fn pf(terms: &[(Complex64, usize, Complex64)]) -> PartialFractions {
        PartialFractions {
            terms: terms
                .iter()
                .map(|&(pole, power, residue)| PfTerm {
                    pole,
                    power,
                    residue,
                })
                .collect(),
            direct: vec![],
        }
    }

    #[test]
    fn first_order_step() {
        // Y/z = 1/(z − 1) − 1/(z − 0.5)  ↔  1 − 0.5^k
        let y = SequenceForm::from_partial_fractions(
            &pf(&[
                (c(1.0, 0.0), 1, c(1.0, 0.0)),
                (c(0.5, 0.0), 1, c(-1.0, 0.0)),
            ]),
            0.1,
        );
        assert_eq!(y.to_string(), "y[k] = 1 - 0.5^k");
        for k in 0..40u64 {
            assert!((y.eval(k) - (1.0 - 0.5f64.powi(k as i32))).abs() < 1e-16);
        }
        assert_eq!(y.eval_at(-1.0), 0.0);
        assert!(y.eval_at(f64::NAN).is_nan());
    }

    #[test]
    fn deltas_negative_poles_and_triple_poles() {
        // Y/z = 2/z + 3/z³ − 1/(z + 0.5) + 1/(z − 0.5)³
        //   ↔ 2δ[k] + 3δ[k−2] − (−0.5)^k + C(k, 2)·0.5^(k−2)
        let y = SequenceForm::from_partial_fractions(
            &pf(&[
                (c(0.0, 0.0), 1, c(2.0, 0.0)),
                (c(0.0, 0.0), 2, c(0.0, 0.0)),
                (c(0.0, 0.0), 3, c(3.0, 0.0)),
                (c(-0.5, 0.0), 1, c(-1.0, 0.0)),
                (c(0.5, 0.0), 1, c(0.0, 0.0)),
                (c(0.5, 0.0), 2, c(0.0, 0.0)),
                (c(0.5, 0.0), 3, c(1.0, 0.0)),
            ]),
            1.0,
        );
        assert_eq!(
            y.expression(),
            "2 δ[k] + 3 δ[k-2] - (-0.5)^k - (2 k - 2 k^2)·0.5^k"
        );
        for k in 0..30u64 {
            let kf = k as f64;
            let want = if k == 0 { 2.0 } else { 0.0 } + if k == 2 { 3.0 } else { 0.0 }
                - (-0.5f64).powi(k as i32)
                + kf * (kf - 1.0) / 2.0 * 0.5f64.powi(k as i32 - 2);
            assert!((y.eval(k) - want).abs() < 1e-14, "{k}");
        }
    }

    #[test]
    fn oscillatory_pair() {
        // Y/z = r/(z − p) + r̄/(z − p̄), p = 0.8 e^(j0.6), r = −0.5j  ↔  0.8^k sin(0.6 k)
        let p = Complex64::from_polar(0.8, 0.6);
        let y = SequenceForm::from_partial_fractions(
            &pf(&[(p, 1, c(0.0, -0.5)), (p.conj(), 1, c(0.0, 0.5))]),
            1.0,
        );
        assert_eq!(y.expression(), "0.8^k cos(0.6 k - 1.5708)");
        for k in 0..50u64 {
            let kf = k as f64;
            let want = 0.8f64.powi(k as i32) * (0.6 * kf).sin();
            assert!((y.eval(k) - want).abs() < 1e-15, "{k}");
            assert!(y.envelope(k) >= want.abs());
        }
    }
}
