//! `ltikit lqr`, `ltikit lqe` (alias `kalman`) and `ltikit lqg`: the linear-quadratic
//! regulator, the Kalman estimator gain and the LQG controller of a plant (the continuous
//! Riccati equation, or the discrete one for a discrete plant), with the Riccati solution,
//! the closed-loop (estimator) poles, the residual and the condition estimate.
//!
//! Weights and covariances are matrices typed like --a (rows separated by ';'); one number
//! stands for that multiple of the identity (of the size the plant needs). They are required
//! (as MATLAB's `lqr` and `lqe` require them).

use anyhow::Result;
use clap::Args;
use nalgebra::DMatrix;
use num_complex::Complex64;
use serde::Serialize;
use std::path::PathBuf;

use super::PlantArgs;
use super::design::{design_plant, rows, title, var};
use super::output::{pair, print, print_json};
use crate::analysis::design::kalman::expand_scalar;
use crate::analysis::design::{Kalman, Lqr, NoiseInput, lqe, lqg, lqr};
use crate::fmt::fmt_sig;
use crate::lti::StateSpace;
use crate::lti::plant::parse_matrix;

#[derive(Args, Debug)]
pub struct LqrArgs {
    /// The plant (state space, or a transfer function realised in controllable canonical
    /// form; --dt T for a discrete plant: the discrete Riccati equation).
    #[command(flatten)]
    pub plant: PlantArgs,
    /// State weight Q (n × n, symmetric positive semidefinite), rows separated by ';', or one
    /// number for that multiple of I: --q "1 0; 0 1" or --q 1.
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub q: String,
    /// Input weight R (m × m, symmetric positive definite), or one number for that multiple
    /// of I.
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub r: String,
    /// Cross weight S (n × m): the cost has 2xᵀSu.
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub s: Option<String>,
    /// Print one JSON document: {"dt", "equation", "k", "x", "closed_loop", "residual",
    /// "condition"}.
    #[arg(long)]
    pub json: bool,
}

#[derive(Args, Debug)]
pub struct LqeArgs {
    /// The plant (state space, or a transfer function realised; --dt T for a discrete plant).
    #[command(flatten)]
    pub plant: PlantArgs,
    /// Process noise covariance Qn: n × n (noise on every state, G = I) or m × m (noise
    /// through the inputs, G = B); its size says which unless --noise-input does.
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub qn: String,
    /// Measurement noise covariance Rn (p × p, positive definite), or one number for that
    /// multiple of I.
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub rn: String,
    /// Cross covariance Nn = E{w vᵀ} (rows as Qn, p columns).
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub nn: Option<String>,
    /// Where the process noise enters: states (G = I) or inputs (G = B); required when the
    /// plant has as many inputs as states. With it, one number for Qn is that multiple of I.
    #[arg(long, value_name = "states|inputs")]
    pub noise_input: Option<String>,
    /// Print one JSON document: {"dt", "equation", "noise_input", "l", "p", "estimator_poles",
    /// "residual", "condition"}.
    #[arg(long)]
    pub json: bool,
}

#[derive(Args, Debug)]
pub struct LqgArgs {
    /// The plant (state space, or a transfer function realised; --dt T for a discrete plant).
    #[command(flatten)]
    pub plant: PlantArgs,
    /// State weight Q of the regulator (n × n, or one number for that multiple of I).
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub q: String,
    /// Input weight R of the regulator (m × m, or one number).
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub r: String,
    /// Process noise covariance Qn (n × n on every state, or m × m through the inputs).
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub qn: String,
    /// Measurement noise covariance Rn (p × p, or one number).
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub rn: String,
    /// Where the process noise enters: states (G = I) or inputs (G = B).
    #[arg(long, value_name = "states|inputs")]
    pub noise_input: Option<String>,
    /// Print one JSON document: {"dt", "equation", "k", "l", "noise_input", "closed_loop",
    /// "estimator_poles", "controller": {"a", "b", "c", "d"}, "residuals"}.
    #[arg(long)]
    pub json: bool,
    /// Write the controller H (y → −u, for negative feedback) as a plant file that --plant
    /// reads.
    #[arg(short = 'o', long, value_name = "FILE.toml", value_parser = super::c2d::toml_path)]
    pub output: Option<PathBuf>,
}

/// A weight typed as text: rows separated by ';', one number standing for that multiple of
/// the identity of size `k`.
fn weight(text: &str, field: &str, k: usize) -> Result<DMatrix<f64>> {
    Ok(expand_scalar(parse_matrix(text, field)?, k))
}

fn equation(ss: &StateSpace) -> &'static str {
    if ss.domain.is_discrete() {
        "dare"
    } else {
        "care"
    }
}

fn equation_text(ss: &StateSpace) -> &'static str {
    if ss.domain.is_discrete() {
        "discrete algebraic Riccati equation (DARE)"
    } else {
        "continuous algebraic Riccati equation (CARE)"
    }
}

fn pairs(v: &[Complex64]) -> Vec<[f64; 2]> {
    v.iter().map(|z| pair(*z)).collect()
}

fn noise_input(text: Option<&str>) -> Result<Option<NoiseInput>> {
    Ok(text.map(NoiseInput::parse).transpose()?)
}

/// Qn from its text: one number is that multiple of I when the noise input is told.
fn process_noise(text: &str, ss: &StateSpace, told: Option<NoiseInput>) -> Result<DMatrix<f64>> {
    let q = parse_matrix(text, "`qn`")?;
    Ok(match told {
        Some(NoiseInput::States) => expand_scalar(q, ss.order()),
        Some(NoiseInput::Inputs) => expand_scalar(q, ss.b.ncols()),
        None => q,
    })
}

#[derive(Serialize)]
struct LqrJson {
    equation: &'static str,
    k: Vec<Vec<f64>>,
    x: Vec<Vec<f64>>,
    closed_loop: Vec<[f64; 2]>,
    residual: f64,
    condition: Option<f64>,
}

pub fn run_lqr(a: &LqrArgs) -> Result<()> {
    let (plant, ss) = design_plant(&a.plant, "lqr")?;
    let (n, m) = (ss.order(), ss.b.ncols());
    let q = weight(&a.q, "`q`", n)?;
    let r = weight(&a.r, "`r`", m)?;
    let s = a.s.as_deref().map(|t| parse_matrix(t, "`s`")).transpose()?;
    let d = lqr(&ss, &q, &r, s.as_ref())?;
    if a.json {
        return print_json(&LqrJson {
            equation: equation(&ss),
            k: rows(&d.gain),
            x: rows(&d.x),
            closed_loop: pairs(&d.closed_loop),
            residual: d.residual,
            condition: super::output::finite(d.condition),
        });
    }
    let mut s = title("Linear-quadratic regulator", &plant, &ss);
    regulator_text(&ss, &d, &mut s);
    print(&s)
}

fn regulator_text(ss: &StateSpace, d: &Lqr, s: &mut String) {
    s.push_str(&format!(
        "{}: relative residual {}, condition estimate {}\n",
        equation_text(ss),
        fmt_sig(d.residual, 2),
        fmt_sig(d.condition, 3)
    ));
    s.push_str("state feedback u = -K x:\n");
    super::linearize::matrix("K", &rows(&d.gain), s);
    s.push_str("Riccati solution:\n");
    super::linearize::matrix("X", &rows(&d.x), s);
    s.push_str(&format!(
        "closed-loop poles eig(A - BK) ({}): {}\n",
        var(ss),
        super::linearize::eigenvalues_text(&d.closed_loop, 6)
    ));
}

fn estimator_text(ss: &StateSpace, k: &Kalman, s: &mut String) {
    let g = match k.noise_input {
        NoiseInput::States => "on every state (G = I)",
        NoiseInput::Inputs => "through the inputs (G = B)",
    };
    s.push_str(&format!("process noise: {g}\n"));
    s.push_str(&format!(
        "dual {}: relative residual {}, condition estimate {}\n",
        equation_text(ss),
        fmt_sig(k.residual, 2),
        fmt_sig(k.condition, 3)
    ));
    s.push_str(if ss.domain.is_discrete() {
        "estimator gain (predictor form x̂[k+1] = A x̂ + B u + L (y - C x̂ - D u)):\n"
    } else {
        "estimator gain (x̂' = A x̂ + B u + L (y - C x̂ - D u)):\n"
    });
    super::linearize::matrix("L", &rows(&k.gain), s);
    s.push_str("steady error covariance:\n");
    super::linearize::matrix("P", &rows(&k.p), s);
    s.push_str(&format!(
        "estimator poles eig(A - LC) ({}): {}\n",
        var(ss),
        super::linearize::eigenvalues_text(&k.estimator_poles, 6)
    ));
}

#[derive(Serialize)]
struct LqeJson {
    equation: &'static str,
    noise_input: &'static str,
    l: Vec<Vec<f64>>,
    p: Vec<Vec<f64>>,
    estimator_poles: Vec<[f64; 2]>,
    residual: f64,
    condition: Option<f64>,
}

pub fn run_lqe(a: &LqeArgs) -> Result<()> {
    let (plant, ss) = design_plant(&a.plant, "lqe")?;
    let told = noise_input(a.noise_input.as_deref())?;
    let qn = process_noise(&a.qn, &ss, told)?;
    let rn = weight(&a.rn, "`rn`", ss.c.nrows())?;
    let nn =
        a.nn.as_deref()
            .map(|t| parse_matrix(t, "`nn`"))
            .transpose()?;
    let k = lqe(&ss, &qn, &rn, nn.as_ref(), told)?;
    if a.json {
        return print_json(&LqeJson {
            equation: equation(&ss),
            noise_input: k.noise_input.name(),
            l: rows(&k.gain),
            p: rows(&k.p),
            estimator_poles: pairs(&k.estimator_poles),
            residual: k.residual,
            condition: super::output::finite(k.condition),
        });
    }
    let mut s = title("Kalman estimator", &plant, &ss);
    estimator_text(&ss, &k, &mut s);
    print(&s)
}

#[derive(Serialize)]
struct ControllerJson {
    a: Vec<Vec<f64>>,
    b: Vec<Vec<f64>>,
    c: Vec<Vec<f64>>,
    d: Vec<Vec<f64>>,
}

#[derive(Serialize)]
struct Residuals {
    regulator: f64,
    estimator: f64,
}

#[derive(Serialize)]
struct LqgJson {
    equation: &'static str,
    noise_input: &'static str,
    k: Vec<Vec<f64>>,
    l: Vec<Vec<f64>>,
    closed_loop: Vec<[f64; 2]>,
    estimator_poles: Vec<[f64; 2]>,
    controller: ControllerJson,
    residuals: Residuals,
}

/// The plant file of the controller.
#[derive(Serialize)]
struct ControllerFile {
    name: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    dt: Option<f64>,
    a: Vec<Vec<f64>>,
    b: Vec<Vec<f64>>,
    c: Vec<Vec<f64>>,
    d: Vec<Vec<f64>>,
}

pub fn run_lqg(a: &LqgArgs) -> Result<()> {
    let (plant, ss) = design_plant(&a.plant, "lqg")?;
    let (n, m, p) = (ss.order(), ss.b.ncols(), ss.c.nrows());
    let q = weight(&a.q, "`q`", n)?;
    let r = weight(&a.r, "`r`", m)?;
    let told = noise_input(a.noise_input.as_deref())?;
    let qn = process_noise(&a.qn, &ss, told)?;
    let rn = weight(&a.rn, "`rn`", p)?;
    let d = lqg(&ss, &q, &r, &qn, &rn, told)?;
    let h = &d.controller;
    // the file first: an error leaves neither a file nor a report
    if let Some(path) = &a.output {
        let file = ControllerFile {
            name: format!("LQG controller (y to -u) of {}", plant.name),
            dt: h.domain.dt(),
            a: rows(&h.a),
            b: rows(&h.b),
            c: rows(&h.c),
            d: rows(&h.d),
        };
        let text = toml::to_string(&file)?;
        crate::plot::output::write_atomic(path, text.as_bytes())?;
    }
    if a.json {
        return print_json(&LqgJson {
            equation: equation(&ss),
            noise_input: d.estimator.noise_input.name(),
            k: rows(&d.regulator.gain),
            l: rows(&d.estimator.gain),
            closed_loop: pairs(&d.regulator.closed_loop),
            estimator_poles: pairs(&d.estimator.estimator_poles),
            controller: ControllerJson {
                a: rows(&h.a),
                b: rows(&h.b),
                c: rows(&h.c),
                d: rows(&h.d),
            },
            residuals: Residuals {
                regulator: d.regulator.residual,
                estimator: d.estimator.residual,
            },
        });
    }
    let mut s = title("LQG controller", &plant, &ss);
    s.push_str("regulator\n");
    regulator_text(&ss, &d.regulator, &mut s);
    s.push_str("\nestimator\n");
    estimator_text(&ss, &d.estimator, &mut s);
    s.push_str(
        "\ncontroller H (input y, output -u: negative feedback u = -H y; the closed loop has \
         the poles of A - BK and A - LC):\n",
    );
    for (name, mat) in [("A", &h.a), ("B", &h.b), ("C", &h.c), ("D", &h.d)] {
        super::linearize::matrix(name, &rows(mat), &mut s);
    }
    if m == 1 && p == 1 {
        let tf = h.to_tf()?;
        let list = |c: &[f64]| {
            c.iter()
                .map(|&x| {
                    if x != 0.0 && !(1e-4..1e15).contains(&x.abs()) {
                        format!("{x:e}")
                    } else {
                        format!("{x}")
                    }
                })
                .collect::<Vec<_>>()
                .join(" ")
        };
        s.push_str(&format!(
            "as a loop controller: --controller \"tf:{}/{}\"\n",
            list(tf.num().coeffs()),
            list(tf.den().coeffs())
        ));
    }
    if let Some(path) = &a.output {
        s.push_str(&format!("written: {}\n", path.display()));
    }
    print(&s)
}
