//! Transmission zeros of a single-input single-output system already in controllability
//! Hessenberg form — the form its controllability staircase produces — as the eigenvalues of
//! an upper Hessenberg matrix: no pencil reduction, no second Hessenberg reduction.
//!
//! # Method
//! Let A = H be upper Hessenberg and b = β·e₁ (β ≠ 0), the form of the SISO controllability
//! staircase ([`super::staircase`]) when no rank drops (for a single input every step is one
//! Householder reflector: it *is* the Hessenberg reduction with b as the first vector).
//!
//! **D = 0.** The zeros are the z where P(z) = \[H − zI, βe₁; c, 0\] is singular. The last
//! column has β in its first row only, so det P(z) = ±β·det M(z), M the rows 2…n of
//! \[H − zI\] over c: M = \[h₂₁·e₁, H₂₂ − zI; c₁, c₂\]. Moving the first column last,
//! \[H₂₂ − zI, h₂₁·e₁; c₂, c₁\], and taking the Schur complement of the pivot c₁:
//! det M(z) = ±c₁·det(H₂₂ − (h₂₁/c₁)·e₁·c₂ − zI). The n − 1 zeros are the eigenvalues of
//! Z = H₂₂ − (h₂₁/c₁)·e₁·c₂, which differs from H₂₂ in its first row only: upper Hessenberg.
//! (c₁ = c·b/β: a non-zero c₁ is relative degree 1.)
//!
//! **D = d ≠ 0.** The zeros are the eigenvalues of A − b·d⁻¹·c = H − (β/d)·e₁·c: again H
//! with its first row changed, upper Hessenberg (relative degree 0, n zeros).
//!
//! **Accuracy, and when this route is taken.** The eigenvalues of the computed Z are exact
//! for Z + E with ‖E‖ ≲ p(n)·ε·‖Z‖ (the Francis iteration is backward stable), and a
//! perturbation of Z is one of H₂₂ (resp. H), an entry of the system matrix
//! S = \[H βe₁; c d\]: the zeros are those of a system within p(n)·ε·‖Z‖ of the given one.
//! The elimination's growth g = ‖Z‖_F/‖S‖_F (≥ ‖h₂₁·c₂‖/(|c₁|·‖S‖): the pivot c₁ small
//! against ‖c‖, i.e. c·b small against ‖c‖·‖b‖) is therefore the factor by which this
//! backward error exceeds that of a backward-stable method on S. The pencil reduction
//! ([`super::zeros`]) eliminates with the pivot c·b/‖c‖ in the same way at relative degree 1,
//! so its growth is of the same order; still, this route is taken only when
//! g ≤ [`MAX_GROWTH`] (at most two digits beyond the normwise backward error ε·‖S‖), and the
//! caller falls back to the pencil reduction otherwise (`None`).

use nalgebra::DMatrix;

/// Largest growth ‖Z‖_F/‖S‖_F of the elimination for which the Hessenberg route is taken
/// (see the [module docs](self)).
pub(crate) const MAX_GROWTH: f64 = 100.0;

/// A single-input single-output system in controllability Hessenberg form: A = H upper
/// Hessenberg, b = β·e₁.
#[derive(Clone, Debug)]
pub(crate) struct HessenbergSiso {
    /// H (n×n, upper Hessenberg: exact zeros below the subdiagonal).
    pub h: DMatrix<f64>,
    /// β: b = β·e₁.
    pub beta: f64,
    /// c (length n).
    pub c: Vec<f64>,
    /// d.
    pub d: f64,
}

/// True when every entry below the subdiagonal of the square `a` is exactly zero.
pub(crate) fn is_upper_hessenberg(a: &DMatrix<f64>) -> bool {
    let n = a.nrows();
    a.ncols() == n && (0..n).all(|j| a.column(j).iter().skip(j + 2).all(|&x| x == 0.0))
}

/// True when every entry above the superdiagonal of the square `a` is exactly zero.
fn is_lower_hessenberg(a: &DMatrix<f64>) -> bool {
    let n = a.nrows();
    a.ncols() == n
        && (0..n).all(|j| {
            a.column(j)
                .iter()
                .take(j.saturating_sub(1))
                .all(|&x| x == 0.0)
        })
}

impl HessenbergSiso {
    /// The form of a SISO realisation (A, b, c, d) when it has it exactly: A upper Hessenberg
    /// with b = β·e₁ (a controllability staircase), or — through the dual (Aᵀ, cᵀ, bᵀ, d),
    /// which has the same transfer function — A lower Hessenberg with c = γ·e₁ᵀ (an
    /// observability staircase). `None` otherwise, or when β = 0 or n = 0.
    pub(crate) fn of(
        a: &DMatrix<f64>,
        b: &DMatrix<f64>,
        c: &DMatrix<f64>,
        d: &DMatrix<f64>,
    ) -> Option<HessenbergSiso> {
        let n = a.nrows();
        if n == 0 || b.shape() != (n, 1) || c.shape() != (1, n) || d.shape() != (1, 1) {
            return None;
        }
        let d = d[(0, 0)];
        let leading_only = |v: &mut dyn Iterator<Item = &f64>| v.skip(1).all(|&x| x == 0.0);
        let form = if b[(0, 0)] != 0.0 && leading_only(&mut b.iter()) && is_upper_hessenberg(a) {
            HessenbergSiso {
                h: a.clone(),
                beta: b[(0, 0)],
                c: c.iter().copied().collect(),
                d,
            }
        } else if c[(0, 0)] != 0.0 && leading_only(&mut c.iter()) && is_lower_hessenberg(a) {
            HessenbergSiso {
                h: a.transpose(),
                beta: c[(0, 0)],
                c: b.iter().copied().collect(),
                d,
            }
        } else {
            return None;
        };
        Some(form)
    }

    /// ‖S‖_F of the system matrix S = \[H βe₁; c d\].
    fn system_norm(&self) -> f64 {
        super::norms::frobenius(
            self.h
                .iter()
                .chain(std::iter::once(&self.beta))
                .chain(&self.c)
                .chain(std::iter::once(&self.d)),
        )
    }

    /// The zero dynamics Z, upper Hessenberg, whose eigenvalues are the finite zeros (see the
    /// [module docs](self)): with d ≠ 0 (relative degree 0) Z = H − (β/d)·e₁·c (n×n), with
    /// d = 0 and c₁ ≠ 0 (relative degree 1) Z = H₂₂ − (h₂₁/c₁)·e₁·c₂ ((n − 1)×(n − 1)).
    /// `None` when the elimination's growth ‖Z‖_F/‖S‖_F exceeds [`MAX_GROWTH`], the pivot is
    /// zero, or an entry is not finite: the caller takes the pencil reduction.
    pub(crate) fn zero_dynamics(&self) -> Option<DMatrix<f64>> {
        let n = self.h.nrows();
        let z = if self.d != 0.0 {
            let f = self.beta / self.d;
            let mut z = self.h.clone();
            for j in 0..n {
                z[(0, j)] -= f * self.c[j];
            }
            z
        } else {
            let c1 = self.c[0];
            if c1 == 0.0 {
                return None;
            }
            if n == 1 {
                return Some(DMatrix::zeros(0, 0));
            }
            let f = self.h[(1, 0)] / c1;
            let mut z = self.h.view((1, 1), (n - 1, n - 1)).clone_owned();
            for j in 0..n - 1 {
                z[(0, j)] -= f * self.c[j + 1];
            }
            z
        };
        let growth = super::norms::frobenius(z.iter()) / self.system_norm();
        (growth.is_finite() && growth <= MAX_GROWTH).then_some(z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::linalg::{controllability_staircase, invariant_zeros, schur_eigenvalues};
    use num_complex::Complex64;

    use crate::numeric::test_rng::uniform;

    fn random_system(n: usize, seed: u64, d: f64) -> [DMatrix<f64>; 4] {
        let mut s = seed;
        let a = DMatrix::from_fn(n, n, |_, _| uniform(&mut s));
        let b = DMatrix::from_fn(n, 1, |_, _| uniform(&mut s));
        let c = DMatrix::from_fn(1, n, |_, _| uniform(&mut s));
        [a, b, c, DMatrix::from_element(1, 1, d)]
    }

    /// The system in controllability Hessenberg form (the staircase of (A, b)).
    fn hessenberg_form(sys: &[DMatrix<f64>; 4]) -> HessenbergSiso {
        let [a, b, c, d] = sys;
        let st = controllability_staircase(a, b, c, None, false).unwrap();
        assert_eq!(st.dim, a.nrows());
        HessenbergSiso::of(&st.a, &st.b, &st.c, d).unwrap()
    }

    /// Every zero of `x` within `tol` of a distinct zero of `y`, one to one (greedy nearest).
    fn same_zeros(x: &[Complex64], y: &[Complex64], tol: f64) -> f64 {
        assert_eq!(x.len(), y.len());
        let mut left: Vec<Complex64> = y.to_vec();
        let mut worst = 0.0f64;
        for z in x {
            let (k, dist) = left
                .iter()
                .enumerate()
                .map(|(k, w)| (k, (w - z).norm() / z.norm().max(1.0)))
                .min_by(|p, q| p.1.total_cmp(&q.1))
                .unwrap();
            assert!(
                dist < tol,
                "zero {z} has no partner within {tol:e} ({dist:e})"
            );
            worst = worst.max(dist);
            left.swap_remove(k);
        }
        worst
    }

    #[test]
    fn hessenberg_zeros_equal_pencil_zeros_on_random_models() {
        for (k, n) in [3usize, 8, 17, 40, 64].into_iter().enumerate() {
            for d in [0.0, 0.7] {
                let sys = random_system(n, 0x2e05 + 31 * k as u64, d);
                let form = hessenberg_form(&sys);
                let z = form.zero_dynamics().expect("a random model is in range");
                assert_eq!(z.nrows(), if d == 0.0 { n - 1 } else { n });
                assert!(is_upper_hessenberg(&z));
                let fast = schur_eigenvalues(&z).unwrap();
                let [a, b, c, dd] = &sys;
                let pencil = invariant_zeros(a, b, c, dd, None).unwrap().zeros;
                // both are backward stable for the pencil; the zeros of a random model are
                // well conditioned (measured worst: 2e-13 at n = 64)
                same_zeros(&fast, &pencil, 1e-10);
            }
        }
    }

    #[test]
    fn the_dual_form_is_recognised() {
        // an observability staircase: A lower Hessenberg, c = γ·e₁ᵀ
        let sys = random_system(12, 0xd0a1, 0.0);
        let form = hessenberg_form(&sys);
        let (at, ct, bt) = (
            form.h.transpose(),
            DMatrix::from_row_slice(1, 12, &{
                let mut v = vec![0.0; 12];
                v[0] = form.beta;
                v
            }),
            DMatrix::from_column_slice(12, 1, &form.c),
        );
        let dual = HessenbergSiso::of(&at, &bt, &ct, &sys[3]).unwrap();
        assert_eq!(dual.h, form.h);
        assert_eq!(dual.c, form.c);
        // neither form: a dense A
        assert!(HessenbergSiso::of(&sys[0], &sys[1], &sys[2], &sys[3]).is_none());
    }

    #[test]
    fn a_small_pivot_falls_back_to_the_pencil() {
        // c·b tiny against ‖c‖·‖b‖: c made orthogonal to b up to 1e-9·‖c‖ (relative degree 1
        // still, but the pivot c₁ = c·b/β is small and the elimination grows by ~1e9)
        let [a, b, c, d] = random_system(10, 0xfa11, 0.0);
        let proj = (&c * &b)[(0, 0)] / b.norm_squared();
        let c = &c - proj * b.transpose() + 1e-9 * c.norm() / b.norm() * b.transpose();
        let form = hessenberg_form(&[a, b, c, d]);
        assert!(form.c[0].abs() < 1e-8 * super::super::norms::frobenius(form.c.iter()));
        assert!(form.zero_dynamics().is_none());
        // and a zero pivot, exactly
        let mut exact = form.clone();
        exact.c[0] = 0.0;
        assert!(exact.zero_dynamics().is_none());
    }

    #[test]
    fn first_order_and_closed_forms() {
        // G = 3/(s + 2): no zero
        let h = HessenbergSiso {
            h: DMatrix::from_element(1, 1, -2.0),
            beta: 1.0,
            c: vec![3.0],
            d: 0.0,
        };
        assert_eq!(h.zero_dynamics().unwrap().nrows(), 0);
        // G = (s − 1)/((s + 2)(s + 3)) in controllable canonical form, permuted to b = e₁:
        // A = [−5 −6; 1 0], b = e₁, c = [1 −1]: Z = 0 − (1/1)·(−1) = 1
        let h = HessenbergSiso {
            h: DMatrix::from_row_slice(2, 2, &[-5.0, -6.0, 1.0, 0.0]),
            beta: 1.0,
            c: vec![1.0, -1.0],
            d: 0.0,
        };
        // exact: 0 − (1/1)·(−1)
        assert!((h.zero_dynamics().unwrap()[(0, 0)] - 1.0).abs() == 0.0);
        // with d = 2: G = 2 + (s − 1)/(s² + 5s + 6), zeros of 2s² + 11s + 11:
        // (−11 ± √33)/4
        let h = HessenbergSiso { d: 2.0, ..h };
        let mut z = schur_eigenvalues(&h.zero_dynamics().unwrap()).unwrap();
        z.sort_by(|p, q| p.re.total_cmp(&q.re));
        assert!((z[0].re - (-11.0 - 33f64.sqrt()) / 4.0).abs() < 1e-14);
        assert!((z[1].re - (-11.0 + 33f64.sqrt()) / 4.0).abs() < 1e-14);
    }
}
