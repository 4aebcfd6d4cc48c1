//! A posteriori error bounds of computed roots, for deciding what is known: a computed root
//! whose real part is within its bound of 0 may lie on the imaginary axis, and is printed
//! and used as lying there.

use num_complex::Complex64;

use crate::poly::{Poly, Root};

/// A bound on the distance from the computed root `r` (claimed with multiplicity `m`) of `p`
/// to the cluster of m true roots it stands for, from the residual at r: E = |p(r)| plus the
/// rounding of the evaluation and of the coefficients (4n·eps·Σ|aᵢ||r|ⁱ); then
/// n·E/|p′(r)| for a simple root (the classical inclusion radius) and
/// 2·(m!·E/|p⁽ᵐ⁾(r)|)^(1/m) for an m-fold one. +∞ when the derivative vanishes.
pub(crate) fn root_error_bound(p: &Poly, r: Complex64, m: usize) -> f64 {
    let n = p.degree();
    if n == 0 || m == 0 {
        return f64::INFINITY;
    }
    let resid = p.eval_complex(r).norm() + 4.0 * n as f64 * f64::EPSILON * p.eval_abs(r.norm());
    let dm = p.nth_derivative(m).eval_complex(r).norm();
    if !(dm > 0.0 && dm.is_finite() && resid.is_finite()) {
        return f64::INFINITY;
    }
    if m == 1 {
        n as f64 * resid / dm
    } else {
        let fact: f64 = (1..=m).map(|k| k as f64).product();
        2.0 * (fact * resid / dm).powf(1.0 / m as f64)
    }
}

/// The roots of `p` with every non-real root whose real part lies within its error bound of
/// 0 put exactly on the imaginary axis (both members of a pair alike): s³ + 3s² + 2s + 6
/// computed as 7.9e-17 ± 1.414j is ±j√2 as far as anything is known.
pub(crate) fn snap_to_axis(p: &Poly, roots: Vec<Root>) -> Vec<Root> {
    roots
        .into_iter()
        .map(|r| {
            let v = r.value;
            if v.im != 0.0 && v.re != 0.0 {
                let upper = Complex64::new(v.re, v.im.abs());
                if v.re.abs() <= root_error_bound(p, upper, r.multiplicity) {
                    return Root::new(Complex64::new(0.0, v.im), r.multiplicity);
                }
            }
            r
        })
        .collect()
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact values are meant: the gain kept, a real part of exactly 0
mod tests {
    use super::*;

    #[test]
    fn closed_loop_crossing_poles_land_on_the_axis() {
        // s³ + 3s² + 2s + 6 = (s + 3)(s² + 2): ±j√2 exactly
        let p = Poly::from_descending(&[1.0, 3.0, 2.0, 6.0]).unwrap();
        let roots = snap_to_axis(&p, p.roots().unwrap());
        for r in &roots {
            if r.value.im != 0.0 {
                assert_eq!(r.value.re, 0.0, "{roots:?}");
                assert!((r.value.im.abs() - 2f64.sqrt()).abs() < 1e-14);
            }
        }
        // a genuinely damped pair stays: s² + 2e-10 s + 1 (bound ~1e-15)
        let p = Poly::from_descending(&[1.0, 2e-10, 1.0]).unwrap();
        let roots = snap_to_axis(&p, p.roots().unwrap());
        assert!(
            roots.iter().all(|r| (r.value.re + 1e-10).abs() < 1e-20),
            "{roots:?}"
        );
    }

    #[test]
    fn double_pairs_use_the_multiple_root_bound() {
        // (s² + 1)²: ±j, each double
        let p = Poly::from_descending(&[1.0, 0.0, 2.0, 0.0, 1.0]).unwrap();
        let roots = snap_to_axis(&p, p.roots().unwrap());
        assert!(
            roots
                .iter()
                .all(|r| r.value.re == 0.0 && r.multiplicity == 2),
            "{roots:?}"
        );
    }
}
