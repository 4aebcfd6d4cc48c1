//! The eigen structure and the eigenvectors of a second-order model from its modes: no Schur
//! form, no back-substitution (see the [module docs](super)).

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::SecondOrder;
use crate::numeric::linalg::eigvec::{EigenvectorSet, normalise_phase, orthonormal, residuals};
use crate::numeric::linalg::modal::single_linkage;
use crate::numeric::linalg::norms::norm_1_inf;
use crate::numeric::linalg::structure::{EigenCluster, EigenStructure, radius};

impl SecondOrder {
    /// The eigenvalues of A grouped into multiple eigenvalues: roots of different modes within
    /// the simple-eigenvalue radius of [`structure`](crate::numeric::linalg::structure) share a
    /// cluster (semisimple: one eigenvector per mode); a critical mode adds two to the
    /// algebraic and one to the geometric multiplicity. Positions are 2k, 2k + 1 for mode k;
    /// `sigma` holds, per critical mode, the non-zero singular value of its block minus the
    /// eigenvalue (relative to ν) and then one 0 per eigenvector.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::numeric::linalg::second_order::SecondOrder;
    /// // q̈ = −q − 2q̇ (critically damped): −1 is a double eigenvalue with one eigenvector
    /// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, -2.0]);
    /// let st = SecondOrder::detect(&a).unwrap().eigen_structure();
    /// assert_eq!(st.clusters.len(), 1);
    /// assert_eq!((st.clusters[0].algebraic, st.clusters[0].geometric), (2, 1));
    /// assert_eq!(st.clusters[0].value.re, -1.0);
    /// ```
    pub fn eigen_structure(&self) -> EigenStructure {
        let n = self.order();
        let scale = self.scale;
        // (value, position, mode critical)
        let mut ev: Vec<(Complex64, usize, bool)> = Vec::with_capacity(n);
        for (k, m) in self.modes.iter().enumerate() {
            ev.push((m.roots[0], 2 * k, m.critical));
            ev.push((m.roots[1], 2 * k + 1, m.critical));
        }
        let tol = radius(1, n, scale);
        let values: Vec<Complex64> = ev.iter().map(|e| e.0).collect();
        let labels = single_linkage(&values, tol);
        // labels number the clusters in order of first appearance
        let count = labels.iter().map(|&l| l + 1).max().unwrap_or(0);
        let mut clusters: Vec<EigenCluster> = (0..count)
            .map(|_| EigenCluster {
                value: Complex64::new(0.0, 0.0),
                algebraic: 0,
                geometric: 0,
                members: Vec::new(),
                positions: Vec::new(),
                sigma: Vec::new(),
            })
            .collect();
        for (&(value, pos, critical), &label) in ev.iter().zip(&labels) {
            let c = &mut clusters[label];
            c.members.push(value);
            c.positions.push(pos);
            c.algebraic += 1;
            // a critical mode's two roots: one eigenvector (counted at its first root)
            if !critical || pos % 2 == 0 {
                c.geometric += 1;
            }
            if critical && pos % 2 == 0 {
                let m = &self.modes[pos / 2];
                let mu = m.roots[0].re;
                // ‖[[−μ, 1], [−λ, −γ − μ]]‖_F (rank 1)
                let s =
                    (mu * mu + 1.0 + m.stiffness * m.stiffness + (m.damping + mu).powi(2)).sqrt();
                c.sigma.push(s / scale.max(f64::MIN_POSITIVE));
            }
        }
        for c in &mut clusters {
            let sum: Complex64 = c.members.iter().sum();
            let mean = sum / c.members.len() as f64;
            let self_conj = c.members.iter().all(|z| {
                c.members
                    .iter()
                    .any(|w| (w.conj() - z).norm() <= tol || w.conj() == *z)
            });
            c.value = if self_conj {
                Complex64::new(mean.re, 0.0)
            } else {
                mean
            };
            c.sigma.sort_by(|a, b| b.total_cmp(a));
            c.sigma.extend(std::iter::repeat_n(0.0, c.geometric));
        }
        // exact conjugate values for mirrored clusters
        let values: Vec<Complex64> = clusters.iter().map(|c| c.value).collect();
        for c in &mut clusters {
            if c.value.im < 0.0
                && let Some(up) = values
                    .iter()
                    .find(|v| v.im > 0.0 && (v.conj() - c.value).norm() <= tol)
            {
                c.value = up.conj();
            }
        }
        EigenStructure {
            clusters,
            scale,
            rank_tol: f64::EPSILON.sqrt() * scale,
        }
    }

    /// The eigenvectors of A (the matrix this structure was recognised in) from the modes:
    /// mode k with shape x (position coordinates) and root μ has the eigenvector (x, μx); a
    /// multiple eigenvalue takes one vector per mode (a critical mode's double root has only
    /// one), orthonormalised; residuals measured against `a` itself. The sets are in the order
    /// of the clusters of [`SecondOrder::eigen_structure`] (also returned).
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::numeric::linalg::second_order::SecondOrder;
    /// // x'' = −4x: eigenvalues ±2j with shapes (1, ±2j)/√5
    /// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, 0.0]);
    /// let (sets, _) = SecondOrder::detect(&a).unwrap().eigenvectors(&a);
    /// assert_eq!(sets.len(), 2);
    /// for s in &sets {
    ///     let v = s.vectors.column(0);
    ///     assert!((v[1] / v[0] - s.value).norm() < 1e-15 && s.residuals[0] < 1e-15);
    /// }
    /// ```
    pub fn eigenvectors(&self, a: &DMatrix<f64>) -> (Vec<EigenvectorSet>, EigenStructure) {
        let so = self;
        let structure = so.eigen_structure();
        let (d, n) = (so.dof, so.order());
        let norm_a = norm_1_inf(a);
        let mut sets = Vec::with_capacity(structure.clusters.len());
        for cluster in &structure.clusters {
            // one vector per mode of the cluster (the first root of a critical mode stands
            // for it)
            let mut modes: Vec<usize> = cluster.positions.iter().map(|&p| p / 2).collect();
            modes.dedup();
            let mut v = DMatrix::<Complex64>::zeros(n, modes.len());
            for (j, &k) in modes.iter().enumerate() {
                for i in 0..d {
                    let x = Complex64::new(so.shapes[(i, k)], 0.0);
                    v[(i, j)] = x;
                    v[(d + i, j)] = x * cluster.value;
                }
            }
            let mut v = orthonormal(&v);
            if cluster.value.im == 0.0 {
                v.iter_mut().for_each(|z| z.im = 0.0);
            }
            normalise_phase(&mut v);
            let residuals = residuals(a, &v, cluster.value, norm_a);
            sets.push(EigenvectorSet {
                value: cluster.value,
                algebraic: cluster.algebraic,
                vectors: v,
                residuals,
            });
        }
        (sets, structure)
    }
}
