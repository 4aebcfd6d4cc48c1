//! The `analyze --json` document of a library [`Analysis`], key for key.
//!
//! The command line builds this document in `ltikit::cli::analyze::json` (private to the CLI);
//! this is the same mapping from the library's `Analysis` — the library computes everything,
//! here the fields are only named as the JSON contract names them (DESIGN §1.2).

use serde_json::{Map, Value, json};

use ltikit::analysis::{Analysis, StepInfo};

use crate::convert::{finite, pair};

/// The complex numbers of `roots`, with repetition, as `[re, im]` pairs.
fn pairs(roots: &[ltikit::Root]) -> Value {
    json!(
        crate::convert::repeated(roots)
            .into_iter()
            .map(pair)
            .collect::<Vec<_>>()
    )
}

/// The step metrics as `analyze --json` writes them: `null` plus a `…_note` for a metric that
/// could not be computed.
pub fn step_info_json(s: &StepInfo) -> Value {
    let mut m = Map::new();
    let put = |m: &mut Map<String, Value>, key: &str, v: Option<f64>| {
        m.insert(key.into(), json!(v));
        if let Some(n) = s.note(key) {
            m.insert(format!("{key}_note"), json!(n));
        }
    };
    put(&mut m, "rise_time", s.rise_time);
    put(&mut m, "settling_time", s.settling_time);
    put(&mut m, "overshoot_percent", s.overshoot_percent);
    put(&mut m, "peak", s.peak);
    put(&mut m, "peak_time", s.peak_time.and_then(finite));
    m.insert("steady_state".into(), json!(s.steady_state));
    put(&mut m, "transient_time", s.transient_time);
    put(&mut m, "settling_min", s.settling_min);
    put(&mut m, "settling_max", s.settling_max);
    put(&mut m, "undershoot_percent", s.undershoot_percent);
    Value::Object(m)
}

/// The `analyze --json` document of one plant.
pub fn analysis_json(a: &Analysis) -> Value {
    let pz = &a.pole_zero;
    let mut m = Map::new();
    m.insert("dt".into(), json!(a.dt));
    m.insert("order".into(), json!(a.order));
    m.insert("relative_degree".into(), json!(a.relative_degree));
    m.insert("poles".into(), pairs(&pz.poles));
    m.insert("zeros".into(), pairs(&pz.zeros));
    m.insert("zeros_at_infinity".into(), json!(pz.zeros_at_infinity));
    m.insert("cancelled".into(), pairs(&pz.cancelled));
    m.insert(
        "near_cancellations".into(),
        json!(
            a.near_cancellations
                .iter()
                .map(|n| json!({
                    "zero": pair(n.zero),
                    "pole": pair(n.pole),
                    "multiplicity": n.multiplicity,
                    "distance": n.distance,
                    "relative_distance": n.relative,
                }))
                .collect::<Vec<_>>()
        ),
    );
    m.insert("dc_gain".into(), json!(a.dc_gain.and_then(finite)));
    m.insert("bibo_stable".into(), json!(a.stability.bibo_stable));
    m.insert(
        "internally_stable".into(),
        json!(a.stability.internally_stable),
    );
    m.insert("stability_reason".into(), json!(a.stability.reason));
    m.insert("structure".into(), json!(a.structure.as_str()));
    m.insert("structure_note".into(), json!(a.structure_note));
    m.insert(
        "modes".into(),
        json!(
            a.modes
                .iter()
                .map(|md| json!({
                    "pole": pair(md.pole),
                    "multiplicity": md.multiplicity,
                    "wn": md.wn,
                    "zeta": md.zeta,
                    "time_constant": md.time_constant,
                }))
                .collect::<Vec<_>>()
        ),
    );
    m.insert(
        "second_order".into(),
        a.second_order.map_or(
            Value::Null,
            |s| json!({"class": s.class, "wn": s.wn, "zeta": s.zeta, "wd": s.wd}),
        ),
    );
    m.insert(
        "step_info".into(),
        a.step_info.as_ref().map_or(Value::Null, step_info_json),
    );
    if let Some(n) = &a.step_info_note {
        m.insert("step_info_note".into(), json!(n));
    }
    Value::Object(m)
}
