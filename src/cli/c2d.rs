//! `ltikit c2d` (sample a continuous-time plant) and `ltikit d2c` (its inverse): the
//! discrete (or continuous) plant, the period, the method and the mapped poles; `--json` in
//! the plant-file schema; `-o F.toml` a plant file that `--plant` reads back.

use anyhow::Result;
use clap::Args;
use nalgebra::DMatrix;
use serde::Serialize;
use std::path::PathBuf;

use super::{PlantArgs, UsageError};
use crate::Root;
use crate::fmt::fmt_num;
use crate::lti::{Discretization, Model, Plant, StateSpace};

#[derive(Args, Debug)]
pub struct C2dArgs {
    /// The continuous-time plant; --dt T is the sampling period of the result.
    #[command(flatten)]
    pub plant: PlantArgs,
    /// zoh | foh | tustin (or bilinear) | matched | impulse.
    #[arg(long, value_name = "METHOD")]
    pub method: String,
    /// Tustin only: the frequency in rad/s where G(z) matches G(s) (0 < W < π/T).
    #[arg(long, value_name = "W", allow_hyphen_values = true)]
    pub prewarp: Option<f64>,
    /// Print one JSON document: {"dt", "method", "num"/"den" or "a"/"b"/"c"/"d", "poles"}.
    #[arg(long)]
    pub json: bool,
    /// Write the discrete plant as a plant file (TOML with dt = T) that --plant reads.
    #[arg(short = 'o', long, value_name = "FILE.toml", value_parser = toml_path)]
    pub output: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct D2cArgs {
    /// The discrete-time plant (with --dt T, or dt = T in its plant file).
    #[command(flatten)]
    pub plant: PlantArgs,
    /// zoh | tustin (or bilinear).
    #[arg(long, value_name = "METHOD")]
    pub method: String,
    /// Tustin only: the prewarp frequency in rad/s the plant was sampled with.
    #[arg(long, value_name = "W", allow_hyphen_values = true)]
    pub prewarp: Option<f64>,
    /// Print one JSON document: {"dt": null, "period", "method", "num"/"den" or "a"/…/"d", "poles"}.
    #[arg(long)]
    pub json: bool,
    /// Write the continuous plant as a plant file (TOML) that --plant reads.
    #[arg(short = 'o', long, value_name = "FILE.toml", value_parser = toml_path)]
    pub output: Option<PathBuf>,
}

/// The value of `-o`: a name ending in `.toml` (a usage error otherwise).
pub(super) fn toml_path(text: &str) -> std::result::Result<PathBuf, String> {
    let path = PathBuf::from(text);
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("toml") => Ok(path),
        _ => Err("the plant is written as a plant file: name it FILE.toml".into()),
    }
}

/// The plant options c2d/d2c do not take (they convert the plant itself).
fn refuse_loop_options(p: &PlantArgs, command: &str) -> Result<()> {
    let given = [
        (p.controller.is_some(), "--controller"),
        (p.open_loop, "--loop"),
        (p.closed_loop, "--closed-loop"),
        (p.sensitivity, "--sensitivity"),
        (p.control_sensitivity, "--control-sensitivity"),
        (p.minreal.is_some(), "--minreal"),
        (p.channel.is_some(), "--channel"),
    ];
    if let Some((_, flag)) = given.iter().find(|(on, _)| *on) {
        return Err(UsageError(format!(
            "{command} converts the plant itself: {flag} is not taken (convert, then analyse the result)"
        ))
        .into());
    }
    Ok(())
}

pub fn run_c2d(a: &C2dArgs) -> Result<()> {
    let mut pa = a.plant.clone();
    let dt = pa
        .dt
        .take()
        .ok_or_else(|| UsageError("c2d needs the sampling period of the result: --dt T".into()))?;
    refuse_loop_options(&pa, "c2d")?;
    let method = Discretization::parse(&a.method, a.prewarp)?;
    let plant = pa.single()?;
    let model = match &plant.model {
        Model::Tf(g) => Model::Tf(g.c2d(dt, method)?),
        Model::Ss(ss) => Model::Ss(ss.c2d(dt, method)?),
    };
    let poles = if is_siso(&plant) {
        plant.factored()?.c2d(dt, method)?.poles().to_vec()
    } else {
        eigen_roots(&model)?
    };
    let name = format!(
        "{} sampled by {} at dt = {} s",
        plant.name,
        method.name(),
        fmt_num(dt)
    );
    finish(
        &model,
        &poles,
        method,
        Some(dt),
        dt,
        &name,
        a.json,
        a.output.as_ref(),
    )
}

pub fn run_d2c(a: &D2cArgs) -> Result<()> {
    refuse_loop_options(&a.plant, "d2c")?;
    let method = Discretization::parse(&a.method, a.prewarp)?;
    let plant = a.plant.single()?;
    let period = plant.domain().require_discrete("d2c")?;
    let model = match &plant.model {
        Model::Tf(g) => Model::Tf(g.d2c(method)?),
        Model::Ss(ss) => Model::Ss(ss.d2c(method)?),
    };
    let poles = if is_siso(&plant) {
        plant.factored()?.d2c(method)?.poles().to_vec()
    } else {
        eigen_roots(&model)?
    };
    let name = format!("{} converted by {} (d2c)", plant.name, method.name());
    finish(
        &model,
        &poles,
        method,
        None,
        period,
        &name,
        a.json,
        a.output.as_ref(),
    )
}

fn is_siso(p: &Plant) -> bool {
    match &p.model {
        Model::Tf(_) => true,
        Model::Ss(ss) => ss.b.ncols() == 1 && ss.c.nrows() == 1,
    }
}

/// The poles of a MIMO result: the eigenvalues of its A with their multiplicities.
fn eigen_roots(model: &Model) -> Result<Vec<Root>> {
    let Model::Ss(ss) = model else {
        return Ok(Vec::new());
    };
    if ss.order() == 0 {
        return Ok(Vec::new());
    }
    let st = crate::numeric::linalg::eigen_structure(&ss.a)?;
    let mut roots: Vec<Root> = st
        .clusters
        .iter()
        .map(|c| Root::new(c.value, c.algebraic))
        .collect();
    crate::poly::roots::sort_roots(&mut roots);
    Ok(roots)
}

fn rows(m: &DMatrix<f64>) -> Vec<Vec<f64>> {
    (0..m.nrows())
        .map(|i| (0..m.ncols()).map(|j| m[(i, j)]).collect())
        .collect()
}

/// The plant-file record of the result (and the model part of the JSON document).
#[derive(Serialize)]
struct Record {
    #[serde(skip_serializing_if = "Option::is_none")]
    name: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    dt: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    num: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    den: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    a: Option<Vec<Vec<f64>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    b: Option<Vec<Vec<f64>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    c: Option<Vec<Vec<f64>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    d: Option<Vec<Vec<f64>>>,
}

fn record(model: &Model, dt: Option<f64>, name: Option<String>) -> Record {
    let mut r = Record {
        name,
        dt,
        num: None,
        den: None,
        a: None,
        b: None,
        c: None,
        d: None,
    };
    match model {
        Model::Tf(g) => {
            r.num = Some(g.num().coeffs().to_vec());
            r.den = Some(g.den().coeffs().to_vec());
        }
        Model::Ss(ss) => {
            r.a = Some(rows(&ss.a));
            r.b = Some(rows(&ss.b));
            r.c = Some(rows(&ss.c));
            r.d = Some(rows(&ss.d));
        }
    }
    r
}

#[derive(Serialize)]
struct Document {
    dt: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    period: Option<f64>,
    method: &'static str,
    prewarp: Option<f64>,
    #[serde(flatten)]
    plant: Record,
    poles: Vec<[f64; 2]>,
}

#[allow(clippy::too_many_arguments)]
fn finish(
    model: &Model,
    poles: &[Root],
    method: Discretization,
    dt: Option<f64>,
    period: f64,
    name: &str,
    json: bool,
    output: Option<&PathBuf>,
) -> Result<()> {
    let prewarp = match method {
        Discretization::Tustin { prewarp } => prewarp,
        _ => None,
    };
    // the file first: an error leaves neither a file nor a report
    if let Some(path) = output {
        let text = toml::to_string(&record(model, dt, Some(name.to_string())))?;
        crate::plot::output::write_atomic(path, text.as_bytes())?;
    }
    if json {
        let doc = Document {
            dt,
            period: dt.is_none().then_some(period),
            method: method.name(),
            prewarp,
            plant: record(model, dt, None),
            poles: poles
                .iter()
                .flat_map(|r| std::iter::repeat_n(super::output::pair(r.value), r.multiplicity))
                .collect(),
        };
        return super::output::print_json(&doc);
    }
    let mut s = String::new();
    let var = if dt.is_some() { "z" } else { "s" };
    match model {
        Model::Tf(g) => s.push_str(&format!("G({var}) = {g}\n")),
        Model::Ss(ss) if ss.b.ncols() == 1 && ss.c.nrows() == 1 => {
            s.push_str(&format!("G({var}) = {}\n", siso_text(ss)?));
            state_space_text(ss, &mut s);
        }
        Model::Ss(ss) => state_space_text(ss, &mut s),
    }
    match dt {
        Some(dt) => s.push_str(&format!("sampling period: dt = {} s\n", fmt_num(dt))),
        None => s.push_str(&format!(
            "continuous time (from the sampling period dt = {} s)\n",
            fmt_num(period)
        )),
    }
    s.push_str(&format!(
        "method: {}{}\n",
        method.name(),
        prewarp.map_or(String::new(), |w| format!(
            " (prewarped at {} rad/s)",
            fmt_num(w)
        ))
    ));
    s.push_str(&format!(
        "poles ({var}): {}\n",
        super::text::roots_text(poles)
    ));
    if let Some(p) = output {
        s.push_str(&format!("written: {}\n", p.display()));
    }
    super::output::print(&s)
}

fn siso_text(ss: &StateSpace) -> Result<String> {
    Ok(ss.to_tf()?.to_string())
}

fn state_space_text(ss: &StateSpace, s: &mut String) {
    for (name, m) in [("A", &ss.a), ("B", &ss.b), ("C", &ss.c), ("D", &ss.d)] {
        super::linearize::matrix(name, &rows(m), s);
    }
}
