//! Roots of a real polynomial with exact multiplicities.
//!
//! # Method
//! 1. Exact zero roots (trailing zero coefficients) are deflated exactly.
//! 2. Candidates: degree 1 and 2 by stable closed forms; otherwise the eigenvalues of the
//!    balanced companion matrix (Francis double-shift QR directly on the Hessenberg companion
//!    matrix, capped, with [`crate::numeric::eigenvalues`] as the fallback). Simple roots come out to
//!    ~eps, but an m-fold root scatters by ~eps^(1/m) (numpy gives (s+1)⁴ as −1 ± 2e-4).
//! 3. Clustering on the closed upper half plane (each upper candidate stands for a conjugate
//!    pair): candidates closer than a generous relative distance form a group; a group is
//!    *accepted* as one root of multiplicity m when Newton's method on p^(m−1) (where an m-fold
//!    root is simple) from the group mean converges to a point c at which p, p′, …, p^(m−2)
//!    vanish to rounding level (|p^(j)(c)| ≤ γ·eps·Σ|aᵢ^(j)||c|ⁱ): i.e. a polynomial within
//!    rounding of p has an exact m-fold root at c. A group that is not accepted is split at the
//!    longest edge of its minimum spanning tree and each part is tried again. Groups that touch
//!    the real axis are tried as a real root first (multiplicity = #real + 2·#upper).
//! 4. Simple roots get a guarded Newton polish on p (accepted only while |p| decreases and the
//!    step stays inside the root's neighbourhood).
//! 5. The result must reproduce the coefficients (lead·Π(s − rₖ)^mₖ against p, componentwise
//!    to a small multiple of eps); if it does not, the polished candidates are returned as
//!    simple roots — no multiplicity is ever claimed that the coefficients do not support.
//!
//! Two simple roots closer than about 2e-7 relative are indistinguishable from a double root
//! perturbed by rounding of the coefficients and are reported as one double root; roots
//! 5e-4 apart (which scipy's `residue` merges) stay distinct.

use num_complex::Complex64;

mod companion;

use super::{MAX_ORDER, Poly, Root};
use crate::error::{LtiError, Result};
use crate::numeric::dd::{self, Dd, two_prod};
use crate::numeric::tol::EPS;

/// Generous relative distance under which candidates are grouped for the multiplicity test.
/// The scatter of an m-fold root is ~eps^(1/m) relative: 2.5e-3 for m = 6, 0.03 for m = 10.
const GROUP_REL: f64 = 0.1;

/// Factor on the predicted scatter radius within which every member of a group must lie for the
/// group to be accepted as one multiple root.
const SCATTER_FACTOR: f64 = 100.0;

/// γ in the acceptance test |p^(j)(c)| ≤ γ·(deg + 1)·eps·Σ|aᵢ^(j)||c|ⁱ.
const GAMMA: f64 = 8.0;

/// Componentwise relative tolerance of the final reconstruction test. It only has to catch a
/// lost or duplicated root (an error of the order of a root separation); accurate multiple
/// roots of a polynomial with rounded coefficients reconstruct to ~1e-11.
const RECONSTRUCT_TOL: f64 = 1e-9;

/// Roots of `p` with exact multiplicities, sorted by decreasing real part, then decreasing
/// imaginary part (a conjugate pair appears as +, −). Complex roots come in exact conjugate
/// pairs; real roots have an imaginary part of exactly 0.
///
/// Errors: the zero polynomial, degree above [`MAX_ORDER`], coefficients whose ratio overflows.
///
/// ```
/// use ltikit::Poly;
/// // (s + 1)^6 — numpy scatters it by 1e-3; here it is one root of multiplicity 6.
/// let p = Poly::from_descending(&[1.0, 6.0, 15.0, 20.0, 15.0, 6.0, 1.0]).unwrap();
/// let r = p.roots().unwrap();
/// assert_eq!(r.len(), 1);
/// assert_eq!(r[0].multiplicity, 6);
/// assert!((r[0].value.re + 1.0).abs() < 1e-13 && r[0].value.im == 0.0);
/// ```
pub fn roots(p: &Poly) -> Result<Vec<Root>> {
    if p.is_zero() {
        return Err(LtiError::ZeroPolynomial {
            what: "polynomial".into(),
        });
    }
    let n = p.degree();
    if n > MAX_ORDER {
        return Err(LtiError::OrderTooHigh {
            order: n,
            max: MAX_ORDER,
        });
    }
    let mut out = Vec::new();
    if n == 0 {
        return Ok(out);
    }
    let k0 = p.zero_root_multiplicity();
    if k0 > 0 {
        out.push(Root {
            value: Complex64::new(0.0, 0.0),
            multiplicity: k0,
        });
    }
    let q = Poly::trimmed(p.coeffs()[..=n - k0].to_vec());
    if q.degree() > 0 {
        let candidates = candidates(&q)?;
        out.extend(resolve_multiplicities(&q, &candidates));
    }
    sort_roots(&mut out);
    Ok(out)
}

/// Roots listed with repetition (a double root appears twice), in the order of [`roots`].
pub fn flatten(roots: &[Root]) -> Vec<Complex64> {
    roots
        .iter()
        .flat_map(|r| std::iter::repeat_n(r.value, r.multiplicity))
        .collect()
}

/// Sorts by decreasing real part, then decreasing imaginary part.
pub fn sort_roots(r: &mut [Root]) {
    r.sort_by(|a, b| {
        b.value
            .re
            .total_cmp(&a.value.re)
            .then(b.value.im.total_cmp(&a.value.im))
    });
}

/// Candidate roots (with repetition): closed forms for degree ≤ 2, companion eigenvalues above.
pub(crate) fn candidates(q: &Poly) -> Result<Vec<Complex64>> {
    let c = q.coeffs();
    let n = q.degree();
    match n {
        1 => Ok(vec![Complex64::new(-c[1] / c[0], 0.0)]),
        2 => Ok(quadratic(c[0], c[1], c[2])),
        _ => {
            let lead = c[0];
            let mut tail = Vec::with_capacity(n);
            for &cj in &c[1..] {
                let v = cj / lead;
                if !v.is_finite() {
                    return Err(LtiError::BadScaling {
                        what: "polynomial".into(),
                        ratio: -v,
                        leading: lead,
                    });
                }
                tail.push(v);
            }
            if let Some(ev) = companion::companion_eigenvalues(&tail) {
                return Ok(ev);
            }
            // The capped double-shift iteration did not converge: the general solver (with
            // its own cap and a retry after a similarity transformation).
            let mut a = nalgebra::DMatrix::<f64>::zeros(n, n);
            for (j, &v) in tail.iter().enumerate() {
                a[(0, j)] = -v;
            }
            for i in 1..n {
                a[(i, i - 1)] = 1.0;
            }
            crate::numeric::eigenvalues_checked(a)
        }
    }
}

/// Roots of a s² + b s + c without cancellation (a ≠ 0, c ≠ 0).
fn quadratic(a: f64, b: f64, c: f64) -> Vec<Complex64> {
    // Scale to avoid overflow in b² and 4ac.
    let s = a.abs().max(b.abs()).max(c.abs());
    let (a, b, c) = (a / s, b / s, c / s);
    let disc = b.mul_add(b, -4.0 * a * c);
    if disc >= 0.0 {
        let sq = disc.sqrt();
        let qq = -0.5 * (b + sq.copysign(b));
        if qq == 0.0 {
            return vec![Complex64::new(0.0, 0.0); 2];
        }
        vec![Complex64::new(qq / a, 0.0), Complex64::new(c / qq, 0.0)]
    } else {
        let re = -b / (2.0 * a);
        let im = (-disc).sqrt() / (2.0 * a.abs());
        vec![Complex64::new(re, im), Complex64::new(re, -im)]
    }
}

/// Groups the candidates and returns roots with multiplicities (or, if the grouped result fails
/// the reconstruction test, the polished candidates as simple roots).
fn resolve_multiplicities(q: &Poly, cand: &[Complex64]) -> Vec<Root> {
    let upper: Vec<Complex64> = cand.iter().copied().filter(|z| z.im >= 0.0).collect();
    let mut found = Vec::new();
    let groups = link_groups(&upper, GROUP_REL);
    let all_isolated = groups.iter().all(|g| g.len() == 1);
    for group in groups {
        resolve_group(q, &group, &upper, &mut found);
    }
    let found = if found.iter().any(|f| f.multiplicity > 1) {
        refine_structured(q, &found).unwrap_or(found)
    } else {
        found
    };
    let roots = expand_conjugates(&found);
    if all_isolated && found.iter().all(|f| f.multiplicity == 1) && reconstructs(q, &roots) {
        // Generic case, fast exit: every candidate is more than GROUP_REL (relative) from
        // every other, so no two candidates are the scatter of one multiple root (an m-fold
        // root scatters by ~eps^(1/m) relative, its neighbouring candidates ~2π·eps^(1/m)/m
        // apart: < 0.06 even for m = 24), and the checks for split or hidden multiple roots
        // (which cost as much again as everything above) are skipped.
        return roots;
    }
    let hidden = hidden_multiple_root(q, &upper, &found);
    if reconstructs(q, &roots) && !any_more_multiple(q, &found) && hidden.is_none() {
        return roots;
    }
    // Clusters overlapped (high multiplicities close together scatter into each other), or a
    // very high multiplicity scattered beyond the grouping distance: find the structure from
    // the derivatives instead.
    let max_weight = link_groups(&upper, GROUP_REL)
        .iter()
        .map(|g| group_weight(g))
        .max()
        .unwrap_or(1)
        .max(hidden.unwrap_or(1));
    if let Some(found) = structure_from_derivatives(q, max_weight) {
        let found = refine_structured(q, &found).unwrap_or(found);
        let roots = expand_conjugates(&found);
        if reconstructs(q, &roots) && !any_more_multiple(q, &found) {
            return roots;
        }
    }
    simple_roots(q, cand)
}

/// True when some found root of multiplicity m is also accepted as an (m+1)-fold root: the
/// grouping then split one multiple root between groups (overlapping clusters), and the
/// structure must come from the derivatives.
fn any_more_multiple(q: &Poly, found: &[Found]) -> bool {
    found.iter().any(|f| {
        let m = f.multiplicity + 1;
        if m > q.degree() {
            return false;
        }
        let reach = GROUP_REL * f.value.norm().max(f64::MIN_POSITIVE);
        if f.value.im == 0.0 {
            confirm_real(q, f.value.re, m, reach).is_some()
        } else {
            confirm_complex(q, f.value, m, reach).is_some()
        }
    })
}

/// Second stage for overlapping clusters. An m-fold root of q is a simple — and usually well
/// conditioned — root of q^(m−1). For m from `max_mult` down to 2, the roots of q^(m−1) at
/// which q, …, q^(m−2) vanish to rounding level are claimed as m-fold roots; the claimed factors
/// are divided out and the quotient's roots are the simple ones. The caller refines the whole
/// structure by Gauss–Newton and checks the reconstruction.
fn structure_from_derivatives(q: &Poly, max_mult: usize) -> Option<Vec<Found>> {
    let n = q.degree();
    let mut claimed: Vec<Found> = Vec::new();
    let mut weight = 0;
    for m in (2..=max_mult.min(n)).rev() {
        let d = q.nth_derivative(m - 1);
        if d.degree() == 0 {
            continue;
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

/// A root found in the closed upper half plane; a non-real one stands for a conjugate pair.
#[derive(Debug, Clone, Copy)]
struct Found {
    value: Complex64,
    multiplicity: usize,
}

fn expand_conjugates(found: &[Found]) -> Vec<Root> {
    let mut out = Vec::new();
    for f in found {
        out.push(Root {
            value: f.value,
            multiplicity: f.multiplicity,
        });
        if f.value.im != 0.0 {
            out.push(Root {
                value: f.value.conj(),
                multiplicity: f.multiplicity,
            });
        }
    }
    out
}

/// Gauss–Newton refinement of all roots jointly with the multiplicity structure held fixed
/// (Zeng's "pejorative manifold"): find real parameters θ (one per real root, (a, b) per pair
/// a ± bj) minimising the weighted distance between the monic coefficients of
/// Π(s − rₖ)^mₖ and those of q. A multiple root computed from p^(m−1) alone is only as accurate
/// as that derivative is well conditioned (2e-6 for a double root next to a triple one); the
/// structured problem is well conditioned and converges to ~eps. Returns None (keep the
/// unrefined roots) if the residual does not decrease.
fn refine_structured(q: &Poly, found: &[Found]) -> Option<Vec<Found>> {
    let n = q.degree();
    let lead = q.leading();
    // Weights: coefficient-wise scale of Π(s + |rₖ|)^mₖ, a natural size for each coefficient.
    let abs_roots: Vec<Root> = found
        .iter()
        .flat_map(|f| {
            let r = Root {
                value: Complex64::new(-f.value.norm(), 0.0),
                multiplicity: f.multiplicity,
            };
            if f.value.im == 0.0 {
                vec![r]
            } else {
                vec![r, r]
            }
        })
        .collect();
    let scale = Poly::from_root_list(&abs_roots).ok()?;
    let w: Vec<f64> = scale.coeffs()[1..]
        .iter()
        .map(|s| 1.0 / s.max(f64::MIN_POSITIVE))
        .collect();

    let mut cur: Vec<Found> = found.to_vec();
    // The residual is formed in double-double: iterative refinement converges to the structured
    // solution only as far as the residual is accurate.
    let residual = |roots: &[Found]| -> Option<(Vec<f64>, f64)> {
        let p = structured_poly_dd(roots);
        if p.len() != n + 1 {
            return None;
        }
        let r: Vec<f64> = p[1..]
            .iter()
            .zip(q.coeffs()[1..].iter())
            .zip(&w)
            .map(|((a, &t), wi)| {
                // a − t/lead, with t/lead formed exactly enough in double-double.
                let quot = t / lead;
                let (pr, pe) = two_prod(quot, lead);
                let corr = ((t - pr) - pe) / lead;
                let tq = Dd { hi: quot, lo: 0.0 } + Dd::from(corr);
                (*a - tq).to_f64() * wi
            })
            .collect();
        let norm = r.iter().map(|x| x * x).sum::<f64>().sqrt();
        norm.is_finite().then_some((r, norm))
    };
    let (mut r, mut norm) = residual(&cur)?;
    let start = norm;
    for _ in 0..20 {
        if norm == 0.0 {
            break;
        }
        let jac = structured_jacobian(&cur, n, &w);
        let rhs = nalgebra::DVector::from_iterator(n, r.iter().map(|x| -x));
        let svd = jac.svd(true, true);
        let delta = svd.solve(&rhs, f64::EPSILON).ok()?;
        let mut next = cur.clone();
        let mut k = 0;
        for f in next.iter_mut() {
            if f.value.im == 0.0 {
                f.value.re += delta[k];
                k += 1;
            } else {
                f.value.re += delta[k];
                f.value.im += delta[k + 1];
                k += 2;
            }
        }
        if next.iter().any(|f| f.value.im < 0.0) {
            break;
        }
        let Some((rn, nn)) = residual(&next) else {
            break;
        };
        let improved = nn < norm;
        if !improved {
            break;
        }
        let size = cur.iter().map(|f| f.value.norm()).fold(0.0, f64::max);
        let step = delta.norm();
        cur = next;
        r = rn;
        norm = nn;
        if step <= 4.0 * EPS * size {
            break;
        }
    }
    (norm < start || start == 0.0).then_some(cur)
}

/// Monic Π over the found roots (real factors, pairs as quadratics) raised to multiplicities,
/// in double-double, descending.
fn structured_poly_dd(found: &[Found]) -> Vec<Dd> {
    let mut p = vec![Dd::from(1.0)];
    for f in found {
        let z = f.value;
        let factor = if z.im == 0.0 {
            vec![Dd::from(1.0), Dd::from(-z.re)]
        } else {
            let (a2, ea) = two_prod(z.re, z.re);
            let (b2, eb) = two_prod(z.im, z.im);
            let norm2 = Dd { hi: a2, lo: ea } + Dd { hi: b2, lo: eb };
            vec![Dd::from(1.0), Dd::from(-2.0 * z.re), norm2]
        };
        for _ in 0..f.multiplicity {
            p = dd::poly_mul(&p, &factor);
        }
    }
    p
}

fn factor_of(z: Complex64) -> Poly {
    if z.im == 0.0 {
        Poly {
            c: vec![1.0, -z.re],
        }
    } else {
        Poly::quadratic_factor(z)
    }
}

/// Weighted Jacobian (n × #parameters) of the monic coefficients (without the leading 1)
/// with respect to the real parameters of each root.
fn structured_jacobian(found: &[Found], n: usize, w: &[f64]) -> nalgebra::DMatrix<f64> {
    let params: usize = found
        .iter()
        .map(|f| if f.value.im == 0.0 { 1 } else { 2 })
        .sum();
    let mut jac = nalgebra::DMatrix::<f64>::zeros(n, params);
    let mut col = 0;
    for (k, f) in found.iter().enumerate() {
        let mut rest = Poly::constant(1.0);
        for (j, g) in found.iter().enumerate() {
            if j != k {
                let fac = factor_of(g.value);
                for _ in 0..g.multiplicity {
                    rest = &rest * &fac;
                }
            }
        }
        let fac = factor_of(f.value);
        for _ in 0..f.multiplicity - 1 {
            rest = &rest * &fac;
        }
        let m = f.multiplicity as f64;
        let z = f.value;
        // d/dθ of factor^m = m·factor^(m−1)·d(factor)/dθ
        let dfactors: Vec<Poly> = if z.im == 0.0 {
            vec![Poly::constant(-m)]
        } else {
            vec![
                Poly {
                    c: vec![-2.0 * m, 2.0 * m * z.re],
                },
                Poly::constant(2.0 * m * z.im),
            ]
        };
        for d in dfactors {
            let col_poly = &rest * &d;
            // Align: col_poly has degree ≤ n − 1; place into rows for s^(n−1) … s^0.
            let deg = col_poly.degree();
            for (i, &c) in col_poly.coeffs().iter().enumerate() {
                let power = deg - i;
                if power < n {
                    let row = n - 1 - power;
                    jac[(row, col)] = c * w[row];
                }
            }
            col += 1;
        }
    }
    jac
}

/// Full-plane root count a group of upper-half-plane candidates stands for.
fn group_weight(g: &[Complex64]) -> usize {
    g.iter().map(|z| if z.im == 0.0 { 1 } else { 2 }).sum()
}

/// Relative distance for the coarse groups examined by [`hidden_multiple_root`]: an m-fold
/// root scatters by ~eps^(1/m), 0.16 for m = 20.
const COARSE_GROUP_REL: f64 = 0.5;

/// A multiplicity the first stage missed because the scatter of a very high multiplicity
/// (m ≳ 20) exceeds the grouping distance: for each coarse group resolved into roots of lower
/// multiplicity, test its (real) mean as a root of the group's total multiplicity W. Returns
/// the largest such W.
fn hidden_multiple_root(q: &Poly, upper: &[Complex64], found: &[Found]) -> Option<usize> {
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

/// Connected components of the "closer than `rel` relative" graph.
fn link_groups(pts: &[Complex64], rel: f64) -> Vec<Vec<Complex64>> {
    let n = pts.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for i in 0..n {
        for j in i + 1..n {
            let d = (pts[i] - pts[j]).norm();
            if d <= rel * pts[i].norm().max(pts[j].norm()) {
                let (a, b) = (find(&mut parent, i), find(&mut parent, j));
                parent[a] = b;
            }
        }
    }
    let mut groups: Vec<Vec<Complex64>> = Vec::new();
    let mut root_of: Vec<Option<usize>> = vec![None; n];
    for (i, &pt) in pts.iter().enumerate() {
        let r = find(&mut parent, i);
        match root_of[r] {
            Some(g) => groups[g].push(pt),
            None => {
                root_of[r] = Some(groups.len());
                groups.push(vec![pt]);
            }
        }
    }
    groups
}

/// Accepts `group` as one root or splits it at the longest minimum-spanning-tree edge.
fn resolve_group(q: &Poly, group: &[Complex64], all: &[Complex64], out: &mut Vec<Found>) {
    if let Some(f) = accept(q, group, all) {
        out.push(f);
        return;
    }
    let (a, b) = split_longest_edge(group);
    resolve_group(q, &a, all, out);
    resolve_group(q, &b, all, out);
}

/// Tries to accept `group` (points in the closed upper half plane) as a single root.
/// Singletons are always accepted (as a simple root, or as a real double root if the point is
/// one half of a conjugate pair that splits a double real root).
fn accept(q: &Poly, group: &[Complex64], all: &[Complex64]) -> Option<Found> {
    let n_real = group.iter().filter(|z| z.im == 0.0).count();
    let n_up = group.len() - n_real;
    let mean = group.iter().sum::<Complex64>() / group.len() as f64;
    let max_im = group.iter().map(|z| z.im).fold(0.0, f64::max);
    let spread = group.iter().map(|z| (z - mean).norm()).fold(0.0, f64::max);
    // Neighbourhood used to guard Newton steps: never move farther than half the distance to
    // the nearest candidate outside the group (or a relative GROUP_REL if there is none).
    let outside = all
        .iter()
        .filter(|z| !group.contains(z))
        .flat_map(|z| [*z, z.conj()])
        .map(|z| (z - mean).norm())
        .fold(f64::INFINITY, f64::min);
    let reach = (0.5 * outside).min(GROUP_REL * mean.norm().max(f64::MIN_POSITIVE));
    let reach = reach.max(4.0 * spread);

    let near_axis = n_real > 0 || max_im <= GROUP_REL * mean.norm();
    if near_axis {
        let m = n_real + 2 * n_up;
        let center = (group
            .iter()
            .map(|z| if z.im == 0.0 { z.re } else { 2.0 * z.re })
            .sum::<f64>())
            / m as f64;
        if m == 1 {
            return Some(Found {
                value: Complex64::new(polish_real(q, center, reach), 0.0),
                multiplicity: 1,
            });
        }
        if let Some(c) = confirm_real(q, center, m, reach)
            && members_within_scatter(q, group, Complex64::new(c, 0.0), m)
        {
            return Some(Found {
                value: Complex64::new(c, 0.0),
                multiplicity: m,
            });
        }
        if n_real > 0 {
            return None;
        }
    }
    let m = n_up;
    if m == 1 {
        let z = polish_complex(q, mean, reach.min(0.5 * mean.im.abs()));
        return Some(Found {
            value: if z.im > 0.0 { z } else { mean },
            multiplicity: 1,
        });
    }
    confirm_complex(q, mean, m, reach)
        .filter(|&c| members_within_scatter(q, group, c, m))
        .map(|c| Found {
            value: c,
            multiplicity: m,
        })
}

/// True when every member of the group lies within SCATTER_FACTOR times the radius by which
/// rounding-level coefficient perturbations scatter an m-fold root at c:
/// ρ = (γ·eps·Σ|aᵢ||c|ⁱ · m! / |p^(m)(c)|)^(1/m). This keeps a distinct neighbour (a simple
/// pair at −10 ± j next to a double root at −10) from being absorbed into the multiple root.
fn members_within_scatter(q: &Poly, group: &[Complex64], c: Complex64, m: usize) -> bool {
    let dm = q.nth_derivative(m).eval_complex(c).norm();
    let factorial: f64 = (1..=m).map(|k| k as f64).product();
    let pert = bound(q, c.norm()) * factorial;
    let rho = if dm > 0.0 {
        (pert / dm).powf(1.0 / m as f64)
    } else {
        f64::INFINITY
    };
    let radius = SCATTER_FACTOR * rho;
    group.iter().all(|z| {
        let d = (z - c).norm().min((z.conj() - c).norm());
        d <= radius
    })
}

/// Acceptance bound for |p^(j)(c)|.
fn bound(d: &Poly, r: f64) -> f64 {
    GAMMA * (d.degree() + 1) as f64 * EPS * d.eval_abs(r)
}

fn confirm_real(q: &Poly, x0: f64, m: usize, reach: f64) -> Option<f64> {
    let dm = q.nth_derivative(m - 1);
    let x = newton_real(&dm, x0, reach)?;
    let mut d = q.clone();
    for _ in 0..m - 1 {
        if d.eval(x).abs() > bound(&d, x.abs()) {
            return None;
        }
        d = d.derivative();
    }
    Some(x)
}

fn confirm_complex(q: &Poly, z0: Complex64, m: usize, reach: f64) -> Option<Complex64> {
    let dm = q.nth_derivative(m - 1);
    let z = newton_complex(&dm, z0, reach)?;
    if z.im <= 0.0 {
        return None;
    }
    let mut d = q.clone();
    for _ in 0..m - 1 {
        if d.eval_complex(z).norm() > bound(&d, z.norm()) {
            return None;
        }
        d = d.derivative();
    }
    Some(z)
}

/// Newton on a polynomial expected to have a simple root near x0; None if it leaves the
/// neighbourhood or does not settle.
fn newton_real(p: &Poly, x0: f64, reach: f64) -> Option<f64> {
    let dp = p.derivative();
    let mut x = x0;
    for _ in 0..50 {
        let f = p.eval(x);
        if f == 0.0 {
            return Some(x);
        }
        let d = dp.eval(x);
        if d == 0.0 || !d.is_finite() {
            return None;
        }
        let step = f / d;
        x -= step;
        if !x.is_finite() || (x - x0).abs() > reach {
            return None;
        }
        if step.abs() <= 4.0 * EPS * x.abs() {
            return Some(x);
        }
    }
    // Converged to rounding noise without meeting the step test: accept if tiny.
    Some(x)
}

fn newton_complex(p: &Poly, z0: Complex64, reach: f64) -> Option<Complex64> {
    let dp = p.derivative();
    let mut z = z0;
    for _ in 0..50 {
        let f = p.eval_complex(z);
        if f.norm() == 0.0 {
            return Some(z);
        }
        let d = dp.eval_complex(z);
        if d.norm() == 0.0 || !d.norm().is_finite() {
            return None;
        }
        let step = f / d;
        z -= step;
        if !z.norm().is_finite() || (z - z0).norm() > reach {
            return None;
        }
        if step.norm() <= 4.0 * EPS * z.norm() {
            return Some(z);
        }
    }
    Some(z)
}

/// Guarded Newton polish of a simple real root: steps are taken only while |p| decreases and
/// the iterate stays within `reach` of the start.
fn polish_real(p: &Poly, x0: f64, reach: f64) -> f64 {
    let dp = p.derivative();
    let mut x = x0;
    let mut fx = p.eval(x).abs();
    for _ in 0..20 {
        if fx == 0.0 {
            break;
        }
        let d = dp.eval(x);
        if d == 0.0 {
            break;
        }
        let xn = x - p.eval(x) / d;
        let fn_ = p.eval(xn).abs();
        let improved = fn_ < fx;
        if !improved || (xn - x0).abs() > reach || !xn.is_finite() {
            break;
        }
        let done = (xn - x).abs() <= 2.0 * EPS * xn.abs();
        x = xn;
        fx = fn_;
        if done {
            break;
        }
    }
    x
}

fn polish_complex(p: &Poly, z0: Complex64, reach: f64) -> Complex64 {
    let dp = p.derivative();
    let mut z = z0;
    let mut fz = p.eval_complex(z).norm();
    for _ in 0..20 {
        if fz == 0.0 {
            break;
        }
        let d = dp.eval_complex(z);
        if d.norm() == 0.0 {
            break;
        }
        let zn = z - p.eval_complex(z) / d;
        let fn_ = p.eval_complex(zn).norm();
        let improved = fn_ < fz;
        if !improved || (zn - z0).norm() > reach || !zn.norm().is_finite() {
            break;
        }
        let done = (zn - z).norm() <= 2.0 * EPS * zn.norm();
        z = zn;
        fz = fn_;
        if done {
            break;
        }
    }
    z
}

/// Splits a group (≥ 2 points) in two at the longest edge of its minimum spanning tree.
fn split_longest_edge(g: &[Complex64]) -> (Vec<Complex64>, Vec<Complex64>) {
    let n = g.len();
    // Prim's algorithm.
    let mut in_tree = vec![false; n];
    let mut best = vec![f64::INFINITY; n];
    let mut link = vec![0usize; n];
    let mut edges: Vec<(usize, usize, f64)> = Vec::with_capacity(n - 1);
    in_tree[0] = true;
    for j in 1..n {
        best[j] = (g[j] - g[0]).norm();
    }
    for _ in 1..n {
        let (k, _) = best
            .iter()
            .enumerate()
            .filter(|(i, _)| !in_tree[*i])
            .min_by(|a, b| a.1.total_cmp(b.1))
            .expect("a vertex outside the tree remains"); // ok: loop runs n-1 times
        in_tree[k] = true;
        edges.push((link[k], k, best[k]));
        for j in 0..n {
            if !in_tree[j] {
                let d = (g[j] - g[k]).norm();
                if d < best[j] {
                    best[j] = d;
                    link[j] = k;
                }
            }
        }
    }
    let (cut, _) = edges
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.2.total_cmp(&b.1.2))
        .expect("a group of two or more points has an edge"); // ok: n >= 2
    // Components of the tree without the cut edge.
    let mut adj = vec![Vec::new(); n];
    for (i, &(a, b, _)) in edges.iter().enumerate() {
        if i != cut {
            adj[a].push(b);
            adj[b].push(a);
        }
    }
    let mut side = vec![false; n];
    let mut stack = vec![edges[cut].0];
    side[edges[cut].0] = true;
    while let Some(v) = stack.pop() {
        for &w in &adj[v] {
            if !side[w] {
                side[w] = true;
                stack.push(w);
            }
        }
    }
    let a = (0..n).filter(|&i| side[i]).map(|i| g[i]).collect();
    let b = (0..n).filter(|&i| !side[i]).map(|i| g[i]).collect();
    (a, b)
}

/// True when lead·Π(s − rₖ)^mₖ reproduces q coefficient by coefficient to rounding level.
fn reconstructs(q: &Poly, roots: &[Root]) -> bool {
    let total: usize = roots.iter().map(|r| r.multiplicity).sum();
    if total != q.degree() {
        return false;
    }
    let Ok(monic) = Poly::from_root_list(roots) else {
        return false;
    };
    let abs_roots: Vec<Complex64> = roots
        .iter()
        .flat_map(|r| std::iter::repeat_n(Complex64::new(-r.value.norm(), 0.0), r.multiplicity))
        .collect();
    let Ok(scale) = Poly::from_roots(&abs_roots) else {
        return false;
    };
    let lead = q.leading();
    let tol = RECONSTRUCT_TOL;
    q.coeffs()
        .iter()
        .zip(monic.coeffs())
        .zip(scale.coeffs())
        .all(|((&a, &b), &s)| (a - lead * b).abs() <= tol * (lead.abs() * s).max(a.abs()))
}

/// Fallback: every candidate polished as a simple root (conjugate pairs kept exact).
fn simple_roots(q: &Poly, cand: &[Complex64]) -> Vec<Root> {
    let mut out = Vec::new();
    for (i, &z) in cand.iter().enumerate() {
        if z.im < 0.0 {
            continue;
        }
        let nearest = cand
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != i)
            .map(|(_, w)| (w - z).norm())
            .fold(f64::INFINITY, f64::min);
        let reach = 0.5 * nearest;
        if z.im == 0.0 {
            out.push(Root {
                value: Complex64::new(polish_real(q, z.re, reach), 0.0),
                multiplicity: 1,
            });
        } else {
            let w = polish_complex(q, z, reach.min(0.5 * z.im));
            let w = if w.im > 0.0 { w } else { z };
            out.push(Root {
                value: w,
                multiplicity: 1,
            });
            out.push(Root {
                value: w.conj(),
                multiplicity: 1,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // these tests expect exact values
    use super::*;

    fn p(c: &[f64]) -> Poly {
        Poly::from_descending(c).unwrap()
    }

    fn pow(base: &Poly, k: usize) -> Poly {
        let mut r = Poly::constant(1.0);
        for _ in 0..k {
            r = &r * base;
        }
        r
    }

    #[test]
    fn s_plus_one_powers() {
        let b = p(&[1.0, 1.0]);
        for k in 1..=6 {
            let r = pow(&b, k).roots().unwrap();
            assert_eq!(r.len(), 1, "k={k}: {r:?}");
            assert_eq!(r[0].multiplicity, k);
            assert!((r[0].value.re + 1.0).abs() <= 1e-12);
            assert_eq!(r[0].value.im, 0.0);
        }
    }

    #[test]
    fn complex_triple() {
        // ((s+1)^2 + 4)^3
        let b = p(&[1.0, 2.0, 5.0]);
        let r = pow(&b, 3).roots().unwrap();
        assert_eq!(r.len(), 2, "{r:?}");
        for x in &r {
            assert_eq!(x.multiplicity, 3);
            assert!((x.value.re + 1.0).abs() <= 1e-12 * 5f64.sqrt());
            assert!((x.value.im.abs() - 2.0).abs() <= 1e-12 * 5f64.sqrt());
        }
        assert_eq!(r[0].value, r[1].value.conj());
    }

    #[test]
    fn imaginary_double_and_zero_triple() {
        let r = p(&[1.0, 0.0, 2.0, 0.0, 1.0]).roots().unwrap(); // (s^2+1)^2
        assert_eq!(r.len(), 2);
        assert!(
            r.iter()
                .all(|x| x.multiplicity == 2 && x.value.re.abs() < 1e-14)
        );
        let r = p(&[1.0, 0.0, 0.0, 0.0]).roots().unwrap();
        assert_eq!(
            r,
            vec![Root {
                value: Complex64::new(0.0, 0.0),
                multiplicity: 3
            }]
        );
    }

    #[test]
    fn tiny_leading_coefficient() {
        let r = p(&[1e-17, 1.0, 3.0, 2.0]).roots().unwrap();
        assert_eq!(r.len(), 3, "{r:?}");
        assert!((r[0].value.re + 1.0).abs() < 1e-14, "{r:?}");
        assert!((r[1].value.re + 2.0).abs() < 1e-14, "{r:?}");
        assert!((r[2].value.re + 1e17).abs() < 1e3, "{r:?}");
    }

    #[test]
    fn close_distinct_roots_stay_distinct() {
        let a =
            Poly::from_roots(&[Complex64::new(-1.0, 0.0), Complex64::new(-1.0005, 0.0)]).unwrap();
        let d = &a * &p(&[1.0, 3.0]);
        let r = d.roots().unwrap();
        assert_eq!(r.len(), 3, "{r:?}");
        assert!(r.iter().all(|x| x.multiplicity == 1));
    }

    #[test]
    fn critically_damped_is_double() {
        for &wn in &[0.3, 1.0, 2.7, 1e3] {
            let q = p(&[1.0, 2.0 * wn, wn * wn]);
            let r = q.roots().unwrap();
            assert_eq!(r.len(), 1, "wn={wn}: {r:?}");
            assert_eq!(r[0].multiplicity, 2);
            assert!((r[0].value.re + wn).abs() <= 1e-12 * wn);
        }
    }

    #[test]
    fn order_limits() {
        let mut c = vec![0.0; MAX_ORDER + 2];
        c[0] = 1.0;
        c[MAX_ORDER + 1] = 1.0;
        assert!(matches!(p(&c).roots(), Err(LtiError::OrderTooHigh { .. })));
        assert!(Poly::zero().roots().is_err());
        assert!(Poly::constant(3.0).roots().unwrap().is_empty());
    }
}
