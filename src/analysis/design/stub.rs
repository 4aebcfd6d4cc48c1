//! TEMPORARY stand-in for `numeric::linalg::{care, dare}` (branch `riccati`) so that the
//! design code can be built and tested before the merge; removed at the merge.
#![allow(dead_code, clippy::type_complexity)]

use nalgebra::DMatrix;
use num_complex::Complex64;

use crate::error::{LtiError, Result};

pub struct Riccati {
    pub x: DMatrix<f64>,
    pub gain: DMatrix<f64>,
    pub closed_loop: Vec<Complex64>,
    pub residual: f64,
    pub condition: f64,
}

fn prep(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    s: Option<&DMatrix<f64>>,
) -> Result<(DMatrix<f64>, DMatrix<f64>, DMatrix<f64>, DMatrix<f64>)> {
    let rinv = r
        .clone()
        .try_inverse()
        .ok_or_else(|| LtiError::invalid("R is singular"))?;
    let (a1, q1) = match s {
        Some(s) => (a - b * &rinv * s.transpose(), q - s * &rinv * s.transpose()),
        None => (a.clone(), q.clone()),
    };
    let g = b * &rinv * b.transpose();
    Ok((a1, g, q1, rinv))
}

/// CARE by the matrix sign function of the Hamiltonian.
pub fn care(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    s: Option<&DMatrix<f64>>,
) -> Result<Riccati> {
    let n = a.nrows();
    let (a1, g, q1, rinv) = prep(a, b, q, r, s)?;
    let mut z = DMatrix::<f64>::zeros(2 * n, 2 * n);
    z.view_mut((0, 0), (n, n)).copy_from(&a1);
    z.view_mut((0, n), (n, n)).copy_from(&(-&g));
    z.view_mut((n, 0), (n, n)).copy_from(&(-&q1));
    z.view_mut((n, n), (n, n)).copy_from(&(-a1.transpose()));
    for _ in 0..100 {
        let lu = z.clone().lu();
        let det = lu.determinant().abs();
        let zi = lu
            .try_inverse()
            .ok_or_else(|| LtiError::invalid("stub: singular"))?;
        let c = det.powf(-1.0 / (2.0 * n as f64));
        let c = if c.is_finite() && c > 0.0 { c } else { 1.0 };
        let z1 = (&z * c + zi / c) * 0.5;
        let d = (&z1 - &z).norm();
        z = z1;
        if d <= 1e-14 * z.norm() {
            break;
        }
    }
    let i = DMatrix::<f64>::identity(n, n);
    let mut lhs = DMatrix::<f64>::zeros(2 * n, n);
    lhs.view_mut((0, 0), (n, n))
        .copy_from(&z.view((0, n), (n, n)));
    lhs.view_mut((n, 0), (n, n))
        .copy_from(&(z.view((n, n), (n, n)) + &i));
    let mut rhs = DMatrix::<f64>::zeros(2 * n, n);
    rhs.view_mut((0, 0), (n, n))
        .copy_from(&(-(z.view((0, 0), (n, n)) + &i)));
    rhs.view_mut((n, 0), (n, n))
        .copy_from(&(-z.view((n, 0), (n, n))));
    let hk = lhs
        .svd(true, true)
        .solve(&rhs, 1e-300)
        .map_err(|e| LtiError::invalid(e.to_string()))?;
    let x = (&hk + hk.transpose()) * 0.5;
    let sb = match s {
        Some(s) => b.transpose() * &x + s.transpose(),
        None => b.transpose() * &x,
    };
    let gain = &rinv * sb;
    let cl = a - b * &gain;
    let res = a.transpose() * &x + &x * a - gain.transpose() * r * &gain + q;
    Ok(Riccati {
        closed_loop: crate::numeric::eigenvalues(&cl)?,
        residual: res.norm() / (q.norm() + 2.0 * a.norm() * x.norm()),
        condition: 1.0,
        x,
        gain,
    })
}

/// DARE by SDA.
pub fn dare(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    s: Option<&DMatrix<f64>>,
) -> Result<Riccati> {
    let n = a.nrows();
    let (a1, g, q1, _) = prep(a, b, q, r, s)?;
    let i = DMatrix::<f64>::identity(n, n);
    let (mut ak, mut gk, mut hk) = (a1, g, q1);
    for _ in 0..100 {
        let wi = (&i + &gk * &hk)
            .try_inverse()
            .ok_or_else(|| LtiError::invalid("stub"))?;
        let a2 = &ak * &wi * &ak;
        let g2 = &gk + &ak * &wi * &gk * ak.transpose();
        let h2 = &hk + ak.transpose() * &hk * &wi * &ak;
        let d = (&h2 - &hk).norm();
        ak = a2;
        gk = g2;
        hk = h2;
        if d <= 1e-15 * hk.norm() {
            break;
        }
    }
    let x = (&hk + hk.transpose()) * 0.5;
    let rb = r + b.transpose() * &x * b;
    let top = match s {
        Some(s) => b.transpose() * &x * a + s.transpose(),
        None => b.transpose() * &x * a,
    };
    let gain = rb
        .clone()
        .lu()
        .solve(&top)
        .ok_or_else(|| LtiError::invalid("stub"))?;
    let cl = a - b * &gain;
    let res = a.transpose() * &x * a - &x - top.transpose() * &gain + q;
    Ok(Riccati {
        closed_loop: crate::numeric::eigenvalues(&cl)?,
        residual: res.norm() / (q.norm() + a.norm().powi(2) * x.norm()),
        condition: 1.0,
        x,
        gain,
    })
}
