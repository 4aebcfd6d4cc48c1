//! Eigenvectors (mode shapes) of a real matrix, one basis per distinct eigenvalue, each
//! vector with its measured residual.
//!
//! # Method
//! From the balanced real Schur form A = D·Q·T·Qᵀ·D⁻¹ and its complex triangular form S
//! (`complex_schur.rs`): for every eigenvalue cluster of [`super::structure`] the
//! eigenspace of S is found by back-substitution (a simple eigenvalue: x\[p\] = 1 and the rows
//! above solved; a multiple one: the null space of the reduced m×m problem), then mapped
//! back, v = D·Q·Z·y (one real matrix product for all clusters), and orthonormalised per
//! eigenvalue. Pivots closer than ε·ν to zero are replaced by ε·ν (LAPACK `dtrevc`'s rule), so
//! a vector is always returned; its residual ‖Av − λv‖₂/(‖A‖·‖v‖₂), ‖A‖ = max(‖A‖₁, ‖A‖∞),
//! is computed with the original A and returned beside it — the accuracy is measured, never
//! assumed. For a real eigenvalue the basis is real (imaginary parts exactly 0); for a
//! conjugate pair the basis of λ̄ is the conjugate of that of λ.
//!
//! A defective eigenvalue gets its g < m true eigenvectors only (no generalised ones).
//!
//! This is the general path ([`general_eigenvectors`]). A matrix with the mechanical structure of
//! [`super::second_order`] takes its vectors from the modes instead: (x, μx) for mode shape x and
//! root μ ([`SecondOrder::eigenvectors`](super::second_order::SecondOrder::eigenvectors));
//! [`eigenvectors`](super::eigenvectors) chooses.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::complex_schur::complex_schur;
use super::schur::{SchurOptions, real_schur};
use super::structure::{EigenStructure, structure_of};
use crate::error::Result;

/// The eigenvectors of one distinct eigenvalue.
#[derive(Clone, Debug)]
pub struct EigenvectorSet {
    /// The eigenvalue (a cluster mean for a multiple one).
    pub value: Complex64,
    /// Its algebraic multiplicity.
    pub algebraic: usize,
    /// Orthonormal basis of the eigenspace, n×g (g the geometric multiplicity); real entries
    /// for a real eigenvalue.
    pub vectors: DMatrix<Complex64>,
    /// ‖Av − λv‖₂ / (max(‖A‖₁, ‖A‖∞)·‖v‖₂) for each column v.
    pub residuals: Vec<f64>,
}

/// Eigenvalues with their eigenspaces by the Schur form whatever the structure of A, in the
/// order of the clusters of the eigen structure (also returned).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::eigvec::general_eigenvectors;
/// // Undamped oscillator x'' = −4x: eigenvalues ±2i, mode shapes (1, ±2i)/√5.
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, 0.0]);
/// let (sets, _) = general_eigenvectors(&a).unwrap();
/// assert_eq!(sets.len(), 2);
/// for s in &sets {
///     assert!(s.residuals[0] < 1e-15);
///     let v = s.vectors.column(0);
///     let ratio = v[1] / v[0];
///     assert!((ratio - s.value).norm() < 1e-14); // v ∝ (1, λ)
/// }
/// ```
pub fn general_eigenvectors(a: &DMatrix<f64>) -> Result<(Vec<EigenvectorSet>, EigenStructure)> {
    let n = super::checks::check_square(a, "the matrix")?;
    let real = real_schur(a, SchurOptions::default())?;
    let cs = complex_schur(&real);
    let (structure, bases) = structure_of(&real, &cs, true);
    let Some(q) = &real.q else {
        return Ok((Vec::new(), structure));
    };
    // Stack Z·y of every computed basis as real and imaginary parts: one product with Q.
    let mut cols: Vec<(usize, usize)> = Vec::new(); // (cluster, column)
    let mut y_re = Vec::new();
    let mut y_im = Vec::new();
    for (ci, basis) in bases.iter().enumerate() {
        let Some(b) = basis else { continue };
        for j in 0..b.ncols() {
            let mut y: Vec<Complex64> = b.column(j).iter().copied().collect();
            cs.apply_z(&mut y);
            y_re.extend(y.iter().map(|z| z.re));
            y_im.extend(y.iter().map(|z| z.im));
            cols.push((ci, j));
        }
    }
    let k = cols.len();
    let vr = q * DMatrix::from_column_slice(n, k, &y_re);
    let vi = q * DMatrix::from_column_slice(n, k, &y_im);
    let norm_a = super::norms::norm_1_inf(a);
    let mut sets: Vec<Option<EigenvectorSet>> = vec![None; structure.clusters.len()];
    for (ci, cluster) in structure.clusters.iter().enumerate() {
        let idx: Vec<usize> = (0..k).filter(|&c| cols[c].0 == ci).collect();
        if idx.is_empty() {
            continue;
        }
        let mut v = DMatrix::from_fn(n, idx.len(), |i, j| {
            Complex64::new(vr[(i, idx[j])], vi[(i, idx[j])]) * real.d[i]
        });
        v = if cluster.value.im == 0.0 {
            real_basis(&v, idx.len())
        } else {
            orthonormal(&v)
        };
        normalise_phase(&mut v);
        let residuals = residuals(a, &v, cluster.value, norm_a);
        sets[ci] = Some(EigenvectorSet {
            value: cluster.value,
            algebraic: cluster.algebraic,
            vectors: v,
            residuals,
        });
    }
    // Lower conjugates: the conjugate of the partner's basis.
    for ci in 0..sets.len() {
        if sets[ci].is_some() {
            continue;
        }
        let c = &structure.clusters[ci];
        let partner = sets
            .iter()
            .flatten()
            .find(|s| s.algebraic == c.algebraic && s.value == c.value.conj() && c.value.im != 0.0);
        if let Some(p) = partner {
            let v = p.vectors.map(|z| z.conj());
            let residuals = residuals(a, &v, c.value, norm_a);
            sets[ci] = Some(EigenvectorSet {
                value: c.value,
                algebraic: c.algebraic,
                vectors: v,
                residuals,
            });
        }
    }
    Ok((sets.into_iter().flatten().collect(), structure))
}

/// Orthonormal columns spanning the same space (thin QR).
pub(crate) fn orthonormal(v: &DMatrix<Complex64>) -> DMatrix<Complex64> {
    if v.ncols() == 1 {
        let nv = v.norm();
        return if nv > 0.0 {
            v / Complex64::new(nv, 0.0)
        } else {
            v.clone()
        };
    }
    v.clone().qr().q()
}

/// A real orthonormal basis (g columns) of the span of the real and imaginary parts.
fn real_basis(v: &DMatrix<Complex64>, g: usize) -> DMatrix<Complex64> {
    let n = v.nrows();
    let stacked = DMatrix::from_fn(n, 2 * v.ncols(), |i, j| {
        let z = v[(i, j / 2)];
        if j % 2 == 0 { z.re } else { z.im }
    });
    // (nalgebra's `svd()` panics on a NaN singular value: non-finite input keeps `v`)
    if stacked.iter().any(|x| !x.is_finite()) {
        return v.clone();
    }
    let Some(svd) = stacked.try_svd(
        true,
        false,
        f64::EPSILON,
        crate::numeric::lstsq::MAX_SVD_ITER,
    ) else {
        return v.clone();
    };
    let Some(u) = svd.u else {
        return v.clone();
    };
    let mut idx: Vec<usize> = (0..svd.singular_values.len()).collect();
    idx.sort_by(|&a, &b| svd.singular_values[b].total_cmp(&svd.singular_values[a]));
    DMatrix::from_fn(n, g, |i, j| Complex64::new(u[(i, idx[j])], 0.0))
}

/// Scales each column so that its largest entry is real and positive.
pub(crate) fn normalise_phase(v: &mut DMatrix<Complex64>) {
    for mut col in v.column_iter_mut() {
        let big = col
            .iter()
            .copied()
            .max_by(|a, b| a.norm().total_cmp(&b.norm()))
            .unwrap_or(Complex64::new(1.0, 0.0));
        if big.norm() > 0.0 {
            let phase = big.conj() / big.norm();
            col.iter_mut().for_each(|z| *z *= phase);
        }
    }
}

/// ‖Av − λv‖₂/(‖A‖·‖v‖₂) per column.
pub(crate) fn residuals(
    a: &DMatrix<f64>,
    v: &DMatrix<Complex64>,
    lambda: Complex64,
    norm_a: f64,
) -> Vec<f64> {
    let vr = v.map(|z| z.re);
    let vi = v.map(|z| z.im);
    let (ar, ai) = (a * &vr, a * &vi);
    (0..v.ncols())
        .map(|j| {
            let mut r2 = 0.0;
            let mut v2 = 0.0;
            for i in 0..v.nrows() {
                let av = Complex64::new(ar[(i, j)], ai[(i, j)]);
                r2 += (av - lambda * v[(i, j)]).norm_sqr();
                v2 += v[(i, j)].norm_sqr();
            }
            if v2 == 0.0 || norm_a == 0.0 {
                r2.sqrt()
            } else {
                r2.sqrt() / (norm_a * v2.sqrt())
            }
        })
        .collect()
}
