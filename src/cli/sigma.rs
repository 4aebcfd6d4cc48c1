//! `ltikit sigma`: the singular values σᵢ(G(jω)) of a (MIMO) plant over a frequency grid —
//! a table, `--json`, or a PNG with `-o` — with the certified peak (H∞, or L∞ for an
//! unstable model) marked.

use anyhow::{Context, Result};
use clap::Args;
use serde::Serialize;
use std::path::PathBuf;

use super::PlantArgs;
use super::norm::plant_state_space;
use super::output::{Stream, print_json};
use crate::analysis::norms::{PeakGain, SigmaResponse, linf_norm, sigma_grid, sigma_response};
use crate::fmt::fmt_sig;
use crate::plot::{PlotOptions, parse_size, sigma_png};

#[derive(Args, Debug)]
pub struct SigmaArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// Log-spaced points of the automatic grid (the extras at lightly damped poles and the
    /// peak frequency are added).
    #[arg(long, default_value_t = 400, value_name = "N")]
    pub points: usize,
    /// Frequencies (rad/s) instead of the automatic grid: "0.1 1 10".
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub w: Option<String>,
    /// Write the sigma plot as a PNG (singular values in dB against ω, the peak marked).
    #[arg(short = 'o', long = "output", value_name = "FILE.png", value_parser = super::png_path)]
    pub output: Option<PathBuf>,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "1000x700", value_name = "WxH")]
    pub size: String,
    /// Title (default: names the plant; "" for none).
    #[arg(long)]
    pub title: Option<String>,
    /// Font scale, like a dpi setting (1 = default; 0.25 … 8).
    #[arg(long, default_value_t = 1.0, value_name = "SCALE")]
    pub font_scale: f64,
    /// Print one JSON document: {"plant", "peak", "w", "sigma"} (sigma[k] the singular values
    /// at w[k], largest first), and "file" with -o.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct SigmaJson<'a> {
    plant: &'a str,
    #[serde(skip_serializing_if = "Option::is_none")]
    file: Option<String>,
    peak: &'a PeakGain,
    #[serde(flatten)]
    response: &'a SigmaResponse,
}

pub fn run(a: &SigmaArgs) -> Result<()> {
    let opts = match &a.output {
        Some(_) => {
            let o = PlotOptions {
                size: parse_size(&a.size)?,
                title: a.title.clone(),
                font_scale: a.font_scale,
                ..Default::default()
            };
            o.validate()?;
            Some(o)
        }
        None => None,
    };
    let (name, ss) = plant_state_space(&a.plant)?;
    crate::limits::NORM_STATES.check_usize("states", ss.order())?;
    let w = match &a.w {
        Some(text) => {
            let w = super::parse::numbers(text, "--w")?;
            crate::limits::POINTS.check_usize("`w`", w.len())?;
            w
        }
        None => sigma_grid(&ss, a.points)?,
    };
    let r = sigma_response(&ss, &w)?;
    let peak = linf_norm(&ss)?;
    if let (Some(path), Some(o)) = (&a.output, &opts) {
        sigma_png(path, &r, Some(&peak), &name, o)
            .with_context(|| format!("sigma plot {}", path.display()))?;
    }
    if a.json {
        return print_json(&SigmaJson {
            plant: &name,
            file: a.output.as_ref().map(|p| p.display().to_string()),
            peak: &peak,
            response: &r,
        });
    }
    let mut out = Stream::stdout();
    let mut head = format!(
        "Singular values of {name}\nmodel: {}\n",
        super::norm::dims(&ss)
    );
    head.push_str(&match &peak.infinite {
        Some(why) => format!("peak: ∞ — {why}\n"),
        None => format!(
            "peak: {} in [{}, {}] at ω = {} rad/s\n",
            fmt_sig(peak.lower, 12),
            fmt_sig(peak.lower, 15),
            fmt_sig(peak.upper, 15),
            fmt_sig(peak.w, 10)
        ),
    });
    if let Some(path) = &a.output {
        head.push_str(&format!("wrote {}\n", path.display()));
    }
    let k = r.sigma.first().map_or(0, Vec::len);
    head.push_str(&format!("\n{:>14}", "w (rad/s)"));
    for i in 1..=k {
        head.push_str(&format!("  {:>14}", format!("sigma{i}")));
    }
    head.push('\n');
    if !out.put(&head)? {
        return Ok(());
    }
    for (x, s) in r.w.iter().zip(&r.sigma) {
        let mut line = format!("{:>14}", fmt_sig(*x, 8));
        for v in s {
            line.push_str(&format!("  {:>14}", fmt_sig(*v, 8)));
        }
        line.push('\n');
        if !out.put(&line)? {
            break;
        }
    }
    out.finish()
}
