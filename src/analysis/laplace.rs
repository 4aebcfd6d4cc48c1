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
//! from [`TransferFunction::time_response`], and [`TransferFunction::response_samples`] reports
//! both and how well they agree.

use num_complex::Complex64;
use serde::Serialize;

use crate::analysis::closed_form::ClosedForm;
use crate::analysis::input::{Input, ic_polynomial};
use crate::analysis::pfe::{
    PartialFractions, PfTerm, partial_fractions_with_poles, principal_parts,
};
use crate::analysis::pz::PoleZero;
use crate::analysis::stability::{HalfPlane, half_plane};
use crate::error::Result;
use crate::lti::TransferFunction;
use crate::numeric::tol::CANCEL_REL_TOL;
use crate::poly::{Poly, Root};

/// A closed-form response and its transient and steady-state parts.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Response {
    /// y(t) = transient + steady state.
    pub closed_form: ClosedForm,
    /// Terms of system poles (and initial conditions, and any δ term).
    pub transient: ClosedForm,
    /// Terms of input poles (including resonant ones).
    pub steady_state: ClosedForm,
}

/// A response sampled at given times: exact values and the closed form side by side.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResponseSamples {
    /// The times, in the caller's order.
    pub t: Vec<f64>,
    /// Exact y(t) (matrix-exponential stepping, [`TransferFunction::time_response`]); δ terms
    /// excluded.
    pub y: Vec<f64>,
    /// y(t) − steady state(t).
    pub transient: Vec<f64>,
    /// The steady-state closed form at t.
    pub steady_state: Vec<f64>,
    /// The full closed form at t.
    pub closed_form: Vec<f64>,
    /// max |closed form − y| over the times (0 for no times): the built-in cross-check.
    pub closed_form_error: f64,
    /// max |y| over the times.
    pub max_abs_y: f64,
}

/// One rational piece num/den of Y(s) with the roots of den (multiplicities, conjugates exact).
#[derive(Debug, Clone)]
pub(crate) struct Part {
    pub num: Poly,
    pub den: Poly,
    pub poles: Vec<Root>,
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

fn same_root(a: Complex64, b: Complex64) -> bool {
    a == b || (a - b).norm() <= CANCEL_REL_TOL * a.norm().max(b.norm())
}

/// `p` with its last `k` coefficients set to exactly 0 (its k-fold root at s = 0 is exact).
fn exact_zero_roots(p: &Poly, k: usize) -> Poly {
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

fn zero_multiplicity(roots: &[Root]) -> usize {
    roots
        .iter()
        .filter(|r| r.value.re == 0.0 && r.value.im == 0.0)
        .map(|r| r.multiplicity)
        .sum()
}

/// Splits Y(s) into its forced and initial-condition parts (see the module docs).
pub(crate) fn decompose(g: &TransferFunction, input: &Input, ics: &[f64]) -> Result<Decomposition> {
    input.validate()?;
    g.require_proper(&format!("the {input} response"), false)?;
    let p_ic = ic_polynomial(g.den(), ics)?;
    decompose_with(g, &g.pole_zero()?, input, p_ic)
}

/// As [`decompose`] with the pole/zero analysis of `g` already at hand and the initial-condition
/// polynomial formed (`input` validated, `g` proper): saves the root finding when the caller
/// (step metrics, `analyze`) has it.
pub(crate) fn decompose_with(
    g: &TransferFunction,
    pz: &PoleZero,
    input: &Input,
    p_ic: Poly,
) -> Result<Decomposition> {
    // Input poles against the zeros of G.
    let mut zeros = pz.reduced_zeros.clone();
    let mut cancelled_zeros: Vec<Complex64> = Vec::new();
    let mut input_poles: Vec<(Complex64, usize)> = Vec::new();
    for (v, m) in input.poles() {
        let mut m = m;
        if let Some(z) = zeros
            .iter_mut()
            .find(|z| z.multiplicity > 0 && same_root(z.value, v))
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

    // The zero of cos:W at s = 0 against an integrator of G.
    // Polynomials: zero roots made exact (the reduced form comes from a division).
    let mut sys = pz.reduced_poles.clone();
    let mut den_r = exact_zero_roots(pz.reduced.den(), zero_multiplicity(&sys));
    let (mut num_u, _) = input.laplace();
    if matches!(input, Input::Cos(_))
        && let Some(p) = sys
            .iter_mut()
            .find(|p| p.value.re == 0.0 && p.value.im == 0.0 && p.multiplicity > 0)
    {
        // D_r = s·D₁ exactly: drop the factor s against the zero of U(s) = s/(s² + ω²).
        p.multiplicity -= 1;
        num_u = Poly::constant(1.0);
        let c = den_r.coeffs();
        den_r = Poly::trimmed(c[..c.len() - 1].to_vec());
    }
    sys.retain(|p| p.multiplicity > 0);
    let num_r = exact_zero_roots(pz.reduced.num(), zero_multiplicity(&pz.reduced_zeros));
    let mut num_f = &num_r * &num_u;
    if !cancelled_zeros.is_empty() {
        num_f = num_f.div_rem(&Poly::from_roots(&cancelled_zeros)?)?.0;
    }
    let flat_inputs: Vec<Complex64> = input_poles
        .iter()
        .flat_map(|&(v, m)| std::iter::repeat_n(v, m))
        .collect();
    let den_f = &den_r * &Poly::from_roots(&flat_inputs)?;

    // Pole table of the forced part: system poles, input poles merged in.
    let mut poles = sys;
    for &(v, m) in &input_poles {
        match poles.iter_mut().find(|p| same_root(p.value, v)) {
            Some(p) => {
                p.value = v;
                p.multiplicity += m;
            }
            None => poles.push(Root {
                value: v,
                multiplicity: m,
            }),
        }
    }
    crate::poly::roots::sort_roots(&mut poles);

    let ic = (!p_ic.is_zero()).then(|| Part {
        num: p_ic,
        den: g.den().clone(),
        poles: pz.poles.clone(),
    });
    Ok(Decomposition {
        forced: Part {
            num: num_f,
            den: den_f,
            poles,
        },
        ic,
        input_poles: input_poles.iter().map(|&(v, _)| v).collect(),
    })
}

impl Decomposition {
    /// The partial fractions of Y(s): forced and initial-condition terms merged by pole.
    pub(crate) fn partial_fractions(&self) -> Result<PartialFractions> {
        let f = &self.forced;
        let forced = partial_fractions_with_poles(&f.num, &f.den, &f.poles)?;
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
            for t in principal_parts(&ic.num, ic.den.leading(), &ic.poles)? {
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
    pub(crate) fn response(&self) -> Result<Response> {
        let pf = self.partial_fractions()?;
        let closed_form = ClosedForm::from_partial_fractions(&pf);
        let is_input = |p: Complex64| self.input_poles.iter().any(|&v| v == p || v == p.conj());
        Ok(Response {
            transient: closed_form.filtered(|p| !is_input(p), true),
            steady_state: closed_form.filtered(is_input, false),
            closed_form,
        })
    }

    /// lim t→∞ y(t) when it exists and is finite: every pole of Y in the open left half plane
    /// except a simple pole at s = 0 (whose residue is the limit).
    pub(crate) fn final_value(&self) -> Option<f64> {
        let mut total = 0.0;
        let parts = std::iter::once(&self.forced).chain(self.ic.as_ref());
        for part in parts {
            if part.num.is_zero() {
                continue;
            }
            for p in &part.poles {
                let at_zero = p.value.re == 0.0 && p.value.im == 0.0;
                let ok = if at_zero {
                    p.multiplicity == 1
                } else {
                    half_plane(p.value) == HalfPlane::Left
                };
                if !ok {
                    return None;
                }
                if at_zero {
                    // D = s·D₁ exactly: the limit of s·N/D at 0 is N(0)/D₁(0).
                    total += part.num.coeff(0) / part.den.coeff(1);
                }
            }
        }
        Some(total)
    }
}

impl TransferFunction {
    /// The closed-form response y(t) to `input` with ODE initial conditions
    /// `ics` = [y(0), y′(0), …] (fewer than the order: the rest are 0), by partial fractions of
    /// Y(s) = G(s)U(s) + P_ic(s)/D(s) (see the [module docs](self) for cancellations and the
    /// transient/steady-state split).
    ///
    /// Errors: an improper G ([`crate::LtiError::Improper`], for every input), more initial
    /// conditions than the order, NaN/∞ values, an invalid input parameter.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::Input;
    /// // Tank (seed eqs. 3.6–3.18): h' + 0.5 h = u, h(0) = 1, step input:
    /// // h(t) = e^(−t/2) + 2 (1 − e^(−t/2)): transient −e^(−t/2), steady state 2.
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 0.5]).unwrap();
    /// let r = g.inverse_laplace(&Input::Step, &[1.0]).unwrap();
    /// assert_eq!(r.closed_form.to_string(), "y(t) = 2 - e^(-0.5 t)");
    /// assert_eq!(r.steady_state.expression(), "2");
    /// assert_eq!(r.transient.expression(), "-e^(-0.5 t)");
    /// ```
    pub fn inverse_laplace(&self, input: &Input, ics: &[f64]) -> Result<Response> {
        decompose(self, input, ics)?.response()
    }

    /// The response at the times `t`: exact values by matrix-exponential stepping, the closed
    /// form at the same times, the transient/steady-state values, and the largest disagreement
    /// between closed form and exact values.
    ///
    /// Errors: those of [`TransferFunction::inverse_laplace`] and
    /// [`TransferFunction::time_response`].
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::Input;
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0, 1.0]).unwrap();
    /// let s = g.response_samples(&Input::Step, &[], &[0.0, 1.0, 5.0]).unwrap();
    /// assert!(s.closed_form_error < 1e-14);
    /// assert!((s.steady_state[2] - 1.0).abs() < 1e-15);
    /// ```
    pub fn response_samples(
        &self,
        input: &Input,
        ics: &[f64],
        t: &[f64],
    ) -> Result<ResponseSamples> {
        crate::analysis::time::check_times(t)?;
        let dec = decompose(self, input, ics)?;
        let response = dec.response()?;
        let y = crate::analysis::time::simulate(&dec, t)?;
        let closed: Vec<f64> = t.iter().map(|&x| response.closed_form.eval(x)).collect();
        let steady: Vec<f64> = t.iter().map(|&x| response.steady_state.eval(x)).collect();
        let transient = y.iter().zip(&steady).map(|(a, b)| a - b).collect();
        let closed_form_error = closed
            .iter()
            .zip(&y)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let max_abs_y = y.iter().map(|v| v.abs()).fold(0.0, f64::max);
        Ok(ResponseSamples {
            t: t.to_vec(),
            y,
            transient,
            steady_state: steady,
            closed_form: closed,
            closed_form_error,
            max_abs_y,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::closed_form::ClosedFormTerm;

    fn tf(n: &[f64], d: &[f64]) -> TransferFunction {
        TransferFunction::from_descending(n, d).unwrap()
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
        let dec = decompose(&g, &Input::Exp(3.0), &[]).unwrap();
        assert_eq!(dec.forced.den.degree(), 2);
        assert!(dec.input_poles.is_empty());
        let r = dec.response().unwrap();
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
        let dec = decompose(&g, &Input::Cos(1.0), &[]).unwrap();
        assert_eq!(dec.forced.den.coeffs(), &[1.0, 0.0, 1.0]);
        // 1/(s²(s + 2)) with cos 3t: one integrator left.
        let g = tf(&[1.0], &[1.0, 2.0, 0.0, 0.0]);
        let s = g
            .response_samples(&Input::Cos(3.0), &[], &[0.5, 2.0, 7.0])
            .unwrap();
        assert!(s.closed_form_error < 1e-14, "{}", s.closed_form_error);
        let dec = decompose(&g, &Input::Cos(3.0), &[]).unwrap();
        assert_eq!(dec.forced.den.degree(), 4);
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
            decompose(&g, &Input::None, &[1.0]).unwrap().final_value(),
            None
        );
        assert_eq!(
            decompose(&g, &Input::Step, &[]).unwrap().final_value(),
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
                    let s = g.response_samples(input, &ics, &t).unwrap();
                    assert!(
                        s.closed_form_error <= 1e-12 * s.max_abs_y.max(1.0),
                        "{g} {input} {ics:?}: {:e}",
                        s.closed_form_error
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
