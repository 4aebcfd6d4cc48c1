//! `ltikit norm`: the certified H∞ norm (or L∞, or H2) of a plant — the interval
//! \[lower, upper\] with its relative width and the peak frequency; `--json` as one document.
//! Also the plant → state-space step shared by `sigma`, `gram`, `hsv` and `balred`.

use anyhow::Result;
use clap::Args;
use serde::Serialize;

use super::PlantArgs;
use super::output::{print, print_json};
use crate::analysis::norms::{NormKind, PeakGain, hinf_norm, linf_norm};
use crate::fmt::{fmt_num, fmt_sig};
use crate::lti::{Model, StateSpace};

#[derive(Args, Debug)]
pub struct NormArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// The H∞ norm, sup over ω of σ_max(G(jω)) of a stable model (the default): a certified
    /// interval with upper/lower − 1 ≤ 1e-10 (∞ for an unstable model).
    #[arg(long, conflicts_with_all = ["linf", "h2"])]
    pub hinf: bool,
    /// The L∞ norm: the same peak for any model without poles on the imaginary axis (unit
    /// circle).
    #[arg(long, conflicts_with = "h2")]
    pub linf: bool,
    /// The H2 norm √(trace C·P·Cᵀ) from the controllability Gramian's Cholesky factor (∞ for
    /// an unstable model, or with a feedthrough D ≠ 0 in continuous time; a discrete model's
    /// includes D).
    #[arg(long)]
    pub h2: bool,
    /// Print one JSON document: {"norm", "value", "lower", "upper", "relative_gap", "w",
    /// "iterations", "infinite", "states", "inputs", "outputs"} ({"norm": "h2", "value",
    /// "residual", "infinite", …} with --h2).
    #[arg(long)]
    pub json: bool,
}

/// The plant as a state-space model: a state-space plant itself; a transfer function, a
/// channel or a loop selection (T, S, C·S, L) as the cascade realisation of its reduced
/// factored form. Returns the name shown in reports too.
pub(crate) fn plant_state_space(pa: &PlantArgs) -> Result<(String, StateSpace)> {
    let plant = pa.single()?;
    let as_is = plant.selection.is_none()
        && pa.channel.is_none()
        && pa.pade.is_none()
        && pa.minreal.is_none()
        && pa.sample.is_none();
    if let (Model::Ss(ss), true) = (&plant.model, as_is) {
        return Ok((plant.name.clone(), ss.clone()));
    }
    let f = pa.factored(&plant)?;
    Ok((plant.name.clone(), f.norm_realization()?))
}

#[derive(Serialize)]
struct NormJson<'a> {
    norm: NormKind,
    value: f64,
    lower: f64,
    upper: f64,
    relative_gap: f64,
    w: f64,
    iterations: usize,
    infinite: Option<&'a str>,
    states: usize,
    inputs: usize,
    outputs: usize,
}

#[derive(Serialize)]
struct H2Json<'a> {
    norm: &'static str,
    value: f64,
    residual: f64,
    infinite: Option<&'a str>,
    states: usize,
    inputs: usize,
    outputs: usize,
}

pub fn run(a: &NormArgs) -> Result<()> {
    let (name, ss) = plant_state_space(&a.plant)?;
    if a.h2 {
        let n = crate::analysis::norms::h2_norm(&ss)?;
        if a.json {
            return print_json(&H2Json {
                norm: "h2",
                value: n.value,
                residual: n.residual,
                infinite: n.infinite.as_deref(),
                states: ss.order(),
                inputs: ss.n_inputs(),
                outputs: ss.n_outputs(),
            });
        }
        let mut s = format!("H2 norm of {name}\n  model:     {}\n", dims(&ss));
        match &n.infinite {
            Some(why) => s.push_str(&format!("  value:     ∞ — {why}\n")),
            None => s.push_str(&format!(
                "  value:     {}\n  Gramian residual (relative): {}\n",
                fmt_sig(n.value, 15),
                fmt_sig(n.residual, 2)
            )),
        }
        return print(&s);
    }
    let n = if a.linf {
        linf_norm(&ss)?
    } else {
        hinf_norm(&ss)?
    };
    if a.json {
        return print_json(&NormJson {
            norm: n.kind,
            value: n.value(),
            lower: n.lower,
            upper: n.upper,
            relative_gap: n.relative_gap(),
            w: n.w,
            iterations: n.iterations,
            infinite: n.infinite.as_deref(),
            states: ss.order(),
            inputs: ss.n_inputs(),
            outputs: ss.n_outputs(),
        });
    }
    print(&peak_text(&name, &ss, &n))
}

/// The text report of a peak gain.
pub(crate) fn peak_text(name: &str, ss: &StateSpace, n: &PeakGain) -> String {
    let mut s = format!(
        "{} norm of {name}\n  model:     {}\n",
        n.kind.symbol(),
        dims(ss)
    );
    if let Some(why) = &n.infinite {
        s.push_str(&format!("  value:     ∞ — {why}\n"));
        return s;
    }
    s.push_str(&format!("  value:     {}\n", fmt_sig(n.value(), 12)));
    s.push_str(&format!(
        "  certified: [{}, {}] (upper/lower − 1 = {})\n",
        fmt_sig(n.lower, 15),
        fmt_sig(n.upper, 15),
        fmt_sig(n.relative_gap(), 2)
    ));
    let w = if n.w.is_infinite() {
        "ω → ∞ (the feedthrough D)".to_string()
    } else {
        format!("ω = {} rad/s", fmt_sig(n.w, 10))
    };
    s.push_str(&format!(
        "  peak at:   {w}\n  Hamiltonian eigenvalue problems: {}\n",
        n.iterations
    ));
    s
}

/// "2 states, 1 input, 1 output" (", discrete, dt = T s" for a discrete model).
pub(crate) fn dims(ss: &StateSpace) -> String {
    let count = |k: usize, what: &str| format!("{k} {what}{}", if k == 1 { "" } else { "s" });
    format!(
        "{}, {}, {}{}",
        count(ss.order(), "state"),
        count(ss.n_inputs(), "input"),
        count(ss.n_outputs(), "output"),
        match ss.domain.dt() {
            Some(dt) => format!(", discrete, dt = {} s", fmt_num(dt)),
            None => String::new(),
        }
    )
}
