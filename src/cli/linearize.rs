//! `ltikit linearize MODEL`: equilibria, A, B, C, D, eigenvalues, local stability and the
//! linearised transfer function.

use anyhow::Result;
use clap::Args;
use serde::Serialize;

use super::output::{pair, print, print_json};
use super::parse;
use super::text::{roots_text, vector_text};
use crate::analysis::Analysis;
use crate::fmt::{fmt_root, fmt_sig};
use crate::lti::StateSpace;
use crate::nonlinear::{
    ChannelTf, EnergyCasimir, EquilibriumSearch, Linearization, LocalStability, build_model,
    linearize, model_info,
};

#[derive(Args, Debug)]
pub struct LinearizeArgs {
    /// Model: pendulum, mems, lorenz, vanderpol, rigid-body, heavy-top, gyroscope,
    /// double-pendulum, or a linear plant (spring-mass-damper, …).
    pub model: String,
    /// A model parameter, NAME=VALUE (repeatable).
    #[arg(long = "param", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub params: Vec<String>,
    /// Constant input at which to find the equilibria (default: the model's operating input).
    #[arg(long, value_name = "VALUES", allow_hyphen_values = true)]
    pub u: Option<String>,
    /// Print one JSON document instead of the report.
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: &LinearizeArgs) -> Result<()> {
    let params = parse::params(&a.params)?;
    let sys = build_model(&a.model, &params)?;
    let u =
        a.u.as_deref()
            .map(|s| parse::numbers(s, "--u"))
            .transpose()?;
    let lin = linearize(sys.as_ref(), u.as_deref(), &EquilibriumSearch::default())?;
    if a.json {
        print_json(&LinearizeJson::from(&lin))
    } else {
        let title = model_info(&a.model).map(|i| i.title).unwrap_or("model");
        print(&report(title, &lin, sys.equilibria_note().as_deref()))
    }
}

/// The `linearize` JSON contract (DESIGN §1.2).
#[derive(Serialize)]
pub struct LinearizeJson {
    model: String,
    params: serde_json::Map<String, serde_json::Value>,
    equilibria: Vec<EquilibriumJson>,
}

#[derive(Serialize)]
struct EquilibriumJson {
    x: Vec<f64>,
    u: Vec<f64>,
    #[serde(rename = "A")]
    a: Vec<Vec<f64>>,
    #[serde(rename = "B")]
    b: Vec<Vec<f64>>,
    #[serde(rename = "C")]
    c: Vec<Vec<f64>>,
    #[serde(rename = "D")]
    d: Vec<Vec<f64>>,
    eigenvalues: Vec<[f64; 2]>,
    hyperbolic: bool,
    stability: &'static str,
    physical: bool,
    tf: Option<TfJson>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    channels: Vec<ChannelJson>,
    #[serde(skip_serializing_if = "Option::is_none")]
    energy_casimir: Option<EnergyCasimir>,
}

/// One input→output channel of a multi-input or multi-output linearisation.
#[derive(Serialize)]
struct ChannelJson {
    input: String,
    output: String,
    num: Vec<f64>,
    den: Vec<f64>,
    /// The channel's analysis (the `analyze` document), when it can be computed.
    #[serde(skip_serializing_if = "Option::is_none")]
    analysis: Option<super::analyze::json::AnalyzeJson>,
}

#[derive(Serialize)]
struct TfJson {
    num: Vec<f64>,
    den: Vec<f64>,
}

fn stability_word(s: LocalStability) -> &'static str {
    match s {
        LocalStability::AsymptoticallyStable => "asymptotically_stable",
        LocalStability::Unstable => "unstable",
        LocalStability::Undetermined => "undetermined",
    }
}

impl From<&Linearization> for LinearizeJson {
    fn from(l: &Linearization) -> Self {
        let mut params = serde_json::Map::new();
        for (k, v) in &l.params {
            params.insert(k.clone(), serde_json::json!(v));
        }
        LinearizeJson {
            model: l.model.clone(),
            params,
            equilibria: l
                .equilibria
                .iter()
                .map(|e| EquilibriumJson {
                    x: e.x.clone(),
                    u: e.u.clone(),
                    a: e.a.clone(),
                    b: e.b.clone(),
                    c: e.c.clone(),
                    d: e.d.clone(),
                    eigenvalues: e.eigenvalues.iter().map(|z| pair(*z)).collect(),
                    hyperbolic: e.hyperbolic,
                    stability: stability_word(e.stability),
                    physical: e.physical,
                    tf: e.tf.as_ref().map(|t| TfJson {
                        num: t.num.clone(),
                        den: t.den.clone(),
                    }),
                    channels: e
                        .channels
                        .iter()
                        .map(|c| ChannelJson {
                            input: c.input_name.clone(),
                            output: c.output_name.clone(),
                            num: c.num.clone(),
                            den: c.den.clone(),
                            analysis: channel_analysis(&e.ss, c)
                                .ok()
                                .map(|a| super::analyze::json::AnalyzeJson::from(&a)),
                        })
                        .collect(),
                    energy_casimir: e.energy_casimir.clone(),
                })
                .collect(),
        }
    }
}

pub(crate) fn matrix(name: &str, m: &[Vec<f64>], out: &mut String) {
    if m.is_empty() || m[0].is_empty() {
        out.push_str(&format!("    {name} = []\n"));
        return;
    }
    let cells: Vec<Vec<String>> = m
        .iter()
        .map(|r| r.iter().map(|x| fmt_sig(*x, 6)).collect())
        .collect();
    let width = cells.iter().flatten().map(|c| c.len()).max().unwrap_or(1);
    for (i, row) in cells.iter().enumerate() {
        let lead = if i == 0 {
            format!("{name} =")
        } else {
            String::new()
        };
        let body = row
            .iter()
            .map(|c| format!("{c:>width$}"))
            .collect::<Vec<_>>()
            .join("  ");
        out.push_str(&format!("    {lead:<4}[ {body} ]\n"));
    }
}

/// Eigenvalues for display: one per conjugate pair, repeated ones as (×m); real or
/// imaginary parts below 1e-13 of the largest |λ| are rounding noise (a zero computed as
/// 6.6e-33, a centre as −1.9e-32 ± 12.7j) and shown as 0.
pub(crate) fn eigenvalues_text(e: &[num_complex::Complex64], sig: usize) -> String {
    let scale = e.iter().map(|z| z.norm()).fold(0.0, f64::max);
    let t = 1e-13 * scale;
    let mut groups: Vec<(String, usize)> = Vec::new();
    for z in e {
        // Rounding noise (below 1e-13 of the largest) is shown as 0, except for a 2×2 matrix,
        // whose eigenvalues come from an accurately rounded determinant (−4e-200 for
        // C = 1e200 in the spring–mass–damper is an eigenvalue, not noise).
        let whole_tiny = e.len() == 2 && z.norm() <= t && z.im == 0.0;
        let z = num_complex::Complex64::new(
            if z.re.abs() <= t && !whole_tiny {
                0.0
            } else {
                z.re
            },
            if z.im.abs() <= t { 0.0 } else { z.im },
        );
        if z.im < 0.0 {
            continue;
        }
        let s = fmt_root(z, sig);
        match groups.iter_mut().find(|g| g.0 == s) {
            Some(g) => g.1 += 1,
            None => groups.push((s, 1)),
        }
    }
    groups
        .into_iter()
        .map(|(s, m)| if m > 1 { format!("{s} (×{m})") } else { s })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The analysis of one channel of a linearisation (the same per-channel analysis as
/// `analyze` on a MIMO plant). It starts from the channel's transfer function with the
/// rounding noise of the Jacobians removed (`reduced`: a gimbal term cos(π/2) = 6e-17 would
/// otherwise leave a spurious zero near 0 that does not cancel the pole at 0); `ss` is the
/// linearisation, kept for the state-space kernels.
fn channel_analysis(_ss: &StateSpace, c: &ChannelTf) -> crate::Result<Analysis> {
    c.reduced.factored()?.analyze()
}

/// One line of a channel's analysis: poles, zeros, dc gain, stability.
fn channel_line(ss: &StateSpace, c: &ChannelTf) -> String {
    match channel_analysis(ss, c) {
        Ok(a) => {
            let pz = &a.pole_zero;
            format!(
                "    poles {}; zeros {}{}; dc gain {}; {}\n",
                roots_text(&pz.reduced_poles),
                roots_text(&pz.reduced_zeros),
                if pz.cancelled.is_empty() {
                    String::new()
                } else {
                    format!(" (cancelled {})", roots_text(&pz.cancelled))
                },
                a.dc_gain
                    .map(|g| fmt_sig(g, 6))
                    .unwrap_or_else(|| "infinite".into()),
                if a.stability.bibo_stable {
                    "BIBO stable"
                } else {
                    "not BIBO stable"
                }
            )
        }
        Err(e) => format!("    (no analysis: {e})\n"),
    }
}

/// Human-readable report; `note` is the model's remark on its equilibria.
pub fn report(title: &str, l: &Linearization, note: Option<&str>) -> String {
    let mut s = format!("{title} ({})\n", l.model);
    if !l.params.is_empty() {
        s.push_str(&format!(
            "  parameters: {}\n",
            l.params
                .iter()
                .map(|(k, v)| format!("{k} = {}", fmt_sig(*v, 6)))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    s.push_str(&format!(
        "  {} equilibri{}\n",
        l.equilibria.len(),
        if l.equilibria.len() == 1 { "um" } else { "a" }
    ));
    if let Some(note) = note {
        s.push_str(&format!("  note: {note}\n"));
    }
    for (i, e) in l.equilibria.iter().enumerate() {
        s.push_str(&format!(
            "\nEquilibrium {}: x = {}{}{}\n",
            i + 1,
            vector_text(&e.x),
            if e.u.is_empty() {
                String::new()
            } else {
                format!(", u = {}", vector_text(&e.u))
            },
            if e.physical { "" } else { "  (not physical)" }
        ));
        matrix("A", &e.a, &mut s);
        if !e.b.is_empty() && !e.b[0].is_empty() {
            matrix("B", &e.b, &mut s);
        }
        matrix("C", &e.c, &mut s);
        if !e.d.is_empty() && !e.d[0].is_empty() {
            matrix("D", &e.d, &mut s);
        }
        let ev = eigenvalues_text(&e.eigenvalues, 6);
        s.push_str(&format!("  eigenvalues: {ev}\n"));
        s.push_str(&format!(
            "  {}; {}\n",
            if e.hyperbolic {
                "hyperbolic"
            } else {
                "not hyperbolic"
            },
            e.stability_reason
        ));
        if let Some(ec) = &e.energy_casimir {
            s.push_str(&format!("  {}\n", ec.reason));
            if !ec.hessian_eigenvalues.is_empty() {
                s.push_str(&format!(
                    "    restricted Hessian eigenvalues: {}\n",
                    ec.hessian_eigenvalues
                        .iter()
                        .map(|v| fmt_sig(*v, 6))
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            }
        }
        for c in &e.channels {
            let zero = c.reduced.num().coeffs().iter().all(|v| *v == 0.0);
            s.push_str(&format!(
                "  {} → {}: G(s) = {}\n",
                c.input_name,
                c.output_name,
                if zero {
                    "0".to_string()
                } else {
                    c.reduced.to_string()
                }
            ));
            if !zero {
                s.push_str(&channel_line(&e.ss, c));
            }
        }
        if let Some(tf) = &e.tf {
            s.push_str(&format!("  linearised G(s) = {}\n", tf.g));
            for m in tf.modes.iter().filter(|m| m.pole.im >= 0.0) {
                s.push_str(&format!(
                    "    pole {}: wn = {} rad/s{}\n",
                    fmt_root(m.pole, 6),
                    fmt_sig(m.wn, 6),
                    m.zeta
                        .map(|z| format!(", zeta = {}", fmt_sig(z, 6)))
                        .unwrap_or_default()
                ));
            }
        }
    }
    s
}
