//! The state-space report of `response`, by exact discretisation ([`crate::analysis::ss`]): a
//! step or impulse on each input with every output, the initial-state response (`--x0`), the
//! states (`--states`), and `lsim` with an input signal from a CSV file (`--input-file`,
//! `--hold zoh|foh`).

use anyhow::{Result, bail};
use serde::Serialize;

use super::args::ResponseArgs;
use crate::analysis::Input;
use crate::analysis::ss::{Hold, SsTimeResponse};
use crate::cli::output::{Stream, json_number, json_value, pretty};
use crate::cli::{Plant, channels, input_file, parse};
use crate::fmt::fmt_sig;
use crate::lti::StateSpace;
use crate::numeric::tol::AXIS_REL_TOL;

// Most values (times × (outputs + states) × responses) of one state-space response.
use crate::limits::MAX_RESPONSE_VALUES;

/// The head of the `response` JSON document of a state-space plant (its `responses` are
/// written by [`stream_json`]).
#[derive(Serialize)]
struct SsResponseJson {
    model: &'static str,
    name: String,
    states: usize,
    inputs: Vec<String>,
    outputs: Vec<String>,
    state_names: Vec<String>,
    x0: Option<Vec<f64>>,
}

/// Runs `response` on the state-space model of `plant` (its chosen channel, if any).
pub(super) fn run(a: &ResponseArgs, plant: &Plant) -> Result<()> {
    let channel = a.plant.channel()?;
    let ss = channel_model(plant, channel)?;
    let (inputs, outputs) = signal_names(plant, channel);
    let x0 = match &a.x0 {
        Some(s) => Some(parse::numbers(s, "--x0")?),
        None => None,
    };
    let hold = match a.hold.as_str() {
        "zoh" => Hold::Zero,
        "foh" => Hold::First,
        other => bail!(
            "--hold '{}': expected zoh or foh",
            crate::error::abbreviate(other)
        ),
    };
    let mut responses = Vec::new();
    if let Some(path) = &a.input_file {
        let sig = input_file::read(path, ss.n_inputs())?;
        check_size(&ss, sig.t.len(), 1, a.states)?;
        let r = ss.lsim(&sig, hold, x0.as_deref(), a.states)?;
        let text = format!(
            "lsim: {} samples from {} ({})",
            sig.t.len(),
            path.display(),
            if hold == Hold::Zero {
                "zero-order hold"
            } else {
                "first-order hold"
            }
        );
        responses.push((None, "lsim", text, r));
    } else {
        let t = times(a, &ss)?;
        let input: Input = a.input.parse()?;
        let free = match &x0 {
            Some(x) => Some(ss.initial_response(x, &t, a.states)?),
            None => None,
        };
        let per_input = match input {
            Input::Step | Input::Impulse => ss.n_inputs(),
            Input::None => 0,
            other => bail!(
                "--input {other}: a state-space response takes step, impulse or none (use \
                 --input-file for another signal)"
            ),
        };
        check_size(&ss, t.len(), per_input.max(1), a.states)?;
        for i in 0..per_input {
            let mut r = if matches!(input, Input::Step) {
                ss.step_response_from(i, &t, a.states)?
            } else {
                ss.impulse_response_from(i, &t, a.states)?
            };
            if let Some(f) = &free {
                add(&mut r, f);
            }
            let kind = if matches!(input, Input::Step) {
                "step"
            } else {
                "impulse"
            };
            let text = format!(
                "unit {kind} on input {}{}",
                inputs.get(i).map_or("?", |x| x),
                if free.is_some() {
                    ", from x(0) = x0"
                } else {
                    ""
                }
            );
            responses.push((Some(i), kind, text, r));
        }
        if per_input == 0 {
            let Some(f) = free else {
                bail!("--input none needs --x0 (the initial state) for a state-space plant");
            };
            responses.push((None, "initial", "initial state x(0) = x0, u = 0".into(), f));
        }
    }
    let mut out = Stream::stdout();
    if a.json {
        let head = SsResponseJson {
            model: "state-space",
            name: plant.name.clone(),
            states: ss.order(),
            inputs: inputs.clone(),
            outputs: outputs.clone(),
            state_names: plant.signals.states.clone(),
            x0,
        };
        return stream_json(out, &head, &inputs, &responses);
    }
    // The text report, written table by table and row block by row block.
    let mut open = out.put(&channels::plant_header(plant))?;
    for (_, _, head, r) in &responses {
        if !open {
            break;
        }
        open = out.put(&format!("\n── {head}\n"))?;
        open = open && table(r, &outputs, &plant.signals.states, &mut out)?;
    }
    if open {
        out.put(match plant.domain().dt() {
            Some(_) => {
                "\nValues by the recursion x[k+1] = A x[k] + B u[k] (powers of the augmented \
                 matrix over each gap; a time between samples reads the sample before it).\n"
            }
            None => {
                "\nValues by exact discretisation (matrix exponential of the augmented matrix \
                 and a recursion).\n"
            }
        })?;
    }
    out.finish()
}

/// One response of the JSON document, and its head fields.
type Labelled = (Option<usize>, &'static str, String, SsTimeResponse);

/// The JSON document, formatted as `print_json` would and written as it is formatted (the
/// numbers are not copied into a JSON tree).
fn stream_json(
    mut out: Stream,
    head: &SsResponseJson,
    inputs: &[String],
    responses: &[Labelled],
) -> Result<()> {
    let mut text = String::from("{\n");
    let v = json_value(head)?;
    for (k, x) in v.as_object().into_iter().flatten() {
        text.push_str(&format!("  {}: ", serde_json::Value::String(k.clone())));
        pretty(x, 1, &mut text);
        text.push_str(",\n");
    }
    text.push_str("  \"responses\": [");
    for (n, (i, kind, _, r)) in responses.iter().enumerate() {
        text.push_str(if n == 0 { "\n    {\n" } else { ",\n    {\n" });
        let fields = serde_json::json!({
            "input": i.map(|i| i + 1),
            "input_name": i.and_then(|i| inputs.get(i).cloned()),
            "kind": kind,
        });
        for (k, x) in fields.as_object().into_iter().flatten() {
            text.push_str(&format!("      {}: ", serde_json::Value::String(k.clone())));
            pretty(x, 3, &mut text);
            text.push_str(",\n");
        }
        text.push_str("      \"t\": ");
        if !numbers(&mut out, &mut text, &r.t)? {
            return out.finish();
        }
        text.push_str(",\n      \"y\": ");
        if !rows(&mut out, &mut text, &r.y)? {
            return out.finish();
        }
        if let Some(x) = &r.x {
            text.push_str(",\n      \"x\": ");
            if !rows(&mut out, &mut text, x)? {
                return out.finish();
            }
        }
        text.push_str("\n    }");
    }
    text.push_str(if responses.is_empty() {
        "]\n}\n"
    } else {
        "\n  ]\n}\n"
    });
    out.put(&text)?;
    out.finish()
}

/// `[a, b, …]` appended to `text`, flushed to `out` in blocks; false once the reader has gone.
fn numbers(out: &mut Stream, text: &mut String, v: &[f64]) -> Result<bool> {
    text.push('[');
    for (i, x) in v.iter().enumerate() {
        if i > 0 {
            text.push_str(", ");
        }
        text.push_str(&json_number(*x));
        if text.len() >= 1 << 16 {
            if !out.put(text)? {
                return Ok(false);
            }
            text.clear();
        }
    }
    text.push(']');
    Ok(true)
}

/// An array of number arrays, one per line (at the indentation of a response's fields).
fn rows(out: &mut Stream, text: &mut String, v: &[Vec<f64>]) -> Result<bool> {
    if v.is_empty() {
        text.push_str("[]");
        return Ok(true);
    }
    text.push_str("[\n");
    for (j, row) in v.iter().enumerate() {
        text.push_str("        ");
        if !numbers(out, text, row)? {
            return Ok(false);
        }
        text.push_str(if j + 1 < v.len() { ",\n" } else { "\n" });
    }
    text.push_str("      ]");
    Ok(true)
}

/// The model, or its chosen channel (input, output).
fn channel_model(plant: &Plant, channel: Option<(usize, usize)>) -> Result<StateSpace> {
    let ss = plant.state_space()?;
    Ok(match channel {
        Some((i, o)) => ss.channel(i, o)?,
        None => ss,
    })
}

/// The input and output names (those of the chosen channel).
fn signal_names(plant: &Plant, channel: Option<(usize, usize)>) -> (Vec<String>, Vec<String>) {
    let sig = &plant.signals;
    match channel {
        Some((i, o)) => (
            sig.inputs.get(i).cloned().into_iter().collect(),
            sig.outputs.get(o).cloned().into_iter().collect(),
        ),
        None => (sig.inputs.clone(), sig.outputs.clone()),
    }
}

/// Adds the free response `f` (same times) to `r`.
fn add(r: &mut SsTimeResponse, f: &SsTimeResponse) {
    for (a, b) in r.y.iter_mut().zip(&f.y) {
        a.iter_mut().zip(b).for_each(|(x, y)| *x += y);
    }
    if let (Some(rx), Some(fx)) = (&mut r.x, &f.x) {
        for (a, b) in rx.iter_mut().zip(fx) {
            a.iter_mut().zip(b).for_each(|(x, y)| *x += y);
        }
    }
}

fn check_size(ss: &StateSpace, times: usize, responses: usize, states: bool) -> Result<()> {
    let per_time = ss.n_outputs() + if states { ss.order() } else { 0 };
    let total = times.saturating_mul(per_time).saturating_mul(responses);
    if total > MAX_RESPONSE_VALUES {
        bail!(
            "{times} times × {per_time} values × {responses} responses exceeds \
             {MAX_RESPONSE_VALUES} values: give fewer times, a channel, or leave out --states"
        );
    }
    Ok(())
}

/// The times: --t, or 11 points over a window from the eigenvalues of A.
fn times(a: &ResponseArgs, ss: &StateSpace) -> Result<Vec<f64>> {
    let t = match &a.t {
        Some(s) => parse::numbers(s, "--t")?,
        None => {
            let span = auto_span(ss)?;
            (0..=10).map(|i| span * i as f64 / 10.0).collect()
        }
    };
    if t.is_empty() {
        bail!("--t: no times given");
    }
    Ok(t)
}

/// A window that shows the response: five time constants of the slowest decaying mode, or
/// four periods of the slowest oscillation when nothing decays (10 s when neither).
fn auto_span(ss: &StateSpace) -> Result<f64> {
    let eig = ss.eigenvalues()?;
    let scale = eig.iter().map(|z| z.norm()).fold(0.0, f64::max);
    let small = AXIS_REL_TOL * scale;
    let decay = eig
        .iter()
        .filter(|z| z.re < -small)
        .map(|z| -z.re)
        .fold(f64::INFINITY, f64::min);
    let osc = eig
        .iter()
        .filter(|z| z.im.abs() > small)
        .map(|z| z.im.abs())
        .fold(f64::INFINITY, f64::min);
    let span = if decay.is_finite() && eig.iter().all(|z| z.re < -small) {
        5.0 / decay
    } else if osc.is_finite() {
        8.0 * std::f64::consts::PI / osc
    } else if decay.is_finite() {
        5.0 / decay
    } else {
        10.0
    };
    Ok(if span.is_finite() && span > 0.0 {
        span
    } else {
        10.0
    })
}

/// A table: t, every output, and the states when kept; written to `out` in blocks. False
/// once the reader has gone.
fn table(
    r: &SsTimeResponse,
    outputs: &[String],
    states: &[String],
    out: &mut Stream,
) -> Result<bool> {
    let mut cols: Vec<(&str, &Vec<f64>)> =
        outputs.iter().map(String::as_str).zip(r.y.iter()).collect();
    let generated: Vec<String>;
    if let Some(x) = &r.x {
        let names = if states.len() == x.len() {
            states
        } else {
            generated = (1..=x.len()).map(|k| format!("x{k}")).collect();
            &generated
        };
        cols.extend(names.iter().map(String::as_str).zip(x.iter()));
    }
    let width = |name: &str| name.chars().count().max(14);
    let mut s = format!("{:>12}", "t [s]");
    for (name, _) in &cols {
        s.push_str(&format!("  {:>w$}", name, w = width(name)));
    }
    s.push('\n');
    for (k, t) in r.t.iter().enumerate() {
        s.push_str(&format!("{:>12}", fmt_sig(*t, 6)));
        for (name, v) in &cols {
            let x = v.get(k).copied().unwrap_or(f64::NAN);
            s.push_str(&format!("  {:>w$}", fmt_sig(x, 10), w = width(name)));
        }
        s.push('\n');
        if s.len() >= 1 << 16 {
            if !out.put(&s)? {
                return Ok(false);
            }
            s.clear();
        }
    }
    out.put(&s)
}
