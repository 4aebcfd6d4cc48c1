//! The Cholesky factor of a Lyapunov solution with a semidefinite right-hand side, by
//! Hammarling's method (IMA J. Numer. Anal. 2, 1982), without forming X.
//!
//! # Method
//! With Ã = Aᵀ = Q·S·Qᴴ (the complex Schur form from the unbalanced real one) and B̃ = Bᵀ,
//! the equation A·X + X·Aᵀ + B·Bᵀ = 0 reads Sᴴ·X̂ + X̂·S = −(B̃Q)ᴴ(B̃Q) for X̂ = Qᴴ·X·Q.
//! B̃Q is triangularised to R (Givens rotations, one row at a time), and X̂ = Uᴴ·U with U upper
//! triangular is found one row of U at a time: u₁₁ = |r₁₁|/√(−2·Re s₁₁), the rest of the row
//! from a triangular system, and the trailing problem has the same form with R₂₂ updated by one
//! row (y = r₁₂ − α·u₁₂, α = r₁₁/u₁₁), re-triangularised by Givens rotations. The discrete
//! equation A·X·Aᵀ − X + B·Bᵀ = 0 is the same with u₁₁ = |r₁₁|/√(1 − |s₁₁|²),
//! (s₁₁·S₂₂ᴴ − I)·u₁₂ᴴ = −α·r₁₂ᴴ − s₁₁·u₁₁·s₁₂ᴴ and y = s₁₁·r₁₂ − α·(u₁₁·s₁₂ + u₁₂·S₂₂).
//! X = (Q·Uᴴ)(Q·Uᴴ)ᴴ; the real lower-triangular L is the transposed R factor of the QR
//! decomposition of [Re(Q·Uᴴ), Im(Q·Uᴴ)]ᵀ (orthogonal, so L·Lᵀ = X exactly in exact
//! arithmetic). All steps are unitary or triangular solves: small Gramian directions keep
//! their relative accuracy, which forming X and taking its Cholesky factor would lose.

use nalgebra::DMatrix;
use num_complex::Complex64 as C;

use super::complex_schur::complex_schur;
use super::lyapunov::{check_coefficient, relative_residual};
use super::modal::schur_path::lartg;
use super::schur::{SchurOptions, real_schur};
use crate::error::{LtiError, Result, complex_number};

/// A Cholesky factor X = L·Lᵀ of a Lyapunov solution, with the relative residual of X.
#[derive(Clone, Debug)]
pub struct CholeskySolution {
    /// L, n×n **lower triangular** with a non-negative diagonal (singular when X is).
    pub l: DMatrix<f64>,
    /// Relative residual of X = L·Lᵀ in the equation, ‖res‖_F / Σ‖term‖_F.
    pub residual: f64,
}

/// The Cholesky factor of the solution of A·X + X·Aᵀ + B·Bᵀ = 0 for Hurwitz A (the
/// controllability Gramian of (A, B); the observability Gramian of (A, C) is
/// `lyap_cholesky(&a.transpose(), &c.transpose())`).
///
/// Errors: non-square or non-finite A, B without n rows, an eigenvalue of A with Re λ ≥ −τ,
/// τ = 1000·ε·max(‖A‖_F, 1): unstable or stable only within rounding
/// ([`LtiError::Undefined`], naming it).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::lyap_cholesky;
/// // 1/(s + 1): X = 1/2, L = 1/√2.
/// let s = lyap_cholesky(&DMatrix::from_element(1, 1, -1.0), &DMatrix::from_element(1, 1, 1.0)).unwrap();
/// assert!((s.l[(0, 0)] - 0.5f64.sqrt()).abs() < 4e-16);
/// let unstable = lyap_cholesky(&DMatrix::from_element(1, 1, 2.0), &DMatrix::from_element(1, 1, 1.0));
/// assert!(unstable.unwrap_err().to_string().contains("λ = 2"));
/// ```
pub fn lyap_cholesky(a: &DMatrix<f64>, b: &DMatrix<f64>) -> Result<CholeskySolution> {
    hammarling(a, b, false)
}

/// The Cholesky factor of the solution of A·X·Aᵀ − X + B·Bᵀ = 0 for Schur-stable A (all
/// |λ| < 1): the discrete controllability Gramian.
///
/// Errors: as [`lyap_cholesky`], with |λ| ≥ 1 − τ.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::dlyap_cholesky;
/// // x = 0.25x + 3 ⇒ x = 4, L = 2.
/// let s = dlyap_cholesky(&DMatrix::from_element(1, 1, 0.5), &DMatrix::from_element(1, 1, 3f64.sqrt())).unwrap();
/// assert!((s.l[(0, 0)] - 2.0).abs() < 1e-15);
/// ```
pub fn dlyap_cholesky(a: &DMatrix<f64>, b: &DMatrix<f64>) -> Result<CholeskySolution> {
    hammarling(a, b, true)
}

fn hammarling(a: &DMatrix<f64>, b: &DMatrix<f64>, discrete: bool) -> Result<CholeskySolution> {
    stable_or_eigenvalue(a, b, discrete)?.map_err(|z| {
        let (what, region) = if discrete {
            (
                "the Cholesky factor of the discrete Lyapunov solution",
                "on or outside the unit circle (within rounding)",
            )
        } else {
            (
                "the Cholesky factor of the Lyapunov solution",
                "in the closed right half-plane (within rounding)",
            )
        };
        LtiError::Undefined {
            what: what.into(),
            reason: format!(
                "A must be stable, but its eigenvalue λ = {} lies {region}",
                complex_number(z.re, z.im)
            ),
        }
    })
}

/// Hammarling's method, or the first eigenvalue of A that is not stable by more than
/// rounding (`checks::unstable_within_rounding`), found on the Schur form the method computes
/// anyway — so that a caller with its own words for an unstable model (the Gramians) needs no
/// eigenvalue computation of its own.
///
/// Errors: the argument errors of [`lyap_cholesky`].
pub(crate) fn stable_or_eigenvalue(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    discrete: bool,
) -> Result<std::result::Result<CholeskySolution, C>> {
    let n = check_coefficient(a, "A")?;
    super::checks::check_input_matrix(b, n)?;
    let opts = SchurOptions {
        balance: false,
        want_q: true,
        want_t: true,
    };
    let real = real_schur(&a.transpose(), opts)?;
    // Stable by more than rounding (the rule of `checks::unstable_within_rounding`).
    let unstable = super::checks::unstable_within_rounding(a, discrete);
    if let Some(z) = real.eigenvalues().into_iter().find(|&z| unstable(z)) {
        return Ok(Err(z));
    }
    let cs = complex_schur(&real);
    let u_real = real.q.unwrap_or_else(|| DMatrix::identity(n, n));
    // Q = U·Z.
    let mut q = u_real.map(|x| C::new(x, 0.0));
    for &(k, [g11, g12, g21, g22]) in &cs.rotations {
        for i in 0..n {
            let (x, y) = (q[(i, k)], q[(i, k + 1)]);
            q[(i, k)] = x * g11 + y * g21;
            q[(i, k + 1)] = x * g12 + y * g22;
        }
    }
    let s = cs.s;
    // R from the rows of B̃Q = BᵀQ.
    let mut r = DMatrix::<C>::zeros(n, n);
    let bt_q = b.transpose().map(|x| C::new(x, 0.0)) * &q;
    let mut row = vec![C::new(0.0, 0.0); n];
    for i in 0..bt_q.nrows() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = bt_q[(i, j)];
        }
        add_row(&mut r, &mut row, 0);
    }
    let u = factor(&s, &mut r, discrete);
    // L_c = Q·Uᴴ, then the real triangular factor of [Re L_c, Im L_c].
    let lc = &q * u.adjoint();
    let mut m = DMatrix::<f64>::zeros(2 * n, n);
    for j in 0..n {
        for i in 0..n {
            m[(j, i)] = lc[(i, j)].re;
            m[(n + j, i)] = lc[(i, j)].im;
        }
    }
    let mut l = m.qr().r().transpose();
    for j in 0..n {
        if l[(j, j)] < 0.0 {
            for i in j..n {
                l[(i, j)] = -l[(i, j)];
            }
        }
    }
    let x = &l * l.transpose();
    let bb = b * b.transpose();
    let residual = if discrete {
        relative_residual(&[&(a * &x * a.transpose()), &(-&x), &bb])
    } else {
        relative_residual(&[&(a * &x), &(&x * a.transpose()), &bb])
    };
    Ok(Ok(CholeskySolution { l, residual }))
}

/// Adds the row `y` (entries `start..`) to the upper triangular trailing block
/// `r[start.., start..]` and re-triangularises by Givens rotations (y is destroyed).
fn add_row(r: &mut DMatrix<C>, y: &mut [C], start: usize) {
    let n = r.nrows();
    for j in start..n {
        if y[j].norm() == 0.0 {
            continue;
        }
        let (c, s) = lartg(r[(j, j)], y[j]);
        for k in j..n {
            let (x, w) = (r[(j, k)], y[k]);
            r[(j, k)] = x * c + s * w;
            y[k] = w * c - s.conj() * x;
        }
        y[j] = C::new(0.0, 0.0);
    }
}

/// Hammarling's recursion: U upper triangular with Uᴴ·U = X̂ (see the module docs).
fn factor(s: &DMatrix<C>, r: &mut DMatrix<C>, discrete: bool) -> DMatrix<C> {
    let n = s.nrows();
    let zero = C::new(0.0, 0.0);
    let mut u = DMatrix::<C>::zeros(n, n);
    let mut v = vec![zero; n];
    let mut y = vec![zero; n];
    for k in 0..n {
        let s11 = s[(k, k)];
        let r11 = r[(k, k)];
        let denom = if discrete {
            1.0 - s11.norm_sqr()
        } else {
            -2.0 * s11.re
        };
        let u11 = r11.norm() / denom.sqrt();
        let alpha = if u11 > 0.0 { r11 / u11 } else { zero };
        u[(k, k)] = C::new(u11, 0.0);
        if k + 1 == n {
            break;
        }
        // The triangular system for v = u₁₂ᴴ (forward substitution down the columns of S).
        for i in k + 1..n {
            let rhs = if discrete {
                -alpha * r[(k, i)].conj() - s11 * u11 * s[(k, i)].conj()
            } else {
                -alpha * r[(k, i)].conj() - u11 * s[(k, i)].conj()
            };
            let mut acc = zero;
            for j in k + 1..i {
                acc += s[(j, i)].conj() * v[j];
            }
            v[i] = if discrete {
                (rhs - s11 * acc) / (s11 * s[(i, i)].conj() - 1.0)
            } else {
                (rhs - acc) / (s[(i, i)].conj() + s11)
            };
            u[(k, i)] = v[i].conj();
        }
        // The row that updates R₂₂.
        for j in k + 1..n {
            y[j] = if discrete {
                let mut w = u11 * s[(k, j)];
                for i in k + 1..=j {
                    w += u[(k, i)] * s[(i, j)];
                }
                s11 * r[(k, j)] - alpha * w
            } else {
                r[(k, j)] - alpha * u[(k, j)]
            };
        }
        add_row(r, &mut y, k + 1);
    }
    u
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::linalg::lyapunov::{dlyap, lyap};

    fn random(n: usize, m: usize, seed: u64) -> DMatrix<f64> {
        let mut state = seed;
        DMatrix::from_fn(n, m, |_, _| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        })
    }

    #[test]
    fn factor_reproduces_the_bartels_stewart_solution() {
        for (n, m, seed) in [
            (1, 1, 1),
            (2, 1, 2),
            (5, 2, 3),
            (20, 3, 4),
            (60, 1, 5),
            (12, 15, 6),
        ] {
            let a = random(n, n, seed) - DMatrix::identity(n, n) * (n as f64).sqrt();
            let b = random(n, m, seed + 7);
            let c = lyap_cholesky(&a, &b).unwrap();
            let x = lyap(&a, &(&b * b.transpose())).unwrap().x;
            let llt = &c.l * c.l.transpose();
            assert!(
                (&llt - &x).norm() < 1e-12 * x.norm(),
                "n={n}: {}",
                (&llt - &x).norm()
            );
            assert!(c.residual < 1e-13, "n={n}: {}", c.residual);
            for i in 0..n {
                assert!(c.l[(i, i)] >= 0.0);
                for j in i + 1..n {
                    assert!(c.l[(i, j)] == 0.0);
                }
            }
            let ad = random(n, n, seed + 3) * (1.2 / (n as f64).sqrt());
            let ad = if super::super::schur::schur_eigenvalues(&ad)
                .unwrap()
                .iter()
                .all(|z| z.norm() < 1.0)
            {
                ad
            } else {
                ad * 0.5
            };
            let c = dlyap_cholesky(&ad, &b).unwrap();
            let x = dlyap(&ad, &(&b * b.transpose())).unwrap().x;
            let llt = &c.l * c.l.transpose();
            assert!(
                (&llt - &x).norm() < 1e-12 * x.norm(),
                "n={n}: {}",
                (&llt - &x).norm()
            );
        }
    }

    #[test]
    fn rank_deficient_and_unstable() {
        // B = 0: L = 0.
        let a = DMatrix::from_row_slice(2, 2, &[-1.0, 1.0, 0.0, -2.0]);
        let c = lyap_cholesky(&a, &DMatrix::zeros(2, 1)).unwrap();
        assert!(c.l.iter().all(|x| *x == 0.0));
        // Uncontrollable second state of diag(−1, −2) with B = e₁: X = diag(1/2, 0).
        let a = DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -2.0]);
        let b = DMatrix::from_row_slice(2, 1, &[1.0, 0.0]);
        let c = lyap_cholesky(&a, &b).unwrap();
        assert!((c.l[(0, 0)] - 0.5f64.sqrt()).abs() < 4e-16, "{}", c.l);
        assert!(c.l[(1, 1)].abs() < 1e-16 && c.l[(1, 0)].abs() < 1e-16);
        let osc = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, 0.0]);
        let e = lyap_cholesky(&osc, &b).unwrap_err().to_string();
        assert!(e.contains("closed right half-plane"), "{e}");
        // A rigid-body mode computed as −5.7e-17 (the periodic lattice's, before this check
        // gave a "Gramian" of 1e15 with residual 0.68): stable only within rounding, refused.
        let rigid = DMatrix::from_row_slice(2, 2, &[-5.7e-17, 0.0, 0.0, -1.0]);
        let e = lyap_cholesky(&rigid, &DMatrix::from_element(2, 1, 1.0))
            .unwrap_err()
            .to_string();
        assert!(e.contains("within rounding"), "{e}");
        let slow = DMatrix::from_row_slice(2, 2, &[-1e-9, 0.0, 0.0, -1.0]);
        assert!(lyap_cholesky(&slow, &DMatrix::from_element(2, 1, 1.0)).is_ok());
        let e = dlyap_cholesky(&DMatrix::identity(1, 1), &DMatrix::identity(1, 1))
            .unwrap_err()
            .to_string();
        assert!(e.contains("unit circle"), "{e}");
        assert!(lyap_cholesky(&a, &DMatrix::zeros(3, 1)).is_err());
    }
}
