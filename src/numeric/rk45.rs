//! Adaptive Dormand–Prince 5(4) integrator with dense output (MATLAB's `ode45`).
//!
//! # Method
//! The explicit Runge–Kutta pair of Dormand and Prince (1980), seven stages with the FSAL
//! property (the last stage of an accepted step is the first of the next, so a step costs six
//! evaluations of f), local extrapolation (the 5th-order solution is propagated, the embedded
//! 4th-order one only estimates the error), and the step-size controller of Hairer–Nørsett–
//! Wanner's `DOPRI5` (error in the root-mean-square norm scaled by `atol + rtol·|x|`, safety
//! factor 0.9, growth limited to ×10 and shrinkage to ×0.2 per step, Lund stabilisation
//! β = 0.04, no growth right after a rejection).
//!
//! **Dense output** is Hairer's 4th-order continuous extension of the same step (coefficients
//! `d₁ … d₇`, no extra evaluations of f): between the mesh points the solution is a quartic in
//! θ = (t − tₙ)/h that matches xₙ, xₙ₊₁ and both derivatives. Requested sample times are
//! interpolated, so they never shorten the steps — this is how `ode45` fills its `tspan`
//! (python-control and scipy do the same). Use [`integrate`] with an observer for events (zero
//! crossings are found by Brent's method on the interpolant).
//!
//! # Failure modes (errors, never panics)
//! - the state leaves the finite numbers or exceeds [`DIVERGENCE_LIMIT`] in magnitude →
//!   [`LtiError::Diverged`] with the time and the size reached;
//! - the step size falls below 16·eps·|t| (MATLAB's minimum): at a finite-time singularity
//!   (ẋ = x² from x(0) = 1 blows up at t = 1) the state has grown by orders of magnitude and
//!   this is reported as [`LtiError::Diverged`]; otherwise (a discontinuous or non-finite right
//!   hand side) as [`LtiError::Undefined`];
//! - more than `max_steps` attempted steps → [`LtiError::StepLimit`];
//! - bad options, non-finite initial state, `t_end ≤ t0` → `InvalidParameter`, `NonFinite`,
//!   `InvalidTime`.

use serde::Serialize;

use crate::error::{LtiError, Result, check_finite};
use crate::numeric::tol::EPS;

/// A state component whose magnitude exceeds this counts as a blow-up.
pub const DIVERGENCE_LIMIT: f64 = 1e100;

/// Growth of ‖x‖∞ (relative to max(1, ‖x₀‖∞)) beyond which a collapse of the step size is
/// reported as a blow-up ([`LtiError::Diverged`]) rather than as an unresolvable right-hand side.
const BLOW_UP_GROWTH: f64 = 1e6;

/// Smallest relative tolerance accepted (100·eps, as MATLAB's `ode45` clamps it).
pub const MIN_RTOL: f64 = 100.0 * EPS;

// Dormand–Prince 5(4) tableau.
const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
// Error estimate: 5th-order minus embedded 4th-order weights.
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
// Dense output (Hairer, DOPRI5 `contd5`).
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

// Step-size controller (DOPRI5 defaults).
const SAFETY: f64 = 0.9;
const FAC_MIN: f64 = 0.2; // smallest ratio h_new / h
const FAC_MAX: f64 = 10.0; // largest ratio h_new / h
const BETA: f64 = 0.04;
const EXPO1: f64 = 0.2 - BETA * 0.75;

/// Options of the integrator (`odeset` in MATLAB). Build with `..Default::default()`.
///
/// ```
/// use ltikit::numeric::rk45::Rk45Options;
/// let o = Rk45Options { rtol: 1e-6, ..Default::default() };
/// assert!(o.validate().is_ok());
/// assert!(Rk45Options { rtol: -1.0, ..o }.validate().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Rk45Options {
    /// Relative tolerance (default 1e-9; at least [`MIN_RTOL`]).
    pub rtol: f64,
    /// Absolute tolerance (default 1e-12; ≥ 0).
    pub atol: f64,
    /// Maximum number of attempted steps, accepted plus rejected (default 1 000 000).
    pub max_steps: usize,
    /// First step size; `None` chooses it from the derivatives (Hairer's `hinit`).
    pub initial_step: Option<f64>,
    /// Largest step size; `None` means unlimited.
    pub max_step: Option<f64>,
}

impl Default for Rk45Options {
    fn default() -> Self {
        Rk45Options {
            rtol: 1e-9,
            atol: 1e-12,
            max_steps: 1_000_000,
            initial_step: None,
            max_step: None,
        }
    }
}

impl Rk45Options {
    /// Checks every option, naming the first bad one.
    pub fn validate(&self) -> Result<()> {
        let bad = |name: &str, value: f64, reason: &str| {
            Err(LtiError::InvalidParameter {
                name: name.into(),
                value,
                reason: reason.into(),
            })
        };
        if !(self.rtol.is_finite() && self.rtol >= MIN_RTOL && self.rtol < 1.0) {
            return bad(
                "rtol",
                self.rtol,
                "the relative tolerance must lie in [2.2e-14, 1)",
            );
        }
        if !(self.atol.is_finite() && self.atol >= 0.0) {
            return bad(
                "atol",
                self.atol,
                "the absolute tolerance must be finite and ≥ 0",
            );
        }
        if self.max_steps == 0 {
            return bad("max_steps", 0.0, "at least one step must be allowed");
        }
        if let Some(h) = self.initial_step.filter(|h| !(h.is_finite() && *h > 0.0)) {
            return bad("initial_step", h, "the initial step must be finite and > 0");
        }
        if let Some(h) = self.max_step.filter(|h| !(h.is_finite() && *h > 0.0)) {
            return bad("max_step", h, "the maximum step must be finite and > 0");
        }
        Ok(())
    }
}

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

/// One accepted step [t₀, t₁] with its continuous extension, handed to the observer of
/// [`integrate`].
#[derive(Debug, Clone, Copy)]
pub struct DenseStep<'a> {
    t0: f64,
    t1: f64,
    h: f64,
    n: usize,
    /// Five blocks of n coefficients of the quartic interpolant.
    coef: &'a [f64],
    x1: &'a [f64],
}

impl DenseStep<'_> {
    /// Start of the step.
    pub fn t_start(&self) -> f64 {
        self.t0
    }

    /// End of the step.
    pub fn t_end(&self) -> f64 {
        self.t1
    }

    /// State at the start of the step.
    pub fn state_start(&self) -> &[f64] {
        &self.coef[..self.n]
    }

    /// State at the end of the step (the propagated 5th-order solution).
    pub fn state_end(&self) -> &[f64] {
        self.x1
    }

    fn theta(&self, t: f64) -> f64 {
        (t - self.t0) / self.h
    }

    /// Component `i` of the interpolated state at `t` (meant for t in the step; outside it the
    /// quartic is extrapolated). Panics if `i` is out of range, like slice indexing.
    pub fn eval_component(&self, t: f64, i: usize) -> f64 {
        let n = self.n;
        let th = self.theta(t);
        let th1 = 1.0 - th;
        let c = self.coef;
        c[i] + th * (c[n + i] + th1 * (c[2 * n + i] + th * (c[3 * n + i] + th1 * c[4 * n + i])))
    }

    /// The interpolated state at `t`, written into `out` (length = state dimension).
    pub fn eval(&self, t: f64, out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate().take(self.n) {
            *o = self.eval_component(t, i);
        }
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

    let mut k1 = vec![0.0; n];
    let mut k2 = vec![0.0; n];
    let mut k3 = vec![0.0; n];
    let mut k4 = vec![0.0; n];
    let mut k5 = vec![0.0; n];
    let mut k6 = vec![0.0; n];
    let mut k7 = vec![0.0; n];
    let mut ytmp = vec![0.0; n];
    let mut y1 = vec![0.0; n];
    let mut coef = vec![0.0; 5 * n];

    f(t, &y, &mut k1);
    stats.evaluations += 1;
    if let Some(bad) = k1.iter().find(|v| !v.is_finite()) {
        return Err(LtiError::NonFinite {
            what: format!("the right-hand side at t = {t0} (initial state)"),
            value: *bad,
        });
    }

    let mut h = match opts.initial_step {
        Some(h) => h.min(hmax),
        None => initial_step(&mut f, t, &y, &k1, hmax, opts, &mut ytmp, &mut k2),
    };
    if opts.initial_step.is_none() {
        stats.evaluations += 1;
    }
    let mut facold: f64 = 1e-4;
    let mut rejected_last = false;
    let mut last_norm = inf_norm(&y);

    loop {
        if stats.steps + stats.rejections >= opts.max_steps {
            return Err(LtiError::StepLimit {
                steps: stats.steps + stats.rejections,
                t,
            });
        }
        let mut last = false;
        if t + 1.01 * h >= t_end {
            h = t_end - t;
            last = true;
        }
        let hmin = 16.0 * EPS * t.abs().max(f64::MIN_POSITIVE);
        if h < hmin {
            return Err(step_collapse(t, h, last_norm, norm0));
        }

        // Stages 2–7.
        for i in 0..n {
            ytmp[i] = y[i] + h * A21 * k1[i];
        }
        f(t + C2 * h, &ytmp, &mut k2);
        for i in 0..n {
            ytmp[i] = y[i] + h * (A31 * k1[i] + A32 * k2[i]);
        }
        f(t + C3 * h, &ytmp, &mut k3);
        for i in 0..n {
            ytmp[i] = y[i] + h * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i]);
        }
        f(t + C4 * h, &ytmp, &mut k4);
        for i in 0..n {
            ytmp[i] = y[i] + h * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i]);
        }
        f(t + C5 * h, &ytmp, &mut k5);
        for i in 0..n {
            ytmp[i] =
                y[i] + h * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i] + A65 * k5[i]);
        }
        let t_new = if last { t_end } else { t + h };
        f(t_new, &ytmp, &mut k6);
        for i in 0..n {
            y1[i] =
                y[i] + h * (A71 * k1[i] + A73 * k3[i] + A74 * k4[i] + A75 * k5[i] + A76 * k6[i]);
        }
        f(t_new, &y1, &mut k7);
        stats.evaluations += 6;

        // Error estimate in the scaled RMS norm.
        let mut err = 0.0;
        for i in 0..n {
            let e =
                h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]);
            let sk = opts.atol + opts.rtol * y[i].abs().max(y1[i].abs());
            err += if sk > 0.0 {
                (e / sk) * (e / sk)
            } else if e == 0.0 {
                0.0
            } else {
                f64::INFINITY
            };
        }
        let err = if n > 0 { (err / n as f64).sqrt() } else { 0.0 };
        let y1_finite = y1.iter().all(|v| v.is_finite()) && k7.iter().all(|v| v.is_finite());

        if !(err.is_finite() && y1_finite) {
            // Non-finite stage: retreat sharply.
            stats.rejections += 1;
            rejected_last = true;
            last_norm = last_norm.max(finite_norm(&ytmp));
            h *= FAC_MIN;
            continue;
        }

        let fac11 = err.powf(EXPO1);
        if err <= 1.0 {
            // Accept.
            stats.steps += 1;
            let norm = inf_norm(&y1);
            if norm > DIVERGENCE_LIMIT {
                return Err(LtiError::Diverged { t: t_new, norm });
            }
            for i in 0..n {
                let ydiff = y1[i] - y[i];
                let bspl = h * k1[i] - ydiff;
                coef[i] = y[i];
                coef[n + i] = ydiff;
                coef[2 * n + i] = bspl;
                coef[3 * n + i] = ydiff - h * k7[i] - bspl;
                coef[4 * n + i] = h
                    * (D1 * k1[i] + D3 * k3[i] + D4 * k4[i] + D5 * k5[i] + D6 * k6[i] + D7 * k7[i]);
            }
            let step = DenseStep {
                t0: t,
                t1: t_new,
                h,
                n,
                coef: &coef,
                x1: &y1,
            };
            let control = observer(&step);
            std::mem::swap(&mut k1, &mut k7); // FSAL
            std::mem::swap(&mut y, &mut y1);
            t = t_new;
            last_norm = norm;
            if control == StepControl::Stop || last {
                return Ok(Rk45Outcome { t, x: y, stats });
            }
            let fac = (fac11 / facold.powf(BETA) / SAFETY).clamp(1.0 / FAC_MAX, 1.0 / FAC_MIN);
            let mut h_new = (h / fac).min(hmax);
            if rejected_last {
                h_new = h_new.min(h);
            }
            facold = err.max(1e-4);
            rejected_last = false;
            h = h_new;
        } else {
            stats.rejections += 1;
            rejected_last = true;
            h /= (fac11 / SAFETY).min(1.0 / FAC_MIN);
        }
    }
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

/// Hairer's starting step: h such that an explicit Euler step changes x by about 1 % of the
/// tolerance scale, refined with an estimate of the second derivative (one extra evaluation).
#[allow(clippy::too_many_arguments)]
fn initial_step<F>(
    f: &mut F,
    t: f64,
    y: &[f64],
    f0: &[f64],
    hmax: f64,
    opts: &Rk45Options,
    y1: &mut [f64],
    f1: &mut [f64],
) -> f64
where
    F: FnMut(f64, &[f64], &mut [f64]),
{
    let n = y.len();
    let sk: Vec<f64> = y
        .iter()
        .map(|v| (opts.atol + opts.rtol * v.abs()).max(f64::MIN_POSITIVE))
        .collect();
    let dnf: f64 = (0..n).map(|i| (f0[i] / sk[i]).powi(2)).sum();
    let dny: f64 = (0..n).map(|i| (y[i] / sk[i]).powi(2)).sum();
    let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
        1e-6
    } else {
        (dny / dnf).sqrt() * 0.01
    };
    h = h.min(hmax);
    for i in 0..n {
        y1[i] = y[i] + h * f0[i];
    }
    f(t + h, y1, f1);
    let der2: f64 = (0..n)
        .map(|i| ((f1[i] - f0[i]) / sk[i]).powi(2))
        .sum::<f64>()
        .sqrt()
        / h;
    let der12 = der2.max(dnf.sqrt());
    let h1 = if !der12.is_finite() {
        1e-6 * h
    } else if der12 <= 1e-15 {
        (h * 1e-3).max(1e-6)
    } else {
        (0.01 / der12).powf(0.2)
    };
    (100.0 * h).min(h1).min(hmax)
}

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

#[cfg(test)]
mod tests {
    use super::*;

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
