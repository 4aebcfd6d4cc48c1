//! `ltikit analyze`. On a state-space plant analysed as a whole (not one `--channel`, not a
//! loop) the report adds the whole-model analysis ([`whole_model`]).

pub(super) mod json;
mod whole_model;

use anyhow::Result;
use clap::Args;

use super::output::{print, print_json};
use super::text::roots_texts;
use super::{Plant, PlantArgs, UsageError, channels};
use crate::analysis::{Analysis, Factored, StepInfo};
use crate::fmt::{fmt_num, fmt_root, fmt_sig};
use json::AnalyzeJson;

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
            let reduced = reduced_text(f.reduced_tf());
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
            None if a.dt.is_some() => "infinite (pole at z = 1)".into(),
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
/// The reduced G as text: "(too large to print)" only when it is beyond the order limit
/// ([`LtiError::OrderTooHigh`](crate::LtiError::OrderTooHigh)); any other error as itself.
fn reduced_text(g: crate::error::Result<crate::TransferFunction>) -> String {
    match g {
        Ok(g) => g.to_string(),
        Err(crate::LtiError::OrderTooHigh { .. }) => "(too large to print)".into(),
        Err(e) => format!("(not formed: {e})"),
    }
}

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
pub(super) fn step_text(si: &StepInfo) -> String {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::LtiError;

    #[test]
    fn only_the_order_limit_reads_too_large_to_print() {
        let big = Err(LtiError::OrderTooHigh {
            order: 300,
            max: 200,
        });
        assert_eq!(reduced_text(big), "(too large to print)");
        let other = Err(LtiError::invalid(
            "root 1 + 2j has no complex conjugate partner",
        ));
        assert_eq!(
            reduced_text(other),
            "(not formed: root 1 + 2j has no complex conjugate partner)"
        );
        let g = crate::TransferFunction::from_descending(&[1.0], &[1.0, 1.0]);
        assert_eq!(reduced_text(g), "1 / (s + 1)");
    }
}
