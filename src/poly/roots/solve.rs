//! The root finder's pipeline ([`roots`]): exact zero roots, scaling, candidates, grouping
//! into multiple roots, refinement and the checks (see the [module docs](super)).

use num_complex::Complex64;

use super::candidates::candidates;
use super::checks::{any_more_multiple, reconstructs, simple_roots};
use super::derivatives::{hidden_multiple_root, structure_from_derivatives};
use super::found::{GROUP_REL, expand_conjugates};
use super::group::{group_weight, link_groups, resolve_group};
use super::order::sort_roots;
use super::refine::refine_structured;
use super::scale;
use crate::error::{LtiError, Result};
use crate::poly::{MAX_ORDER, Poly, Root};

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
        out.extend(solve(&q)?);
    }
    sort_roots(&mut out);
    Ok(out)
}

/// Roots of `q` (no zero roots), in its own frame or piece by piece (see `scale.rs`).
fn solve(q: &Poly) -> Result<Vec<Root>> {
    let pieces = match scale::plan(q)? {
        scale::Plan::Native => {
            let cand = candidates(q)?;
            return Ok(resolve_multiplicities(q, &cand));
        }
        scale::Plan::Pieces(p) => p,
    };
    let mut out = Vec::new();
    for piece in pieces {
        let cand = candidates(&piece.poly)?;
        for r in resolve_multiplicities(&piece.poly, &cand) {
            let value = scale::unscale(r.value, piece.shift);
            if !(value.re.is_finite() && value.im.is_finite()) {
                return Err(LtiError::invalid(format!(
                    "a root of the polynomial is about 2^{} in magnitude, beyond the range of f64",
                    piece.shift
                )));
            }
            out.push(Root {
                value,
                multiplicity: r.multiplicity,
            });
        }
    }
    let total: usize = out.iter().map(|r| r.multiplicity).sum();
    if total != q.degree() {
        return Err(LtiError::NoConvergence {
            what: format!("root finder (found {total} of {} roots)", q.degree()),
            iterations: 0,
        });
    }
    Ok(out)
}

/// Groups the candidates and returns roots with multiplicities (or, if the grouped result fails
/// the reconstruction test, the polished candidates as simple roots).
pub(super) fn resolve_multiplicities(q: &Poly, cand: &[Complex64]) -> Vec<Root> {
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
    fn simple_roots_are_exact_to_the_last_bit_of_the_coefficients() {
        // Wilkinson's (x − 1)(x − 2)…(x − 12): integer coefficients, exact in f64 (the largest,
        // 12! = 479 001 600, and the sum of the others stay below 2⁵³), roots 1 … 12 exactly.
        // A polish on the f64 residual stops where rounding hides p(x) (x = 1 came out
        // 4.5 ulp off); on the double-double residual every root is within 4 ulp.
        let mut q = Poly::constant(1.0);
        for k in 1..=12 {
            q = &q * &p(&[1.0, -(k as f64)]);
        }
        let mut r: Vec<f64> = q.roots().unwrap().iter().map(|r| r.value.re).collect();
        r.sort_by(f64::total_cmp);
        assert_eq!(r.len(), 12);
        for (k, x) in r.iter().enumerate() {
            let want = (k + 1) as f64;
            assert!(
                (x - want).abs() <= 4.0 * f64::EPSILON * want,
                "{x} vs {want}"
            );
        }
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
