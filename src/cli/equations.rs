//! `ltikit lyap`, `sylvester`, `care`, `dare`: the matrix equations of
//! [`crate::numeric::linalg::lyapunov`] and [`crate::numeric::linalg::riccati`] — the
//! solution, for the Riccati equations the gain and the closed-loop eigenvalues, always the
//! relative residual and the condition estimate.
//!
//! Matrices are given like a state-space plant's (`--a "0 1; -2 -3"`), or in a TOML file
//! (`--from FILE.toml` with keys a, b, c, q, r, s, each a list of rows or a string of rows;
//! an option on the command line replaces the file's entry).

use std::path::PathBuf;

use anyhow::{Result, anyhow};
use clap::Args;
use nalgebra::DMatrix;
use serde::{Deserialize, Serialize};

use super::output::{pair, print, print_json};
use crate::lti::plant::{MatrixSpec, parse_matrix};
use crate::numeric::linalg::{care, dare, dlyap, lyap, lyap_cholesky, sylvester};

/// `ltikit lyap`.
#[derive(Args, Debug)]
pub struct LyapArgs {
    /// A (n × n), rows separated by ';': --a "0 1; -2 -3".
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub a: Option<String>,
    /// Q (n × n): solve A·X + X·Aᵀ + Q = 0 (--discrete: A·X·Aᵀ − X + Q = 0).
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub q: Option<String>,
    /// B (n × m) in place of --q: Q = B·Bᵀ (a Gramian), and the Cholesky factor X = L·Lᵀ by
    /// Hammarling's method (A must be stable).
    #[arg(
        long,
        value_name = "ROWS",
        allow_hyphen_values = true,
        conflicts_with = "q"
    )]
    pub b: Option<String>,
    /// The discrete (Stein) equation A·X·Aᵀ − X + Q = 0.
    #[arg(long)]
    pub discrete: bool,
    /// A TOML file with the matrices (keys a, q, b), for large ones.
    #[arg(long, value_name = "FILE.toml")]
    pub from: Option<PathBuf>,
    /// Print one JSON document: {"equation", "n", "x", "l", "residual", "condition"}.
    #[arg(long)]
    pub json: bool,
}

/// `ltikit sylvester`.
#[derive(Args, Debug)]
pub struct SylvesterArgs {
    /// A (m × m) of A·X + X·B = C.
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub a: Option<String>,
    /// B (n × n).
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub b: Option<String>,
    /// C (m × n).
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub c: Option<String>,
    /// A TOML file with the matrices (keys a, b, c).
    #[arg(long, value_name = "FILE.toml")]
    pub from: Option<PathBuf>,
    /// Print one JSON document: {"equation", "n", "x", "residual", "condition"}.
    #[arg(long)]
    pub json: bool,
}

/// `ltikit care` and `ltikit dare`.
#[derive(Args, Debug)]
pub struct RiccatiArgs {
    /// A (n × n).
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub a: Option<String>,
    /// B (n × m).
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub b: Option<String>,
    /// Q (n × n, symmetric): the state weight.
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub q: Option<String>,
    /// R (m × m, symmetric positive definite): the input weight.
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub r: Option<String>,
    /// S (n × m): the cross term (zero when absent).
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true)]
    pub s: Option<String>,
    /// A TOML file with the matrices (keys a, b, q, r, s).
    #[arg(long, value_name = "FILE.toml")]
    pub from: Option<PathBuf>,
    /// Print one JSON document: {"equation", "n", "m", "x", "gain", "closed_loop",
    /// "residual", "condition", "refinements"}.
    #[arg(long)]
    pub json: bool,
}

/// The matrices of a `--from` file.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct MatrixFile {
    a: Option<MatrixSpec>,
    b: Option<MatrixSpec>,
    c: Option<MatrixSpec>,
    q: Option<MatrixSpec>,
    r: Option<MatrixSpec>,
    s: Option<MatrixSpec>,
}

impl MatrixFile {
    fn read(path: &Option<PathBuf>) -> Result<MatrixFile> {
        let Some(path) = path else {
            return Ok(MatrixFile::default());
        };
        let text = crate::lti::plant::read_text(path)?;
        toml::from_str(&text).map_err(|e| {
            anyhow!(
                "{}: {}",
                crate::error::abbreviate(&path.display().to_string()),
                super::one_line(&anyhow!(e.message().to_string()))
            )
        })
    }

    fn entry(&self, key: &str) -> Option<&MatrixSpec> {
        match key {
            "a" => self.a.as_ref(),
            "b" => self.b.as_ref(),
            "c" => self.c.as_ref(),
            "q" => self.q.as_ref(),
            "r" => self.r.as_ref(),
            _ => self.s.as_ref(),
        }
    }

    /// The matrix `key` from its option, else from the file; `None` when neither has it.
    fn get(&self, key: &str, option: &Option<String>) -> Result<Option<DMatrix<f64>>> {
        let what = format!("`{key}`");
        if let Some(text) = option {
            return Ok(Some(parse_matrix(text, &what)?));
        }
        Ok(match self.entry(key) {
            Some(spec) => Some(spec.matrix(&what)?),
            None => None,
        })
    }

    fn need(&self, key: &str, option: &Option<String>) -> Result<DMatrix<f64>> {
        self.get(key, option)?.ok_or_else(|| {
            anyhow!(
                "--{key}: the matrix {} is required (or key {key} in --from FILE.toml)",
                key.to_uppercase()
            )
        })
    }
}

fn rows(m: &DMatrix<f64>) -> Vec<Vec<f64>> {
    m.row_iter().map(|r| r.iter().copied().collect()).collect()
}

#[derive(Serialize)]
struct LinearJson {
    equation: String,
    n: usize,
    x: Vec<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    l: Option<Vec<Vec<f64>>>,
    residual: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    condition: Option<f64>,
}

fn linear_text(j: &LinearJson) -> String {
    let mut s = format!("{}\n\n", j.equation);
    super::linearize::matrix("X", &j.x, &mut s);
    if let Some(l) = &j.l {
        s.push('\n');
        super::linearize::matrix("L", l, &mut s);
        s.push_str("    (X = L·Lᵀ, L lower triangular: Hammarling's method)\n");
    }
    s.push_str(&format!(
        "\nRelative residual:  {}\n",
        crate::fmt::fmt_sig(j.residual, 3)
    ));
    if let Some(c) = j.condition {
        s.push_str(&format!(
            "Condition estimate: {} (a lower bound of the relative condition number)\n",
            crate::fmt::fmt_sig(c, 3)
        ));
    }
    s
}

fn emit(j: &LinearJson, json: bool) -> Result<()> {
    if json {
        print_json(j)
    } else {
        print(&linear_text(j))
    }
}

/// `ltikit lyap`.
pub fn run_lyap(args: &LyapArgs) -> Result<()> {
    let file = MatrixFile::read(&args.from)?;
    let a = file.need("a", &args.a)?;
    let b = if args.q.is_none() {
        file.get("b", &args.b)?
    } else {
        None
    };
    let (q, l) = match b {
        Some(b) => {
            let l = if args.discrete {
                crate::numeric::linalg::dlyap_cholesky(&a, &b)?
            } else {
                lyap_cholesky(&a, &b)?
            };
            (&b * b.transpose(), Some(l))
        }
        None => (file.need("q", &args.q)?, None),
    };
    let (sol, equation) = if args.discrete {
        (
            dlyap(&a, &q)?,
            "Discrete Lyapunov equation A·X·Aᵀ − X + Q = 0",
        )
    } else {
        (lyap(&a, &q)?, "Lyapunov equation A·X + X·Aᵀ + Q = 0")
    };
    let with_b = if l.is_some() { " with Q = B·Bᵀ" } else { "" };
    let j = LinearJson {
        equation: format!("{equation}{with_b} (n = {})", a.nrows()),
        n: a.nrows(),
        x: rows(&sol.x),
        l: l.as_ref().map(|l| rows(&l.l)),
        residual: sol.residual,
        condition: Some(sol.condition),
    };
    emit(&j, args.json)
}

/// `ltikit sylvester`.
pub fn run_sylvester(args: &SylvesterArgs) -> Result<()> {
    let file = MatrixFile::read(&args.from)?;
    let a = file.need("a", &args.a)?;
    let b = file.need("b", &args.b)?;
    let c = file.need("c", &args.c)?;
    let sol = sylvester(&a, &b, &c)?;
    let j = LinearJson {
        equation: format!(
            "Sylvester equation A·X + X·B = C ({}×{})",
            a.nrows(),
            b.nrows()
        ),
        n: a.nrows(),
        x: rows(&sol.x),
        l: None,
        residual: sol.residual,
        condition: Some(sol.condition),
    };
    emit(&j, args.json)
}

#[derive(Serialize)]
struct RiccatiJson {
    equation: String,
    n: usize,
    m: usize,
    x: Vec<Vec<f64>>,
    gain: Vec<Vec<f64>>,
    closed_loop: Vec<[f64; 2]>,
    residual: f64,
    condition: f64,
    refinements: usize,
}

/// `ltikit care` (`discrete` false) and `ltikit dare`.
pub fn run_riccati(args: &RiccatiArgs, discrete: bool) -> Result<()> {
    let file = MatrixFile::read(&args.from)?;
    let a = file.need("a", &args.a)?;
    let b = file.need("b", &args.b)?;
    let q = file.need("q", &args.q)?;
    let r = file.need("r", &args.r)?;
    let s = file.get("s", &args.s)?;
    let sol = if discrete {
        dare(&a, &b, &q, &r, s.as_ref())?
    } else {
        care(&a, &b, &q, &r, s.as_ref())?
    };
    let equation = if discrete {
        "Discrete algebraic Riccati equation AᵀXA − X − (AᵀXB + S)(R + BᵀXB)⁻¹(BᵀXA + Sᵀ) + Q = 0"
    } else {
        "Continuous algebraic Riccati equation AᵀX + XA − (XB + S)R⁻¹(BᵀX + Sᵀ) + Q = 0"
    };
    let j = RiccatiJson {
        equation: format!("{equation} (n = {}, m = {})", a.nrows(), b.ncols()),
        n: a.nrows(),
        m: b.ncols(),
        x: rows(&sol.x),
        gain: rows(&sol.gain),
        closed_loop: sol.closed_loop.iter().copied().map(pair).collect(),
        residual: sol.residual,
        condition: sol.condition,
        refinements: sol.refinements,
    };
    if args.json {
        return print_json(&j);
    }
    let mut t = format!("{}\n\nStabilising solution\n", j.equation);
    super::linearize::matrix("X", &j.x, &mut t);
    t.push_str(if discrete {
        "\nGain K = (R + BᵀXB)⁻¹(BᵀXA + Sᵀ), u = −K·x\n"
    } else {
        "\nGain K = R⁻¹(BᵀX + Sᵀ), u = −K·x\n"
    });
    super::linearize::matrix("K", &j.gain, &mut t);
    t.push_str(&format!(
        "\nClosed-loop eigenvalues (A − B·K): {}\n",
        super::linearize::eigenvalues_text(&sol.closed_loop, 6)
    ));
    t.push_str(&format!(
        "\nRelative residual:  {} (after {} Newton refinement step{})\n",
        crate::fmt::fmt_sig(j.residual, 3),
        j.refinements,
        if j.refinements == 1 { "" } else { "s" }
    ));
    t.push_str(&format!(
        "Condition estimate: {} (a lower bound of the relative condition number)\n",
        crate::fmt::fmt_sig(j.condition, 3)
    ));
    print(&t)
}
