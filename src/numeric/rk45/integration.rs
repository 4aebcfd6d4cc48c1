//! The integration loop ([`integrate`]): steps, the controller, the observer, and how an
//! integration fails (see the [module docs](super)).

use serde::Serialize;

use super::dense::DenseStep;
use super::options::Rk45Options;
use super::stepper::{Controller, Stepper};
use crate::error::{LtiError, Result, check_finite};
use crate::numeric::tol::EPS;

/// A state component whose magnitude exceeds this counts as a blow-up.
pub const DIVERGENCE_LIMIT: f64 = 1e100;

/// Growth of ‖x‖∞ (relative to max(1, ‖x₀‖∞)) beyond which a collapse of the step size is
/// reported as a blow-up ([`LtiError::Diverged`]) rather than as an unresolvable right-hand side.
const BLOW_UP_GROWTH: f64 = 1e6;

/// Work done by one integration.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Rk45Stats {
    /// Accepted steps.
    pub steps: usize,
    /// Rejected step attempts.
    pub rejections: usize,
    /// Evaluations of the right-hand side f.
    pub evaluations: usize,
}

impl Rk45Stats {
    /// Adds another run's work (used when a simulation is restarted at an input jump).
    pub fn add(&mut self, other: &Rk45Stats) {
        self.steps += other.steps;
        self.rejections += other.rejections;
        self.evaluations += other.evaluations;
    }
}

/// What the observer of [`integrate`] wants after a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepControl {
    /// Keep integrating.
    Continue,
    /// Stop now (e.g. enough events were found).
    Stop,
}

/// Where an integration ended.
#[derive(Debug, Clone, PartialEq)]
pub struct Rk45Outcome {
    /// Time reached (`t_end`, or the end of the step at which the observer stopped).
    pub t: f64,
    /// State at that time.
    pub x: Vec<f64>,
    /// Work done.
    pub stats: Rk45Stats,
}

/// Integrates ẋ = f(t, x) from (t0, x0) to `t_end`, calling `observer` with every accepted
/// step and its dense output.
///
/// `f(t, x, dx)` writes the derivative into `dx` (same length as `x0`). The last step lands
/// exactly on `t_end`.
///
/// ```
/// use ltikit::numeric::rk45::{integrate, Rk45Options, StepControl};
/// // ẋ = −x: x(1) = e^{−1}.
/// let out = integrate(|_t, x, dx| dx[0] = -x[0], 0.0, &[1.0], 1.0,
///                     &Rk45Options::default(), |_| StepControl::Continue).unwrap();
/// assert!((out.x[0] - (-1.0f64).exp()).abs() < 1e-10);
/// assert_eq!(out.t, 1.0);
/// ```
pub fn integrate<F, O>(
    mut f: F,
    t0: f64,
    x0: &[f64],
    t_end: f64,
    opts: &Rk45Options,
    mut observer: O,
) -> Result<Rk45Outcome>
where
    F: FnMut(f64, &[f64], &mut [f64]),
    O: FnMut(&DenseStep<'_>) -> StepControl,
{
    check_inputs(t0, x0, t_end, opts)?;
    let n = x0.len();
    let mut stats = Rk45Stats::default();
    if n == 0 {
        // Nothing evolves: one trivial step covers the interval.
        observer(&DenseStep {
            t0,
            t1: t_end,
            h: t_end - t0,
            n: 0,
            coef: &[],
            x1: &[],
        });
        return Ok(Rk45Outcome {
            t: t_end,
            x: Vec::new(),
            stats,
        });
    }
    let mut t = t0;
    let mut y = x0.to_vec();
    let norm0 = inf_norm(x0).max(1.0);
    let hmax = opts.max_step.unwrap_or(f64::INFINITY).min(t_end - t0);
    let mut st = Stepper::new(n);
    f(t, &y, &mut st.k1);
    stats.evaluations += 1;
    if let Some(bad) = st.k1.iter().find(|v| !v.is_finite()) {
        return Err(LtiError::NonFinite {
            what: format!("the right-hand side at t = {t0} (initial state)"),
            value: *bad,
        });
    }
    let mut h = match opts.initial_step {
        Some(h) => h.min(hmax),
        None => {
            stats.evaluations += 1;
            st.initial_step(&mut f, t, &y, hmax, opts)
        }
    };
    let mut control = Controller::new();
    let mut last_norm = inf_norm(&y);
    loop {
        if stats.steps + stats.rejections >= opts.max_steps {
            return Err(LtiError::StepLimit {
                steps: stats.steps + stats.rejections,
                t,
            });
        }
        let last = t + 1.01 * h >= t_end;
        if last {
            h = t_end - t;
        }
        let hmin = 16.0 * EPS * t.abs().max(f64::MIN_POSITIVE);
        if h < hmin {
            return Err(step_collapse(t, h, last_norm, norm0));
        }
        let t_new = if last { t_end } else { t + h };
        st.stages(&mut f, t, &y, h, t_new);
        stats.evaluations += 6;
        let err = st.error_norm(&y, h, opts);
        if err > 1.0 {
            stats.rejections += 1;
            if !err.is_finite() {
                // Non-finite stage: retreat sharply.
                last_norm = last_norm.max(finite_norm(&st.ytmp));
            }
            h = control.reject(err, h);
            continue;
        }
        stats.steps += 1;
        let norm = inf_norm(&st.y1);
        if norm > DIVERGENCE_LIMIT {
            return Err(LtiError::Diverged { t: t_new, norm });
        }
        st.dense_coefficients(&y, h);
        let step = DenseStep {
            t0: t,
            t1: t_new,
            h,
            n,
            coef: &st.coef,
            x1: &st.y1,
        };
        let wanted = observer(&step);
        std::mem::swap(&mut st.k1, &mut st.k7); // FSAL
        std::mem::swap(&mut y, &mut st.y1);
        t = t_new;
        last_norm = norm;
        if wanted == StepControl::Stop || last {
            return Ok(Rk45Outcome { t, x: y, stats });
        }
        h = control.accept(err, h, hmax);
    }
}

/// Errors unless the options are valid, the times finite with t_end > t0, and x0 finite.
fn check_inputs(t0: f64, x0: &[f64], t_end: f64, opts: &Rk45Options) -> Result<()> {
    opts.validate()?;
    check_finite(|| "the start time".into(), t0)?;
    check_finite(|| "the end time".into(), t_end)?;
    if t_end <= t0 {
        return Err(LtiError::InvalidTime {
            value: t_end,
            reason: format!("the end time must be later than the start time {t0}"),
        });
    }
    for (i, &v) in x0.iter().enumerate() {
        check_finite(|| format!("component {} of the initial state", i + 1), v)?;
    }
    Ok(())
}

/// The error for a step size that fell below the minimum at time `t`.
fn step_collapse(t: f64, h: f64, norm: f64, norm0: f64) -> LtiError {
    if !norm.is_finite() || norm > BLOW_UP_GROWTH * norm0 {
        LtiError::Diverged { t, norm }
    } else {
        LtiError::Undefined {
            what: format!("the solution beyond t = {t}"),
            reason: format!(
                "the step size fell to {h:e}, below the minimum 16·eps·|t|: the right-hand side \
                 is discontinuous, not finite, or too stiff for an explicit method here"
            ),
        }
    }
}

fn inf_norm(x: &[f64]) -> f64 {
    x.iter().fold(
        0.0_f64,
        |m, v| if v.is_nan() { f64::NAN } else { m.max(v.abs()) },
    )
}

/// Largest finite magnitude in `x`, or ∞ when any entry is not finite.
fn finite_norm(x: &[f64]) -> f64 {
    if x.iter().all(|v| v.is_finite()) {
        inf_norm(x)
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::rk45::solve;

    #[test]
    fn order_of_accuracy_is_five() {
        // Fixed steps (tolerances loose, steps forced by max_step and initial_step): the
        // global error of ẋ = −x over [0, 1] falls by ~2⁵ when h halves.
        let run = |h: f64| {
            let opts = Rk45Options {
                rtol: 1e-2,
                atol: 1.0,
                initial_step: Some(h),
                max_step: Some(h),
                ..Default::default()
            };
            let out = integrate(
                |_t, x, dx| dx[0] = -x[0],
                0.0,
                &[1.0],
                1.0,
                &opts,
                |_| StepControl::Continue,
            )
            .unwrap();
            (out.x[0] - (-1.0f64).exp()).abs()
        };
        let e1 = run(0.1);
        let e2 = run(0.05);
        let ratio = e1 / e2;
        assert!(
            (28.0..36.0).contains(&ratio),
            "ratio {ratio}, errors {e1:e} {e2:e}"
        );
    }

    #[test]
    fn dense_output_is_fourth_order_accurate_inside_steps() {
        // One step of length h on ẋ = x; the interpolant at mid-step differs from e^{t} by
        // O(h⁵).
        let h = 0.1;
        let opts = Rk45Options {
            rtol: 1e-2,
            atol: 1.0,
            initial_step: Some(h),
            max_step: Some(h),
            ..Default::default()
        };
        let mut worst: f64 = 0.0;
        integrate(
            |_t, x, dx| dx[0] = x[0],
            0.0,
            &[1.0],
            h,
            &opts,
            |s| {
                for j in 1..10 {
                    let t = h * j as f64 / 10.0;
                    worst = worst.max((s.eval_component(t, 0) - t.exp()).abs());
                }
                StepControl::Continue
            },
        )
        .unwrap();
        assert!(worst < 1e-7 && worst > 0.0, "dense error {worst:e}");
    }

    #[test]
    fn options_are_validated() {
        let f = |_t: f64, x: &[f64], dx: &mut [f64]| dx[0] = x[0];
        for o in [
            Rk45Options {
                rtol: 0.0,
                ..Default::default()
            },
            Rk45Options {
                atol: f64::NAN,
                ..Default::default()
            },
            Rk45Options {
                max_steps: 0,
                ..Default::default()
            },
            Rk45Options {
                max_step: Some(-1.0),
                ..Default::default()
            },
        ] {
            assert!(integrate(f, 0.0, &[1.0], 1.0, &o, |_| StepControl::Continue).is_err());
        }
        let o = Rk45Options::default();
        assert!(matches!(
            integrate(f, 0.0, &[1.0], 0.0, &o, |_| StepControl::Continue),
            Err(LtiError::InvalidTime { .. })
        ));
        assert!(matches!(
            integrate(f, 0.0, &[f64::NAN], 1.0, &o, |_| StepControl::Continue),
            Err(LtiError::NonFinite { .. })
        ));
        assert!(solve(f, 0.0, &[1.0], 1.0, &[0.5, 0.2], &o).is_err());
        assert!(solve(f, 0.0, &[1.0], 1.0, &[2.0], &o).is_err());
    }

    #[test]
    fn empty_state_is_trivial() {
        let sol = solve(
            |_t, _x, _dx| {},
            0.0,
            &[],
            3.0,
            &[0.0, 1.5, 3.0],
            &Rk45Options::default(),
        )
        .unwrap();
        assert_eq!(sol.x, vec![Vec::<f64>::new(); 3]);
        assert_eq!(sol.stats.evaluations, 0);
    }

    #[test]
    fn observer_can_stop() {
        let out = integrate(
            |_t, _x, dx| dx[0] = 1.0,
            0.0,
            &[0.0],
            100.0,
            &Rk45Options {
                max_step: Some(1.0),
                ..Default::default()
            },
            |s| {
                if s.t_end() >= 5.0 {
                    StepControl::Stop
                } else {
                    StepControl::Continue
                }
            },
        )
        .unwrap();
        assert!(out.t >= 5.0 && out.t < 7.0);
        assert!((out.x[0] - out.t).abs() < 1e-12);
    }
}
