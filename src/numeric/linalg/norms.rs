//! The norms in which the kernels state their tolerances: Frobenius without overflow, and
//! max(‖A‖₁, ‖A‖∞).

use nalgebra::DMatrix;

/// Frobenius norm without overflow or harmful underflow (scaled by the largest magnitude).
pub(crate) fn frobenius<'a>(values: impl Iterator<Item = &'a f64> + Clone) -> f64 {
    let big = values.clone().fold(0.0f64, |m, x| m.max(x.abs()));
    if big == 0.0 || !big.is_finite() {
        return big;
    }
    let s: f64 = values.map(|x| (x / big) * (x / big)).sum();
    big * s.sqrt()
}

/// max(‖A‖₁, ‖A‖∞) — a cheap upper bound of the 2-norm within a factor √n, the scale in which
/// eigenvalue tolerances are stated.
pub(crate) fn norm_1_inf(a: &DMatrix<f64>) -> f64 {
    // one pass down the contiguous columns; the row sums accumulate in the same order
    // (column index increasing) as a row-by-row sum would
    let mut rows = vec![0.0f64; a.nrows()];
    let mut one = 0.0f64;
    for c in a.column_iter() {
        let mut sum = 0.0;
        for (r, x) in rows.iter_mut().zip(c.iter()) {
            let v = x.abs();
            sum += v;
            *r += v;
        }
        one = one.max(sum);
    }
    let inf = rows.into_iter().fold(0.0, f64::max);
    one.max(inf)
}
