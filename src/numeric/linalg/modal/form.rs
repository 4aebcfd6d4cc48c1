//! The modal form itself: Λ's blocks, B̂ and Ĉ, X⁻¹ for initial states, and its evaluation
//! (see the [module docs](super)).

use nalgebra::DMatrix;
use num_complex::Complex64;

/// Eigenvalues closer than this times ‖A‖_F share a block (a 2×2 Jordan block of A computed
/// in f64 splits into a pair ~2·√(ε·‖A‖·|coupling|) apart, ~3e-8·‖A‖).
pub const CLUSTER_REL: f64 = 1e-6;
/// Largest block: beyond it the per-point solves are no longer cheap.
pub const MAX_BLOCK: usize = 32;
/// Largest accepted condition estimate ‖Y‖_F·‖Y⁻¹‖_F of the block diagonalisation.
pub const MAX_COND: f64 = 1e6;
/// Largest relative difference from the Hessenberg evaluation at the probe points.
pub const CHECK_REL: f64 = 1e-10;

pub(super) type C = Complex64;

/// A block of the modal form: rows/columns `start..start + size` of Λ.
#[derive(Clone, Debug)]
pub struct ModalBlock {
    /// First index.
    pub start: usize,
    /// Upper triangular Λᵢ (size × size).
    pub lambda: DMatrix<C>,
}

/// The modal form (see the [module docs](super)).
#[derive(Clone, Debug)]
pub struct ModalForm {
    /// The diagonal blocks of Λ.
    pub blocks: Vec<ModalBlock>,
    /// B̂ = X⁻¹·B (n × m).
    pub b: DMatrix<C>,
    /// Ĉ = C·X (p × n).
    pub c: DMatrix<C>,
    /// X⁻¹, for initial states.
    pub(super) inverse: Inverse,
    /// D (p × m).
    pub d: DMatrix<f64>,
    /// The condition estimate of the block diagonalisation.
    pub cond: f64,
}

/// X⁻¹ in factored form (for the modal coordinates of an initial state).
#[derive(Clone, Debug)]
pub(super) enum Inverse {
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

impl ModalForm {
    /// A modal form in the coordinates of a second-order model's modes (built by
    /// [`SecondOrder::modal_form`](crate::numeric::linalg::second_order::SecondOrder::modal_form)): X⁻¹ maps a
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
}
