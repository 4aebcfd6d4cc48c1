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

use super::complex_schur::{ComplexSchur, complex_schur};
use super::schur::{RealSchur, SchurOptions, real_schur};
use crate::error::Result;

/// Largest cluster size whose radius grows with the size; larger clusters (semisimple ones
/// such as the identity's) are held to the radius of this size.
pub const MAX_DEFECTIVE_SIZE: usize = 6;

/// Growth factor K in the cluster radius ν·(K·n·ε)^(1/m).
const RADIUS_GROWTH: f64 = 64.0;

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

/// Cluster radius for a cluster of m members (see the module docs).
pub(crate) fn radius(m: usize, n: usize, scale: f64) -> f64 {
    let m = m.clamp(1, MAX_DEFECTIVE_SIZE) as f64;
    scale * (RADIUS_GROWTH * n.max(1) as f64 * f64::EPSILON).powf(1.0 / m)
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

/// Clustering top-down: the connected components of the graph linking eigenvalues closer
/// than 2·r_6 (the largest radius), each split at the longest link of its minimum spanning
/// tree until its diameter is within 2·r_m for its size m.
///
/// Top-down, not closest-pairs-first: the m members of a defective eigenvalue lie on a circle
/// and are about equally far apart (a Jordan block of size 3 scatters into a near-equilateral
/// triangle), so no pair of them may satisfy the bound r_2 of a pair although the three
/// together satisfy r_3; a bottom-up merge would never form the triple.
fn link_clusters(ev: &[Complex64], scale: f64) -> Vec<Vec<usize>> {
    let n = ev.len();
    let reach = 2.0 * radius(MAX_DEFECTIVE_SIZE, n, scale);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| ev[a].re.total_cmp(&ev[b].re));
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut k: usize) -> usize {
        while parent[k] != k {
            parent[k] = parent[parent[k]];
            k = parent[k];
        }
        k
    }
    for (ia, &a) in order.iter().enumerate() {
        for &b in &order[ia + 1..] {
            if ev[b].re - ev[a].re > reach {
                break;
            }
            if dist(ev[a], ev[b]) <= reach {
                let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                if ra != rb {
                    parent[rb] = ra;
                }
            }
        }
    }
    let mut components: Vec<Vec<usize>> = vec![Vec::new(); n];
    for k in 0..n {
        let r = root(&mut parent, k);
        components[r].push(k);
    }
    // Each component's minimum spanning tree once; a split at a tree's longest link leaves
    // two subtrees that are the minimum spanning trees of their members (the cut property),
    // so every later split is read off the same tree: O(m) per split instead of a new O(m²)
    // tree (a random matrix's spectrum is one component, peeled a member at a time).
    let mut work: Vec<(Vec<usize>, Vec<Link>)> = components
        .into_iter()
        .filter(|g| !g.is_empty())
        .map(|g| {
            let tree = spanning_tree(&g, ev);
            (g, tree)
        })
        .collect();
    let mut out = Vec::new();
    let mut owner = vec![usize::MAX; n];
    while let Some((g, tree)) = work.pop() {
        if g.len() > 1 && diameter_exceeds(&g, ev, 2.0 * radius(g.len(), n, scale)) {
            let [left, right] = cut_longest_link(g, tree, &mut owner);
            work.push(left);
            work.push(right);
        } else {
            out.push(g);
        }
    }
    for g in &mut out {
        g.sort_unstable();
    }
    out.sort_unstable_by_key(|g| g.first().copied().unwrap_or(0));
    out
}

/// A link of a spanning tree: its two members (indices into the eigenvalues) and length.
type Link = (usize, usize, f64);

/// The minimum spanning tree of the members `g` (Prim's algorithm from `g[0]`):
/// `g.len() − 1` links, member i's link to its parent in the order of `g`.
fn spanning_tree(g: &[usize], ev: &[Complex64]) -> Vec<Link> {
    let m = g.len();
    let mut in_tree = vec![false; m];
    let mut best = vec![f64::INFINITY; m];
    let mut parent = vec![0usize; m];
    best[0] = 0.0;
    for _ in 0..m {
        let next = (0..m)
            .filter(|&i| !in_tree[i])
            .min_by(|&x, &y| best[x].total_cmp(&best[y]))
            .unwrap_or(0);
        in_tree[next] = true;
        for i in 0..m {
            if !in_tree[i] {
                let d = dist(ev[g[i]], ev[g[next]]);
                if d < best[i] {
                    best[i] = d;
                    parent[i] = next;
                }
            }
        }
    }
    (1..m).map(|i| (g[i], g[parent[i]], best[i])).collect()
}

/// Whether the largest distance between members of `g` exceeds `limit`: decided by the
/// bounding box when it can be (a side longer than `limit`, or a diagonal within it), by
/// all pairs otherwise.
fn diameter_exceeds(g: &[usize], ev: &[Complex64], limit: f64) -> bool {
    let (mut re0, mut re1, mut im0, mut im1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &k in g {
        re0 = re0.min(ev[k].re);
        re1 = re1.max(ev[k].re);
        im0 = im0.min(ev[k].im);
        im1 = im1.max(ev[k].im);
    }
    let (w, h) = (re1 - re0, im1 - im0);
    if w > limit || h > limit {
        return true;
    }
    if w.hypot(h) <= limit {
        return false;
    }
    g.iter()
        .enumerate()
        .any(|(i, &x)| g[i + 1..].iter().any(|&y| dist(ev[x], ev[y]) > limit))
}

/// The members and spanning tree split at the tree's longest link (the last of equal ones):
/// the two subtrees with their members, in the order of `g`.
/// `owner` is scratch space indexed by eigenvalue (any contents).
fn cut_longest_link(
    g: Vec<usize>,
    mut tree: Vec<Link>,
    owner: &mut [usize],
) -> [(Vec<usize>, Vec<Link>); 2] {
    let cut = (0..tree.len())
        .max_by(|&x, &y| tree[x].2.total_cmp(&tree[y].2))
        .unwrap_or(0);
    let (a, _, _) = tree.swap_remove(cut);
    // union-find over the remaining links
    for &k in &g {
        owner[k] = k;
    }
    fn root(owner: &mut [usize], mut k: usize) -> usize {
        while owner[k] != k {
            owner[k] = owner[owner[k]];
            k = owner[k];
        }
        k
    }
    for &(x, y, _) in &tree {
        let (rx, ry) = (root(owner, x), root(owner, y));
        if rx != ry {
            owner[ry] = rx;
        }
    }
    let ra = root(owner, a);
    let (mut below, mut rest) = (Vec::new(), Vec::new());
    for &k in &g {
        if root(owner, k) == ra {
            below.push(k);
        } else {
            rest.push(k);
        }
    }
    let (mut tb, mut tr) = (Vec::new(), Vec::new());
    for l in tree {
        if root(owner, l.0) == ra {
            tb.push(l);
        } else {
            tr.push(l);
        }
    }
    [(rest, tr), (below, tb)]
}

/// |a − b| without libm's `hypot` where the squares cannot overflow or underflow (the
/// clustering compares O(n²) distances: `hypot` was a sixth of a 256-state channel's
/// factorisation); `hypot` otherwise. Equal to it within an ulp.
fn dist(a: Complex64, b: Complex64) -> f64 {
    let (dx, dy) = ((a.re - b.re).abs(), (a.im - b.im).abs());
    let m = dx.max(dy);
    if m > 1e-150 && m < 1e150 {
        (dx * dx + dy * dy).sqrt()
    } else {
        dx.hypot(dy)
    }
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

/// Splits a cluster in two at the longest link of its minimum spanning tree
/// ([`spanning_tree`], cut by [`cut_longest_link`]): (the rest, the subtree below the cut),
/// each in the order of `g`.
fn split_longest_link(g: &[usize], ev: &[Complex64]) -> (Vec<usize>, Vec<usize>) {
    if g.len() < 2 {
        return (g.to_vec(), Vec::new()); // no link to cut
    }
    let tree = spanning_tree(g, ev);
    let mut owner = vec![usize::MAX; ev.len()];
    let [(rest, _), (below, _)] = cut_longest_link(g.to_vec(), tree, &mut owner);
    (rest, below)
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

/// A group larger than this that is not one eigenvalue is split into halves (at the median
/// along its wider direction) instead of at its longest link, which in a tight cloud of
/// distinct eigenvalues peels one member at a time: log₂ m reduced problems deep, not m.
/// A multiple eigenvalue cut by such a split is missed (examined as smaller parts), never
/// invented; groups this large are far beyond the defective sizes the radii allow.
const BALANCED_SPLIT_ABOVE: usize = 32;

/// A group that is not one eigenvalue, in two: at its longest link, or in halves when large.
fn split(g: &[usize], ev: &[Complex64]) -> [Vec<usize>; 2] {
    let (left, right) = if g.len() > BALANCED_SPLIT_ABOVE {
        split_in_halves(g, ev)
    } else {
        split_longest_link(g, ev)
    };
    [left, right]
}

/// `g` cut at the median of its members' real or imaginary parts, whichever spread more.
fn split_in_halves(g: &[usize], ev: &[Complex64]) -> (Vec<usize>, Vec<usize>) {
    let spread = |f: &dyn Fn(Complex64) -> f64| {
        let (lo, hi) = g
            .iter()
            .map(|&k| f(ev[k]))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            });
        hi - lo
    };
    let by_re = spread(&|z| z.re) >= spread(&|z| z.im);
    let mut sorted = g.to_vec();
    sorted.sort_by(|&a, &b| {
        if by_re {
            ev[a].re.total_cmp(&ev[b].re)
        } else {
            ev[a].im.total_cmp(&ev[b].im)
        }
    });
    let right = sorted.split_off(sorted.len() / 2);
    (sorted, right)
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
