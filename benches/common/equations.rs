//! The matrix-equation problems of the benches and of `benches/compare/compare_equations.py`
//! (which generates the same matrices bit for bit with the same integer recurrence).
//!
//! Entries: the 64-bit LCG xₖ₊₁ = 6364136223846793005·xₖ + 1442695040888963407 (mod 2⁶⁴),
//! value (xₖ₊₁ >> 11)/2⁵³ − 0.5, column by column; A = random(n, n; seed 11)·2/√n − I
//! (stable: the random part has spectral radius ≈ 0.6), B = random(n, 3; seed 12),
//! Q = I (care) or B·Bᵀ (lyap), R = I.

use nalgebra::DMatrix;

/// The seed's matrix of uniform entries in [−0.5, 0.5), column-major.
pub fn random(rows: usize, cols: usize, seed: u64) -> DMatrix<f64> {
    let mut state = seed;
    DMatrix::from_fn(rows, cols, |_, _| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    })
}

/// (A, B) of order n with 3 inputs.
pub fn problem(n: usize) -> (DMatrix<f64>, DMatrix<f64>) {
    let a = random(n, n, 11) * (2.0 / (n as f64).sqrt()) - DMatrix::identity(n, n);
    (a, random(n, 3, 12))
}
