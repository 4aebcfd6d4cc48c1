//! Step 4: Gauss–Newton refinement of all roots with the multiplicity structure fixed, the
//! residual in double-double arithmetic.

use num_complex::Complex64;

use super::found::Found;
use crate::numeric::dd::{self, Dd, two_prod};
use crate::numeric::tol::EPS;
use crate::poly::{Poly, Root};

/// Iteration cap of the SVD behind each Gauss–Newton step, per column of the Jacobian.
const SVD_ITER_PER_COLUMN: usize = 100;

/// Gauss–Newton refinement of all roots jointly with the multiplicity structure held fixed
/// (Zeng's "pejorative manifold"): find real parameters θ (one per real root, (a, b) per pair
/// a ± bj) minimising the weighted distance between the monic coefficients of
/// Π(s − rₖ)^mₖ and those of q. A multiple root computed from p^(m−1) alone is only as accurate
/// as that derivative is well conditioned (2e-6 for a double root next to a triple one); the
/// structured problem is well conditioned and converges to ~eps. Returns None (keep the
/// unrefined roots) if the residual does not decrease.
pub(super) fn refine_structured(q: &Poly, found: &[Found]) -> Option<Vec<Found>> {
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
        // nalgebra's `svd()` iterates without a cap (and never ends on a Jacobian with
        // non-finite or wildly scaled entries): finite entries only, capped iteration.
        if jac.iter().any(|x| !x.is_finite()) {
            break;
        }
        let cols = jac.ncols();
        // (5·eps is the tolerance of nalgebra's own `svd()`.)
        let cap = SVD_ITER_PER_COLUMN * cols.max(1);
        let svd = nalgebra::SVD::try_new(jac, true, true, 5.0 * EPS, cap)?;
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
pub(super) fn structured_poly_dd(found: &[Found]) -> Vec<Dd> {
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

pub(super) fn factor_of(z: Complex64) -> Poly {
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
pub(super) fn structured_jacobian(found: &[Found], n: usize, w: &[f64]) -> nalgebra::DMatrix<f64> {
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
