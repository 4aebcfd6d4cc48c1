//! `ltikit response`: the closed-form y(t) for a standard input and ODE initial conditions,
//! its transient and steady-state parts, and exact values.

use anyhow::{Result, bail};
use clap::Args;
use serde::Serialize;

use super::output::{print, print_json};
use super::{PlantArgs, parse};
use crate::analysis::{Input, auto_time_span};
use crate::fmt::fmt_sig;

#[derive(Args, Debug)]
pub struct ResponseArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// Input: impulse, step, ramp, exp:A (e^(A t)), sin:W, cos:W, or none (initial conditions
    /// only).
    #[arg(long, default_value = "step", allow_hyphen_values = true)]
    pub input: String,
    /// ODE initial conditions "y(0) y'(0) …" (input zero for t < 0; missing ones are 0).
    #[arg(long, value_name = "VALUES", allow_hyphen_values = true)]
    pub ic: Option<String>,
    /// Times (s, ≥ 0) at which to report values, e.g. --t "0 0.5 1 2". Default: 11 points
    /// over an automatic window.
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub t: Option<String>,
    /// Print one JSON document: {"closed_form", "t", "y", "transient", "steady_state"} (a
    /// state-space response: see docs/ARCHITECTURE.md, "MIMO plants").
    #[arg(long)]
    pub json: bool,
    /// Initial state x(0) of a state-space plant, "x1 x2 …" (added to the response; with
    /// --input none the free response).
    #[arg(long, value_name = "VALUES", allow_hyphen_values = true)]
    pub x0: Option<String>,
    /// Include the state trajectories (state-space plants).
    #[arg(long)]
    pub states: bool,
    /// Simulate an input signal from a CSV file (lsim): columns t, u1 … um, one sample a line
    /// (an optional header line); values at the file's times. At most 1 000 000 samples.
    #[arg(long, value_name = "FILE.csv", conflicts_with = "t")]
    pub input_file: Option<std::path::PathBuf>,
    /// How the --input-file signal moves between samples: zoh (held) or foh (linear).
    #[arg(long, default_value = "zoh", value_name = "zoh|foh")]
    pub hold: String,
}

/// The `response` JSON contract (DESIGN §1.2).
#[derive(Serialize)]
struct ResponseJson {
    closed_form: String,
    t: Vec<f64>,
    y: Vec<f64>,
    transient: Vec<f64>,
    steady_state: Vec<f64>,
}

fn input_words(i: &Input) -> String {
    match i {
        Input::Impulse => "unit impulse δ(t)".into(),
        Input::Step => "unit step 1(t)".into(),
        Input::Ramp => "unit ramp t·1(t)".into(),
        Input::Exp(a) => format!("e^({} t)·1(t)", fmt_sig(*a, 6)),
        Input::Sin(w) => format!("sin({} t)·1(t)", fmt_sig(*w, 6)),
        Input::Cos(w) => format!("cos({} t)·1(t)", fmt_sig(*w, 6)),
        Input::None => "none (initial-condition response)".into(),
    }
}

pub fn run(a: &ResponseArgs) -> Result<()> {
    let plant = a.plant.single()?;
    if super::ss_response::wanted(a, &plant) {
        return super::ss_response::run(a, &plant);
    }
    let f = match a.plant.factored(&plant) {
        Ok(f) => f,
        // A state-space plant the factored core cannot take yet (order beyond the coefficient
        // path): its response by exact discretisation.
        Err(_) if matches!(plant.model, crate::lti::Model::Ss(_)) && a.ic.is_none() => {
            return super::ss_response::run(a, &plant);
        }
        Err(e) => return Err(e),
    };
    let input: Input = a.input.parse()?;
    let ics = match &a.ic {
        Some(s) => parse::numbers(s, "--ic")?,
        None => Vec::new(),
    };
    let t = match &a.t {
        Some(s) => parse::numbers(s, "--t")?,
        None => {
            let span = auto_time_span(&f)?.t_end;
            (0..=10).map(|i| span * i as f64 / 10.0).collect()
        }
    };
    if t.is_empty() {
        bail!("--t: no times given");
    }
    let resp = f.response(&input, &ics, &t)?;
    let samples = &resp.samples;
    if a.json {
        return print_json(&ResponseJson {
            closed_form: resp.closed_form.formula("y(t)"),
            t: samples.t.clone(),
            y: samples.y.clone(),
            transient: samples.transient.clone(),
            steady_state: samples.steady_state.clone(),
        });
    }
    let mut s = format!("{}\n", super::text::g_text(&plant, &f));
    s.push_str(&format!("Input: {}", input_words(&input)));
    if !ics.is_empty() {
        let names: Vec<String> = (0..ics.len())
            .map(|k| format!("y{}(0) = {}", "'".repeat(k), fmt_sig(ics[k], 6)))
            .collect();
        s.push_str(&format!("; initial conditions {}", names.join(", ")));
    }
    s.push_str("\n\n");
    s.push_str(&format!("{}\n", resp.closed_form.formula("y(t)")));
    s.push_str(&format!(
        "  transient (system poles):    {}\n",
        resp.transient.expression()
    ));
    s.push_str(&format!(
        "  steady state (input poles):  {}\n\n",
        resp.steady_state.expression()
    ));
    s.push_str(&format!(
        "{:>12} {:>16} {:>16} {:>16}\n",
        "t [s]", "y(t)", "transient", "steady state"
    ));
    for i in 0..samples.t.len() {
        s.push_str(&format!(
            "{:>12} {:>16} {:>16} {:>16}\n",
            fmt_sig(samples.t[i], 6),
            fmt_sig(samples.y[i], 10),
            fmt_sig(samples.transient[i], 10),
            fmt_sig(samples.steady_state[i], 10)
        ));
    }
    s.push_str(&format!(
        "\nValues by exact matrix-exponential stepping; the closed form agrees to {} \
         (max |difference| over these times, relative to max|y| = {}).\n",
        fmt_sig(
            if samples.max_abs_y > 0.0 {
                samples.closed_form_error / samples.max_abs_y
            } else {
                samples.closed_form_error
            },
            2
        ),
        fmt_sig(samples.max_abs_y, 6)
    ));
    print(&s)
}
