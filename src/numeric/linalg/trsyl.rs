//! The quasi-triangular Sylvester and Stein kernels of Bartels–Stewart (LAPACK `dtrsyl`
//! style, real arithmetic): with Tₐ and T_b upper quasi-triangular (1×1 and 2×2 diagonal
//! blocks), solve
//!
//! * continuous: Tₐ·Z + Z·T_b = G,
//! * discrete:   Tₐ·Z·T_b − Z = G,
//!
//! in place of G. The columns of Z are found block by block from the left (a matrix–vector
//! product brings in the blocks already known), each block column by a back substitution over
//! Tₐ's blocks from the bottom, one 1×1 … 4×4 system per pair of diagonal blocks (Gaussian
//! elimination with complete pivoting; a pivot below `tiny` is raised to it, as LAPACK's
//! `dlasy2` does, so a near-singular equation gives large but finite numbers — the callers
//! reject singular equations before, naming the eigenvalues).
//!
//! All loops run down contiguous columns of the column-major storage.

use nalgebra::DMatrix;

use super::schur::blocks_of;

/// Which of the two equations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Equation {
    /// Tₐ·Z + Z·T_b = G.
    Continuous,
    /// Tₐ·Z·T_b − Z = G.
    Discrete,
}

/// Solves the equation in place of `g` (see the module docs). `tiny` is the smallest pivot
/// allowed in the small systems (e.g. ε·(‖Tₐ‖ + ‖T_b‖)).
pub(crate) fn solve(
    ta: &DMatrix<f64>,
    tb: &DMatrix<f64>,
    g: &mut DMatrix<f64>,
    eq: Equation,
    tiny: f64,
) {
    let (m, n) = (ta.nrows(), tb.nrows());
    if m == 0 || n == 0 {
        return;
    }
    let a_blocks = blocks_of(ta);
    let tas = ta.as_slice();
    let mut scratch = vec![0.0; 2 * m];
    for (l, bl) in blocks_of(tb) {
        // Bring in the columns already solved: G_l −= Z_{<l}·T_b[<l, l] (continuous), or
        // G_l −= Tₐ·(Z_{<l}·T_b[<l, l]) (discrete).
        if l > 0 {
            let (done, rest) = g.as_mut_slice().split_at_mut(l * m);
            for c in 0..bl {
                let col = &mut scratch[c * m..(c + 1) * m];
                col.iter_mut().for_each(|x| *x = 0.0);
                for j in 0..l {
                    let t = tb[(j, l + c)];
                    if t != 0.0 {
                        axpy(col, -t, &done[j * m..(j + 1) * m]);
                    }
                }
                let target = &mut rest[c * m..(c + 1) * m];
                match eq {
                    Equation::Continuous => axpy(target, 1.0, col),
                    Equation::Discrete => {
                        // target += Tₐ·col (Tₐ upper Hessenberg).
                        for (k, &v) in col.iter().enumerate() {
                            if v != 0.0 {
                                let hi = (k + 2).min(m);
                                axpy(&mut target[..hi], v, &tas[k * m..k * m + hi]);
                            }
                        }
                    }
                }
            }
        }
        // The block column: Tₐ·Z_l + Z_l·S = G_l, or Tₐ·Z_l·S − Z_l = G_l, S = T_b[l, l].
        let mut s = [[0.0; 2]; 2];
        for (r, row) in s.iter_mut().enumerate().take(bl) {
            for (c, x) in row.iter_mut().enumerate().take(bl) {
                *x = tb[(l + r, l + c)];
            }
        }
        let gs = g.as_mut_slice();
        for &(k, ak) in a_blocks.iter().rev() {
            let mut a = [[0.0; 2]; 2];
            for (r, row) in a.iter_mut().enumerate().take(ak) {
                for (c, x) in row.iter_mut().enumerate().take(ak) {
                    *x = ta[(k + r, k + c)];
                }
            }
            // Right-hand side: rows k.., columns l.. of G (already updated below).
            let mut rhs = [0.0; 4];
            for c in 0..bl {
                for r in 0..ak {
                    rhs[c * ak + r] = gs[(l + c) * m + k + r];
                }
            }
            let z = small_solve(&a, ak, &s, bl, eq, &rhs, tiny);
            for c in 0..bl {
                for r in 0..ak {
                    gs[(l + c) * m + k + r] = z[c * ak + r];
                }
            }
            if k == 0 {
                continue;
            }
            // Update the rows above: G[..k, l+c] −= Tₐ[..k, k..k+ak]·W[:, c], with W = Z_k
            // (continuous) or Z_k·S (discrete).
            for c in 0..bl {
                for r in 0..ak {
                    let w = match eq {
                        Equation::Continuous => z[c * ak + r],
                        Equation::Discrete => (0..bl).map(|j| z[j * ak + r] * s[j][c]).sum(),
                    };
                    if w != 0.0 {
                        let col = (l + c) * m;
                        let acol = (k + r) * m;
                        axpy(&mut gs[col..col + k], -w, &tas[acol..acol + k]);
                    }
                }
            }
        }
    }
}

/// y += α·x.
#[inline]
fn axpy(y: &mut [f64], alpha: f64, x: &[f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += alpha * xi;
    }
}

/// The small system for one pair of blocks: A·Z + Z·S = H (continuous) or A·Z·S − Z = H
/// (discrete), A p×p, S q×q, Z and H p×q stored column-major in 4 slots.
#[allow(clippy::needless_range_loop)] // Kronecker indices
fn small_solve(
    a: &[[f64; 2]; 2],
    p: usize,
    s: &[[f64; 2]; 2],
    q: usize,
    eq: Equation,
    h: &[f64; 4],
    tiny: f64,
) -> [f64; 4] {
    let dim = p * q;
    // vec(A·Z) = (I ⊗ A)·vec Z, vec(Z·S) = (Sᵀ ⊗ I)·vec Z, vec(A·Z·S) = (Sᵀ ⊗ A)·vec Z.
    let mut k = [[0.0; 4]; 4];
    for c in 0..q {
        for r in 0..p {
            let row = c * p + r;
            for c2 in 0..q {
                for r2 in 0..p {
                    let col = c2 * p + r2;
                    let v = match eq {
                        Equation::Continuous => {
                            let mut v = 0.0;
                            if c == c2 {
                                v += a[r][r2];
                            }
                            if r == r2 {
                                v += s[c2][c];
                            }
                            v
                        }
                        Equation::Discrete => {
                            a[r][r2] * s[c2][c] - if row == col { 1.0 } else { 0.0 }
                        }
                    };
                    k[row][col] = v;
                }
            }
        }
    }
    let mut x = [0.0; 4];
    x[..dim].copy_from_slice(&h[..dim]);
    gauss_complete(&mut k, &mut x, dim, tiny);
    x
}

/// Gaussian elimination with complete pivoting on a dim×dim system (dim ≤ 4), pivots below
/// `tiny` raised to it.
#[allow(clippy::needless_range_loop)] // row operations on a 4×4 array
fn gauss_complete(k: &mut [[f64; 4]; 4], x: &mut [f64; 4], dim: usize, tiny: f64) {
    let mut perm = [0usize, 1, 2, 3];
    for i in 0..dim {
        let (mut pr, mut pc, mut big) = (i, i, -1.0);
        for (r, row) in k.iter().enumerate().take(dim).skip(i) {
            for (c, v) in row.iter().enumerate().take(dim).skip(i) {
                if v.abs() > big {
                    (pr, pc, big) = (r, c, v.abs());
                }
            }
        }
        k.swap(i, pr);
        x.swap(i, pr);
        if pc != i {
            for row in k.iter_mut() {
                row.swap(i, pc);
            }
            perm.swap(i, pc);
        }
        if k[i][i].abs() < tiny {
            k[i][i] = if k[i][i] < 0.0 { -tiny } else { tiny };
        }
        for r in i + 1..dim {
            let f = k[r][i] / k[i][i];
            if f != 0.0 {
                for c in i..dim {
                    k[r][c] -= f * k[i][c];
                }
                x[r] -= f * x[i];
            }
        }
    }
    for i in (0..dim).rev() {
        let mut v = x[i];
        for c in i + 1..dim {
            v -= k[i][c] * x[c];
        }
        x[i] = v / k[i][i];
    }
    let mut out = [0.0; 4];
    for i in 0..dim {
        out[perm[i]] = x[i];
    }
    *x = out;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::linalg::{SchurOptions, real_schur};

    fn random(n: usize, seed: u64) -> DMatrix<f64> {
        let mut state = seed;
        DMatrix::from_fn(n, n, |_, _| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        })
    }

    fn schur_t(a: &DMatrix<f64>) -> DMatrix<f64> {
        let opts = SchurOptions {
            balance: false,
            ..SchurOptions::default()
        };
        real_schur(a, opts).unwrap().t
    }

    #[test]
    fn both_equations_on_random_quasi_triangular_matrices() {
        // Random matrices have complex pairs: 2×2 blocks in both factors.
        for (m, n) in [(1, 1), (2, 3), (7, 5), (12, 12)] {
            let ta = schur_t(&random(m, 1 + m as u64));
            let tb = schur_t(&random(n, 100 + n as u64)) * 0.5;
            let g = DMatrix::from_fn(m, n, |i, j| (i as f64 + 1.0) - 0.3 * j as f64);
            let mut z = g.clone();
            solve(&ta, &tb, &mut z, Equation::Continuous, 1e-300);
            let r = &ta * &z + &z * &tb - &g;
            assert!(r.norm() < 1e-12 * g.norm(), "{m}×{n}: {}", r.norm());
            let mut z = g.clone();
            solve(&ta, &tb, &mut z, Equation::Discrete, 1e-300);
            let r = &ta * &z * &tb - &z - &g;
            assert!(r.norm() < 1e-12 * g.norm(), "{m}×{n}: {}", r.norm());
        }
    }
}
