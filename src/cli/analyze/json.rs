//! The `analyze` JSON contract (DESIGN §1.2): the library's analysis as the documents
//! `analyze --json` and each line of `analyze --batch` print. A quantity that could not be
//! computed is `null` with a `…_note` beside it.

use serde::Serialize;

use super::whole_model;
use crate::analysis::{Analysis, StepInfo};
use crate::cli::output::{finite, pair};
use crate::poly::roots::flatten;

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
    pub(super) whole_model: Option<whole_model::WholeModelJson>,
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
pub(crate) struct StepInfoJson {
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
