//! Continuous and discrete algebraic Riccati equations with a cross term: the stabilising
//! solution, the optimal gain and the closed-loop eigenvalues.
//!
//! | function | equation | gain K |
//! |---|---|---|
//! | [`care`] | AᵀX + XA − (XB + S)R⁻¹(BᵀX + Sᵀ) + Q = 0 | R⁻¹(BᵀX + Sᵀ) |
//! | [`dare`] | AᵀXA − X − (AᵀXB + S)(R + BᵀXB)⁻¹(BᵀXA + Sᵀ) + Q = 0 | (R + BᵀXB)⁻¹(BᵀXA + Sᵀ) |
//!
//! The stabilising solution makes A − B·K Hurwitz (care) or Schur stable (dare).
//!
//! # Method
//! The cross term is removed first: Ã = A − B·R⁻¹·Sᵀ, Q̃ = Q − S·R⁻¹·Sᵀ, G = B·R⁻¹·Bᵀ.
//! * **care**: the stable invariant subspace [U₁; U₂] of the Hamiltonian
//!   H = [Ã −G; −Q̃ −Ãᵀ] from its (unbalanced) complex Schur form, reordered by unitary swaps
//!   of adjacent diagonal entries (`ztrexc`) so that the n eigenvalues with Re λ < 0 lead;
//!   X = U₂·U₁⁻¹ (real part, symmetrised).
//! * **dare**: the structure-preserving doubling algorithm (SDA; Chu, Fan, Lin 2005) on
//!   (Ã, G, Q̃): A_{k+1} = A_k(I + G_kH_k)⁻¹A_k, G_{k+1} = G_k + A_k(I + G_kH_k)⁻¹G_kA_kᵀ,
//!   H_{k+1} = H_k + A_kᵀH_k(I + G_kH_k)⁻¹A_k, H_k → X quadratically. It needs no inverse of
//!   A (a singular A, e.g. a plant with a pure delay, is fine).
//!
//! Both are then refined by Newton steps in defect-correction form (Newton–Kleinman for care,
//! Hewer for dare): the correction Δ solves the closed-loop Lyapunov equation
//! A_clᵀΔ + ΔA_cl + 𝓡(X) = 0 (resp. A_clᵀΔA_cl − Δ + 𝓡(X) = 0) with
//! [`lyap`](super::lyap) / [`dlyap`](super::dlyap),
//! while the residual decreases (at most 6 steps).
//!
//! # Existence (checked, each with its own error)
//! R symmetric positive definite (its smallest eigenvalue named otherwise); Q symmetric;
//! (A, B) stabilisable (an uncontrollable mode with Re λ ≥ 0, resp. |λ| ≥ 1, is named);
//! no eigenvalue of H on the imaginary axis (|Re λ| ≤ 100·n·ε·‖H‖_F; typically an
//! unobservable mode of (Q, A) on the axis); the closed loop of the result stable. The
//! joint weight [Q S; Sᵀ R] ⪰ 0 is **not** checked: it guarantees that the stabilising
//! solution is positive semidefinite, but an indefinite weight can still have one.
//!
//! # What is reported
//! * `residual` = ‖𝓡(X)‖_F / (sum of the Frobenius norms of the terms of 𝓡);
//! * `condition` = sep⁻¹·(‖Q‖_F + 2‖A‖_F‖X‖_F + ‖G‖_F‖X‖_F²)/‖X‖_F (care; dare with ‖A‖_F² in
//!   place of 2‖A‖_F and ‖G‖_F‖A‖_F²‖X‖_F² for the quadratic term) — the first-order relative
//!   condition number of Byers (1985) / Sun (1998) with sep⁻¹ of the closed-loop Lyapunov
//!   operator replaced by the [lower bound](super::lyapunov) of the last Newton step: a
//!   lower-bound estimate.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::lyapunov::{check_coefficient, check_shape, symmetrise};
use super::norms::frobenius;
use super::schur::schur_eigenvalues;
use crate::error::{LtiError, Result, complex_number, number};

mod doubling;
mod hamiltonian;
mod refine;

use doubling::doubling;
use hamiltonian::hamiltonian_solution;
use refine::refine;

/// The stabilising solution of an algebraic Riccati equation (see the [module docs](self)).
#[derive(Clone, Debug)]
pub struct Riccati {
    /// The symmetric stabilising solution X.
    pub x: DMatrix<f64>,
    /// The gain K (m×n): R⁻¹(BᵀX + Sᵀ) for care, (R + BᵀXB)⁻¹(BᵀXA + Sᵀ) for dare.
    pub gain: DMatrix<f64>,
    /// The eigenvalues of A − B·K.
    pub closed_loop: Vec<Complex64>,
    /// Relative residual ‖𝓡(X)‖_F / Σ‖term‖_F.
    pub residual: f64,
    /// Lower-bound estimate of the relative condition number (module docs).
    pub condition: f64,
    /// Newton refinement steps taken.
    pub refinements: usize,
}

/// The checked, cross-term-free data: (A, B, Q, R, S, Ã, Q̃, G, R⁻¹).
struct Data {
    a: DMatrix<f64>,
    b: DMatrix<f64>,
    q: DMatrix<f64>,
    r: DMatrix<f64>,
    s: DMatrix<f64>,
    at: DMatrix<f64>,
    qt: DMatrix<f64>,
    g: DMatrix<f64>,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Continuous,
    Discrete,
}

impl Kind {
    fn equation(self) -> &'static str {
        match self {
            Kind::Continuous => "the continuous Riccati equation",
            Kind::Discrete => "the discrete Riccati equation",
        }
    }
}

fn symmetric_checked(m: &DMatrix<f64>, name: &str) -> Result<DMatrix<f64>> {
    let asym = frobenius((m - m.transpose()).iter());
    let scale = frobenius(m.iter());
    if asym > 100.0 * f64::EPSILON * scale {
        return Err(LtiError::invalid(format!(
            "{name} must be symmetric (‖{name} − {name}ᵀ‖_F = {} relative to ‖{name}‖_F = {})",
            number(asym),
            number(scale)
        )));
    }
    Ok((m + m.transpose()) * 0.5)
}

fn prepare(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    s: Option<&DMatrix<f64>>,
    kind: Kind,
) -> Result<Data> {
    let n = check_coefficient(a, "A")?;
    // a 2n × 2n Hamiltonian Schur form (or doubling) and Newton steps of order n
    crate::limits::DESIGN_STATES.check_usize("`a`", n)?;
    let m = super::checks::check_input_matrix(b, n)?;
    if m == 0 {
        return Err(LtiError::invalid("B must have at least one column (input)"));
    }
    check_shape(q, "Q", n, n)?;
    check_shape(r, "R", m, m)?;
    let s = match s {
        Some(s) => {
            check_shape(s, "S", n, m)?;
            s.clone()
        }
        None => DMatrix::zeros(n, m),
    };
    let q = symmetric_checked(q, "Q")?;
    let r = symmetric_checked(r, "R")?;
    let eig = r.clone().symmetric_eigenvalues();
    let (lo, hi) = eig.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
        (lo.min(x), hi.max(x.abs()))
    });
    if lo <= m as f64 * f64::EPSILON * hi || hi == 0.0 {
        return Err(LtiError::invalid(format!(
            "R must be positive definite, but its smallest eigenvalue is {} (largest {})",
            number(lo),
            number(hi)
        )));
    }
    check_stabilisable(a, b, kind)?;
    let chol = r
        .clone()
        .cholesky()
        .ok_or_else(|| LtiError::invalid("R must be positive definite (Cholesky failed)"))?;
    let rinv_bt = chol.solve(&b.transpose());
    let rinv_st = chol.solve(&s.transpose());
    let at = a - b * &rinv_st;
    let mut qt = &q - &s * &rinv_st;
    let mut g = b * rinv_bt;
    symmetrise(&mut qt);
    symmetrise(&mut g);
    Ok(Data {
        a: a.clone(),
        b: b.clone(),
        q,
        r,
        s,
        at,
        qt,
        g,
    })
}

/// Errors at an uncontrollable mode of (A, B) outside the stability region.
fn check_stabilisable(a: &DMatrix<f64>, b: &DMatrix<f64>, kind: Kind) -> Result<()> {
    let c = DMatrix::zeros(0, a.nrows());
    let st = super::staircase::controllability_staircase(a, b, &c, None, false)?;
    if st.dim == a.nrows() {
        return Ok(());
    }
    for z in schur_eigenvalues(&st.removed_block())? {
        let bad = match kind {
            Kind::Continuous => z.re >= 0.0,
            Kind::Discrete => z.norm() >= 1.0,
        };
        if bad {
            return Err(LtiError::SingularEquation {
                equation: kind.equation().into(),
                reason: format!(
                    "no stabilising solution: (A, B) is not stabilisable, the uncontrollable mode λ = {} is {}",
                    complex_number(z.re, z.im),
                    match kind {
                        Kind::Continuous => "not in the open left half-plane",
                        Kind::Discrete => "not inside the unit circle",
                    }
                ),
            });
        }
    }
    Ok(())
}

/// Solves the continuous algebraic Riccati equation
/// AᵀX + XA − (XB + S)R⁻¹(BᵀX + Sᵀ) + Q = 0 for its stabilising solution (`s`: the cross
/// term, n×m; `None` for 0).
///
/// Errors: sizes, non-finite entries, R not symmetric positive definite, Q not symmetric,
/// (A, B) not stabilisable, a Hamiltonian eigenvalue on the imaginary axis (each naming the
/// numbers).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::care;
/// // LQR of the double integrator, Q = I, R = 1: K = [1, √3], X = [[√3, 1], [1, √3]].
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
/// let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
/// let sol = care(&a, &b, &DMatrix::identity(2, 2), &DMatrix::identity(1, 1), None).unwrap();
/// assert!((sol.gain[(0, 0)] - 1.0).abs() < 1e-14);
/// assert!((sol.gain[(0, 1)] - 3f64.sqrt()).abs() < 1e-14);
/// assert!(sol.closed_loop.iter().all(|z| z.re < 0.0));
/// ```
pub fn care(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    s: Option<&DMatrix<f64>>,
) -> Result<Riccati> {
    let d = prepare(a, b, q, r, s, Kind::Continuous)?;
    let x0 = hamiltonian_solution(&d)?;
    refine(&d, x0, Kind::Continuous)
}

/// Solves the discrete algebraic Riccati equation
/// AᵀXA − X − (AᵀXB + S)(R + BᵀXB)⁻¹(BᵀXA + Sᵀ) + Q = 0 for its stabilising solution.
///
/// Errors: as [`care`]; (A, B) must be stabilisable in the discrete sense, and no eigenvalue
/// of the symplectic pencil on the unit circle (the doubling then fails to converge, or the
/// closed loop is not stable: both reported).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::dare;
/// // Scalar a = 1, b = 1, q = 1, r = 1: x² − x − 1 = 0 ⇒ x = (1 + √5)/2, k = x/(1 + x).
/// let one = DMatrix::from_element(1, 1, 1.0);
/// let sol = dare(&one, &one, &one, &one, None).unwrap();
/// let x = (1.0 + 5f64.sqrt()) / 2.0;
/// assert!((sol.x[(0, 0)] - x).abs() < 1e-15);
/// assert!((sol.gain[(0, 0)] - x / (1.0 + x)).abs() < 1e-15);
/// ```
pub fn dare(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    s: Option<&DMatrix<f64>>,
) -> Result<Riccati> {
    let d = prepare(a, b, q, r, s, Kind::Discrete)?;
    let x0 = doubling(&d)?;
    refine(&d, x0, Kind::Discrete)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::linalg::lyapunov::tests::random;

    #[test]
    fn double_integrator_lqr() {
        let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
        let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
        let sol = care(
            &a,
            &b,
            &DMatrix::identity(2, 2),
            &DMatrix::identity(1, 1),
            None,
        )
        .unwrap();
        let r3 = 3f64.sqrt();
        // Closed form: X = [[√3, 1], [1, √3]], K = BᵀX = [1, √3].
        assert!((sol.gain[(0, 0)] - 1.0).abs() <= 1e-14, "{}", sol.gain);
        assert!((sol.gain[(0, 1)] - r3).abs() <= 1e-14, "{}", sol.gain);
        let want = DMatrix::from_row_slice(2, 2, &[r3, 1.0, 1.0, r3]);
        assert!((&sol.x - want).norm() <= 1e-14);
        assert!(sol.residual < 1e-15);
    }

    #[test]
    fn scalar_closed_forms() {
        // care: 2ax − b²x²/r + q = 0 ⇒ x = r(a + √(a² + b²q/r))/b².
        for (a, b, q, r) in [
            (1.0, 1.0, 1.0, 1.0),
            (-2.0, 0.5, 3.0, 2.0),
            (0.0, 2.0, 1.0, 0.1),
        ] {
            let m = |v: f64| DMatrix::from_element(1, 1, v);
            let sol = care(&m(a), &m(b), &m(q), &m(r), None).unwrap();
            let x = r * (a + (a * a + b * b * q / r).sqrt()) / (b * b);
            assert!((sol.x[(0, 0)] - x).abs() < 1e-14 * x, "{} vs {x}", sol.x);
        }
        // dare: a²x − x − a²b²x²/(r + b²x) + q = 0; with a = 0.5, b = 1, q = 1, r = 1:
        // x² + 0.75x − 1 … ⇒ b²x² + (r(1 − a²) − qb²)x − qr = 0: x² − 0.25x − 1 = 0.
        let m = |v: f64| DMatrix::from_element(1, 1, v);
        let sol = dare(&m(0.5), &m(1.0), &m(1.0), &m(1.0), None).unwrap();
        let x = (0.25 + (0.0625f64 + 4.0).sqrt()) / 2.0;
        assert!((sol.x[(0, 0)] - x).abs() < 1e-15, "{}", sol.x);
    }

    #[test]
    fn cross_term_equals_the_transformed_problem() {
        let n = 4;
        let a = random(n, n, 1);
        let b = random(n, 2, 2);
        let q0 = random(n, n, 3);
        let q = &q0 * q0.transpose() + DMatrix::identity(n, n);
        let r = DMatrix::from_row_slice(2, 2, &[2.0, 0.3, 0.3, 1.0]);
        let s = random(n, 2, 4) * 0.2;
        let rinv = r.clone().try_inverse().unwrap();
        let at = &a - &b * &rinv * s.transpose();
        let qt = &q - &s * &rinv * s.transpose();
        for kind in [Kind::Continuous, Kind::Discrete] {
            let solve = |a: &DMatrix<f64>, q: &DMatrix<f64>, s: Option<&DMatrix<f64>>| match kind {
                Kind::Continuous => care(a, &b, q, &r, s).unwrap(),
                Kind::Discrete => dare(a, &b, q, &r, s).unwrap(),
            };
            let with = solve(&a, &q, Some(&s));
            let without = solve(&at, &qt, None);
            assert!((&with.x - &without.x).norm() < 1e-12 * with.x.norm());
            assert!(with.residual < 1e-14, "{}", with.residual);
        }
    }

    #[test]
    fn dare_with_singular_a() {
        // A shift register (nilpotent): z⁻¹ delays; A singular.
        let a = DMatrix::from_row_slice(3, 3, &[0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
        let b = DMatrix::from_row_slice(3, 1, &[0.0, 0.0, 1.0]);
        let q = DMatrix::identity(3, 3);
        let sol = dare(&a, &b, &q, &DMatrix::identity(1, 1), None).unwrap();
        assert!(sol.residual < 1e-15, "{}", sol.residual);
        assert!(sol.closed_loop.iter().all(|z| z.norm() < 1.0));
    }

    #[test]
    fn random_100_states() {
        // A random stable A (spectral radius of the random part ≈ 0.6, shifted by −1): with
        // 3 inputs and an unstable A the stabilising X of a random 100-state problem has
        // ‖X‖ ≈ 1e16 (nearly not stabilisable), an ill-posed test.
        let n = 100;
        let a = random(n, n, 11) * (2.0 / (n as f64).sqrt()) - DMatrix::identity(n, n);
        let b = random(n, 3, 12);
        let q = DMatrix::identity(n, n);
        let r = DMatrix::identity(3, 3);
        let sol = care(&a, &b, &q, &r, None).unwrap();
        assert!(sol.residual <= 1e-12, "care {}", sol.residual);
        let ad = random(n, n, 11) * (1.0 / (n as f64).sqrt());
        let sol = dare(&ad, &b, &q, &r, None).unwrap();
        assert!(sol.residual <= 1e-12, "dare {}", sol.residual);
    }

    #[test]
    fn existence_errors() {
        let a = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 2.0]);
        let b = DMatrix::from_row_slice(2, 1, &[1.0, 0.0]);
        let i2 = DMatrix::identity(2, 2);
        let one = DMatrix::identity(1, 1);
        let e = care(&a, &b, &i2, &one, None).unwrap_err().to_string();
        assert!(e.contains("not stabilisable") && e.contains("λ = 2"), "{e}");
        let e = care(&i2, &DMatrix::identity(2, 1), &i2, &(-&one), None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("smallest eigenvalue is -1"), "{e}");
        // An undamped oscillator that Q does not see: Hamiltonian eigenvalues ±j.
        let osc = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, 0.0]);
        let b2 = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
        let e = care(&osc, &b2, &DMatrix::zeros(2, 2), &one, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("imaginary axis"), "{e}");
        let e = dare(&(&osc * 1.0), &b2, &DMatrix::zeros(2, 2), &one, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("no stabilising solution"), "{e}");
        let nq = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 0.0, 1.0]);
        assert!(care(&osc, &b2, &nq, &one, None).is_err());
    }
}
