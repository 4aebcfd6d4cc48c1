//! `ltikit simulate MODEL`: adaptive Dormand–Prince simulation, CSV or JSON output.

use anyhow::{Result, bail};
use clap::Args;

use super::output::{Stream, json_number, print};
use super::parse;
use crate::analysis::Input;
use crate::error::abbreviate;
use crate::nonlinear::{
    ConservedDrift, InputSignal, SimulationSummary, build_model, check_kept_values, sample_times,
    simulate_each,
};
use crate::numeric::rk45::Rk45Options;

#[derive(Args, Debug)]
pub struct SimulateArgs {
    /// Model: pendulum, mems, lorenz, vanderpol, rigid-body, heavy-top, gyroscope,
    /// double-pendulum, or a linear plant (spring-mass-damper, …).
    pub model: String,
    /// A model parameter, NAME=VALUE (repeatable).
    #[arg(long = "param", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub params: Vec<String>,
    /// Initial state, e.g. --x0 "0.5 0" (state order as in `ltikit linearize MODEL`).
    /// Default: the model's own start (Lorenz [1, 0, 0], the pendulum released from 1 rad, …).
    #[arg(long, value_name = "VALUES", allow_hyphen_values = true)]
    pub x0: Option<String>,
    /// End time (s), > 0. Default: the model's own horizon (Lorenz 50 s, …).
    #[arg(long = "t-end", value_name = "SECONDS", allow_hyphen_values = true)]
    pub t_end: Option<f64>,
    /// Number of output samples, uniform from 0 to the end time.
    #[arg(long, default_value_t = 1001)]
    pub points: usize,
    /// Input: constant values ("0.5"), a step "step:T:BEFORE:AFTER", or a signal added to the
    /// operating input (step, ramp, exp:A, sin:W, cos:W; single input). Default: the model's
    /// operating input (e.g. the MEMS voltage v).
    #[arg(long, value_name = "U", allow_hyphen_values = true)]
    pub input: Option<String>,
    /// Relative tolerance.
    #[arg(long, default_value_t = 1e-9)]
    pub rtol: f64,
    /// Absolute tolerance.
    #[arg(long, default_value_t = 1e-12)]
    pub atol: f64,
    /// Largest number of integration steps (accepted plus rejected).
    #[arg(long = "max-steps", default_value_t = 1_000_000)]
    pub max_steps: usize,
    /// Print JSON instead of CSV.
    #[arg(long)]
    pub json: bool,
    /// Also draw a PNG: the states against time, or with --phase a phase portrait.
    #[arg(short = 'o', long = "output", value_name = "FILE.png", value_parser = super::png_path)]
    pub output: Option<std::path::PathBuf>,
    /// Phase portrait axes: two state numbers (1-based) or names, e.g. --phase 1,2.
    #[arg(long, value_name = "X,Y", requires = "output")]
    pub phase: Option<String>,
    /// Image size for -o, WIDTHxHEIGHT.
    #[arg(long, default_value = "1000x700", value_name = "WxH")]
    pub size: String,
}

/// Index of a state given by 1-based number or name.
fn state_index(s: &str, names: &[String]) -> Result<usize> {
    let s = s.trim();
    if let Ok(k) = s.parse::<usize>() {
        if k >= 1 && k <= names.len() {
            return Ok(k - 1);
        }
        bail!(
            "--phase: state {k} does not exist (the model has {} states)",
            names.len()
        );
    }
    names.iter().position(|n| n == s).ok_or_else(|| {
        anyhow::anyhow!(
            "--phase: no state called '{}' (states: {})",
            abbreviate(s),
            names.join(", ")
        )
    })
}

/// The samples of a simulation kept whole (for a JSON document or a picture): flat arrays of
/// numbers, 8 bytes each, no allocation per sample.
struct Samples {
    t: Vec<f64>,
    /// States, `nx` per sample.
    x: Vec<f64>,
    /// Outputs, `ny` per sample.
    y: Vec<f64>,
    nx: usize,
    ny: usize,
    summary: SimulationSummary,
}

impl Samples {
    /// Simulates and keeps every sample (the number of kept values checked first against
    /// `limits::MAX_SIMULATION_VALUES`).
    fn collect(
        sys: &dyn crate::nonlinear::DynSystem,
        x0: &[f64],
        input: &InputSignal,
        times: &[f64],
        opts: &Rk45Options,
    ) -> Result<Samples> {
        check_kept_values(sys, times.len())?;
        let (nx, ny) = (sys.nx(), sys.ny());
        let mut t = Vec::with_capacity(times.len());
        let mut x = Vec::with_capacity(times.len().saturating_mul(nx));
        let mut y = Vec::with_capacity(times.len().saturating_mul(ny));
        let summary = simulate_each(sys, x0, input, times, opts, &mut |ti, xi, yi| {
            t.push(ti);
            x.extend_from_slice(xi);
            y.extend_from_slice(yi);
            Ok(true)
        })?;
        Ok(Samples {
            t,
            x,
            y,
            nx,
            ny,
            summary,
        })
    }

    /// The time series of state `k`.
    fn state(&self, k: usize) -> Vec<f64> {
        self.x
            .iter()
            .skip(k)
            .step_by(self.nx.max(1))
            .copied()
            .collect()
    }
}

fn picture(a: &SimulateArgs, sys: &dyn crate::nonlinear::DynSystem, sim: &Samples) -> Result<()> {
    use crate::plot::{
        Curve, Equilibrium, PhasePortrait, PlotOptions, phase_portrait_png, time_plot_png,
    };
    let Some(path) = &a.output else {
        return Ok(());
    };
    let names = &sim.summary.state_names;
    let opts = PlotOptions {
        size: crate::plot::parse_size(&a.size)?,
        title: Some(format!("{} simulation", sim.summary.model)),
        ..Default::default()
    };
    match &a.phase {
        None => {
            let curves = (0..names.len())
                .map(|k| Ok(Curve::from_xy(&sim.t, &sim.state(k))?.label(names[k].clone())))
                .collect::<Result<Vec<_>>>()?;
            time_plot_png(path, &curves, "states", &opts)?;
        }
        Some(spec) => {
            let Some((xs, ys)) = spec.split_once(',') else {
                bail!(
                    "--phase '{}': expected two states, e.g. 1,2",
                    abbreviate(spec)
                );
            };
            let (i, j) = (state_index(xs, names)?, state_index(ys, names)?);
            let traj = Curve::new(sim.x.chunks_exact(sim.nx.max(1)).map(|x| (x[i], x[j])));
            let lin = crate::nonlinear::linearize(
                sys,
                Some(&sys.operating_input()),
                &crate::nonlinear::EquilibriumSearch::default(),
            )?;
            let equilibria = lin
                .equilibria
                .iter()
                .map(|e| Equilibrium {
                    at: (e.x[i], e.x[j]),
                    stable: e.stability == crate::nonlinear::LocalStability::AsymptoticallyStable,
                    label: None,
                })
                .collect();
            let p = PhasePortrait {
                trajectories: vec![traj],
                equilibria,
                x_label: names[i].clone(),
                y_label: names[j].clone(),
                ..Default::default()
            };
            phase_portrait_png(path, &p, &opts)?;
        }
    }
    Ok(())
}

/// Parses the `--input` value for a model whose operating input is `operating`.
///
/// - absent: the operating input, constant;
/// - numbers ("0.5", "0.3 -0.1 0.05"): constant;
/// - `step:T:BEFORE:AFTER` (single input): a jump at T;
/// - a standard signal (`step`, `ramp`, `exp:A`, `sin:W`, `cos:W`, as in `response`) added to
///   the operating input with unit amplitude from t = 0 (single input).
pub fn parse_input(text: Option<&str>, operating: &[f64]) -> Result<InputSignal> {
    let Some(text) = text else {
        return Ok(InputSignal::constant(operating.to_vec()));
    };
    let single = || -> Result<()> {
        if operating.is_empty() {
            bail!("--input '{}': this model has no input", abbreviate(text));
        }
        if operating.len() != 1 {
            bail!(
                "--input '{}': a step or a signal is only for single-input models (this one has {} inputs)",
                abbreviate(text),
                operating.len()
            );
        }
        Ok(())
    };
    if let Some(rest) = text.strip_prefix("step:") {
        let parts: Vec<&str> = rest.split(':').collect();
        let [t_step, before, after] = parts.as_slice() else {
            bail!(
                "--input '{}': a step is step:T:BEFORE:AFTER, e.g. step:1:0:0.5",
                abbreviate(text)
            );
        };
        let num = |s: &str, what: &str| -> Result<f64> {
            s.trim().parse::<f64>().map_err(|_| {
                anyhow::anyhow!(
                    "--input '{}': {what} '{}' is not a number",
                    abbreviate(text),
                    abbreviate(s)
                )
            })
        };
        single()?;
        return Ok(InputSignal::step(
            num(t_step, "the step time")?,
            vec![num(before, "the value before")?],
            vec![num(after, "the value after")?],
        ));
    }
    if text
        .trim_start()
        .starts_with(|c: char| c.is_ascii_alphabetic())
    {
        let shape: Input = text.parse()?;
        single()?;
        let after: Vec<f64> = operating.iter().map(|u| u + 1.0).collect();
        return Ok(InputSignal::shaped(operating.to_vec(), after, shape, 0.0));
    }
    Ok(InputSignal::constant(parse::numbers(text, "--input")?))
}

pub fn run(a: &SimulateArgs) -> Result<()> {
    let params = parse::params(&a.params)?;
    let sys = build_model(&a.model, &params)?;
    let x0 = match &a.x0 {
        Some(text) => parse::numbers(text, "--x0")?,
        None => sys.default_initial_state(),
    };
    let t_end = a.t_end.unwrap_or_else(|| sys.default_horizon());
    let input = parse_input(a.input.as_deref(), &sys.operating_input())?;
    let times = sample_times(t_end, a.points)?;
    let opts = Rk45Options {
        rtol: a.rtol,
        atol: a.atol,
        max_steps: a.max_steps,
        ..Default::default()
    };
    let defaults = defaults_note(a, &x0, t_end);
    if a.output.is_some() || a.json {
        // A picture or a JSON document needs every sample: simulate whole, then draw and
        // report.
        let sim = Samples::collect(sys.as_ref(), &x0, &input, &times, &opts)?;
        if let Some(path) = &a.output {
            picture(a, sys.as_ref(), &sim)?;
            if !a.json {
                let s = &sim.summary;
                let mut text = format!(
                    "Figure: {} ({} samples, {} steps)\n",
                    path.display(),
                    sim.t.len(),
                    s.stats.steps
                );
                text.push_str(&csv_footer(s.stop.as_ref(), &s.conserved));
                text.push_str(&defaults);
                return print(&text);
            }
        }
        let mut out = Stream::stdout();
        write_json(&mut |text| out.put(text), &sim, &x0)?;
        return out.finish();
    }
    let mut out = Stream::stdout();
    // CSV, written as it is computed: memory does not grow with --points. The first
    // HOLD_BYTES are held back, so a simulation that fails early (a step limit, a NaN) prints
    // nothing but the error; one that fails after that ends its CSV with a `# error:` line.
    let mut text = csv_header(&sys.state_names(), &sys.output_names());
    let mut streaming = false;
    let mut open = true;
    let result = simulate_each(sys.as_ref(), &x0, &input, &times, &opts, &mut |t, x, y| {
        csv_row(t, x, y, &mut text);
        if text.len() >= if streaming { 1 << 16 } else { HOLD_BYTES } {
            streaming = true;
            open = out
                .put(&text)
                .map_err(|e| crate::error::LtiError::invalid(e.to_string()))?;
            text.clear();
        }
        Ok(open)
    });
    let s = match result {
        Ok(s) => s,
        Err(e) => {
            if streaming && open {
                out.put(&text)?;
                out.put(&format!("# error: {e}\n"))?;
                out.finish()?;
            }
            return Err(e.into());
        }
    };
    if open && !s.ended_by_sink {
        text.push_str(&csv_footer(s.stop.as_ref(), &s.conserved));
        text.push_str(&defaults);
        out.put(&text)?;
    }
    out.finish()
}

/// CSV bytes held back before `simulate` starts streaming (see `run`).
const HOLD_BYTES: usize = 8 << 20;

/// The `# …` line saying which of x0 and t_end are the model's defaults (empty when both
/// were given).
fn defaults_note(a: &SimulateArgs, x0: &[f64], t_end: f64) -> String {
    if a.x0.is_some() && a.t_end.is_some() {
        return String::new();
    }
    format!(
        "# x0 = {} and t_end = {} s{}\n",
        super::text::vector_text(x0),
        t_end,
        match (a.x0.is_none(), a.t_end.is_none()) {
            (true, true) => " are the model's defaults",
            (true, false) => ": x0 is the model's default",
            _ => ": t_end is the model's default",
        }
    )
}

/// The JSON document of kept samples, written as it is formatted (the same document as
/// `SimulationJson` through `print_json`, without its tree of values); `put` takes each block
/// and says whether the reader is still there.
fn write_json(put: &mut dyn FnMut(&str) -> Result<bool>, sim: &Samples, x0: &[f64]) -> Result<()> {
    let (s, t) = (&sim.summary, &sim.t);
    let (xs, ys, nx, ny) = (&sim.x, &sim.y, sim.nx, sim.ny);
    let head = serde_json::json!({
        "model": s.model,
        "state_names": s.state_names,
        "output_names": s.output_names,
    });
    let mut text = String::from("{\n");
    for (k, v) in head.as_object().into_iter().flatten() {
        text.push_str(&format!("  {}: ", serde_json::Value::String(k.clone())));
        super::output::pretty(v, 1, &mut text);
        text.push_str(",\n");
    }
    text.push_str("  \"t\": [");
    let mut open = put(&text)?;
    text.clear();
    for (i, v) in t.iter().enumerate() {
        if !open {
            return Ok(());
        }
        if i > 0 {
            text.push_str(", ");
        }
        text.push_str(&json_number(*v));
        if text.len() >= 1 << 16 {
            open = put(&text)?;
            text.clear();
        }
    }
    text.push_str("],\n");
    for (key, flat, width) in [("x", &xs, nx), ("y", &ys, ny)] {
        text.push_str(&format!("  \"{key}\": ["));
        let rows = flat.len().checked_div(width).unwrap_or(0);
        for r in 0..rows {
            text.push_str(if r == 0 { "\n    [" } else { ",\n    [" });
            for (j, v) in flat[r * width..(r + 1) * width].iter().enumerate() {
                if j > 0 {
                    text.push_str(", ");
                }
                text.push_str(&json_number(*v));
            }
            text.push(']');
            if text.len() >= 1 << 16 {
                if !put(&text)? {
                    return Ok(());
                }
                text.clear();
            }
        }
        text.push_str(if rows == 0 { "],\n" } else { "\n  ],\n" });
    }
    let mut tail = serde_json::json!({
        "x0": x0,
        "steps": s.stats.steps,
        "rejected_steps": s.stats.rejections,
        "stopped": s.stop.as_ref().map(|st| serde_json::json!({"t": st.t, "reason": st.reason})),
    });
    if !s.conserved.is_empty() {
        if let Some(m) = tail.as_object_mut() {
            m.insert("conserved".into(), super::output::json_value(&s.conserved)?);
        }
    }
    let tail = super::output::json_value(&tail)?;
    let entries: Vec<_> = tail.as_object().into_iter().flatten().collect();
    for (i, (k, v)) in entries.iter().enumerate() {
        text.push_str(&format!("  {}: ", serde_json::Value::String((*k).clone())));
        super::output::pretty(v, 1, &mut text);
        text.push_str(if i + 1 < entries.len() { ",\n" } else { "\n" });
    }
    text.push_str("}\n");
    put(&text)?;
    Ok(())
}

/// The CSV header line: t, the states, the outputs (prefixed y: when a name repeats).
fn csv_header(state_names: &[String], output_names: &[String]) -> String {
    let mut header = vec!["t".to_string()];
    header.extend(state_names.iter().cloned());
    for n in output_names {
        if header.contains(n) {
            header.push(format!("y:{n}"));
        } else {
            header.push(n.clone());
        }
    }
    let mut out = header.join(",");
    out.push('\n');
    out
}

/// One CSV row, appended to `out`.
fn csv_row(t: f64, x: &[f64], y: &[f64], out: &mut String) {
    use std::fmt::Write;
    let _ = write!(out, "{t}");
    for v in x.iter().chain(y) {
        let _ = write!(out, ",{v}");
    }
    out.push('\n');
}

/// The `# …` lines after the samples: where the simulation stopped, conserved drifts.
fn csv_footer(
    stop: Option<&crate::nonlinear::SimulationStop>,
    conserved: &[ConservedDrift],
) -> String {
    let mut out = String::new();
    if let Some(st) = stop {
        out.push_str(&format!("# stopped at t = {}: {}\n", st.t, st.reason));
    }
    for c in conserved {
        out.push_str(&format!(
            "# conserved {}: {} at t = 0, drift {:.3e} (relative {:.3e})\n",
            c.name,
            crate::fmt::fmt_sig(c.initial, 12),
            c.max_drift,
            c.relative_drift
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nonlinear::Simulation;
    use serde::Serialize;

    /// The document as a tree of values (what `print_json` would write).
    #[derive(serde::Serialize)]
    struct SimulationJson<'a> {
        model: &'a str,
        state_names: &'a [String],
        output_names: &'a [String],
        t: &'a [f64],
        x: &'a [Vec<f64>],
        y: &'a [Vec<f64>],
        x0: &'a [f64],
        steps: usize,
        rejected_steps: usize,
        stopped: Option<StopJson<'a>>,
        #[serde(skip_serializing_if = "<[_]>::is_empty")]
        conserved: &'a [ConservedDrift],
    }

    #[derive(Serialize)]
    struct StopJson<'a> {
        t: f64,
        reason: &'a str,
    }

    impl<'a> From<&'a Simulation> for SimulationJson<'a> {
        fn from(s: &'a Simulation) -> Self {
            SimulationJson {
                model: &s.model,
                state_names: &s.state_names,
                output_names: &s.output_names,
                t: &s.t,
                x: &s.states,
                y: &s.outputs,
                x0: &[],
                steps: s.stats.steps,
                rejected_steps: s.stats.rejections,
                stopped: s.stop.as_ref().map(|st| StopJson {
                    t: st.t,
                    reason: &st.reason,
                }),
                conserved: &s.conserved,
            }
        }
    }

    /// The streamed document is byte for byte the tree's: a model with conserved quantities
    /// (the rigid body), one with an input (the MEMS mirror), two samples only (Lorenz).
    #[test]
    fn the_streamed_json_is_the_tree_s() {
        let opts = Rk45Options::default();
        for (model, x0, t_end, points) in [
            ("rigid-body", vec![0.6, -1.0, 2.0], 3.0, 31),
            ("mems", vec![], 1e-3, 11),
            ("lorenz", vec![1.0, 0.0, 0.0], 1.0, 2),
        ] {
            let sys = build_model(model, &[]).unwrap();
            let x0 = if x0.is_empty() {
                sys.default_initial_state()
            } else {
                x0
            };
            let input = InputSignal::constant(sys.operating_input());
            let times = sample_times(t_end, points).unwrap();
            let kept =
                crate::nonlinear::simulate(sys.as_ref(), &x0, &input, &times, &opts).unwrap();
            let mut tree = String::new();
            let mut j = SimulationJson::from(&kept);
            j.x0 = &x0;
            super::super::output::pretty(
                &super::super::output::json_value(&j).unwrap(),
                0,
                &mut tree,
            );
            tree.push('\n');
            let flat = Samples::collect(sys.as_ref(), &x0, &input, &times, &opts).unwrap();
            let mut streamed = String::new();
            write_json(
                &mut |t| {
                    streamed.push_str(t);
                    Ok(true)
                },
                &flat,
                &x0,
            )
            .unwrap();
            assert_eq!(streamed, tree, "{model}");
        }
    }
}
