//! The robust pole placement of Kautsky, Nichols and Van Dooren (1985), method 0, for
//! several inputs (the algorithm of `scipy.signal.place_poles(method="KNV0")`, here in
//! complex arithmetic so that complex pairs are placed too).
//!
//! # Method
//! With B = \[U₀ U₁\]·\[Z; 0\] (QR, Z invertible m × m), a vector x can be an eigenvector of
//! A − BK for λ exactly when U₁ᵀ(A − λI)x = 0: the columns of Sᵢ, an orthonormal basis of that
//! m-dimensional kernel, span the choices for the pole λᵢ. KNV0 picks one unit vector xᵢ in
//! each Sᵢ so that X = \[x₁ … x_n\] is as well conditioned as it can make it: it sweeps over
//! the columns, replacing xᵢ by the projection onto Sᵢ of the direction orthogonal to all the
//! other columns (the conjugate of row i of X⁻¹, kept by rank-one updates), which maximises
//! |det X| over that column; it stops when |det X| changes by less than 1e-6 relative or after
//! 50 sweeps. A real pole keeps a real eigenvector (the real combination of Sᵢ closest to the
//! update), a complex pair keeps conjugate eigenvectors. Then M = XΛX⁻¹ is real (up to
//! rounding, which is dropped) and K = Z⁻¹U₀ᵀ(A − M).
//!
//! With as many independent inputs as states, any X works: X = I and M the real block
//! diagonal of the poles.

use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

use crate::error::{LtiError, Result};

/// The result of KNV0: the gain, κ₂(X) and the sweeps made.
pub(crate) struct Knv {
    pub gain: DMatrix<f64>,
    pub condition: f64,
    pub iterations: usize,
}

const MAX_SWEEPS: usize = 50;
const DET_RTOL: f64 = 1e-6;

/// KNV0 for (A, B) controllable, B of full column rank m ≥ 2, `poles` closed under
/// conjugation with `partner[i]` the index of the conjugate of pole i (i itself when real).
pub(crate) fn knv0(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    poles: &[Complex64],
    partner: &[usize],
) -> Result<Knv> {
    let n = a.nrows();
    let m = b.ncols();
    // full QR of B through [B I]: the thin Q of an n × (m + n) matrix is n × n
    let mut bi = DMatrix::<f64>::zeros(n, m + n);
    bi.view_mut((0, 0), (n, m)).copy_from(b);
    bi.view_mut((0, m), (n, n)).fill_with_identity();
    let qr = bi.qr();
    let q = qr.q();
    let r = qr.r();
    let u0 = q.columns(0, m).clone_owned();
    let z = r.view((0, 0), (m, m)).clone_owned();
    let (x, condition, iterations) = if m == n {
        (None, 1.0, 0)
    } else {
        let u1t = q.columns(m, n - m).transpose();
        let spaces = kernels(a, &u1t, poles, partner)?;
        let (x, sweeps) = sweep(&spaces, poles, partner)?;
        let sv = x.clone().singular_values();
        let cond = if sv.min() > 0.0 {
            sv.max() / sv.min()
        } else {
            f64::INFINITY
        };
        (Some(x), cond, sweeps)
    };
    let mreal = match x {
        Some(x) => {
            let xinv = x.clone().try_inverse().ok_or_else(singular_x)?;
            let mut xl = x.clone();
            for (j, p) in poles.iter().enumerate() {
                let mut col = xl.column_mut(j);
                col *= *p;
            }
            (xl * xinv).map(|v| v.re)
        }
        None => block_diagonal(poles, partner),
    };
    let rhs = u0.transpose() * (a - mreal);
    let gain = z
        .solve_upper_triangular(&rhs)
        .ok_or_else(|| LtiError::invalid("B has dependent columns"))?;
    if gain.iter().any(|v| !v.is_finite()) {
        return Err(LtiError::invalid(
            "the placement overflowed: the requested poles or A are too large",
        ));
    }
    Ok(Knv {
        gain,
        condition,
        iterations,
    })
}

fn singular_x() -> LtiError {
    LtiError::invalid(
        "the robust placement found no independent closed-loop eigenvectors for these poles \
         (the requested poles cannot be placed with a diagonalisable closed loop)",
    )
}

/// The real block diagonal of the poles (a pair as \[\[α, β\], \[−β, α\]\]).
fn block_diagonal(poles: &[Complex64], partner: &[usize]) -> DMatrix<f64> {
    let n = poles.len();
    let mut m = DMatrix::<f64>::zeros(n, n);
    let mut k = 0;
    for (i, p) in poles.iter().enumerate() {
        if partner[i] == i {
            m[(k, k)] = p.re;
            k += 1;
        } else if p.im > 0.0 {
            m[(k, k)] = p.re;
            m[(k + 1, k + 1)] = p.re;
            m[(k, k + 1)] = p.im;
            m[(k + 1, k)] = -p.im;
            k += 2;
        }
    }
    m
}

/// Sᵢ for every pole: an orthonormal basis (n × m) of the kernel of U₁ᵀ(A − λᵢI); a conjugate
/// partner's basis is the conjugate.
fn kernels(
    a: &DMatrix<f64>,
    u1t: &DMatrix<f64>,
    poles: &[Complex64],
    partner: &[usize],
) -> Result<Vec<DMatrix<Complex64>>> {
    let n = a.nrows();
    let k = u1t.nrows(); // n − m
    let u1a = u1t * a;
    let mut out: Vec<Option<DMatrix<Complex64>>> = vec![None; n];
    for (i, p) in poles.iter().enumerate() {
        if partner[i] != i && p.im < 0.0 {
            continue;
        }
        let basis = if partner[i] == i {
            // real: the transpose of U₁ᵀ(A − λI), completed by I, orthogonalised
            let mut mt = DMatrix::<f64>::zeros(n, k + n);
            mt.view_mut((0, 0), (n, k))
                .copy_from(&(&u1a - u1t * p.re).transpose());
            mt.view_mut((0, k), (n, n)).fill_with_identity();
            let q = mt.qr().q();
            q.columns(k, n - k).map(|v| Complex64::new(v, 0.0))
        } else {
            let mc = u1a.map(|v| Complex64::new(v, 0.0)) - u1t.map(|v| *p * v);
            let mut mt = DMatrix::<Complex64>::zeros(n, k + n);
            mt.view_mut((0, 0), (n, k)).copy_from(&mc.adjoint());
            mt.view_mut((0, k), (n, n)).fill_with_identity();
            let q = mt.qr().q();
            q.columns(k, n - k).clone_owned()
        };
        if partner[i] != i {
            out[partner[i]] = Some(basis.map(|v| v.conj()));
        }
        out[i] = Some(basis);
    }
    out.into_iter()
        .map(|s| s.ok_or_else(|| LtiError::invalid("internal: a pole without its kernel")))
        .collect()
}

/// The sweeps of KNV0; returns X and the number of sweeps.
fn sweep(
    spaces: &[DMatrix<Complex64>],
    poles: &[Complex64],
    partner: &[usize],
) -> Result<(DMatrix<Complex64>, usize)> {
    let n = poles.len();
    let m = spaces[0].ncols();
    let mut x = DMatrix::<Complex64>::zeros(n, n);
    for i in 0..n {
        if partner[i] != i && poles[i].im < 0.0 {
            continue;
        }
        // deterministic, distinct weights: a repeated pole gets independent vectors
        let w = DVector::<Complex64>::from_fn(m, |k, _| {
            Complex64::new(
                1.0 + 0.5 * (((i * 7 + k * 13) as f64) * 0.618_034).fract(),
                0.0,
            )
        });
        let col = unit(&spaces[i] * w);
        x.set_column(i, &col);
        if partner[i] != i {
            x.set_column(partner[i], &col.map(|v| v.conj()));
        }
    }
    let mut prev_det = 0.0;
    let mut sweeps = 0;
    for s in 0..MAX_SWEEPS {
        let lu = x.clone().lu();
        let det = lu.determinant().norm();
        let mut xinv = lu.try_inverse().ok_or_else(singular_x)?;
        if s > 0 && (det - prev_det).abs() <= DET_RTOL * det {
            break;
        }
        prev_det = det;
        sweeps = s + 1;
        for i in 0..n {
            if partner[i] != i && poles[i].im < 0.0 {
                continue;
            }
            let y = xinv.row(i).adjoint();
            let v = spaces[i].adjoint() * &y;
            let new = if partner[i] == i {
                unit(&spaces[i] * real_direction(&v))
            } else {
                unit(&spaces[i] * v)
            };
            if new.iter().any(|c| !c.re.is_finite() || !c.im.is_finite()) {
                continue;
            }
            if !replace(&mut x, &mut xinv, i, &new) {
                continue;
            }
            if partner[i] != i {
                replace(&mut x, &mut xinv, partner[i], &new.map(|c| c.conj()));
            }
        }
    }
    Ok((x, sweeps))
}

/// The unit real vector w maximising |wᵀv|: the top left singular vector of \[Re v, Im v\]
/// (returned as complex with zero imaginary parts).
fn real_direction(v: &DVector<Complex64>) -> DVector<Complex64> {
    let re = v.map(|c| c.re);
    let im = v.map(|c| c.im);
    let (g11, g22, g12) = (re.dot(&re), im.dot(&im), re.dot(&im));
    let top = 0.5 * (g11 + g22) + (0.25 * (g11 - g22).powi(2) + g12 * g12).sqrt();
    let (c0, c1) = if g12.abs() > 1e-300 {
        (top - g22, g12)
    } else if g11 >= g22 {
        (1.0, 0.0)
    } else {
        (0.0, 1.0)
    };
    (re * c0 + im * c1).map(|v| Complex64::new(v, 0.0))
}

fn unit(v: DVector<Complex64>) -> DVector<Complex64> {
    let nrm = v.norm();
    if nrm > 0.0 {
        v / Complex64::new(nrm, 0.0)
    } else {
        v
    }
}

/// Replaces column i of X by `new` and updates X⁻¹ by Sherman–Morrison; false (nothing
/// changed) when the new X would be (nearly) singular.
fn replace(
    x: &mut DMatrix<Complex64>,
    xinv: &mut DMatrix<Complex64>,
    i: usize,
    new: &DVector<Complex64>,
) -> bool {
    let d = new - x.column(i);
    let u = &*xinv * &d;
    let denom = Complex64::new(1.0, 0.0) + u[i];
    if denom.norm() < 1e-8 || !new.iter().all(|c| c.norm() > 0.0 || new.norm() > 0.0) {
        return false;
    }
    let row = xinv.row(i).clone_owned();
    *xinv -= (u / denom) * row;
    x.set_column(i, new);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_b_uses_the_block_diagonal() {
        let a = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 3.0, 4.0]);
        let b = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 1.0, 2.0]);
        let p = [Complex64::new(-1.0, 2.0), Complex64::new(-1.0, -2.0)];
        let k = knv0(&a, &b, &p, &[1, 0]).unwrap();
        let ev = crate::numeric::eigenvalues(&(&a - &b * &k.gain)).unwrap();
        for e in ev {
            assert!(
                (e.re + 1.0).abs() < 1e-13 && (e.im.abs() - 2.0).abs() < 1e-13,
                "{e}"
            );
        }
    }
}
