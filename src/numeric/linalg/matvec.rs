//! y = M·x for a column-major M, the product the dense time march repeats thousands of times.
//!
//! nalgebra's product with a vector goes through a strided kernel that the compiler cannot
//! vectorise (the strides are run-time values: one entry per cycle at best). Here the columns
//! are contiguous slices, taken four at a time so that y is loaded and stored once per four
//! columns; each entry is still summed column by column in order (M₀x₀ + M₁x₁, then plus
//! M₂x₂, and so on: the order of nalgebra's loop), so the results are the same to the bit.
//! On x86-64 the same loop is also compiled for AVX2 and picked at run time (no fused
//! multiply–add: the same roundings).

use nalgebra::DMatrix;

/// y ← M·x (`y.len()` = rows of M, `x.len()` = columns).
pub(crate) fn mat_vec(m: &DMatrix<f64>, x: &[f64], y: &mut [f64]) {
    debug_assert_eq!((m.nrows(), m.ncols()), (y.len(), x.len()));
    #[cfg(all(ltikit_simd, target_arch = "x86_64"))]
    {
        if is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2 (checked just above).
            unsafe { mat_vec_avx2(m, x, y) };
            return;
        }
    }
    mat_vec_portable(m, x, y);
}

#[cfg(all(ltikit_simd, target_arch = "x86_64"))]
#[target_feature(enable = "avx2")]
#[allow(clippy::incompatible_msrv)]
fn mat_vec_avx2(m: &DMatrix<f64>, x: &[f64], y: &mut [f64]) {
    mat_vec_portable(m, x, y);
}

#[inline(always)]
fn mat_vec_portable(m: &DMatrix<f64>, x: &[f64], y: &mut [f64]) {
    let r = y.len();
    y.fill(0.0);
    if r == 0 {
        return;
    }
    let data = m.as_slice();
    let n = x.len();
    let mut j = 0;
    while j + 4 <= n {
        let (c0, c1, c2, c3) = (
            &data[j * r..(j + 1) * r],
            &data[(j + 1) * r..(j + 2) * r],
            &data[(j + 2) * r..(j + 3) * r],
            &data[(j + 3) * r..(j + 4) * r],
        );
        let (x0, x1, x2, x3) = (x[j], x[j + 1], x[j + 2], x[j + 3]);
        for ((((yi, a), b), c), d) in y.iter_mut().zip(c0).zip(c1).zip(c2).zip(c3) {
            *yi = (((*yi + a * x0) + b * x1) + c * x2) + d * x3;
        }
        j += 4;
    }
    for (col, xj) in data[j * r..].chunks_exact(r).zip(&x[j..]) {
        for (yi, a) in y.iter_mut().zip(col) {
            *yi += a * xj;
        }
    }
}

/// y ← Mᵀ·x (the row vector xᵀM): one contiguous dot product per column of M, [`dot`] (for
/// the few rows that nalgebra's `gemm` would send through its strided kernel: it takes
/// matrixmultiply only above five rows).
pub(crate) fn vec_mat(x: &[f64], m: &DMatrix<f64>, y: &mut [f64]) {
    debug_assert_eq!((m.nrows(), m.ncols()), (x.len(), y.len()));
    let r = x.len();
    if r == 0 {
        y.fill(0.0);
        return;
    }
    for (yj, col) in y.iter_mut().zip(m.as_slice().chunks_exact(r)) {
        *yj = dot(col, x);
    }
}

/// Σ aᵢbᵢ with sixteen partial sums (four vector registers): a single running sum is bound
/// by the latency of the addition, which made the reflectors' left products (`householder.rs`) a third
/// of a 256-state staircase.
#[inline]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    const W: usize = 16;
    let mut acc = [0.0; W];
    let (ac, bc) = (a.chunks_exact(W), b.chunks_exact(W));
    let tail: f64 = ac
        .remainder()
        .iter()
        .zip(bc.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ac.zip(bc) {
        for k in 0..W {
            acc[k] += x[k] * y[k];
        }
    }
    let mut w = W;
    while w > 1 {
        w /= 2;
        for k in 0..w {
            acc[k] += acc[k + w];
        }
    }
    acc[0] + tail
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_bits_as_nalgebra() {
        // shapes with and without a remainder of the four-column groups
        for &(r, c) in &[(1, 1), (3, 5), (64, 256), (7, 4), (10, 0)] {
            let m = DMatrix::from_fn(r, c, |i, j| ((i * 31 + j * 17) % 23) as f64 / 7.0 - 1.3);
            let x = nalgebra::DVector::from_fn(c, |j, _| (j as f64 * 0.37).sin());
            let mut y = vec![f64::NAN; r];
            mat_vec(&m, x.as_slice(), &mut y);
            let want = &m * &x;
            assert_eq!(y.as_slice(), want.as_slice(), "{r}×{c}");
            // xᵀM against nalgebra to rounding
            let v = nalgebra::DVector::from_fn(r, |i, _| (i as f64 * 0.61).cos());
            let mut z = vec![f64::NAN; c];
            vec_mat(v.as_slice(), &m, &mut z);
            let want = m.tr_mul(&v);
            for (zj, wj) in z.iter().zip(want.iter()) {
                assert!((zj - wj).abs() <= 1e-13 * (1.0 + wj.abs()), "{r}×{c}");
            }
        }
    }
}
