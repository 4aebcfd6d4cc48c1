//! `ltikit balred`: square-root balanced truncation to `--order k` or `--error e`, the a
//! priori bound beside the certified measured error, the reduced model (`-o F.toml` as a
//! plant file the other commands read).

use anyhow::{Result, bail};
use clap::Args;
use serde::Serialize;
use std::path::PathBuf;

use super::PlantArgs;
use super::c2d::{Record, record, rows, toml_path};
use super::linearize::matrix;
use super::norm::{dims, plant_state_space};
use super::output::{print, print_json};
use crate::analysis::norms::{ReducedOrder, balanced_truncation};
use crate::fmt::fmt_sig;
use crate::lti::Model;

#[derive(Args, Debug)]
pub struct BalredArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// The order k of the reduced model.
    #[arg(
        long,
        value_name = "K",
        conflicts_with = "error",
        required_unless_present = "error"
    )]
    pub order: Option<usize>,
    /// The smallest order whose bound 2·Σ_{i>k} σᵢ is at most E.
    #[arg(long, value_name = "E", allow_hyphen_values = true)]
    pub error: Option<f64>,
    /// Write the reduced model as a plant file (TOML, a, b, c, d and dt) that --plant reads.
    #[arg(short = 'o', long, value_name = "FILE.toml", value_parser = toml_path)]
    pub output: Option<PathBuf>,
    /// Print one JSON document: {"states", "order", "hsv", "bound", "error", "residuals",
    /// "dt", "a", "b", "c", "d"}.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct ErrorJson {
    lower: f64,
    upper: f64,
    w: f64,
}

#[derive(Serialize)]
struct BalredJson {
    states: usize,
    order: usize,
    hsv: Vec<f64>,
    bound: f64,
    error: ErrorJson,
    residuals: [f64; 2],
    #[serde(flatten)]
    reduced: Record,
}

pub fn run(a: &BalredArgs) -> Result<()> {
    let order = match (a.order, a.error) {
        (Some(k), _) => ReducedOrder::Order(k),
        (None, Some(e)) => ReducedOrder::Error(e),
        (None, None) => bail!("balred needs --order K or --error E"),
    };
    let (name, ss) = plant_state_space(&a.plant)?;
    let r = balanced_truncation(&ss, order)?;
    let k = r.reduced.order();
    let dt = r.reduced.domain.dt();
    let model = Model::Ss(r.reduced.clone());
    // the file first: an error leaves neither a file nor a report
    if let Some(path) = &a.output {
        let title = format!("{name} reduced to {k} states by balanced truncation");
        let text = toml::to_string(&record(&model, dt, Some(title)))?;
        crate::plot::output::write_atomic(path, text.as_bytes())?;
    }
    if a.json {
        return print_json(&BalredJson {
            states: ss.order(),
            order: k,
            hsv: r.hsv.clone(),
            bound: r.bound,
            error: ErrorJson {
                lower: r.error.lower,
                upper: r.error.upper,
                w: r.error.w,
            },
            residuals: [r.residuals.0, r.residuals.1],
            reduced: record(&model, dt, None),
        });
    }
    let mut s = format!(
        "Balanced truncation of {name}\n  model:   {}\n  reduced: {k} states\n",
        dims(&ss)
    );
    // the two values in one column (the labels' widths counted in characters)
    let bound_label = format!("a priori bound 2·Σ_{{i>{k}}} σᵢ:");
    let error_label = "measured ‖G − G_r‖∞:";
    let width = bound_label.chars().count().max(error_label.chars().count()) + 1;
    let pad = |l: &str| format!("{l}{}", " ".repeat(width - l.chars().count()));
    s.push_str(&format!(
        "  {}{}\n  {}[{}, {}] (certified)",
        pad(&bound_label),
        fmt_sig(r.bound, 6),
        pad(error_label),
        fmt_sig(r.error.lower, 6),
        fmt_sig(r.error.upper, 6)
    ));
    if r.error.lower > 0.0 {
        let w = if r.error.w.is_infinite() {
            "ω → ∞".to_string()
        } else {
            format!("ω = {} rad/s", fmt_sig(r.error.w, 6))
        };
        s.push_str(&format!(" at {w}"));
    }
    s.push('\n');
    s.push_str("  Hankel singular values (kept | dropped):\n   ");
    for (i, v) in r.hsv.iter().enumerate() {
        if i == k {
            s.push_str(" |");
        }
        s.push_str(&format!(" {}", fmt_sig(*v, 6)));
    }
    s.push_str(&format!(
        "\n  Gramian residuals (relative): P {}, Q {}\n\n  reduced model:\n",
        fmt_sig(r.residuals.0, 2),
        fmt_sig(r.residuals.1, 2)
    ));
    for (label, m) in [
        ("A", &r.reduced.a),
        ("B", &r.reduced.b),
        ("C", &r.reduced.c),
        ("D", &r.reduced.d),
    ] {
        matrix(label, &rows(m), &mut s);
    }
    if let Some(path) = &a.output {
        s.push_str(&format!("\n  wrote {}\n", path.display()));
    }
    print(&s)
}
