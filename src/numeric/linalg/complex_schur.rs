//! The complex (triangular) Schur form from the real one: A = D·Q·Z·S·Zᴴ·Qᵀ·D⁻¹ with S upper
//! triangular and Z unitary block diagonal.
//!
//! Each standardised 2×2 block [a b; c a] (b·c < 0) has the eigenvector x = (b, iω),
//! ω = √(−bc), for λ = a + iω; the unitary G = [x, x⊥]/‖x‖ makes it upper triangular with
//! diagonal (λ, λ̄). G is applied to the two rows and columns of the block: O(n) per block,
//! O(n²) in all. Z (the G's) is kept factored: a vector y in Schur coordinates maps to
//! D·Q·(Z·y) with one real matrix product.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::schur::{RealSchur, blocks_of};

/// The 2×2 unitary G = [g11 g12; g21 g22] acting on coordinates k, k+1.
pub type BlockRotation = (usize, [Complex64; 4]);

/// A complex Schur form A = D·Q·Z·S·Zᴴ·Qᵀ·D⁻¹ (Q and D those of the real form).
#[derive(Clone, Debug)]
pub struct ComplexSchur {
    /// Upper triangular S; its diagonal holds the eigenvalues (a conjugate pair of the real
    /// form as λ then λ̄ with Im λ > 0).
    pub s: DMatrix<Complex64>,
    /// Z as the rotations of the 2×2 blocks (disjoint, so they commute).
    pub rotations: Vec<BlockRotation>,
}

impl ComplexSchur {
    /// y ← Z·y (Schur coordinates of S to those of the real form's T).
    pub fn apply_z(&self, y: &mut [Complex64]) {
        for &(k, [g11, g12, g21, g22]) in &self.rotations {
            let (a, b) = (y[k], y[k + 1]);
            y[k] = g11 * a + g12 * b;
            y[k + 1] = g21 * a + g22 * b;
        }
    }
}

/// Converts a real Schur form (with the whole T) to the complex triangular form.
pub fn complex_schur(real: &RealSchur) -> ComplexSchur {
    let n = real.order();
    let mut s = real.t.map(|x| Complex64::new(x, 0.0));
    let mut rotations = Vec::new();
    for (k, size) in blocks_of(&real.t) {
        if size != 2 {
            continue;
        }
        let (b, c) = (real.t[(k, k + 1)], real.t[(k + 1, k)]);
        let a = real.t[(k, k)];
        let omega = b.abs().sqrt() * c.abs().sqrt();
        let norm = b.hypot(omega);
        if norm == 0.0 {
            continue;
        }
        // G = [g11 g12; g21 g22], first column the eigenvector for λ = a + iω.
        let g11 = Complex64::new(b / norm, 0.0);
        let g21 = Complex64::new(0.0, omega / norm);
        let g12 = Complex64::new(0.0, omega / norm);
        let g22 = Complex64::new(b / norm, 0.0);
        // Rows k, k+1 ← Gᴴ·rows (columns k..n).
        for j in k..n {
            let (x, y) = (s[(k, j)], s[(k + 1, j)]);
            s[(k, j)] = g11.conj() * x + g21.conj() * y;
            s[(k + 1, j)] = g12.conj() * x + g22.conj() * y;
        }
        // Columns k, k+1 ← columns·G (rows 0..k+2).
        rotate_cols(&mut s, k, 0..k + 2, (g11, g12, g21, g22));
        rotations.push((k, [g11, g12, g21, g22]));
        s[(k + 1, k)] = Complex64::new(0.0, 0.0);
        s[(k, k)] = Complex64::new(a, omega);
        s[(k + 1, k + 1)] = Complex64::new(a, -omega);
    }
    ComplexSchur { s, rotations }
}

/// Columns k, k+1 of m times G = [g11 g12; g21 g22] on the given rows.
fn rotate_cols(
    m: &mut DMatrix<Complex64>,
    k: usize,
    rows: std::ops::Range<usize>,
    g: (Complex64, Complex64, Complex64, Complex64),
) {
    let (g11, g12, g21, g22) = g;
    for i in rows {
        let (x, y) = (m[(i, k)], m[(i, k + 1)]);
        m[(i, k)] = x * g11 + y * g21;
        m[(i, k + 1)] = x * g12 + y * g22;
    }
}

#[cfg(test)]
mod tests {
    /// `complex_schur` on a worked example (an internal kernel: a unit test, not a doctest).
    #[test]
    #[allow(clippy::float_cmp)] // exact values are meant
    fn complex_schur_example() {
        use crate::numeric::linalg::complex_schur::complex_schur;
        use crate::numeric::linalg::{SchurOptions, real_schur};
        use nalgebra::DMatrix;
        let a = DMatrix::from_row_slice(3, 3, &[0.0, 1.0, 0.0, -2.0, -0.3, 1.0, 0.0, 0.0, -1.0]);
        let cs = complex_schur(&real_schur(&a, SchurOptions::default()).unwrap());
        for i in 0..3 {
            for j in 0..i {
                assert_eq!(cs.s[(i, j)].norm(), 0.0);
            }
        }
        // The diagonal: −1 and the pair −0.15 ± i·√(2 − 0.15²).
        let im = (2.0f64 - 0.0225).sqrt();
        assert!(
            (0..3).any(|k| (cs.s[(k, k)] - num_complex::Complex64::new(-0.15, im)).norm() < 1e-14)
        );
    }
}
