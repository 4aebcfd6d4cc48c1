//! The zero-order-hold discretisation of a second-order model from its modes
//! ([`SecondOrder::zoh`]): one 4×4 exponential per mode and four products of half the order,
//! instead of the exponential of the whole (n + m)-square augmented matrix.

use nalgebra::DMatrix;

use super::SecondOrder;
use crate::error::Result;

impl SecondOrder {
    /// Φ = e^(AT) and Γ = ∫₀ᵀ e^(Aτ) dτ · B of the model whose A this structure was recognised
    /// in (see the [module docs](super)): per mode, the exponential of the 4×4 matrix
    /// [[M·T, I·T], [0, 0]] (M = [[0, 1], [−λ, −γ]]) gives its φ = e^(MT) and ψ = ∫₀ᵀ e^(Mτ) dτ
    /// at once — critical modes and free modes (λ = 0) included, no closed form to cancel —
    /// and the blocks of Φ are X_q·diag(φᵢⱼ)·X_q⁻¹ (four d×d products), Γ = diag(X_q, X_q)·ψ·
    /// diag(X_q⁻¹, X_q⁻¹)·B.
    ///
    /// The modes' stiffness and damping were snapped within [`super::snap_tol`] when
    /// recognised: Φ and Γ are those of a matrix within that distance of A.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::numeric::{expm, linalg::second_order::SecondOrder};
    /// // q̈ = −4q − 0.8q̇ + u
    /// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, -0.8]);
    /// let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
    /// let (phi, gamma) = SecondOrder::detect(&a).unwrap().zoh(&b, 0.1).unwrap();
    /// // against the exponential of the augmented matrix [[A·T, B·T], [0, 0]]
    /// let mut aug = DMatrix::zeros(3, 3);
    /// aug.view_mut((0, 0), (2, 2)).copy_from(&(&a * 0.1));
    /// aug.view_mut((0, 2), (2, 1)).copy_from(&(&b * 0.1));
    /// let e = expm(&aug).unwrap();
    /// assert!((phi - e.view((0, 0), (2, 2))).norm() < 1e-15);
    /// assert!((gamma - e.view((0, 2), (2, 1))).norm() < 1e-16);
    /// ```
    pub fn zoh(&self, b: &DMatrix<f64>, dt: f64) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
        let d = self.dof;
        let m = b.ncols();
        // inputs in modal coordinates: β_q = X_q⁻¹·B_q, β_v = X_q⁻¹·B_v
        let beta_q = &self.shapes_inv * b.rows(0, d);
        let beta_v = &self.shapes_inv * b.rows(d, d);
        let mut phi = [vec![0.0; d], vec![0.0; d], vec![0.0; d], vec![0.0; d]];
        let mut gq = DMatrix::<f64>::zeros(d, m);
        let mut gv = DMatrix::<f64>::zeros(d, m);
        let mut aug = DMatrix::<f64>::zeros(4, 4);
        for (k, mode) in self.modes.iter().enumerate() {
            aug.fill(0.0);
            aug[(0, 1)] = dt;
            aug[(1, 0)] = -mode.stiffness * dt;
            aug[(1, 1)] = -mode.damping * dt;
            aug[(0, 2)] = dt;
            aug[(1, 3)] = dt;
            let e = crate::numeric::expm(&aug)?;
            phi[0][k] = e[(0, 0)];
            phi[1][k] = e[(0, 1)];
            phi[2][k] = e[(1, 0)];
            phi[3][k] = e[(1, 1)];
            let (p11, p12, p21, p22) = (e[(0, 2)], e[(0, 3)], e[(1, 2)], e[(1, 3)]);
            for j in 0..m {
                let (bq, bv) = (beta_q[(k, j)], beta_v[(k, j)]);
                gq[(k, j)] = p11 * bq + p12 * bv;
                gv[(k, j)] = p21 * bq + p22 * bv;
            }
        }
        let n = 2 * d;
        let mut big_phi = DMatrix::<f64>::zeros(n, n);
        for (idx, (r, c)) in [(0, 0), (0, d), (d, 0), (d, d)].into_iter().enumerate() {
            // X_q·diag(φ)·X_q⁻¹: scale the columns of X_q, then one product
            let mut scaled = self.shapes.clone();
            for (k, mut col) in scaled.column_iter_mut().enumerate() {
                col *= phi[idx][k];
            }
            big_phi
                .view_mut((r, c), (d, d))
                .copy_from(&(&scaled * &self.shapes_inv));
        }
        let mut gamma = DMatrix::<f64>::zeros(n, m);
        gamma
            .view_mut((0, 0), (d, m))
            .copy_from(&(&self.shapes * &gq));
        gamma
            .view_mut((d, 0), (d, m))
            .copy_from(&(&self.shapes * &gv));
        Ok((big_phi, gamma))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::expm;

    /// The exponential of the augmented matrix [[A·T, B·T], [0, 0]]: Φ and Γ the dense way.
    fn dense(a: &DMatrix<f64>, b: &DMatrix<f64>, dt: f64) -> (DMatrix<f64>, DMatrix<f64>) {
        let (n, m) = (a.nrows(), b.ncols());
        let mut aug = DMatrix::zeros(n + m, n + m);
        aug.view_mut((0, 0), (n, n)).copy_from(&(a * dt));
        aug.view_mut((0, n), (n, m)).copy_from(&(b * dt));
        let e = expm(&aug).unwrap();
        (
            e.view((0, 0), (n, n)).into_owned(),
            e.view((0, n), (n, m)).into_owned(),
        )
    }

    /// A chain of `d` masses (1 + i/d) joined by unit springs, fixed to walls at both ends or
    /// free at both (`free`: K singular, a rigid-body mode), Rayleigh damping C = α·M + β·K:
    /// A = [[0, I], [−M⁻¹K, −M⁻¹C]].
    fn chain(d: usize, alpha: f64, beta: f64, free: bool) -> DMatrix<f64> {
        let mut k = DMatrix::<f64>::zeros(d, d);
        for i in 0..d {
            k[(i, i)] = if free && i == 0 { 1.0 } else { 2.0 };
            if i + 1 < d {
                k[(i, i + 1)] = -1.0;
                k[(i + 1, i)] = -1.0;
            }
        }
        if free {
            // a free chain: the last spring to the wall removed as well, so K is singular
            k[(d - 1, d - 1)] = 1.0;
        }
        let mass: Vec<f64> = (0..d).map(|i| 1.0 + i as f64 / d as f64).collect();
        let mut a = DMatrix::<f64>::zeros(2 * d, 2 * d);
        for i in 0..d {
            a[(i, d + i)] = 1.0;
            for j in 0..d {
                let g = k[(i, j)] / mass[i];
                a[(d + i, j)] = -g;
                let identity = if i == j { 1.0 } else { 0.0 };
                a[(d + i, d + j)] = -(alpha * identity + beta * g); // M⁻¹C = αI + βM⁻¹K
            }
        }
        a
    }

    #[test]
    fn agrees_with_the_dense_exponential() {
        for (alpha, beta, free) in [
            (0.0, 0.0, false),
            (0.05, 0.01, false),
            (0.0, 0.02, true),
            (0.3, 0.0, true),
        ] {
            let a = chain(12, alpha, beta, free);
            let mut b = DMatrix::<f64>::zeros(24, 2);
            b[(12, 0)] = 1.0;
            b[(20, 1)] = 0.5;
            b[(3, 1)] = 0.25; // an input on a position derivative too
            let so = SecondOrder::detect(&a).expect("a chain is second order");
            for dt in [0.01, 0.1, 1.0] {
                let (phi, gamma) = so.zoh(&b, dt).unwrap();
                let (pd, gd) = dense(&a, &b, dt);
                let ep = (&phi - &pd).norm() / pd.norm();
                let eg = (&gamma - &gd).norm() / gd.norm();
                assert!(
                    ep < 1e-13 && eg < 1e-13,
                    "α={alpha} β={beta} T={dt}: {ep:.1e} {eg:.1e}"
                );
            }
        }
    }

    #[test]
    fn a_critical_mode_and_a_free_mode() {
        // q̈ = −q − 2q̇ (critical: s = −1 double) and q̈ = 0 (free): exact e^(MT) and ψ
        let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, -2.0]);
        let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
        let t = 0.5f64;
        let (phi, gamma) = SecondOrder::detect(&a).unwrap().zoh(&b, t).unwrap();
        let e = (-t).exp();
        // e^(MT) = e^(−T)·[[1 + T, T], [−T, 1 − T]]; Γ = [1 − e^(−T)(1 + T), T·e^(−T)]
        let want = DMatrix::from_row_slice(2, 2, &[e * (1.0 + t), e * t, -e * t, e * (1.0 - t)]);
        assert!((&phi - want).norm() < 1e-15);
        assert!((gamma[(0, 0)] - (1.0 - e * (1.0 + t))).abs() < 1e-16);
        assert!((gamma[(1, 0)] - t * e).abs() < 1e-16);
        let free = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
        let (phi, gamma) = SecondOrder::detect(&free).unwrap().zoh(&b, t).unwrap();
        assert_eq!(phi.as_slice(), &[1.0, 0.0, t, 1.0]); // column-major [[1, T], [0, 1]]
        assert_eq!(gamma.as_slice(), &[t * t / 2.0, t]);
    }
}
