//! Controllability and observability by the orthogonal staircase form (Van Dooren 1981,
//! Algorithm 1; the form SLICOT's `TB01UD` computes, Varga's "orthogonal canonical form").
//!
//! # Method
//! A rank-revealing QR ([`super::rrqr`]) compresses the rows of B to ρ₁ independent ones;
//! the same orthogonal transformation, applied as a similarity, brings A's block below them
//! into view; that block is compressed in turn, and so on until a block has numerical rank 0
//! (the rest is uncontrollable) or the states are exhausted:
//!
//! ```text
//!      ⎡A₁₁ A₁₂ ⋯  A₁ₖ   *  ⎤        ⎡B₁⎤
//!      ⎢A₂₁ A₂₂ ⋯  A₂ₖ   *  ⎥        ⎢0 ⎥
//! ZᵀAZ=⎢ 0  A₃₂ ⋯   ⋮    *  ⎥,  ZᵀB = ⎢⋮ ⎥,  B₁, A₂₁, A₃₂, … of full row rank.
//!      ⎢ ⋮       ⋱  Aₖₖ   *  ⎥        ⎢  ⎥
//!      ⎣ 0   ⋯   0   0  A_uc⎦        ⎣0 ⎦
//! ```
//! The controllable dimension is ρ₁ + … + ρₖ; the eigenvalues of A_uc are the uncontrollable
//! modes. Observability is the same on the dual (Aᵀ, Cᵀ).
//!
//! **Balancing first.** The system matrix \[A B; C 0\] is balanced by an exact diagonal
//! similarity with powers of two (D⁻¹AD, D⁻¹B, CD), as SLICOT's `TB01PD` does with `TB01ID`
//! before its staircases. Without it one large entry sets the tolerance for every state:
//! ControlSystems.jl's "difficult test case for zeros" has an input entry of 5e8 into a state
//! whose couplings are 1e-18, and the unbalanced staircase called three of its four modes
//! uncontrollable (minimal order 1 instead of 3).
//!
//! **Tolerance.** A block is of rank ρ when its pivoted QR leaves only columns of norm
//! ≤ tol·‖[A B]‖_F (of the balanced system), with the default tol = n²·ε (`TB01UD`'s
//! default); setting the rest to zero is a perturbation of that size, so the computed form is
//! exactly that of a system within n²·ε·‖[A B]‖_F·√m per step of the balanced one. All
//! transformations after the balancing are products of Householder reflectors (backward
//! stable, O(n³)).

use nalgebra::DMatrix;

use super::householder::Reflector;
use super::rrqr::rank_revealing_qr;
use crate::error::Result;

/// A staircase form (ZᵀAZ, ZᵀB, CZ) and its controllable (or, for
/// [`observability_staircase`], observable) dimension.
#[derive(Clone, Debug)]
pub struct Staircase {
    /// ZᵀAZ: for controllability upper block Hessenberg in its leading block and block upper
    /// triangular ([A_c *; 0 A_uc]); for observability the transpose pattern
    /// ([A_o 0; * A_uo]).
    pub a: DMatrix<f64>,
    /// ZᵀB.
    pub b: DMatrix<f64>,
    /// CZ.
    pub c: DMatrix<f64>,
    /// Z (orthogonal), when requested: the form is ZᵀD⁻¹ADZ, ZᵀD⁻¹B, CDZ.
    pub z: Option<DMatrix<f64>>,
    /// The diagonal of D, the balancing's exact power-of-two scaling of the states (all ones
    /// for a well-scaled system).
    pub scaling: Vec<f64>,
    /// Dimension of the controllable (observable) part: the leading states.
    pub dim: usize,
    /// Sizes ρ₁, ρ₂, … of the staircase steps (ρ₁ = rank of B, resp. C).
    pub blocks: Vec<usize>,
    /// The absolute rank tolerance used (tol·‖[A B]‖_F).
    pub abs_tol: f64,
    /// How far above the tolerance the kept directions were: the smallest pivot |R_kk| of
    /// the rank-revealing QR factors, over every step and every kept k, over `abs_tol` (∞
    /// when nothing was kept or the tolerance is 0). A small margin marks a rank decision
    /// that rounding could have made.
    pub margin: f64,
}

impl Staircase {
    /// The uncontrollable (unobservable) block: the trailing (n − dim)×(n − dim) part of A.
    pub fn removed_block(&self) -> DMatrix<f64> {
        let n = self.a.nrows();
        self.a
            .view((self.dim, self.dim), (n - self.dim, n - self.dim))
            .clone_owned()
    }
}

/// Default relative rank tolerance n²·ε of the staircase (SLICOT `TB01UD`).
pub fn default_tol(n: usize) -> f64 {
    (n * n).max(1) as f64 * f64::EPSILON
}

/// Controllability staircase of (A, B), C transformed along (pass a 0×n matrix if there is
/// none). `tol` is relative to ‖[A B]‖_F (`None`: n²·ε); `want_z` forms Z.
///
/// Errors: inconsistent dimensions, non-finite entries.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::controllability_staircase;
/// // Two modes −1, −2; the input reaches only the first.
/// let a = DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -2.0]);
/// let b = DMatrix::from_row_slice(2, 1, &[1.0, 0.0]);
/// let c = DMatrix::from_row_slice(1, 2, &[1.0, 1.0]);
/// let s = controllability_staircase(&a, &b, &c, None, false).unwrap();
/// assert_eq!(s.dim, 1);
/// assert!((s.removed_block()[(0, 0)] + 2.0).abs() < 1e-15);
/// ```
pub fn controllability_staircase(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    tol: Option<f64>,
    want_z: bool,
) -> Result<Staircase> {
    staircase(a, b, c, tol, want_z, true)
}

/// The controllability staircase, with or without the balancing (a caller that balanced the
/// system once — the minimal realisation, for both of its staircases — passes `false`).
pub(crate) fn staircase(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    tol: Option<f64>,
    want_z: bool,
    balance: bool,
) -> Result<Staircase> {
    let d = DMatrix::zeros(c.nrows(), b.ncols());
    let (n, m, p) = super::checks::check_system(a, b, c, &d)?;
    let mut a = a.clone();
    let mut b = b.clone();
    let mut c = c.clone();
    let scaling = if balance {
        crate::numeric::balance::balance_system(&mut a, &mut b, &mut c)
    } else {
        vec![1.0; n]
    };
    let mut z = want_z.then(|| DMatrix::<f64>::identity(n, n));
    let norm = super::norms::frobenius(a.iter().chain(b.iter()));
    let abs_tol = tol.unwrap_or_else(|| default_tol(n)) * norm;
    let mut blocks = Vec::new();
    let mut margin = f64::INFINITY;
    let mut r0 = 0; // first row not yet in the staircase
    let mut c_prev = 0; // first column of the block being compressed (in A)
    while r0 < n {
        let cand = if blocks.is_empty() {
            b.clone()
        } else {
            a.view((r0, c_prev), (n - r0, r0 - c_prev)).clone_owned()
        };
        let f = rank_revealing_qr(&cand, abs_tol);
        let rho = f.rank;
        if abs_tol > 0.0 {
            for k in 0..rho {
                margin = margin.min(f.r[(k, k)].abs() / abs_tol);
            }
        }
        for refl in &f.reflectors {
            let r = Reflector {
                offset: refl.offset + r0,
                v: refl.v.clone(),
                tau: refl.tau,
            };
            if blocks.is_empty() {
                r.apply_left(&mut b, 0..m);
                r.apply_left(&mut a, 0..n);
            } else {
                r.apply_left(&mut a, c_prev..n);
            }
            r.apply_right(&mut a, 0..n);
            r.apply_right(&mut c, 0..p);
            if let Some(z) = z.as_mut() {
                r.apply_right(z, 0..n);
            }
        }
        // The compressed block: rows below its rank are negligible — make them exact zeros.
        if blocks.is_empty() {
            for j in 0..m {
                for i in rho..n {
                    b[(i, j)] = 0.0;
                }
            }
        } else {
            for j in c_prev..r0 {
                for i in r0 + rho..n {
                    a[(i, j)] = 0.0;
                }
            }
        }
        if rho == 0 {
            break;
        }
        blocks.push(rho);
        c_prev = r0;
        r0 += rho;
    }
    Ok(Staircase {
        a,
        b,
        c,
        z,
        scaling,
        dim: r0,
        blocks,
        abs_tol,
        margin,
    })
}

/// Observability staircase of (A, C), B transformed along: the controllability staircase of
/// the dual (Aᵀ, Cᵀ, Bᵀ), transposed back. The result has A = [A_o 0; * A_uo],
/// C = [C_o 0]; `dim` is the observable dimension. `tol` is relative to ‖[A; C]‖_F (of the
/// balanced system; `scaling` is D of the primal form ZᵀD⁻¹ADZ).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::observability_staircase;
/// // The output sees only the first of two decoupled modes.
/// let a = DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -2.0]);
/// let b = DMatrix::from_row_slice(2, 1, &[1.0, 1.0]);
/// let c = DMatrix::from_row_slice(1, 2, &[1.0, 0.0]);
/// let s = observability_staircase(&a, &b, &c, None, false).unwrap();
/// assert_eq!(s.dim, 1);
/// assert!((s.removed_block()[(0, 0)] + 2.0).abs() < 1e-15);
/// ```
pub fn observability_staircase(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    tol: Option<f64>,
    want_z: bool,
) -> Result<Staircase> {
    let dual =
        controllability_staircase(&a.transpose(), &c.transpose(), &b.transpose(), tol, want_z)?;
    Ok(Staircase {
        a: dual.a.transpose(),
        b: dual.c.transpose(),
        c: dual.b.transpose(),
        z: dual.z,
        // The dual was balanced as E⁻¹AᵀE: back in the primal that is D = E⁻¹.
        scaling: dual.scaling.iter().map(|e| 1.0 / e).collect(),
        dim: dual.dim,
        blocks: dual.blocks,
        abs_tol: dual.abs_tol,
        margin: dual.margin,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // these tests expect exact zeros and exact values
    use super::*;

    /// The margin is the smallest kept pivot over the tolerance: here the coupling 3e-3 of
    /// the second state (b already is e₁, so the first pivot is 1).
    #[test]
    fn margin_is_the_smallest_kept_pivot() {
        let a = DMatrix::from_row_slice(2, 2, &[-1.0, 0.5, 3e-3, -2.0]);
        let b = DMatrix::from_row_slice(2, 1, &[1.0, 0.0]);
        let c = DMatrix::from_row_slice(1, 2, &[1.0, 1.0]);
        let s = staircase(&a, &b, &c, None, false, false).unwrap();
        assert_eq!(s.dim, 2);
        let smallest = s.margin * s.abs_tol;
        assert!((smallest - 3e-3).abs() <= 1e-15, "{smallest}");
        // nothing kept: an infinite margin
        let z = DMatrix::zeros(2, 1);
        let s = staircase(&a, &z, &c, None, false, false).unwrap();
        assert_eq!(s.dim, 0);
        assert_eq!(s.margin, f64::INFINITY);
    }

    #[test]
    fn orthogonal_similarity_and_zero_pattern() {
        // A controllable pair hidden by a rotation plus an uncontrollable mode.
        let a0 = DMatrix::from_row_slice(
            4,
            4,
            &[
                -1.0, 1.0, 0.0, 0.3, //
                0.0, -2.0, 1.0, 0.2, //
                0.0, 0.0, -3.0, 0.1, //
                0.0, 0.0, 0.0, -5.0,
            ],
        );
        let b0 = DMatrix::from_row_slice(4, 1, &[0.0, 0.0, 1.0, 0.0]);
        let h = super::super::householder::form_product(
            4,
            &[super::super::householder::fixed_reflector(4)],
        );
        let a = &h * &a0 * &h;
        let b = &h * &b0;
        let c = DMatrix::from_row_slice(1, 4, &[1.0, 2.0, 3.0, 4.0]);
        let s = controllability_staircase(&a, &b, &c, None, true).unwrap();
        assert_eq!(s.dim, 3);
        assert_eq!(s.blocks, vec![1, 1, 1]);
        let z = s.z.clone().unwrap();
        let d = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(s.scaling.clone()));
        let d_inv = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(
            s.scaling.iter().map(|x| 1.0 / x).collect(),
        ));
        let (a, b, c) = (&d_inv * &a * &d, &d_inv * &b, &c * &d);
        assert!((z.transpose() * &a * &z - &s.a).norm() < 1e-14 * a.norm());
        assert!((z.transpose() * &b - &s.b).norm() < 1e-15);
        assert!((&c * &z - &s.c).norm() < 1e-14);
        assert!((s.removed_block()[(0, 0)] + 5.0).abs() < 1e-14);
        for j in 0..3 {
            assert_eq!(s.a[(3, j)], 0.0);
        }
    }
}
