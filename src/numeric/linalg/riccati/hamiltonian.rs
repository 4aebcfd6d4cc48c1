//! care's first solution: the stable invariant subspace of the Hamiltonian from its ordered
//! complex Schur form.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::{Data, Kind, symmetrise};
use crate::error::{LtiError, Result, complex_number, number};
use crate::numeric::linalg::complex_schur::complex_schur;
use crate::numeric::linalg::modal::schur_path::swap;
use crate::numeric::linalg::norms::frobenius;
use crate::numeric::linalg::schur::{SchurOptions, real_schur};

/// X = U₂U₁⁻¹ from the reordered complex Schur form of the Hamiltonian.
pub(super) fn hamiltonian_solution(d: &Data) -> Result<DMatrix<f64>> {
    let n = d.a.nrows();
    if n == 0 {
        return Ok(DMatrix::zeros(0, 0));
    }
    let mut h = DMatrix::<f64>::zeros(2 * n, 2 * n);
    h.view_mut((0, 0), (n, n)).copy_from(&d.at);
    h.view_mut((0, n), (n, n)).copy_from(&(-&d.g));
    h.view_mut((n, 0), (n, n)).copy_from(&(-&d.qt));
    h.view_mut((n, n), (n, n)).copy_from(&(-d.at.transpose()));
    let opts = SchurOptions {
        balance: false,
        want_q: true,
        want_t: true,
    };
    let real = real_schur(&h, opts)?;
    let tol = 100.0 * (2 * n) as f64 * f64::EPSILON * frobenius(h.iter());
    for z in real.eigenvalues() {
        if z.re.abs() <= tol {
            return Err(LtiError::SingularEquation {
                equation: Kind::Continuous.equation().into(),
                reason: format!(
                    "no stabilising solution: the Hamiltonian matrix has the eigenvalue {} on the imaginary axis (|Re| ≤ {}; is a mode of A on the axis unobservable through Q?)",
                    complex_number(z.re, z.im),
                    number(tol)
                ),
            });
        }
    }
    let cs = complex_schur(&real);
    let mut s = cs.s;
    let qr = real
        .q
        .ok_or_else(|| LtiError::invalid("the Schur vectors were not formed"))?;
    let mut w = qr.map(|x| Complex64::new(x, 0.0));
    for &(k, [g11, g12, g21, g22]) in &cs.rotations {
        for i in 0..2 * n {
            let (x, y) = (w[(i, k)], w[(i, k + 1)]);
            w[(i, k)] = x * g11 + y * g21;
            w[(i, k + 1)] = x * g12 + y * g22;
        }
    }
    // Stable eigenvalues to the top, keeping their order.
    let mut top = 0;
    for k in 0..2 * n {
        if s[(k, k)].re < 0.0 {
            for j in (top..k).rev() {
                swap(&mut s, &mut w, j);
            }
            top += 1;
        }
    }
    if top != n {
        return Err(LtiError::SingularEquation {
            equation: Kind::Continuous.equation().into(),
            reason: format!(
                "no stabilising solution: the Hamiltonian matrix has {top} stable eigenvalues instead of {n}"
            ),
        });
    }
    let u1 = w.view((0, 0), (n, n)).clone_owned();
    let u2 = w.view((n, 0), (n, n)).clone_owned();
    // Xᴴ = U₁⁻ᴴU₂ᴴ.
    let lu = u1.adjoint().lu();
    let xh = lu.solve(&u2.adjoint()).ok_or_else(|| LtiError::SingularEquation {
        equation: Kind::Continuous.equation().into(),
        reason: "no stabilising solution: the stable invariant subspace of the Hamiltonian is not a graph (U₁ singular)".into(),
    })?;
    let mut x = xh.adjoint().map(|z| z.re);
    symmetrise(&mut x);
    if x.iter().any(|v| !v.is_finite()) {
        return Err(LtiError::SingularEquation {
            equation: Kind::Continuous.equation().into(),
            reason: "no stabilising solution: U₁ of the stable invariant subspace is numerically singular".into(),
        });
    }
    Ok(x)
}
