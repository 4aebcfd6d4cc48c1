//! Recognition of the second-order structure in A, and the modes it yields (see the
//! [module docs](super)).

use nalgebra::{DMatrix, SymmetricEigen};
use num_complex::Complex64;

use super::circulant;
use super::sparse::ColumnSparse;

/// Relative asymmetry accepted in the symmetrised stiffness and damping (rounding of the
/// model's own construction, e.g. M⁻¹K formed in floating point).
pub const SYM_REL: f64 = 64.0 * f64::EPSILON;

/// Growth factor of the snapping tolerance (as [`crate::numeric::linalg::structure`]'s cluster
/// radius).
const GROWTH: f64 = 64.0;

/// One mode η̈ + γη̇ + λη = … of a second-order model.
#[derive(Clone, Debug, PartialEq)]
pub struct SecondOrderMode {
    /// Stiffness λ (rad²/s²): an eigenvalue of G.
    pub stiffness: f64,
    /// Damping γ (1/s): the matching eigenvalue of E.
    pub damping: f64,
    /// The two eigenvalues of A of this mode: the upper one of a complex pair first; for a
    /// real pair the one nearer 0 first; equal for a critical mode.
    pub roots: [Complex64; 2],
    /// True when the two roots are one double eigenvalue with one eigenvector (a Jordan block).
    pub critical: bool,
}

/// A state-space matrix recognised as second order (see the [module docs](super)).
#[derive(Clone, Debug)]
pub struct SecondOrder {
    /// Degrees of freedom d (A is 2d × 2d).
    pub dof: usize,
    /// X_q = Δ⁻¹·V (d × d): column k is mode k's shape in the position coordinates.
    pub shapes: DMatrix<f64>,
    /// X_q⁻¹ = Vᵀ·Δ.
    pub shapes_inv: DMatrix<f64>,
    /// The modes, in order of increasing stiffness.
    pub modes: Vec<SecondOrderMode>,
    /// ν = max(‖A‖₁, ‖A‖∞): the scale of the tolerances.
    pub scale: f64,
    /// δ: the diagonal of the symmetrising similarity Δ (X_q = Δ⁻¹·V).
    pub(super) delta: Vec<f64>,
    /// G = −A₂₁ and E = −A₂₂ by columns, when both are sparse (see [`SPARSE_PER_COLUMN`]).
    pub(super) coupling: Option<(ColumnSparse, ColumnSparse)>,
    /// G and E are symmetric circulants (Δ = I) and the shapes their Fourier modes: every
    /// block of a function of A is circulant (see `circulant.rs`).
    pub(super) circulant: bool,
}

/// G and E are kept sparse (products in O(nnz·d)) when each has at most this many non-zero
/// entries per column on average: a chain has 3, a ring 3, a square grid 5.
pub const SPARSE_PER_COLUMN: usize = 8;

/// The absolute tolerance within which values of a symmetric d×d matrix of norm `norm` are
/// equal (or 0): 64·(2d)·ε·norm — the cluster radius of a simple eigenvalue of A.
pub fn snap_tol(dof: usize, norm: f64) -> f64 {
    GROWTH * (2 * dof) as f64 * f64::EPSILON * norm
}

/// max row sum of |m| (m symmetric: also the 1-norm).
fn norm_inf(m: &DMatrix<f64>) -> f64 {
    m.row_iter()
        .map(|r| r.iter().map(|x| x.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// The diagonal δ making Δ·G·Δ⁻¹ and Δ·E·Δ⁻¹ symmetric, or `None`.
fn symmetrizer(g: &DMatrix<f64>, e: &DMatrix<f64>) -> Option<Vec<f64>> {
    let d = g.nrows();
    let close = |x: f64, y: f64| (x - y).abs() <= SYM_REL * x.abs().max(y.abs());
    let symmetric = |m: &DMatrix<f64>| (0..d).all(|j| (0..j).all(|i| close(m[(i, j)], m[(j, i)])));
    if symmetric(g) && symmetric(e) {
        return Some(vec![1.0; d]);
    }
    // δⱼ² = δᵢ²·mᵢⱼ/mⱼᵢ along a spanning forest of the coupling graph (G, else E).
    let mut m2 = vec![f64::NAN; d];
    for root in 0..d {
        if !m2[root].is_nan() {
            continue;
        }
        m2[root] = 1.0;
        let mut stack = vec![root];
        while let Some(i) = stack.pop() {
            for j in 0..d {
                if j == i || !m2[j].is_nan() {
                    continue;
                }
                let ratio = if g[(i, j)] != 0.0 || g[(j, i)] != 0.0 {
                    g[(i, j)] / g[(j, i)]
                } else if e[(i, j)] != 0.0 || e[(j, i)] != 0.0 {
                    e[(i, j)] / e[(j, i)]
                } else {
                    continue;
                };
                let v = m2[i] * ratio;
                if !(v.is_finite() && v > 0.0) {
                    return None;
                }
                m2[j] = v;
                stack.push(j);
            }
        }
    }
    let delta: Vec<f64> = m2.iter().map(|v| v.sqrt()).collect();
    let ok = |m: &DMatrix<f64>| {
        (0..d).all(|j| {
            (0..j).all(|i| {
                close(
                    delta[i] * m[(i, j)] / delta[j],
                    delta[j] * m[(j, i)] / delta[i],
                )
            })
        })
    };
    (ok(g) && ok(e)).then_some(delta)
}

/// Δ·M·Δ⁻¹, symmetrised.
fn symmetrized(m: &DMatrix<f64>, delta: &[f64]) -> DMatrix<f64> {
    let d = m.nrows();
    DMatrix::from_fn(d, d, |i, j| {
        0.5 * (delta[i] * m[(i, j)] / delta[j] + delta[j] * m[(j, i)] / delta[i])
    })
}

/// Symmetric eigen decomposition with an iteration cap, eigenvalues ascending.
fn sym_eig(m: DMatrix<f64>) -> Option<(Vec<f64>, DMatrix<f64>)> {
    let d = m.nrows();
    let eig = SymmetricEigen::try_new(m, f64::EPSILON, 64 * d.max(8))?;
    let mut order: Vec<usize> = (0..d).collect();
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let values = order.iter().map(|&k| eig.eigenvalues[k]).collect();
    let vectors = DMatrix::from_fn(d, d, |i, j| eig.eigenvectors[(i, order[j])]);
    Some((values, vectors))
}

/// Groups of consecutive sorted values within `tol` (single linkage): index ranges.
fn runs(values: &[f64], tol: f64) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < values.len() {
        let mut j = i + 1;
        while j < values.len() && values[j] - values[j - 1] <= tol {
            j += 1;
        }
        out.push((i, j));
        i = j;
    }
    out
}

/// Sets every member of each run to the run's mean, and values within `tol` of 0 to 0.
fn snap(values: &mut [f64], ranges: &[(usize, usize)], tol: f64) {
    for &(a, b) in ranges {
        let mut m = values[a..b].iter().sum::<f64>() / (b - a) as f64;
        if m.abs() <= tol || values[a..b].iter().any(|v| v.abs() <= tol) {
            m = 0.0;
        }
        values[a..b].iter_mut().for_each(|v| *v = m);
    }
}

impl SecondOrderMode {
    /// The mode with stiffness λ and damping γ; `critical_tol` bounds |μ₁ − μ₂| for a double
    /// root.
    fn new(stiffness: f64, damping: f64, critical_tol: f64) -> SecondOrderMode {
        // μ = 2^e·ν with ν² + (γ/2^e)ν + λ/2^(2e) = 0, 2^e near max(|γ|, √|λ|): exact
        // scaling, and no square overflows or underflows
        use crate::numeric::balance::{exponent, ldexp};
        let e = exponent(damping.abs().max(stiffness.abs().sqrt())).unwrap_or(0);
        let (l, g) = (ldexp(stiffness, -2 * e), ldexp(damping, -e));
        let c = |re: f64, im: f64| Complex64::new(ldexp(re, e), ldexp(im, e));
        let unit = ldexp(1.0, e);
        // disc = γ² − 4λ rounded once (γ² exact in the fused multiply-add, 4λ exact)
        let disc = g.mul_add(g, -4.0 * l);
        if disc.abs().sqrt() * unit <= critical_tol {
            let mu = c(-0.5 * g, 0.0);
            return SecondOrderMode {
                stiffness,
                damping,
                roots: [mu, mu],
                critical: true,
            };
        }
        let roots = if disc < 0.0 {
            let w = 0.5 * (-disc).sqrt();
            [c(-0.5 * g, w), c(-0.5 * g, -w)]
        } else {
            // q = −(γ + sign(γ)·√disc)/2 is the root of larger magnitude, λ/q the other
            let sq = disc.sqrt();
            let q = -0.5 * (g + if g >= 0.0 { sq } else { -sq });
            let small = if q == 0.0 { 0.0 } else { l / q };
            [c(small, 0.0), c(q, 0.0)]
        };
        SecondOrderMode {
            stiffness,
            damping,
            roots,
            critical: false,
        }
    }

    /// The mode's 2×2 block [[0, 1], [−λ, −γ]] in the coordinates (η, η̇).
    pub fn block(&self) -> [[f64; 2]; 2] {
        [[0.0, 1.0], [-self.stiffness, -self.damping]]
    }
}

impl SecondOrder {
    /// Recognises the second-order structure of `a` (see the [module docs](super)); `None` when
    /// `a` does not have it (or the symmetric eigenproblem does not converge, practically
    /// never). `a` must be finite.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::numeric::linalg::second_order::SecondOrder;
    /// // Two unit masses between walls, springs k = 1, Rayleigh damping E = 0.1·G:
    /// // G = [[2, −1], [−1, 2]], modes λ = 1, 3 with γ = 0.1, 0.3.
    /// let a = DMatrix::from_row_slice(4, 4, &[
    ///     0.0, 0.0, 1.0, 0.0,
    ///     0.0, 0.0, 0.0, 1.0,
    ///     -2.0, 1.0, -0.2, 0.1,
    ///     1.0, -2.0, 0.1, -0.2,
    /// ]);
    /// let so = SecondOrder::detect(&a).unwrap();
    /// assert_eq!(so.dof, 2);
    /// assert!((so.modes[0].stiffness - 1.0).abs() < 1e-15 && (so.modes[1].stiffness - 3.0).abs() < 1e-15);
    /// assert!((so.modes[1].damping - 0.3).abs() < 1e-15);
    /// // a general matrix is not second order
    /// assert!(SecondOrder::detect(&DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 0.0])).is_none());
    /// ```
    pub fn detect(a: &DMatrix<f64>) -> Option<SecondOrder> {
        SecondOrder::detect_with(a, true)
    }

    /// [`SecondOrder::detect`], with the Fourier modes of a circulant G and E (`fourier`) or
    /// always the general symmetric eigen solver (to check the one against the other).
    pub(super) fn detect_with(a: &DMatrix<f64>, fourier: bool) -> Option<SecondOrder> {
        let n = a.nrows();
        if n < 2 || n % 2 != 0 || !a.is_square() {
            return None;
        }
        let d = n / 2;
        // exact zero and identity blocks on top (bitwise: the structure is exact or absent)
        #[allow(clippy::float_cmp)]
        for j in 0..n {
            for i in 0..d {
                let want = if j == d + i { 1.0 } else { 0.0 };
                if a[(i, j)] != want {
                    return None;
                }
            }
        }
        let g = DMatrix::from_fn(d, d, |i, j| -a[(d + i, j)]);
        let e = DMatrix::from_fn(d, d, |i, j| -a[(d + i, d + j)]);
        let delta = symmetrizer(&g, &e)?;
        let sg = symmetrized(&g, &delta);
        let se = symmetrized(&e, &delta);
        let max_nnz = SPARSE_PER_COLUMN * d;
        let coupling = ColumnSparse::build(d, max_nnz, |i, j| g[(i, j)]).zip(ColumnSparse::build(
            d,
            max_nnz,
            |i, j| e[(i, j)],
        ));
        let (norm_g, norm_e) = (norm_inf(&sg), norm_inf(&se));
        // beyond f64 (entries near 1e308): the general path scales by powers of two first
        if !(norm_g.is_finite() && norm_e.is_finite() && norm_g * 4.0 < f64::MAX) {
            return None;
        }
        let (tol_g, tol_e) = (snap_tol(d, norm_g), snap_tol(d, norm_e));
        // a periodic ring of identical cells (symmetric circulant G and E, no mass scaling):
        // the Fourier modes, no eigen solver (see `circulant`)
        #[allow(clippy::float_cmp)] // exactly 1: no mass scaling
        let circulant = fourier
            && delta.iter().all(|&x| x == 1.0)
            && circulant::is_circulant(&sg)
            && circulant::is_circulant(&se);
        let (mut lam, fourier_gam, mut v) = if circulant {
            let (lam, gam, v) = circulant::fourier_modes(&sg, &se);
            (lam, Some(gam), v)
        } else {
            let (lam, v) = sym_eig(sg.clone())?;
            (lam, None, v)
        };
        if lam.iter().chain(v.iter()).any(|x| !x.is_finite()) {
            return None;
        }
        // residuals ‖S·V − V·diag(values)‖ (S_G, S_E have G's and E's pattern: sparse with it)
        let residual = |s: &DMatrix<f64>, values: &[f64], v: &DMatrix<f64>| -> f64 {
            let sv = match &coupling {
                Some(_) => ColumnSparse::build(d, max_nnz, |i, j| s[(i, j)])
                    .map_or_else(|| s * v, |c| c.mul(v)),
                None => s * v,
            };
            let mut r = 0.0f64;
            for (j, (col, vj)) in sv.column_iter().zip(v.column_iter()).enumerate() {
                for (x, y) in col.iter().zip(vj.iter()) {
                    let t = (x - y * values[j]).abs();
                    if t.is_nan() {
                        return f64::NAN;
                    }
                    r = r.max(t);
                }
            }
            r
        };
        let r = residual(&sg, &lam, &v);
        if r.is_nan() || r > tol_g.max(f64::MIN_POSITIVE) {
            return None;
        }
        let groups = runs(&lam, tol_g);
        snap(&mut lam, &groups, tol_g);
        // the damping in the stiffness modes, diagonalised within each group of equal λ
        let mut gam = vec![0.0; d];
        if let Some(fg) = fourier_gam.filter(|_| norm_e > 0.0) {
            // the Fourier modes diagonalise every circulant: checked by the residual
            let r = residual(&se, &fg, &v);
            if r.is_nan() || r > tol_e {
                return None;
            }
            gam = fg;
        } else if norm_e > 0.0 {
            let mut ev = v.transpose() * &se * &v;
            for &(i0, i1) in &groups {
                let k = i1 - i0;
                if k > 1 {
                    let block = DMatrix::from_fn(k, k, |i, j| {
                        0.5 * (ev[(i0 + i, i0 + j)] + ev[(i0 + j, i0 + i)])
                    });
                    let (_, w) = sym_eig(block)?;
                    let cols = v.columns(i0, k) * &w;
                    v.columns_mut(i0, k).copy_from(&cols);
                }
            }
            if groups.iter().any(|&(i0, i1)| i1 - i0 > 1) {
                ev = v.transpose() * &se * &v;
            }
            let mut off = 0.0f64;
            for j in 0..d {
                for i in 0..d {
                    if i != j {
                        off = off.max(ev[(i, j)].abs());
                    }
                }
                gam[j] = ev[(j, j)];
            }
            if off.is_nan() || off > tol_e {
                return None;
            }
        }
        if norm_e > 0.0 {
            // one damping for every mode when they all agree (E = γI rounds differently in
            // each mode), else equal damping within a stiffness group (sorted for the runs)
            let (lo, hi) = gam
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &g| {
                    (a.min(g), b.max(g))
                });
            if hi - lo <= tol_e {
                let mut m = gam.iter().sum::<f64>() / d as f64;
                if m.abs() <= tol_e {
                    m = 0.0;
                }
                gam.iter_mut().for_each(|g| *g = m);
            }
            for &(i0, i1) in &groups {
                let mut idx: Vec<usize> = (i0..i1).collect();
                idx.sort_by(|&x, &y| gam[x].total_cmp(&gam[y]));
                let sorted: Vec<f64> = idx.iter().map(|&k| gam[k]).collect();
                let mut vals = sorted.clone();
                let r = runs(&sorted, tol_e);
                snap(&mut vals, &r, tol_e);
                for (slot, &k) in idx.iter().enumerate() {
                    gam[k] = vals[slot];
                }
            }
        }
        let scale = crate::numeric::linalg::norms::norm_1_inf(a);
        // the cluster diameter of a double eigenvalue (linalg/structure: 2·r₂)
        let critical_tol = 2.0 * crate::numeric::linalg::structure::radius(2, n, scale);
        let modes = lam
            .iter()
            .zip(&gam)
            .map(|(&l, &g)| SecondOrderMode::new(l, g, critical_tol))
            .collect();
        let shapes = DMatrix::from_fn(d, d, |i, j| v[(i, j)] / delta[i]);
        let shapes_inv = DMatrix::from_fn(d, d, |i, j| v[(j, i)] * delta[j]);
        Some(SecondOrder {
            dof: d,
            shapes,
            shapes_inv,
            modes,
            scale,
            delta,
            coupling,
            circulant,
        })
    }

    /// Order 2d of A.
    pub fn order(&self) -> usize {
        2 * self.dof
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // exact zeros are the contract
    use super::*;
    use std::f64::consts::PI;

    /// [[0, I], [−G, −E]].
    fn assemble(g: &DMatrix<f64>, e: &DMatrix<f64>) -> DMatrix<f64> {
        let d = g.nrows();
        let mut a = DMatrix::zeros(2 * d, 2 * d);
        for i in 0..d {
            a[(i, d + i)] = 1.0;
            for j in 0..d {
                a[(d + i, j)] = -g[(i, j)];
                a[(d + i, d + j)] = -e[(i, j)];
            }
        }
        a
    }

    /// The periodic chain's Ω-matrix negated: 2 on the diagonal, −1 to the neighbours (ring).
    fn ring(d: usize) -> DMatrix<f64> {
        let mut g = DMatrix::zeros(d, d);
        for i in 0..d {
            g[(i, i)] = 2.0;
            g[(i, (i + 1) % d)] -= 1.0;
            g[(i, (i + d - 1) % d)] -= 1.0;
        }
        g
    }

    #[test]
    fn periodic_ring_modes_and_structure() {
        // λ_p = 4 sin²(πp/N): p and N − p degenerate, p = 0 the free translation.
        let d = 32;
        let so = SecondOrder::detect(&assemble(&ring(d), &DMatrix::zeros(d, d))).unwrap();
        let mut want: Vec<f64> = (0..d)
            .map(|p| 4.0 * (PI * p as f64 / d as f64).sin().powi(2))
            .collect();
        want.sort_by(f64::total_cmp);
        for (m, w) in so.modes.iter().zip(&want) {
            assert!((m.stiffness - w).abs() < 1e-14, "{} vs {w}", m.stiffness);
            assert_eq!(m.damping, 0.0);
        }
        assert_eq!(
            so.modes[0].stiffness, 0.0,
            "the free translation is exactly 0"
        );
        assert!(so.modes[0].critical);
        let st = so.eigen_structure();
        let zero = st.clusters.iter().find(|c| c.value.norm() == 0.0).unwrap();
        assert_eq!((zero.algebraic, zero.geometric), (2, 1));
        // ±jω_p of multiplicity 2 (semisimple) for p = 1 … N/2 − 1, simple ±2j
        let doubles = st
            .clusters
            .iter()
            .filter(|c| c.algebraic == 2 && c.geometric == 2)
            .count();
        assert_eq!(doubles, 2 * (d / 2 - 1));
        for c in &st.clusters {
            assert_eq!(c.value.re, 0.0, "undamped: on the axis exactly");
        }
        let top = st.clusters.iter().find(|c| c.value.im > 1.999).unwrap();
        assert_eq!(top.algebraic, 1);
        assert!((top.value.im - 2.0).abs() < 1e-14, "{}", top.value.im - 2.0);
    }

    #[test]
    fn rayleigh_damping_is_recognised_and_diagonal() {
        let d = 10;
        let mut g = DMatrix::zeros(d, d);
        for i in 0..d {
            g[(i, i)] = 2.0;
            if i + 1 < d {
                g[(i, i + 1)] = -1.0;
                g[(i + 1, i)] = -1.0;
            }
        }
        let e = DMatrix::identity(d, d) * 0.05 + &g * 0.02;
        let so = SecondOrder::detect(&assemble(&g, &e)).unwrap();
        for (k, m) in so.modes.iter().enumerate() {
            let w = 4.0 * (PI * (k + 1) as f64 / (2.0 * (d + 1) as f64)).sin().powi(2);
            assert!((m.stiffness - w).abs() < 1e-14);
            assert!((m.damping - (0.05 + 0.02 * w)).abs() < 1e-15);
            // the roots satisfy μ² + γμ + λ = 0
            for mu in m.roots {
                assert!((mu * mu + m.damping * mu + m.stiffness).norm() < 1e-14);
            }
        }
    }

    #[test]
    fn diagonal_masses_are_symmetrised() {
        // M = diag(1, 4), K = [[3, −1], [−1, 1]]: G = M⁻¹K is not symmetric.
        let k = DMatrix::from_row_slice(2, 2, &[3.0, -1.0, -1.0, 1.0]);
        let minv = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![1.0, 0.25]));
        let g = &minv * &k;
        let so = SecondOrder::detect(&assemble(&g, &DMatrix::zeros(2, 2))).unwrap();
        // eigenvalues of M⁻¹K: λ² − 3.25λ + 0.5 = 0
        let disc = (3.25f64 * 3.25 - 2.0).sqrt();
        let want = [(3.25 - disc) / 2.0, (3.25 + disc) / 2.0];
        for (m, w) in so.modes.iter().zip(want) {
            assert!((m.stiffness - w).abs() < 1e-14);
        }
        // the shapes are eigenvectors of G: G·x = λ·x
        for (kk, m) in so.modes.iter().enumerate() {
            let x = so.shapes.column(kk);
            let r = &g * x - x * m.stiffness;
            assert!(r.amax() < 1e-14);
        }
        let id = &so.shapes_inv * &so.shapes;
        assert!((id - DMatrix::identity(2, 2)).amax() < 1e-15);
    }

    #[test]
    fn coupling_damping_and_general_matrices_are_refused() {
        // one damper on the first mass of a 3-chain: does not commute with G
        let mut g = DMatrix::zeros(3, 3);
        for i in 0..3 {
            g[(i, i)] = 2.0;
            if i + 1 < 3 {
                g[(i, i + 1)] = -1.0;
                g[(i + 1, i)] = -1.0;
            }
        }
        let mut e = DMatrix::zeros(3, 3);
        e[(0, 0)] = 0.3;
        assert!(SecondOrder::detect(&assemble(&g, &e)).is_none());
        // not the block pattern
        let mut a = assemble(&g, &DMatrix::zeros(3, 3));
        a[(0, 0)] = 1e-300;
        assert!(SecondOrder::detect(&a).is_none());
        // a sign pattern no positive diagonal can symmetrise
        let g = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, -1.0, 1.0]);
        assert!(SecondOrder::detect(&assemble(&g, &DMatrix::zeros(2, 2))).is_none());
        // odd order
        assert!(SecondOrder::detect(&DMatrix::zeros(3, 3)).is_none());
    }

    #[test]
    fn critical_and_overdamped_modes() {
        // one dof: λ = 1, γ = 2 (critical: −1 double, a Jordan block); λ = 1, γ = 3 (−0.38, −2.62)
        let crit =
            SecondOrder::detect(&DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, -2.0])).unwrap();
        assert!(crit.modes[0].critical);
        assert_eq!(crit.modes[0].roots[0], Complex64::new(-1.0, 0.0));
        let st = crit.eigen_structure();
        assert_eq!(st.clusters.len(), 1);
        assert_eq!((st.clusters[0].algebraic, st.clusters[0].geometric), (2, 1));
        let over =
            SecondOrder::detect(&DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, -3.0])).unwrap();
        let r = over.modes[0].roots;
        let s5 = 5f64.sqrt();
        assert!((r[0].re - (-3.0 + s5) / 2.0).abs() < 1e-16);
        assert!((r[1].re - (-3.0 - s5) / 2.0).abs() < 1e-15);
        // negative stiffness (an inverted pendulum): ±1 real
        let inv =
            SecondOrder::detect(&DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 1.0, 0.0])).unwrap();
        let mut re: Vec<f64> = inv.modes[0].roots.iter().map(|z| z.re).collect();
        re.sort_by(f64::total_cmp);
        assert_eq!(re, vec![-1.0, 1.0]);
    }

    #[test]
    fn shared_root_of_two_modes_is_a_semisimple_double_eigenvalue() {
        // modes (λ, γ) = (2, 3): roots −1, −2 and (3, 4): roots −1, −3 — as G = diag(2, 3),
        // E = diag(3, 4): −1 is a double eigenvalue with two eigenvectors.
        let g = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![2.0, 3.0]));
        let e = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![3.0, 4.0]));
        let so = SecondOrder::detect(&assemble(&g, &e)).unwrap();
        let st = so.eigen_structure();
        let m1 = st
            .clusters
            .iter()
            .find(|c| (c.value.re + 1.0).abs() < 1e-14)
            .unwrap();
        assert_eq!((m1.algebraic, m1.geometric), (2, 2));
        assert_eq!(st.clusters.len(), 3);
    }
}
