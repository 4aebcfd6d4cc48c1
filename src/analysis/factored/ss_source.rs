//! A SISO state-space model entering the factored core without coefficients.
//!
//! The model is reduced to a minimal realisation (orthogonal staircases,
//! [`crate::numeric::linalg::minimal_realization`]); the removed uncontrollable and
//! unobservable modes become the *cancelled* roots, as common roots of a transfer function do.
//! Poles are the eigenvalues of A with the multiplicities of their eigen structure
//! ([`StateMatrix::eigen_structure`]), zeros are the transmission zeros (the
//! invariant zeros of the minimal part), and the gain k of G(s) = k·Π(s − zᵢ)/Π(s − pⱼ) is the
//! first non-zero Markov parameter (D, or C·A^(r−1)·B for relative degree r). The minimal
//! realisation is kept: G(s) is evaluated by one Hessenberg reduction and an O(n²) solve per
//! point, and the dc gain by a solve, D − C·A⁻¹·B (from the factors when A has an eigenvalue
//! exactly 0 or a zero lies exactly at 0). No polynomial coefficient is ever formed.
//!
//! The model's A is recognised once, here, where the model enters the factored core
//! ([`StateMatrix::recognise`]); every kernel below takes the structure from it. A model with
//! the mechanical structure of [`crate::numeric::linalg::second_order`] whose input acts on the
//! velocities is reduced in modal coordinates instead ([`super::ss_modal`]): modes of equal
//! stiffness and damping merge into one block (the rest of the group is uncontrollable), a
//! root the output cannot see is removed, and every pole — kept or removed — is a mode's root,
//! exact to the symmetric eigenproblem.
//!
//! Every value is snapped as the eigen structure's radius allows (to 0, onto the imaginary
//! axis); the reduced poles and the removed modes take the value of the eigenvalue of A they
//! belong to, so the same pole never reads differently in two lists.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::low_frequency::LowFrequency;
use super::pole_zero::{MAX_FACTORED_ORDER, PoleZero, count, merge};
use super::ss_modal;
use crate::error::{LtiError, Result};
use crate::lti::StateSpace;
use crate::numeric::linalg::hessenberg_zeros::{HessenbergSiso, is_upper_hessenberg};
use crate::numeric::linalg::structure::{radius, snap};
use crate::numeric::linalg::{
    EigenStructure, HessenbergResponse, MinimalRealization, RelativeDegree, StateMatrix,
    minimal_realization, relative_degree, transmission_zeros,
};
use crate::poly::Root;

/// The minimal realisation of a SISO state-space plant and its Hessenberg form.
#[derive(Debug, Clone)]
pub(crate) struct SsSource {
    /// The minimal realisation (what the responses and the dc gain use).
    pub minimal: MinimalRealization,
    /// G(s) evaluation: Hessenberg form of the minimal A.
    pub response: HessenbergResponse,
    /// How the factors were found, and how well they agree with the realisation.
    pub note: String,
}

/// Largest relative disagreement between the factored G and the realisation's G at the probe
/// points that is still called agreement; beyond it the structure note warns.
pub(crate) const FACTORS_AGREE_REL: f64 = 1e-6;

/// The relative disagreement of the factors (gain, reduced zeros and poles) with the minimal
/// realisation's G at five points off the axis, log-spaced over the poles' magnitudes (where a
/// solve is accurate: no resonance, not beyond the spectrum where a sum of modes cancels).
fn factors_agreement(pz: &PoleZero, gain: f64, response: &HessenbergResponse) -> Option<f64> {
    let mags: Vec<f64> = pz
        .reduced_poles
        .iter()
        .map(|p| p.value.norm())
        .filter(|&m| m > 0.0 && m.is_finite())
        .collect();
    let lo = mags.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = mags.iter().copied().fold(0.0, f64::max);
    if !(lo.is_finite() && hi > 0.0) {
        return None;
    }
    let mut worst = 0.0f64;
    for k in 0..5 {
        let w = lo * (hi / lo).powf(k as f64 / 4.0);
        let s = Complex64::new(0.5 * w, w);
        let direct = response.eval_siso(s);
        let factors = super::series::eval_factors(gain, &pz.reduced_zeros, &pz.reduced_poles, s);
        let scale = direct.norm();
        if !(scale.is_finite() && scale > 0.0) {
            continue;
        }
        worst = worst.max((factors - direct).norm() / scale);
    }
    Some(worst)
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
    if n > MAX_FACTORED_ORDER {
        return Err(LtiError::OrderTooHigh {
            order: n,
            max: MAX_FACTORED_ORDER,
        });
    }
    // the one recognition of this model's A: every kernel below takes the structure from here
    let a = StateMatrix::recognise(&ss.a);
    let finite = ss.a.iter().chain(&ss.b).chain(&ss.c).all(|x| x.is_finite());
    let second = finite
        .then(|| a.second_order())
        .flatten()
        .and_then(|so| ss_modal::second_order_minimal(ss, so).map(|m| (so, m)));
    let known: Option<ss_modal::KnownZeros>;
    let mut method = String::from(
        "eigenvalues of A by the Schur form, minimal realisation by staircases, transmission \
         zeros by the system pencil",
    );
    let (eigenvalues, minimal, reduced_poles, removed, rd, found) = match second {
        Some((so, red)) => {
            let rayleigh = ss_modal::rayleigh_zeros(ss, so, &red);
            method = format!(
                "second order — modes by the symmetric eigenproblem of the stiffness, minimal \
                 realisation in modal coordinates, zeros {}",
                if rayleigh.is_some() {
                    "through the modal variable w (Rayleigh damping)"
                } else {
                    "by the system pencil"
                }
            );
            known = rayleigh.or_else(|| ss_modal::model_zeros(ss, &red));
            let rd = degree(known.as_ref(), || normwise_degree(&red.minimal))?;
            let ev = Eigenvalues::new(so.eigen_structure(), n);
            let by_position = ev.by_position();
            let kept: Vec<Complex64> = red.kept.iter().map(|&p| by_position[p]).collect();
            let removed: Vec<Complex64> = red.removed.iter().map(|&p| by_position[p]).collect();
            (
                ev,
                red.minimal,
                conjugate_closed(&group(&kept)),
                removed,
                rd,
                None,
            )
        }
        None => {
            let minimal = minimal_realization(&ss.a, &ss.b, &ss.c, &ss.d, None)?;
            // the pencil's normwise degree of the minimal realisation, once: the
            // componentwise decision compares against it, and it stands when that finds
            // nothing lower
            let normwise = normwise_degree(&minimal)?;
            if n == 0 {
                let rd = degree(None, || Ok(normwise))?;
                return finish(
                    Vec::new(),
                    minimal,
                    Vec::new(),
                    Vec::new(),
                    None,
                    "no states",
                    rd,
                    None,
                );
            }
            let removed: Vec<Complex64> = minimal
                .uncontrollable
                .iter()
                .chain(&minimal.unobservable)
                .copied()
                .collect();
            known = finer_structure(ss, &minimal, &removed, &normwise)?;
            let rd = degree(known.as_ref(), || Ok(normwise))?;
            // Nothing removed (the generic case): the minimal A is an orthogonal similarity
            // of the balanced A, so its eigen structure is A's — one eigenproblem, not two,
            // and on the staircases' Hessenberg form (no second reduction) — and the zeros'
            // eigenproblem, independent of it, runs beside it on a second core when both
            // are large. Else A's structure and the minimal part's, whose values are mapped
            // to A's below, and the zeros afterwards.
            let (st, reduced, found) = if minimal.order() == n {
                let zeros_here = known.is_none() && rd.r.is_some();
                let (st, found) = crate::numeric::parallel::join(
                    zeros_here && n >= PARALLEL_ORDER,
                    || structure_of_similar(&ss.a, &minimal.a),
                    || zeros_here.then(|| minimal_zeros(&minimal, rd.r)),
                );
                (st?, None, found.transpose()?)
            } else {
                (
                    a.eigen_structure()?,
                    Some(roots_of_matrix(&minimal.a)?),
                    None,
                )
            };
            if let Some(k) = &known {
                method = format!(
                    "eigenvalues of A by the Schur form, minimal realisation by staircases; \
                     relative degree {} from the model's Markov parameters (C·A^k·B above \
                     its componentwise rounding bound, below the pencil's normwise \
                     tolerance), zeros by the system pencil reduced to that degree and \
                     refined by Newton on G(s) of the minimal realisation",
                    k.r
                );
            }
            // the reduced poles and the removed modes are eigenvalues of A: its values
            let ev = Eigenvalues::new(st, n);
            let reduced = match reduced {
                None => ev.roots(),
                Some(reduced) => reduced
                    .iter()
                    .map(|r| Root::new(ev.nearest(r.value), r.multiplicity))
                    .collect(),
            };
            let removed = removed.iter().map(|&v| ev.nearest(v)).collect();
            (ev, minimal, reduced, removed, rd, found)
        }
    };
    let poles = eigenvalues.roots();
    finish(
        poles,
        minimal,
        reduced_poles,
        removed,
        known,
        &method,
        rd,
        found,
    )
}

/// Order from which the zeros' eigenproblem runs beside the poles' on a second core (the
/// pair then costs about one; below it a thread costs more than it saves).
const PARALLEL_ORDER: usize = 64;

/// The relative degree and first Markov parameter of the channel: from the zeros known
/// already (the componentwise decision, or the modes) when there are such, else the pencil's
/// normwise rule on the minimal realisation (`normwise`, asked only then).
fn degree(
    known: Option<&ss_modal::KnownZeros>,
    normwise: impl FnOnce() -> Result<RelativeDegree>,
) -> Result<RelativeDegree> {
    match known {
        Some(k) => Ok(RelativeDegree {
            r: Some(k.r),
            gain: k.gain,
        }),
        None => normwise(),
    }
}

/// The pencil's normwise relative degree of a minimal realisation.
fn normwise_degree(minimal: &MinimalRealization) -> Result<RelativeDegree> {
    relative_degree(&minimal.a, &minimal.b, &minimal.c, &minimal.d, None)
}

/// The zeros of a minimal realisation of relative degree `r` (distinct values with their
/// multiplicities, not yet snapped), and whether they are the eigenvalues of its Hessenberg
/// zero dynamics (else the system pencil's).
struct MinimalZeros {
    distinct: Vec<(Complex64, usize)>,
    by_hessenberg: bool,
}

fn minimal_zeros(minimal: &MinimalRealization, r: Option<usize>) -> Result<MinimalZeros> {
    Ok(match hessenberg_zero_dynamics(minimal, r) {
        Some(z) => MinimalZeros {
            distinct: if z.nrows() == 0 {
                Vec::new()
            } else {
                let st = StateMatrix::recognise(&z).eigen_structure()?;
                st.clusters.iter().map(|c| (c.value, c.algebraic)).collect()
            },
            by_hessenberg: true,
        },
        None => MinimalZeros {
            distinct: transmission_zeros(&minimal.a, &minimal.b, &minimal.c, &minimal.d, None)?
                .distinct,
            by_hessenberg: false,
        },
    })
}

/// The structure of a single channel that the pencil's normwise rank decisions miss: when
/// the model's Markov parameters, decided against their componentwise rounding bound, give a
/// lower relative degree than the reduction of the minimal realisation, that degree, its
/// Markov parameter and the zeros refined on the minimal realisation
/// (`numeric::linalg::componentwise`); `None` otherwise (the normwise results stand).
fn finer_structure(
    ss: &StateSpace,
    minimal: &MinimalRealization,
    removed: &[Complex64],
    normwise: &RelativeDegree,
) -> Result<Option<ss_modal::KnownZeros>> {
    use crate::numeric::linalg::componentwise::{
        componentwise_relative_degree, refined_channel_zeros,
    };
    let Some((r, gain)) = componentwise_relative_degree(&ss.a, &ss.b, &ss.c, &ss.d) else {
        return Ok(None);
    };
    if normwise.r.is_none_or(|rn| r >= rn) {
        return Ok(None);
    }
    let response = siso_response(minimal)?;
    let Some(zeros) = refined_channel_zeros(&ss.a, &ss.b, &ss.c, r, removed, &response)? else {
        return Ok(None);
    };
    Ok(Some(ss_modal::KnownZeros { zeros, r, gain }))
}

/// The pole–zero part from the poles, the minimal realisation, its poles and the removed
/// modes: zeros are the transmission zeros of the minimal part (`found` when computed
/// already), the gain its first non-zero Markov parameter (`rd`, see [`degree`]).
#[allow(clippy::too_many_arguments)] // the parts of one factorisation, passed once
fn finish(
    poles: Vec<Root>,
    minimal: MinimalRealization,
    mut reduced_poles: Vec<Root>,
    removed: Vec<Complex64>,
    known: Option<ss_modal::KnownZeros>,
    method: &str,
    rd: RelativeDegree,
    found: Option<MinimalZeros>,
) -> Result<(PoleZero, f64, SsSource)> {
    crate::poly::roots::sort_roots(&mut reduced_poles);
    let cancelled = conjugate_closed(&group(&removed));
    let zero = rd.r.is_none();
    let mut by_hessenberg = false;
    // G ≡ 0: the minimal realisation has order 0 and every mode of A is decoupled from the
    // channel — the channel has no poles (issue 24: it listed every eigenvalue of A).
    let poles = if zero { reduced_poles.clone() } else { poles };
    let reduced_zeros = if zero {
        Vec::new()
    } else if let Some(k) = &known {
        conjugate_closed(&k.zeros)
    } else {
        let found = match found {
            Some(f) => f,
            None => minimal_zeros(&minimal, rd.r)?,
        };
        by_hessenberg = found.by_hessenberg;
        let distinct = found.distinct;
        let scale = crate::numeric::linalg::norms::norm_1_inf(&minimal.a);
        let nm = minimal.order().max(1);
        let snapped: Vec<(Complex64, usize)> = distinct
            .iter()
            .map(|&(z, m)| (snap(z, radius(m, nm, scale)), m))
            .collect();
        conjugate_closed(&snapped)
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
    let response = siso_response(&minimal)?;
    let agreement = match factors_agreement(&pz, rd.gain, &response) {
        Some(e) if e.is_nan() || e > FACTORS_AGREE_REL => format!(
            "; the factors DISAGREE with G(s) by {} (relative, off the axis within the poles' \
             range): the zeros and the gain are not resolved (an ill-conditioned pencil), and \
             what is built on them (Bode, margins, closed forms, step metrics) is not reliable",
            crate::fmt::fmt_sig(e, 2)
        ),
        Some(e) => format!(
            "; the factors agree with G(s) to {}",
            crate::fmt::fmt_sig(e.max(f64::EPSILON), 2)
        ),
        None => String::new(),
    };
    let method = if by_hessenberg {
        method.replacen(
            "zeros by the system pencil",
            "zeros as the eigenvalues of the zero dynamics of the staircases' Hessenberg form",
            1,
        )
    } else {
        method.to_string()
    };
    let note = format!("numerical (state space: {method}{agreement})");
    Ok((
        pz,
        rd.gain,
        SsSource {
            minimal,
            response,
            note,
        },
    ))
}

/// The zero dynamics of the minimal realisation when it is in the staircases' Hessenberg
/// form and the relative degree (decided by the pencil's normwise rule, or componentwise) is
/// 0 with D ≠ 0 or 1 with D = 0: an upper Hessenberg matrix whose eigenvalues are the zeros
/// (see `numeric::linalg::hessenberg_zeros`); `None` otherwise, or when the elimination's
/// growth is beyond its bound (the pencil reduction then finds the zeros).
fn hessenberg_zero_dynamics(
    minimal: &MinimalRealization,
    r: Option<usize>,
) -> Option<DMatrix<f64>> {
    let d = minimal.d.get((0, 0)).copied()?;
    match r {
        Some(0) if d != 0.0 => {}
        Some(1) if d == 0.0 => {}
        _ => return None,
    }
    HessenbergSiso::of(&minimal.a, &minimal.b, &minimal.c, &minimal.d)?.zero_dynamics()
}

/// G(s) of the minimal realisation by the Hessenberg solve; in the staircases' Hessenberg
/// form (or its dual, the same G for one channel) the reduction has nothing left to do.
fn siso_response(minimal: &MinimalRealization) -> Result<HessenbergResponse> {
    match HessenbergSiso::of(&minimal.a, &minimal.b, &minimal.c, &minimal.d) {
        Some(form) => {
            let n = form.h.nrows();
            let mut b = DMatrix::zeros(n, 1);
            b[(0, 0)] = form.beta;
            let c = DMatrix::from_row_slice(1, n, &form.c);
            HessenbergResponse::new(&form.h, &b, &c, &minimal.d)
        }
        None => HessenbergResponse::new(&minimal.a, &minimal.b, &minimal.c, &minimal.d),
    }
}

/// The eigenvalues of A: its eigen structure and every cluster's value snapped once.
struct Eigenvalues {
    st: EigenStructure,
    /// `values[k]`: cluster k's value, snapped (see [`snap`]).
    values: Vec<Complex64>,
    n: usize,
}

impl Eigenvalues {
    fn new(st: EigenStructure, n: usize) -> Eigenvalues {
        let values = st
            .clusters
            .iter()
            .map(|c| snap(c.value, radius(c.algebraic, n, st.scale)))
            .collect();
        Eigenvalues { st, values, n }
    }

    /// The eigenvalue (snapped cluster value) nearest to `v` when `v` lies within that
    /// cluster's radius, else `v` snapped on its own.
    fn nearest(&self, v: Complex64) -> Complex64 {
        let (n, scale) = (self.n, self.st.scale);
        self.st
            .clusters
            .iter()
            .zip(&self.values)
            .map(|(c, &val)| ((c.value - v).norm(), radius(c.algebraic, n, scale), val))
            .filter(|(d, r, _)| d <= r)
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map_or_else(|| snap(v, radius(1, n, scale)), |(_, _, val)| val)
    }

    /// The value at each position of the structure (positions 2k, 2k + 1 are mode k's roots in
    /// the second-order structure).
    fn by_position(&self) -> Vec<Complex64> {
        let mut out = vec![Complex64::new(0.0, 0.0); self.n];
        for (c, &v) in self.st.clusters.iter().zip(&self.values) {
            for &p in &c.positions {
                if let Some(slot) = out.get_mut(p) {
                    *slot = v;
                }
            }
        }
        out
    }

    /// The clusters as roots: an eigenvalue within its cluster radius of 0 is 0 for a matrix
    /// within ε‖A‖ of A (an integrator, the free translation of a lattice), as a root of a
    /// polynomial with a zero constant coefficient is; likewise a real part within the radius
    /// is 0 (the undamped lattice's ±jωₖ come out with real parts of ~1e-16 otherwise).
    fn roots(&self) -> Vec<Root> {
        let pairs: Vec<(Complex64, usize)> = self
            .values
            .iter()
            .zip(&self.st.clusters)
            .map(|(&v, c)| (v, c.algebraic))
            .collect();
        conjugate_closed(&pairs)
    }
}

/// Eigenvalues of `a` as roots with algebraic multiplicities, sorted as polynomial roots. (The
/// minimal realisation is a model of its own: its structure is recognised like the model's.)
fn roots_of_matrix(a: &DMatrix<f64>) -> Result<Vec<Root>> {
    if a.nrows() == 0 {
        return Ok(Vec::new());
    }
    Ok(Eigenvalues::new(StateMatrix::recognise(a).eigen_structure()?, a.nrows()).roots())
}

/// The eigen structure of A, from A itself when it is (upper or lower) Hessenberg — a
/// diagonal or triangular A keeps its eigenvalues exactly — else from `similar`, a matrix
/// similar to it in the form the staircases leave, when that is Hessenberg, else from A. A
/// lower Hessenberg matrix is transposed (the same eigenvalues and Jordan structure), so the
/// Schur form starts from an upper Hessenberg matrix and skips the reduction.
fn structure_of_similar(a: &DMatrix<f64>, similar: &DMatrix<f64>) -> Result<EigenStructure> {
    for m in [a, similar] {
        if is_upper_hessenberg(m) {
            return StateMatrix::recognise(m).eigen_structure();
        }
        let t = m.transpose();
        if is_upper_hessenberg(&t) {
            return StateMatrix::recognise(&t).eigen_structure();
        }
    }
    StateMatrix::recognise(a).eigen_structure()
}

/// Equal values merged (exact equality), with multiplicities.
fn group(values: &[Complex64]) -> Vec<(Complex64, usize)> {
    merge(&values.iter().map(|&v| (v, 1)).collect::<Vec<_>>())
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

    /// G(s), G′(s) and the size of the terms summed for G, from the Hessenberg form of the
    /// minimal realisation (what the margins refine their crossings on).
    pub(crate) fn eval_with_derivative(&self, s: Complex64) -> Option<(Complex64, Complex64, f64)> {
        self.response.eval_siso_with_derivative(s)
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
