//! `ltikit mems-pullin -o FILE.png`: equilibrium gap against voltage, stable and unstable
//! branches, the pull-in point.

use anyhow::{Result, bail};
use clap::Args;

use super::output::print;
use super::parse;
use crate::fmt::fmt_sig;
use crate::lti::params::with_overrides;
use crate::nonlinear::mems_pullin;
use crate::nonlinear::models::{MEMS_PARAMS, Mems};
use crate::plot::{Curve, LineStyle, Marker, MarkerShape, PlotOptions, XyPlot, parse_size, xy_png};

#[derive(Args, Debug)]
pub struct PullinArgs {
    /// Output PNG file.
    #[arg(short = 'o', long = "output", value_name = "FILE.png", value_parser = super::png_path)]
    pub output: std::path::PathBuf,
    /// A MEMS parameter, NAME=VALUE (eps, A, m, k, l0, b, R; repeatable).
    #[arg(long = "param", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub params: Vec<String>,
    /// Highest voltage drawn (default 1.25 × the pull-in voltage).
    #[arg(long)]
    pub vmax: Option<f64>,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1000x700", value_name = "WxH")]
    pub size: String,
    /// Print one JSON document describing what was drawn (the file, the pull-in voltage by
    /// the formula and where the stable branch ends, the pull-in gap, the voltage range)
    /// instead of the summary line.
    #[arg(long)]
    pub json: bool,
}

/// What the pull-in diagram shows.
pub struct PullinDrawn {
    /// √(8 k l0³/(27 εA)) (V).
    pub formula_voltage: f64,
    /// Where the computed stable branch ends (V).
    pub found_voltage: f64,
    /// The gap at pull-in (m).
    pub gap: f64,
    /// The highest voltage drawn (V).
    pub vmax: f64,
}

/// The MEMS model with parameter overrides.
pub fn mems_with(params: &[(String, f64)]) -> Result<Mems> {
    Ok(Mems::from_values(&with_overrides(
        "mems",
        MEMS_PARAMS,
        params,
    )?)?)
}

/// Draws the pull-in diagram; returns what it marks.
pub fn pullin_figure(
    path: &std::path::Path,
    m: &Mems,
    vmax: Option<f64>,
    opts: &PlotOptions,
) -> Result<PullinDrawn> {
    let v_pi = m.pull_in_voltage();
    let vmax = match vmax {
        Some(v) if v.is_finite() && v > 0.0 => v,
        Some(v) => bail!(
            "--vmax must be a finite number > 0, got {}",
            crate::error::number(v)
        ),
        None if v_pi.is_finite() && v_pi > 0.0 && (1.25 * v_pi).is_finite() => 1.25 * v_pi,
        None => bail!(
            "the pull-in voltage √(8 k l0³/(27 ε A)) = {v_pi:e} is not a usable number for these parameters (it under- or overflows); give --vmax or change the parameters"
        ),
    };
    let d = mems_pullin(m, vmax, 401)?;
    let stable = Curve::new(d.stable.iter().map(|p| (p[0], p[1])))
        .label("stable equilibrium")
        .width(1.5);
    let unstable = Curve::new(d.unstable.iter().map(|p| (p[0], p[1])))
        .label("unstable equilibrium")
        .style(LineStyle::Dashed);
    let plot = XyPlot {
        curves: vec![stable, unstable],
        markers: vec![
            Marker::new((d.pull_in_voltage, d.pull_in_gap), MarkerShape::Disc).label(format!(
                "pull-in: v = {} V, l = 2 l0/3 = {}",
                fmt_sig(d.pull_in_voltage, 5),
                fmt_sig(d.pull_in_gap, 4)
            )),
        ],
        x_label: "voltage v (V)".into(),
        y_label: "equilibrium gap l (m)".into(),
        notes: vec![format!(
            "l²(l0 − l) = εA v²/(2k); pull-in √(8 k l0³/(27 εA)) = {} V",
            fmt_sig(v_pi, 6)
        )],
        title: "MEMS mirror: equilibrium gap against voltage (pull-in)".into(),
        ..Default::default()
    };
    xy_png(path, &plot, opts)?;
    Ok(PullinDrawn {
        formula_voltage: v_pi,
        found_voltage: d.pull_in_voltage_found,
        gap: d.pull_in_gap,
        vmax,
    })
}

pub fn run(a: &PullinArgs) -> Result<()> {
    let params = parse::params(&a.params)?;
    let m = mems_with(&params)?;
    let opts = PlotOptions {
        size: parse_size(&a.size)?,
        ..Default::default()
    };
    let d = pullin_figure(&a.output, &m, a.vmax, &opts)?;
    let (v_pi, found) = (d.formula_voltage, d.found_voltage);
    if a.json {
        return super::output::print_json(&serde_json::json!({
            "file": a.output.display().to_string(),
            "pull_in_voltage": v_pi,
            "pull_in_voltage_found": found,
            "pull_in_gap": d.gap,
            "vmax": d.vmax,
        }));
    }
    print(&format!(
        "pull-in voltage {} V (formula √(8 k l0³/(27 εA))), {} V where the stable branch ends; \
         wrote {}\n",
        fmt_sig(v_pi, 10),
        fmt_sig(found, 10),
        a.output.display()
    ))
}
