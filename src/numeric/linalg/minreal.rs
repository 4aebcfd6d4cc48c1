//! Minimal realisation: the controllable and observable part of (A, B, C, D), with the
//! removed modes reported.
//!
//! # Method
//! SLICOT `TB01PD`'s order: the [controllability staircase](super::staircase) splits off the
//! uncontrollable part (its eigenvalues are the *uncontrollable modes*), then the staircase of
//! the dual of the controllable part splits off the unobservable part (*unobservable modes*:
//! controllable but not observable). What is left is minimal, and it has the same transfer
//! matrix: only exactly decoupled (to the rank tolerance) parts are removed, by orthogonal
//! similarities. A mode that is both uncontrollable and unobservable is reported among the
//! uncontrollable ones. When the observability staircase of the whole system finds fewer
//! observable states than that order's result, the other order (observable part, then its
//! controllable part) is computed too and the smaller realisation kept (its modes both
//! unobservable and uncontrollable are reported as unobservable): rank decisions in different
//! coordinates can disagree for a defective eigenvalue behind an ill-conditioned
//! similarity, and the minimal order must not exceed the observable (or controllable)
//! dimension that a report states beside it. The removed modes are what a transfer function would show as
//! cancelled pole–zero pairs.
//!
//! The second staircase works on a subsystem the first computed, so its rank decisions see
//! the first one's rounding on top of the tolerance. The observability staircase of the whole
//! system bounds the observable dimension; when the first order exceeds it, the other order
//! (observable part first) is computed and the smaller kept. On harold's defective example
//! (eigenvalue −6 of algebraic multiplicity 3, geometric 2; G = 2(s + 7)/(s + 6)² in every
//! column) the second staircase alone kept the unobservable mode 6 behind a block of 6.7e-14
//! against a tolerance of 2.4e-14: minimal order 3 instead of 2, as SLICOT's `TB01PD`
//! (python-control's `minreal`) gives.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::schur::schur_eigenvalues;
use super::staircase::staircase;
use crate::error::Result;

/// A minimal realisation and what was removed to get it.
#[derive(Clone, Debug)]
pub struct MinimalRealization {
    /// A of the minimal part (n_min × n_min).
    pub a: DMatrix<f64>,
    /// B of the minimal part.
    pub b: DMatrix<f64>,
    /// C of the minimal part.
    pub c: DMatrix<f64>,
    /// D (unchanged).
    pub d: DMatrix<f64>,
    /// Eigenvalues of the removed uncontrollable part.
    pub uncontrollable: Vec<Complex64>,
    /// Eigenvalues of the removed unobservable (controllable) part.
    pub unobservable: Vec<Complex64>,
    /// Dimension of the controllable part: n less the uncontrollable modes listed.
    pub n_controllable: usize,
    /// The absolute rank tolerances of the two staircases.
    pub abs_tol: (f64, f64),
}

impl MinimalRealization {
    /// Order of the minimal realisation.
    pub fn order(&self) -> usize {
        self.a.nrows()
    }
}

/// Minimal realisation of (A, B, C, D); `tol` is the relative rank tolerance of the staircases
/// (`None`: n²·ε, see [`super::staircase`]).
///
/// Errors: inconsistent dimensions, non-finite entries, or (practically never) an eigenvalue
/// iteration that does not converge on a removed part.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::minimal_realization;
/// // (s + 1)/((s + 1)(s + 2)) in controllable canonical form: the pole −1 cancels.
/// let a = DMatrix::from_row_slice(2, 2, &[-3.0, -2.0, 1.0, 0.0]);
/// let b = DMatrix::from_row_slice(2, 1, &[1.0, 0.0]);
/// let c = DMatrix::from_row_slice(1, 2, &[1.0, 1.0]);
/// let d = DMatrix::zeros(1, 1);
/// let m = minimal_realization(&a, &b, &c, &d, None).unwrap();
/// assert_eq!(m.order(), 1);
/// assert!((m.a[(0, 0)] + 2.0).abs() < 1e-14);
/// assert!(m.uncontrollable.is_empty());
/// assert!((m.unobservable[0].re + 1.0).abs() < 1e-14);
/// ```
pub fn minimal_realization(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    tol: Option<f64>,
) -> Result<MinimalRealization> {
    super::checks::check_system(a, b, c, d)?;
    // Balanced once (TB01ID, as TB01PD does); every staircase below works on these
    // coordinates without balancing again, so the second stage sees the first one's rounding
    // at the same scale as its tolerance.
    let (mut a, mut b, mut c) = (a.clone(), b.clone(), c.clone());
    crate::numeric::balance::balance_system(&mut a, &mut b, &mut c);
    let (a, b, c) = (&a, &b, &c);
    let (first, obs_margin) = controllable_then_observable(a, b, c, d, tol)?;
    // Nothing removed and every rank decision of the second staircase far above its
    // tolerance: the staircase of the whole system cannot find fewer observable states (see
    // `CERTAIN_MARGIN`), and the first realisation stands.
    if first.order() == a.nrows() && obs_margin >= CERTAIN_MARGIN {
        return Ok(first);
    }
    // The observability staircase of the whole system (what a report states as its
    // observability rank) decides its ranks in other coordinates than the second staircase
    // above; with a defective eigenvalue behind an ill-conditioned similarity the two can
    // disagree (issue 24: observable rank 2 of 5, yet minimal order 5 and no unobservable
    // mode). The other order — observable part first, then its controllable part — is as
    // valid; the smaller realisation is kept, so the order never exceeds either rank.
    let obs = staircase(
        &a.transpose(),
        &c.transpose(),
        &b.transpose(),
        tol,
        false,
        false,
    )?;
    if first.order() <= obs.dim {
        return Ok(first);
    }
    let second = observable_then_controllable(a.nrows(), d, tol, obs)?;
    Ok(if second.order() < first.order() {
        second
    } else {
        first
    })
}

/// How far above its tolerance every rank decision of the observability staircase of the
/// controllable part must be for the whole system's observability staircase to be skipped
/// when nothing was removed. With one input and one output every step of a staircase is
/// one column (the Hessenberg reduction with b, resp. cᵀ, as its first vector), and by the
/// implicit Q theorem the staircases of (A, c) and of an orthogonal similarity (QᵀAQ, cQ)
/// compute the same subdiagonal magnitudes in exact arithmetic: the two computed ones
/// differ only through the backward errors, ~n·ε·‖A‖ each, amplified by the conditioning of
/// the Krylov basis. A decision 2²⁰ times the tolerance n²·ε·‖\[A; C\]‖ — itself n times
/// those backward errors — leaves room for an amplification of ~10⁸ before the other
/// staircase could call that step rank deficient; kron10's defective case (6.7e-14 against
/// 2.4e-14) is decided by the full rule.
const CERTAIN_MARGIN: f64 = (1u64 << 20) as f64;

/// The smallest rank decision of a staircase whose steps are all one column and which kept
/// every state, relative to its tolerance: min(|b₁|, |a₂₁|, |a₃₂|, …)/tol; 0 otherwise.
fn single_column_margin(st: &super::staircase::Staircase) -> f64 {
    let n = st.a.nrows();
    if st.dim != n || st.b.ncols() != 1 || st.blocks.iter().any(|&r| r != 1) || st.abs_tol <= 0.0 {
        return 0.0;
    }
    let smallest = (0..n.saturating_sub(1))
        .map(|k| st.a[(k + 1, k)].abs())
        .fold(st.b[(0, 0)].abs(), f64::min);
    smallest / st.abs_tol
}

/// `TB01PD`'s order: the controllable part, then its observable part; with the margin of
/// the second staircase's rank decisions ([`single_column_margin`]).
fn controllable_then_observable(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    tol: Option<f64>,
) -> Result<(MinimalRealization, f64)> {
    let ctrl = staircase(a, b, c, tol, false, false)?;
    let nc = ctrl.dim;
    let uncontrollable = schur_eigenvalues(&ctrl.removed_block())?;
    let ac = ctrl.a.view((0, 0), (nc, nc)).clone_owned();
    let bc = ctrl.b.rows(0, nc).clone_owned();
    let cc = ctrl.c.columns(0, nc).clone_owned();
    // Observable part of the controllable part: the controllable part of its dual.
    let obs = staircase(
        &ac.transpose(),
        &cc.transpose(),
        &bc.transpose(),
        tol,
        false,
        false,
    )?;
    let no = obs.dim;
    let unobservable = schur_eigenvalues(&obs.removed_block())?;
    let margin = single_column_margin(&obs);
    let minimal = MinimalRealization {
        a: obs.a.view((0, 0), (no, no)).transpose(),
        b: obs.c.columns(0, no).transpose(),
        c: obs.b.rows(0, no).transpose(),
        d: d.clone(),
        uncontrollable,
        unobservable,
        n_controllable: nc,
        abs_tol: (ctrl.abs_tol, obs.abs_tol),
    };
    Ok((minimal, margin))
}

/// The other order: the observable part (`obs`, the staircase of the dual of the whole
/// system), then its controllable part. A mode both unobservable and uncontrollable is then
/// listed as unobservable.
fn observable_then_controllable(
    n: usize,
    d: &DMatrix<f64>,
    tol: Option<f64>,
    obs: super::staircase::Staircase,
) -> Result<MinimalRealization> {
    let no = obs.dim;
    let unobservable = schur_eigenvalues(&obs.removed_block())?;
    let ao = obs.a.view((0, 0), (no, no)).transpose();
    let bo = obs.c.columns(0, no).transpose();
    let co = obs.b.rows(0, no).transpose();
    let ctrl = staircase(&ao, &bo, &co, tol, false, false)?;
    let nc = ctrl.dim;
    let uncontrollable = schur_eigenvalues(&ctrl.removed_block())?;
    Ok(MinimalRealization {
        a: ctrl.a.view((0, 0), (nc, nc)).clone_owned(),
        b: ctrl.b.rows(0, nc).clone_owned(),
        c: ctrl.c.columns(0, nc).clone_owned(),
        d: d.clone(),
        n_controllable: n - uncontrollable.len(),
        uncontrollable,
        unobservable,
        abs_tol: (ctrl.abs_tol, obs.abs_tol),
    })
}
