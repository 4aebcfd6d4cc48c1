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
    let one = a
        .column_iter()
        .map(|c| c.iter().map(|x| x.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let inf = a
        .row_iter()
        .map(|r| r.iter().map(|x| x.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    one.max(inf)
}
