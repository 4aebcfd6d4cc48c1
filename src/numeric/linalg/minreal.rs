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
//!
//! Last, when a direction the staircases kept was within `CERTAIN_MARGIN` of the tolerance
//! (`Staircase::margin`) or the two orders disagreed, the Popov–Belevitch–Hautus test runs on
//! what the staircases kept: a simple eigenvalue whose
//! computed right eigenvector v has ‖C·v‖ (left eigenvector w: ‖wᵀ·B‖) and ‖A·v − λ·v‖ within
//! the staircase's absolute tolerance is a mode the model is that close to having exactly
//! unobservable (uncontrollable), and it is removed by an orthogonal similarity onto its
//! invariant subspace, the dropped blocks checked against the tolerance. Rank decisions made
//! block by block can amplify rounding where an eigenvector does not: harold's second model
//! (eigenvalue 1 unobservable for every value of its entries) kept 5 states behind a last
//! block of 1.0e-13 against 2.4e-14, as `TB01PD` does; its eigenvector gives ‖C·v‖ = 1.1e-16
//! and order 4.

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
    let (first, obs_margin, margin) = controllable_then_observable(a, b, c, d, tol)?;
    // Nothing removed and every rank decision of the second staircase far above its
    // tolerance: the staircase of the whole system cannot find fewer observable states (see
    // `CERTAIN_MARGIN`), and the first realisation stands.
    if first.order() == a.nrows() && obs_margin >= CERTAIN_MARGIN {
        return Ok(first);
    }
    let first_order = first.order();
    let chosen = smaller_of_both_orders(a, b, c, d, tol, first)?;
    // The eigenvector test only where a rank decision was close: a kept direction within
    // CERTAIN_MARGIN of the tolerance in either staircase, or the two orders disagreeing.
    Ok(
        if margin < CERTAIN_MARGIN || chosen.order() != first_order {
            eigenvector_test(chosen)
        } else {
            chosen
        },
    )
}

/// The first realisation, or the other order's when the whole system's observability
/// staircase finds fewer observable states and that order gives a smaller realisation.
fn smaller_of_both_orders(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    tol: Option<f64>,
    first: MinimalRealization,
) -> Result<MinimalRealization> {
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
/// the second staircase's rank decisions ([`single_column_margin`]) and the smallest margin
/// of a kept direction in either staircase (`Staircase::margin`).
fn controllable_then_observable(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    tol: Option<f64>,
) -> Result<(MinimalRealization, f64, f64)> {
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
    Ok((minimal, margin, ctrl.margin.min(obs.margin)))
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

/// Which kind of mode the eigenvector test looks for.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    /// C·v = 0 for a right eigenvector v.
    Unobservable,
    /// wᵀ·B = 0 for a left eigenvector w.
    Uncontrollable,
}

/// The Popov–Belevitch–Hautus test on what the staircases kept: a simple eigenvalue λ of the
/// realisation with a computed eigenvector v (unit, A·v ≈ λ·v) whose output C·v (for a left
/// eigenvector w, the input coupling wᵀ·B) is within the staircase's absolute tolerance is a
/// mode the model is that close to having exactly unobservable (uncontrollable): A + E, C + F
/// with ‖E‖ ≤ ‖A·v − λ·v‖ and ‖F‖ ≤ ‖C·v‖ have it exactly. It is removed by the orthogonal
/// similarity whose first columns span its real invariant subspace, one mode at a time; the
/// blocks dropped are checked against the tolerance. The staircases decide ranks block by
/// block in coordinates that can amplify rounding (harold's second model: the unobservable
/// mode 1 behind a subdiagonal of 3.2e-3 left a last block of 1.0e-13 against 2.4e-14, while
/// its eigenvector gives ‖C·v‖ = 1.1e-16). Defective eigenvalues are left to the staircases.
fn eigenvector_test(mut m: MinimalRealization) -> MinimalRealization {
    for kind in [Kind::Unobservable, Kind::Uncontrollable] {
        let tol = match kind {
            Kind::Unobservable => m.abs_tol.1,
            Kind::Uncontrollable => m.abs_tol.0,
        };
        if tol <= 0.0 {
            continue;
        }
        // at most one removal per state: every pass either removes a mode or stops
        for _ in 0..m.order() {
            // an eigenvector computation that fails (no convergence) leaves the staircases'
            // result as it is: the test can only remove modes, never be needed
            let Ok(Some((values, kept))) = remove_one_mode(&m, kind, tol) else {
                break;
            };
            m.a = kept.0;
            m.b = kept.1;
            m.c = kept.2;
            match kind {
                Kind::Unobservable => m.unobservable.extend(values),
                Kind::Uncontrollable => {
                    m.n_controllable -= values.len();
                    m.uncontrollable.extend(values);
                }
            }
        }
    }
    m
}

/// The realisation without one mode that fails the eigenvector test (see
/// [`eigenvector_test`]): its eigenvalues (one, or a conjugate pair) and the (A, B, C) left;
/// `None` when every simple eigenvalue passes.
#[allow(clippy::type_complexity)]
fn remove_one_mode(
    m: &MinimalRealization,
    kind: Kind,
    tol: f64,
) -> Result<Option<(Vec<Complex64>, (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>))>> {
    let r = m.order();
    if r == 0 {
        return Ok(None);
    }
    // the dual for the input side: left eigenvectors of A are right ones of Aᵀ
    let (a, c, b) = match kind {
        Kind::Unobservable => (m.a.clone(), m.c.clone(), m.b.clone()),
        Kind::Uncontrollable => (m.a.transpose(), m.b.transpose(), m.c.transpose()),
    };
    let (sets, _) = super::eigvec::general_eigenvectors(&a)?;
    let norm_a = super::norms::norm_1_inf(&a);
    for set in &sets {
        if set.algebraic != 1 || set.value.im < 0.0 || set.vectors.ncols() != 1 {
            continue;
        }
        let v = set.vectors.column(0);
        let residual = set.residuals.first().copied().unwrap_or(f64::INFINITY) * norm_a;
        let vr = v.map(|z| z.re);
        let vi = v.map(|z| z.im);
        let cv = ((&c * &vr).norm_squared() + (&c * &vi).norm_squared()).sqrt();
        if !(residual <= tol && cv <= tol) {
            continue;
        }
        // What removing the mode changes in G: its residue (C·v)(uᵀ·B)/(uᵀ·v), u the
        // eigenvector of Aᵀ (the left one). A small ‖C·v‖ on an ill-conditioned eigenvalue
        // (a split Jordan chain) can still carry a large residue: such a mode stays.
        let Some(residue) = mode_residue(&a, &c, &b, set.value, &v.clone_owned())? else {
            continue;
        };
        if residue.is_nan() || residue > tol * b.norm() {
            continue;
        }
        // a real orthonormal basis of the mode's invariant subspace: v, or (Re v, Im v)
        let basis = if set.value.im == 0.0 {
            DMatrix::from_columns(&[vr])
        } else {
            DMatrix::from_columns(&[vr, vi])
        };
        let k = basis.ncols();
        let Some(q) = orthogonal_completion(basis) else {
            continue;
        };
        let at = q.transpose() * &a * &q;
        let ct = &c * &q;
        let bt = q.transpose() * &b;
        // what is dropped: the coupling of the kept states into the mode, and its output
        let dropped_a = at.view((k, 0), (r - k, k)).norm();
        let dropped_c = ct.columns(0, k).norm();
        if !(dropped_a <= tol && dropped_c <= tol) {
            continue;
        }
        let ak = at.view((k, k), (r - k, r - k)).clone_owned();
        let bk = bt.rows(k, r - k).clone_owned();
        let ck = ct.columns(k, r - k).clone_owned();
        let kept = match kind {
            Kind::Unobservable => (ak, bk, ck),
            Kind::Uncontrollable => (ak.transpose(), ck.transpose(), bk.transpose()),
        };
        let values = if k == 1 {
            vec![set.value]
        } else {
            vec![set.value, set.value.conj()]
        };
        return Ok(Some((values, kept)));
    }
    Ok(None)
}

/// ‖(C·v)(uᵀ·B)‖/|uᵀ·v| for the eigenvalue λ of A with right eigenvector v: the size of the
/// mode's term in the transfer matrix, with u the eigenvector of Aᵀ for λ (the computed one
/// nearest λ); `None` when none is near or uᵀ·v vanishes.
fn mode_residue(
    a: &DMatrix<f64>,
    c: &DMatrix<f64>,
    b: &DMatrix<f64>,
    lambda: Complex64,
    v: &nalgebra::DVector<Complex64>,
) -> Result<Option<f64>> {
    let (sets, st) = super::eigvec::general_eigenvectors(&a.transpose())?;
    let Some(set) = sets
        .iter()
        .filter(|s| s.algebraic == 1 && s.vectors.ncols() == 1)
        .min_by(|x, y| {
            (x.value - lambda)
                .norm()
                .total_cmp(&(y.value - lambda).norm())
        })
    else {
        return Ok(None);
    };
    if (set.value - lambda).norm() > super::structure::radius(1, a.nrows(), st.scale) {
        return Ok(None);
    }
    let u = set.vectors.column(0);
    let utv: Complex64 = u.iter().zip(v.iter()).map(|(x, y)| x * y).sum();
    let cx = c.map(|x| Complex64::new(x, 0.0));
    let bx = b.map(|x| Complex64::new(x, 0.0));
    let cv = &cx * v;
    let ub = u.transpose() * &bx;
    let size = cv.norm() * ub.norm();
    Ok((utv.norm() > 0.0).then(|| size / utv.norm()))
}

/// An orthogonal r×r matrix whose first k columns span the columns of `basis` (r×k), by
/// Householder QR; `None` when they are numerically dependent (a pivot below √ε of its
/// column).
fn orthogonal_completion(mut basis: DMatrix<f64>) -> Option<DMatrix<f64>> {
    let (r, k) = basis.shape();
    let mut reflectors = Vec::with_capacity(k);
    for j in 0..k {
        let size = basis.column(j).norm();
        let x: Vec<f64> = basis.view((j, j), (r - j, 1)).iter().copied().collect();
        let (h, beta) = super::householder::Reflector::new(j, &x);
        if !beta.is_finite() || beta.abs() <= f64::EPSILON.sqrt() * size {
            return None;
        }
        h.apply_left(&mut basis, j..k);
        reflectors.push(h);
    }
    Some(super::householder::form_product(r, &reflectors))
}
