//! Step 5, second stage: the multiplicity structure from the derivatives (an m-fold root of p
//! is a simple root of p^(m−1)), for overlapping clusters and very high multiplicities.

use num_complex::Complex64;

use super::candidates::candidates;
use super::found::{Found, GROUP_REL};
use super::group::{group_weight, link_groups};
use super::newton::{confirm_complex, confirm_real};
use super::refine::factor_of;
use crate::poly::Poly;

/// The derivative stage's work bound, in full-degree eigenvalue problems (see
/// [`structure_from_derivatives`]).
pub(super) const DERIVATIVE_WORK: f64 = 6.0;

/// Second stage for overlapping clusters. An m-fold root of q is a simple — and usually well
/// conditioned — root of q^(m−1). For m from `max_mult` down to 2, the roots of q^(m−1) at
/// which q, …, q^(m−2) vanish to rounding level are claimed as m-fold roots; the claimed factors
/// are divided out and the quotient's roots are the simple ones. The caller refines the whole
/// structure by Gauss–Newton and checks the reconstruction.
pub(super) fn structure_from_derivatives(q: &Poly, max_mult: usize) -> Option<Vec<Found>> {
    let n = q.degree();
    let mut claimed: Vec<Found> = Vec::new();
    let mut weight = 0;
    // Work bound: each m costs an eigenvalue problem of degree n − m + 1 (~10·deg³ flops) and
    // the candidates' confirmation. A random polynomial of degree ~170 has its roots near a
    // circle, 2π/n apart: the grouping links them all, max_mult ≈ n, and trying every m cost
    // ~140 eigenvalue problems (0.6 s). The search stops after DERIVATIVE_WORK·n³ (as many
    // full-degree problems) — the multiplicities below that m are not looked for, and the
    // caller's checks decide between the claimed structure and simple roots (a multiplicity
    // may be missed, never invented).
    let budget = DERIVATIVE_WORK * (n as f64).powi(3);
    let mut work = 0.0;
    for m in (2..=max_mult.min(n)).rev() {
        if weight >= n {
            break;
        }
        let d = q.nth_derivative(m - 1);
        if d.degree() == 0 {
            continue;
        }
        work += (d.degree() as f64).powi(3);
        if work > budget {
            break;
        }
        for z in candidates(&d).ok()? {
            if z.im < 0.0 {
                continue;
            }
            let reach = GROUP_REL * z.norm().max(f64::MIN_POSITIVE);
            if claimed
                .iter()
                .any(|f| (f.value - z).norm() <= reach || (f.value.conj() - z).norm() <= reach)
            {
                continue;
            }
            let w = if z.im == 0.0 { m } else { 2 * m };
            if weight + w > n {
                continue;
            }
            // A root of q^(m−1) close to the real axis may be a real multiple root.
            let as_real = confirm_real(q, z.re, m, reach).map(|x| Complex64::new(x, 0.0));
            let found = if z.im == 0.0 || (as_real.is_some() && z.im <= reach) {
                as_real
            } else {
                confirm_complex(q, z, m, reach)
            };
            if let Some(c) = found {
                let w = if c.im == 0.0 { m } else { 2 * m };
                if weight + w <= n {
                    claimed.push(Found {
                        value: c,
                        multiplicity: m,
                    });
                    weight += w;
                }
            }
        }
    }
    if claimed.is_empty() {
        return None;
    }
    // The simple roots: those of q divided by the claimed factors.
    let mut divisor = Poly::constant(1.0);
    for f in &claimed {
        let fac = factor_of(f.value);
        for _ in 0..f.multiplicity {
            divisor = &divisor * &fac;
        }
    }
    let (quot, _) = q.div_rem(&divisor).ok()?;
    if quot.degree() + divisor.degree() != n {
        return None;
    }
    if quot.degree() > 0 {
        for z in candidates(&quot).ok()? {
            if z.im >= 0.0 {
                claimed.push(Found {
                    value: z,
                    multiplicity: 1,
                });
            }
        }
    }
    Some(claimed)
}

/// Relative distance for the coarse groups examined by [`hidden_multiple_root`]: an m-fold
/// root scatters by ~eps^(1/m), 0.16 for m = 20.
pub(super) const COARSE_GROUP_REL: f64 = 0.5;

/// A multiplicity the first stage missed because the scatter of a very high multiplicity
/// (m ≳ 20) exceeds the grouping distance: for each coarse group resolved into roots of lower
/// multiplicity, test its (real) mean as a root of the group's total multiplicity W. Returns
/// the largest such W.
pub(super) fn hidden_multiple_root(
    q: &Poly,
    upper: &[Complex64],
    found: &[Found],
) -> Option<usize> {
    let mut best = None;
    for g in link_groups(upper, COARSE_GROUP_REL) {
        let w = group_weight(&g);
        if w < 3 || found.iter().any(|f| f.multiplicity >= w) {
            continue;
        }
        let mean = g.iter().sum::<Complex64>() / g.len() as f64;
        let reach = COARSE_GROUP_REL * mean.norm().max(f64::MIN_POSITIVE);
        let real_mean = g
            .iter()
            .map(|z| if z.im == 0.0 { z.re } else { 2.0 * z.re })
            .sum::<f64>()
            / w as f64;
        if confirm_real(q, real_mean, w, reach).is_some() {
            best = best.max(Some(w));
        }
    }
    best
}
