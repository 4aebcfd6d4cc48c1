//! Margins, bandwidth and resonance of a plant given as a dense state-space realisation
//! (issue 24 item 2): the crossings are found on the factors computed from the realisation
//! (eigenvalues, transmission zeros, gain) and then refined on the realisation's own G(jω).
//!
//! The model (`tests/data/dense18.json`): nine second-order sections, lightly (ζ = 0.02) and
//! heavily (ζ = 0.8) damped in turn, ωₙ log-spaced over [0.3, 30], each lightly damped one
//! with a lightly damped zero pair just above it, behind a dense random similarity: 18 states
//! without structure. Its reference margins are computed
//! from the stored matrices with mpmath at 40 digits by `tests/data/dense18_reference.py`
//! (which also built the model). The stored matrices are the model (the rounding of the
//! similarity moves G a little away from the sections it came from).

use ltikit::StateSpace;
use ltikit::analysis::Factored;
use serde_json::Value;

mod common;
use common::{json_matrix, rel};

fn fixture() -> (StateSpace, Value) {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/dense18.json"
    ))
    .unwrap();
    let v: Value = serde_json::from_str(&text).unwrap();
    let ss = StateSpace::new(
        json_matrix(&v["a"]),
        json_matrix(&v["b"]),
        json_matrix(&v["c"]),
        json_matrix(&v["d"]),
    )
    .unwrap();
    (ss, v)
}

#[test]
fn margins_of_a_dense_realisation_to_ten_digits() {
    let (ss, r) = fixture();
    assert_eq!(ss.order(), 18);
    let f = Factored::from_state_space(&ss).unwrap();
    let m = f.margins().unwrap();
    let mut worst = Vec::new();
    let mut check = |name: String, got: f64, want: f64| {
        eprintln!("{name}: {got} vs {want}: {:.1e}", rel(got, want));
        worst.push((rel(got, want), name));
    };
    let gains = r["gain_crossings"].as_array().unwrap();
    assert_eq!(
        m.gain_crossings.len(),
        gains.len(),
        "{:?}",
        m.gain_crossings
    );
    for (i, (a, b)) in m.gain_crossings.iter().zip(gains).enumerate() {
        check(format!("gain crossing {i}"), a.w, b["w"].as_f64().unwrap());
        check(
            format!("phase margin {i}"),
            a.phase_margin_deg,
            b["phase_margin_deg"].as_f64().unwrap(),
        );
    }
    // Phase crossings where |G| ≥ 1e-4 (gain margin ≤ 1e4): to ten digits. Beyond, G(jω) of
    // the realisation is a sum that cancels (the refinement keeps the factors' value there).
    let phases = r["phase_crossings"].as_array().unwrap();
    assert_eq!(
        m.phase_crossings.len(),
        phases.len(),
        "{:?}",
        m.phase_crossings
    );
    for (i, (a, b)) in m.phase_crossings.iter().zip(phases).enumerate() {
        let want = b["gain_margin"].as_f64().unwrap();
        if want > 1e4 {
            eprintln!(
                "phase crossing {i} (|G| = {:.1e}, not checked): {} vs {}",
                1.0 / want,
                a.w,
                b["w"]
            );
            continue;
        }
        check(format!("phase crossing {i}"), a.w, b["w"].as_f64().unwrap());
        check(format!("gain margin {i}"), a.gain_margin, want);
    }
    // MATLAB's headline: the gain margin closest to 0 dB, the phase margin closest to 0°
    let gm = phases
        .iter()
        .map(|p| p["gain_margin"].as_f64().unwrap())
        .min_by(|a, b| a.ln().abs().total_cmp(&b.ln().abs()))
        .unwrap();
    let pm = gains
        .iter()
        .map(|p| p["phase_margin_deg"].as_f64().unwrap())
        .min_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap();
    check("gain margin (headline)".into(), m.gain_margin.unwrap(), gm);
    check(
        "phase margin (headline)".into(),
        m.phase_margin_deg.unwrap(),
        pm,
    );
    check(
        "bandwidth".into(),
        m.bandwidth.unwrap(),
        r["bandwidth"].as_f64().unwrap(),
    );
    check(
        "resonant peak".into(),
        m.resonant_peak.unwrap(),
        r["resonant_peak"].as_f64().unwrap(),
    );
    check(
        "resonant frequency".into(),
        m.resonant_frequency.unwrap(),
        r["resonant_frequency"].as_f64().unwrap(),
    );
    let bad: Vec<_> = worst
        .iter()
        .filter(|(e, _)| e.is_nan() || *e > 1e-10)
        .collect();
    assert!(bad.is_empty(), "{bad:?}");
}
