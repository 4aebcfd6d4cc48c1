//! `ltikit place`: the state feedback u = −K x that puts the eigenvalues of A − BK at the
//! requested poles (Ackermann for one input, Kautsky–Nichols–Van Dooren for several), with
//! the achieved poles, their distance to the requested ones and a condition figure.

use anyhow::Result;
use clap::Args;
use serde::Serialize;

use super::PlantArgs;
use super::design::{design_plant, rows, title, var};
use super::output::{pair, print, print_json};
use crate::analysis::design::poles::complex_label;
use crate::analysis::design::{PlacementMethod, parse_poles, place};
use crate::fmt::fmt_sig;

#[derive(Args, Debug)]
pub struct PlaceArgs {
    /// The plant (state space, or a transfer function realised in controllable canonical
    /// form; --dt T for a discrete plant: the poles are then in z).
    #[command(flatten)]
    pub plant: PlantArgs,
    /// The closed-loop poles, as many as states, complex ones in conjugate pairs:
    /// --poles "-1, -2+1j, -2-1j".
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub poles: String,
    /// Print one JSON document: {"dt", "method", "k", "requested", "achieved", "distance",
    /// "relative_error", "condition", "iterations"}.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct PlaceJson {
    method: &'static str,
    k: Vec<Vec<f64>>,
    requested: Vec<[f64; 2]>,
    achieved: Vec<[f64; 2]>,
    distance: Vec<f64>,
    relative_error: f64,
    condition: Option<f64>,
    iterations: usize,
    note: Option<String>,
}

pub fn run(a: &PlaceArgs) -> Result<()> {
    let (plant, ss) = design_plant(&a.plant, "place")?;
    let poles = parse_poles(&a.poles)?;
    let p = place(&ss, &poles)?;
    let note = p.conditioning_note();
    if a.json {
        return print_json(&PlaceJson {
            method: p.method.name(),
            k: rows(&p.gain),
            requested: p.requested.iter().map(|z| pair(*z)).collect(),
            achieved: p.achieved.iter().map(|z| pair(*z)).collect(),
            distance: p.distance.clone(),
            relative_error: p.relative_error,
            condition: super::output::finite(p.condition),
            iterations: p.iterations,
            note,
        });
    }
    let mut s = title("Pole placement", &plant, &ss);
    match p.method {
        PlacementMethod::Ackermann => s.push_str(&format!(
            "method: Ackermann's formula (one input); condition number of the controllability \
             matrix κ(W_c) = {}\n",
            fmt_sig(p.condition, 3)
        )),
        PlacementMethod::Knv0 => s.push_str(&format!(
            "method: Kautsky–Nichols–Van Dooren (method 0, {} sweep{}); condition number of \
             the closed-loop eigenvectors κ(X) = {}\n",
            p.iterations,
            if p.iterations == 1 { "" } else { "s" },
            fmt_sig(p.condition, 3)
        )),
    }
    s.push_str("state feedback u = -K x:\n");
    super::linearize::matrix("K", &rows(&p.gain), &mut s);
    let v = var(&ss);
    s.push_str(&format!(
        "\n    {:<28} {:<28} {}\n",
        format!("requested ({v})"),
        format!("achieved eig(A - BK)"),
        "distance"
    ));
    for ((r, z), d) in p.requested.iter().zip(&p.achieved).zip(&p.distance) {
        s.push_str(&format!(
            "    {:<28} {:<28} {}\n",
            complex_label(*r, 10),
            complex_label(*z, 10),
            fmt_sig(*d, 2)
        ));
    }
    s.push_str(&format!(
        "largest distance / largest requested |pole|: {}\n",
        fmt_sig(p.relative_error, 2)
    ));
    if let Some(n) = note {
        super::warn(n);
    }
    print(&s)
}
