//! `ltikit gangof4 <plant> --controller …`: the gang of four of the unity negative feedback
//! loop L = C·G — S = 1/(1 + L), P·S = G/(1 + L), C·S = C/(1 + L), T = L/(1 + L) — each with its
//! poles (in lowest terms), dc gain and peak max|F(jω)|; the loop's internal stability; a Bode
//! diagram of the four with `-o FILE.png`.

use anyhow::Result;
use clap::Args;
use serde::Serialize;
use std::path::PathBuf;

use super::{PlantArgs, UsageError};
use crate::analysis::closed_loop::peak;
use crate::analysis::{Factored, LoopSystem};
use crate::fmt::fmt_sig;

#[derive(Args, Debug)]
pub struct GangArgs {
    /// The plant G and the controller C (--controller; C = 1 without it).
    #[command(flatten)]
    pub plant: PlantArgs,
    /// Print one JSON document: {"name", "internally_stable", "stability_reason", "systems":
    /// [{"system", "formula", "poles", "dc_gain", "peak", "peak_w"}]}.
    #[arg(long)]
    pub json: bool,
    /// Write a Bode diagram of S, P·S, C·S and T.
    #[arg(short = 'o', long, value_name = "FILE.png", value_parser = super::png_path)]
    pub output: Option<PathBuf>,
}

#[derive(Serialize)]
struct SystemJson {
    system: &'static str,
    formula: &'static str,
    poles: Vec<[f64; 2]>,
    dc_gain: Option<f64>,
    peak: f64,
    /// null for the limit ω → ∞.
    peak_w: Option<f64>,
}

#[derive(Serialize)]
struct GangJson {
    name: String,
    internally_stable: bool,
    stability_reason: String,
    systems: Vec<SystemJson>,
}

pub fn run(a: &GangArgs) -> Result<()> {
    let p = &a.plant;
    if p.open_loop || p.closed_loop || p.sensitivity || p.control_sensitivity {
        return Err(UsageError(
            "gangof4 reports all four transfer functions of the loop: --loop, --closed-loop, \
             --sensitivity and --control-sensitivity are not taken"
                .into(),
        )
        .into());
    }
    let mut plant = p.single_for(LoopSystem::ClosedLoop)?;
    if plant.selection.is_none() {
        plant.selection = Some(LoopSystem::ClosedLoop);
        plant.name = format!("C = 1, G = {}", plant.name);
    }
    let (_, cl) = p.factored_with_loop(&plant)?;
    let Some(cl) = cl else {
        anyhow::bail!("the loop could not be formed for this plant");
    };
    let systems: [(&'static str, &'static str, Factored); 4] = [
        ("S", "1/(1 + L)", cl.system(LoopSystem::Sensitivity)?),
        ("PS", "G/(1 + L)", cl.plant_sensitivity()?),
        (
            "CS",
            "C/(1 + L)",
            cl.system(LoopSystem::ControlSensitivity)?,
        ),
        ("T", "L/(1 + L)", cl.system(LoopSystem::ClosedLoop)?),
    ];
    let st = cl.internal_stability();
    let mut rows = Vec::new();
    for (name, formula, f) in &systems {
        let pk = peak(f)?;
        rows.push(SystemJson {
            system: name,
            formula,
            poles: crate::poly::roots::flatten(f.reduced_poles())
                .into_iter()
                .map(super::output::pair)
                .collect(),
            dc_gain: f.dc_gain(),
            peak: pk.value,
            peak_w: pk.w.is_finite().then_some(pk.w),
        });
    }
    // the picture first: an error leaves no report
    if let Some(path) = &a.output {
        let plants: Vec<(String, Factored)> = systems
            .iter()
            .map(|(n, formula, f)| (format!("{n} = {formula}"), f.clone()))
            .collect();
        super::plots::bode_figure(
            path,
            &plants,
            None,
            false,
            false,
            &crate::plot::PlotOptions {
                title: Some("Gang of four: S, P·S, C·S, T".into()),
                ..Default::default()
            },
        )?;
    }
    let name = plant
        .name
        .strip_prefix(&format!("{} with ", LoopSystem::ClosedLoop.formula()))
        .unwrap_or(&plant.name)
        .to_string();
    if a.json {
        return super::output::print_json(&GangJson {
            name,
            internally_stable: st.stable,
            stability_reason: st.reason,
            systems: rows,
        });
    }
    let mut s = format!("Gang of four of the loop L = C·G: {name}\n");
    s.push_str(&format!(
        "internally {}: {}\n\n",
        if st.stable { "stable" } else { "unstable" },
        st.reason
    ));
    for (r, (_, _, f)) in rows.iter().zip(&systems) {
        let dc = r.dc_gain.map_or("∞".to_string(), |g| fmt_sig(g, 7));
        let w = r.peak_w.map_or("ω → ∞".to_string(), |w| {
            format!("ω = {} rad/s", fmt_sig(w, 7))
        });
        s.push_str(&format!(
            "{:<3}= {:<10} poles {}\n     dc gain {dc}, peak {} at {w}\n",
            r.system,
            r.formula,
            super::text::roots_text(f.reduced_poles()),
            fmt_sig(r.peak, 7)
        ));
    }
    if let Some(p) = &a.output {
        s.push_str(&format!("\nwritten: {}\n", p.display()));
    }
    super::output::print(&s)
}
