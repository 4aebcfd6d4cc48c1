//! `ltikit analyze`. On a state-space plant analysed as a whole (not one `--channel`, not a
//! loop) the report adds the whole-model analysis ([`whole_model`]).

mod whole_model;

use anyhow::Result;
use clap::Args;
use serde::Serialize;

use super::output::{finite, pair, print, print_json};
use super::text::roots_texts;
use super::{Plant, PlantArgs, UsageError, channels};
use crate::analysis::{Analysis, Factored, StepInfo};
use crate::fmt::{fmt_num, fmt_root, fmt_sig};
use crate::poly::roots::flatten;

#[derive(Args, Debug)]
pub struct AnalyzeArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// Print one JSON document (the stable contract) instead of the report.
    #[arg(long)]
    pub json: bool,
    /// Analyse many plants: a JSONL file (one {"num": [...], "den": [...], "name": "..."} per
    /// line, or - for stdin); prints one JSON line per plant (the analyze contract plus
    /// "margins"), in input order, using all cores.
    #[arg(long, value_name = "FILE.jsonl")]
    pub batch: Option<String>,
    /// State-space plant: print the whole modes table of the whole-model section also for a
    /// large model (more than 20 distinct eigenvalues up to conjugation, which get a summary).
    #[arg(long, conflicts_with = "batch")]
    pub modes: bool,
    /// State-space plant: also print every mode's shapes (unit eigenvectors, each as its 4
    /// largest components with the state names; implies --modes); with --json, "shapes" in
    /// every mode of "state_space".
    #[arg(long, conflicts_with = "batch")]
    pub shapes: bool,
}

pub fn run(a: &AnalyzeArgs) -> Result<()> {
    if let Some(src) = &a.batch {
        return super::batch::run(src);
    }
    let plant = a.plant.single()?;
    let chans = a.plant.channels(&plant)?;
    let whole = whole_model::for_plant(&plant, a.plant.channel()?.is_some());
    if whole.is_none() && (a.modes || a.shapes) {
        return Err(UsageError(
            "--modes and --shapes belong to the whole-model section of a state-space plant: \
             not for a transfer function, a loop with a controller or one --channel"
                .into(),
        )
        .into());
    }
    let detail = whole_model::Detail {
        modes: a.modes,
        shapes: a.shapes,
    };
    let whole_json = whole
        .as_ref()
        .map(|w| whole_model::WholeModelJson::new(w, a.shapes));
    if !chans.per_channel {
        let f = &chans.list[0].factored;
        let analysis = f.analyze()?;
        return if a.json {
            let mut doc = AnalyzeJson::from(&analysis);
            doc.whole_model = whole_json;
            print_json(&doc)
        } else {
            let mut text = report(&plant, f, &analysis);
            if let Some(w) = &whole {
                text.push('\n');
                text.push_str(&whole_model::text(&plant, w, detail));
            }
            print(&text)
        };
    }
    let mut docs = Vec::with_capacity(chans.list.len());
    let mut text = channels::plant_header(&plant);
    if let Some(w) = &whole {
        text.push('\n');
        text.push_str(&whole_model::text(&plant, w, detail));
    }
    for ch in &chans.list {
        let analysis = ch.factored.analyze()?;
        if a.json {
            docs.push((ch.input, ch.output, AnalyzeJson::from(&analysis)));
        } else {
            text.push_str(&channels::block_heading(&plant, ch));
            text.push_str(&format!("{}\n", super::text::channel_g_text(&ch.factored)));
            text.push_str(&body(&ch.factored, &analysis));
        }
    }
    if a.json {
        print_json(&channels::mimo_json(&plant, &docs)?.with_whole_model(whole_json)?)
    } else {
        print(&text)
    }
}

/// The `analyze` JSON contract (DESIGN §1.2).
#[derive(Serialize)]
pub struct AnalyzeJson {
    order: usize,
    relative_degree: Option<i64>,
    poles: Vec<[f64; 2]>,
    zeros: Vec<[f64; 2]>,
    zeros_at_infinity: Option<usize>,
    cancelled: Vec<[f64; 2]>,
    /// Zeros within a relative 1e-6 of a pole that do not cancel it.
    near_cancellations: Vec<NearPairJson>,
    dc_gain: Option<f64>,
    bibo_stable: bool,
    internally_stable: bool,
    stability_reason: String,
    structure: &'static str,
    structure_note: String,
    modes: Vec<ModeJson>,
    second_order: Option<SecondOrderJson>,
    step_info: Option<StepInfoJson>,
    /// Why `step_info` is `null` (absent when it is not).
    #[serde(skip_serializing_if = "Option::is_none")]
    step_info_note: Option<String>,
    /// `"state_space"` and `"state_space_note"`: only for a state-space plant analysed as a
    /// whole (absent otherwise, and in batch lines and linearisations).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    whole_model: Option<whole_model::WholeModelJson>,
}

#[derive(Serialize)]
struct NearPairJson {
    zero: [f64; 2],
    pole: [f64; 2],
    multiplicity: usize,
    distance: f64,
    relative_distance: f64,
}

#[derive(Serialize)]
struct ModeJson {
    pole: [f64; 2],
    multiplicity: usize,
    wn: f64,
    zeta: Option<f64>,
    time_constant: Option<f64>,
}

#[derive(Serialize)]
struct SecondOrderJson {
    class: &'static str,
    wn: Option<f64>,
    zeta: Option<f64>,
    wd: Option<f64>,
}

/// The step metrics in JSON: a metric that could not be computed is `null` with a
/// `…_note` beside it; a value obtained otherwise than by root-finding carries its note too.
#[derive(Serialize)]
pub(super) struct StepInfoJson {
    rise_time: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rise_time_note: Option<String>,
    settling_time: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    settling_time_note: Option<String>,
    overshoot_percent: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    overshoot_percent_note: Option<String>,
    peak: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    peak_note: Option<String>,
    /// `null` also when the peak is only approached as t → ∞ (no note then).
    peak_time: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    peak_time_note: Option<String>,
    steady_state: f64,
    transient_time: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    transient_time_note: Option<String>,
    settling_min: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    settling_min_note: Option<String>,
    settling_max: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    settling_max_note: Option<String>,
    undershoot_percent: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    undershoot_percent_note: Option<String>,
}

impl From<&StepInfo> for StepInfoJson {
    fn from(s: &StepInfo) -> Self {
        let note = |q: &str| s.note(q).map(str::to_string);
        StepInfoJson {
            rise_time: s.rise_time,
            rise_time_note: note("rise_time"),
            settling_time: s.settling_time,
            settling_time_note: note("settling_time"),
            overshoot_percent: s.overshoot_percent,
            overshoot_percent_note: note("overshoot_percent"),
            peak: s.peak,
            peak_note: note("peak"),
            peak_time: s.peak_time.and_then(finite),
            peak_time_note: note("peak_time"),
            steady_state: s.steady_state,
            transient_time: s.transient_time,
            transient_time_note: note("transient_time"),
            settling_min: s.settling_min,
            settling_min_note: note("settling_min"),
            settling_max: s.settling_max,
            settling_max_note: note("settling_max"),
            undershoot_percent: s.undershoot_percent,
            undershoot_percent_note: note("undershoot_percent"),
        }
    }
}

impl From<&Analysis> for AnalyzeJson {
    fn from(a: &Analysis) -> Self {
        let pz = &a.pole_zero;
        AnalyzeJson {
            order: a.order,
            relative_degree: a.relative_degree,
            poles: flatten(&pz.poles).into_iter().map(pair).collect(),
            zeros: flatten(&pz.zeros).into_iter().map(pair).collect(),
            zeros_at_infinity: pz.zeros_at_infinity,
            cancelled: flatten(&pz.cancelled).into_iter().map(pair).collect(),
            near_cancellations: a
                .near_cancellations
                .iter()
                .map(|n| NearPairJson {
                    zero: pair(n.zero),
                    pole: pair(n.pole),
                    multiplicity: n.multiplicity,
                    distance: n.distance,
                    relative_distance: n.relative,
                })
                .collect(),
            dc_gain: a.dc_gain.and_then(finite),
            bibo_stable: a.stability.bibo_stable,
            internally_stable: a.stability.internally_stable,
            stability_reason: a.stability.reason.clone(),
            structure: a.structure.as_str(),
            structure_note: a.structure_note.clone(),
            modes: a
                .modes
                .iter()
                .map(|m| ModeJson {
                    pole: pair(m.pole),
                    multiplicity: m.multiplicity,
                    wn: m.wn,
                    zeta: m.zeta,
                    time_constant: m.time_constant,
                })
                .collect(),
            second_order: a.second_order.map(|s| SecondOrderJson {
                class: match s.class {
                    crate::analysis::DampingClass::Undamped => "undamped",
                    crate::analysis::DampingClass::Underdamped => "underdamped",
                    crate::analysis::DampingClass::CriticallyDamped => "critically_damped",
                    crate::analysis::DampingClass::Overdamped => "overdamped",
                    crate::analysis::DampingClass::Unstable => "unstable",
                },
                wn: s.wn,
                zeta: s.zeta,
                wd: s.wd,
            }),
            step_info: a.step_info.as_ref().map(StepInfoJson::from),
            step_info_note: a.step_info_note.clone(),
            whole_model: None,
        }
    }
}

/// The human-readable report.
pub fn report(plant: &Plant, f: &Factored, a: &Analysis) -> String {
    let mut s = String::new();
    s.push_str(&format!("{}\n", super::text::g_text(plant, f)));
    if !plant.name.contains(" / ") {
        s.push_str(&format!("  {}\n", plant.name));
    }
    if let Some(d) = &plant.description {
        s.push_str(&format!("  {d}\n"));
    }
    s.push_str(&body(f, a));
    s
}

/// The report below the plant's name: order, poles and zeros, stability, modes, step metrics.
pub fn body(f: &Factored, a: &Analysis) -> String {
    let pz = &a.pole_zero;
    let mut s = String::new();
    match a.relative_degree {
        Some(r) => s.push_str(&format!("  order {}, relative degree {r}\n\n", a.order)),
        None => s.push_str(&format!(
            "  order {}, G = 0 (no relative degree, no zeros)\n\n",
            a.order
        )),
    }
    // one precision for every list: distinct values across them never print alike
    let near_values: Vec<crate::Root> = a
        .near_cancellations
        .iter()
        .flat_map(|n| [crate::Root::new(n.zero, 1), crate::Root::new(n.pole, 1)])
        .collect();
    let texts = roots_texts(&[&pz.poles, &pz.zeros, &pz.cancelled, &near_values]);
    s.push_str(&format!("Poles:     {}\n", texts[0]));
    s.push_str(&format!("Zeros:     {}", texts[1]));
    if let Some(k) = pz.zeros_at_infinity.filter(|&k| k > 0) {
        s.push_str(&format!("; {k} at infinity"));
    }
    s.push('\n');
    if !pz.cancelled.is_empty() {
        if f.transfer_function().is_none()
            && f.reduced_poles()
                .iter()
                .map(|r| r.multiplicity)
                .sum::<usize>()
                > super::text::MAX_PRINTED_ORDER
        {
            s.push_str(&format!(
                "Cancelled: {} (modes removed by the minimal realisation: uncontrollable or unobservable; minimal order {})\n",
                texts[2],
                f.reduced_poles().iter().map(|r| r.multiplicity).sum::<usize>()
            ));
        } else {
            let reduced = f
                .reduced_tf()
                .map(|g| g.to_string())
                .unwrap_or_else(|_| "(too large to print)".into());
            s.push_str(&format!(
                "Cancelled: {} ({}; reduced G = {reduced})\n",
                texts[2],
                if pz.cancelled.iter().all(|c| pz.zeros.iter().any(|z| {
                    if a.structure == crate::analysis::StructurePath::Exact {
                        z.value == c.value
                    } else {
                        z.same_as(c.value)
                    }
                })) {
                    "common to numerator and denominator"
                } else {
                    "against zeros within the --minreal tolerance"
                },
            ));
        }
    }
    s.push_str(&near_text(&a.near_cancellations));
    s.push_str(&format!(
        "dc gain:   {}\n\n",
        match a.dc_gain {
            Some(g) => fmt_num(g),
            None => "infinite (pole at s = 0)".into(),
        }
    ));
    let st = &a.stability;
    s.push_str(&format!(
        "Stability: {}, {} — {}\n",
        if st.bibo_stable {
            "BIBO stable"
        } else {
            "not BIBO stable"
        },
        if st.internally_stable {
            "internally stable"
        } else {
            "not internally stable"
        },
        st.reason
    ));
    s.push_str(&format!("Structure: {}\n\n", a.structure_note));
    if !a.modes.is_empty() {
        s.push_str("Modes:\n");
        s.push_str(&format!(
            "  {:<28} {:>12} {:>10} {:>14}\n",
            "pole", "wn [rad/s]", "zeta", "tau [s]"
        ));
        for m in a.modes.iter().filter(|m| m.pole.im >= 0.0) {
            let mult = if m.multiplicity > 1 {
                format!(" (×{})", m.multiplicity)
            } else {
                String::new()
            };
            s.push_str(&format!(
                "  {:<28} {:>12} {:>10} {:>14}\n",
                format!("{}{mult}", fmt_root(m.pole, 6)),
                fmt_sig(m.wn, 6),
                m.zeta.map(|z| fmt_sig(z, 6)).unwrap_or_else(|| "-".into()),
                m.time_constant
                    .map(|t| fmt_sig(t, 6))
                    .unwrap_or_else(|| "-".into())
            ));
        }
        s.push('\n');
    }
    if let Some(so) = &a.second_order {
        s.push_str(&format!("Second order: {}", so.class.words()));
        if let (Some(wn), Some(z)) = (so.wn, so.zeta) {
            s.push_str(&format!(
                ", wn = {} rad/s, zeta = {}",
                fmt_sig(wn, 6),
                fmt_sig(z, 6)
            ));
        }
        if let Some(wd) = so.wd {
            s.push_str(&format!(", wd = {} rad/s", fmt_sig(wd, 6)));
        }
        s.push_str("\n\n");
    }
    match (&a.step_info, &a.step_info_note) {
        (Some(si), _) => s.push_str(&step_text(si)),
        (None, Some(note)) => s.push_str(&format!("Step response: {note}\n")),
        (None, None) => s.push_str("Step response: no step metrics\n"),
    }
    s
}

/// The near pole-zero pairs, one line each: "Near:      zero -2.00000000001 and pole -2
/// (distance 1e-11, relative 5e-12; not cancelled — --minreal 1e-11 cancels pairs this close)".
fn near_text(near: &[crate::analysis::NearPair]) -> String {
    let mut s = String::new();
    for (k, n) in near.iter().enumerate() {
        let sig = super::text::distinguishing_digits(&[n.zero, n.pole], 6);
        let mult = if n.multiplicity > 1 {
            format!(" (×{})", n.multiplicity)
        } else {
            String::new()
        };
        s.push_str(&format!(
            "{}zero {} and pole {}{mult} (distance {}, relative {}; not cancelled: --minreal {} \
             cancels pairs this close)\n",
            if k == 0 { "Near:      " } else { "           " },
            fmt_root(n.zero, sig),
            fmt_root(n.pole, sig),
            fmt_sig(n.distance, 3),
            fmt_sig(n.relative, 3),
            fmt_sig(10f64.powf((n.relative * (1.0 + 1e-9)).log10().ceil()), 1),
        ));
    }
    s
}

/// The step metrics in words; a metric that could not be computed reads "not computed"
/// and its note follows.
fn step_text(si: &StepInfo) -> String {
    let v = |x: Option<f64>| x.map_or_else(|| "not computed".to_string(), |x| fmt_sig(x, 7));
    let peak_at = match si.peak_time {
        Some(t) if t.is_finite() => format!("at t = {} s", fmt_sig(t, 7)),
        Some(_) => "approached as t → ∞".into(),
        None => String::new(),
    };
    let mut s = format!(
        "Step response (exact):\n  rise time {} s (10–90 %), settling time {} s (2 %)\n  \
         overshoot {} %, peak {} {peak_at}, final value {}\n",
        v(si.rise_time),
        v(si.settling_time),
        v(si.overshoot_percent),
        v(si.peak),
        fmt_sig(si.steady_state, 7)
    );
    s.push_str(&format!(
        "  settling min {}, max {}; undershoot {} %; transient time {} s\n",
        v(si.settling_min),
        v(si.settling_max),
        v(si.undershoot_percent),
        v(si.transient_time)
    ));
    for n in &si.notes {
        s.push_str(&format!(
            "  {}: {}\n",
            n.quantities.join(", ").replace('_', " "),
            n.reason
        ));
    }
    s
}
