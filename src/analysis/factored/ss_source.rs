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
//!
//! A model with the mechanical structure of [`crate::numeric::linalg::second_order`] whose
//! input acts on the velocities is reduced in modal coordinates instead: modes of equal
//! stiffness and damping merge into one block (the rest of the group is uncontrollable), a
//! root the output cannot see is removed, and every pole — kept or removed — is a mode's root,
//! exact to the symmetric eigenproblem.
//!
//! Every value is snapped as the eigen structure's radius allows (to 0, onto the imaginary
//! axis); the reduced poles and the removed modes take the value of the eigenvalue of A they
//! belong to, so the same pole never reads differently in two lists.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::pole_zero::{PoleZero, count};
use super::source::LowFrequency;
use crate::error::{LtiError, Result};
use crate::lti::StateSpace;
use crate::numeric::linalg::second_order::{self, SecondOrder};
use crate::numeric::linalg::structure::{radius, snap};
use crate::numeric::linalg::{
    EigenStructure, HessenbergResponse, MinimalRealization, eigen_structure, minimal_realization,
    relative_degree, transmission_zeros,
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
    if n > super::MAX_FACTORED_ORDER {
        return Err(LtiError::OrderTooHigh {
            order: n,
            max: super::MAX_FACTORED_ORDER,
        });
    }
    let finite = ss.a.iter().chain(&ss.b).chain(&ss.c).all(|x| x.is_finite());
    let second = finite
        .then(|| SecondOrder::detect(&ss.a))
        .flatten()
        .and_then(|so| second_order_minimal(ss, &so).map(|m| (so, m)));
    let mut known = None;
    let mut method = String::from(
        "eigenvalues of A by the Schur form, minimal realisation by staircases, transmission \
         zeros by the system pencil",
    );
    let (structure, minimal, reduced_poles, removed) = match second {
        Some((so, red)) => {
            let rayleigh = rayleigh_zeros(ss, &so, &red);
            method = format!(
                "second order — modes by the symmetric eigenproblem of the stiffness, minimal \
                 realisation in modal coordinates, zeros {}",
                if rayleigh.is_some() {
                    "through the modal variable w (Rayleigh damping)"
                } else {
                    "by the system pencil"
                }
            );
            known = rayleigh.or_else(|| model_zeros(ss, &red));
            let st = so.eigen_structure();
            let by_position = values_by_position(&st, n);
            let kept: Vec<Complex64> = red.kept.iter().map(|&p| by_position[p]).collect();
            let removed: Vec<Complex64> = red.removed.iter().map(|&p| by_position[p]).collect();
            (st, red.minimal, conjugate_closed(&group(&kept)), removed)
        }
        None => {
            let st = if n == 0 {
                None
            } else {
                Some(eigen_structure(&ss.a)?)
            };
            let minimal = minimal_realization(&ss.a, &ss.b, &ss.c, &ss.d, None)?;
            let reduced = roots_of_matrix(&minimal.a)?;
            let removed: Vec<Complex64> = minimal
                .uncontrollable
                .iter()
                .chain(&minimal.unobservable)
                .copied()
                .collect();
            let Some(st) = st else {
                return finish(Vec::new(), minimal, reduced, Vec::new(), None, "no states");
            };
            // the reduced poles and the removed modes are eigenvalues of A: its values
            let reduced = reduced
                .iter()
                .map(|r| Root::new(nearest_pole(&st, n, r.value), r.multiplicity))
                .collect();
            let removed = removed.iter().map(|&v| nearest_pole(&st, n, v)).collect();
            (st, minimal, reduced, removed)
        }
    };
    let poles = roots_of_structure(&structure, n);
    finish(poles, minimal, reduced_poles, removed, known, &method)
}

/// The pole–zero part from the poles, the minimal realisation, its poles and the removed
/// modes: zeros are the transmission zeros of the minimal part, the gain its first non-zero
/// Markov parameter.
fn finish(
    poles: Vec<Root>,
    minimal: MinimalRealization,
    mut reduced_poles: Vec<Root>,
    removed: Vec<Complex64>,
    known: Option<KnownZeros>,
    method: &str,
) -> Result<(PoleZero, f64, SsSource)> {
    crate::poly::roots::sort_roots(&mut reduced_poles);
    let cancelled = conjugate_closed(&group(&removed));
    let rd = match &known {
        Some(k) => crate::numeric::linalg::RelativeDegree {
            r: Some(k.r),
            gain: k.gain,
        },
        None => relative_degree(&minimal.a, &minimal.b, &minimal.c, &minimal.d, None)?,
    };
    let zero = rd.r.is_none();
    let reduced_zeros = if zero {
        Vec::new()
    } else if let Some(k) = &known {
        conjugate_closed(&k.zeros)
    } else {
        let tz = transmission_zeros(&minimal.a, &minimal.b, &minimal.c, &minimal.d, None)?;
        let scale = crate::numeric::linalg::norm_1_inf(&minimal.a);
        let nm = minimal.order().max(1);
        let snapped: Vec<(Complex64, usize)> = tz
            .distinct
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
    let response = HessenbergResponse::new(&minimal.a, &minimal.b, &minimal.c, &minimal.d)?;
    let agreement = match factors_agreement(&pz, rd.gain, &response) {
        Some(e) if e.is_nan() || e > FACTORS_AGREE_REL => format!(
            "; the factors DISAGREE with G(s) by {} (relative, off the axis within the poles' \
             range): the zeros and the gain are not resolved (an ill-conditioned pencil), and \
             what is built on them (Bode, margins, closed forms, step metrics) is not reliable",
            crate::poly::fmt_sig(e, 2)
        ),
        Some(e) => format!(
            "; the factors agree with G(s) to {}",
            crate::poly::fmt_sig(e.max(f64::EPSILON), 2)
        ),
        None => String::new(),
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

/// The snapped value of each eigenvalue cluster of A.
fn snapped_values(st: &EigenStructure, n: usize) -> Vec<Complex64> {
    st.clusters
        .iter()
        .map(|c| snap(c.value, radius(c.algebraic, n, st.scale)))
        .collect()
}

/// The eigenvalue of A (a cluster value, snapped) nearest to `v` when `v` lies within that
/// cluster's radius, else `v` snapped on its own.
fn nearest_pole(st: &EigenStructure, n: usize, v: Complex64) -> Complex64 {
    let values = snapped_values(st, n);
    st.clusters
        .iter()
        .zip(&values)
        .map(|(c, &val)| ((c.value - v).norm(), radius(c.algebraic, n, st.scale), val))
        .filter(|(d, r, _)| d <= r)
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map_or_else(|| snap(v, radius(1, n, st.scale)), |(_, _, val)| val)
}

/// The snapped cluster value at each position of the structure (positions 2k, 2k + 1 are
/// mode k's roots in the second-order structure).
fn values_by_position(st: &EigenStructure, n: usize) -> Vec<Complex64> {
    let mut out = vec![Complex64::new(0.0, 0.0); n];
    for (c, v) in st.clusters.iter().zip(snapped_values(st, n)) {
        for &p in &c.positions {
            if let Some(slot) = out.get_mut(p) {
                *slot = v;
            }
        }
    }
    out
}

/// The minimal realisation of a SISO channel of a second-order model whose input acts on the
/// velocities only (B's position rows zero), built in modal coordinates: modes with the same
/// stiffness and damping share one 2×2 block [[0, 1], [−λ, −γ]] with input (0, ‖β‖) and output
/// Σ uₖ·(c_q,k, c_v,k)·‖β‖ (u = β/‖β‖, β the modes' inputs) — the other directions of the group
/// are uncontrollable — and a root μ with c_q + μ·c_v = 0 is unobservable (the block shrinks
/// to the other root, or vanishes). Returns the realisation, the positions (2k + i: root i of
/// mode k) of the kept roots, and those of the removed ones; `None` when B moves positions.
fn second_order_minimal(ss: &StateSpace, so: &SecondOrder) -> Option<ModalReduction> {
    let d = so.dof;
    let n = 2 * d;
    if ss.b.rows(0, d).iter().any(|&x| x != 0.0) {
        return None;
    }
    let beta = &so.shapes_inv * ss.b.rows(d, d);
    let cq = ss.c.columns(0, d) * &so.shapes;
    let cv = ss.c.columns(d, d) * &so.shapes;
    if beta
        .iter()
        .chain(cq.iter())
        .chain(cv.iter())
        .any(|x| !x.is_finite())
    {
        return None;
    }
    let eps_n2 = (n * n) as f64 * f64::EPSILON;
    let tol_b = eps_n2 * beta.norm();
    let tol_c = eps_n2 * (cq.norm_squared() + cv.norm_squared()).sqrt();
    // groups of modes with the same stiffness and damping (exactly: snapped when recognised)
    let mut order: Vec<usize> = (0..d).collect();
    let key = |k: usize| (so.modes[k].stiffness, so.modes[k].damping);
    order.sort_by(|&x, &y| {
        let (a, b) = (key(x), key(y));
        a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1))
    });
    let mut blocks: Vec<(DMatrix<f64>, Vec<f64>, Vec<f64>)> = Vec::new();
    let (mut kept, mut uncontrollable, mut unobservable) = (Vec::new(), Vec::new(), Vec::new());
    let mut i = 0;
    while i < d {
        let mut j = i + 1;
        while j < d && key(order[j]) == key(order[i]) {
            j += 1;
        }
        let group = &order[i..j];
        i = j;
        let nb = group.iter().map(|&k| beta[k] * beta[k]).sum::<f64>().sqrt();
        let roots_of = |k: usize| [2 * k, 2 * k + 1];
        if nb <= tol_b {
            uncontrollable.extend(group.iter().flat_map(|&k| roots_of(k)));
            continue;
        }
        // the controllable direction is one mode of the group; the others are removed
        let lead = group[0];
        uncontrollable.extend(group[1..].iter().flat_map(|&k| roots_of(k)));
        let ceq: f64 = group.iter().map(|&k| beta[k] * cq[k]).sum();
        let cev: f64 = group.iter().map(|&k| beta[k] * cv[k]).sum();
        let m = &so.modes[lead];
        let [mu1, mu2] = m.roots;
        let seen = |mu: Complex64| {
            (Complex64::new(ceq, 0.0) + mu * cev).norm() > tol_c * nb * (1.0 + mu.norm())
        };
        let (s1, s2) = if m.critical {
            // (c_v·s + c_q)/(s − μ)²: the numerator's root at μ leaves c_v/(s − μ)
            let top = seen(mu1);
            let any = top || cev.abs() > tol_c * nb;
            (any, top)
        } else {
            (seen(mu1), seen(mu2))
        };
        let [p1, p2] = roots_of(lead);
        match (s1, s2) {
            (true, true) => {
                let [[a11, a12], [a21, a22]] = m.block();
                blocks.push((
                    DMatrix::from_row_slice(2, 2, &[a11, a12, a21, a22]),
                    vec![0.0, 1.0],
                    vec![ceq, cev],
                ));
                kept.extend([p1, p2]);
            }
            (false, false) => unobservable.extend([p1, p2]),
            (keep_first, _) => {
                // one real root left: (c_v·μ + c_q)/(μ − μ_other) at it (the Jordan case:
                // c_v at μ)
                let (keep, gone, pk, pg) = if keep_first {
                    (mu1, mu2, p1, p2)
                } else {
                    (mu2, mu1, p2, p1)
                };
                if keep.im != 0.0 {
                    return None;
                }
                let r = if m.critical {
                    cev
                } else {
                    ((Complex64::new(ceq, 0.0) + keep * cev) / (keep - gone)).re
                };
                blocks.push((DMatrix::from_element(1, 1, keep.re), vec![1.0], vec![r]));
                kept.push(pk);
                unobservable.push(pg);
            }
        }
    }
    let order_min: usize = blocks.iter().map(|b| b.0.nrows()).sum();
    let mut a = DMatrix::zeros(order_min, order_min);
    let mut b = DMatrix::zeros(order_min, 1);
    let mut c = DMatrix::zeros(1, order_min);
    let mut at = 0;
    for (blk, bb, cc) in &blocks {
        let k = blk.nrows();
        a.view_mut((at, at), (k, k)).copy_from(blk);
        for r in 0..k {
            b[(at + r, 0)] = bb[r];
            c[(0, at + r)] = cc[r];
        }
        at += k;
    }
    let to_values = |ps: &[usize]| -> Vec<Complex64> {
        ps.iter().map(|&p| so.modes[p / 2].roots[p % 2]).collect()
    };
    let n_controllable = n - uncontrollable.len();
    let minimal = MinimalRealization {
        a,
        b,
        c,
        d: ss.d.clone(),
        uncontrollable: to_values(&uncontrollable),
        unobservable: to_values(&unobservable),
        n_controllable,
        abs_tol: (tol_b, tol_c),
    };
    let removed = uncontrollable.into_iter().chain(unobservable).collect();
    let pairs = blocks.iter().filter(|b| b.0.nrows() == 2).count();
    let singles = blocks.len() - pairs;
    Some(ModalReduction {
        minimal,
        kept,
        removed,
        pairs,
        singles,
    })
}

/// What [`second_order_minimal`] found.
struct ModalReduction {
    minimal: MinimalRealization,
    /// Positions (2k + i: root i of mode k) of the roots kept …
    kept: Vec<usize>,
    /// … and of those removed.
    removed: Vec<usize>,
    /// Kept groups with both roots (2×2 blocks) and with one (1×1 blocks).
    pairs: usize,
    singles: usize,
}

/// Zeros (with multiplicities), relative degree and gain of a channel computed in advance.
struct KnownZeros {
    zeros: Vec<(Complex64, usize)>,
    r: usize,
    gain: f64,
}

/// The zeros of a position output of a force input under classical damping of Rayleigh's form
/// γₖ = α + β·λₖ (no damping: α = β = 0) through the modal variable w = (s² + αs)/(1 + βs):
/// every mode's factor is s² + γₖs + λₖ = (1 + βs)·(w + λₖ), so G(s) = H(w)/(1 + βs) with
/// H(w) = C_q·(wI + G)⁻¹·B_v, the same channel with s² replaced by w. With H = h·Π(w − wᵢ)/
/// Π(w + λₖ) of relative degree ρ,
///
/// G(s) = h·β^(ρ−1)·Π(s² + (α − βwᵢ)s − wᵢ)·(s + 1/β)^(ρ−1) / Π(s² + γₖs + λₖ)
///
/// — each zero wᵢ of H gives two zeros of G, and a ρ−1-fold zero sits exactly at −1/β (which
/// the pencil of the 2n-state model scatters or loses to infinity: its gain is β^(ρ−1) times
/// smaller). H's zeros and gain come from the n-state model (−G, B_v, C_q) in the model's own
/// coordinates. `None` when the model is not of that kind (velocity output, D ≠ 0, damping
/// not affine in the stiffness) or H's counts do not match the modal reduction.
fn rayleigh_zeros(ss: &StateSpace, so: &SecondOrder, red: &ModalReduction) -> Option<KnownZeros> {
    let d = so.dof;
    let zero_cols = ss.c.columns(d, d).iter().all(|&x| x == 0.0);
    if !zero_cols || ss.d.iter().any(|&x| x != 0.0) || red.singles > 0 || red.pairs == 0 {
        return None;
    }
    // γ = α + βλ over the modes (α, β from the extreme stiffnesses)
    let (lo, hi) = (so.modes.first()?, so.modes.last()?);
    let norm_e = so.modes.iter().map(|m| m.damping.abs()).fold(0.0, f64::max);
    let tol = second_order::snap_tol(d, norm_e.max(f64::MIN_POSITIVE));
    let span = hi.stiffness - lo.stiffness;
    // From the matrices when G couples the states: E = αI + βG entry by entry (a model built
    // as Rayleigh's has β exactly, e.g. 0.01·(−1)/(−1)); else from the extreme modes.
    let (g, e) = (ss.a.view((d, 0), (d, d)), ss.a.view((d, d), (d, d)));
    let mut ratios: Vec<f64> = Vec::new();
    for j in 0..d {
        for i in 0..d {
            if i != j && g[(i, j)] != 0.0 {
                ratios.push(e[(i, j)] / g[(i, j)]);
            }
        }
    }
    ratios.sort_by(f64::total_cmp);
    // the median ratio (exact when the model was built with one β)
    let from_entries = ratios.get(ratios.len() / 2).map(|&beta| {
        let alpha = (0..d).map(|i| beta * g[(i, i)] - e[(i, i)]).sum::<f64>() / d as f64;
        (alpha, beta)
    });
    let (alpha, beta) = if let Some(ab) = from_entries
        && so
            .modes
            .iter()
            .all(|m| (m.damping - (ab.0 + ab.1 * m.stiffness)).abs() <= tol)
    {
        ab
    } else if span > 0.0 && (hi.damping - lo.damping).abs() > tol {
        let beta = (hi.damping - lo.damping) / span;
        (lo.damping - beta * lo.stiffness, beta)
    } else {
        // no stiffness dependence within the tolerance: β = 0 exactly (a β of 1e-17 would
        // put a zero at −1e17)
        let mean = so.modes.iter().map(|m| m.damping).sum::<f64>() / d as f64;
        (mean, 0.0)
    };
    if so
        .modes
        .iter()
        .any(|m| (m.damping - (alpha + beta * m.stiffness)).abs() > tol)
    {
        return None;
    }
    let a_w = ss.a.view((d, 0), (d, d)).clone_owned();
    let b_w = ss.b.rows(d, d).clone_owned();
    let c_w = ss.c.columns(0, d).clone_owned();
    let d_w = DMatrix::zeros(1, 1);
    let rd = relative_degree(&a_w, &b_w, &c_w, &d_w, None).ok()?;
    let rho = rd.r?;
    let tz = transmission_zeros(&a_w, &b_w, &c_w, &d_w, None).ok()?;
    let p: usize = tz.distinct.iter().map(|z| z.1).sum();
    if rho == 0 || p + rho != red.pairs {
        return None;
    }
    let scale = crate::numeric::linalg::norm_1_inf(&a_w);
    let mut zeros: Vec<(Complex64, usize)> = Vec::new();
    for &(w, m) in &tz.distinct {
        let r = radius(m, d, scale);
        // a zero of H within its radius of the real axis is real (H has real data)
        let w = if w.im.abs() <= r {
            Complex64::new(w.re, 0.0)
        } else {
            w
        };
        for z in quadratic_roots(Complex64::new(alpha, 0.0) - beta * w, -w) {
            zeros.push((z, m));
        }
    }
    let (mut gain, extra) = (rd.gain, rho - 1);
    if beta != 0.0 && extra > 0 {
        zeros.push((Complex64::new(-1.0 / beta, 0.0), extra));
        gain *= beta.powi(extra as i32);
    }
    let r = 2 * red.pairs - 2 * p - if beta != 0.0 { extra } else { 0 };
    (gain.is_finite() && gain != 0.0).then_some(KnownZeros {
        zeros: merge(&zeros),
        r,
        gain,
    })
}

/// Zeros, relative degree and gain of a second-order channel that is not of Rayleigh's kind,
/// from the model in its own coordinates (sparse and exact where the modal form is dense and
/// rounded: the pencil and the Markov parameters of a lattice see its couplings exactly);
/// `None` when the counts do not match the modal reduction's minimal order.
fn model_zeros(ss: &StateSpace, red: &ModalReduction) -> Option<KnownZeros> {
    let rd = relative_degree(&ss.a, &ss.b, &ss.c, &ss.d, None).ok()?;
    let r = rd.r?;
    let tz = transmission_zeros(&ss.a, &ss.b, &ss.c, &ss.d, None).ok()?;
    let p: usize = tz.distinct.iter().map(|z| z.1).sum();
    if p + r != red.minimal.order() {
        return None;
    }
    let scale = crate::numeric::linalg::norm_1_inf(&ss.a);
    let n = ss.a.nrows();
    let zeros = tz
        .distinct
        .iter()
        .map(|&(z, m)| (snap(z, radius(m, n, scale)), m))
        .collect();
    Some(KnownZeros {
        zeros,
        r,
        gain: rd.gain,
    })
}

/// The roots of s² + b·s + c (complex coefficients) without cancellation.
fn quadratic_roots(b: Complex64, c: Complex64) -> [Complex64; 2] {
    let disc = (b * b - 4.0 * c).sqrt();
    // the sign that adds magnitudes: q = −(b ± √disc)/2 with Re(b̄·√disc) ≥ 0
    let sq = if (b.conj() * disc).re >= 0.0 {
        disc
    } else {
        -disc
    };
    let q = -(b + sq) / 2.0;
    if q.norm() == 0.0 {
        return [q, q];
    }
    let other = c / q;
    // a real quadratic's complex pair as exact conjugates
    if b.im == 0.0 && c.im == 0.0 && q.im != 0.0 {
        return [q, q.conj()];
    }
    [q, other]
}

/// Equal values merged, multiplicities added.
fn merge(values: &[(Complex64, usize)]) -> Vec<(Complex64, usize)> {
    let mut out: Vec<(Complex64, usize)> = Vec::new();
    for &(v, m) in values {
        match out.iter_mut().find(|(w, _)| *w == v) {
            Some((_, k)) => *k += m,
            None => out.push((v, m)),
        }
    }
    out
}

/// Eigenvalues of `a` as roots with algebraic multiplicities, sorted as polynomial roots.
fn roots_of_matrix(a: &DMatrix<f64>) -> Result<Vec<Root>> {
    if a.nrows() == 0 {
        return Ok(Vec::new());
    }
    Ok(roots_of_structure(&eigen_structure(a)?, a.nrows()))
}

/// The clusters of an eigen structure as roots: an eigenvalue within its cluster radius of 0
/// is 0 for a matrix within ε‖A‖ of A (an integrator, the free translation of a lattice), as a
/// root of a polynomial with a zero constant coefficient is; likewise a real part within the
/// radius is 0 (the undamped lattice's ±jωₖ come out with real parts of ~1e-16 otherwise).
fn roots_of_structure(st: &EigenStructure, n: usize) -> Vec<Root> {
    let pairs: Vec<(Complex64, usize)> = snapped_values(st, n)
        .into_iter()
        .zip(&st.clusters)
        .map(|(v, c)| (v, c.algebraic))
        .collect();
    conjugate_closed(&pairs)
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
