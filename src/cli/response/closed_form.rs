//! The closed-form report of `response`: y(t) of a SISO plant (a transfer function, one
//! channel of a state-space model, or a loop) for a standard input and ODE initial conditions
//! from its factored form, the transient and steady-state parts, and exact values; for a
//! discrete-time plant the sequence y\[k\] with the initial conditions y\[−1\], y\[−2\], … of its
//! difference equation, and the samples the times read.

use anyhow::{Result, bail};
use serde::Serialize;

use super::args::ResponseArgs;
use crate::analysis::{Input, auto_time_span};
use crate::cli::output::{print, print_json};
use crate::cli::{Plant, parse, text};
use crate::fmt::fmt_sig;

/// The `response` JSON contract (DESIGN §1.2).
#[derive(Serialize)]
struct ResponseJson {
    closed_form: String,
    t: Vec<f64>,
    y: Vec<f64>,
    transient: Vec<f64>,
    steady_state: Vec<f64>,
}

fn input_words(i: &Input, discrete: bool) -> String {
    if discrete {
        return match i {
            Input::Impulse => "unit sample δ[k]".into(),
            Input::Step => "unit step 1[k]".into(),
            Input::Ramp => "ramp kT".into(),
            Input::Exp(a) => format!("e^({} kT)", fmt_sig(*a, 6)),
            Input::Sin(w) => format!("sin({} kT)", fmt_sig(*w, 6)),
            Input::Cos(w) => format!("cos({} kT)", fmt_sig(*w, 6)),
            Input::None => "none (initial-condition response)".into(),
        };
    }
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

/// Runs `response` on the factored form of `plant` (its channel or loop when one is chosen).
pub(super) fn run(a: &ResponseArgs, plant: &Plant) -> Result<()> {
    let f = a.plant.factored(plant)?;
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
            closed_form: resp.closed_form.to_string(),
            t: samples.t.clone(),
            y: samples.y.clone(),
            transient: samples.transient.clone(),
            steady_state: samples.steady_state.clone(),
        });
    }
    let seq = resp.closed_form.sequence();
    let mut s = format!("{}\n", text::g_text(plant, &f));
    s.push_str(&format!("Input: {}", input_words(&input, seq.is_some())));
    if !ics.is_empty() {
        let names: Vec<String> = (0..ics.len())
            .map(|k| {
                let name = if seq.is_some() {
                    format!("y[-{}]", k + 1)
                } else {
                    format!("y{}(0)", "'".repeat(k))
                };
                format!("{name} = {}", fmt_sig(ics[k], 6))
            })
            .collect();
        s.push_str(&format!("; initial conditions {}", names.join(", ")));
    }
    s.push_str("\n\n");
    s.push_str(&format!("{}\n", resp.closed_form));
    s.push_str(&format!(
        "  transient (system poles):    {}\n",
        resp.transient.expression()
    ));
    s.push_str(&format!(
        "  steady state (input poles):  {}\n\n",
        resp.steady_state.expression()
    ));
    match seq {
        Some(q) => {
            s.push_str(&format!(
                "{:>12} {:>10} {:>16} {:>16} {:>16}\n",
                "t [s]", "k", "y[k]", "transient", "steady state"
            ));
            for i in 0..samples.t.len() {
                s.push_str(&format!(
                    "{:>12} {:>10} {:>16} {:>16} {:>16}\n",
                    fmt_sig(samples.t[i], 6),
                    q.sample(samples.t[i]),
                    fmt_sig(samples.y[i], 10),
                    fmt_sig(samples.transient[i], 10),
                    fmt_sig(samples.steady_state[i], 10)
                ));
            }
        }
        None => {
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
        }
    }
    let how = if seq.is_some() {
        "Values by exact marching of the difference equation (a time reads the sample at or \
         before it)"
    } else {
        "Values by exact matrix-exponential stepping"
    };
    s.push_str(&format!(
        "\n{how}; the closed form agrees to {} \
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
