//! Real Schur form A = D·Q·T·Qᵀ·D⁻¹ (D = I unless balanced), its eigenvalues and its backward
//! error.
//!
//! # Method
//! 1. optional **balancing** (the overflow-safe, capped Parlett–Reinsch of
//!    [`mod@crate::numeric::balance`]): D is a diagonal of powers of two, so D⁻¹AD is exact;
//! 2. **power-of-two scaling** into the range where no intermediate overflows
//!    ([`crate::numeric::eig::SAFE_EXP`]), exact and undone on T;
//! 3. [Hessenberg reduction](mod@super::hessenberg) and the
//!    [Francis double-shift QR](super::francis) with exceptional shifts and an iteration cap;
//! 4. on exhaustion of the cap, **one retry** on H·M·H for a fixed Householder reflector H
//!    (an orthogonal similarity that breaks cyclic structure; DESIGN §5), with Q ← H·Q.
//!
//! Accuracy (measured, `tests/ss_kernels.rs`): ‖QTQᵀ − A‖_F/‖A‖_F ≈ 1e-15 at n = 256 and
//! ≈ 3e-15 at n = 1000 for random matrices (unbalanced, so that Q is the whole
//! transformation); nalgebra's `Schur` gives 2e-13 and 7.6e-13 there.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::francis::{hqr, lanv2};
use super::householder::fixed_reflector;
use crate::error::{LtiError, Result};
use crate::numeric::balance::{balance, exponent_range, ldexp};
use crate::numeric::eig::safe_scale_exponent;

/// What [`real_schur`] computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SchurOptions {
    /// Balance first (A = D·Q·T·Qᵀ·D⁻¹). Better eigenvalues for badly scaled matrices; the
    /// transformation is then no longer orthogonal.
    pub balance: bool,
    /// Accumulate Q (~2.5× the work of eigenvalues alone).
    pub want_q: bool,
    /// Keep the whole quasi-triangular T (needed for Q, eigenvectors and multiplicities);
    /// without it only T's diagonal blocks are valid (eigenvalues only, ~2× faster).
    pub want_t: bool,
}

impl Default for SchurOptions {
    /// Balanced, with T and Q.
    fn default() -> Self {
        SchurOptions {
            balance: true,
            want_q: true,
            want_t: true,
        }
    }
}

/// A real Schur form A = D·Q·T·Qᵀ·D⁻¹.
#[derive(Clone, Debug)]
pub struct RealSchur {
    /// Quasi-upper-triangular T: 1×1 blocks (real eigenvalues) and standardised 2×2 blocks
    /// [a b; c a] with b·c < 0 (a conjugate pair a ± i√(−bc)). Only its diagonal blocks are
    /// meaningful when computed without `want_t`.
    pub t: DMatrix<f64>,
    /// Orthogonal Q (`None` unless requested).
    pub q: Option<DMatrix<f64>>,
    /// Diagonal of the balancing D (powers of two; all ones without balancing).
    pub d: Vec<f64>,
    /// Francis sweeps spent.
    pub sweeps: usize,
    /// Whether the retry after a Householder similarity was needed.
    pub retried: bool,
}

/// Real Schur form of a square, finite matrix (see the [module docs](self)).
///
/// Errors: not square, a NaN/∞ entry, an iteration cap exhausted twice
/// ([`LtiError::NoConvergence`]), or T beyond the range of f64.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::{SchurOptions, real_schur};
/// // Companion matrix of s⁴ + 1 (nalgebra's uncapped iteration hangs on it).
/// let mut a = DMatrix::<f64>::zeros(4, 4);
/// a[(0, 3)] = -1.0;
/// for i in 1..4 { a[(i, i - 1)] = 1.0; }
/// let opts = SchurOptions { balance: false, ..SchurOptions::default() };
/// let s = real_schur(&a, opts).unwrap();
/// assert!(s.backward_error(&a) < 1e-15);
/// for z in s.eigenvalues() { assert!((z.norm() - 1.0).abs() < 1e-14); }
/// ```
pub fn real_schur(a: &DMatrix<f64>, opts: SchurOptions) -> Result<RealSchur> {
    let n = super::checks::check_square(a, "the matrix")?;
    let want_t = opts.want_t || opts.want_q;
    let mut m = a.clone();
    let d = if opts.balance && n >= 2 {
        balance(&mut m)
    } else {
        vec![1.0; n]
    };
    let e = exponent_range(m.iter().copied()).map_or(0, |(lo, hi)| safe_scale_exponent(lo, hi));
    if e != 0 {
        m.apply(|x| *x = ldexp(*x, -e));
    }
    let (mut t, q, sweeps, retried) = match schur_core(m.clone(), want_t, opts.want_q) {
        Ok((t, q, s)) => (t, q, s, false),
        Err(first) => {
            let h = fixed_reflector(n);
            h.apply_left(&mut m, 0..n);
            h.apply_right(&mut m, 0..n);
            let (t, q, s) =
                schur_core(m, want_t, opts.want_q).map_err(|second| LtiError::NoConvergence {
                    what: format!("the Francis QR iteration on a {n}×{n} matrix (retried)"),
                    iterations: first + second,
                })?;
            let q = q.map(|mut q| {
                h.apply_left(&mut q, 0..n);
                q
            });
            (t, q, first + s, true)
        }
    };
    if e != 0 {
        t.apply(|x| *x = ldexp(*x, e));
        if let Some(x) = t.iter().find(|x| !x.is_finite()) {
            return Err(LtiError::NonFinite {
                what: "an entry of the Schur form (beyond the range of f64)".into(),
                value: *x,
            });
        }
    }
    Ok(RealSchur {
        t,
        q,
        d,
        sweeps,
        retried,
    })
}

/// T, the optional Q and the number of sweeps.
type SchurCore = (DMatrix<f64>, Option<DMatrix<f64>>, usize);

/// Hessenberg reduction plus Francis iteration; Err(sweeps) when the cap is hit.
fn schur_core(
    mut m: DMatrix<f64>,
    want_t: bool,
    want_q: bool,
) -> std::result::Result<SchurCore, usize> {
    let n = m.nrows();
    let reflectors = super::hessenberg::reduce_in_place(&mut m);
    let mut q = want_q.then(|| super::householder::form_product(n, &reflectors));
    let sweeps = hqr(
        m.as_mut_slice(),
        n,
        want_t,
        q.as_mut().map(|q| q.as_mut_slice()),
    )?;
    Ok((m, q, sweeps))
}

/// Eigenvalues of a square, finite matrix from its balanced real Schur form (T only, no Q):
/// conjugate pairs exact, in the order of T's diagonal.
///
/// ```
/// use nalgebra::DMatrix;
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, -0.8]);
/// let ev = ltikit::numeric::linalg::schur_eigenvalues(&a).unwrap();
/// // s² + 0.8s + 4: −0.4 ± j·√(4 − 0.16) = −0.4 ± j·√3.84.
/// assert!((ev[0].re + 0.4).abs() < 1e-15 && (ev[0].im.abs() - 3.84f64.sqrt()).abs() < 1e-15);
/// assert_eq!(ev[0], ev[1].conj());
/// ```
pub fn schur_eigenvalues(a: &DMatrix<f64>) -> Result<Vec<Complex64>> {
    let s = real_schur(
        a,
        SchurOptions {
            balance: true,
            want_q: false,
            want_t: false,
        },
    )?;
    Ok(s.eigenvalues())
}

impl RealSchur {
    /// Order of the matrix.
    pub fn order(&self) -> usize {
        self.t.nrows()
    }

    /// Eigenvalues in the order of T's diagonal; a conjugate pair is listed (a + ib, a − ib)
    /// with b > 0, exactly conjugate.
    pub fn eigenvalues(&self) -> Vec<Complex64> {
        quasi_triangular_eigenvalues(&self.t)
    }

    /// The blocks of T as (start, size) with size 1 or 2.
    pub fn blocks(&self) -> Vec<(usize, usize)> {
        blocks_of(&self.t)
    }

    /// Backward error ‖D·Q·T·Qᵀ·D⁻¹ − A‖_F / ‖A‖_F against the original A (0 for A = 0);
    /// ∞ when Q was not computed.
    pub fn backward_error(&self, a: &DMatrix<f64>) -> f64 {
        let Some(q) = &self.q else {
            return f64::INFINITY;
        };
        if a.shape() != self.t.shape() {
            return f64::INFINITY;
        }
        let mut r = q * &self.t * q.transpose();
        for j in 0..r.ncols() {
            for i in 0..r.nrows() {
                r[(i, j)] = r[(i, j)] * self.d[i] / self.d[j] - a[(i, j)];
            }
        }
        let na = super::norms::frobenius(a.iter());
        if na == 0.0 {
            return super::norms::frobenius(r.iter());
        }
        super::norms::frobenius(r.iter()) / na
    }
}

/// The diagonal blocks (start, size) of a quasi-triangular matrix: a non-zero subdiagonal
/// entry opens a 2×2 block.
pub(crate) fn blocks_of(t: &DMatrix<f64>) -> Vec<(usize, usize)> {
    let n = t.nrows();
    let mut out = Vec::with_capacity(n);
    let mut k = 0;
    while k < n {
        if k + 1 < n && t[(k + 1, k)] != 0.0 {
            out.push((k, 2));
            k += 2;
        } else {
            out.push((k, 1));
            k += 1;
        }
    }
    out
}

/// Eigenvalues of a quasi-triangular matrix, each 2×2 block through [`lanv2`] (robust when
/// the block has two nearly equal real eigenvalues, where the discriminant formula gives
/// NaN or cancels).
pub(crate) fn quasi_triangular_eigenvalues(t: &DMatrix<f64>) -> Vec<Complex64> {
    let mut out = Vec::with_capacity(t.nrows());
    for (k, size) in blocks_of(t) {
        if size == 1 {
            out.push(Complex64::new(t[(k, k)], 0.0));
            continue;
        }
        let blk = lanv2(t[(k, k)], t[(k, k + 1)], t[(k + 1, k)], t[(k + 1, k + 1)]);
        let (r1, i1, r2, i2) = blk.eigenvalues();
        if i1 == 0.0 {
            out.push(Complex64::new(r1, 0.0));
            out.push(Complex64::new(r2, 0.0));
        } else {
            let z = Complex64::new(r1, i1.abs());
            out.push(z);
            out.push(z.conj());
        }
        let _ = i2;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `quasi_triangular_eigenvalues` on a worked example (an internal kernel: a unit test, not a doctest).
    #[test]
    #[allow(clippy::float_cmp)] // exact values are meant
    fn quasi_triangular_eigenvalues_example() {
        use crate::numeric::linalg::schur::quasi_triangular_eigenvalues;
        use nalgebra::DMatrix;
        // A 2×2 block with real eigenvalues 1 ± 1e-10 (not standardised).
        let t = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1e-20, 1.0]);
        let ev = quasi_triangular_eigenvalues(&t);
        assert!(ev.iter().all(|z| z.im == 0.0));
        // Near 1 an f64 resolves ε = 2.2e-16: the split is 2e-10 to about that.
        assert!(((ev[0].re - ev[1].re).abs() - 2e-10).abs() <= 2.0 * f64::EPSILON);
    }

    #[test]
    fn cyclic_companions_terminate() {
        // sⁿ ± c up to n = 40 (DESIGN §5): no hang, eigenvalues on the circle |z| = |c|^(1/n).
        for n in 2..=40 {
            for &c in &[1.0, -1.0, 2.5] {
                let mut a = DMatrix::<f64>::zeros(n, n);
                a[(0, n - 1)] = -c;
                for i in 1..n {
                    a[(i, i - 1)] = 1.0;
                }
                let s = real_schur(&a, SchurOptions::default()).unwrap();
                let r = f64::abs(c).powf(1.0 / n as f64);
                for z in s.eigenvalues() {
                    assert!((z.norm() - r).abs() < 1e-12 * r, "n={n} c={c}: {z}");
                }
                assert!(
                    s.backward_error(&a) < 1e-14,
                    "n={n}: {}",
                    s.backward_error(&a)
                );
            }
        }
    }

    #[test]
    fn trivial_orders_and_bad_input() {
        let s = real_schur(&DMatrix::zeros(0, 0), SchurOptions::default()).unwrap();
        assert!(s.eigenvalues().is_empty());
        let a = DMatrix::from_element(1, 1, -3.0);
        let s = real_schur(&a, SchurOptions::default()).unwrap();
        assert_eq!(s.eigenvalues(), vec![Complex64::new(-3.0, 0.0)]);
        assert!(real_schur(&DMatrix::zeros(2, 3), SchurOptions::default()).is_err());
        let nan = DMatrix::from_row_slice(2, 2, &[0.0, f64::NAN, 1.0, 0.0]);
        assert!(schur_eigenvalues(&nan).is_err());
    }

    #[test]
    fn extreme_scales() {
        // Entries near the ends of the f64 range: scaled by a power of two, then back.
        for &s in &[1e-300, 1e300] {
            let a = DMatrix::from_row_slice(2, 2, &[0.0, s, -s, 0.0]);
            let ev = schur_eigenvalues(&a).unwrap();
            assert!((ev[0].im.abs() - s).abs() <= 1e-15 * s, "{ev:?}");
        }
    }
}
