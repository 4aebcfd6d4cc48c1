//! A SISO state-space model entering the factored core without coefficients.
//!
//! The model is reduced to a minimal realisation (orthogonal staircases,
//! [`crate::numeric::linalg::minimal_realization`]); the removed uncontrollable and
//! unobservable modes become the *cancelled* roots, as common roots of a transfer function do.
//! Poles are the eigenvalues of A with the multiplicities of their eigen structure
//! ([`crate::numeric::linalg::eigen_structure`]), zeros are the transmission zeros (the
//! invariant zeros of the minimal part), and the gain k of G(s) = k·Π(s − zᵢ)/Π(s − pⱼ) is the
//! first non-zero Markov parameter (D, or C·A^(r−1)·B for relative degree r). The minimal
//! realisation is kept: G(s) is evaluated by one Hessenberg reduction and an O(n²) solve per
//! point, and the dc gain by a solve, D − C·A⁻¹·B (from the factors when A has an eigenvalue
//! exactly 0 or a zero lies exactly at 0). No polynomial coefficient is ever formed.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::pole_zero::{PoleZero, count};
use super::source::LowFrequency;
use crate::error::{LtiError, Result};
use crate::lti::StateSpace;
use crate::numeric::linalg::structure::radius;
use crate::numeric::linalg::{
    HessenbergResponse, MinimalRealization, eigen_structure, minimal_realization, relative_degree,
    transmission_zeros,
};
use crate::poly::Root;

/// The minimal realisation of a SISO state-space plant and its Hessenberg form.
#[derive(Debug, Clone)]
pub(crate) struct SsSource {
    /// The minimal realisation (what the responses and the dc gain use).
    pub minimal: MinimalRealization,
    /// G(s) evaluation: Hessenberg form of the minimal A.
    pub response: HessenbergResponse,
}

/// Poles, zeros, cancellations and gain of a SISO state-space model, and its source.
pub(crate) fn factor_state_space(ss: &StateSpace) -> Result<(PoleZero, f64, SsSource)> {
    if ss.b.ncols() != 1 || ss.c.nrows() != 1 {
        return Err(LtiError::invalid(format!(
            "the factored form needs one input and one output; the model has {} inputs and {} outputs: choose a channel",
            ss.b.ncols(),
            ss.c.nrows()
        )));
    }
    let n = ss.a.nrows();
    if n > super::MAX_FACTORED_ORDER {
        return Err(LtiError::OrderTooHigh {
            order: n,
            max: super::MAX_FACTORED_ORDER,
        });
    }
    let minimal = minimal_realization(&ss.a, &ss.b, &ss.c, &ss.d, None)?;
    let poles = roots_of_matrix(&ss.a)?;
    let reduced_poles = roots_of_matrix(&minimal.a)?;
    let removed: Vec<Complex64> = minimal
        .uncontrollable
        .iter()
        .chain(&minimal.unobservable)
        .copied()
        .collect();
    let cancelled = conjugate_closed(&group(&removed));
    let rd = relative_degree(&minimal.a, &minimal.b, &minimal.c, &minimal.d, None)?;
    let zero = rd.r.is_none();
    let reduced_zeros = if zero {
        Vec::new()
    } else {
        let tz = transmission_zeros(&minimal.a, &minimal.b, &minimal.c, &minimal.d, None)?;
        conjugate_closed(&tz.distinct)
    };
    let mut zeros = reduced_zeros.clone();
    if !zero {
        zeros.extend(cancelled.iter().copied());
    }
    crate::poly::roots::sort_roots(&mut zeros);
    let zeros_at_infinity = (!zero).then(|| count(&poles).saturating_sub(count(&zeros)));
    let pz = PoleZero {
        poles,
        zeros,
        cancelled: if zero { Vec::new() } else { cancelled },
        reduced_poles,
        reduced_zeros,
        zeros_at_infinity,
    };
    let response = HessenbergResponse::new(&minimal.a, &minimal.b, &minimal.c, &minimal.d)?;
    Ok((pz, rd.gain, SsSource { minimal, response }))
}

/// Eigenvalues of `a` as roots with algebraic multiplicities, sorted as polynomial roots.
fn roots_of_matrix(a: &DMatrix<f64>) -> Result<Vec<Root>> {
    if a.nrows() == 0 {
        return Ok(Vec::new());
    }
    let st = eigen_structure(a)?;
    let n = a.nrows();
    // An eigenvalue within its cluster radius of 0 is 0 for a matrix within ε‖A‖ of A (an
    // integrator, the free translation of a lattice): it is made exactly 0, as a root of a
    // polynomial with a zero constant coefficient is.
    let pairs: Vec<(Complex64, usize)> = st
        .clusters
        .iter()
        .map(|c| {
            let r = radius(c.algebraic, n, st.scale);
            let v = if c.value.norm() <= r {
                Complex64::new(0.0, 0.0)
            } else if c.value.re.abs() <= r {
                // Likewise a real part within the radius: on the imaginary axis (the undamped
                // lattice's ±jωₖ come out with real parts of ~1e-16 otherwise).
                Complex64::new(0.0, c.value.im)
            } else {
                c.value
            };
            (v, c.algebraic)
        })
        .collect();
    Ok(conjugate_closed(&pairs))
}

/// Equal values merged (exact equality), with multiplicities.
fn group(values: &[Complex64]) -> Vec<(Complex64, usize)> {
    let mut out: Vec<(Complex64, usize)> = Vec::new();
    for &v in values {
        match out.iter_mut().find(|(w, _)| *w == v) {
            Some((_, m)) => *m += 1,
            None => out.push((v, 1)),
        }
    }
    out
}

/// Roots closed under conjugation: real values and upper ones are kept, each upper one with
/// its exact conjugate (the kernels return exact conjugate pairs; this makes it a contract),
/// lower ones are dropped as mirrors. Sorted as polynomial roots.
fn conjugate_closed(values: &[(Complex64, usize)]) -> Vec<Root> {
    let mut out = Vec::new();
    for &(v, m) in values {
        if v.im == 0.0 {
            out.push(Root::new(v, m));
        } else if v.im > 0.0 {
            out.push(Root::new(v, m));
            out.push(Root::new(v.conj(), m));
        }
    }
    crate::poly::roots::sort_roots(&mut out);
    out
}

impl SsSource {
    /// G(s) from the Hessenberg form of the minimal realisation.
    pub(crate) fn eval(&self, s: Complex64) -> Complex64 {
        self.response.eval_siso(s)
    }

    /// The dc gain D − C·A⁻¹·B of the minimal realisation by an LU solve; `None` when A is
    /// singular to working precision (the caller then takes the asymptote from the factors).
    pub(crate) fn low_frequency(&self) -> Option<LowFrequency> {
        let m = &self.minimal;
        let d = m.d.get((0, 0)).copied().unwrap_or(0.0);
        if m.order() == 0 {
            return Some(LowFrequency::of_value(d));
        }
        let x = m.a.clone().lu().solve(&m.b)?;
        let k = d - (&m.c * x).get((0, 0)).copied()?;
        k.is_finite().then(|| LowFrequency::of_value(k))
    }
}
