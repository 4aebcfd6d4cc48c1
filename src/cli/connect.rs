//! `ltikit series|parallel|feedback A.toml B.toml` (two plant files joined) and
//! `ltikit connect DIAGRAM.toml` (a diagram file closed into one model): the resulting model,
//! its poles and dc gain; `--json` in the plant-file schema; `-o F.toml` a plant file that
//! `--plant` reads back.
//!
//! Two transfer functions give a transfer function (the methods of `lti::interconnect`, no
//! cancellation); anything with a state-space model gives state space.

use anyhow::Result;
use clap::Args;
use serde::Serialize;
use std::path::{Path, PathBuf};

use super::UsageError;
use super::c2d::{Record, eigen_roots, record, siso_text, state_space_text, toml_path};
use crate::Root;
use crate::fmt::fmt_num;
use crate::lti::connect::state_space_of;
use crate::lti::{Model, Plant, TransferFunction};

/// `series` and the shared options.
#[derive(Args, Debug)]
pub struct SeriesArgs {
    /// The first model (a plant or diagram file): the signal goes through it first.
    #[arg(value_name = "A.toml")]
    pub first: PathBuf,
    /// The second model: the result is B·A (its inputs are A's outputs).
    #[arg(value_name = "B.toml")]
    pub second: PathBuf,
    /// Print one JSON document: {"operation", "sign", "dt", "num"/"den" or "a"/"b"/"c"/"d",
    /// "poles", "dc_gain"}.
    #[arg(long)]
    pub json: bool,
    /// Write the result as a plant file (TOML) that --plant reads.
    #[arg(short = 'o', long, value_name = "FILE.toml", value_parser = toml_path)]
    pub output: Option<PathBuf>,
}

/// `parallel`: A + sign·B.
#[derive(Args, Debug)]
pub struct ParallelArgs {
    #[command(flatten)]
    pub pair: SeriesArgs,
    /// +1 (default): A + B; -1: A − B.
    #[arg(
        long,
        value_name = "±1",
        allow_hyphen_values = true,
        default_value = "1"
    )]
    pub sign: f64,
}

/// `feedback`: G with H in the loop.
#[derive(Args, Debug)]
pub struct FeedbackArgs {
    #[command(flatten)]
    pub pair: SeriesArgs,
    /// -1 (default): negative feedback, G/(1 + G·H); +1: positive feedback, G/(1 − G·H).
    #[arg(
        long,
        value_name = "±1",
        allow_hyphen_values = true,
        default_value = "-1"
    )]
    pub sign: f64,
}

/// `connect`: a diagram file.
#[derive(Args, Debug)]
pub struct ConnectArgs {
    /// The diagram file (TOML with [blocks], [sums], inputs and outputs).
    #[arg(value_name = "DIAGRAM.toml")]
    pub diagram: PathBuf,
    /// Print one JSON document: {"operation", "dt", "inputs", "outputs", "a", "b", "c", "d",
    /// "poles", "dc_gain"}.
    #[arg(long)]
    pub json: bool,
    /// Write the connected model as a plant file (TOML) that --plant reads.
    #[arg(short = 'o', long, value_name = "FILE.toml", value_parser = toml_path)]
    pub output: Option<PathBuf>,
}

/// The interconnection of two models.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Operation {
    Series,
    Parallel(f64),
    Feedback(f64),
}

impl Operation {
    fn name(self) -> &'static str {
        match self {
            Operation::Series => "series",
            Operation::Parallel(_) => "parallel",
            Operation::Feedback(_) => "feedback",
        }
    }

    fn sign(self) -> Option<f64> {
        match self {
            Operation::Series => None,
            Operation::Parallel(s) | Operation::Feedback(s) => Some(s),
        }
    }
}

pub fn run_series(a: &SeriesArgs) -> Result<()> {
    run_pair(a, Operation::Series)
}

pub fn run_parallel(a: &ParallelArgs) -> Result<()> {
    run_pair(&a.pair, Operation::Parallel(check_sign(a.sign)?))
}

pub fn run_feedback(a: &FeedbackArgs) -> Result<()> {
    run_pair(&a.pair, Operation::Feedback(check_sign(a.sign)?))
}

fn check_sign(sign: f64) -> Result<f64> {
    if [1.0, -1.0].contains(&sign) {
        Ok(sign)
    } else {
        Err(UsageError(format!(
            "--sign {}: the sign is -1 or +1",
            crate::error::abbreviate(&fmt_num(sign))
        ))
        .into())
    }
}

/// Loads a plant file for an interconnection: the plant itself (a `[controller]` section is
/// refused: it would be silently left out).
fn load(path: &Path) -> Result<Plant> {
    let p = Plant::from_file(path)?;
    if p.controller.is_some() {
        anyhow::bail!(
            "{}: the plant file has a [controller] section; connect the controller as a model \
             of its own (a plant file or a diagram block)",
            crate::error::abbreviate(&path.display().to_string())
        );
    }
    Ok(p)
}

fn run_pair(a: &SeriesArgs, op: Operation) -> Result<()> {
    let (p1, p2) = (load(&a.first)?, load(&a.second)?);
    let model = combine(&p1.model, &p2.model, op)?;
    let name = match op {
        Operation::Series => format!("series: {}, then {}", p1.name, p2.name),
        Operation::Parallel(s) => format!(
            "parallel: {} {} {}",
            p1.name,
            if s > 0.0 { "+" } else { "−" },
            p2.name
        ),
        Operation::Feedback(s) => format!(
            "feedback ({}): G = {}, H = {}",
            if s > 0.0 { "positive" } else { "negative" },
            p1.name,
            p2.name
        ),
    };
    finish(
        &model,
        &name,
        op.name(),
        op.sign(),
        a.json,
        a.output.as_ref(),
    )
}

/// The two models joined: transfer functions stay transfer functions, anything else becomes
/// state space.
fn combine(g1: &Model, g2: &Model, op: Operation) -> Result<Model> {
    if let (Model::Tf(a), Model::Tf(b)) = (g1, g2) {
        return Ok(Model::Tf(match op {
            Operation::Series => a.series(b)?,
            Operation::Parallel(s) => a.parallel(&b.series(&TransferFunction::constant(s))?)?,
            Operation::Feedback(s) => {
                well_posed_tf(a, b, s)?;
                a.feedback(b, s)?
            }
        }));
    }
    let a = state_space_of(g1, &format!("the {} model", ordinal(1)))?;
    let mut b = state_space_of(g2, &format!("the {} model", ordinal(2)))?;
    Ok(Model::Ss(match op {
        Operation::Series => a.series(&b)?,
        Operation::Parallel(s) => {
            b.c *= s;
            b.d *= s;
            a.parallel(&b)?
        }
        Operation::Feedback(s) => a.feedback(&b, s)?,
    }))
}

/// Errors when 1 − sign·G(∞)·H(∞) = 0 for proper G and H: the algebraic loop through the
/// feedthroughs is not well posed (the closed loop would be improper or undefined).
fn well_posed_tf(g: &TransferFunction, h: &TransferFunction, sign: f64) -> Result<()> {
    let at_infinity = |t: &TransferFunction| {
        if t.num().degree() == t.den().degree() {
            t.num().leading() / t.den().leading()
        } else {
            0.0
        }
    };
    if !(g.is_proper() && h.is_proper()) {
        return Ok(());
    }
    let loop_gain = sign * at_infinity(g) * at_infinity(h);
    if (1.0 - loop_gain).abs() <= 1e-12 * loop_gain.abs().max(1.0) {
        anyhow::bail!(
            "feedback: 1 {} D_G·D_H = 0 (D = the gains at infinite frequency, {} and {}): the \
             algebraic loop is not well posed",
            if sign < 0.0 { "+" } else { "−" },
            fmt_num(at_infinity(g)),
            fmt_num(at_infinity(h))
        );
    }
    Ok(())
}

fn ordinal(k: usize) -> &'static str {
    if k == 1 { "first" } else { "second" }
}

pub fn run_connect(a: &ConnectArgs) -> Result<()> {
    let p = Plant::from_file(&a.diagram)?;
    let name = p.name.clone();
    if let Some(path) = &a.output {
        write_plant(&p.model, &name, Some(&p.signals), path)?;
    }
    report(
        &p.model,
        &name,
        "connect",
        None,
        Some(&p.signals),
        a.json,
        a.output.as_ref(),
    )
}

fn finish(
    model: &Model,
    name: &str,
    operation: &'static str,
    sign: Option<f64>,
    json: bool,
    output: Option<&PathBuf>,
) -> Result<()> {
    // the file first: an error leaves neither a file nor a report
    if let Some(path) = output {
        write_plant(model, name, None, path)?;
    }
    report(model, name, operation, sign, None, json, output)
}

/// The plant file of `model` (with the signal names of a diagram).
#[derive(Serialize)]
struct PlantRecord {
    #[serde(flatten)]
    model: Record,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    inputs: Vec<String>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    outputs: Vec<String>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    states: Vec<String>,
}

fn write_plant(
    model: &Model,
    name: &str,
    signals: Option<&crate::lti::Signals>,
    path: &Path,
) -> Result<()> {
    let dt = domain_dt(model);
    let r = PlantRecord {
        model: record(model, dt, Some(name.to_string())),
        inputs: signals.map(|s| s.inputs.clone()).unwrap_or_default(),
        outputs: signals.map(|s| s.outputs.clone()).unwrap_or_default(),
        states: signals.map(|s| s.states.clone()).unwrap_or_default(),
    };
    let text = toml::to_string(&r)?;
    crate::plot::output::write_atomic(path, text.as_bytes())?;
    Ok(())
}

fn domain_dt(model: &Model) -> Option<f64> {
    match model {
        Model::Tf(g) => g.domain().dt(),
        Model::Ss(ss) => ss.domain.dt(),
    }
}

#[derive(Serialize)]
struct Document {
    operation: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    sign: Option<f64>,
    dt: Option<f64>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    inputs: Vec<String>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    outputs: Vec<String>,
    #[serde(flatten)]
    plant: Record,
    poles: Vec<[f64; 2]>,
    /// Rows = outputs, columns = inputs; null where infinite.
    dc_gain: Vec<Vec<Option<f64>>>,
}

/// The poles of the result (the transfer function's characteristic roots, or the eigenvalues
/// of A) and its dc gain per channel (`None` where infinite).
/// The dc gain of each channel, rows = outputs (`None` where infinite).
type DcGains = Vec<Vec<Option<f64>>>;

fn poles_and_dc(model: &Model) -> Result<(Vec<Root>, DcGains)> {
    match model {
        Model::Tf(g) => {
            let f = g.factored()?;
            Ok((f.poles().to_vec(), vec![vec![f.dc_gain()]]))
        }
        Model::Ss(ss) => {
            let poles = eigen_roots(model)?;
            let dc = (0..ss.n_outputs())
                .map(|o| {
                    (0..ss.n_inputs())
                        .map(|i| {
                            let f =
                                crate::analysis::Factored::from_state_space(&ss.channel(i, o)?)?;
                            Ok(f.dc_gain())
                        })
                        .collect::<crate::error::Result<Vec<_>>>()
                })
                .collect::<crate::error::Result<Vec<_>>>()?;
            Ok((poles, dc))
        }
    }
}

fn report(
    model: &Model,
    name: &str,
    operation: &'static str,
    sign: Option<f64>,
    signals: Option<&crate::lti::Signals>,
    json: bool,
    output: Option<&PathBuf>,
) -> Result<()> {
    let dt = domain_dt(model);
    let (poles, dc) = poles_and_dc(model)?;
    if json {
        let doc = Document {
            operation,
            sign,
            dt,
            inputs: signals.map(|s| s.inputs.clone()).unwrap_or_default(),
            outputs: signals.map(|s| s.outputs.clone()).unwrap_or_default(),
            plant: record(model, dt, None),
            poles: poles
                .iter()
                .flat_map(|r| std::iter::repeat_n(super::output::pair(r.value), r.multiplicity))
                .collect(),
            dc_gain: dc,
        };
        return super::output::print_json(&doc);
    }
    let var = if dt.is_some() { "z" } else { "s" };
    let mut s = format!("{name}\n");
    match model {
        Model::Tf(g) => s.push_str(&format!("G({var}) = {g}\n")),
        Model::Ss(ss) if ss.n_inputs() == 1 && ss.n_outputs() == 1 => {
            s.push_str(&format!("G({var}) = {}\n", siso_text(ss)?));
            state_space_text(ss, &mut s);
        }
        Model::Ss(ss) => state_space_text(ss, &mut s),
    }
    if let Some(sig) = signals {
        s.push_str(&format!(
            "inputs: {}; outputs: {}\n",
            sig.inputs.join(", "),
            sig.outputs.join(", ")
        ));
    }
    if let Some(dt) = dt {
        s.push_str(&format!("sampling period: dt = {} s\n", fmt_num(dt)));
    }
    s.push_str(&format!(
        "poles ({var}): {}\n",
        super::text::roots_text(&poles)
    ));
    let dc_text: Vec<String> = dc
        .iter()
        .map(|row| {
            row.iter()
                .map(|x| x.map_or("∞".to_string(), |v| crate::fmt::fmt_sig(v, 7)))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    s.push_str(&format!("dc gain: {}\n", dc_text.join("; ")));
    if let Some(p) = output {
        s.push_str(&format!("written: {}\n", p.display()));
    }
    super::output::print(&s)
}
