//! Multiplicity structure of the eigenvalues: which computed eigenvalues are one multiple
//! eigenvalue, and whether it is semisimple (as many eigenvectors as its multiplicity) or
//! defective (a Jordan block).
//!
//! # Method
//! **Clusters.** A perturbation of size ε‖A‖ moves a simple eigenvalue by ~ε‖A‖ but scatters
//! an m-fold defective one over a circle of radius ~(ε)^(1/m)‖A‖. Computed eigenvalues are
//! therefore grouped top-down (components of the graph of links shorter than 2·r_6, split at their
//! longest spanning-tree link) into clusters whose diameter is at most 2·r_m, m the size, and
//! r_m = ν·(64·n·ε)^(1/min(m, 6)), ν = max(‖T‖₁, ‖T‖∞) of the balanced Schur form.
//! The cluster's value is its mean (the trace of its invariant subspace divided by m, which
//! is accurate to O(ε‖A‖) although the members are not); self-conjugate clusters are made
//! exactly real and conjugate clusters exact conjugates.
//!
//! **Resolution** (issue 24). The radius is relative to the global scale ν, so it would merge
//! distinct well-conditioned eigenvalues that lie close together beside a large-norm part. A
//! cluster is one multiple eigenvalue only when its spread is explained by the perturbation
//! bound of its own members: each member's condition number κ as a simple eigenvalue (from
//! the left and right eigenvectors of the complex Schur form, two triangular solves) bounds
//! its error by ~K·n·ε·ν·κ (K = 64), and members farther apart than the sum of their bounds are
//! resolved — the cluster splits into the connected components of the unresolved pairs. The
//! members of a defective eigenvalue have κ ~ ε^(1/m − 1) and those of a semisimple one meet
//! vanishing pivots (κ large): both stay together.
//!
//! **Geometric multiplicity** g = dim null(A − λI) is computed on the complex Schur form S
//! (unitarily similar, so the dimension is the same) without an n×n SVD: the unknowns of
//! (S − λI)x = 0 at the m cluster positions are free, every other row is solved by
//! back-substitution, and what remains is an m×m system R·y = 0 whose rows are the residuals
//! at the cluster positions. With W (n×m) the back-substituted vectors, W = Q_W·R_W, the
//! singular values of R̃ = R·R_W⁻¹ are the residual norms ‖(S − λI)v‖ of unit vectors
//! v ∈ span W, so g = #{σᵢ(R̃) ≤ τ} with τ = √ε·ν: λ is an eigenvalue of geometric
//! multiplicity g of a matrix within distance τ of A. A cluster with g = 0 is not one
//! eigenvalue: it is split at its longest link and both halves are examined again.
//! The null vectors of R̃ give a basis of the eigenspace ([`super::eigvec`]).

use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

mod grouping;

pub use grouping::MAX_DEFECTIVE_SIZE;
pub(crate) use grouping::radius;
use grouping::{RADIUS_GROWTH, dist, link_clusters, split};

use super::complex_schur::{ComplexSchur, complex_schur};
use super::schur::{RealSchur, SchurOptions, real_schur};
use crate::error::Result;

/// One (possibly multiple) eigenvalue.
#[derive(Clone, Debug, PartialEq)]
pub struct EigenCluster {
    /// The eigenvalue: the mean of the members.
    pub value: Complex64,
    /// Algebraic multiplicity (the number of members).
    pub algebraic: usize,
    /// Geometric multiplicity (the number of independent eigenvectors), 1 ≤ g ≤ algebraic.
    pub geometric: usize,
    /// The computed eigenvalues of the cluster.
    pub members: Vec<Complex64>,
    /// Their positions on the diagonal of the complex Schur form.
    pub positions: Vec<usize>,
    /// Singular values of the reduced m×m problem (relative to ν), largest first: the last
    /// `geometric` ones are ≤ √ε, the others are the couplings of the Jordan structure.
    pub sigma: Vec<f64>,
}

impl EigenCluster {
    /// True when the eigenvalue has as many eigenvectors as its multiplicity.
    pub fn is_semisimple(&self) -> bool {
        self.geometric == self.algebraic
    }
}

/// The eigenvalues of a matrix with their multiplicity structure.
#[derive(Clone, Debug)]
pub struct EigenStructure {
    /// The clusters, in the order of their first member on the Schur diagonal.
    pub clusters: Vec<EigenCluster>,
    /// ν = max(‖T‖₁, ‖T‖∞) of the balanced Schur form: the scale of every tolerance.
    pub scale: f64,
    /// The rank tolerance τ = √ε·ν of the geometric multiplicity.
    pub rank_tol: f64,
}

/// Eigenvalues of a square, finite A grouped into multiple eigenvalues with algebraic and
/// geometric multiplicities (see the [module docs](self)), by the Schur form whatever the
/// structure of A. [`eigen_structure`](super::eigen_structure) takes a second-order model's
/// modes instead when A has that structure.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::structure::general_eigen_structure;
/// // A Jordan block of size 2 at −1 next to a simple eigenvalue −3.
/// let a = DMatrix::from_row_slice(3, 3, &[-1.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -3.0]);
/// let s = general_eigen_structure(&a).unwrap();
/// let double = s.clusters.iter().find(|c| c.algebraic == 2).unwrap();
/// assert!((double.value.re + 1.0).abs() < 1e-14 && double.value.im == 0.0);
/// assert_eq!(double.geometric, 1);
/// ```
pub fn general_eigen_structure(a: &DMatrix<f64>) -> Result<EigenStructure> {
    let opts = SchurOptions {
        balance: true,
        want_q: false,
        want_t: true,
    };
    let real = real_schur(a, opts)?;
    Ok(structure_of(&real, &complex_schur(&real), false).0)
}

/// The structure from a real Schur form (with the whole T) and its complex form. With
/// `want_vectors` it also returns, per cluster, an orthonormal eigenvector basis (n×g) in the
/// coordinates of the complex Schur form (`None` for a lower conjugate that mirrors its
/// partner); without, simple eigenvalues are not examined (g = 1) and no basis is returned.
pub(crate) fn structure_of(
    real: &RealSchur,
    cs: &ComplexSchur,
    want_vectors: bool,
) -> (EigenStructure, Vec<Option<DMatrix<Complex64>>>) {
    let n = real.order();
    let scale = super::norms::norm_1_inf(&real.t);
    let rank_tol = f64::EPSILON.sqrt() * scale;
    let ev: Vec<Complex64> = (0..n).map(|k| cs.s[(k, k)]).collect();
    let mut groups = link_clusters(&ev, scale);
    let mut clusters = Vec::new();
    let mut bases = Vec::new();
    // Upper and self-conjugate clusters first; a lower one is the mirror of its partner when
    // there is one, and examined on its own otherwise.
    let mut lower: Vec<Vec<usize>> = Vec::new();
    let mut lower_pass = false;
    loop {
        let Some(g) = groups.pop() else {
            if lower_pass || lower.is_empty() {
                break;
            }
            lower_pass = true;
            for g in std::mem::take(&mut lower) {
                let value = mean(&g, &ev);
                let partner = clusters.iter().position(|c: &EigenCluster| {
                    c.algebraic == g.len()
                        && (c.value.conj() - value).norm() <= radius(g.len(), n, scale)
                });
                match partner {
                    Some(i) => {
                        let mut c = provisional(&g, &ev, clusters[i].value.conj());
                        c.geometric = clusters[i].geometric;
                        c.sigma = clusters[i].sigma.clone();
                        clusters.push(c);
                        bases.push(None);
                    }
                    None => groups.push(g),
                }
            }
            continue;
        };
        let value = mean(&g, &ev);
        if value.im < 0.0 && !lower_pass {
            lower.push(g);
            continue;
        }
        if g.len() == 1 && !want_vectors {
            let mut c = provisional(&g, &ev, value);
            c.sigma = vec![0.0];
            clusters.push(c);
            bases.push(None);
            continue;
        }
        // Members resolved by the computation (their spread exceeds what the backward error
        // can explain through their own condition numbers) are distinct eigenvalues, however
        // close they are against ν: the group splits into its unresolved parts.
        if g.len() > 1 {
            let parts = resolved_parts(&cs.s, &g, &ev, scale);
            if parts.len() > 1 {
                groups.extend(parts);
                continue;
            }
        }
        // A group that is not one eigenvalue (g = 0) needs σ_min(S − λI) > τ; an O(n²)
        // estimate of it rejects such a group before the O(n²·m + m³) reduced problem. A
        // large group of distinct eigenvalues (a random matrix's tight spectrum) is split one
        // member at a time, so this keeps the whole pass at O(n³) instead of O(n⁴).
        if g.len() > 1 && inverse_norm_estimate(&cs.s, value, scale) * rank_tol < REJECT_MARGIN {
            groups.extend(split(&g, &ev));
            continue;
        }
        let reduced = reduced_problem(&cs.s, &g, value, scale);
        let g_mult = reduced.sigma.iter().filter(|&&s| s <= rank_tol).count();
        if g_mult == 0 && g.len() > 1 {
            groups.extend(split(&g, &ev));
            continue;
        }
        let mut c = provisional(&g, &ev, value);
        c.geometric = g_mult.max(1);
        c.sigma = reduced
            .sigma
            .iter()
            .map(|s| s / scale.max(f64::MIN_POSITIVE))
            .collect();
        clusters.push(c);
        bases.push(Some(reduced.null_basis(g_mult.max(1))));
    }
    let mut order: Vec<usize> = (0..clusters.len()).collect();
    order.sort_by_key(|&i| clusters[i].positions.first().copied().unwrap_or(0));
    let clusters: Vec<EigenCluster> = order.iter().map(|&i| clusters[i].clone()).collect();
    let bases = order.iter().map(|&i| bases[i].clone()).collect();
    (
        EigenStructure {
            clusters,
            scale,
            rank_tol,
        },
        bases,
    )
}

fn provisional(g: &[usize], ev: &[Complex64], value: Complex64) -> EigenCluster {
    EigenCluster {
        value,
        algebraic: g.len(),
        geometric: 1,
        members: g.iter().map(|&k| ev[k]).collect(),
        positions: g.to_vec(),
        sigma: Vec::new(),
    }
}

/// The eigenvalue rule for a value with error radius `r` (a cluster radius): within `r` of 0
/// it is 0, a real part within `r` is 0 (on the imaginary axis) — A is within ε‖A‖ of a
/// matrix with the value there (an integrator, an undamped mode, a zero at the origin).
pub(crate) fn snap(v: Complex64, r: f64) -> Complex64 {
    if v.norm() <= r {
        Complex64::new(0.0, 0.0)
    } else if v.re.abs() <= r {
        Complex64::new(0.0, v.im)
    } else {
        v
    }
}

/// The cluster mean; exactly real when the cluster is closed under conjugation.
fn mean(g: &[usize], ev: &[Complex64]) -> Complex64 {
    let sum: Complex64 = g.iter().map(|&k| ev[k]).sum();
    let z = sum / g.len() as f64;
    if is_self_conjugate(g, ev, z) {
        Complex64::new(z.re, 0.0)
    } else {
        z
    }
}

/// A cluster is self-conjugate when it has as many members above the real axis as below.
fn is_self_conjugate(g: &[usize], ev: &[Complex64], _z: Complex64) -> bool {
    let up = g.iter().filter(|&&k| ev[k].im > 0.0).count();
    let down = g.iter().filter(|&&k| ev[k].im < 0.0).count();
    up == down
}

/// The backward error factor K in the resolution test: members λᵢ, λⱼ are resolved when
/// |λᵢ − λⱼ| > K·n·ε·ν·(κᵢ + κⱼ) (the same growth constant as the cluster radius).
fn resolution_bound(n: usize, scale: f64) -> f64 {
    RADIUS_GROWTH * n.max(1) as f64 * f64::EPSILON * scale
}

/// Condition number κ = ‖x‖‖y‖/|yᴴx| of the computed eigenvalue at position k of the upper
/// triangular S, as if it were simple: x by back substitution with x_k = 1 (zero below k), y
/// by forward substitution with y_k = 1 (zero above k), so yᴴx = 1. A pivot S_jj − λ below
/// ε·`scale` is taken as that size (a member of a multiple eigenvalue then reads as
/// ill-conditioned, as it is); an overflowing vector reads as κ = ∞. O(n²).
fn member_condition(s: &DMatrix<Complex64>, k: usize, scale: f64) -> f64 {
    let n = s.nrows();
    let lambda = s[(k, k)];
    let smin = (f64::EPSILON * scale).max(f64::MIN_POSITIVE * 1e10);
    let pivot = |j: usize| {
        let d = s[(j, j)] - lambda;
        if d.re.abs().max(d.im.abs()) < smin && d.norm() < smin {
            Complex64::new(smin, 0.0)
        } else {
            d
        }
    };
    const BIG: f64 = 1e150;
    // |z| > BIG, with `hypot` only when the larger part does not decide it
    let too_big = |z: Complex64| {
        let m = z.re.abs().max(z.im.abs());
        m > BIG || (m > 0.5 * BIG && z.norm() > BIG)
    };
    // right: (S − λI)x = 0 on rows 0..k, by columns (contiguous): rhs = −S[0..k, k], then
    // x_j = rhs_j/pivot and rhs[0..j] −= S[0..j, j]·x_j
    let mut x: Vec<Complex64> = (0..k).map(|i| -s[(i, k)]).collect();
    for j in (0..k).rev() {
        let xj = x[j] / pivot(j);
        x[j] = xj;
        if too_big(xj) {
            return f64::INFINITY;
        }
        let col = &s.as_slice()[j * n..j * n + j];
        for (t, sij) in x[..j].iter_mut().zip(col) {
            *t -= sij * xj;
        }
    }
    x.push(Complex64::new(1.0, 0.0));
    // left: yᴴ(S − λI) = 0 on columns k..n (y stored conjugated: w = yᴴ)
    let mut w = vec![Complex64::new(0.0, 0.0); n - k];
    w[0] = Complex64::new(1.0, 0.0);
    for j in k + 1..n {
        let mut acc = Complex64::new(0.0, 0.0);
        for l in k..j {
            acc -= w[l - k] * s[(l, j)];
        }
        w[j - k] = acc / pivot(j);
        if too_big(w[j - k]) {
            return f64::INFINITY;
        }
    }
    let norm = |v: &[Complex64]| v.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
    norm(&x) * norm(&w)
}

/// The parts of a group that the computation does not resolve: members linked when their
/// distance is within the first-order perturbation bound of both, K·n·ε·ν·(κᵢ + κⱼ)
/// ([`member_condition`]); the connected components. A defective eigenvalue's members are
/// ill-conditioned as simple eigenvalues (κ ~ ε^(1/m − 1)), a semisimple one's meet zero
/// pivots: both stay linked. Well-conditioned distinct eigenvalues, however close against
/// the global scale ν, come apart.
fn resolved_parts(
    s: &DMatrix<Complex64>,
    g: &[usize],
    ev: &[Complex64],
    scale: f64,
) -> Vec<Vec<usize>> {
    let m = g.len();
    let bound = resolution_bound(s.nrows(), scale);
    let kappa: Vec<f64> = g.iter().map(|&k| member_condition(s, k, scale)).collect();
    let mut parent: Vec<usize> = (0..m).collect();
    fn root(parent: &mut [usize], mut k: usize) -> usize {
        while parent[k] != k {
            parent[k] = parent[parent[k]];
            k = parent[k];
        }
        k
    }
    for i in 0..m {
        for j in i + 1..m {
            let allowed = bound * (kappa[i] + kappa[j]);
            if dist(ev[g[i]], ev[g[j]]) <= allowed || !allowed.is_finite() {
                let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
                if ri != rj {
                    parent[rj] = ri;
                }
            }
        }
    }
    let mut parts: Vec<Vec<usize>> = vec![Vec::new(); m];
    for (i, &k) in g.iter().enumerate() {
        let r = root(&mut parent, i);
        parts[r].push(k);
    }
    parts.retain(|p| !p.is_empty());
    parts
}

/// The reduced m×m problem of a cluster: W (n×m) and R (m×m), see the module docs.
pub(crate) struct Reduced {
    /// Orthonormal basis of span W.
    q_w: DMatrix<Complex64>,
    /// Singular values of R̃, largest first.
    pub sigma: Vec<f64>,
    /// Right singular vectors of R̃ (columns, in the order of `sigma`).
    v: DMatrix<Complex64>,
}

impl Reduced {
    /// Orthonormal basis (n×g) of the approximate null space: the last g right singular
    /// vectors mapped through Q_W.
    pub(crate) fn null_basis(&self, g: usize) -> DMatrix<Complex64> {
        let m = self.v.ncols();
        let cols = self.v.columns(m - g.min(m), g.min(m));
        &self.q_w * cols
    }
}

/// A group is rejected without its reduced problem only when the estimate of
/// ‖(S − λI)⁻¹‖ says σ_min(S − λI) exceeds the rank tolerance by this factor (the estimate
/// is a lower bound of ‖(S − λI)⁻¹‖, close to it after a few steps; a multiplicity may be
/// missed, never invented).
const REJECT_MARGIN: f64 = 1e-3;

/// An estimate of ‖(S − λI)⁻¹‖₂ for the upper triangular `s` (a lower bound): three steps of
/// the power method on (S − λI)⁻ᴴ(S − λI)⁻¹ by triangular solves, O(n²) each; a pivot below
/// ε·`scale` is taken as that size (a singular matrix then reads as nearly so).
fn inverse_norm_estimate(s: &DMatrix<Complex64>, lambda: Complex64, scale: f64) -> f64 {
    let n = s.nrows();
    if n == 0 {
        return 0.0;
    }
    let smin = (f64::EPSILON * scale).max(f64::MIN_POSITIVE * 1e10);
    let pivot = |i: usize| {
        let d = s[(i, i)] - lambda;
        if d.norm() < smin {
            Complex64::new(smin, 0.0)
        } else {
            d
        }
    };
    // a start with every component present (alternating signs and sizes)
    let mut x: Vec<Complex64> = (0..n)
        .map(|i| {
            Complex64::new(
                if i % 2 == 0 { 1.0 } else { -1.0 } * (1.0 + i as f64 / n as f64),
                0.0,
            )
        })
        .collect();
    let norm = |v: &[Complex64]| v.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
    let mut est: f64 = 0.0;
    for _ in 0..3 {
        let nx = norm(&x);
        if !(nx > 0.0 && nx.is_finite()) {
            return f64::INFINITY;
        }
        x.iter_mut().for_each(|z| *z /= nx);
        // y = (S − λI)⁻¹ x: back substitution
        let mut y = x.clone();
        for i in (0..n).rev() {
            let mut acc = y[i];
            for j in i + 1..n {
                acc -= s[(i, j)] * y[j];
            }
            y[i] = acc / pivot(i);
        }
        let ny = norm(&y);
        if !ny.is_finite() {
            return f64::INFINITY;
        }
        est = est.max(ny);
        // x = (S − λI)⁻ᴴ y: forward substitution with the conjugate transpose
        for i in 0..n {
            let mut acc = y[i];
            for j in 0..i {
                acc -= s[(j, i)].conj() * y[j];
            }
            y[i] = acc / pivot(i).conj();
        }
        x = y;
    }
    est
}

/// Back-substitution with the cluster positions free (see the module docs).
pub(crate) fn reduced_problem(
    s: &DMatrix<Complex64>,
    positions: &[usize],
    lambda: Complex64,
    scale: f64,
) -> Reduced {
    let n = s.nrows();
    let m = positions.len();
    let smin = (f64::EPSILON * scale).max(f64::MIN_POSITIVE * 1e10);
    let mut w = DMatrix::<Complex64>::zeros(n, m);
    let mut r = DMatrix::<Complex64>::zeros(m, m);
    let slot = |j: usize| positions.iter().position(|&p| p == j);
    for (k, &pk) in positions.iter().enumerate() {
        let (x, res) = back_substitute(s, pk, lambda, smin, &slot);
        for (i, xi) in x.iter().enumerate() {
            w[(i, k)] = *xi;
        }
        for (l, v) in res {
            r[(l, k)] = v;
        }
        // x[p] is 1, or smaller when back_substitute rescaled x against overflow.
        r[(k, k)] = (s[(pk, pk)] - lambda) * x[pk];
    }
    let qr = w.clone().qr();
    let (q_w, r_w) = (qr.q(), qr.r());
    // R̃ = R·R_W⁻¹ (R_W upper triangular, non-singular: W has a unit entry per column at its
    // own position and zeros at the others).
    let rt = match r_w.solve_upper_triangular(&DMatrix::identity(m, m)) {
        Some(inv) => &r * inv,
        None => r.clone(),
    };
    // The SVD on an exactly scaled copy (singular values scale back linearly), capped; an
    // overflowed entry (eigenvalues near the top of the f64 range) or no convergence leaves
    // the cluster at full rank — split into simple eigenvalues later: a multiplicity may be
    // missed, never invented. (nalgebra's `svd()` panics on a NaN singular value.)
    let amax = rt
        .iter()
        .fold(0.0f64, |a, z| a.max(z.re.abs()).max(z.im.abs()));
    let full_rank = |m: usize| Reduced {
        q_w: q_w.clone(),
        sigma: vec![f64::INFINITY; m],
        v: DMatrix::identity(m, m),
    };
    if amax == 0.0 {
        // R̃ = 0: every direction is null (e.g. a multiple of the identity)
        return Reduced {
            q_w,
            sigma: vec![0.0; m],
            v: DMatrix::identity(m, m),
        };
    }
    if !amax.is_finite() {
        return full_rank(m);
    }
    let k = -(amax.log2().floor() as i32);
    let rt = rt.map(|z| z * 2f64.powi(k));
    let Some(mut svd) = rt.try_svd(
        false,
        true,
        f64::EPSILON,
        crate::numeric::lstsq::MAX_SVD_ITER,
    ) else {
        return full_rank(m);
    };
    if svd.singular_values.iter().any(|x| !x.is_finite()) {
        return full_rank(m);
    }
    svd.singular_values.apply(|x| *x *= 2f64.powi(-k));
    let mut idx: Vec<usize> = (0..m).collect();
    idx.sort_by(|&a, &b| svd.singular_values[b].total_cmp(&svd.singular_values[a]));
    let sigma: Vec<f64> = idx.iter().map(|&i| svd.singular_values[i]).collect();
    let v = match &svd.v_t {
        Some(vt) => {
            let vv = vt.adjoint();
            DMatrix::from_fn(m, m, |i, j| vv[(i, idx[j])])
        }
        None => DMatrix::identity(m, m),
    };
    Reduced { q_w, sigma, v }
}

/// Solves (S − λI)x = 0 with x\[p\] = 1, x\[j\] = 0 below p and at the other cluster positions
/// (`slot(j)` is Some for them); returns x (scaled to avoid overflow) and the residuals at
/// the cluster positions above p as (slot, value).
pub(crate) fn back_substitute(
    s: &DMatrix<Complex64>,
    p: usize,
    lambda: Complex64,
    smin: f64,
    slot: &dyn Fn(usize) -> Option<usize>,
) -> (DVector<Complex64>, Vec<(usize, Complex64)>) {
    let n = s.nrows();
    let mut x = DVector::<Complex64>::zeros(n);
    x[p] = Complex64::new(1.0, 0.0);
    // rhs = −S[0..p, p]·x_p, updated column by column (contiguous).
    let mut rhs: Vec<Complex64> = (0..p).map(|i| -s[(i, p)]).collect();
    let mut residuals = Vec::new();
    const BIG: f64 = 1e150;
    for j in (0..p).rev() {
        if let Some(l) = slot(j) {
            residuals.push((l, -rhs[j]));
            continue;
        }
        let mut piv = s[(j, j)] - lambda;
        if piv.norm() < smin {
            piv = Complex64::new(smin, 0.0);
        }
        let xj = rhs[j] / piv;
        x[j] = xj;
        if xj.norm() > BIG {
            let f = 1.0 / xj.norm();
            x.iter_mut().for_each(|t| *t *= f);
            rhs.iter_mut().for_each(|t| *t *= f);
            residuals.iter_mut().for_each(|t| t.1 *= f);
        }
        let xj = x[j];
        let col = s.column(j);
        for (t, sij) in rhs[..j].iter_mut().zip(col.iter()) {
            *t -= sij * xj;
        }
    }
    (x, residuals)
}
