//! A SISO channel of a second-order model (see [`crate::numeric::linalg::second_order`])
//! reduced in modal coordinates, and its zeros — through the modal variable w under Rayleigh
//! damping, else from the model's own pencil. Used by [`super::ss_source`], which falls back to
//! the general path whenever a function here returns `None`.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::pole_zero::merge;
use crate::lti::StateSpace;
use crate::numeric::linalg::second_order::{self, SecondOrder};
use crate::numeric::linalg::structure::{radius, snap};
use crate::numeric::linalg::{MinimalRealization, relative_degree, transmission_zeros};

/// The minimal realisation of a SISO channel of a second-order model whose input acts on the
/// velocities only (B's position rows zero), built in modal coordinates: modes with the same
/// stiffness and damping share one 2×2 block [[0, 1], [−λ, −γ]] with input (0, ‖β‖) and output
/// Σ uₖ·(c_q,k, c_v,k)·‖β‖ (u = β/‖β‖, β the modes' inputs) — the other directions of the group
/// are uncontrollable — and a root μ with c_q + μ·c_v = 0 is unobservable (the block shrinks
/// to the other root, or vanishes). Returns the realisation, the positions (2k + i: root i of
/// mode k) of the kept roots, and those of the removed ones; `None` when B moves positions.
pub(super) fn second_order_minimal(ss: &StateSpace, so: &SecondOrder) -> Option<ModalReduction> {
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
pub(super) struct ModalReduction {
    pub minimal: MinimalRealization,
    /// Positions (2k + i: root i of mode k) of the roots kept …
    pub kept: Vec<usize>,
    /// … and of those removed.
    pub removed: Vec<usize>,
    /// Kept groups with both roots (2×2 blocks) and with one (1×1 blocks).
    pairs: usize,
    singles: usize,
}

/// Zeros (with multiplicities), relative degree and gain of a channel computed in advance.
pub(super) struct KnownZeros {
    pub zeros: Vec<(Complex64, usize)>,
    pub r: usize,
    pub gain: f64,
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
pub(super) fn rayleigh_zeros(
    ss: &StateSpace,
    so: &SecondOrder,
    red: &ModalReduction,
) -> Option<KnownZeros> {
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
    let scale = crate::numeric::linalg::norms::norm_1_inf(&a_w);
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
pub(super) fn model_zeros(ss: &StateSpace, red: &ModalReduction) -> Option<KnownZeros> {
    let rd = relative_degree(&ss.a, &ss.b, &ss.c, &ss.d, None).ok()?;
    let r = rd.r?;
    let tz = transmission_zeros(&ss.a, &ss.b, &ss.c, &ss.d, None).ok()?;
    let p: usize = tz.distinct.iter().map(|z| z.1).sum();
    if p + r != red.minimal.order() {
        return None;
    }
    let scale = crate::numeric::linalg::norms::norm_1_inf(&ss.a);
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
