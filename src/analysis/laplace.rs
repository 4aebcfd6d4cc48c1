//! The inverse Laplace transform of Y(s) = G(s)U(s) + P_ic(s)/D(s): closed-form responses
//! split into transient and steady-state parts (seed eqs. 3.11–3.18 and 3.28–3.40).
//!
//! # How Y(s) is put together
//! - **Forced part** G(s)U(s) uses G in lowest terms ([`TransferFunction::pole_zero`]), so a
//!   cancelled pole never appears in it. An input pole that coincides (to the cancellation
//!   tolerance 1e-8 relative) with a zero of G is cancelled too (e.g. `exp:3` into a G with a
//!   zero at s = 3), and the integrator of G cancels the zero of `cos:W` at s = 0. An input pole
//!   that coincides with a pole of G (resonance) raises its multiplicity: the pole is then taken
//!   at the input's exact value (0, a or ±jω).
//! - **Initial-condition part** P_ic(s)/D(s) uses the characteristic polynomial as given:
//!   hidden (cancelled) modes appear in it — that is physics, not numerics.
//!
//! # Transient and steady state
//! Terms of system poles (including every initial-condition term) form the *transient*; terms
//! of input poles form the *steady state* (seed eqs. 3.39–3.40). A pole that is both (resonance,
//! e.g. `sin:1` into 1/(s² + 1)) belongs to the steady state, since it is driven by the input
//! and does not die out. A δ(t) term (impulse into a biproper G) is put in the transient.
//!
//! # Accuracy
//! Where poles nearly coincide (ζ = 1 ± 1e-9, residues ~1e4 that cancel) the closed form is
//! still evaluable but its values carry the rounding of those residues; the exact values come
//! from [`TransferFunction::time_response`], and [`TransferFunction::response`] reports
//! both and how well they agree.

use num_complex::Complex64;

use crate::analysis::closed_form::ClosedForm;
use crate::analysis::factored::{Factored, ScaledProduct};
use crate::analysis::input::{Input, ic_polynomial};
use crate::analysis::pfe::{
    PartialFractions, PfTerm, direct_factored, partial_fractions_with_poles, principal_parts,
    principal_parts_factored,
};
use crate::error::{LtiError, Result};
use crate::lti::{StateSpace, TransferFunction};
use crate::poly::{HalfPlane, Poly, Root, same_root};

/// A closed-form response and its transient and steady-state parts.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ClosedParts {
    /// y(t) = transient + steady state.
    pub closed_form: ClosedForm,
    /// Terms of system poles (and initial conditions, and any δ term).
    pub transient: ClosedForm,
    /// Terms of input poles (including resonant ones).
    pub steady_state: ClosedForm,
    /// lim t→∞ y(t) when it exists and is finite.
    pub final_value: Option<f64>,
}

/// The numerator of a rational piece of Y(s), as coefficients or as factors.
#[derive(Debug, Clone)]
pub(crate) enum PartForm {
    /// num/den with both polynomials (the roots of den are the part's poles).
    Coeffs { num: Poly, den: Poly },
    /// gain·Π(s − z)/Π(s − p) over the part's poles (monic denominator).
    Factors { gain: f64, zeros: Vec<Root> },
}

/// One rational piece of Y(s) with the roots of its denominator (multiplicities,
/// conjugates exact).
#[derive(Debug, Clone)]
pub(crate) struct Part {
    pub form: PartForm,
    pub poles: Vec<Root>,
}

impl Part {
    pub(crate) fn is_zero(&self) -> bool {
        match &self.form {
            PartForm::Coeffs { num, .. } => num.is_zero(),
            PartForm::Factors { gain, .. } => *gain == 0.0,
        }
    }

    /// Partial fractions of the part.
    pub(crate) fn partial_fractions(&self) -> Result<PartialFractions> {
        match &self.form {
            PartForm::Coeffs { num, den } => partial_fractions_with_poles(num, den, &self.poles),
            PartForm::Factors { gain, zeros } => Ok(PartialFractions {
                terms: principal_parts_factored(*gain, zeros, &self.poles)?,
                direct: direct_factored(*gain, zeros, &self.poles),
            }),
        }
    }

    /// The principal parts only (the direct part of an initial-condition piece is zero).
    fn principal_parts(&self) -> Result<Vec<PfTerm>> {
        match &self.form {
            PartForm::Coeffs { num, den } => principal_parts(num, den.leading(), &self.poles),
            PartForm::Factors { gain, zeros } => {
                principal_parts_factored(*gain, zeros, &self.poles)
            }
        }
    }

    /// The residue at a simple pole at s = 0: lim s→0 s·N/D.
    fn residue_at_origin(&self) -> f64 {
        match &self.form {
            // D = s·D₁ exactly: the limit of s·N/D at 0 is N(0)/D₁(0).
            PartForm::Coeffs { num, den } => num.coeff(0) / den.coeff(1),
            PartForm::Factors { gain, zeros } => {
                let mut acc = ScaledProduct::new(Complex64::new(*gain, 0.0));
                for z in zeros {
                    acc.mul_pow(-z.value, z.multiplicity);
                }
                for p in self.poles.iter().filter(|p| !p.is_origin()) {
                    acc.div_pow(-p.value, p.multiplicity);
                }
                acc.value().re
            }
        }
    }

    /// A realisation (A, B, C) of the strictly proper part (the impulse response without its
    /// δ terms); `None` when that part is zero.
    pub(crate) fn realization(&self) -> Result<Option<StateSpace>> {
        if self.is_zero() || self.poles.is_empty() {
            return Ok(None);
        }
        match &self.form {
            PartForm::Coeffs { num, den } => {
                let r = if num.degree() >= den.degree() {
                    num.div_rem(den)?.1
                } else {
                    num.clone()
                };
                if r.is_zero() {
                    return Ok(None);
                }
                if stiff(&self.poles) {
                    // The companion matrix of poles 1e8 and more apart in size is too badly
                    // scaled for the exponential; the cascade of sections is triangular.
                    let gain = r.leading() / den.leading();
                    return Ok(Some(StateSpace::from_zpk(&r.roots()?, &self.poles, gain)?));
                }
                let g = TransferFunction::new(r, den.clone())?;
                Ok(Some(StateSpace::from_tf(&g)?))
            }
            PartForm::Factors { gain, zeros } => {
                Ok(Some(StateSpace::from_zpk(zeros, &self.poles, *gain)?))
            }
        }
    }
}

/// Pole magnitudes (non-zero) spread over more than this ratio make a part stiff.
const STIFF_RATIO: f64 = 1e8;

/// True when the non-zero pole magnitudes spread over more than [`STIFF_RATIO`].
fn stiff(poles: &[Root]) -> bool {
    let mags = poles.iter().map(|p| p.value.norm()).filter(|&m| m > 0.0);
    let (lo, hi) = mags.fold((f64::INFINITY, 0.0f64), |(lo, hi), m| {
        (lo.min(m), hi.max(m))
    });
    hi > STIFF_RATIO * lo
}

/// Y(s) = forced + initial-condition part, and which poles are the input's.
#[derive(Debug, Clone)]
pub(crate) struct Decomposition {
    /// G(s)U(s) after cancellations.
    pub forced: Part,
    /// P_ic(s)/D(s); `None` when all initial conditions are zero.
    pub ic: Option<Part>,
    /// Remaining input poles (exact values, both members of a pair).
    pub input_poles: Vec<Complex64>,
}

/// `p` with its last `k` coefficients set to exactly 0 (its k-fold root at s = 0 is exact).
pub(crate) fn exact_zero_roots(p: &Poly, k: usize) -> Poly {
    if k == 0 || p.is_zero() {
        return p.clone();
    }
    let mut c = p.coeffs().to_vec();
    let n = c.len();
    for x in c.iter_mut().skip(n.saturating_sub(k)) {
        *x = 0.0;
    }
    Poly::trimmed(c)
}

pub(crate) fn zero_multiplicity(roots: &[Root]) -> usize {
    roots
        .iter()
        .filter(|r| r.is_origin())
        .map(|r| r.multiplicity)
        .sum()
}

/// How the input meets the plant: which zeros of G cancel input poles, which input poles
/// remain, and whether the zero of cos:W at s = 0 cancels an integrator of G.
pub(crate) struct Meeting {
    pub zeros_left: Vec<Root>,
    pub cancelled_zeros: Vec<Complex64>,
    pub input_poles: Vec<(Complex64, usize)>,
    pub integrator_cancelled: bool,
    /// Poles of G·U: the reduced poles with the input poles merged in.
    pub poles: Vec<Root>,
}

/// How the input with the poles `input_poles` (exact values, multiplicities) meets G; with
/// `cancel_integrator` (cos:W in s) the input's zero at the origin takes one pole of G there.
pub(crate) fn meet(
    f: &Factored,
    input_poles_given: Vec<(Complex64, usize)>,
    cancel_integrator: bool,
) -> Meeting {
    // Input poles against the zeros of G.
    let mut zeros = f.reduced_zeros().to_vec();
    let mut cancelled_zeros: Vec<Complex64> = Vec::new();
    let mut input_poles: Vec<(Complex64, usize)> = Vec::new();
    for (v, m) in input_poles_given {
        let mut m = m;
        if let Some(z) = zeros
            .iter_mut()
            .find(|z| z.multiplicity > 0 && z.same_as(v))
        {
            let k = m.min(z.multiplicity);
            z.multiplicity -= k;
            m -= k;
            cancelled_zeros.extend(std::iter::repeat_n(z.value, k));
        }
        if m > 0 {
            input_poles.push((v, m));
        }
    }
    zeros.retain(|z| z.multiplicity > 0);
    // The zero of cos:W at s = 0 against an integrator of G.
    let mut sys = f.reduced_poles().to_vec();
    let mut integrator_cancelled = false;
    if cancel_integrator
        && let Some(p) = sys.iter_mut().find(|p| p.is_origin() && p.multiplicity > 0)
    {
        p.multiplicity -= 1;
        integrator_cancelled = true;
    }
    sys.retain(|p| p.multiplicity > 0);
    // Pole table of the forced part: system poles, input poles merged in.
    let mut poles = sys;
    for &(v, m) in &input_poles {
        match poles.iter_mut().find(|p| same_root(p.value, v)) {
            Some(p) => {
                p.value = v;
                p.multiplicity += m;
            }
            None => poles.push(Root::new(v, m)),
        }
    }
    crate::poly::roots::sort_roots(&mut poles);
    Meeting {
        zeros_left: zeros,
        cancelled_zeros,
        input_poles,
        integrator_cancelled,
        poles,
    }
}

impl Decomposition {
    /// Splits Y(s) into its forced and initial-condition parts (see the module docs).
    pub(crate) fn new(f: &Factored, input: &Input, ics: &[f64]) -> Result<Decomposition> {
        f.domain()
            .require_continuous("the closed form y(t) (inverse Laplace transform)")?;
        input.validate()?;
        f.require_proper(&format!("the {input} response"), false)?;
        let meeting = meet(f, input.poles(), matches!(input, Input::Cos(_)));
        let (forced, ic) = match f.source().coefficients() {
            Some(c) => {
                let forced = forced_coeffs(f, &c.reduced, input, &meeting)?;
                let p_ic = ic_polynomial(c.tf.den(), ics)?;
                let ic = (!p_ic.is_zero()).then(|| Part {
                    form: PartForm::Coeffs {
                        num: p_ic,
                        den: c.tf.den().clone(),
                    },
                    poles: f.poles().to_vec(),
                });
                (forced, ic)
            }
            None => {
                if !ics.is_empty() {
                    return Err(LtiError::invalid(
                        "initial conditions y(0), y'(0), … are those of an ODE: this plant is given by its zeros and poles, not by ODE coefficients",
                    ));
                }
                (forced_factors(f, input, &meeting), None)
            }
        };
        Ok(Decomposition {
            forced,
            ic,
            input_poles: meeting.input_poles.iter().map(|&(v, _)| v).collect(),
        })
    }

    /// The partial fractions of Y(s): forced and initial-condition terms merged by pole.
    pub(crate) fn partial_fractions(&self) -> Result<PartialFractions> {
        let forced = self.forced.partial_fractions()?;
        let mut groups: Vec<(Complex64, Vec<Complex64>)> = Vec::new();
        let mut add = |t: &PfTerm, exact_only: bool| {
            let k = groups.iter().position(|(p, _)| *p == t.pole).or_else(|| {
                (!exact_only)
                    .then(|| groups.iter().position(|(p, _)| same_root(*p, t.pole)))
                    .flatten()
            });
            let g = match k {
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
        };
        for t in &forced.terms {
            add(t, true);
        }
        if let Some(ic) = &self.ic {
            for t in ic.principal_parts()? {
                add(&t, false);
            }
        }
        // Decreasing real part; at equal real part real poles first, then a pair as +, −.
        groups.sort_by(|a, b| {
            b.0.re
                .total_cmp(&a.0.re)
                .then(a.0.im.abs().total_cmp(&b.0.im.abs()))
                .then(b.0.im.total_cmp(&a.0.im))
        });
        let terms = groups
            .into_iter()
            .flat_map(|(pole, res)| {
                res.into_iter().enumerate().map(move |(k, residue)| PfTerm {
                    pole,
                    power: k + 1,
                    residue,
                })
            })
            .collect();
        Ok(PartialFractions {
            terms,
            direct: forced.direct,
        })
    }

    /// The closed form and its transient/steady-state split.
    pub(crate) fn closed_form(&self) -> Result<ClosedParts> {
        let pf = self.partial_fractions()?;
        let closed_form = ClosedForm::from_partial_fractions(&pf);
        let is_input = |p: Complex64| self.input_poles.iter().any(|&v| v == p || v == p.conj());
        Ok(ClosedParts {
            transient: closed_form.filtered(|p| !is_input(p), true),
            steady_state: closed_form.filtered(is_input, false),
            closed_form,
            final_value: self.final_value(),
        })
    }

    /// lim t→∞ y(t) when it exists and is finite: every pole of Y in the open left half plane
    /// except a simple pole at s = 0 (whose residue is the limit).
    pub(crate) fn final_value(&self) -> Option<f64> {
        let mut total = 0.0;
        for part in std::iter::once(&self.forced).chain(self.ic.as_ref()) {
            if part.is_zero() {
                continue;
            }
            for p in &part.poles {
                let ok = if p.is_origin() {
                    p.multiplicity == 1
                } else {
                    p.half_plane() == HalfPlane::Left
                };
                if !ok {
                    return None;
                }
                if p.is_origin() {
                    total += part.residue_at_origin();
                }
            }
        }
        Some(total)
    }
}

/// The forced part G·U from the reduced coefficients.
fn forced_coeffs(
    f: &Factored,
    reduced: &TransferFunction,
    input: &Input,
    m: &Meeting,
) -> Result<Part> {
    // Polynomials: zero roots made exact (the reduced form comes from a division).
    let mut den_r = exact_zero_roots(reduced.den(), zero_multiplicity(f.reduced_poles()));
    let (mut num_u, _) = input.laplace();
    if m.integrator_cancelled {
        // D_r = s·D₁ exactly: drop the factor s against the zero of U(s) = s/(s² + ω²).
        num_u = Poly::constant(1.0);
        let c = den_r.coeffs();
        den_r = Poly::trimmed(c[..c.len() - 1].to_vec());
    }
    let num_r = exact_zero_roots(reduced.num(), zero_multiplicity(f.reduced_zeros()));
    let mut num_f = &num_r * &num_u;
    if !m.cancelled_zeros.is_empty() {
        num_f = num_f.div_rem(&Poly::from_roots(&m.cancelled_zeros)?)?.0;
    }
    let flat_inputs: Vec<Complex64> = m
        .input_poles
        .iter()
        .flat_map(|&(v, k)| std::iter::repeat_n(v, k))
        .collect();
    let den_f = &den_r * &Poly::from_roots(&flat_inputs)?;
    Ok(Part {
        form: PartForm::Coeffs {
            num: num_f,
            den: den_f,
        },
        poles: m.poles.clone(),
    })
}

/// The forced part G·U from the factors.
fn forced_factors(f: &Factored, input: &Input, m: &Meeting) -> Part {
    let (gain_u, zero_at_origin) = match input {
        Input::Sin(w) => (*w, false),
        Input::Cos(_) => (1.0, !m.integrator_cancelled),
        Input::None => (0.0, false),
        _ => (1.0, false),
    };
    let mut zeros = m.zeros_left.clone();
    if zero_at_origin {
        match zeros.iter_mut().find(|z| z.is_origin()) {
            Some(z) => z.multiplicity += 1,
            None => zeros.push(Root::new(Complex64::new(0.0, 0.0), 1)),
        }
        crate::poly::roots::sort_roots(&mut zeros);
    }
    Part {
        form: PartForm::Factors {
            gain: f.gain() * gain_u,
            zeros,
        },
        poles: m.poles.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::closed_form::ClosedFormTerm;

    fn tf(n: &[f64], d: &[f64]) -> TransferFunction {
        TransferFunction::from_descending(n, d).unwrap()
    }

    fn forced_den(d: &Decomposition) -> &Poly {
        match &d.forced.form {
            PartForm::Coeffs { den, .. } => den,
            PartForm::Factors { .. } => panic!("coefficient part expected"),
        }
    }

    #[test]
    fn resonance_goes_to_steady_state() {
        // sin(t) into 1/(s² + 1): Y = 1/(s² + 1)², y = (sin t − t cos t)/2
        let r = tf(&[1.0], &[1.0, 0.0, 1.0])
            .inverse_laplace(&Input::Sin(1.0), &[])
            .unwrap();
        assert!(r.transient.is_zero());
        assert_eq!(r.steady_state.terms().len(), 1);
        for t in [0.5f64, 3.0, 10.0] {
            let want = (t.sin() - t * t.cos()) / 2.0;
            assert!((r.closed_form.eval(t) - want).abs() < 1e-14);
        }
    }

    #[test]
    fn input_pole_cancelled_by_a_zero() {
        // exp:3 into (s − 3)/(s + 1)²: the unstable input mode is cancelled.
        let g = tf(&[1.0, -3.0], &[1.0, 2.0, 1.0]);
        let dec = Decomposition::new(&g.factored().unwrap(), &Input::Exp(3.0), &[]).unwrap();
        assert_eq!(forced_den(&dec).degree(), 2);
        assert!(dec.input_poles.is_empty());
        let r = dec.closed_form().unwrap();
        // Y = 1/(s + 1)²
        assert!(r.steady_state.is_zero());
        assert!((r.closed_form.eval(2.0) - 2.0 * (-2f64).exp()).abs() < 1e-15);
        assert_eq!(dec.final_value(), Some(0.0));
    }

    #[test]
    fn cos_into_integrator() {
        // cos t into 1/s: y = sin t, no constant term; the same for the exact values.
        let g = tf(&[1.0], &[1.0, 0.0]);
        let r = g.inverse_laplace(&Input::Cos(1.0), &[]).unwrap();
        assert_eq!(r.closed_form.terms().len(), 1);
        assert!((r.closed_form.eval(1.0) - 1f64.sin()).abs() < 1e-15);
        let dec = Decomposition::new(&g.factored().unwrap(), &Input::Cos(1.0), &[]).unwrap();
        assert_eq!(forced_den(&dec).coeffs(), &[1.0, 0.0, 1.0]);
        // 1/(s²(s + 2)) with cos 3t: one integrator left.
        let g = tf(&[1.0], &[1.0, 2.0, 0.0, 0.0]);
        let s = &g.response(&Input::Cos(3.0), &[], &[0.5, 2.0, 7.0]).unwrap();
        assert!(
            s.samples.closed_form_error < 1e-14,
            "{}",
            s.samples.closed_form_error
        );
        let dec = Decomposition::new(&g.factored().unwrap(), &Input::Cos(3.0), &[]).unwrap();
        assert_eq!(forced_den(&dec).degree(), 4);
    }

    #[test]
    fn impulse_into_biproper_gives_delta() {
        // (2s + 3)/(s + 1) = 2 + 1/(s + 1)
        let r = tf(&[2.0, 3.0], &[1.0, 1.0])
            .inverse_laplace(&Input::Impulse, &[])
            .unwrap();
        assert_eq!(r.closed_form.to_string(), "y(t) = 2 δ(t) + e^(-t)");
        assert!(matches!(
            r.transient.terms()[0],
            ClosedFormTerm::Impulse { derivative: 0, .. }
        ));
    }

    #[test]
    fn hidden_mode_appears_only_with_initial_conditions() {
        // (s − 1)/((s − 1)(s + 2)): the step response has no e^t, the IC response does.
        let g = tf(&[1.0, -1.0], &[1.0, 1.0, -2.0]);
        let r = g.inverse_laplace(&Input::Step, &[]).unwrap();
        assert!(
            r.closed_form
                .terms()
                .iter()
                .all(|t| t.pole().unwrap().re <= 0.0)
        );
        let r = g.inverse_laplace(&Input::None, &[1.0]).unwrap();
        assert!(
            r.closed_form
                .terms()
                .iter()
                .any(|t| t.pole().unwrap().re > 0.0)
        );
        assert_eq!(
            Decomposition::new(&g.factored().unwrap(), &Input::None, &[1.0])
                .unwrap()
                .final_value(),
            None
        );
        assert_eq!(
            Decomposition::new(&g.factored().unwrap(), &Input::Step, &[])
                .unwrap()
                .final_value(),
            Some(0.5)
        );
    }

    #[test]
    fn closed_form_and_exact_values_agree_for_every_input() {
        // Plants with integrators, zeros on input poles, resonances, hidden modes, feedthrough.
        let plants = [
            tf(&[1.0], &[1.0, 0.0]),
            tf(&[1.0], &[1.0, 2.0, 0.0, 0.0]),
            tf(&[1.0, 0.0], &[1.0, 3.0, 2.0]),
            tf(&[1.0, 0.0, 4.0], &[1.0, 1.0, 4.0, 2.0]),
            tf(&[2.0, 1.0], &[1.0, 0.5]),
            tf(&[1.0, 0.5], &[1.0, 0.5, 4.0, 0.0]),
            tf(&[1.0, 1.0], &[1.0, 2.0, 1.0]),
            tf(&[3.0], &[1.0]),
        ];
        let inputs = [
            Input::Impulse,
            Input::Step,
            Input::Ramp,
            Input::Exp(-1.0),
            Input::Exp(0.0),
            Input::Sin(2.0),
            Input::Cos(2.0),
            Input::Cos(1.0),
            Input::None,
        ];
        let t: Vec<f64> = (0..=60).map(|k| k as f64 * 0.1).collect();
        for g in &plants {
            for input in &inputs {
                for ics in [vec![], vec![0.5, -1.0][..g.order().min(2)].to_vec()] {
                    let s = g.response(input, &ics, &t).unwrap();
                    assert!(
                        s.samples.closed_form_error <= 1e-12 * s.samples.max_abs_y.max(1.0),
                        "{g} {input} {ics:?}: {:e}",
                        s.samples.closed_form_error
                    );
                }
            }
        }
    }

    #[test]
    fn improper_and_bad_ics_are_rejected() {
        let g = tf(&[1.0, 0.0, 0.0], &[1.0, 1.0]);
        for i in [Input::Impulse, Input::Step, Input::None] {
            assert!(matches!(
                g.inverse_laplace(&i, &[]),
                Err(crate::LtiError::Improper { .. })
            ));
        }
        let g = tf(&[1.0], &[1.0, 1.0]);
        assert!(g.inverse_laplace(&Input::Step, &[1.0, 2.0]).is_err());
        assert!(g.inverse_laplace(&Input::Sin(-1.0), &[]).is_err());
    }
}
