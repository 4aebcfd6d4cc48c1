//! `ltikit margins`: gain and phase margins with all crossings, bandwidth, resonance.

use anyhow::Result;
use clap::Args;

use super::PlantArgs;
use super::output::{print, print_json};
use crate::analysis::Margins;
use crate::poly::fmt_sig;

#[derive(Args, Debug)]
pub struct MarginsArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// Print one JSON document (infinite margins are null) instead of the report.
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: &MarginsArgs) -> Result<()> {
    let plant = a.plant.single()?;
    let f = a.plant.factored(&plant)?;
    let m = f.margins()?;
    if a.json {
        print_json(&m)
    } else {
        print(&format!(
            "{}\n\n{}",
            super::text::g_text(&plant, &f),
            report(&m)
        ))
    }
}

fn opt(x: Option<f64>, unit: &str) -> String {
    match x {
        Some(v) if v.is_finite() => format!("{}{unit}", fmt_sig(v, 7)),
        Some(_) | None => "∞".into(),
    }
}

/// Human-readable margins report ("∞" for infinite margins).
pub fn report(m: &Margins) -> String {
    let mut s = String::new();
    s.push_str(&format!(
        "Gain margin:   {} ({}){}\n",
        opt(m.gain_margin, ""),
        opt(m.gain_margin_db, " dB"),
        m.phase_crossover
            .map(|w| format!(" at the phase crossover w = {} rad/s", fmt_sig(w, 7)))
            .unwrap_or_else(|| " (the phase never reaches -180°)".into())
    ));
    s.push_str(&format!(
        "Phase margin:  {}{}\n",
        opt(m.phase_margin_deg, "°"),
        m.gain_crossover
            .map(|w| format!(" at the gain crossover w = {} rad/s", fmt_sig(w, 7)))
            .unwrap_or_else(|| " (|G| never crosses 1)".into())
    ));
    if m.phase_crossings.len() > 1 || m.gain_crossings.len() > 1 {
        s.push_str("All crossings:\n");
        for c in &m.phase_crossings {
            s.push_str(&format!(
                "  phase -180° at w = {} rad/s: gain margin {} ({} dB)\n",
                fmt_sig(c.w, 7),
                fmt_sig(c.gain_margin, 7),
                fmt_sig(c.gain_margin_db, 7)
            ));
        }
        for c in &m.gain_crossings {
            s.push_str(&format!(
                "  |G| = 1 at w = {} rad/s: phase margin {}°\n",
                fmt_sig(c.w, 7),
                fmt_sig(c.phase_margin_deg, 7)
            ));
        }
    }
    s.push_str(&format!(
        "Bandwidth:     {}\n",
        m.bandwidth
            .map(|b| format!("{} rad/s (-3 dB below the dc gain)", fmt_sig(b, 7)))
            .unwrap_or_else(|| "not defined (dc gain 0 or infinite, or no -3 dB point)".into())
    ));
    match (m.resonant_peak, m.resonant_frequency) {
        (Some(mr), Some(wr)) => s.push_str(&format!(
            "Resonance:     Mr = {} ({} dB) at wr = {} rad/s\n",
            opt(Some(mr), ""),
            opt(Some(20.0 * mr.log10()), ""),
            fmt_sig(wr, 7)
        )),
        _ => s.push_str("Resonance:     none (|G| has no peak above the dc gain)\n"),
    }
    s
}
