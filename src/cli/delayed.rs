//! A loop closed around a dead time: T = L·e^(−sT)/(1 + L·e^(−sT)) has no rational transfer
//! function, so the commands that close the loop (`analyze`, `step`, `response`) read it here,
//! exactly — stability in the delay (`analysis::delay`: crossing frequencies and delays, the
//! stable delay intervals, the rightmost characteristic roots) and the closed-loop response by
//! the method of steps — instead of the rational closed loop. `--pade N` takes the rational
//! way instead.

use anyhow::{Context, Result, bail};
use serde_json::{Value, json};

use super::PlantArgs;
use super::output::{pair, print, print_json};
use super::plots::optional_json;
use crate::analysis::delay::{CLOSED_FORM_PIECES, DelayMethod};
use crate::analysis::{
    CrossingDirection, DelayRoots, DelayStability, DelayedResponse, Factored, Input, StepInfo,
    StepInfoOptions, TimeResponse,
};
use crate::fmt::{fmt_num, fmt_root, fmt_sig};
use crate::lti::Plant;
use crate::lti::controller::LoopSystem;
use crate::plot::{PlotOptions, StepSeries, step_png};

/// How many characteristic roots the reports list.
const ROOTS_LISTED: usize = 4;
/// Most delays a default horizon spans (beyond `CLOSED_FORM_PIECES` the collocation march):
/// 20 000 delays are 660 000 collocation nodes for a loop without fast poles (the march's
/// limit is 4·10⁶), a few tens of milliseconds; a delay shorter than 1/20 000 of the loop's
/// settling time shows the start of the response only (the report names the horizon).
const HORIZON_DELAYS: f64 = 20_000.0;

/// A controller in unity feedback around a plant with a dead time.
pub struct DelayedLoop {
    /// L = C·G, the rational part of the loop.
    pub l: Factored,
    /// The dead time T (s).
    pub delay: f64,
    /// Which signal: T (the output) or S (the error).
    pub which: LoopSystem,
    /// Stability for every delay.
    pub stability: DelayStability,
}

/// The delayed loop `plant` closes, when it closes one (T or S selected) around a dead time
/// and `--pade` does not replace the delay; `None` otherwise (the rational way applies).
pub fn of(args: &PlantArgs, plant: &Plant) -> Result<Option<DelayedLoop>> {
    let Some(which) = plant.selection else {
        return Ok(None);
    };
    if which == LoopSystem::Loop || args.pade.is_some() || args.sample.is_some() {
        return Ok(None);
    }
    // the delay from the model itself (no factorisation only to ask)
    let delay = match (&plant.model, args.channel()?) {
        (crate::lti::Model::Ss(ss), Some((i, o))) => ss.channel_delay(i, o),
        _ => plant.delay(),
    };
    if delay == 0.0 || plant.domain().is_discrete() {
        return Ok(None);
    }
    let g = match args.channel()? {
        Some((i, o)) => plant.factored_channel(i, o)?,
        None => plant.factored()?,
    };
    if which == LoopSystem::ControlSensitivity {
        bail!(
            "the control sensitivity C·S of a loop with a dead time is not available exactly: \
             analyse T or S, or replace the delay by a Padé approximant (--pade N)"
        );
    }
    let c = crate::analysis::closed_loop::loop_controller(plant)?;
    let l = c.tf()?.factored()?.series(&g.rational())?;
    l.require_proper("the loop L = C·G", false)?;
    let stability = l.delay_stability()?;
    Ok(Some(DelayedLoop {
        l,
        delay: g.delay(),
        which,
        stability,
    }))
}

impl DelayedLoop {
    /// Unstable characteristic roots at the loop's own delay.
    pub fn unstable(&self) -> Result<usize> {
        Ok(self.stability.unstable_roots_at(self.delay)?)
    }

    /// The rightmost characteristic roots at the loop's delay.
    pub fn roots(&self) -> Result<DelayRoots> {
        Ok(self.l.closed_loop_delay_roots(self.delay, ROOTS_LISTED)?)
    }

    /// A horizon for responses and step metrics: the delay plus six time constants of the
    /// slowest of the rightmost roots (ten delays for an unstable loop), at most
    /// [`HORIZON_DELAYS`] delays.
    pub fn horizon(&self, roots: &DelayRoots) -> f64 {
        let slowest = roots
            .roots
            .iter()
            .map(|r| r.value.re)
            .fold(f64::NEG_INFINITY, f64::max);
        let t = if slowest < 0.0 {
            self.delay + 6.0 / -slowest
        } else {
            10.0 * self.delay
        };
        t.clamp(2.0 * self.delay, HORIZON_DELAYS * self.delay)
    }

    /// The closed-loop response (y for T, e = r − y for S) to `input` at the times `t`.
    pub fn response(&self, input: &Input, t: &[f64]) -> Result<Vec<f64>> {
        let r = self.l.delayed_feedback_response(self.delay, input, t)?;
        Ok(self.signal(&r).to_vec())
    }

    /// The selected signal of a closed-loop response: y for T, the error e = r − y for S.
    fn signal<'a>(&self, r: &'a DelayedResponse) -> &'a [f64] {
        match self.which {
            LoopSystem::Sensitivity => &r.error,
            _ => &r.y,
        }
    }

    /// Asymptotically stable at the loop's own delay: no root in the right half plane and
    /// none at the origin.
    pub fn is_stable(&self) -> Result<bool> {
        Ok(self.unstable()? == 0 && !self.stability.root_at_origin)
    }

    /// Step metrics of T over `horizon` (`None` when unstable at the delay, or for S).
    pub fn step_info(&self, horizon: f64) -> Result<Option<StepInfo>> {
        if self.which != LoopSystem::ClosedLoop {
            return Ok(None);
        }
        let stable = self.is_stable()?;
        Ok(self
            .l
            .delayed_step_info(self.delay, horizon, stable, &StepInfoOptions::default())?)
    }

    /// "T = L·e^(−0.5 s)/(1 + L·e^(−0.5 s)), L = …".
    pub fn heading(&self, plant: &Plant) -> String {
        let e = crate::lti::delay::factor_text(self.delay);
        let formula = match self.which {
            LoopSystem::Sensitivity => format!("S = 1/(1 + L·{e})"),
            _ => format!("T = L·{e}/(1 + L·{e})"),
        };
        format!(
            "{}\n{formula}, L = C·G = {}\n  (a loop around a dead time: not a rational transfer \
             function — analysed exactly)",
            plant.name, self.l
        )
    }

    /// The stability-in-the-delay section of a report.
    pub fn stability_text(&self, roots: &DelayRoots) -> Result<String> {
        let st = &self.stability;
        let mut s = String::new();
        let n = self.unstable()?;
        let verdict = if st.root_at_origin {
            "not asymptotically stable: L(0) = −1 puts a root at s = 0 for every delay".to_string()
        } else if n == 0 {
            "stable".to_string()
        } else {
            format!("unstable: {n} characteristic roots in the right half plane")
        };
        s.push_str(&format!(
            "Stability at T = {} s: {verdict} (crossing delays of D(s) + N(s)·e^(−sT), decided \
             for every T)\n",
            fmt_num(self.delay)
        ));
        s.push_str(&format!(
            "  without the delay: {}\n",
            if st.stable_without_delay {
                "stable".to_string()
            } else {
                format!("{} roots in the right half plane", st.unstable_at_zero)
            }
        ));
        match st.critical_delay {
            Some(t) if t.is_finite() => s.push_str(&format!(
                "  critical delay: {} s (the loop stays stable for every smaller delay; delay \
                 margin left: {} s)\n",
                fmt_sig(t, 10),
                fmt_sig(t - self.delay, 7)
            )),
            Some(_) => s.push_str("  critical delay: ∞ (stable for every delay)\n"),
            None => {}
        }
        if !st.stable_intervals.is_empty() {
            let shown: Vec<String> = st
                .stable_intervals
                .iter()
                .take(6)
                .map(|i| {
                    let to = if i.to.is_finite() {
                        format!("{})", fmt_sig(i.to, 7))
                    } else {
                        "∞)".into()
                    };
                    format!("[{}, {to}", fmt_sig(i.from, 7))
                })
                .collect();
            let more = st.stable_intervals.len().saturating_sub(6);
            s.push_str(&format!(
                "  stable for T in {}{}\n",
                shown.join(" ∪ "),
                if more > 0 {
                    format!(" and {more} more intervals")
                } else {
                    String::new()
                }
            ));
        } else {
            s.push_str("  stable for no delay\n");
        }
        for c in st.crossings.iter().take(4) {
            let dir = match c.direction {
                CrossingDirection::Destabilizing => "roots move into the right half plane",
                CrossingDirection::Stabilizing => "roots move back into the left half plane",
                CrossingDirection::Tangential => "roots touch the axis and turn back",
            };
            s.push_str(&format!(
                "  crossing at ω = {} rad/s for T = {} + {}·k s: {dir}\n",
                fmt_sig(c.frequency, 7),
                fmt_sig(c.delay(0), 7),
                fmt_sig(c.period(), 7)
            ));
        }
        for note in &st.notes {
            s.push_str(&format!("  note: {note}\n"));
        }
        s.push_str("Rightmost characteristic roots (relative residual):\n");
        for r in &roots.roots {
            if r.value.im < 0.0 {
                continue;
            }
            s.push_str(&format!(
                "  {}   ({})\n",
                fmt_root(r.value, 7),
                fmt_sig(r.relative_residual, 2)
            ));
        }
        if let Some(note) = &roots.note {
            s.push_str(&format!("  note: {note}\n"));
        }
        Ok(s)
    }

    /// The stability part as JSON.
    pub fn stability_json(&self, roots: &DelayRoots) -> Result<Value> {
        let st = &self.stability;
        Ok(json!({
            "unstable_roots": self.unstable()?,
            "stable": self.is_stable()?,
            "stable_without_delay": st.stable_without_delay,
            "critical_delay": st.critical_delay.filter(|t| t.is_finite()),
            "stable_intervals": st.stable_intervals.iter().map(|i| {
                json!([i.from, if i.to.is_finite() { json!(i.to) } else { Value::Null }])
            }).collect::<Vec<_>>(),
            "crossings": st.crossings.iter().map(|c| json!({
                "w": c.frequency,
                "first_delay": c.delay(0),
                "period": c.period(),
                "direction": format!("{:?}", c.direction).to_lowercase(),
            })).collect::<Vec<_>>(),
            "rightmost_roots": roots.roots.iter().map(|r| pair(r.value)).collect::<Vec<_>>(),
            "relative_residuals": roots.roots.iter().map(|r| r.relative_residual).collect::<Vec<_>>(),
            "notes": st.notes,
        }))
    }
}

/// `ltikit analyze`: a loop closed around a dead time is reported here ([`analyze`]),
/// everything else by the analyze command itself.
pub fn analyze_command(a: &super::analyze::AnalyzeArgs) -> Result<()> {
    if a.batch.is_none() {
        let plant = a.plant.single()?;
        if let Some(dl) = of(&a.plant, &plant)? {
            return analyze(&plant, &dl, a.json);
        }
    }
    super::analyze::run(a)
}

/// `ltikit analyze` of a delayed loop: the loop, stability in the delay, the rightmost roots
/// and the step metrics of T over a horizon.
pub fn analyze(plant: &Plant, dl: &DelayedLoop, as_json: bool) -> Result<()> {
    let roots = dl.roots()?;
    let horizon = dl.horizon(&roots);
    let info = dl.step_info(horizon);
    if as_json {
        let mut doc = json!({
            "loop": dl.l.to_string(),
            "delay": dl.delay,
            "system": dl.which.formula(),
            "stability_in_delay": dl.stability_json(&roots)?,
            "horizon": horizon,
        });
        if let Some(m) = doc.as_object_mut() {
            let v = match &info {
                Ok(Some(i)) => serde_json::to_value(super::analyze::json::StepInfoJson::from(i))?,
                _ => Value::Null,
            };
            m.insert("step_info".into(), v);
            if let Err(e) = &info {
                m.insert("step_info_note".into(), json!(super::one_line(e)));
            }
        }
        return print_json(&doc);
    }
    let mut s = format!("{}\n\n", dl.heading(plant));
    s.push_str(&dl.stability_text(&roots)?);
    s.push('\n');
    match info {
        Ok(Some(i)) => {
            s.push_str(&super::analyze::step_text(&i));
            s.push_str(&format!(
                "  (the closed loop by the method of steps over t ≤ {} s: {})\n",
                fmt_sig(horizon, 4),
                if horizon / dl.delay > CLOSED_FORM_PIECES as f64 {
                    "a Chebyshev collocation march of the delay equation, interval by interval"
                } else {
                    "exact pieces"
                }
            ));
        }
        Ok(None) => {
            s.push_str("Step metrics: not computed (the loop is not stable at this delay)\n")
        }
        Err(e) => s.push_str(&format!(
            "Step metrics: not computed ({})\n",
            super::one_line(&e)
        )),
    }
    print(&s)
}

/// `ltikit response` of a delayed loop: exact samples and the piecewise closed form.
pub fn response(
    plant: &Plant,
    dl: &DelayedLoop,
    input: &Input,
    t: Option<Vec<f64>>,
    as_json: bool,
) -> Result<()> {
    let roots = dl.roots()?;
    let t = match t {
        Some(t) => t,
        None => {
            let h = dl.horizon(&roots);
            (0..=10).map(|i| h * i as f64 / 10.0).collect()
        }
    };
    let r = dl.l.delayed_feedback_response(dl.delay, input, &t)?;
    let y = dl.signal(&r).to_vec();
    if as_json {
        return print_json(&json!({
            "closed_form": r.closed_form.to_string(),
            "t": r.t,
            "y": y,
            "cancellation_bound": r.cancellation_bound,
            "method": r.method,
            "estimated_error": r.estimated_error,
        }));
    }
    let mut s = format!("{}\nInput: {}\n\n", dl.heading(plant), input.title());
    s.push_str(&format!("{}\n", r.closed_form));
    s.push_str("\n       t [s]             y(t)\n");
    for (ti, yi) in t.iter().zip(&y) {
        s.push_str(&format!(
            "{:>12} {:>16}\n",
            fmt_sig(*ti, 7),
            fmt_sig(*yi, 10)
        ));
    }
    s.push_str(&match r.method {
        DelayMethod::Pieces => format!(
            "\nValues exact (each piece stepped by the matrix exponential, the closed form beside \
             it agrees to {}; rounding bound of the alternating sum {}).\n",
            fmt_sig(r.closed_form_error, 2),
            fmt_sig(r.max_cancellation_bound, 2)
        ),
        DelayMethod::CollocationMarch => format!(
            "\nValues by a Chebyshev collocation march of the delay equation, interval by \
             interval (the closed form above covers the first {} pieces only and agrees with it \
             to {}; estimated error {}).\n",
            r.closed_form.len(),
            fmt_sig(r.closed_form_error, 2),
            fmt_sig(r.estimated_error, 2)
        ),
    });
    print(&s)
}

/// `ltikit step`: a single loop closed around a dead time is drawn here, exactly
/// ([`delayed_step`]); everything else by the step command itself.
pub fn step_command(a: &super::plots::StepArgs) -> Result<()> {
    let input: Input = a.input.parse()?;
    if !matches!(input, Input::None)
        && let [p] = a.plant.resolve_for(LoopSystem::ClosedLoop)?.as_slice()
        && let Some(dl) = of(&a.plant, p)?
    {
        let opts = a.plot.options()?;
        return delayed_step(a, p, &dl, &input, &opts);
    }
    super::plots::step(a)
}

/// The step (or other) response of a loop around a dead time, exact by the method of steps,
/// with the step metrics of T marked.
fn delayed_step(
    a: &super::plots::StepArgs,
    plant: &crate::lti::Plant,
    dl: &DelayedLoop,
    input: &Input,
    opts: &PlotOptions,
) -> Result<()> {
    let roots = dl.roots()?;
    let t_end = match a.t_end {
        Some(t) if t.is_finite() && t > 0.0 => t,
        Some(t) => bail!("--t-end must be > 0, got {}", crate::error::number(t)),
        None => dl.horizon(&roots),
    };
    let t: Vec<f64> = (0..=2000).map(|i| t_end * i as f64 / 2000.0).collect();
    let y = dl.response(input, &t)?;
    let stable = dl.is_stable()?;
    let info = if matches!(input, Input::Step) {
        dl.step_info(t_end)
            .map_err(|e| super::warn(format!("step metrics not marked: {}", super::one_line(&e))))
            .ok()
            .flatten()
    } else {
        None
    };
    let r = TimeResponse {
        t,
        y,
        final_value: info.as_ref().map(|i| i.steady_state),
    };
    let label = format!(
        "{} (dead time {} s, exact)",
        dl.which.formula(),
        crate::fmt::fmt_num(dl.delay)
    );
    let mut s = StepSeries::new(&r)
        .label(&label)
        .input(*input)
        .unstable(!stable);
    if let Some(i) = &info {
        s = s.info(i);
    }
    let mut opts = opts.clone();
    if opts.title.is_none() {
        opts.title = Some(format!("{} response of {}", input.title(), plant.name));
    }
    step_png(&a.plot.output, &[s], &opts)
        .with_context(|| format!("response plot {}", a.plot.output.display()))?;
    if !a.plot.json {
        return Ok(());
    }
    print_json(&json!({
        "file": a.plot.output.display().to_string(),
        "input": a.input,
        "t_end": t_end,
        "plants": [{
            "label": label,
            "step_info": optional_json(
                info.as_ref()
                    .map(super::analyze::json::StepInfoJson::from)
                    .as_ref()
            )?,
            "diverges": !stable,
        }],
    }))
}
