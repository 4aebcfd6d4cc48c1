//! The closed form of a discrete-time response: Y(z) = G(z)U(z) + Y_ic(z) in partial
//! fractions of Y(z)/z, and their inverse z-transform y\[k\] (a
//! [`SequenceForm`](crate::analysis::SequenceForm)).
//!
//! # The sampled inputs
//! Each input is read at t = kT (u\[k\] = u(kT), k ≥ 0) and enters as Ũ(z) = U(z)/z:
//!
//! | input | u\[k\] | U(z)/z |
//! |---|---|---|
//! | impulse | δ\[k\] | 1/z |
//! | step | 1 | 1/(z − 1) |
//! | ramp | kT | T/(z − 1)² |
//! | exp:a | r^k, r = e^(aT) | 1/(z − r) |
//! | sin:ω | sin(θk), θ = ωT | sin θ/((z − e^(jθ))(z − e^(−jθ))) |
//! | cos:ω | cos(θk) | (z − cos θ)/((z − e^(jθ))(z − e^(−jθ))) |
//!
//! θ is taken modulo 2π into [0, π] (a frequency above the Nyquist frequency π/T aliases:
//! sin changes sign when θ is folded); at θ = 0 or π the samples of sin are 0 and those of
//! cos are 1 or (−1)^k (a single real input pole).
//!
//! # Y(z)/z
//! The forced part G·Ũ is built from the factors of G in lowest terms, as in continuous time
//! ([`crate::analysis::laplace`]): an input pole on a zero of G cancels, an input pole on a
//! pole of G (resonance) raises its multiplicity and is taken at the input's exact value, a
//! pole at z = 0 of G or of the impulse gives delayed unit samples δ\[k − m\].
//!
//! **Initial conditions** are those of the difference equation
//! a₀y\[k\] + a₁y\[k−1\] + … + a_n y\[k−n\] = b₀u\[k\] + … (the coefficients of D(z) as given, with
//! u\[k\] = 0 for k < 0): `ics` = [y\[−1\], y\[−2\], …, y\[−n\]] (fewer: the rest are 0). The
//! one-sided z-transform of the delays gives Y_ic(z) = N_ic(z)/D(z) with
//! N_ic(z) = −Σᵢ₌₁ⁿ aᵢ Σⱼ₌₁ⁱ y\[−j\] z^(n−i+j), which has the factor z.
//!
//! Transient and steady state are split as in continuous time: terms of input poles
//! (resonant ones included) are the steady state, the rest (and every δ term) the transient.

use num_complex::Complex64;

use crate::analysis::HalfPlane;
use crate::analysis::closed_form::{ClosedForm, SequenceForm};
use crate::analysis::factored::Factored;
use crate::analysis::input::Input;
use crate::analysis::laplace::{
    ClosedParts, Decomposition, Meeting, Part, PartForm, exact_zero_roots, meet, zero_multiplicity,
};
use crate::error::{LtiError, Result, check_finite};
use crate::lti::TransferFunction;
use crate::poly::{Poly, Root, same_root};

/// Ũ(z) = U(z)/z = gain·Π(z − zeros)/Π(z − poles) of a sampled input.
struct SampledInput {
    gain: f64,
    zeros: Vec<Complex64>,
    /// Exact values with multiplicities; a pair upper member first.
    poles: Vec<(Complex64, usize)>,
}

fn sampled_input(input: &Input, dt: f64) -> SampledInput {
    let c = Complex64::new;
    let simple = |gain: f64, p: f64| SampledInput {
        gain,
        zeros: vec![],
        poles: vec![(c(p, 0.0), 1)],
    };
    match *input {
        Input::Impulse => simple(1.0, 0.0),
        Input::Step => simple(1.0, 1.0),
        Input::Ramp => SampledInput {
            gain: dt,
            zeros: vec![],
            poles: vec![(c(1.0, 0.0), 2)],
        },
        Input::Exp(a) => simple(1.0, (a * dt).exp()),
        Input::Sin(w) | Input::Cos(w) => {
            let tau = std::f64::consts::TAU;
            let folded = (w * dt).rem_euclid(tau);
            let (theta, sign) = if folded > std::f64::consts::PI {
                (tau - folded, -1.0)
            } else {
                (folded, 1.0)
            };
            let (s, co) = theta.sin_cos();
            let is_sin = matches!(input, Input::Sin(_));
            if s.abs() <= 4.0 * f64::EPSILON {
                // θ = 0 or π: sin(θk) = 0, cos(θk) = (±1)^k
                return if is_sin {
                    simple(0.0, 1.0)
                } else {
                    simple(1.0, co.signum())
                };
            }
            let p = c(co, s);
            SampledInput {
                gain: if is_sin { sign * s } else { 1.0 },
                zeros: if is_sin { vec![] } else { vec![c(co, 0.0)] },
                poles: vec![(p, 1), (p.conj(), 1)],
            }
        }
        Input::None => simple(0.0, 1.0),
    }
}

/// N_ic(z)/z for the characteristic polynomial `den` (degree n, descending coefficients
/// a₀ … a_n) and `ics` = [y\[−1\], …] (see the module docs). Errors: more than n values, NaN/∞.
pub(crate) fn ic_numerator_over_z(den: &Poly, ics: &[f64]) -> Result<Poly> {
    let n = den.degree();
    if ics.len() > n {
        return Err(LtiError::invalid(format!(
            "{} initial conditions given for an order-{n} difference equation (at most {n}: \
             y[-1]{})",
            ics.len(),
            match n {
                0 => " is not needed: the system has no state".to_string(),
                1 => String::new(),
                2 => ", y[-2]".to_string(),
                _ => format!(", …, y[-{n}]"),
            }
        )));
    }
    for (j, &y) in ics.iter().enumerate() {
        check_finite(|| format!("initial condition y[-{}]", j + 1), y)?;
    }
    // a_i is the coefficient of z^(n−i); the coefficient of z^e in N_ic (1 ≤ e ≤ n) is
    // −Σ_{i=n−e+1..n} a_i·y[−(e − n + i)]; N_ic/z shifts e down by one.
    let a = |i: usize| den.coeff(n - i);
    let asc: Vec<f64> = (1..=n)
        .map(|e| {
            -(n - e + 1..=n)
                .map(|i| a(i) * ics.get(e + i - n - 1).copied().unwrap_or(0.0))
                .sum::<f64>()
        })
        .collect();
    if asc.is_empty() {
        return Ok(Poly::zero());
    }
    Ok(Poly::trimmed(asc.into_iter().rev().collect()))
}

/// The forced part G·Ũ from the reduced coefficients (a finite impulse response stays exact:
/// its expansion is the Taylor shift of the numerator at z = 0).
fn forced_coeffs(
    f: &Factored,
    reduced: &TransferFunction,
    u: &SampledInput,
    m: &Meeting,
) -> Result<Part> {
    let den_r = exact_zero_roots(reduced.den(), zero_multiplicity(f.reduced_poles()));
    let num_r = exact_zero_roots(reduced.num(), zero_multiplicity(f.reduced_zeros()));
    let num_u = Poly::from_roots(&u.zeros)?.scale(u.gain);
    let mut num = &num_r * &num_u;
    if !m.cancelled_zeros.is_empty() {
        num = num.div_rem(&Poly::from_roots(&m.cancelled_zeros)?)?.0;
    }
    let flat: Vec<Complex64> = m
        .input_poles
        .iter()
        .flat_map(|&(v, k)| std::iter::repeat_n(v, k))
        .collect();
    Ok(Part {
        form: PartForm::Coeffs {
            num,
            den: &den_r * &Poly::from_roots(&flat)?,
        },
        poles: m.poles.clone(),
    })
}

/// The forced part G·Ũ from the factors of G.
fn forced_factors(f: &Factored, u: &SampledInput, m: &Meeting) -> Part {
    let mut zeros = m.zeros_left.clone();
    let mut poles = m.poles.clone();
    for &z in &u.zeros {
        // the zero of cos on a pole of G cancels it
        match poles
            .iter_mut()
            .find(|p| p.multiplicity > 0 && same_root(p.value, z))
        {
            Some(p) => p.multiplicity -= 1,
            None => match zeros.iter_mut().find(|x| x.value == z) {
                Some(x) => x.multiplicity += 1,
                None => zeros.push(Root::new(z, 1)),
            },
        }
    }
    poles.retain(|p| p.multiplicity > 0);
    Part {
        form: PartForm::Factors {
            gain: f.gain() * u.gain,
            zeros,
        },
        poles,
    }
}

/// Y(z)/z as forced and initial-condition parts, and the input poles left (the split).
pub(crate) fn decomposition(f: &Factored, input: &Input, ics: &[f64]) -> Result<Decomposition> {
    let dt = f
        .domain()
        .require_discrete("the closed form y[k] (inverse z-transform)")?;
    input.validate()?;
    f.require_proper(
        &format!("the {input} response (an improper G(z) is not causal)"),
        false,
    )?;
    let u = sampled_input(input, dt);
    let m = meet(f, u.poles.clone(), false);
    let forced = match f.source().coefficients() {
        // the zero of cos on a pole of G (it cancels): from the factors
        Some(c)
            if !u
                .zeros
                .iter()
                .any(|&z| m.poles.iter().any(|p| same_root(p.value, z))) =>
        {
            forced_coeffs(f, &c.reduced, &u, &m)?
        }
        _ => forced_factors(f, &u, &m),
    };
    let ic = if ics.is_empty() {
        None
    } else {
        let Some(c) = f.source().coefficients() else {
            return Err(LtiError::invalid(
                "initial conditions y[-1], y[-2], … are those of a difference equation: this \
                 plant is given by its zeros and poles or as state space, not by its \
                 coefficients (give a state-space plant an initial state)",
            ));
        };
        let num = ic_numerator_over_z(c.tf.den(), ics)?;
        (!num.is_zero()).then(|| Part {
            form: PartForm::Coeffs {
                num,
                den: c.tf.den().clone(),
            },
            poles: f.poles().to_vec(),
        })
    };
    // the impulse's pole at z = 0 gives δ terms: transient, not an input mode
    let input_poles = m
        .input_poles
        .iter()
        .map(|&(v, _)| v)
        .filter(|v| !matches!(input, Input::Impulse) || *v != Complex64::new(0.0, 0.0))
        .collect();
    Ok(Decomposition {
        forced,
        ic,
        input_poles,
    })
}

/// The closed-form sequence y\[k\] and its transient/steady-state split.
pub(crate) fn closed_parts(f: &Factored, input: &Input, ics: &[f64]) -> Result<ClosedParts> {
    let dec = decomposition(f, input, ics)?;
    let dt = f.domain().dt().unwrap_or(1.0);
    let pf = dec.partial_fractions()?;
    let seq = SequenceForm::from_partial_fractions(&pf, dt);
    let is_input = |p: Complex64| dec.input_poles.iter().any(|&v| v == p || v == p.conj());
    // lim y[k]: every pole of Y strictly inside the unit circle but a simple pole at z = 1,
    // whose coefficient is the limit
    let one = Complex64::new(1.0, 0.0);
    let mut settles = true;
    for part in std::iter::once(&dec.forced).chain(dec.ic.as_ref()) {
        if part.is_zero() {
            continue;
        }
        for p in &part.poles {
            let ok = if p.value == one {
                p.multiplicity == 1
            } else {
                p.value.norm() == 0.0 || f.side_of(p.value) == HalfPlane::Left
            };
            settles &= ok;
        }
    }
    let final_value = settles.then(|| {
        pf.terms
            .iter()
            .filter(|t| t.pole == one && t.power == 1)
            .map(|t| t.residue.re)
            .sum::<f64>()
    });
    Ok(ClosedParts {
        transient: ClosedForm::from_sequence(seq.filtered(|p| !is_input(p), true)),
        steady_state: ClosedForm::from_sequence(seq.filtered(is_input, false)),
        closed_form: ClosedForm::from_sequence(seq),
        final_value,
    })
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact values are meant: the samples of sin(πk) are 0
mod tests {
    use super::*;

    #[test]
    fn ic_numerator_of_a_first_and_second_order_equation() {
        // y[k] − a y[k−1] = u[k]: Y_ic = a y[−1] z/(z − a), N_ic/z = a y[−1]
        let d = Poly::from_descending(&[1.0, -0.5]).unwrap();
        assert_eq!(ic_numerator_over_z(&d, &[2.0]).unwrap().coeffs(), &[1.0]);
        // a0 y[k] + a1 y[k−1] + a2 y[k−2]: N_ic = −(a1 y[−1] + a2 y[−2]) z² − a2 y[−1] z
        let d = Poly::from_descending(&[1.0, 3.0, 5.0]).unwrap();
        let n = ic_numerator_over_z(&d, &[7.0, 11.0]).unwrap();
        assert_eq!(n.coeffs(), &[-(3.0 * 7.0 + 5.0 * 11.0), -5.0 * 7.0]);
        assert!(ic_numerator_over_z(&d, &[1.0, 2.0, 3.0]).is_err());
        assert!(ic_numerator_over_z(&d, &[f64::NAN]).is_err());
    }

    #[test]
    fn aliased_sine_changes_sign() {
        // ωT = 2π − 0.3: sin(ωTk) = −sin(0.3k)
        let u = sampled_input(&Input::Sin(std::f64::consts::TAU - 0.3), 1.0);
        assert!((u.gain + 0.3f64.sin()).abs() < 1e-15);
        assert!((u.poles[0].0.arg() - 0.3).abs() < 1e-14);
        // ωT = π: cos(πk) = (−1)^k, sin(πk) = 0
        let u = sampled_input(&Input::Cos(std::f64::consts::PI), 1.0);
        assert_eq!(u.poles, vec![(Complex64::new(-1.0, 0.0), 1)]);
        assert_eq!(
            sampled_input(&Input::Sin(std::f64::consts::PI), 1.0).gain,
            0.0
        );
    }
}
