//! Elementary (Householder) reflectors P = I − τ·v·vᵀ with v₀ = 1, and their application to
//! blocks of column-major matrices without forming P.
//!
//! Every orthogonal transformation of the kernels (Hessenberg reduction, rank-revealing QR,
//! staircase, pencil reduction) is a product of these. Applying one to a k-row block costs
//! 4·k·(columns) flops; the loops run down contiguous columns.

use nalgebra::DMatrix;

/// An elementary reflector P = I − τ·v·vᵀ acting on `v.len()` consecutive coordinates
/// starting at `offset`; `v[0] == 1`. τ = 0 is the identity.
#[derive(Clone, Debug, PartialEq)]
pub struct Reflector {
    /// First coordinate the reflector acts on.
    pub offset: usize,
    /// The Householder vector, v\[0\] = 1.
    pub v: Vec<f64>,
    /// The factor τ (0 ≤ τ ≤ 2).
    pub tau: f64,
}

/// Builds the reflector that maps x to β·e₁ (LAPACK's `dlarfg` convention: β = −sign(x₀)‖x‖,
/// so no cancellation) and returns (β, τ); `x` is overwritten by v (x\[0\] = 1).
/// For x\[1..\] = 0 the reflector is the identity (τ = 0) and β = x₀.
pub fn make_reflector(x: &mut [f64]) -> (f64, f64) {
    let Some((&alpha, tail)) = x.split_first() else {
        return (0.0, 0.0);
    };
    let tail_norm = super::norms::frobenius(tail.iter());
    if tail_norm == 0.0 {
        x[0] = 1.0;
        return (alpha, 0.0);
    }
    let norm = alpha.hypot(tail_norm);
    let beta = if alpha >= 0.0 { -norm } else { norm };
    let tau = (beta - alpha) / beta;
    let scale = 1.0 / (alpha - beta);
    for t in x.iter_mut().skip(1) {
        *t *= scale;
    }
    x[0] = 1.0;
    (beta, tau)
}

impl Reflector {
    /// Builds the reflector of `x` placed at `offset` (see [`make_reflector`]); returns it and β.
    pub fn new(offset: usize, x: &[f64]) -> (Self, f64) {
        let mut v = x.to_vec();
        let (beta, tau) = make_reflector(&mut v);
        (Reflector { offset, v, tau }, beta)
    }

    /// M ← P·M on the columns `cols` (all of P's rows).
    ///
    /// On x86-64 this and [`Reflector::apply_right`] are also compiled for AVX2 and picked at
    /// run time (no fused multiply–add: the same roundings, four lanes instead of two).
    pub fn apply_left(&self, m: &mut DMatrix<f64>, cols: std::ops::Range<usize>) {
        if self.tau == 0.0 {
            return;
        }
        #[cfg(all(ltikit_simd, target_arch = "x86_64"))]
        {
            if is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2 (checked just above).
                unsafe { self.apply_left_avx2(m, cols) };
                return;
            }
        }
        self.apply_left_portable(m, cols);
    }

    #[cfg(all(ltikit_simd, target_arch = "x86_64"))]
    #[target_feature(enable = "avx2")]
    #[allow(clippy::incompatible_msrv)]
    fn apply_left_avx2(&self, m: &mut DMatrix<f64>, cols: std::ops::Range<usize>) {
        self.apply_left_portable(m, cols);
    }

    #[inline(always)]
    fn apply_left_portable(&self, m: &mut DMatrix<f64>, cols: std::ops::Range<usize>) {
        let (r0, k) = (self.offset, self.v.len());
        for j in cols {
            let col = &mut m.column_mut(j);
            let slice = &mut col.as_mut_slice()[r0..r0 + k];
            let f = self.tau * super::matvec::dot(slice, &self.v);
            for (a, v) in slice.iter_mut().zip(&self.v) {
                *a -= f * v;
            }
        }
    }

    /// M ← M·P on the rows `rows` (all of P's columns).
    pub fn apply_right(&self, m: &mut DMatrix<f64>, rows: std::ops::Range<usize>) {
        if self.tau == 0.0 || rows.is_empty() {
            return;
        }
        #[cfg(all(ltikit_simd, target_arch = "x86_64"))]
        {
            if is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2 (checked just above).
                unsafe { self.apply_right_avx2(m, rows) };
                return;
            }
        }
        self.apply_right_portable(m, rows);
    }

    #[cfg(all(ltikit_simd, target_arch = "x86_64"))]
    #[target_feature(enable = "avx2")]
    #[allow(clippy::incompatible_msrv)]
    fn apply_right_avx2(&self, m: &mut DMatrix<f64>, rows: std::ops::Range<usize>) {
        self.apply_right_portable(m, rows);
    }

    #[inline(always)]
    fn apply_right_portable(&self, m: &mut DMatrix<f64>, rows: std::ops::Range<usize>) {
        let (c0, k) = (self.offset, self.v.len());
        let nrows = m.nrows();
        let data = m.as_mut_slice();
        let mut w = vec![0.0; rows.len()];
        for (l, &vl) in self.v.iter().enumerate() {
            let col = &data[(c0 + l) * nrows + rows.start..(c0 + l) * nrows + rows.end];
            for (wi, a) in w.iter_mut().zip(col) {
                *wi += vl * a;
            }
        }
        for (l, &vl) in self.v.iter().enumerate().take(k) {
            let f = self.tau * vl;
            let col = &mut data[(c0 + l) * nrows + rows.start..(c0 + l) * nrows + rows.end];
            for (a, wi) in col.iter_mut().zip(&w) {
                *a -= f * wi;
            }
        }
    }
}

/// An orthogonal n×n matrix as the product P₀·P₁·…·P_k of reflectors (formed explicitly).
pub fn form_product(n: usize, reflectors: &[Reflector]) -> DMatrix<f64> {
    let mut q = DMatrix::<f64>::identity(n, n);
    // Q = P₀(P₁(…(P_k·I))): apply from the last, each touching only its own rows.
    for r in reflectors.iter().rev() {
        r.apply_left(&mut q, r.offset..n);
    }
    q
}

/// A fixed, non-trivial reflector H = I − 2wwᵀ/(wᵀw) of order n (symmetric, orthogonal), used
/// to break the cyclic structure that stalls a QR iteration (DESIGN §5).
pub(crate) fn fixed_reflector(n: usize) -> Reflector {
    let w: Vec<f64> = (0..n)
        .map(|i| 1.0 + 0.37 * i as f64 + if i % 2 == 0 { 0.5 } else { -0.25 })
        .collect();
    let ww: f64 = w.iter().map(|x| x * x).sum();
    // P = I − τ v vᵀ with v = w/w₀ and τ = 2w₀²/wᵀw.
    let v: Vec<f64> = w.iter().map(|x| x / w[0]).collect();
    Reflector {
        offset: 0,
        v,
        tau: 2.0 * w[0] * w[0] / ww,
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // these tests expect exact zeros and exact values

    /// The run-time dispatch (AVX2 where the CPU has it) gives the portable loops' bits.
    #[test]
    fn dispatched_products_equal_the_portable_ones() {
        use nalgebra::DMatrix;
        let m0 = DMatrix::from_fn(37, 29, |i, j| ((i * 31 + j * 17) % 23) as f64 / 7.0 - 1.3);
        for (offset, len) in [(0, 37), (3, 20), (10, 1), (5, 19)] {
            let x: Vec<f64> = (0..len).map(|k| (k as f64 * 0.77).sin() + 0.1).collect();
            let (h, _) = super::Reflector::new(offset, &x);
            let (mut a, mut b) = (m0.clone(), m0.clone());
            h.apply_left(&mut a, 2..29);
            h.apply_left_portable(&mut b, 2..29);
            assert_eq!(a, b);
            let h = super::Reflector {
                offset: offset.min(29 - len.min(29)),
                v: h.v[..len.min(29)].to_vec(),
                tau: h.tau,
            };
            let (mut a, mut b) = (m0.clone(), m0.clone());
            h.apply_right(&mut a, 1..37);
            h.apply_right_portable(&mut b, 1..37);
            assert_eq!(a, b);
        }
    }

    /// `make_reflector` on a worked example (an internal kernel: a unit test, not a doctest).
    #[test]
    #[allow(clippy::float_cmp)] // exact values are meant
    fn make_reflector_example() {
        use crate::numeric::linalg::householder::make_reflector;
        let mut x = [3.0, 4.0];
        let (beta, tau) = make_reflector(&mut x);
        assert!((beta + 5.0).abs() < 1e-15);
        // P·[3, 4] = β e₁ with P = I − τ v vᵀ
        let v = x;
        let s = 3.0 * v[0] + 4.0 * v[1];
        assert!((4.0 - tau * s * v[1]).abs() < 1e-15);
    }
    use super::*;

    #[test]
    fn reflector_maps_to_multiple_of_e1() {
        let x = [1.0, -2.0, 0.5, 3.0];
        let (r, beta) = Reflector::new(1, &x);
        let mut m = DMatrix::from_fn(5, 2, |i, j| {
            if i == 0 {
                9.0
            } else {
                x[i - 1] * (j + 1) as f64
            }
        });
        r.apply_left(&mut m, 0..2);
        let norm = x.iter().map(|t| t * t).sum::<f64>().sqrt();
        assert!((beta.abs() - norm).abs() < 1e-14);
        assert!((m[(1, 0)] - beta).abs() < 1e-14);
        for i in 2..5 {
            assert!(m[(i, 0)].abs() < 1e-15 && m[(i, 1)].abs() < 1e-14);
        }
        assert!(
            (m[(0, 0)] - 9.0).abs() < 1e-15,
            "row outside the reflector untouched"
        );
    }

    #[test]
    fn left_and_right_agree_with_the_formed_matrix() {
        let (r, _) = Reflector::new(1, &[0.3, -1.0, 2.0]);
        let p = form_product(4, std::slice::from_ref(&r));
        assert!((&p * p.transpose() - DMatrix::identity(4, 4)).norm() < 1e-15);
        let m0 = DMatrix::from_fn(4, 4, |i, j| (i * 4 + j) as f64 - 3.5);
        let mut left = m0.clone();
        r.apply_left(&mut left, 0..4);
        assert!((left - &p * &m0).norm() < 1e-13);
        let mut right = m0.clone();
        r.apply_right(&mut right, 0..4);
        assert!((right - &m0 * &p).norm() < 1e-13);
        let h = form_product(6, &[fixed_reflector(6)]);
        assert!((&h * &h - DMatrix::identity(6, 6)).norm() < 1e-14);
        assert!((&h - h.transpose()).norm() < 1e-15);
    }

    #[test]
    fn zero_tail_is_identity() {
        let mut x = [-2.0, 0.0, 0.0];
        let (beta, tau) = make_reflector(&mut x);
        assert_eq!(tau, 0.0);
        assert_eq!(beta, -2.0);
        assert!(make_reflector(&mut []).1 == 0.0);
    }
}
