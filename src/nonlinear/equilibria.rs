//! Equilibria f(x̄, ū) = 0: closed forms where the model has them, otherwise a damped Newton
//! search with the exact (AD) Jacobian from many starting points, de-duplicated.
//!
//! Every equilibrium carries its residual ‖f(x̄, ū)‖∞ (evaluated, not assumed) and whether it
//! is physically meaningful ([`SystemInfo::is_physical`](crate::nonlinear::SystemInfo::is_physical)).

use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use crate::error::{LtiError, Result};
use crate::nonlinear::system::{DynSystem, check_point};

/// How an equilibrium was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EquilibriumMethod {
    /// From the model's closed form.
    ClosedForm,
    /// By the Newton search.
    Newton,
}

/// An equilibrium (x̄, ū).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Equilibrium {
    /// The state x̄.
    pub x: Vec<f64>,
    /// The constant input ū.
    pub u: Vec<f64>,
    /// ‖f(x̄, ū)‖∞.
    pub residual: f64,
    /// Whether x̄ is physically meaningful.
    pub physical: bool,
    /// How it was found.
    pub method: EquilibriumMethod,
}

/// Options of the Newton search.
#[derive(Debug, Clone, PartialEq)]
pub struct EquilibriumSearch {
    /// Box [lo, hi] per state in which starting points are spread (Halton sequence). Empty:
    /// [−10, 10] for every state. A single entry applies to every state.
    pub bounds: Vec<(f64, f64)>,
    /// Number of starting points (the box centre is always the first).
    pub starts: usize,
    /// Newton iterations per start.
    pub max_iter: usize,
    /// Acceptance: ‖f‖∞ ≤ `tol` · (1 + ‖A‖∞ ‖x‖∞), a backward-error style scale.
    pub tol: f64,
    /// Use the model's closed form when it has one (default true).
    pub use_closed_form: bool,
}

impl Default for EquilibriumSearch {
    fn default() -> Self {
        EquilibriumSearch {
            bounds: Vec::new(),
            starts: 200,
            max_iter: 60,
            tol: 1e-10,
            use_closed_form: true,
        }
    }
}

/// ‖f(x, u)‖∞ with dimension checks.
pub fn residual(sys: &dyn DynSystem, x: &[f64], u: &[f64]) -> Result<f64> {
    check_point(sys, x, u)?;
    Ok(residual_unchecked(sys, x, u))
}

fn residual_unchecked(sys: &dyn DynSystem, x: &[f64], u: &[f64]) -> f64 {
    let mut dx = vec![0.0; sys.nx()];
    sys.eval_f(x, u, &mut dx);
    inf_norm(&dx)
}

fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(
        0.0_f64,
        |m, x| {
            if x.is_nan() { f64::NAN } else { m.max(x.abs()) }
        },
    )
}

/// All equilibria for the constant input `u`: the model's closed form when it has one (and
/// `search.use_closed_form`), otherwise [`newton_equilibria`]. Sorted by state, lexicographically.
///
/// ```
/// use ltikit::nonlinear::{equilibria, EquilibriumSearch, models::Lorenz};
/// let eq = equilibria(&Lorenz::default(), &[], &EquilibriumSearch::default()).unwrap();
/// assert_eq!(eq.len(), 3); // C−, origin, C+
/// assert!(eq.iter().all(|e| e.residual < 1e-12));
/// ```
pub fn equilibria(
    sys: &dyn DynSystem,
    u: &[f64],
    search: &EquilibriumSearch,
) -> Result<Vec<Equilibrium>> {
    check_point(sys, &vec![0.0; sys.nx()], u)?;
    if search.use_closed_form {
        if let Some(list) = sys.closed_form_equilibria(u) {
            let mut out = Vec::with_capacity(list.len());
            for x in list {
                check_point(sys, &x, u)?;
                out.push(Equilibrium {
                    residual: residual_unchecked(sys, &x, u),
                    physical: sys.is_physical(&x),
                    u: u.to_vec(),
                    x,
                    method: EquilibriumMethod::ClosedForm,
                });
            }
            sort(&mut out);
            return Ok(out);
        }
    }
    newton_equilibria(sys, u, search)
}

fn sort(eq: &mut [Equilibrium]) {
    eq.sort_by(|a, b| {
        a.x.iter()
            .zip(&b.x)
            .map(|(p, q)| p.total_cmp(q))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
}

/// The Newton search alone: damped Newton (backtracking on ‖f‖₂) with the AD Jacobian from
/// `search.starts` points of a Halton sequence in the box, singular Jacobians handled by a
/// least-squares (SVD) step; converged points within 1e-7 relative are merged (keeping the
/// smaller residual).
///
/// ```
/// use ltikit::nonlinear::{newton_equilibria, EquilibriumSearch, models::Lorenz};
/// let eq = newton_equilibria(&Lorenz::default(), &[], &EquilibriumSearch {
///     bounds: vec![(-30.0, 30.0)], ..Default::default() }).unwrap();
/// assert_eq!(eq.len(), 3);
/// let c = (8.0f64 / 3.0 * 27.0).sqrt();
/// assert!((eq[2].x[0] - c).abs() < 1e-12);
/// ```
pub fn newton_equilibria(
    sys: &dyn DynSystem,
    u: &[f64],
    search: &EquilibriumSearch,
) -> Result<Vec<Equilibrium>> {
    let n = sys.nx();
    check_point(sys, &vec![0.0; n], u)?;
    let bounds = resolve_bounds(&search.bounds, n)?;
    if search.starts == 0 || search.max_iter == 0 {
        return Err(LtiError::invalid(
            "the equilibrium search needs at least one start and one iteration",
        ));
    }
    if !(search.tol.is_finite() && search.tol > 0.0) {
        return Err(LtiError::InvalidParameter {
            name: "tol".into(),
            value: search.tol,
            reason: "the equilibrium tolerance must be finite and > 0".into(),
        });
    }
    if n == 0 {
        return Ok(vec![Equilibrium {
            x: Vec::new(),
            u: u.to_vec(),
            residual: 0.0,
            physical: true,
            method: EquilibriumMethod::Newton,
        }]);
    }
    let primes = first_primes(n);
    let mut found: Vec<Equilibrium> = Vec::new();
    for k in 0..search.starts {
        let x0: Vec<f64> = (0..n)
            .map(|i| {
                let (lo, hi) = bounds[i];
                let s = if k == 0 {
                    0.5
                } else {
                    halton(k as u64, primes[i])
                };
                lo + s * (hi - lo)
            })
            .collect();
        let span = bounds
            .iter()
            .map(|(lo, hi)| lo.abs().max(hi.abs()))
            .fold(1.0_f64, f64::max);
        if let Some((x, res)) = newton(sys, x0, u, search, span) {
            let scale = 1.0 + inf_norm(&x);
            if let Some(e) = found.iter_mut().find(|e| {
                e.x.iter()
                    .zip(&x)
                    .all(|(a, b)| (a - b).abs() <= 1e-7 * scale)
            }) {
                if res < e.residual {
                    e.x = x;
                    e.residual = res;
                }
            } else {
                found.push(Equilibrium {
                    physical: sys.is_physical(&x),
                    x,
                    u: u.to_vec(),
                    residual: res,
                    method: EquilibriumMethod::Newton,
                });
            }
        }
    }
    for e in &mut found {
        e.physical = sys.is_physical(&e.x);
    }
    sort(&mut found);
    Ok(found)
}

fn resolve_bounds(b: &[(f64, f64)], n: usize) -> Result<Vec<(f64, f64)>> {
    let list = match b.len() {
        0 => vec![(-10.0, 10.0); n],
        1 => vec![b[0]; n],
        k if k == n => b.to_vec(),
        k => {
            return Err(LtiError::invalid(format!(
                "the search box has {k} intervals, the model has {n} states"
            )));
        }
    };
    for (lo, hi) in &list {
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return Err(LtiError::invalid(format!(
                "search interval [{lo}, {hi}] must be finite with lo < hi"
            )));
        }
    }
    Ok(list)
}

/// One Newton run; `Some((x, residual))` when it converged to an acceptable point.
fn newton(
    sys: &dyn DynSystem,
    mut x: Vec<f64>,
    u: &[f64],
    search: &EquilibriumSearch,
    span: f64,
) -> Option<(Vec<f64>, f64)> {
    let n = x.len();
    let mut fx = vec![0.0; n];
    let mut trial = vec![0.0; n];
    let mut ft = vec![0.0; n];
    sys.eval_f(&x, u, &mut fx);
    let norm2 = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
    let mut fnorm = norm2(&fx);
    if !fnorm.is_finite() {
        return None;
    }
    let mut small_steps = 0;
    for _ in 0..search.max_iter {
        if fnorm == 0.0 {
            break;
        }
        let (a, _) = sys.jacobian_f(&x, u);
        let dx = newton_step(&a, &fx)?;
        let mut alpha = 1.0;
        let mut accepted = false;
        while alpha >= 1.0 / 1024.0 {
            for i in 0..n {
                trial[i] = x[i] - alpha * dx[i];
            }
            sys.eval_f(&trial, u, &mut ft);
            let tn = norm2(&ft);
            if tn.is_finite() && tn <= (1.0 - 1e-4 * alpha) * fnorm {
                accepted = true;
                break;
            }
            alpha *= 0.5;
        }
        if !accepted {
            // No decrease along the Newton direction: either converged to rounding level or
            // stuck. Stop; acceptance is decided below.
            break;
        }
        std::mem::swap(&mut x, &mut trial);
        std::mem::swap(&mut fx, &mut ft);
        fnorm = norm2(&fx);
        let step = alpha * dx.amax();
        if inf_norm(&x) > 1e6 * span {
            return None;
        }
        if step <= 4.0 * f64::EPSILON * (1.0 + inf_norm(&x)) {
            small_steps += 1;
            if small_steps >= 2 {
                break;
            }
        }
    }
    let res = inf_norm(&fx);
    let (a, _) = sys.jacobian_f(&x, u);
    let scale = 1.0 + a.abs().row_sum().max() * inf_norm(&x);
    (res.is_finite() && res <= search.tol * scale).then_some((x, res))
}

/// Solves A dx = f: LU, or the minimum-norm least-squares solution when A is singular.
fn newton_step(a: &DMatrix<f64>, f: &[f64]) -> Option<DVector<f64>> {
    let rhs = DVector::from_column_slice(f);
    if let Some(dx) = a.clone().lu().solve(&rhs) {
        if dx.iter().all(|v| v.is_finite()) {
            return Some(dx);
        }
    }
    crate::numeric::lstsq::min_norm_solve(a, &rhs, 1e-13)
}

/// The k-th element of the van der Corput sequence in base `b` (Halton coordinate).
fn halton(mut k: u64, b: u64) -> f64 {
    let mut f = 1.0;
    let mut r = 0.0;
    let bf = b as f64;
    while k > 0 {
        f /= bf;
        r += f * (k % b) as f64;
        k /= b;
    }
    r
}

fn first_primes(n: usize) -> Vec<u64> {
    let mut p = Vec::with_capacity(n);
    let mut c = 2u64;
    while p.len() < n {
        if p.iter().take_while(|&&q| q * q <= c).all(|&q| c % q != 0) {
            p.push(c);
        }
        c += 1;
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nonlinear::models::{Mems, Pendulum, VanDerPol};

    #[test]
    fn halton_is_low_discrepancy() {
        assert!((halton(1, 2) - 0.5).abs() < 1e-15);
        assert!((halton(2, 2) - 0.25).abs() < 1e-15);
        assert!((halton(1, 3) - 1.0 / 3.0).abs() < 1e-15);
        assert_eq!(first_primes(5), vec![2, 3, 5, 7, 11]);
    }

    #[test]
    fn newton_finds_the_pendulum_equilibria_in_a_window() {
        let p = Pendulum::default();
        let s = EquilibriumSearch {
            bounds: vec![(-4.0, 4.0), (-1.0, 1.0)],
            use_closed_form: false,
            ..Default::default()
        };
        let eq = equilibria(&p, &[0.0], &s).unwrap();
        // θ = −π, 0, π, and possibly ±2π reached from starts near the edge.
        let pi = std::f64::consts::PI;
        for target in [-pi, 0.0, pi] {
            assert!(
                eq.iter().any(|e| (e.x[0] - target).abs() < 1e-12),
                "{target} missing from {eq:?}"
            );
        }
        for e in &eq {
            let k = e.x[0] / pi;
            assert!((k - k.round()).abs() < 1e-12);
            assert!(e.residual < 1e-12);
        }
    }

    #[test]
    fn newton_agrees_with_closed_forms() {
        let m = Mems::default();
        let s = EquilibriumSearch {
            use_closed_form: false,
            ..Default::default()
        };
        let newton = equilibria(&m, &[1.5], &s).unwrap();
        let closed = equilibria(&m, &[1.5], &EquilibriumSearch::default()).unwrap();
        assert_eq!(newton.len(), closed.len(), "{newton:?}");
        for (a, b) in newton.iter().zip(&closed) {
            for (p, q) in a.x.iter().zip(&b.x) {
                assert!((p - q).abs() < 1e-12 * (1.0 + q.abs()), "{a:?} vs {b:?}");
            }
            assert_eq!(a.physical, b.physical);
        }
        let v = equilibria(&VanDerPol, &[], &s).unwrap();
        assert_eq!(v.len(), 1);
        assert!(v[0].x.iter().all(|c| c.abs() < 1e-14));
    }

    #[test]
    fn bad_search_options() {
        let p = Pendulum::default();
        let s = EquilibriumSearch {
            bounds: vec![(1.0, -1.0)],
            use_closed_form: false,
            ..Default::default()
        };
        assert!(equilibria(&p, &[0.0], &s).is_err());
        assert!(equilibria(&p, &[0.0, 1.0], &EquilibriumSearch::default()).is_err());
        assert!(equilibria(&p, &[f64::NAN], &EquilibriumSearch::default()).is_err());
    }
}
