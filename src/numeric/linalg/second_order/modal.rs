//! The modal form of a second-order model from its modes ([`SecondOrder::modal_form`]): no
//! Schur form, no reordering, no Sylvester solves.

use nalgebra::DMatrix;
use num_complex::Complex64 as C;

use super::SecondOrder;
use crate::numeric::linalg::modal::{CLUSTER_REL, MAX_COND, ModalBlock, ModalForm};

impl SecondOrder {
    /// The modal form of the model (A, B, C, D) whose A this structure was recognised in (see
    /// the [module docs](super)), built from its modes without a Schur form:
    /// X = diag(X_q, X_q)·P with, per mode, P = [[1, 1], [μ₁, μ₂]] (two 1×1 blocks μ₁, μ₂; the
    /// lower one of a complex pair with exactly conjugate data) or, for a critical mode or
    /// roots closer than [`CLUSTER_REL`]·ν, P = [[1, 0], [μ₁, 1]] and the 2×2 block
    /// [[μ₁, 1], [0, μ₂]]. `None` when the condition estimate exceeds [`MAX_COND`]. No
    /// Hessenberg check: the modes were verified by their residuals when recognised.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::numeric::linalg::second_order::SecondOrder;
    /// // q̈ = −4q − 0.8q̇ + u, y = q: G = 1/(s² + 0.8s + 4)
    /// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, -0.8]);
    /// let (b, c) = (DMatrix::from_row_slice(2, 1, &[0.0, 1.0]), DMatrix::from_row_slice(1, 2, &[1.0, 0.0]));
    /// let so = SecondOrder::detect(&a).unwrap();
    /// let m = so.modal_form(&b, &c, &DMatrix::zeros(1, 1)).unwrap();
    /// let s = num_complex::Complex64::new(0.1, 1.5);
    /// assert!((m.eval(s)[(0, 0)] - 1.0 / (s * s + 0.8 * s + 4.0)).norm() < 1e-15);
    /// ```
    pub fn modal_form(
        &self,
        b: &DMatrix<f64>,
        c: &DMatrix<f64>,
        d: &DMatrix<f64>,
    ) -> Option<ModalForm> {
        let so = self;
        let dof = so.dof;
        let n = 2 * dof;
        let (m, p) = (b.ncols(), c.nrows());
        let beta_q = &so.shapes_inv * b.rows(0, dof);
        let beta_v = &so.shapes_inv * b.rows(dof, dof);
        let gam_q = c.columns(0, dof) * &so.shapes;
        let gam_v = c.columns(dof, dof) * &so.shapes;
        let mut blocks = Vec::with_capacity(n);
        let mut b_hat = DMatrix::<C>::zeros(n, m);
        let mut c_hat = DMatrix::<C>::zeros(p, n);
        let mut maps = Vec::with_capacity(dof);
        let one = C::new(1.0, 0.0);
        let zero = C::new(0.0, 0.0);
        let mut cond_p = 1.0f64;
        for (k, mode) in so.modes.iter().enumerate() {
            let [m1, m2] = mode.roots;
            let i0 = 2 * k;
            let split = !mode.critical && (m1 - m2).norm() > CLUSTER_REL * so.scale;
            let (pm, pinv) = if split {
                let det = m2 - m1;
                (
                    [[one, one], [m1, m2]],
                    [[m2 / det, -one / det], [-m1 / det, one / det]],
                )
            } else {
                ([[one, zero], [m1, one]], [[one, zero], [-m1, one]])
            };
            let fro2 = |x: &[[C; 2]; 2]| x.iter().flatten().map(|z| z.norm_sqr()).sum::<f64>();
            cond_p = cond_p.max((fro2(&pm) * fro2(&pinv)).sqrt() / 2.0);
            for col in 0..m {
                let (bq, bv) = (beta_q[(k, col)], beta_v[(k, col)]);
                b_hat[(i0, col)] = pinv[0][0] * bq + pinv[0][1] * bv;
                b_hat[(i0 + 1, col)] = pinv[1][0] * bq + pinv[1][1] * bv;
            }
            for row in 0..p {
                let (cq, cv) = (gam_q[(row, k)], gam_v[(row, k)]);
                c_hat[(row, i0)] = pm[0][0] * cq + pm[1][0] * cv;
                c_hat[(row, i0 + 1)] = pm[0][1] * cq + pm[1][1] * cv;
            }
            let mut pinv = pinv;
            if split && m1.im > 0.0 && m2 == m1.conj() {
                // the lower member of a complex pair: exactly the conjugate of the upper one
                for col in 0..m {
                    b_hat[(i0 + 1, col)] = b_hat[(i0, col)].conj();
                }
                for row in 0..p {
                    c_hat[(row, i0 + 1)] = c_hat[(row, i0)].conj();
                }
                pinv[1] = [pinv[0][0].conj(), pinv[0][1].conj()];
            }
            maps.push(pinv);
            if split {
                blocks.push(ModalBlock {
                    start: i0,
                    lambda: DMatrix::from_element(1, 1, m1),
                });
                blocks.push(ModalBlock {
                    start: i0 + 1,
                    lambda: DMatrix::from_element(1, 1, m2),
                });
            } else {
                blocks.push(ModalBlock {
                    start: i0,
                    lambda: DMatrix::from_row_slice(2, 2, &[m1, one, zero, m2]),
                });
            }
        }
        let fro = |x: &DMatrix<f64>| x.norm();
        let cond = cond_p * fro(&so.shapes) * fro(&so.shapes_inv) / dof as f64;
        if !(cond.is_finite() && cond <= MAX_COND) {
            return None;
        }
        Some(ModalForm::in_mode_coordinates(
            blocks,
            b_hat,
            c_hat,
            d.clone(),
            cond,
            so.shapes_inv.clone(),
            maps,
        ))
    }
}
