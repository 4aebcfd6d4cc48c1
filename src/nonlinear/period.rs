//! The period of the undamped pendulum against its amplitude (seed §2.3.1.1).
//!
//! θ̈ + ω² sin θ = 0 with ω² = 3g/(2L), released at rest from θ₀ ∈ (0, π): the period is
//! T = 4K(k)/ω with modulus k = sin(θ₀/2) and K the complete elliptic integral of the first
//! kind ([`elliptic_k`], from the arithmetic–geometric mean; see
//! [`crate::nonlinear::elliptic`]). The small-angle period is 2π/ω; T → ∞ as
//! θ₀ → π (the separatrix).
//!
//! The *measured* period comes from a simulation: the zero crossings of θ̇ (every half period)
//! located by Brent's method on the integrator's dense output.

use serde::Serialize;

use crate::error::{LtiError, Result, check_finite};
pub use crate::nonlinear::elliptic::{agm, elliptic_k};
use crate::nonlinear::models::Pendulum;
use crate::nonlinear::system::{DynSystem, check_point};
use crate::numeric::rk45::{Rk45Options, StepControl, integrate};
use crate::numeric::scalar::{Bracket, brent};

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
    // Horizon: the exact period times the number of half periods (twice what is needed).
    let t_max = pendulum_period_exact(p.omega(), theta0)? * half_periods as f64;
    let crossings = crossing_times(&p, &[theta0, 0.0], &[0.0], 1, half_periods, t_max, opts)?;
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

/// The first `count` times in (0, `t_max`] at which state component `component` changes sign
/// along the solution from x(0) = `x0` under the constant input `u`, located by Brent's method
/// on the integrator's dense output (to 1e-15 relative). A start exactly at zero is not a
/// crossing. Fewer than `count` are returned when `t_max` comes first.
///
/// ```
/// use ltikit::nonlinear::{period::crossing_times, models::VanDerPol};
/// use ltikit::numeric::rk45::Rk45Options;
/// // On the unit-circle limit cycle x₁ = cos t: crossings at π/2, 3π/2.
/// let opts = Rk45Options { rtol: 1e-12, atol: 1e-14, ..Default::default() };
/// let t = crossing_times(&VanDerPol, &[1.0, 0.0], &[], 0, 2, 10.0, &opts).unwrap();
/// assert!((t[0] - std::f64::consts::FRAC_PI_2).abs() < 1e-10);
/// assert!((t[1] - 1.5 * std::f64::consts::PI).abs() < 1e-10);
/// ```
pub fn crossing_times(
    sys: &dyn DynSystem,
    x0: &[f64],
    u: &[f64],
    component: usize,
    count: usize,
    t_max: f64,
    opts: &Rk45Options,
) -> Result<Vec<f64>> {
    check_point(sys, x0, u)?;
    if component >= sys.nx() {
        return Err(LtiError::invalid(format!(
            "state component {component} does not exist (the model has {} states)",
            sys.nx()
        )));
    }
    let mut crossings: Vec<f64> = Vec::with_capacity(count);
    if count == 0 {
        return Ok(crossings);
    }
    let mut failure: Option<LtiError> = None;
    integrate(
        |_t, x, dx| sys.eval_f(x, u, dx),
        0.0,
        x0,
        t_max,
        opts,
        |step| {
            let (ta, tb) = (step.t_start(), step.t_end());
            let fa = step.state_start()[component];
            let fb = step.state_end()[component];
            let strict = fa != 0.0 && fb != 0.0 && (fa < 0.0) != (fb < 0.0);
            let at_end = fb == 0.0 && tb > 0.0;
            if strict {
                match brent(
                    |t| step.eval_component(t, component),
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
            if crossings.len() >= count {
                StepControl::Stop
            } else {
                StepControl::Continue
            }
        },
    )?;
    if let Some(e) = failure {
        return Err(e);
    }
    Ok(crossings)
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
