//! Rank-revealing QR: Householder QR with column pivoting (Businger & Golub 1965), stopped
//! when every remaining column is negligible.
//!
//! For an r×c block X: Qᵀ·X·P = [R₁₁ R₁₂; 0 R₂₂] with the largest remaining column moved to
//! the front at every step. The numerical rank ρ is the number of steps taken before the
//! largest remaining column norm falls to `tol` or below; then ‖R₂₂‖_F ≤ √c·tol, and setting
//! R₂₂ to zero is a perturbation of X of that size (a backward-stable rank decision). Column
//! norms are downdated (with recomputation when cancellation makes the downdate unreliable,
//! the rule of LAPACK's `dgeqp3`).

use nalgebra::DMatrix;

use super::householder::Reflector;

/// The result of [`rank_revealing_qr`].
#[derive(Clone, Debug)]
pub struct RankQr {
    /// Numerical rank ρ.
    pub rank: usize,
    /// The ρ reflectors (in row coordinates of the block: offset k for the k-th) with
    /// Qᵀ = P_{ρ−1}⋯P₀.
    pub reflectors: Vec<Reflector>,
    /// Qᵀ·X·P, upper trapezoidal in its first ρ rows; rows ρ.. are exactly zero.
    pub r: DMatrix<f64>,
    /// The column permutation: column j of R is column `perm[j]` of X.
    pub perm: Vec<usize>,
    /// Largest remaining column norm when the factorisation stopped (0 at full rank).
    pub residual: f64,
}

/// Rank-revealing QR of `x` with absolute tolerance `tol` (see the [module docs](self)).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::rrqr::rank_revealing_qr;
/// // Rank 2: the third column is the sum of the first two.
/// let x = DMatrix::from_row_slice(3, 3, &[1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 1.0, 1.0, 2.0]);
/// let f = rank_revealing_qr(&x, 1e-12);
/// assert_eq!(f.rank, 2);
/// assert!(f.residual < 1e-15);
/// ```
pub fn rank_revealing_qr(x: &DMatrix<f64>, tol: f64) -> RankQr {
    let (rows, cols) = x.shape();
    let mut r = x.clone();
    let mut perm: Vec<usize> = (0..cols).collect();
    let mut norms: Vec<f64> = (0..cols).map(|j| col_norm(&r, j, 0)).collect();
    let mut reference = norms.clone();
    let mut reflectors = Vec::new();
    let steps = rows.min(cols);
    let mut residual = 0.0;
    for k in 0..steps {
        let (jmax, &nmax) = norms[k..]
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(b.1))
            .map(|(j, v)| (j + k, v))
            .unwrap_or((k, &0.0));
        if nmax <= tol {
            residual = nmax;
            break;
        }
        if jmax != k {
            r.swap_columns(k, jmax);
            perm.swap(k, jmax);
            norms.swap(k, jmax);
            reference.swap(k, jmax);
        }
        let v: Vec<f64> = r.column(k).rows_range(k..rows).iter().copied().collect();
        let (refl, beta) = Reflector::new(k, &v);
        refl.apply_left(&mut r, k + 1..cols);
        r[(k, k)] = beta;
        for i in k + 1..rows {
            r[(i, k)] = 0.0;
        }
        reflectors.push(refl);
        // Downdate the remaining column norms.
        for j in k + 1..cols {
            if norms[j] == 0.0 {
                continue;
            }
            let t = (r[(k, j)] / norms[j]).abs();
            let t = (1.0 - t * t).max(0.0);
            let ratio = norms[j] / reference[j];
            if t * ratio * ratio <= f64::EPSILON.sqrt() {
                norms[j] = col_norm(&r, j, k + 1);
                reference[j] = norms[j];
            } else {
                norms[j] *= t.sqrt();
            }
        }
    }
    let rank = reflectors.len();
    if rank == steps {
        residual = 0.0;
    }
    for j in rank..cols {
        for i in rank..rows {
            r[(i, j)] = 0.0;
        }
    }
    RankQr {
        rank,
        reflectors,
        r,
        perm,
        residual,
    }
}

/// 2-norm of column j from row `from` down (overflow-safe).
fn col_norm(m: &DMatrix<f64>, j: usize, from: usize) -> f64 {
    super::norms::frobenius(m.column(j).rows_range(from..m.nrows()).iter())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reconstructs_and_reveals_rank() {
        // 5×4 of rank 2: X = U·V with U 5×2, V 2×4, plus a 1e-14 perturbation.
        let u = DMatrix::from_fn(5, 2, |i, j| (i as f64 + 1.0).powi(j as i32 + 1) / 10.0);
        let v = DMatrix::from_fn(2, 4, |i, j| ((i + 2 * j) as f64).sin());
        let mut x = &u * &v;
        x[(4, 3)] += 1e-14;
        let f = rank_revealing_qr(&x, 1e-10);
        assert_eq!(f.rank, 2);
        // Qᵀ X P = R up to the discarded block.
        let mut qtx = x.clone();
        for refl in &f.reflectors {
            refl.apply_left(&mut qtx, 0..4);
        }
        let xp = DMatrix::from_fn(5, 4, |i, j| qtx[(i, f.perm[j])]);
        assert!((xp - &f.r).norm() < 1e-10);
        let full = rank_revealing_qr(&x, 0.0);
        assert_eq!(full.rank, 4);
        assert!(rank_revealing_qr(&DMatrix::zeros(3, 2), 0.0).rank == 0);
        assert!(rank_revealing_qr(&DMatrix::zeros(0, 2), 1.0).rank == 0);
    }
}
