//! The modal form by the general path: the complex Schur form, reordered so that each cluster
//! is contiguous, block-diagonalised by Sylvester solves, and checked against the Hessenberg
//! evaluation (see the [module docs](super)).

use nalgebra::DMatrix;

use super::cluster::single_linkage;
use super::form::{C, CHECK_REL, CLUSTER_REL, Inverse, MAX_BLOCK, MAX_COND, ModalBlock, ModalForm};
use crate::error::Result;
use crate::numeric::linalg::freqresp::HessenbergResponse;
use crate::numeric::linalg::schur::{SchurOptions, real_schur};

/// Givens rotation (c real, s complex) with [c s; −s̄ c]·[f; g] = [r; 0] (LAPACK `zlartg`).
pub(crate) fn lartg(f: C, g: C) -> (f64, C) {
    let (fa, ga) = (f.norm(), g.norm());
    if ga == 0.0 {
        return (1.0, C::new(0.0, 0.0));
    }
    if fa == 0.0 {
        return (0.0, g.conj() / ga);
    }
    let nrm = fa.hypot(ga);
    (fa / nrm, (f / fa) * g.conj() / nrm)
}

/// x ← c·x + s·y, y ← c·y − s̄·x (LAPACK `zrot`) on two rows of `m`, columns `cols`.
pub(crate) fn rot_rows(
    m: &mut DMatrix<C>,
    i: usize,
    k: usize,
    cols: std::ops::Range<usize>,
    c: f64,
    s: C,
) {
    for j in cols {
        let (x, y) = (m[(i, j)], m[(k, j)]);
        m[(i, j)] = x * c + s * y;
        m[(k, j)] = y * c - s.conj() * x;
    }
}

/// The same on two columns, rows `rows`.
pub(crate) fn rot_cols(
    m: &mut DMatrix<C>,
    i: usize,
    k: usize,
    rows: std::ops::Range<usize>,
    c: f64,
    s: C,
) {
    for r in rows {
        let (x, y) = (m[(r, i)], m[(r, k)]);
        m[(r, i)] = x * c + s * y;
        m[(r, k)] = y * c - s.conj() * x;
    }
}

/// Swaps the adjacent diagonal entries k, k+1 of upper triangular `s` by a unitary rotation,
/// accumulated into the columns of `w` (LAPACK `ztrexc`).
pub(crate) fn swap(s: &mut DMatrix<C>, w: &mut DMatrix<C>, k: usize) {
    let n = s.nrows();
    let (t11, t22) = (s[(k, k)], s[(k + 1, k + 1)]);
    let (c, sn) = lartg(s[(k, k + 1)], t22 - t11);
    if k + 2 < n {
        rot_rows(s, k, k + 1, k + 2..n, c, sn);
    }
    rot_cols(s, k, k + 1, 0..k, c, sn.conj());
    s[(k, k)] = t22;
    s[(k + 1, k + 1)] = t11;
    rot_cols(w, k, k + 1, 0..n, c, sn.conj());
}

/// Cluster labels of the diagonal of `s` (single linkage at distance `tol`), numbered in order
/// of first appearance.
fn clusters(s: &DMatrix<C>, tol: f64) -> Vec<usize> {
    let values: Vec<C> = (0..s.nrows()).map(|i| s[(i, i)]).collect();
    single_linkage(&values, tol)
}

/// Solves S_ii·Z − Z·S_jj = −S_ij for Z (the diagonal blocks `(i0, i1)` and `(j0, j1)` of
/// upper triangular `s`, disjoint spectra), column by column; Z row-major into `z`.
fn sylvester(s: &DMatrix<C>, (i0, i1): (usize, usize), (j0, j1): (usize, usize), z: &mut [C]) {
    let (p, q) = (i1 - i0, j1 - j0);
    for col in 0..q {
        let mu = s[(j0 + col, j0 + col)];
        // (S_ii − μI)·z_col = −S_ij[:, col] + Σ_{r<col} z_r·S_jj[r, col], by back substitution
        for i in (0..p).rev() {
            let mut acc = -s[(i0 + i, j0 + col)];
            for r in 0..col {
                acc += z[i * q + r] * s[(j0 + r, j0 + col)];
            }
            for k in i + 1..p {
                acc -= s[(i0 + i, i0 + k)] * z[k * q + col];
            }
            z[i * q + col] = acc / (s[(i0 + i, i0 + i)] - mu);
        }
    }
}

/// Frobenius norm of a complex matrix.
fn fro(m: &DMatrix<C>) -> f64 {
    m.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt()
}

impl ModalForm {
    /// The modal form of (A, B, C, D) by the general (Schur) path whatever the structure of A,
    /// or `None` when it is not safe (see the module docs). [`ModalForm::new`] takes a
    /// second-order model's modes instead when A has that structure.
    ///
    /// Errors: the Schur step's.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::numeric::linalg::modal::ModalForm;
    /// // ẍ = u (a double integrator: a Jordan block at 0) next to ẋ = −x + u: one block of
    /// // size 2 and one of size 1.
    /// let a = DMatrix::from_row_slice(3, 3, &[0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0]);
    /// let b = DMatrix::from_row_slice(3, 1, &[0.0, 1.0, 1.0]);
    /// let c = DMatrix::from_row_slice(1, 3, &[1.0, 0.0, 1.0]);
    /// let m = ModalForm::from_schur(&a, &b, &c, &DMatrix::zeros(1, 1)).unwrap().unwrap();
    /// let mut sizes: Vec<usize> = m.blocks.iter().map(|k| k.lambda.nrows()).collect();
    /// sizes.sort();
    /// assert_eq!(sizes, vec![1, 2]);
    /// // G(s) = 1/s² + 1/(s + 1) at s = j
    /// let s = num_complex::Complex64::new(0.0, 1.0);
    /// let g = m.eval(s)[(0, 0)];
    /// assert!((g - (1.0 / (s * s) + 1.0 / (s + 1.0))).norm() < 1e-14);
    /// ```
    pub fn from_schur(
        a: &DMatrix<f64>,
        b: &DMatrix<f64>,
        c: &DMatrix<f64>,
        d: &DMatrix<f64>,
    ) -> Result<Option<ModalForm>> {
        let n = a.nrows();
        if n == 0 {
            return Ok(None);
        }
        let real = real_schur(a, SchurOptions::default())?;
        let Some(q) = &real.q else {
            return Ok(None);
        };
        let cs = crate::numeric::linalg::complex_schur::complex_schur(&real);
        let mut s = cs.s.clone();
        // X0 = D·Q·Z as a complex matrix: columns of Q (scaled by D) rotated by Z.
        let mut x0 = DMatrix::<C>::from_fn(n, n, |i, j| C::new(real.d[i] * q[(i, j)], 0.0));
        for &(k, [g11, g12, g21, g22]) in &cs.rotations {
            for i in 0..n {
                let (u, v) = (x0[(i, k)], x0[(i, k + 1)]);
                x0[(i, k)] = u * g11 + v * g21;
                x0[(i, k + 1)] = u * g12 + v * g22;
            }
        }
        // X0⁻¹ = Zᴴ·Qᵀ·D⁻¹.
        let mut x0_inv = DMatrix::<C>::from_fn(n, n, |i, j| C::new(q[(j, i)] / real.d[j], 0.0));
        for &(k, [g11, g12, g21, g22]) in &cs.rotations {
            for j in 0..n {
                let (u, v) = (x0_inv[(k, j)], x0_inv[(k + 1, j)]);
                x0_inv[(k, j)] = g11.conj() * u + g21.conj() * v;
                x0_inv[(k + 1, j)] = g12.conj() * u + g22.conj() * v;
            }
        }
        let norm_a = a.norm().max(f64::MIN_POSITIVE);
        let labels = clusters(&s, CLUSTER_REL * norm_a);
        // Reorder (bubble sort by label with adjacent swaps) so each cluster is contiguous.
        let mut w = DMatrix::<C>::identity(n, n);
        let mut lab = labels;
        for i in 0..n {
            for k in (i..n - 1).rev() {
                if lab[k + 1] < lab[k] {
                    swap(&mut s, &mut w, k);
                    lab.swap(k, k + 1);
                }
            }
        }
        // The block ranges.
        let mut ranges: Vec<(usize, usize)> = Vec::new();
        let mut i = 0;
        while i < n {
            let mut j = i + 1;
            while j < n && lab[j] == lab[i] {
                j += 1;
            }
            ranges.push((i, j));
            i = j;
        }
        if ranges.iter().any(|(a, b)| b - a > MAX_BLOCK) {
            return Ok(None);
        }
        // Block diagonalisation: S ← Y⁻¹·S·Y.
        let mut y = DMatrix::<C>::identity(n, n);
        let qn = ranges.len();
        let mut z = vec![C::new(0.0, 0.0); MAX_BLOCK * MAX_BLOCK];
        for jb in 1..qn {
            let (j0, j1) = ranges[jb];
            let kj = j1 - j0;
            for ib in (0..jb).rev() {
                let (i0, i1) = ranges[ib];
                let ki = i1 - i0;
                sylvester(&s, (i0, i1), (j0, j1), &mut z);
                // S_ij ← 0; S_ik ← S_ik − Z·S_jk for the columns right of block j
                for cc in j0..j1 {
                    for r in i0..i1 {
                        s[(r, cc)] = C::new(0.0, 0.0);
                    }
                }
                for col in j1..n {
                    for r in 0..ki {
                        let mut acc = C::new(0.0, 0.0);
                        for c in 0..kj {
                            acc += z[r * kj + c] * s[(j0 + c, col)];
                        }
                        s[(i0 + r, col)] -= acc;
                    }
                }
                // Y[:, j] ← Y[:, j] + Y[:, i]·Z (Y is unit upper triangular: rows < i1)
                for c in 0..kj {
                    for row in 0..i1 {
                        let mut acc = C::new(0.0, 0.0);
                        for r in 0..ki {
                            acc += y[(row, i0 + r)] * z[r * kj + c];
                        }
                        y[(row, j0 + c)] += acc;
                    }
                }
            }
        }
        // Y is unit upper triangular: its inverse by back substitution.
        let mut y_inv = DMatrix::<C>::identity(n, n);
        for col in 0..n {
            for i in (0..col).rev() {
                let mut acc = C::new(0.0, 0.0);
                for k in i + 1..=col {
                    acc += y[(i, k)] * y_inv[(k, col)];
                }
                y_inv[(i, col)] = -acc;
            }
        }
        let cond = fro(&y) * fro(&y_inv) / n as f64;
        if !(cond.is_finite() && cond <= MAX_COND) {
            return Ok(None);
        }
        // Ĉ = ((C·X0)·W)·Y and B̂ = Y⁻¹·(Wᴴ·(X0⁻¹·B)): thin products only.
        let bc = b.map(|v| C::new(v, 0.0));
        let cc = c.map(|v| C::new(v, 0.0));
        let c_hat = &(&(&cc * &x0) * &w) * &y;
        let b_hat = &y_inv * &(w.ad_mul(&(&x0_inv * &bc)));
        let blocks = ranges
            .iter()
            .map(|&(i0, i1)| ModalBlock {
                start: i0,
                lambda: s.view((i0, i0), (i1 - i0, i1 - i0)).into_owned(),
            })
            .collect();
        let form = ModalForm {
            blocks,
            b: b_hat,
            c: c_hat,
            inverse: Inverse::Schur { y_inv, w, x0_inv },
            d: d.clone(),
            cond,
        };
        if !form.agrees_with_hessenberg(a, b, c, d)? {
            return Ok(None);
        }
        Ok(Some(form))
    }

    /// Compares with the Hessenberg evaluation at probe points spread over the eigenvalues'
    /// frequency range (and off the axis).
    fn agrees_with_hessenberg(
        &self,
        a: &DMatrix<f64>,
        b: &DMatrix<f64>,
        c: &DMatrix<f64>,
        d: &DMatrix<f64>,
    ) -> Result<bool> {
        let h = HessenbergResponse::new(a, b, c, d)?;
        let ev = self.eigenvalues();
        let top = ev.iter().map(|z| z.norm()).fold(0.0, f64::max).max(1e-300);
        // from the smallest eigenvalue magnitude (not below 1e-4 of the largest: a cluster at
        // 0, e.g. a split Jordan block, would put the probes where G is huge) to the largest
        let low = ev
            .iter()
            .map(|z| z.norm())
            .filter(|x| *x > 1e-4 * top)
            .fold(f64::INFINITY, f64::min)
            .min(top);
        let probes: Vec<C> = (0..8)
            .map(|i| {
                let w = low * (top / low).powf(i as f64 / 7.0) * 1.37;
                C::new(0.3 * w, w)
            })
            .collect();
        for s in probes {
            let (gm, gh) = (self.eval(s), h.eval(s));
            let scale = gh.iter().map(|z| z.norm()).fold(0.0, f64::max);
            let diff = (&gm - &gh).iter().map(|z| z.norm()).fold(0.0, f64::max);
            if diff.is_nan() || diff > CHECK_REL * scale.max(f64::MIN_POSITIVE) {
                return Ok(false);
            }
        }
        Ok(true)
    }
}
