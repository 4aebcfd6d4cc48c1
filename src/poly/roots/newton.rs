//! Newton's method for the acceptance test (an m-fold root is a simple root of p^(m−1), at which
//! p … p^(m−2) vanish to rounding level) and the guarded polish of simple roots.

use num_complex::Complex64;

use crate::numeric::dd::Dd;
use crate::numeric::tol::EPS;
use crate::poly::Poly;

/// p(x) by Horner in double-double: the residual of a computed root to ~2⁻¹⁰⁶·Σ|aᵢ||x|ⁱ, so
/// Newton can reach the root of the coefficients as given instead of stalling where the
/// `f64` evaluation's rounding (eps·Σ|aᵢ||x|ⁱ) hides p(x).
fn eval_dd(p: &Poly, x: f64) -> f64 {
    let xd = Dd::from(x);
    p.coeffs()
        .iter()
        .fold(Dd::ZERO, |r, &a| r * xd + Dd::from(a))
        .to_f64()
}

/// p(z) by Horner in double-double real and imaginary parts (see [`eval_dd`]).
fn eval_dd_complex(p: &Poly, z: Complex64) -> Complex64 {
    let (zr, zi) = (Dd::from(z.re), Dd::from(z.im));
    let (re, im) = p
        .coeffs()
        .iter()
        .fold((Dd::ZERO, Dd::ZERO), |(rr, ri), &a| {
            (rr * zr - ri * zi + Dd::from(a), rr * zi + ri * zr)
        });
    Complex64::new(re.to_f64(), im.to_f64())
}

/// At most this many Newton steps on the double-double residual after the `f64` polish.
const DD_STEPS: usize = 3;

/// γ in the acceptance test |p^(j)(c)| ≤ γ·(deg + 1)·eps·Σ|aᵢ^(j)||c|ⁱ.
pub(super) const GAMMA: f64 = 8.0;

/// Acceptance bound for |p^(j)(c)|.
pub(super) fn bound(d: &Poly, r: f64) -> f64 {
    GAMMA * (d.degree() + 1) as f64 * EPS * d.eval_abs(r)
}

pub(super) fn confirm_real(q: &Poly, x0: f64, m: usize, reach: f64) -> Option<f64> {
    let dm = q.nth_derivative(m - 1);
    let x = newton_real(&dm, x0, reach)?;
    let mut d = q.clone();
    for _ in 0..m - 1 {
        if d.eval(x).abs() > bound(&d, x.abs()) {
            return None;
        }
        d = d.derivative();
    }
    Some(x)
}

pub(super) fn confirm_complex(q: &Poly, z0: Complex64, m: usize, reach: f64) -> Option<Complex64> {
    let dm = q.nth_derivative(m - 1);
    let z = newton_complex(&dm, z0, reach)?;
    if z.im <= 0.0 {
        return None;
    }
    let mut d = q.clone();
    for _ in 0..m - 1 {
        if d.eval_complex(z).norm() > bound(&d, z.norm()) {
            return None;
        }
        d = d.derivative();
    }
    Some(z)
}

/// Newton on a polynomial expected to have a simple root near x0; None if it leaves the
/// neighbourhood or does not settle.
pub(super) fn newton_real(p: &Poly, x0: f64, reach: f64) -> Option<f64> {
    let dp = p.derivative();
    let mut x = x0;
    for _ in 0..50 {
        let f = p.eval(x);
        if f == 0.0 {
            return Some(x);
        }
        let d = dp.eval(x);
        if d == 0.0 || !d.is_finite() {
            return None;
        }
        let step = f / d;
        x -= step;
        if !x.is_finite() || (x - x0).abs() > reach {
            return None;
        }
        if step.abs() <= 4.0 * EPS * x.abs() {
            return Some(x);
        }
    }
    // Converged to rounding noise without meeting the step test: accept if tiny.
    Some(x)
}

pub(super) fn newton_complex(p: &Poly, z0: Complex64, reach: f64) -> Option<Complex64> {
    let dp = p.derivative();
    let mut z = z0;
    for _ in 0..50 {
        let f = p.eval_complex(z);
        if f.norm() == 0.0 {
            return Some(z);
        }
        let d = dp.eval_complex(z);
        if d.norm() == 0.0 || !d.norm().is_finite() {
            return None;
        }
        let step = f / d;
        z -= step;
        if !z.norm().is_finite() || (z - z0).norm() > reach {
            return None;
        }
        if step.norm() <= 4.0 * EPS * z.norm() {
            return Some(z);
        }
    }
    Some(z)
}

/// Guarded Newton polish of a simple real root: steps are taken only while |p| decreases and
/// the iterate stays within `reach` of the start.
pub(super) fn polish_real(p: &Poly, x0: f64, reach: f64) -> f64 {
    let dp = p.derivative();
    let x = guarded_steps_real(&dp, x0, x0, reach, 20, |x| p.eval(x));
    // the f64 residual stalls at the evaluation's rounding level: finish on the exact one
    guarded_steps_real(&dp, x, x0, reach, DD_STEPS, |x| eval_dd(p, x))
}

/// Newton steps x ← x − f(x)/p′(x) from `x`, each kept only while |f| decreases and the
/// iterate stays finite and within `reach` of `x0`; stops at a relative step of 2ε.
fn guarded_steps_real(
    dp: &Poly,
    mut x: f64,
    x0: f64,
    reach: f64,
    steps: usize,
    f: impl Fn(f64) -> f64,
) -> f64 {
    let mut fx = f(x).abs();
    for _ in 0..steps {
        let d = dp.eval(x);
        if fx == 0.0 || d == 0.0 || !d.is_finite() {
            break;
        }
        let xn = x - f(x) / d;
        let fn_ = f(xn).abs();
        if fn_.partial_cmp(&fx) != Some(std::cmp::Ordering::Less)
            || (xn - x0).abs() > reach
            || !xn.is_finite()
        {
            break;
        }
        let done = (xn - x).abs() <= 2.0 * EPS * xn.abs();
        x = xn;
        fx = fn_;
        if done {
            break;
        }
    }
    x
}

pub(super) fn polish_complex(p: &Poly, z0: Complex64, reach: f64) -> Complex64 {
    let dp = p.derivative();
    let z = guarded_steps_complex(&dp, z0, z0, reach, 20, |z| p.eval_complex(z));
    // the f64 residual stalls at the evaluation's rounding level: finish on the exact one
    guarded_steps_complex(&dp, z, z0, reach, DD_STEPS, |z| eval_dd_complex(p, z))
}

/// [`guarded_steps_real`] in the complex plane.
fn guarded_steps_complex(
    dp: &Poly,
    mut z: Complex64,
    z0: Complex64,
    reach: f64,
    steps: usize,
    f: impl Fn(Complex64) -> Complex64,
) -> Complex64 {
    let mut fz = f(z).norm();
    for _ in 0..steps {
        let d = dp.eval_complex(z);
        if fz == 0.0 || d.norm() == 0.0 || !d.norm().is_finite() {
            break;
        }
        let zn = z - f(z) / d;
        let fn_ = f(zn).norm();
        if fn_.partial_cmp(&fz) != Some(std::cmp::Ordering::Less)
            || (zn - z0).norm() > reach
            || !zn.norm().is_finite()
        {
            break;
        }
        let done = (zn - z).norm() <= 2.0 * EPS * zn.norm();
        z = zn;
        fz = fn_;
        if done {
            break;
        }
    }
    z
}
