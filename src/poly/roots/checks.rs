//! Step 5: the checks on a result (reconstruction of the coefficients, no root more multiple
//! than claimed) and the fallback to polished simple roots.

use num_complex::Complex64;

use super::found::{Found, GROUP_REL};
use super::newton::{confirm_complex, confirm_real, polish_complex, polish_real};
use crate::poly::{Poly, Root};

/// Componentwise relative tolerance of the final reconstruction test. It only has to catch a
/// lost or duplicated root (an error of the order of a root separation); accurate multiple
/// roots of a polynomial with rounded coefficients reconstruct to ~1e-11.
pub(super) const RECONSTRUCT_TOL: f64 = 1e-9;

/// True when some found root of multiplicity m is also accepted as an (m+1)-fold root: the
/// grouping then split one multiple root between groups (overlapping clusters), and the
/// structure must come from the derivatives.
pub(super) fn any_more_multiple(q: &Poly, found: &[Found]) -> bool {
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

/// True when lead·Π(s − rₖ)^mₖ reproduces q coefficient by coefficient to rounding level.
pub(super) fn reconstructs(q: &Poly, roots: &[Root]) -> bool {
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
pub(super) fn simple_roots(q: &Poly, cand: &[Complex64]) -> Vec<Root> {
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
