//! Data for phase portraits and for the sensitivity of chaotic trajectories (the plots only
//! read these structs).

use serde::Serialize;

use crate::error::{LtiError, Result};
use crate::nonlinear::models::{Lorenz, Pendulum};
use crate::nonlinear::signal::InputSignal;
use crate::nonlinear::simulate::{Simulation, simulate};
use crate::nonlinear::system::DynSystem;
use crate::numeric::rk45::Rk45Options;

/// Simulates one trajectory per start (same input and times) — the curves of a phase portrait.
///
/// ```
/// use ltikit::nonlinear::{trajectories, sample_times, InputSignal, models::VanDerPol};
/// use ltikit::numeric::rk45::Rk45Options;
/// let t = sample_times(10.0, 101).unwrap();
/// let starts = vec![vec![0.01, 0.0], vec![2.0, 0.0]];
/// let tr = trajectories(&VanDerPol, &starts, &InputSignal::none(), &t, &Rk45Options::default()).unwrap();
/// assert_eq!(tr.len(), 2);
/// ```
pub fn trajectories(
    sys: &dyn DynSystem,
    starts: &[Vec<f64>],
    input: &InputSignal,
    times: &[f64],
    opts: &Rk45Options,
) -> Result<Vec<Simulation>> {
    if starts.is_empty() {
        return Err(LtiError::invalid("no starting points given"));
    }
    starts
        .iter()
        .map(|x0| simulate(sys, x0, input, times, opts))
        .collect()
}

/// The energy ½θ̇² + 2ω² sin²(θ/2) of the undamped pendulum (seed eq. 2.20).
pub fn pendulum_energy(omega: f64, theta: f64, theta_dot: f64) -> f64 {
    0.5 * theta_dot * theta_dot + 2.0 * omega * omega * (theta / 2.0).sin().powi(2)
}

/// The separatrices of the undamped pendulum (C = 0): the level set of the upright
/// equilibrium's energy 2ω², θ̇ = ±2ω|cos(θ/2)|, sampled at `points` angles in
/// [`theta_min`, `theta_max`]. Returns the upper and the lower curve as (θ, θ̇) points.
///
/// ```
/// use ltikit::nonlinear::{pendulum_separatrices, pendulum_energy, models::Pendulum};
/// let p = Pendulum::default();
/// let [upper, lower] = pendulum_separatrices(&p, -3.0, 3.0, 61).unwrap();
/// let w = p.omega();
/// for q in upper.iter().chain(&lower) {
///     assert!((pendulum_energy(w, q[0], q[1]) - 2.0 * w * w).abs() < 1e-12);
/// }
/// ```
pub fn pendulum_separatrices(
    pendulum: &Pendulum,
    theta_min: f64,
    theta_max: f64,
    points: usize,
) -> Result<[Vec<[f64; 2]>; 2]> {
    if !(theta_min.is_finite() && theta_max.is_finite() && theta_min < theta_max) {
        return Err(LtiError::invalid(format!(
            "the angle range [{theta_min}, {theta_max}] must be finite and increasing"
        )));
    }
    if points < 2 {
        return Err(LtiError::invalid("at least 2 points are needed"));
    }
    let w = pendulum.omega();
    let last = (points - 1) as f64;
    let upper: Vec<[f64; 2]> = (0..points)
        .map(|k| {
            let th = theta_min + (theta_max - theta_min) * k as f64 / last;
            [th, 2.0 * w * (th / 2.0).cos().abs()]
        })
        .collect();
    let lower = upper.iter().map(|p| [p[0], -p[1]]).collect();
    Ok([upper, lower])
}

/// Two trajectories from nearby starts and their distance (seed fig. 2.10).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Divergence {
    /// The first trajectory.
    pub a: Simulation,
    /// The second trajectory.
    pub b: Simulation,
    /// Euclidean distance of the states at each sample time.
    pub distance: Vec<f64>,
}

impl Divergence {
    /// The first sample time at which the distance exceeds `threshold`.
    pub fn separation_time(&self, threshold: f64) -> Option<f64> {
        self.a
            .t
            .iter()
            .zip(&self.distance)
            .find(|(_, d)| **d > threshold)
            .map(|(t, _)| *t)
    }
}

/// Simulates from `x0a` and `x0b` and records how far apart the trajectories get.
pub fn divergence(
    sys: &dyn DynSystem,
    x0a: &[f64],
    x0b: &[f64],
    input: &InputSignal,
    times: &[f64],
    opts: &Rk45Options,
) -> Result<Divergence> {
    let a = simulate(sys, x0a, input, times, opts)?;
    let b = simulate(sys, x0b, input, times, opts)?;
    let distance = a
        .states
        .iter()
        .zip(&b.states)
        .map(|(p, q)| {
            p.iter()
                .zip(q)
                .map(|(x, y)| (x - y) * (x - y))
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    Ok(Divergence { a, b, distance })
}

/// The Lorenz trajectories from [1, 0, 0] and [1 + `delta`, 0, 0] (seed figs. 2.9–2.10 use
/// delta = 0.001).
///
/// ```
/// use ltikit::nonlinear::{lorenz_divergence, sample_times, models::Lorenz};
/// use ltikit::numeric::rk45::Rk45Options;
/// let t = sample_times(30.0, 3001).unwrap();
/// let d = lorenz_divergence(&Lorenz::default(), 1e-3, &t, &Rk45Options::default()).unwrap();
/// let ts = d.separation_time(1.0).unwrap();
/// assert!(ts > 5.0 && ts < 30.0);
/// ```
pub fn lorenz_divergence(
    lorenz: &Lorenz,
    delta: f64,
    times: &[f64],
    opts: &Rk45Options,
) -> Result<Divergence> {
    divergence(
        lorenz,
        &[1.0, 0.0, 0.0],
        &[1.0 + delta, 0.0, 0.0],
        &InputSignal::none(),
        times,
        opts,
    )
}
