//! The zero-order-hold discretisation of a second-order model from its modes
//! ([`SecondOrder::zoh`]): one 4×4 exponential per mode, two half products of half the order
//! for the upper block row of Φ, and the lower block row from it (sparse products with the
//! stiffness and damping when they are sparse, two more half products when not), instead of
//! the exponential of the whole (n + m)-square augmented matrix; for a periodic ring (circulant
//! G and E) each block from one column.

use nalgebra::{DMatrix, DMatrixViewMut};

use super::{SecondOrder, circulant};
use crate::error::Result;

impl SecondOrder {
    /// Φ = e^(AT) and Γ = ∫₀ᵀ e^(Aτ) dτ · B of the model whose A this structure was recognised
    /// in (see the [module docs](super)): per mode, the exponential of the 4×4 matrix
    /// [[M·T, I·T], [0, 0]] (M = [[0, 1], [−λ, −γ]]) gives its φ = e^(MT) and ψ = ∫₀ᵀ e^(Mτ) dτ
    /// at once — critical modes and free modes (λ = 0) included, no closed form to cancel —
    /// and the blocks of Φ are X_q·diag(φᵢⱼ)·X_q⁻¹ = Δ⁻¹·V·diag(φᵢⱼ)·Vᵀ·Δ (symmetric but
    /// for Δ: half of each by products), Γ = diag(X_q, X_q)·ψ·diag(X_q⁻¹, X_q⁻¹)·B. When G
    /// and E are sparse (a chain, a ring) the lower block row comes from the upper one:
    /// e^(AT) commutes with A, so Φ₂₁ = −Φ₁₂·G and Φ₂₂ = Φ₁₁ − Φ₁₂·E. When G and E are
    /// symmetric circulants (a periodic ring, the shapes its Fourier modes) every block
    /// V·diag(φᵢⱼ)·Vᵀ is circulant: its first column V·(φᵢⱼ ∘ V(0, :)ᵀ) determines it, O(d²)
    /// per block. A mode with the same stiffness and damping as the one before it (the
    /// degenerate pairs of a ring) reuses its 4×4 exponential.
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
        // the 4×4 exponential of the previous mode, reused by a mode with the same stiffness
        // and damping (degenerate modes were snapped to equal values when recognised)
        let mut last: Option<(f64, f64, DMatrix<f64>)> = None;
        for (k, mode) in self.modes.iter().enumerate() {
            let e = match last.take() {
                #[allow(clippy::float_cmp)] // bitwise the same mode
                Some(prev) if prev.0 == mode.stiffness && prev.1 == mode.damping => prev.2,
                _ => {
                    aug.fill(0.0);
                    aug[(0, 1)] = dt;
                    aug[(1, 0)] = -mode.stiffness * dt;
                    aug[(1, 1)] = -mode.damping * dt;
                    aug[(0, 2)] = dt;
                    aug[(1, 3)] = dt;
                    crate::numeric::expm(&aug)?
                }
            };
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
            last = Some((mode.stiffness, mode.damping, e));
        }
        let n = 2 * d;
        let mut big_phi = DMatrix::<f64>::zeros(n, n);
        if self.circulant {
            // a ring: each block V·diag(φ)·Vᵀ is circulant, its first column V·(φ ∘ V(0, :)ᵀ)
            let top = self.shapes.row(0);
            for (f, (r, c)) in phi.iter().zip([(0, 0), (0, d), (d, 0), (d, d)]) {
                let w = nalgebra::DVector::from_fn(d, |m, _| f[m] * top[m]);
                let col = &self.shapes * w;
                circulant::fill(col.as_slice(), &mut big_phi.view_mut((r, c), (d, d)));
            }
            return Ok((big_phi, self.gamma(&gq, &gv, m)));
        }
        // Φ₁₁ and Φ₁₂: X_q·diag(φ)·X_q⁻¹ = Δ⁻¹·(V·diag(φ)·Vᵀ)·Δ, its lower half by products
        let mut w = self.shapes.clone();
        self.similar(&phi[0], &mut w, &mut big_phi, 0, 0);
        self.similar(&phi[1], &mut w, &mut big_phi, 0, d);
        match &self.coupling {
            Some((g, e)) => {
                // e^(AT) commutes with A: the top block rows of A·Φ = Φ·A give Φ₂₁ = −Φ₁₂·G
                // and Φ₂₂ = Φ₁₁ − Φ₁₂·E, sparse products with G = −A₂₁ and E = −A₂₂
                let (top, mut bottom) = big_phi.rows_range_pair_mut(0..d, d..n);
                bottom.columns_mut(d, d).copy_from(&top.columns(0, d));
                g.mul_left_add(&top.columns(d, d), &mut bottom.columns_mut(0, d), -1.0);
                e.mul_left_add(&top.columns(d, d), &mut bottom.columns_mut(d, d), -1.0);
            }
            None => {
                self.similar(&phi[2], &mut w, &mut big_phi, d, 0);
                self.similar(&phi[3], &mut w, &mut big_phi, d, d);
            }
        }
        Ok((big_phi, self.gamma(&gq, &gv, m)))
    }

    /// Γ = diag(X_q, X_q)·\[γ_q; γ_v\] from the modal input columns.
    fn gamma(&self, gq: &DMatrix<f64>, gv: &DMatrix<f64>, m: usize) -> DMatrix<f64> {
        let d = self.dof;
        let mut gamma = DMatrix::<f64>::zeros(2 * d, m);
        gamma
            .view_mut((0, 0), (d, m))
            .copy_from(&(&self.shapes * gq));
        gamma
            .view_mut((d, 0), (d, m))
            .copy_from(&(&self.shapes * gv));
        gamma
    }

    /// X_q·diag(f)·X_q⁻¹ into the d×d block of `out` at (r, c) (`w`: d×d workspace). It is
    /// Δ⁻¹·S·Δ with S = V·diag(f)·Vᵀ symmetric: the blocks on and below the diagonal by
    /// products (about half the work of one d×d×d product), the entries above from
    /// M_ji = M_ij·(δᵢ/δⱼ)².
    fn similar(&self, f: &[f64], w: &mut DMatrix<f64>, out: &mut DMatrix<f64>, r: usize, c: usize) {
        let d = self.dof;
        for (k, (mut col, x)) in w
            .column_iter_mut()
            .zip(self.shapes.column_iter())
            .enumerate()
        {
            col.copy_from(&x);
            col *= f[k];
        }
        let mut m = out.view_mut((r, c), (d, d));
        lower_product(w, &self.shapes_inv, &mut m, 0, d);
        let delta = &self.delta;
        #[allow(clippy::float_cmp)] // exactly 1: no scaling to apply
        let unit = delta.iter().all(|&x| x == 1.0);
        for j in 0..d {
            for i in (j + 1)..d {
                let x = m[(i, j)];
                m[(j, i)] = if unit {
                    x
                } else {
                    let q = delta[i] / delta[j];
                    x * q * q
                };
            }
        }
    }
}

/// Below this size a diagonal block of [`lower_product`] is one full product.
const HALF_PRODUCT_BASE: usize = 32;

/// The rows and columns lo..hi of W·Y on and below the diagonal (diagonal blocks up to
/// [`HALF_PRODUCT_BASE`] in full), into `m`: two halves recursively, the block below them
/// as one product.
fn lower_product(
    w: &DMatrix<f64>,
    y: &DMatrix<f64>,
    m: &mut DMatrixViewMut<'_, f64>,
    lo: usize,
    hi: usize,
) {
    let s = hi - lo;
    if s <= HALF_PRODUCT_BASE {
        m.view_mut((lo, lo), (s, s))
            .gemm(1.0, &w.rows(lo, s), &y.columns(lo, s), 0.0);
        return;
    }
    let mid = lo + s / 2;
    lower_product(w, y, m, lo, mid);
    m.view_mut((mid, lo), (hi - mid, mid - lo)).gemm(
        1.0,
        &w.rows(mid, hi - mid),
        &y.columns(lo, mid - lo),
        0.0,
    );
    lower_product(w, y, m, mid, hi);
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
        // 12 masses: one full product per half; 70: the halves split down to 32 rows
        for (d, alpha, beta, free) in [
            (12, 0.0, 0.0, false),
            (12, 0.05, 0.01, false),
            (12, 0.0, 0.02, true),
            (12, 0.3, 0.0, true),
            (70, 0.05, 0.01, false),
        ] {
            let a = chain(d, alpha, beta, free);
            let mut b = DMatrix::<f64>::zeros(2 * d, 2);
            b[(d, 0)] = 1.0;
            b[(d + 8, 1)] = 0.5;
            b[(3, 1)] = 0.25; // an input on a position derivative too
            let so = SecondOrder::detect(&a).expect("a chain is second order");
            assert!(so.coupling.is_some(), "a chain is sparse");
            for dt in [0.01, 0.1, 1.0] {
                let (phi, gamma) = so.zoh(&b, dt).unwrap();
                let (pd, gd) = dense(&a, &b, dt);
                let ep = (&phi - &pd).norm() / pd.norm();
                let eg = (&gamma - &gd).norm() / gd.norm();
                assert!(
                    ep < 1e-13 && eg < 1e-13,
                    "d={d} α={alpha} β={beta} T={dt}: {ep:.1e} {eg:.1e}"
                );
            }
        }
    }

    /// A ring of `d` unit masses joined by springs k = 1 (the seed's N-periodic lattice),
    /// each also tied to the ground by a spring `ground` (0: the free ring, whose translation
    /// is a zero mode), damping E = α·I + β·G: A = [[0, I], [−G, −E]].
    fn ring(d: usize, ground: f64, alpha: f64, beta: f64) -> DMatrix<f64> {
        let mut a = DMatrix::<f64>::zeros(2 * d, 2 * d);
        for i in 0..d {
            a[(i, d + i)] = 1.0;
            let mut g = vec![0.0; d];
            g[i] += 2.0 + ground;
            g[(i + 1) % d] -= 1.0;
            g[(i + d - 1) % d] -= 1.0;
            for j in 0..d {
                a[(d + i, j)] = -g[j];
                let identity = if i == j { 1.0 } else { 0.0 };
                a[(d + i, d + j)] = -(alpha * identity + beta * g[j]);
            }
        }
        a
    }

    #[test]
    fn rings_take_the_fourier_modes_and_agree_with_the_general_path() {
        // odd and even N (the Nyquist mode), free (λ = 0: the rigid-body limits
        // sin(ωT)/ω → T, (1 − cos ωT)/ω² → T²/2) and grounded, undamped and damped
        for (d, ground, alpha, beta) in [
            (3, 0.0, 0.0, 0.0),
            (4, 0.0, 0.0, 0.0),
            (7, 0.0, 0.0, 0.0),
            (8, 0.5, 0.0, 0.0),
            (9, 0.3, 0.05, 0.01),
            (16, 0.0, 0.0, 0.02),
            (33, 0.0, 0.0, 0.0),
            (64, 0.0, 0.0, 0.0),
            (65, 0.2, 0.1, 0.0),
        ] {
            let a = ring(d, ground, alpha, beta);
            let mut b = DMatrix::<f64>::zeros(2 * d, 2);
            b[(d, 0)] = 1.0;
            b[(d + 2, 1)] = 0.5;
            b[(1, 1)] = 0.25; // an input on a position derivative too
            let so = SecondOrder::detect(&a).expect("a ring is second order");
            assert!(so.circulant, "N={d}: a ring is circulant");
            let general = SecondOrder::detect_with(&a, false).unwrap();
            assert!(!general.circulant);
            let mut worst = [0.0f64; 2];
            for dt in [0.01, 0.1, 1.0] {
                let (phi, gamma) = so.zoh(&b, dt).unwrap();
                let (pd, gd) = dense(&a, &b, dt);
                let ep = (&phi - &pd).norm() / pd.norm();
                let eg = (&gamma - &gd).norm() / gd.norm();
                let (pg, gg) = general.zoh(&b, dt).unwrap();
                let fp = (&phi - &pg).norm() / pg.norm();
                let fg = (&gamma - &gg).norm() / gg.norm();
                worst[0] = worst[0].max(ep.max(eg));
                worst[1] = worst[1].max(fp.max(fg));
                assert!(
                    ep < 1e-13 && eg < 1e-13 && fp < 1e-13 && fg < 1e-13,
                    "N={d} κ={ground} α={alpha} β={beta} T={dt}: dense {ep:.1e} {eg:.1e}, \
                     general {fp:.1e} {fg:.1e}"
                );
            }
            println!(
                "ring N={d} κ={ground} α={alpha} β={beta}: against the dense exponential {:.1e}, \
                 against SymmetricEigen's modes {:.1e}",
                worst[0], worst[1]
            );
        }
    }

    #[test]
    fn a_perturbed_ring_is_not_circulant() {
        // one mass 1 % heavier: G = M⁻¹K is no longer circulant (nor symmetric): the general
        // path, still exact against the dense exponential
        let d = 10;
        let mut a = ring(d, 0.0, 0.0, 0.0);
        for j in 0..d {
            a[(d + 3, j)] /= 1.01;
        }
        let so = SecondOrder::detect(&a).expect("still second order");
        assert!(!so.circulant);
        let b = DMatrix::from_fn(2 * d, 1, |i, _| if i == d { 1.0 } else { 0.0 });
        let (phi, gamma) = so.zoh(&b, 0.1).unwrap();
        let (pd, gd) = dense(&a, &b, 0.1);
        assert!((&phi - &pd).norm() / pd.norm() < 1e-13);
        assert!((&gamma - &gd).norm() / gd.norm() < 1e-13);
    }

    #[test]
    fn dense_coupling_takes_the_four_products() {
        // every mass coupled to every other (K = L·Lᵀ + I with L dense), masses 1 + i/d,
        // Rayleigh damping: more than SPARSE_PER_COLUMN non-zeros per column, so Φ₂₁ and Φ₂₂
        // come from the modes rather than from Φ₁₂·G and Φ₁₂·E
        let d = 10;
        let l = DMatrix::from_fn(d, d, |i, j| ((3 * i + 5 * j) % 7) as f64 / 7.0 - 0.4);
        let k = &l * l.transpose() + DMatrix::identity(d, d);
        let mass: Vec<f64> = (0..d).map(|i| 1.0 + i as f64 / d as f64).collect();
        let g = DMatrix::from_fn(d, d, |i, j| k[(i, j)] / mass[i]);
        let e = DMatrix::identity(d, d) * 0.1 + &g * 0.03;
        let mut a = DMatrix::<f64>::zeros(2 * d, 2 * d);
        a.view_mut((0, d), (d, d))
            .copy_from(&DMatrix::identity(d, d));
        a.view_mut((d, 0), (d, d)).copy_from(&(-&g));
        a.view_mut((d, d), (d, d)).copy_from(&(-&e));
        let so = SecondOrder::detect(&a).expect("Rayleigh-damped masses are second order");
        assert!(so.coupling.is_none(), "G is dense");
        let b = DMatrix::from_fn(2 * d, 1, |i, _| if i == d + 2 { 1.0 } else { 0.0 });
        for dt in [0.05, 0.5] {
            let (phi, gamma) = so.zoh(&b, dt).unwrap();
            let (pd, gd) = dense(&a, &b, dt);
            let ep = (&phi - &pd).norm() / pd.norm();
            let eg = (&gamma - &gd).norm() / gd.norm();
            assert!(ep < 1e-13 && eg < 1e-13, "T={dt}: {ep:.1e} {eg:.1e}");
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
