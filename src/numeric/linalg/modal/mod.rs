//! The modal (block-diagonal) form of a state-space system: A = X·Λ·X⁻¹ with Λ block diagonal,
//! each block upper triangular and holding one cluster of close eigenvalues, so that
//! G(s) = D + Σᵢ Ĉᵢ·(sI − Λᵢ)⁻¹·B̂ᵢ (Ĉ = C·X, B̂ = X⁻¹·B) costs O(Σ nᵢ²) per point instead
//! of the Hessenberg solve's O(n²), and a time step costs O(Σ nᵢ²) instead of a dense n×n
//! product.
//!
//! # Method (Golub–Van Loan §7.6.3, Bavely–Stewart)
//! 1. The complex Schur form A = D·Q·Z·S·Zᴴ·Qᵀ·D⁻¹ ([`super::complex_schur`]).
//! 2. Clusters: eigenvalues closer than [`CLUSTER_REL`]·‖A‖ (single linkage) — repeated
//!    eigenvalues, semisimple or defective (a 2×2 Jordan block splits by ~√ε·‖A‖), stay in one
//!    block. S is reordered by adjacent swaps (unitary rotations, as LAPACK `ztrexc`) so each
//!    cluster is contiguous.
//! 3. The off-diagonal blocks are removed by a unit upper-triangular Y from the Sylvester
//!    equations Sᵢᵢ·Z − Z·Sⱼⱼ = −Sᵢⱼ (triangular, solved by substitution).
//!
//! This is the general path ([`ModalForm::from_schur`]), whatever the structure of A. A model
//! with the mechanical structure of [`super::second_order`] gets its modal form from its modes
//! instead ([`SecondOrder::modal_form`](super::second_order::SecondOrder::modal_form): no Schur
//! form, 1×1 blocks except for critical modes); [`ModalForm::new`] (with the model's
//! [`StateMatrix`](super::StateMatrix)) chooses.
//!
//! The form is **used only when it is safe**: blocks of at most [`MAX_BLOCK`], a transformation
//! whose condition estimate ‖Y‖_F·‖Y⁻¹‖_F is at most [`MAX_COND`], and agreement with the
//! Hessenberg evaluation to [`CHECK_REL`] at probe points; otherwise [`ModalForm::from_schur`]
//! returns `None` and the caller keeps the Hessenberg path.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::freqresp::HessenbergResponse;
use super::schur::{SchurOptions, real_schur};
use crate::error::Result;

/// Eigenvalues closer than this times ‖A‖_F share a block (a 2×2 Jordan block of A computed
/// in f64 splits into a pair ~2·√(ε·‖A‖·|coupling|) apart, ~3e-8·‖A‖).
pub const CLUSTER_REL: f64 = 1e-6;
/// Largest block: beyond it the per-point solves are no longer cheap.
pub const MAX_BLOCK: usize = 32;
/// Largest accepted condition estimate ‖Y‖_F·‖Y⁻¹‖_F of the block diagonalisation.
pub const MAX_COND: f64 = 1e6;
/// Largest relative difference from the Hessenberg evaluation at the probe points.
pub const CHECK_REL: f64 = 1e-10;

type C = Complex64;

/// A block of the modal form: rows/columns `start..start + size` of Λ.
#[derive(Clone, Debug)]
pub struct ModalBlock {
    /// First index.
    pub start: usize,
    /// Upper triangular Λᵢ (size × size).
    pub lambda: DMatrix<C>,
}

/// The modal form (see the [module docs](self)).
#[derive(Clone, Debug)]
pub struct ModalForm {
    /// The diagonal blocks of Λ.
    pub blocks: Vec<ModalBlock>,
    /// B̂ = X⁻¹·B (n × m).
    pub b: DMatrix<C>,
    /// Ĉ = C·X (p × n).
    pub c: DMatrix<C>,
    /// X⁻¹, for initial states.
    inverse: Inverse,
    /// D (p × m).
    pub d: DMatrix<f64>,
    /// The condition estimate of the block diagonalisation.
    pub cond: f64,
}

/// X⁻¹ in factored form (for the modal coordinates of an initial state).
#[derive(Clone, Debug)]
enum Inverse {
    /// The Schur path: X⁻¹ = Y⁻¹·Wᴴ·X0⁻¹ with X0⁻¹ = Zᴴ·Qᵀ·D⁻¹ (the Schur basis), W the
    /// reordering rotations, Y the block diagonalisation.
    Schur {
        y_inv: DMatrix<C>,
        w: DMatrix<C>,
        x0_inv: DMatrix<C>,
    },
    /// The second-order path: (η, η̇) = (X_q⁻¹·q, X_q⁻¹·q̇), then per mode k the 2×2 map
    /// `modes[k]` onto the modal coordinates 2k, 2k + 1.
    SecondOrder {
        shapes_inv: DMatrix<f64>,
        modes: Vec<[[C; 2]; 2]>,
    },
}

/// Givens rotation (c real, s complex) with [c s; −s̄ c]·[f; g] = [r; 0] (LAPACK `zlartg`).
fn lartg(f: C, g: C) -> (f64, C) {
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
fn rot_rows(m: &mut DMatrix<C>, i: usize, k: usize, cols: std::ops::Range<usize>, c: f64, s: C) {
    for j in cols {
        let (x, y) = (m[(i, j)], m[(k, j)]);
        m[(i, j)] = x * c + s * y;
        m[(k, j)] = y * c - s.conj() * x;
    }
}

/// The same on two columns, rows `rows`.
fn rot_cols(m: &mut DMatrix<C>, i: usize, k: usize, rows: std::ops::Range<usize>, c: f64, s: C) {
    for r in rows {
        let (x, y) = (m[(r, i)], m[(r, k)]);
        m[(r, i)] = x * c + s * y;
        m[(r, k)] = y * c - s.conj() * x;
    }
}

/// Swaps the adjacent diagonal entries k, k+1 of upper triangular `s` by a unitary rotation,
/// accumulated into the columns of `w` (LAPACK `ztrexc`).
fn swap(s: &mut DMatrix<C>, w: &mut DMatrix<C>, k: usize) {
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

/// Cluster labels of `values` (single linkage: values closer than `tol`, |Δ| ≤ tol, share a
/// cluster, transitively), numbered in order of first appearance.
pub(crate) fn single_linkage(values: &[C], tol: f64) -> Vec<usize> {
    let n = values.len();
    let mut label: Vec<usize> = (0..n).collect();
    fn find(l: &mut [usize], i: usize) -> usize {
        let mut r = i;
        while l[r] != r {
            r = l[r];
        }
        let mut j = i;
        while l[j] != r {
            let next = l[j];
            l[j] = r;
            j = next;
        }
        r
    }
    // sort by real part to link neighbours cheaply: pairs within tol have |Δre| ≤ tol
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| values[a].re.total_cmp(&values[b].re));
    for (x, &i) in order.iter().enumerate() {
        for &j in &order[x + 1..] {
            if values[j].re - values[i].re > tol {
                break;
            }
            if (values[i] - values[j]).norm() <= tol {
                let (ri, rj) = (find(&mut label, i), find(&mut label, j));
                if ri != rj {
                    label[ri.max(rj)] = ri.min(rj);
                }
            }
        }
    }
    let roots: Vec<usize> = (0..n).map(|i| find(&mut label, i)).collect();
    let mut id = vec![usize::MAX; n];
    let mut next = 0;
    roots
        .iter()
        .map(|&r| {
            if id[r] == usize::MAX {
                id[r] = next;
                next += 1;
            }
            id[r]
        })
        .collect()
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
        let cs = super::complex_schur::complex_schur(&real);
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

    /// A modal form in the coordinates of a second-order model's modes (built by
    /// [`SecondOrder::modal_form`](super::second_order::SecondOrder::modal_form)): X⁻¹ maps a
    /// state (q, q̇) to (X_q⁻¹·q, X_q⁻¹·q̇) and then, per mode k, by the 2×2 map `maps[k]` onto
    /// the modal coordinates 2k, 2k + 1.
    pub(crate) fn in_mode_coordinates(
        blocks: Vec<ModalBlock>,
        b: DMatrix<C>,
        c: DMatrix<C>,
        d: DMatrix<f64>,
        cond: f64,
        shapes_inv: DMatrix<f64>,
        maps: Vec<[[C; 2]; 2]>,
    ) -> ModalForm {
        ModalForm {
            blocks,
            b,
            c,
            inverse: Inverse::SecondOrder {
                shapes_inv,
                modes: maps,
            },
            d,
            cond,
        }
    }

    /// Modal coordinates z = X⁻¹·x of a state x.
    pub fn modal_coordinates(&self, x: &[f64]) -> Vec<C> {
        match &self.inverse {
            Inverse::Schur { y_inv, w, x0_inv } => {
                let v =
                    nalgebra::DVector::from_iterator(x.len(), x.iter().map(|v| C::new(*v, 0.0)));
                let z = y_inv * &w.ad_mul(&(x0_inv * &v));
                z.iter().copied().collect()
            }
            Inverse::SecondOrder { shapes_inv, modes } => {
                let dof = shapes_inv.nrows();
                let eta = shapes_inv * nalgebra::DVector::from_column_slice(&x[..dof]);
                let xi = shapes_inv * nalgebra::DVector::from_column_slice(&x[dof..2 * dof]);
                let mut z = Vec::with_capacity(2 * dof);
                for (k, pinv) in modes.iter().enumerate() {
                    z.push(pinv[0][0] * eta[k] + pinv[0][1] * xi[k]);
                    z.push(pinv[1][0] * eta[k] + pinv[1][1] * xi[k]);
                }
                z
            }
        }
    }

    /// Order n.
    pub fn order(&self) -> usize {
        self.b.nrows()
    }

    /// The eigenvalues (Λ's diagonal).
    pub fn eigenvalues(&self) -> Vec<C> {
        self.blocks
            .iter()
            .flat_map(|k| (0..k.lambda.nrows()).map(move |i| k.lambda[(i, i)]))
            .collect()
    }

    /// G(s) (p × m).
    pub fn eval(&self, s: C) -> DMatrix<C> {
        let (p, m) = (self.c.nrows(), self.b.ncols());
        let mut g = self.d.map(|v| C::new(v, 0.0));
        for blk in &self.blocks {
            let k = blk.lambda.nrows();
            let i0 = blk.start;
            for col in 0..m {
                // v = (sI − Λ)⁻¹·B̂[block, col] by back substitution
                let mut v = [C::new(0.0, 0.0); MAX_BLOCK];
                for i in (0..k).rev() {
                    let mut acc = self.b[(i0 + i, col)];
                    for (j, vj) in v.iter().enumerate().take(k).skip(i + 1) {
                        acc += blk.lambda[(i, j)] * vj;
                    }
                    v[i] = acc / (s - blk.lambda[(i, i)]);
                }
                for row in 0..p {
                    let acc: C = v
                        .iter()
                        .take(k)
                        .enumerate()
                        .map(|(i, vi)| self.c[(row, i0 + i)] * vi)
                        .sum();
                    g[(row, col)] += acc;
                }
            }
        }
        g
    }

    /// One channel (input → output, 0-based) as a sum of simple fractions, for fast evaluation
    /// at many points ([`ModalChannel::eval`]).
    pub fn channel(&self, input: usize, output: usize) -> ModalChannel {
        let mut simple = Vec::new();
        let mut pairs = Vec::new();
        let mut general = Vec::new();
        for (bi, blk) in self.blocks.iter().enumerate() {
            let i0 = blk.start;
            let (cr, bc) = (
                |i: usize| self.c[(output, i0 + i)],
                |i: usize| self.b[(i0 + i, input)],
            );
            match blk.lambda.nrows() {
                1 => simple.push((blk.lambda[(0, 0)], cr(0) * bc(0))),
                2 => {
                    let (a, b, t) = (blk.lambda[(0, 0)], blk.lambda[(1, 1)], blk.lambda[(0, 1)]);
                    pairs.push([a, b, cr(0) * bc(0), cr(1) * bc(1), cr(0) * t * bc(1)]);
                }
                _ => general.push(bi),
            }
        }
        ModalChannel {
            d: C::new(self.d[(output, input)], 0.0),
            simple,
            pairs,
            general: general
                .into_iter()
                .map(|bi| {
                    let blk = &self.blocks[bi];
                    let k = blk.lambda.nrows();
                    let i0 = blk.start;
                    (
                        blk.lambda.clone(),
                        (0..k).map(|i| self.c[(output, i0 + i)]).collect(),
                        (0..k).map(|i| self.b[(i0 + i, input)]).collect(),
                    )
                })
                .collect(),
        }
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

/// One channel of a [`ModalForm`]: G(s) = d + Σ r/(s − λ) over the 1×1 blocks, the closed form
/// of each 2×2 block, and a back substitution for larger blocks.
#[derive(Clone, Debug)]
pub struct ModalChannel {
    d: C,
    /// (λ, r) of the 1×1 blocks.
    simple: Vec<(C, C)>,
    /// [a, b, r_a, r_b, r_ab] of the 2×2 blocks [a t; 0 b]: r_a/(s − a) + r_b/(s − b) +
    /// r_ab/((s − a)(s − b)).
    pairs: Vec<[C; 5]>,
    /// Larger blocks: (Λᵢ, Ĉᵢ row, B̂ᵢ column).
    general: Vec<(DMatrix<C>, Vec<C>, Vec<C>)>,
}

impl ModalChannel {
    /// G(s).
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::numeric::linalg::modal::ModalForm;
    /// // 1/(s + 1)² as a 2×2 Jordan block: ẋ₁ = −x₁ + x₂, ẋ₂ = −x₂ + u, y = x₁
    /// let a = DMatrix::from_row_slice(2, 2, &[-1.0, 1.0, 0.0, -1.0]);
    /// let m = ModalForm::new(&a, &DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
    ///     &DMatrix::from_row_slice(1, 2, &[1.0, 0.0]), &DMatrix::zeros(1, 1)).unwrap().unwrap();
    /// let s = num_complex::Complex64::new(0.0, 2.0);
    /// assert!((m.channel(0, 0).eval(s) - 1.0 / ((s + 1.0) * (s + 1.0))).norm() < 1e-15);
    /// ```
    pub fn eval(&self, s: C) -> C {
        let mut g = self.d;
        for &(l, r) in &self.simple {
            g += r / (s - l);
        }
        for &[a, b, ra, rb, rab] in &self.pairs {
            let (ia, ib) = (1.0 / (s - a), 1.0 / (s - b));
            g += ra * ia + rb * ib + rab * ia * ib;
        }
        for (lam, c, b) in &self.general {
            let k = lam.nrows();
            let mut v = vec![C::new(0.0, 0.0); k];
            for i in (0..k).rev() {
                let mut acc = b[i];
                for j in i + 1..k {
                    acc += lam[(i, j)] * v[j];
                }
                v[i] = acc / (s - lam[(i, i)]);
            }
            g += c.iter().zip(&v).map(|(x, y)| x * y).sum::<C>();
        }
        g
    }
}
