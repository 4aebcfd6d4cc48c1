//! `ltikit margins`: gain and phase margins with all crossings, bandwidth, resonance; on a
//! loop with a controller also the closed-loop poles, hidden modes, internal stability and the
//! robustness margins (Ms, Mt, delay margin).

use anyhow::Result;
use clap::Args;
use serde::Serialize;

use super::PlantArgs;
use super::output::{finite, json_value, pair, print, print_json};
use crate::analysis::{ClosedLoop, Margins, Peak, Robustness};
use crate::fmt::{fmt_root, fmt_sig};
use crate::lti::controller::LoopSystem;
use crate::poly::roots::flatten;

#[derive(Args, Debug)]
pub struct MarginsArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// Print one JSON document (infinite margins are null) instead of the report.
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: &MarginsArgs) -> Result<()> {
    let plant = a.plant.single_for(LoopSystem::Loop)?;
    if plant.selection.is_none() {
        // No controller: the plant itself, per channel when MIMO.
        let chans = a.plant.channels(&plant)?;
        return super::channels::print_each(&plant, &chans, a.json, |f| f.margins(), report);
    }
    let (f, cl) = a.plant.factored_with_loop(&plant)?;
    let m = f.margins()?;
    // the robustness margins belong to the loop L
    let lp = match cl.filter(|_| plant.selection == Some(LoopSystem::Loop)) {
        Some(cl) => Some((cl.robustness()?, cl)),
        None => None,
    };
    if a.json {
        let mut v = json_value(&m)?;
        if let (Some((r, cl)), Some(obj)) = (&lp, v.as_object_mut()) {
            obj.insert("loop".into(), json_value(&LoopJson::new(cl, r))?);
        }
        print_json(&v)
    } else {
        let mut text = format!("{}\n\n{}", super::text::g_text(&plant, &f), report(&m));
        if let Some((r, cl)) = &lp {
            text.push_str(&loop_report(cl, r));
        }
        print(&text)
    }
}

/// The JSON of the loop: closed-loop poles (hidden modes included), hidden modes, internal
/// stability, Ms, Mt and the delay margin.
#[derive(Serialize)]
struct LoopJson {
    closed_loop_poles: Vec<[f64; 2]>,
    hidden_modes: Vec<[f64; 2]>,
    internally_stable: bool,
    internal_stability: String,
    ms: Option<f64>,
    ms_w: Option<f64>,
    mt: Option<f64>,
    mt_w: Option<f64>,
    delay_margin: Option<f64>,
    delay_margin_w: Option<f64>,
}

impl LoopJson {
    fn new(cl: &ClosedLoop, r: &Robustness) -> LoopJson {
        let st = cl.internal_stability();
        LoopJson {
            closed_loop_poles: flatten(cl.poles()).into_iter().map(pair).collect(),
            hidden_modes: flatten(cl.hidden()).into_iter().map(pair).collect(),
            internally_stable: st.stable,
            internal_stability: st.reason,
            ms: finite(r.ms.value),
            ms_w: finite(r.ms.w),
            mt: finite(r.mt.value),
            mt_w: finite(r.mt.w),
            delay_margin: finite(r.delay_margin),
            delay_margin_w: finite(r.delay_margin_w),
        }
    }
}

fn peak_text(p: &Peak) -> String {
    let at = if p.w == 0.0 {
        "at w = 0".to_string()
    } else if p.w.is_finite() {
        format!("at w = {} rad/s", fmt_sig(p.w, 7))
    } else {
        "as w → ∞".to_string()
    };
    format!(
        "{} ({} dB) {at}",
        opt(Some(p.value), ""),
        opt(Some(20.0 * p.value.log10()), "")
    )
}

/// The loop part of the report.
pub fn loop_report(cl: &ClosedLoop, r: &Robustness) -> String {
    let st = cl.internal_stability();
    let roots = |v: &[crate::poly::Root]| -> String {
        v.iter()
            .filter(|r| r.value.im >= 0.0)
            .map(|r| {
                let m = if r.multiplicity > 1 {
                    format!(" (×{})", r.multiplicity)
                } else {
                    String::new()
                };
                format!("{}{m}", fmt_root(r.value, 7))
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut s = format!("\nClosed-loop poles: {}\n", roots(cl.poles()));
    if !cl.hidden().is_empty() {
        s.push_str(&format!(
            "Hidden modes (cancelled in C·G): {}\n",
            roots(cl.hidden())
        ));
    }
    s.push_str(&format!("Internal stability: {}\n", st.reason));
    s.push_str(&format!(
        "Peak sensitivity Ms:               {}\n",
        peak_text(&r.ms)
    ));
    s.push_str(&format!(
        "Peak complementary sensitivity Mt: {}\n",
        peak_text(&r.mt)
    ));
    if !r.closed_loop_stable {
        s.push_str(
            "Note: the closed loop is not stable; these margins do not measure robustness.\n",
        );
    }
    s
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
    match (m.delay_margin, m.delay_margin_w) {
        (Some(d), Some(w)) => s.push_str(&format!(
            "Delay margin:  {} s (PM/wc at the gain crossover w = {} rad/s{})\n",
            fmt_sig(d, 7),
            fmt_sig(w, 7),
            if m.crossings_listed_to.is_some() {
                "; what remains beyond the loop's own dead time"
            } else {
                ""
            }
        )),
        _ => s.push_str("Delay margin:  ∞ (no gain crossover: |G| never crosses 1)\n"),
    }
    if m.phase_crossings.len() > 1 || m.gain_crossings.len() > 1 {
        s.push_str("All crossings:\n");
        // a dead time makes them endless: the first few in the text (all listed in --json)
        let shown = if m.crossings_listed_to.is_some() {
            6
        } else {
            usize::MAX
        };
        for c in m.phase_crossings.iter().take(shown) {
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
    if let Some(w) = m.crossings_listed_to {
        let more = m.phase_crossings.len().saturating_sub(6);
        s.push_str(&format!(
            "  (the dead time makes the phase cross -180° infinitely often: {} crossings up to \
             w = {} rad/s{}, all in --json)\n",
            m.phase_crossings.len(),
            fmt_sig(w, 7),
            if more > 0 {
                format!(", {more} not shown")
            } else {
                String::new()
            }
        ));
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
