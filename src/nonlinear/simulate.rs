//! Simulation of a model with the adaptive Dormand–Prince integrator
//! ([`crate::numeric::rk45`]) under an [`InputSignal`] (constant, step, ramp, exponential,
//! sine or cosine), outputs at requested times from the dense output.
//!
//! An input that starts at t₀ > 0 is handled by stopping exactly at t₀ and restarting from the
//! state reached there: the right-hand side may jump in t, and stepping across the jump would
//! make the controller reject steps until it has located it.

use serde::Serialize;

use super::signal::InputSignal;
use crate::error::{LtiError, Result, check_finite};
use crate::nonlinear::system::{DynSystem, SystemInfo, check_point};
use crate::numeric::rk45::{
    DenseStep, Rk45Options, Rk45Stats, StepControl, check_sample_times, integrate,
};

/// A simulated trajectory.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Simulation {
    /// Model name.
    pub model: String,
    /// State names.
    pub state_names: Vec<String>,
    /// Output names.
    pub output_names: Vec<String>,
    /// Sample times.
    pub t: Vec<f64>,
    /// State at each sample time.
    pub states: Vec<Vec<f64>>,
    /// Output y = h(x, u(t)) at each sample time.
    pub outputs: Vec<Vec<f64>>,
    /// Integrator work.
    pub stats: Rk45Stats,
    /// Set when the simulation ended before the last requested time.
    pub stop: Option<SimulationStop>,
    /// The drift of each conserved quantity ([`SystemInfo::conserved_names`]) over the
    /// integrator's steps — only for zero input, the condition under which they are
    /// conserved; empty otherwise.
    pub conserved: Vec<ConservedDrift>,
}

/// How far a conserved quantity drifted along a simulation: the integrator's error, since the
/// exact solution keeps it constant.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ConservedDrift {
    /// Its name.
    pub name: String,
    /// Its value at t = 0.
    pub initial: f64,
    /// max |Q(tₖ) − Q(0)| over the integrator's steps tₖ.
    pub max_drift: f64,
    /// The reference magnitude: max(|Q(0)|, the model's natural scale of Q,
    /// [`SystemInfo::conserved_scales`]).
    pub reference: f64,
    /// `max_drift / reference` (`max_drift` itself when the reference is 0).
    pub relative_drift: f64,
}

/// The integration segments [ta, tb] and whether u varies on them: one segment, or two when
/// the input changes at a start time inside (0, t_end) (the right-hand side jumps there, and
/// stepping across the jump would make the controller reject steps until it has located it).
fn segments(input: &InputSignal, t_end: f64) -> Vec<(f64, f64, bool)> {
    if input.is_constant() || input.start >= t_end {
        vec![(0.0, t_end, false)]
    } else if input.start > 0.0 {
        vec![(0.0, input.start, false), (input.start, t_end, true)]
    } else {
        vec![(0.0, t_end, true)]
    }
}

/// Why and when a simulation ended early.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SimulationStop {
    /// Time of the stop (the last sample).
    pub t: f64,
    /// Why.
    pub reason: String,
}

impl Simulation {
    /// The time series of state component `i`.
    pub fn state(&self, i: usize) -> Vec<f64> {
        self.states.iter().map(|x| x[i]).collect()
    }

    /// The time series of output component `i`.
    pub fn output(&self, i: usize) -> Vec<f64> {
        self.outputs.iter().map(|y| y[i]).collect()
    }
}

/// `points` equally spaced times from 0 to `t_end` (both included); `t_end` must be > 0 and
/// 2 ≤ `points` ≤ [`crate::limits::MAX_POINTS`] (checked before anything is allocated).
///
/// ```
/// let t = ltikit::nonlinear::sample_times(2.0, 5).unwrap();
/// assert_eq!(t, vec![0.0, 0.5, 1.0, 1.5, 2.0]);
/// assert!(ltikit::nonlinear::sample_times(0.0, 5).is_err());
/// assert!(ltikit::nonlinear::sample_times(1.0, usize::MAX).is_err());
/// ```
pub fn sample_times(t_end: f64, points: usize) -> Result<Vec<f64>> {
    check_finite(|| "the end time".into(), t_end)?;
    if t_end <= 0.0 {
        return Err(LtiError::InvalidTime {
            value: t_end,
            reason: "the end time must be > 0".into(),
        });
    }
    if points < 2 {
        return Err(LtiError::invalid(format!(
            "`points`: at least 2 sample points are needed, got {points}"
        )));
    }
    crate::limits::POINTS.check_usize("`points`", points)?;
    let last = (points - 1) as f64;
    let mut t: Vec<f64> = (0..points).map(|k| t_end * k as f64 / last).collect();
    t[points - 1] = t_end;
    Ok(t)
}

/// Simulates `sys` from x(0) = `x0` under `input`, returning states and outputs at `times`
/// (non-decreasing, starting at ≥ 0; the last one is the end time and must be > 0).
///
/// If x0 is in the model's domain ([`SystemInfo::in_domain`]) and the trajectory leaves it,
/// the simulation stops there: the samples end with the last state inside the domain (located
/// by bisection on the dense output to ~1e-14 s) and [`Simulation::stop`] says when and why.
/// [`simulate_each`] hands the samples over one by one instead of keeping them.
///
/// Errors besides the integrator's: more kept values (samples × (1 + states + outputs)) than
/// [`crate::limits::MAX_SIMULATION_VALUES`], checked before anything is allocated.
///
/// ```
/// use ltikit::nonlinear::{simulate, sample_times, InputSignal, models::VanDerPol};
/// use ltikit::numeric::rk45::Rk45Options;
/// let t = sample_times(20.0, 201).unwrap();
/// let sim = simulate(&VanDerPol, &[0.1, 0.0], &InputSignal::none(), &t, &Rk45Options::default()).unwrap();
/// let end = sim.states.last().unwrap();
/// assert!((end[0].hypot(end[1]) - 1.0).abs() < 1e-6); // on the unit-circle limit cycle
/// ```
pub fn simulate(
    sys: &dyn DynSystem,
    x0: &[f64],
    input: &InputSignal,
    times: &[f64],
    opts: &Rk45Options,
) -> Result<Simulation> {
    check_kept_values(sys, times.len())?;
    let mut t_out: Vec<f64> = Vec::with_capacity(times.len());
    let mut states: Vec<Vec<f64>> = Vec::with_capacity(times.len());
    let mut outputs: Vec<Vec<f64>> = Vec::with_capacity(times.len());
    let s = simulate_each(sys, x0, input, times, opts, &mut |t, x, y| {
        t_out.push(t);
        states.push(x.to_vec());
        outputs.push(y.to_vec());
        Ok(true)
    })?;
    Ok(Simulation {
        model: s.model,
        state_names: s.state_names,
        output_names: s.output_names,
        t: t_out,
        states,
        outputs,
        stats: s.stats,
        stop: s.stop,
        conserved: s.conserved,
    })
}

/// Checks that keeping `samples` samples of `sys` (time, state and output: 1 + nx + ny values
/// each) stays within [`crate::limits::MAX_SIMULATION_VALUES`].
///
/// ```
/// use ltikit::nonlinear::{check_kept_values, models::VanDerPol};
/// assert!(check_kept_values(&VanDerPol, 1000).is_ok());
/// let e = check_kept_values(&VanDerPol, 10_000_000).unwrap_err().to_string();
/// assert!(e.starts_with("`points` × 5 values per sample: 50000000 exceeds"), "{e}");
/// ```
pub fn check_kept_values(sys: &dyn DynSystem, samples: usize) -> Result<()> {
    let per_sample = 1 + sys.nx() + sys.ny();
    crate::limits::SIMULATION_VALUES.check(
        &format!("`points` × {per_sample} values per sample"),
        samples as u128 * per_sample as u128,
    )?;
    Ok(())
}

/// What a simulation reports besides its samples ([`simulate_each`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SimulationSummary {
    /// Model name.
    pub model: String,
    /// State names.
    pub state_names: Vec<String>,
    /// Output names.
    pub output_names: Vec<String>,
    /// Samples handed over.
    pub samples: usize,
    /// Integrator work.
    pub stats: Rk45Stats,
    /// Set when the simulation ended before the last requested time.
    pub stop: Option<SimulationStop>,
    /// The drift of each conserved quantity (see [`Simulation::conserved`]).
    pub conserved: Vec<ConservedDrift>,
    /// The sink asked to stop (e.g. the reader of the output has gone).
    pub ended_by_sink: bool,
}

/// One sample handed over by [`simulate_each`]: time, state, output. `Ok(false)` stops the
/// simulation (the samples so far stand); an error ends it with that error.
pub type SampleSink<'a> = dyn FnMut(f64, &[f64], &[f64]) -> Result<bool> + 'a;

/// [`simulate`] without keeping the samples: each one goes to `sink` as soon as it is
/// computed, so memory does not grow with the number of samples (the CLI streams CSV this
/// way).
///
/// ```
/// use ltikit::nonlinear::{simulate_each, sample_times, InputSignal, models::VanDerPol};
/// use ltikit::numeric::rk45::Rk45Options;
/// let t = sample_times(20.0, 2001).unwrap();
/// let mut last = vec![];
/// let s = simulate_each(&VanDerPol, &[0.1, 0.0], &InputSignal::none(), &t,
///     &Rk45Options::default(), &mut |_, x, _| { last = x.to_vec(); Ok(true) }).unwrap();
/// assert_eq!(s.samples, 2001);
/// assert!((last[0].hypot(last[1]) - 1.0).abs() < 1e-6); // on the unit-circle limit cycle
/// ```
pub fn simulate_each(
    sys: &dyn DynSystem,
    x0: &[f64],
    input: &InputSignal,
    times: &[f64],
    opts: &Rk45Options,
    sink: &mut SampleSink<'_>,
) -> Result<SimulationSummary> {
    crate::limits::SIMULATION_STEPS.check_usize("`max_steps`", opts.max_steps)?;
    let check_domain = check_start(sys, x0, input, times)?;
    let Some(&t_end) = times.last() else {
        return Err(LtiError::invalid("no sample times given"));
    };
    let segments = segments(input, t_end);
    let mut tracker = DriftTracker::new(sys, x0, input);
    let mut out = Emit {
        sys,
        input,
        sink,
        y: vec![0.0; sys.ny()],
        last_t: None,
        count: 0,
        error: None,
        ended: false,
    };
    let mut stats = Rk45Stats::default();
    let mut stop: Option<SimulationStop> = None;
    let mut x = x0.to_vec();
    let mut next = 0;
    let nseg = segments.len();
    let n = sys.nx();
    let mut u = vec![0.0; sys.nu()];
    let mut xs = vec![0.0; n];
    let mut buf = vec![0.0; n];
    for (k, &(ta, tb, varying)) in segments.iter().enumerate() {
        // Samples in [ta, tb] (the last segment takes everything left).
        let seg_end = if k + 1 == nseg {
            times.len()
        } else {
            next + times[next..].iter().take_while(|&&t| t <= tb).count()
        };
        let outcome = integrate(
            |t, xv: &[f64], dx: &mut [f64]| {
                // A segment before the start holds `before` up to its end (the jump belongs
                // to the next segment).
                input.eval(if varying { t.max(ta) } else { ta }, &mut u);
                sys.eval_f(xv, &u, dx)
            },
            ta,
            &x,
            tb,
            opts,
            |step| {
                tracker.observe(sys, step.state_end());
                let cut = (check_domain && !sys.in_domain(step.state_end()))
                    .then(|| leave_time(sys, step, &mut buf));
                let limit = cut.unwrap_or(step.t_end());
                while next < seg_end && times[next] <= limit {
                    let ts = times[next];
                    if ts >= step.t_end() {
                        xs.copy_from_slice(step.state_end());
                    } else if ts <= step.t_start() {
                        xs.copy_from_slice(step.state_start());
                    } else {
                        step.eval(ts, &mut xs);
                    }
                    next += 1;
                    if !out.emit(ts, &xs) {
                        return StepControl::Stop;
                    }
                }
                match cut {
                    Some(tc) => {
                        step.eval(tc, &mut buf);
                        if out.last_t.is_none_or(|t| t < tc) {
                            out.emit(tc, &buf);
                        }
                        stop = Some(SimulationStop {
                            t: tc,
                            reason: "the state left the model's domain".into(),
                        });
                        StepControl::Stop
                    }
                    None => StepControl::Continue,
                }
            },
        )?;
        stats.add(&outcome.stats);
        x = outcome.x;
        if let Some(e) = out.error.take() {
            return Err(e);
        }
        if stop.is_some() || out.ended {
            break;
        }
        next = seg_end;
    }
    Ok(SimulationSummary {
        model: SystemInfo::model_name(sys),
        state_names: sys.state_names(),
        output_names: sys.output_names(),
        samples: out.count,
        stats,
        stop,
        conserved: tracker.finish(sys),
        ended_by_sink: out.ended,
    })
}

/// The checks before a simulation; true when the domain is to be watched (x0 inside it).
fn check_start(
    sys: &dyn DynSystem,
    x0: &[f64],
    input: &InputSignal,
    times: &[f64],
) -> Result<bool> {
    check_point(sys, x0, &vec![0.0; sys.nu()])?;
    input.check(sys.nu())?;
    let Some(&t_end) = times.last() else {
        return Err(LtiError::invalid("no sample times given"));
    };
    check_finite(|| "the end time".into(), t_end)?;
    if t_end <= 0.0 {
        return Err(LtiError::InvalidTime {
            value: t_end,
            reason: "the end time must be > 0".into(),
        });
    }
    check_sample_times(times, 0.0, t_end)?;
    let check_domain = sys.in_domain(x0);
    if !check_domain {
        // Outside the domain the equations may be singular: say so rather than report a NaN.
        let mut dx = vec![0.0; sys.nx()];
        sys.eval_f(x0, &input.at(0.0), &mut dx);
        if dx.iter().any(|v| !v.is_finite()) {
            return Err(LtiError::invalid(format!(
                "the initial state {x0:?} is outside the model's domain{}, where its equations \
                 are singular",
                sys.domain_note()
                    .map(|d| format!(" ({d})"))
                    .unwrap_or_default()
            )));
        }
    }
    Ok(check_domain)
}

/// Hands samples to the sink with their outputs; remembers a stop request or an error.
struct Emit<'s, 'k> {
    sys: &'s dyn DynSystem,
    input: &'s InputSignal,
    sink: &'s mut SampleSink<'k>,
    y: Vec<f64>,
    last_t: Option<f64>,
    count: usize,
    error: Option<LtiError>,
    ended: bool,
}

impl Emit<'_, '_> {
    /// False when the simulation must stop.
    fn emit(&mut self, t: f64, x: &[f64]) -> bool {
        if self.ended || self.error.is_some() {
            return false;
        }
        self.sys.eval_h(x, &self.input.at(t), &mut self.y);
        self.last_t = Some(t);
        match (self.sink)(t, x, &self.y) {
            Ok(true) => {
                self.count += 1;
                true
            }
            Ok(false) => {
                self.count += 1;
                self.ended = true;
                false
            }
            Err(e) => {
                self.error = Some(e);
                false
            }
        }
    }
}

/// The running drift of the conserved quantities (tracked only for zero input).
struct DriftTracker {
    names: Vec<String>,
    initial: Vec<f64>,
    buf: Vec<f64>,
    drift: Vec<f64>,
}

impl DriftTracker {
    fn new(sys: &dyn DynSystem, x0: &[f64], input: &InputSignal) -> Self {
        let names = if input.is_zero() {
            sys.conserved_names()
        } else {
            Vec::new()
        };
        let mut initial = vec![0.0; names.len()];
        if !names.is_empty() {
            sys.eval_conserved(x0, &mut initial);
        }
        DriftTracker {
            buf: initial.clone(),
            drift: vec![0.0; names.len()],
            names,
            initial,
        }
    }

    fn observe(&mut self, sys: &dyn DynSystem, x: &[f64]) {
        if self.drift.is_empty() {
            return;
        }
        sys.eval_conserved(x, &mut self.buf);
        for ((d, c), c0) in self.drift.iter_mut().zip(&self.buf).zip(&self.initial) {
            *d = d.max((c - c0).abs());
        }
    }

    fn finish(self, sys: &dyn DynSystem) -> Vec<ConservedDrift> {
        let scales = sys.conserved_scales();
        self.names
            .into_iter()
            .zip(self.initial.iter().zip(&self.drift))
            .enumerate()
            .map(|(i, (name, (&initial, &max_drift)))| {
                let reference = initial.abs().max(scales.get(i).copied().unwrap_or(0.0));
                ConservedDrift {
                    name,
                    initial,
                    max_drift,
                    reference,
                    relative_drift: if reference > 0.0 {
                        max_drift / reference
                    } else {
                        max_drift
                    },
                }
            })
            .collect()
    }
}

/// The last time in the step at which the state is still in the domain (bisection on the
/// dense output; the step starts inside and ends outside).
fn leave_time(sys: &dyn DynSystem, step: &DenseStep<'_>, buf: &mut [f64]) -> f64 {
    let (mut lo, mut hi) = (step.t_start(), step.t_end());
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        step.eval(mid, buf);
        if sys.in_domain(buf) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}
