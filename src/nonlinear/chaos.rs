//! Sensitivity to initial conditions: the largest Lyapunov exponent by Benettin's method on
//! the variational equation (with the exact AD Jacobian), and the finite-time exponent read
//! off two nearby trajectories ([`crate::nonlinear::divergence`]).
//!
//! **Benettin** (Benettin, Galgani, Giorgilli & Strelcyn, Meccanica 15, 1980): integrate
//! ẋ = f(x, u) together with δ̇ = A(x(t)) δ, A = ∂f/∂x exact by forward-mode AD; every
//! `interval` seconds add ln|δ| to a sum and renormalise δ to unit length. The running mean
//! (sum)/t converges to the largest exponent λ₁ (slowly: the error decays like 1/t); the
//! history is returned so that the convergence can be judged.
//!
//! **Finite-time exponent** of two trajectories d(t) apart: the least-squares slope of
//! ln d(t) over the samples where d₀·10³ < d < 10⁻² (after the difference has turned into the
//! most unstable direction, before it saturates at the size of the attractor).

use serde::Serialize;

use crate::error::{LtiError, Result, check_finite};
use crate::nonlinear::portraits::Divergence;
use crate::nonlinear::system::{DynSystem, check_point};
use crate::numeric::rk45::{Rk45Options, StepControl, integrate};

/// A Lyapunov-exponent estimate with its convergence history.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LyapunovEstimate {
    /// The estimate of the largest exponent λ₁ (1/s) at the end time.
    pub exponent: f64,
    /// (t, running estimate) after each renormalisation.
    pub history: Vec<(f64, f64)>,
    /// The state at the end time.
    pub final_state: Vec<f64>,
}

/// Largest Lyapunov exponent of the solution from `x0` under the constant input `u` over
/// [0, `t_end`] (module docs), renormalising every `interval` seconds.
///
/// ```
/// use ltikit::nonlinear::{lyapunov_exponent, models::Lorenz};
/// use ltikit::numeric::rk45::Rk45Options;
/// // Lorenz (σ, r, b) = (10, 28, 8/3): λ₁ ≈ 0.906 (Sprott, "Chaos and Time-Series Analysis", 2003).
/// let est = lyapunov_exponent(&Lorenz::default(), &[1.0, 0.0, 0.0], &[], 200.0, 0.5,
///                             &Rk45Options::default()).unwrap();
/// assert!((est.exponent - 0.906).abs() < 0.08, "{}", est.exponent);
/// ```
pub fn lyapunov_exponent(
    sys: &dyn DynSystem,
    x0: &[f64],
    u: &[f64],
    t_end: f64,
    interval: f64,
    opts: &Rk45Options,
) -> Result<LyapunovEstimate> {
    check_point(sys, x0, u)?;
    for (what, v) in [
        ("the end time", t_end),
        ("the renormalisation interval", interval),
    ] {
        check_finite(|| what.into(), v)?;
        if v <= 0.0 {
            return Err(LtiError::InvalidTime {
                value: v,
                reason: format!("{what} must be > 0"),
            });
        }
    }
    let n = sys.nx();
    if n == 0 {
        return Err(LtiError::invalid(
            "a model without states has no Lyapunov exponent",
        ));
    }
    let steps = (t_end / interval).ceil().max(1.0) as usize;
    let dt = t_end / steps as f64;
    let mut z = vec![0.0; 2 * n];
    z[..n].copy_from_slice(x0);
    let unit = 1.0 / (n as f64).sqrt();
    for v in &mut z[n..] {
        *v = unit;
    }
    let mut sum = 0.0;
    let mut history = Vec::with_capacity(steps);
    for k in 0..steps {
        let out = integrate(
            |_t, zs: &[f64], dz: &mut [f64]| {
                let (x, d) = zs.split_at(n);
                sys.eval_f(x, u, &mut dz[..n]);
                let (a, _) = sys.jacobian_f(x, u);
                for i in 0..n {
                    dz[n + i] = (0..n).map(|j| a[(i, j)] * d[j]).sum();
                }
            },
            k as f64 * dt,
            &z,
            (k + 1) as f64 * dt,
            opts,
            |_| StepControl::Continue,
        )?;
        z = out.x;
        let growth = z[n..].iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(growth.is_finite() && growth > 0.0) {
            return Err(LtiError::Undefined {
                what: "the Lyapunov exponent".into(),
                reason: format!(
                    "the tangent vector became {growth} at t = {}",
                    (k + 1) as f64 * dt
                ),
            });
        }
        sum += growth.ln();
        for v in &mut z[n..] {
            *v /= growth;
        }
        let t = (k + 1) as f64 * dt;
        history.push((t, sum / t));
    }
    Ok(LyapunovEstimate {
        exponent: sum / t_end,
        history,
        final_state: z[..n].to_vec(),
    })
}

/// A straight line fitted to ln d(t): the finite-time exponent.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ExponentFit {
    /// The slope (1/s).
    pub exponent: f64,
    /// ln d at t = 0 on the fitted line.
    pub intercept: f64,
    /// First sample time used.
    pub t_start: f64,
    /// Last sample time used.
    pub t_end: f64,
}

/// The finite-time exponent of two nearby trajectories: least-squares line through ln d(t)
/// over the samples with 10³·d(0) < d < 10⁻² (module docs); `None` with fewer than 3 such
/// samples.
///
/// ```
/// use ltikit::nonlinear::{divergence, finite_time_exponent, sample_times, InputSignal, models::Lorenz};
/// use ltikit::numeric::rk45::Rk45Options;
/// let t = sample_times(60.0, 6001).unwrap();
/// let o = Rk45Options { rtol: 1e-12, atol: 1e-14, ..Default::default() };
/// let d = divergence(&Lorenz::default(), &[1.0, 0.0, 0.0], &[1.0 + 1e-9, 0.0, 0.0],
///                    &InputSignal::none(), &t, &o).unwrap();
/// let fit = finite_time_exponent(&d).unwrap();
/// assert!(fit.exponent > 0.5 && fit.exponent < 1.5, "{fit:?}");
/// ```
pub fn finite_time_exponent(d: &Divergence) -> Option<ExponentFit> {
    let d0 = d.distance.first().copied()?;
    let pts: Vec<(f64, f64)> =
        d.a.t
            .iter()
            .zip(&d.distance)
            .filter(|(_, dd)| **dd > 1e3 * d0 && **dd < 1e-2)
            .map(|(t, dd)| (*t, dd.ln()))
            .collect();
    if pts.len() < 3 {
        return None;
    }
    let m = pts.len() as f64;
    let (st, sy) = pts.iter().fold((0.0, 0.0), |(a, b), p| (a + p.0, b + p.1));
    let (tm, ym) = (st / m, sy / m);
    let (mut num, mut den) = (0.0, 0.0);
    for (t, y) in &pts {
        num += (t - tm) * (y - ym);
        den += (t - tm) * (t - tm);
    }
    let slope = num / den;
    (den > 0.0).then(|| ExponentFit {
        exponent: slope,
        intercept: ym - slope * tm,
        t_start: pts[0].0,
        t_end: pts[pts.len() - 1].0,
    })
}
