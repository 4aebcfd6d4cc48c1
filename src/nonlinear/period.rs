//! The period of the undamped pendulum against its amplitude (seed §2.3.1.1).
//!
//! θ̈ + ω² sin θ = 0 with ω² = 3g/(2L), released at rest from θ₀ ∈ (0, π): the period is
//! T = 4K(k)/ω with modulus k = sin(θ₀/2) and K the complete elliptic integral of the first
//! kind, computed from the arithmetic–geometric mean K(k) = π / (2·AGM(1, √(1 − k²))) (quadratic
//! convergence, full precision in ~5 iterations). The small-angle period is 2π/ω; T → ∞ as
//! θ₀ → π (the separatrix).
//!
//! The *measured* period comes from a simulation: the zero crossings of θ̇ (every half period)
//! located by Brent's method on the integrator's dense output.

use serde::Serialize;

use crate::error::{LtiError, Result, check_finite};
use crate::nonlinear::models::Pendulum;
use crate::nonlinear::system::NonlinearSystem;
use crate::numeric::rk45::{Rk45Options, StepControl, integrate};
use crate::numeric::{Bracket, brent};

/// The arithmetic–geometric mean of two non-negative numbers.
///
/// ```
/// let g = ltikit::nonlinear::agm(1.0, 2f64.sqrt());
/// assert!((g - 1.1981402347355922).abs() < 1e-15); // Gauss's constant relation
/// ```
pub fn agm(a: f64, b: f64) -> f64 {
    let (mut a, mut b) = (a, b);
    for _ in 0..64 {
        let an = 0.5 * (a + b);
        let bn = (a * b).sqrt();
        if (an - bn).abs() <= 2.0 * f64::EPSILON * an {
            return an;
        }
        a = an;
        b = bn;
    }
    a
}

/// Complete elliptic integral of the first kind K(k) = ∫₀^{π/2} dψ/√(1 − k² sin²ψ), modulus
/// 0 ≤ k < 1.
///
/// ```
/// let k = ltikit::nonlinear::elliptic_k(0.0).unwrap();
/// assert!((k - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
/// // K(1/√2) = Γ(1/4)² / (4√π)
/// let k = ltikit::nonlinear::elliptic_k(0.5f64.sqrt()).unwrap();
/// assert!((k - 1.8540746773013719).abs() < 1e-15);
/// assert!(ltikit::nonlinear::elliptic_k(1.0).is_err());
/// ```
pub fn elliptic_k(k: f64) -> Result<f64> {
    check_finite(|| "the elliptic modulus".into(), k)?;
    if !(0.0..1.0).contains(&k.abs()) {
        return Err(LtiError::InvalidParameter {
            name: "k".into(),
            value: k,
            reason: "the elliptic modulus must satisfy |k| < 1 (K is infinite at |k| = 1)".into(),
        });
    }
    // √(1 − k²) as √((1 − k)(1 + k)): no cancellation for k near 1.
    let kp = ((1.0 - k.abs()) * (1.0 + k.abs())).sqrt();
    Ok(std::f64::consts::PI / (2.0 * agm(1.0, kp)))
}

fn check_amplitude(theta0: f64) -> Result<()> {
    check_finite(|| "the amplitude".into(), theta0)?;
    if !(theta0 > 0.0 && theta0 < std::f64::consts::PI) {
        return Err(LtiError::InvalidParameter {
            name: "amplitude".into(),
            value: theta0,
            reason: "the amplitude must lie in (0, π) rad (π is the separatrix)".into(),
        });
    }
    Ok(())
}

/// Exact period 4K(sin(θ₀/2))/ω of θ̈ + ω² sin θ = 0 released at rest from θ₀ ∈ (0, π).
///
/// ```
/// use ltikit::nonlinear::pendulum_period_exact;
/// let w = 2.0;
/// let small = pendulum_period_exact(w, 1e-4).unwrap();
/// assert!((small - std::f64::consts::PI).abs() < 1e-8); // 2π/ω
/// ```
pub fn pendulum_period_exact(omega: f64, theta0: f64) -> Result<f64> {
    check_finite(|| "ω".into(), omega)?;
    if omega <= 0.0 {
        return Err(LtiError::InvalidParameter {
            name: "omega".into(),
            value: omega,
            reason: "the angular frequency must be > 0".into(),
        });
    }
    check_amplitude(theta0)?;
    Ok(4.0 * elliptic_k((theta0 / 2.0).sin())? / omega)
}

/// Period measured by simulating the undamped pendulum (C set to 0, τ = 0) released at rest
/// from θ₀: `half_periods` successive zero crossings of θ̇ are located on the dense output with
/// Brent's method and T = 2·t_last/half_periods.
pub fn pendulum_period_simulated(
    pendulum: &Pendulum,
    theta0: f64,
    half_periods: usize,
    opts: &Rk45Options,
) -> Result<f64> {
    check_amplitude(theta0)?;
    if half_periods == 0 {
        return Err(LtiError::invalid("at least one half period is needed"));
    }
    let p = Pendulum::new(pendulum.m, pendulum.l, 0.0, pendulum.g)?;
    // Generous horizon: the exact period times the number of half periods, doubled.
    let t_max = pendulum_period_exact(p.omega(), theta0)? * half_periods as f64;
    let mut crossings: Vec<f64> = Vec::with_capacity(half_periods);
    let mut failure: Option<LtiError> = None;
    integrate(
        |_t, x, dx| p.f(x, &[0.0], dx),
        0.0,
        &[theta0, 0.0],
        t_max,
        opts,
        |step| {
            let (ta, tb) = (step.t_start(), step.t_end());
            let fa = step.state_start()[1];
            let fb = step.state_end()[1];
            // θ̇(0) = 0 exactly: the release is not a crossing.
            let strict = fa != 0.0 && fb != 0.0 && (fa < 0.0) != (fb < 0.0);
            let at_end = fb == 0.0 && tb > 0.0;
            if strict {
                match brent(
                    |t| step.eval_component(t, 1),
                    Bracket {
                        a: ta,
                        b: tb,
                        fa,
                        fb,
                    },
                    1e-15 * tb.max(1.0),
                ) {
                    Ok(t) => crossings.push(t),
                    Err(e) => {
                        failure = Some(e);
                        return StepControl::Stop;
                    }
                }
            } else if at_end {
                crossings.push(tb);
            }
            if crossings.len() >= half_periods {
                StepControl::Stop
            } else {
                StepControl::Continue
            }
        },
    )?;
    if let Some(e) = failure {
        return Err(e);
    }
    if crossings.len() < half_periods {
        // Can only happen when the tolerances are so loose that the period is badly off.
        return Err(LtiError::Undefined {
            what: "the simulated period".into(),
            reason: format!(
                "only {} of {half_periods} half periods were completed by t = {t_max}",
                crossings.len()
            ),
        });
    }
    Ok(2.0 * crossings[half_periods - 1] / half_periods as f64)
}

/// One row of the period-against-amplitude table.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PeriodPoint {
    /// Amplitude θ₀ (rad).
    pub amplitude: f64,
    /// Exact period 4K(k)/ω (s).
    pub exact: f64,
    /// Period measured by simulation (s).
    pub simulated: f64,
    /// Small-angle period 2π/ω (s).
    pub small_angle: f64,
    /// |simulated − exact| / exact.
    pub relative_error: f64,
}

/// Exact, simulated and small-angle periods of the undamped pendulum (the pendulum's C is
/// ignored) for each amplitude in (0, π). The simulation measures two full periods.
///
/// ```
/// use ltikit::nonlinear::{pendulum_periods, models::Pendulum};
/// use ltikit::numeric::rk45::Rk45Options;
/// let rows = pendulum_periods(&Pendulum::default(), &[0.5, 2.5], &Rk45Options::default()).unwrap();
/// assert!(rows[1].exact > rows[0].exact && rows[0].exact > rows[0].small_angle);
/// assert!(rows.iter().all(|r| r.relative_error < 1e-7));
/// ```
pub fn pendulum_periods(
    pendulum: &Pendulum,
    amplitudes: &[f64],
    opts: &Rk45Options,
) -> Result<Vec<PeriodPoint>> {
    let w = pendulum.omega();
    amplitudes
        .iter()
        .map(|&a| {
            let exact = pendulum_period_exact(w, a)?;
            let simulated = pendulum_period_simulated(pendulum, a, 4, opts)?;
            Ok(PeriodPoint {
                amplitude: a,
                exact,
                simulated,
                small_angle: 2.0 * std::f64::consts::PI / w,
                relative_error: (simulated - exact).abs() / exact,
            })
        })
        .collect()
}
