//! Each section of a report stands alone, and only what is known is printed (issue 25): every
//! command over plants that break one quantity at a time, noise printed as 0, near pole-zero
//! pairs shown with their distance and cancelled on request, the delay margin of any loop.
//! Runs the real binary.

use serde_json::Value;

mod common;
use common::{json, ltikit, stdout};

/// Plants that each break one quantity: (numerator, denominator, what breaks).
const BREAKERS: [(&str, &str, &str); 7] = [
    (
        "1",
        "1 2e-6 1",
        "a resonator (Q = 5e5): step metrics used to fail as a whole",
    ),
    (
        "1",
        "1 2e-20 1",
        "a pair 1e-20 left of the axis: settling finer than double time",
    ),
    (
        "1 0 0",
        "1 1",
        "improper: no step response, no step metrics",
    ),
    (
        "1",
        "1 0",
        "an integrator: no dc gain, no bandwidth, no step metrics",
    ),
    (
        "0.1",
        "1 1",
        "|G| < 1 everywhere: no gain crossing, no phase or delay margin",
    ),
    (
        "1 -1",
        "1 1 -2",
        "a cancelled unstable pole: BIBO stable, internally unstable",
    ),
    ("1", "1 0 1", "undamped: does not settle"),
];

/// Commands whose whole product needs a proper G (an improper plant is refused by them).
const NEED_PROPER: [&str; 4] = ["response", "rlocus", "step", "nyquist"];

#[test]
fn every_command_over_plants_that_break_one_quantity() {
    let dir = std::env::temp_dir().join(format!("ltikit-known-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (num, den, what) in BREAKERS {
        let improper = num.split(' ').count() > den.split(' ').count();
        for cmd in [
            "analyze", "residue", "response", "freq", "margins", "routh", "rlocus", "bode", "step",
            "pzmap", "nyquist",
        ] {
            let png = dir.join(format!("{cmd}.png"));
            let png = png.to_str().unwrap();
            let mut args = vec![cmd, "--num", num, "--den", den];
            if ["bode", "step", "pzmap", "nyquist"].contains(&cmd) {
                args.extend(["-o", png]);
            }
            let out = ltikit(&args);
            let err = String::from_utf8_lossy(&out.stderr);
            if improper && NEED_PROPER.contains(&cmd) {
                assert_eq!(out.status.code(), Some(1), "{what}: {cmd}");
                assert!(err.contains("proper"), "{what}: {cmd}: {err}");
                continue;
            }
            assert!(out.status.success(), "{what}: {cmd} failed: {err}");
            assert!(!err.contains("panicked"), "{what}: {cmd}: {err}");
            if args.contains(&"-o") {
                let bytes = std::fs::read(png).unwrap();
                assert_eq!(&bytes[1..4], b"PNG", "{what}: {cmd}");
                std::fs::remove_file(png).unwrap();
            } else {
                assert!(!out.stdout.is_empty(), "{what}: {cmd}");
            }
        }
        // analyze --json: every section present; no step metrics comes with the reason
        let v = json(&["analyze", "--json", "--num", num, "--den", den]);
        for key in [
            "poles",
            "zeros",
            "dc_gain",
            "bibo_stable",
            "modes",
            "step_info",
        ] {
            assert!(v.get(key).is_some(), "{what}: {key} missing");
        }
        if v["step_info"].is_null() {
            let note = v["step_info_note"]
                .as_str()
                .unwrap_or_else(|| panic!("{what}: {v}"));
            assert!(note.contains("no step metrics"), "{what}: {note}");
        } else {
            assert!(v.get("step_info_note").is_none(), "{what}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn resonator_report_is_complete_with_exact_metrics() {
    // ζ = 1e-6, ωn = 1 (Q = 5e5): overshoot e^(−πζ/√(1−ζ²)) = 99.99969 %, peak at π/ω_d,
    // settling ≈ ln(50)/ζ = 3.912e6 s (issue 25's first measured failure).
    let s = stdout(&["analyze", "--num", "1", "--den", "1 2e-6 1"]);
    assert!(s.contains("Poles:     -1e-6 ± 1j"), "{s}");
    assert!(s.contains("zeta = 1e-6"), "{s}");
    assert!(
        s.contains("overshoot 99.99969 %, peak 1.999997 at t = 3.141593 s"),
        "{s}"
    );
    assert!(s.contains("settling time 3912021 s"), "{s}");
    let v = json(&["analyze", "--json", "--num", "1", "--den", "1 2e-12 1"]);
    let si = &v["step_info"];
    let os = 100.0 * (-std::f64::consts::PI * 1e-12f64).exp();
    assert!(
        (si["overshoot_percent"].as_f64().unwrap() - os).abs() < 1e-9,
        "{si}"
    );
    assert_eq!(v["modes"][0]["zeta"].as_f64(), Some(1e-12)); // exact: not 0
    assert_eq!(v["second_order"]["class"], "underdamped");
}

#[test]
fn a_quantity_finer_than_double_time_is_null_free_but_noted() {
    // ζ = 1e-20: the settling time is the envelope's horizon, with the reason in a note beside
    // the value in JSON and after the metrics in the text.
    let v = json(&["analyze", "--json", "--num", "1", "--den", "1 2e-20 1"]);
    let si = &v["step_info"];
    let ts = si["settling_time"].as_f64().unwrap();
    assert!((ts - 50f64.ln() / 1e-20).abs() / ts < 1e-14, "{si}");
    assert!(
        si["settling_time_note"]
            .as_str()
            .unwrap()
            .contains("envelope"),
        "{si}"
    );
    let s = stdout(&["analyze", "--num", "1", "--den", "1 2e-20 1"]);
    assert!(s.contains("settling time: from the envelope"), "{s}");
}

#[test]
fn noise_prints_as_zero() {
    // The README's PID loop: the response oscillates below its final value; its minimum is
    // y(0) = 0, computed as −1.3e-17 before (printed "undershoot 1.301043e-15 %").
    let args = [
        "analyze",
        "--model",
        "spring-mass-damper",
        "--controller",
        "pid:kp=2,ki=1,kd=0.5,tf=0.01",
    ];
    let s = stdout(&args);
    assert!(s.contains("undershoot 0 %"), "{s}");
    let mut j = args.to_vec();
    j.push("--json");
    let v: Value = serde_json::from_str(&stdout(&j)).unwrap();
    assert_eq!(v["step_info"]["undershoot_percent"].as_f64(), Some(0.0));
    assert_eq!(v["step_info"]["overshoot_percent"].as_f64(), Some(0.0));
    // 1/(s(s+1)(s+2)) closed with K = 6 has poles ±j√2 and −3: the crossing pair's real part
    // (7.9e-17 before) is within its error bound of the axis, so it is 0.
    let s = stdout(&[
        "analyze",
        "--num",
        "1",
        "--den",
        "1 3 2 0",
        "--controller",
        "p:kp=6",
    ]);
    assert!(s.contains("Poles:     ±1.41421j, -3"), "{s}");
    let v = json(&[
        "analyze",
        "--json",
        "--num",
        "1",
        "--den",
        "1 3 2 0",
        "--controller",
        "p:kp=6",
    ]);
    let poles = v["poles"].as_array().unwrap();
    assert!(
        poles
            .iter()
            .any(|p| p[0].as_f64() == Some(0.0) && p[1].as_f64().unwrap() > 1.41)
    );
    // Mr of ζ = 5e-21 typed as text is 1/(2ζ√(1−ζ²)) = 1e20, not ∞ (the pair is in the open
    // left half plane, decided exactly).
    let v = json(&["margins", "--json", "--num", "1", "--den", "1 1e-20 1"]);
    let mr = v["resonant_peak"].as_f64().unwrap();
    assert!((mr - 1e20).abs() / 1e20 < 1e-12, "{v}");
}

#[test]
fn near_pole_zero_pairs_are_listed_and_cancelled_on_request() {
    // A zero at −2.00000000001 and a pole at −2: distinct (exactly), printed with the digits
    // that tell them apart, listed as a near pair with their distance.
    let args = ["analyze", "--num", "1 2.00000000001", "--den", "1 3 2"];
    let s = stdout(&args);
    assert!(s.contains("Poles:     -1, -2\n"), "{s}");
    assert!(s.contains("Zeros:     -2.00000000001;"), "{s}");
    assert!(
        s.contains("Near:      zero -2.00000000001 and pole -2 (distance 1e-11"),
        "{s}"
    );
    let mut j = args.to_vec();
    j.push("--json");
    let v: Value = serde_json::from_str(&stdout(&j)).unwrap();
    let near = &v["near_cancellations"][0];
    assert!(
        (near["distance"].as_f64().unwrap() - 1e-11).abs() < 1e-15,
        "{near}"
    );
    assert!(v["cancelled"].as_array().unwrap().is_empty());
    // --minreal cancels within the tolerance (and says so on stderr); 1e-12 is too tight
    let out = ltikit(&[
        "analyze",
        "--num",
        "1 2.00000000001",
        "--den",
        "1 3 2",
        "--minreal",
        "1e-8",
    ]);
    let s = String::from_utf8(out.stdout).unwrap();
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        s.contains(
            "Cancelled: -2 (against zeros within the --minreal tolerance; reduced G = 1 / (s + 1))"
        ),
        "{s}"
    );
    assert!(
        err.contains("--minreal 1e-8: cancelled zero -2.00000000001 against pole -2"),
        "{err}"
    );
    let v = json(&[
        "analyze",
        "--json",
        "--num",
        "1 2.00000000001",
        "--den",
        "1 3 2",
        "--minreal",
        "1e-12",
    ]);
    assert!(v["cancelled"].as_array().unwrap().is_empty());
    assert_eq!(v["near_cancellations"].as_array().unwrap().len(), 1);
    // a bad tolerance is one line, exit 1
    let out = ltikit(&["analyze", "--num", "1", "--den", "1 1", "--minreal=-1"]);
    assert_eq!(out.status.code(), Some(1));
}

#[test]
fn margins_report_the_delay_margin_of_any_loop() {
    // 2/(s(s+1)(s+2)): PM = 32.6131° at ω_c = 0.7493683 (margins tests), delay margin
    // PM/ω_c = 0.569198 rad / 0.7493683 rad/s = 0.759581 s (MATLAB allmargin's DelayMargin).
    let v = json(&["margins", "--json", "--num", "2", "--den", "1 3 2 0"]);
    let pm = v["phase_margin_deg"].as_f64().unwrap().to_radians();
    let wc = v["gain_crossover"].as_f64().unwrap();
    let dm = v["delay_margin"].as_f64().unwrap();
    assert!((dm - pm / wc).abs() < 1e-14, "{v}");
    assert!((dm - 0.759581).abs() < 1e-6);
    let s = stdout(&["margins", "--num", "2", "--den", "1 3 2 0"]);
    assert!(s.contains("Delay margin:  0.759581 s"), "{s}");
    // no gain crossing: infinite
    let s = stdout(&["margins", "--num", "0.1", "--den", "1 1"]);
    assert!(s.contains("Delay margin:  ∞"), "{s}");
}
