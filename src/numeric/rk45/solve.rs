//! Integration sampled at requested times, from the dense output.

use super::integration::{Rk45Stats, StepControl, integrate};
use super::options::Rk45Options;
use crate::error::{LtiError, Result, check_finite};

/// A solution sampled at requested times.
#[derive(Debug, Clone, PartialEq)]
pub struct Rk45Solution {
    /// The sample times as requested.
    pub t: Vec<f64>,
    /// The state at each sample time (dense output).
    pub x: Vec<Vec<f64>>,
    /// The state at `t_end` (a mesh point, not interpolated).
    pub x_end: Vec<f64>,
    /// Work done.
    pub stats: Rk45Stats,
}

/// Integrates ẋ = f(t, x) from (t0, x0) to `t_end` and returns the state at each of `times`
/// (non-decreasing, within [t0, t_end]) from the dense output.
///
/// ```
/// use ltikit::numeric::rk45::{solve, Rk45Options};
/// // Harmonic oscillator: x = (cos t, −sin t).
/// let times: Vec<f64> = (0..=10).map(|k| k as f64).collect();
/// let opts = Rk45Options { rtol: 1e-12, atol: 1e-14, ..Default::default() };
/// let sol = solve(|_t, x, dx| { dx[0] = x[1]; dx[1] = -x[0]; }, 0.0, &[1.0, 0.0], 10.0,
///                 &times, &opts).unwrap();
/// for (t, x) in sol.t.iter().zip(&sol.x) {
///     assert!((x[0] - t.cos()).abs() < 1e-10);
/// }
/// ```
pub fn solve<F>(
    f: F,
    t0: f64,
    x0: &[f64],
    t_end: f64,
    times: &[f64],
    opts: &Rk45Options,
) -> Result<Rk45Solution>
where
    F: FnMut(f64, &[f64], &mut [f64]),
{
    check_sample_times(times, t0, t_end)?;
    let n = x0.len();
    let mut out: Vec<Vec<f64>> = Vec::with_capacity(times.len());
    let mut next = 0;
    let outcome = integrate(f, t0, x0, t_end, opts, |step| {
        while next < times.len() && times[next] <= step.t_end() {
            let mut x = vec![0.0; n];
            let ts = times[next];
            if ts >= step.t_end() {
                // ok: a mesh point, no interpolation error
                x.copy_from_slice(step.state_end());
            } else if ts <= step.t_start() {
                x.copy_from_slice(step.state_start());
            } else {
                step.eval(ts, &mut x);
            }
            out.push(x);
            next += 1;
        }
        StepControl::Continue
    })?;
    Ok(Rk45Solution {
        t: times.to_vec(),
        x: out,
        x_end: outcome.x,
        stats: outcome.stats,
    })
}

/// Checks that sample times are finite, non-decreasing and inside [t0, t_end].
pub fn check_sample_times(times: &[f64], t0: f64, t_end: f64) -> Result<()> {
    let mut prev = t0;
    for (k, &t) in times.iter().enumerate() {
        check_finite(|| format!("sample time {}", k + 1), t)?;
        if t < prev {
            return Err(LtiError::InvalidTime {
                value: t,
                reason: if k == 0 {
                    format!("sample times must not precede the start time {t0}")
                } else {
                    format!("sample times must be non-decreasing (previous {prev})")
                },
            });
        }
        if t > t_end {
            return Err(LtiError::InvalidTime {
                value: t,
                reason: format!("sample times must not exceed the end time {t_end}"),
            });
        }
        prev = t;
    }
    Ok(())
}
