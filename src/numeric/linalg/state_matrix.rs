//! The state matrix A of a model with the structure recognised in it: the one place where the
//! second-order (mechanical) recognition runs.
//!
//! A state-space model enters the eigen analyses through a [`StateMatrix`], built once per
//! model ([`StateMatrix::recognise`]). It carries the structure of [`super::second_order`] — or
//! its absence — and hands it to the kernels that can use it: the eigen structure, the
//! eigenvectors and the modal form come from the modes when A has the structure, and from the
//! general (Schur) kernels of [`super::structure`], [`super::eigvec`] and [`super::modal`]
//! otherwise. Those kernels know nothing of the structure; the second-order module builds on
//! their types, and this file chooses between them.
//!
//! The free functions [`eigen_structure`] and [`eigenvectors`] and [`ModalForm::new`] recognise
//! a matrix and use it once: for a caller with one question about one matrix. A caller with
//! several (the factored core's state-space channel, the whole-model analysis) recognises once
//! and asks the [`StateMatrix`].

use nalgebra::DMatrix;

use super::checks::check_square;
use super::eigvec::{EigenvectorSet, general_eigenvectors};
use super::modal::ModalForm;
use super::second_order::SecondOrder;
use super::structure::{EigenStructure, general_eigen_structure};
use crate::error::Result;

/// A state matrix A with its recognised structure (see the [module docs](self)).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::StateMatrix;
/// // Two unit masses between walls, springs k = 1, Rayleigh damping E = 0.1·G:
/// // recognised once, then three questions without a Schur form.
/// let a = DMatrix::from_row_slice(4, 4, &[
///     0.0, 0.0, 1.0, 0.0,
///     0.0, 0.0, 0.0, 1.0,
///     -2.0, 1.0, -0.2, 0.1,
///     1.0, -2.0, 0.1, -0.2,
/// ]);
/// let sm = StateMatrix::recognise(&a);
/// assert_eq!(sm.second_order().map(|so| so.dof), Some(2));
/// assert_eq!(sm.eigen_structure().unwrap().clusters.len(), 4);
/// let (sets, _) = sm.eigenvectors().unwrap();
/// assert!(sets.iter().all(|s| s.residuals[0] < 1e-15));
/// let b = DMatrix::from_row_slice(4, 1, &[0.0, 0.0, 1.0, 0.0]);
/// let c = DMatrix::from_row_slice(1, 4, &[1.0, 0.0, 0.0, 0.0]);
/// let m = sm.modal_form(&b, &c, &DMatrix::zeros(1, 1)).unwrap().unwrap();
/// assert_eq!(m.blocks.len(), 4);
/// // a general matrix has no structure: the general kernels answer
/// let g = DMatrix::from_row_slice(2, 2, &[-1.0, 1.0, 0.0, -2.0]);
/// assert!(StateMatrix::recognise(&g).second_order().is_none());
/// ```
#[derive(Clone, Debug)]
pub struct StateMatrix<'a> {
    a: &'a DMatrix<f64>,
    second_order: Option<SecondOrder>,
}

impl<'a> StateMatrix<'a> {
    /// Recognises the structure of `a` (see [`SecondOrder::detect`]; a matrix with a NaN or
    /// infinite entry has none).
    pub fn recognise(a: &'a DMatrix<f64>) -> StateMatrix<'a> {
        let second_order = if a.iter().all(|x| x.is_finite()) {
            SecondOrder::detect(a)
        } else {
            None
        };
        StateMatrix { a, second_order }
    }

    /// The matrix A.
    pub fn matrix(&self) -> &'a DMatrix<f64> {
        self.a
    }

    /// The second-order structure of A, when it has it.
    pub fn second_order(&self) -> Option<&SecondOrder> {
        self.second_order.as_ref()
    }

    /// The eigenvalues of A with their multiplicity structure: from the modes of a
    /// second-order A ([`SecondOrder::eigen_structure`]), else by the Schur form
    /// ([`general_eigen_structure`]).
    ///
    /// Errors: the Schur form's (a non-finite entry, an iteration that does not converge).
    pub fn eigen_structure(&self) -> Result<EigenStructure> {
        match &self.second_order {
            Some(so) => Ok(so.eigen_structure()),
            None => general_eigen_structure(self.a),
        }
    }

    /// The eigenvectors of A, one orthonormal basis per distinct eigenvalue, in the order of
    /// the clusters of its eigen structure (also returned): from the modes of a second-order A
    /// ([`SecondOrder::eigenvectors`]), else by the Schur form ([`general_eigenvectors`]).
    ///
    /// Errors: a matrix that is not square or not finite, the Schur form's.
    pub fn eigenvectors(&self) -> Result<(Vec<EigenvectorSet>, EigenStructure)> {
        check_square(self.a, "the matrix")?;
        match &self.second_order {
            Some(so) => Ok(so.eigenvectors(self.a)),
            None => general_eigenvectors(self.a),
        }
    }

    /// The modal form of (A, B, C, D), or `None` when it is not safe (see [`super::modal`]):
    /// from the modes of a second-order A ([`SecondOrder::modal_form`]), else by the Schur
    /// form ([`ModalForm::from_schur`]).
    ///
    /// Errors: the Schur form's.
    pub fn modal_form(
        &self,
        b: &DMatrix<f64>,
        c: &DMatrix<f64>,
        d: &DMatrix<f64>,
    ) -> Result<Option<ModalForm>> {
        if self.a.nrows() == 0 {
            return Ok(None);
        }
        match &self.second_order {
            Some(so) => Ok(so.modal_form(b, c, d)),
            None => ModalForm::from_schur(self.a, b, c, d),
        }
    }
}

/// Eigenvalues of a square, finite A grouped into multiple eigenvalues with algebraic and
/// geometric multiplicities (see [`super::structure`]): the structure is recognised first, so a
/// matrix with the mechanical structure of [`super::second_order`] gets its eigenvalues from
/// the modes (a symmetric eigenproblem of half the order) instead of the Schur form.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::eigen_structure;
/// // A Jordan block of size 2 at −1 next to a simple eigenvalue −3.
/// let a = DMatrix::from_row_slice(3, 3, &[-1.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -3.0]);
/// let s = eigen_structure(&a).unwrap();
/// let double = s.clusters.iter().find(|c| c.algebraic == 2).unwrap();
/// assert!((double.value.re + 1.0).abs() < 1e-14 && double.value.im == 0.0);
/// assert_eq!(double.geometric, 1);
/// // The identity: one eigenvalue of multiplicity 3, semisimple.
/// let s = eigen_structure(&DMatrix::identity(3, 3)).unwrap();
/// assert_eq!(s.clusters.len(), 1);
/// assert!(s.clusters[0].is_semisimple() && s.clusters[0].algebraic == 3);
/// ```
pub fn eigen_structure(a: &DMatrix<f64>) -> Result<EigenStructure> {
    StateMatrix::recognise(a).eigen_structure()
}

/// Eigenvalues with their eigenspaces (see [`super::eigvec`]), in the order of the clusters of
/// [`eigen_structure`] (also returned); the structure is recognised first (see
/// [`StateMatrix::eigenvectors`]).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::eigenvectors;
/// // Undamped oscillator x'' = −4x: eigenvalues ±2i, mode shapes (1, ±2i)/√5.
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, 0.0]);
/// let (sets, _) = eigenvectors(&a).unwrap();
/// assert_eq!(sets.len(), 2);
/// for s in &sets {
///     assert!(s.residuals[0] < 1e-15);
///     let v = s.vectors.column(0);
///     let ratio = v[1] / v[0];
///     assert!((ratio - s.value).norm() < 1e-14); // v ∝ (1, λ)
/// }
/// ```
pub fn eigenvectors(a: &DMatrix<f64>) -> Result<(Vec<EigenvectorSet>, EigenStructure)> {
    StateMatrix::recognise(a).eigenvectors()
}

impl ModalForm {
    /// The modal form of (A, B, C, D), or `None` when it is not safe (see [`super::modal`]):
    /// the structure of A is recognised first (see [`StateMatrix::modal_form`]).
    ///
    /// Errors: the Schur step's.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use num_complex::Complex64;
    /// use ltikit::numeric::linalg::{HessenbergResponse, modal::ModalForm};
    /// // Two masses between walls, force on the first, position of the second: second order,
    /// // so the form comes from the modes (four 1×1 blocks); it agrees with the Hessenberg solve.
    /// let a = DMatrix::from_row_slice(4, 4, &[
    ///     0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, -2.0, 1.0, -0.2, 0.1, 1.0, -2.0, 0.1, -0.2,
    /// ]);
    /// let b = DMatrix::from_row_slice(4, 1, &[0.0, 0.0, 1.0, 0.0]);
    /// let (c, d) = (DMatrix::from_row_slice(1, 4, &[0.0, 1.0, 0.0, 0.0]), DMatrix::zeros(1, 1));
    /// let m = ModalForm::new(&a, &b, &c, &d).unwrap().unwrap();
    /// assert_eq!(m.blocks.len(), 4);
    /// let s = Complex64::new(0.3, 2.0);
    /// let h = HessenbergResponse::new(&a, &b, &c, &d).unwrap();
    /// assert!((m.eval(s)[(0, 0)] - h.eval_siso(s)).norm() < 1e-14);
    /// ```
    pub fn new(
        a: &DMatrix<f64>,
        b: &DMatrix<f64>,
        c: &DMatrix<f64>,
        d: &DMatrix<f64>,
    ) -> Result<Option<ModalForm>> {
        StateMatrix::recognise(a).modal_form(b, c, d)
    }
}
