//! Newton refinement in defect-correction form (Newton–Kleinman, Hewer), the residual and the
//! condition estimate.

use nalgebra::DMatrix;

use super::{Data, Kind, Riccati, symmetrise};
use crate::error::{LtiError, Result, complex_number};
use crate::numeric::linalg::lyapunov::{MatrixSolution, dlyap, lyap};
use crate::numeric::linalg::norms::frobenius;
use crate::numeric::linalg::schur::schur_eigenvalues;

/// 𝓡(X), K(X), and the Frobenius norms of 𝓡's terms summed.
fn residual(d: &Data, x: &DMatrix<f64>, kind: Kind) -> Option<(DMatrix<f64>, DMatrix<f64>, f64)> {
    let (a, b, q, r, s) = (&d.a, &d.b, &d.q, &d.r, &d.s);
    let fro = |m: &DMatrix<f64>| frobenius(m.iter());
    match kind {
        Kind::Continuous => {
            let xa = x * a;
            let xb_s = x * b + s;
            let k = r.clone().cholesky()?.solve(&xb_s.transpose());
            let quad = &xb_s * &k;
            let mut res = xa.transpose() + &xa - &quad + q;
            symmetrise(&mut res);
            let scale = 2.0 * fro(&xa) + fro(&quad) + fro(q);
            Some((res, k, scale))
        }
        Kind::Discrete => {
            let xa = x * a;
            let ata = a.transpose() * &xa;
            let bx = b.transpose() * x;
            let m = r + &bx * b;
            let lhs = &bx * a + s.transpose();
            let k = m.clone().cholesky()?.solve(&lhs);
            let quad = lhs.transpose() * &k;
            let mut res = &ata - x - &quad + q;
            symmetrise(&mut res);
            let scale = fro(&ata) + fro(x) + fro(&quad) + fro(q);
            Some((res, k, scale))
        }
    }
}

/// Newton steps in defect-correction form while the residual decreases; the closed loop
/// checked.
pub(super) fn refine(d: &Data, x0: DMatrix<f64>, kind: Kind) -> Result<Riccati> {
    let fail = |why: &str| LtiError::SingularEquation {
        equation: kind.equation().into(),
        reason: why.to_string(),
    };
    let rel = |res: &DMatrix<f64>, scale: f64| {
        if scale == 0.0 {
            0.0
        } else {
            frobenius(res.iter()) / scale
        }
    };
    let mut x = x0;
    let (mut res, mut k, scale) = residual(d, &x, kind).ok_or_else(|| {
        fail("no stabilising solution: R + BᵀXB is not positive definite at the computed X")
    })?;
    let mut best = rel(&res, scale);
    let mut steps = 0;
    let mut sep_solution: Option<MatrixSolution> = None;
    for _ in 0..6 {
        let acl = &d.a - &d.b * &k;
        let step = match kind {
            Kind::Continuous => lyap(&acl.transpose(), &res),
            Kind::Discrete => dlyap(&acl.transpose(), &res),
        };
        let Ok(step) = step else { break };
        let trial = &x + &step.x;
        let Some((r2, k2, s2)) = residual(d, &trial, kind) else {
            break;
        };
        let e = rel(&r2, s2);
        sep_solution = Some(step);
        if e.is_nan() || e >= best {
            break;
        }
        x = trial;
        res = r2;
        k = k2;
        best = e;
        steps += 1;
        if best <= f64::EPSILON {
            break;
        }
    }
    let acl = &d.a - &d.b * &k;
    let closed_loop = schur_eigenvalues(&acl)?;
    for z in &closed_loop {
        let bad = match kind {
            Kind::Continuous => z.re >= 0.0,
            Kind::Discrete => z.norm() >= 1.0,
        };
        if bad {
            return Err(fail(&format!(
                "no stabilising solution: the computed solution leaves the closed-loop eigenvalue {} unstable",
                complex_number(z.re, z.im)
            )));
        }
    }
    let condition = condition(d, &x, &acl, sep_solution, kind);
    Ok(Riccati {
        x,
        gain: k,
        closed_loop,
        residual: best,
        condition,
        refinements: steps,
    })
}

/// The condition estimate of the module docs.
fn condition(
    d: &Data,
    x: &DMatrix<f64>,
    acl: &DMatrix<f64>,
    step: Option<MatrixSolution>,
    kind: Kind,
) -> f64 {
    let fro = |m: &DMatrix<f64>| frobenius(m.iter());
    let nx = fro(x);
    if nx == 0.0 {
        return 0.0;
    }
    let na = fro(&d.a);
    let nacl = fro(acl);
    // condition of the Lyapunov step = coeff·sep⁻¹ (lower bound) ⇒ sep⁻¹ ≥ condition/coeff.
    let sep_inv = match (step, kind) {
        (Some(s), Kind::Continuous) if nacl > 0.0 => s.condition / (2.0 * nacl),
        (Some(s), Kind::Discrete) => s.condition / (nacl * nacl + 1.0),
        _ => 0.0,
    };
    let (lin, quad) = match kind {
        Kind::Continuous => (2.0 * na, fro(&d.g)),
        Kind::Discrete => (na * na, fro(&d.g) * na * na),
    };
    sep_inv * (fro(&d.q) + lin * nx + quad * nx * nx) / nx
}
