//! `ltikit gram` (a Gramian or its Cholesky factor, with the residual of its Lyapunov
//! equation) and `ltikit hsv` (the Hankel singular values).

use anyhow::{Result, bail};
use clap::Args;
use serde::Serialize;

use super::PlantArgs;
use super::c2d::rows;
use super::linearize::matrix;
use super::norm::{dims, plant_state_space};
use super::output::{print, print_json};
use crate::analysis::norms::{GramianKind, gramian, hankel_singular_values};
use crate::fmt::fmt_sig;

#[derive(Args, Debug)]
pub struct GramArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// c: the controllability Gramian P (A·P + P·Aᵀ + B·Bᵀ = 0), o: the observability Gramian
    /// Q (Aᵀ·Q + Q·A + Cᵀ·C = 0); the discrete equations for a discrete plant.
    #[arg(long, default_value = "c", value_name = "c|o")]
    pub kind: String,
    /// Print the lower-triangular Cholesky factor L (Gramian = L·Lᵀ) instead of the Gramian.
    #[arg(long)]
    pub cholesky: bool,
    /// Print one JSON document: {"kind", "cholesky", "matrix", "residual"}.
    #[arg(long)]
    pub json: bool,
}

#[derive(Args, Debug)]
pub struct HsvArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// Print one JSON document: {"hsv", "residuals"}.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct GramJson {
    kind: GramianKind,
    cholesky: bool,
    matrix: Vec<Vec<f64>>,
    residual: f64,
}

pub fn run_gram(a: &GramArgs) -> Result<()> {
    let kind = match a.kind.as_str() {
        "c" | "controllability" => GramianKind::Controllability,
        "o" | "observability" => GramianKind::Observability,
        other => bail!(
            "--kind: c (controllability) or o (observability), not '{}'",
            crate::error::abbreviate(other)
        ),
    };
    let (name, ss) = plant_state_space(&a.plant)?;
    let g = gramian(&ss, kind)?;
    let m = if a.cholesky {
        g.factor.clone()
    } else {
        g.matrix()
    };
    if a.json {
        return print_json(&GramJson {
            kind,
            cholesky: a.cholesky,
            matrix: rows(&m),
            residual: g.residual,
        });
    }
    let (what, eq) = match kind {
        GramianKind::Controllability => ("Controllability Gramian P", "B·Bᵀ"),
        GramianKind::Observability => ("Observability Gramian Q", "Cᵀ·C"),
    };
    let mut s = format!("{what} of {name}\n  model: {}\n", dims(&ss));
    if a.cholesky {
        s.push_str("  Cholesky factor L (lower triangular, Gramian = L·Lᵀ):\n");
    }
    matrix(if a.cholesky { "L" } else { "X" }, &rows(&m), &mut s);
    s.push_str(&format!(
        "  relative residual of its Lyapunov equation (right-hand side {eq}): {}\n",
        fmt_sig(g.residual, 2)
    ));
    print(&s)
}

#[derive(Serialize)]
struct HsvJson {
    hsv: Vec<f64>,
    residuals: [f64; 2],
}

pub fn run_hsv(a: &HsvArgs) -> Result<()> {
    let (name, ss) = plant_state_space(&a.plant)?;
    let h = hankel_singular_values(&ss)?;
    let residuals = [h.controllability.residual, h.observability.residual];
    if a.json {
        return print_json(&HsvJson {
            hsv: h.values,
            residuals,
        });
    }
    let mut s = format!("Hankel singular values of {name}\n  model: {}\n", dims(&ss));
    let total: f64 = h.values.iter().sum();
    let mut tail = total;
    s.push_str(&format!(
        "\n  {:>4}  {:>22}  {:>22}\n",
        "i", "sigma_i", "bound 2·Σ_{j>i} sigma_j"
    ));
    for (i, v) in h.values.iter().enumerate() {
        tail -= v;
        s.push_str(&format!(
            "  {:>4}  {:>22}  {:>22}\n",
            i + 1,
            fmt_sig(*v, 15),
            fmt_sig(2.0 * tail.max(0.0), 6)
        ));
    }
    s.push_str(&format!(
        "\n  Gramian residuals (relative): P {}, Q {}\n",
        fmt_sig(residuals[0], 2),
        fmt_sig(residuals[1], 2)
    ));
    print(&s)
}
