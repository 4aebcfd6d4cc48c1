//! State-space plants on the command line: MIMO plants per channel (text and JSON contract),
//! the whole-model section of `analyze` (text, JSON, --modes, --shapes, the size limit),
//! the Bode grid, time responses (step per input, --x0, --states, lsim from CSV), the lattice
//! as a model, the per-channel linearisation, and bad input. Runs the real binary.
//!
//! The MIMO test plant is ẋ = diag(−1, −2) x + u, y = [[1, 1], [1, −1]] x (inputs "force 1
//! [N]", "force 2 [N]", outputs "sum [m]", "difference [m]"), whose channels are, in closed
//! form, G11 = G12 = 1/(s + 1) and G21 = 1/(s + 2), G22 = −1/(s + 2) (Gij: input i → output
//! j); the mode s = −2 is uncontrollable from input 1, s = −1 from input 2.

mod common;

use common::{json, ltikit, stdout};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The error line of a failing command and its exit code.
fn error(args: &[&str]) -> (String, i32) {
    let out = ltikit(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(err.lines().count(), 1, "one line expected: {err}");
    (err, out.status.code().unwrap_or(-1))
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("ltikit-cli-ss-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(path: &Path, text: &str) -> String {
    std::fs::write(path, text).unwrap();
    path.display().to_string()
}

fn mimo_file(d: &Path) -> String {
    write(
        &d.join("mimo.toml"),
        "name = \"Two masses\"\n\
         a = \"-1 0; 0 -2\"\n\
         b = [[1, 0], [0, 1]]\n\
         c = \"1 1; 1 -1\"\n\
         inputs = [\"force 1 [N]\", \"force 2 [N]\"]\n\
         outputs = [\"sum [m]\", \"difference [m]\"]\n\
         states = [\"x1\", \"x2\"]\n",
    )
}

#[test]
fn analyze_mimo_per_channel_json_contract() {
    let d = dir("analyze");
    let p = mimo_file(&d);
    let v = json(&["analyze", "--plant", &p, "--json"]);
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    // The whole-model keys of a state-space plant sit before the channels.
    assert_eq!(
        keys,
        [
            "dt",
            "model",
            "name",
            "states",
            "inputs",
            "outputs",
            "state_space",
            "state_space_note",
            "channels"
        ]
    );
    assert_eq!(v["model"], "state-space");
    assert_eq!(v["states"], 2);
    assert_eq!(v["inputs"][1], "force 2 [N]");
    assert_eq!(v["outputs"][0], "sum [m]");
    let ch = v["channels"].as_array().unwrap();
    // Channels input-major; dc gains C_j (−A)⁻¹ B_i: 1, 1, 1/2, −1/2.
    let want = [(1, 1, 1.0), (1, 2, 1.0), (2, 1, 0.5), (2, 2, -0.5)];
    assert_eq!(ch.len(), want.len());
    for (c, (i, o, g)) in ch.iter().zip(want) {
        assert_eq!(
            (c["input"].as_u64(), c["output"].as_u64()),
            (Some(i), Some(o))
        );
        assert!((f(&c["dc_gain"]) - g).abs() < 1e-12, "{c}");
        assert_eq!(c["bibo_stable"], true);
        // The rest is the SISO analyze document.
        assert!(c.get("step_info").is_some() && c.get("modes").is_some());
    }
    assert_eq!(ch[2]["input_name"], "force 2 [N]");
    assert_eq!(ch[3]["output_name"], "difference [m]");
    // Input 1 cannot reach the mode s = −2: it cancels in G11.
    let cancelled = ch[0]["cancelled"].as_array().unwrap();
    assert_eq!(cancelled.len(), 1);
    assert!((f(&cancelled[0][0]) + 2.0).abs() < 1e-9, "{cancelled:?}");
}

#[test]
fn analyze_mimo_text_names_every_channel() {
    let d = dir("text");
    let p = mimo_file(&d);
    let s = stdout(&["analyze", "--plant", &p]);
    for h in [
        "input force 1 [N] → output sum [m]",
        "input force 1 [N] → output difference [m]",
        "input force 2 [N] → output sum [m]",
        "input force 2 [N] → output difference [m]",
    ] {
        assert_eq!(s.matches(h).count(), 1, "{h} in\n{s}");
    }
    assert!(s.contains("2 states, 2 inputs, 2 outputs") && s.contains("states:  x1, x2"));
    // A chosen channel is the SISO report and document, as before.
    let one = json(&["analyze", "--plant", &p, "--channel", "2,2", "--json"]);
    assert!(one.get("channels").is_none());
    assert!(one.get("state_space").is_none() && one.get("state_space_note").is_none());
    assert!((f(&one["dc_gain"]) + 0.5).abs() < 1e-12);
    // A SISO state-space plant keeps the SISO document.
    let siso = json(&[
        "analyze",
        "--a",
        "0 1; -4 -0.8",
        "--b",
        "0; 4",
        "--c",
        "1 0",
        "--json",
    ]);
    assert!(siso.get("channels").is_none());
    assert!((f(&siso["dc_gain"]) - 1.0).abs() < 1e-12);
}

#[test]
fn margins_residue_freq_per_channel() {
    let d = dir("freq");
    let p = mimo_file(&d);
    let v = json(&["freq", "--plant", &p, "--w", "1", "--json"]);
    let ch = v["channels"].as_array().unwrap();
    // |1/(j + 1)| = 1/√2, |−1/(j + 2)| = 1/√5; phases −45° and 180° − atan(1/2).
    let m = |k: usize| f(&ch[k]["points"][0]["magnitude"]);
    assert!((m(0) - 0.5f64.sqrt()).abs() < 1e-12);
    assert!((m(3) - 0.2f64.sqrt()).abs() < 1e-12);
    assert!((f(&ch[0]["points"][0]["phase_deg"]) + 45.0).abs() < 1e-9);
    let text = stdout(&["freq", "--plant", &p, "--w", "1 10"]);
    assert!(text.contains("M[4]") && text.contains("[2] input force 1 [N] → output difference"));
    let r = json(&["residue", "--plant", &p, "--json"]);
    // G22 = −1/(s + 2): one term, residue −1 at −2.
    let t = &r["channels"][3]["terms"];
    let live: Vec<&Value> = t
        .as_array()
        .unwrap()
        .iter()
        .filter(|x| f(&x["residue"][0]).abs() > 1e-12)
        .collect();
    assert_eq!(live.len(), 1, "{t}");
    assert!((f(&live[0]["residue"][0]) + 1.0).abs() < 1e-12);
    assert!((f(&live[0]["pole"][0]) + 2.0).abs() < 1e-12);
    let g = json(&["margins", "--plant", &p, "--json"]);
    assert_eq!(g["channels"].as_array().unwrap().len(), 4);
    // |G11| ≤ 1 everywhere: never crosses 1 above ω = 0.
    assert!(g["channels"][0].get("bandwidth").is_some());
}

/// Width and height from a PNG's IHDR chunk, after checking the signature.
fn png_size(path: &Path) -> (u32, u32) {
    let b = std::fs::read(path).unwrap();
    assert_eq!(
        &b[..8],
        b"\x89PNG\r\n\x1a\n",
        "not a PNG: {}",
        path.display()
    );
    assert_eq!(&b[12..16], b"IHDR");
    let n = |k: usize| u32::from_be_bytes([b[k], b[k + 1], b[k + 2], b[k + 3]]);
    (n(16), n(20))
}

#[test]
fn pictures_of_a_mimo_plant() {
    let d = dir("png");
    let p = mimo_file(&d);
    let grid = d.join("grid.png");
    stdout(&[
        "bode",
        "--plant",
        &p,
        "-o",
        grid.to_str().unwrap(),
        "--size",
        "900x640",
    ]);
    assert_eq!(png_size(&grid), (900, 640));
    let step = d.join("step.png");
    stdout(&["step", "--plant", &p, "-o", step.to_str().unwrap()]);
    assert_eq!(png_size(&step), (1000, 700));
    let pz = d.join("pz.png");
    let listed = stdout(&["pzmap", "--plant", &p, "-o", pz.to_str().unwrap()]);
    for (i, o) in [(1, 1), (1, 2), (2, 1), (2, 2)] {
        let f = d.join(format!("pz-{i}-{o}.png"));
        assert_eq!(png_size(&f), (1000, 700));
        assert!(listed.contains(&f.display().to_string()));
    }
    // One channel: the ordinary Bode diagram.
    let one = d.join("one.png");
    stdout(&[
        "bode",
        "--plant",
        &p,
        "--channel",
        "1,2",
        "-o",
        one.to_str().unwrap(),
    ]);
    assert_eq!(png_size(&one), (1000, 700));
    // Too many cells for the image: one line, exit 1, no file.
    let small = d.join("small.png");
    let (e, code) = error(&[
        "bode",
        "--plant",
        &p,
        "-o",
        small.to_str().unwrap(),
        "--size",
        "200x150",
    ]);
    assert_eq!(code, 1);
    assert!(e.contains("do not fit"), "{e}");
    assert!(!small.exists());
}

#[test]
fn step_impulse_and_initial_state_responses() {
    let d = dir("resp");
    let p = mimo_file(&d);
    let v = json(&["response", "--plant", &p, "--t", "0 1", "--json"]);
    let r = v["responses"].as_array().unwrap();
    assert_eq!(r.len(), 2);
    assert_eq!(r[1]["input"], 2);
    assert_eq!(r[1]["kind"], "step");
    // Closed forms: step on input 1 → y1 = 1 − e^(−t); input 2 → y2 = −(1 − e^(−2t))/2.
    let e1 = 1.0 - (-1f64).exp();
    let e2 = -(1.0 - (-2f64).exp()) / 2.0;
    assert!((f(&r[0]["y"][0][1]) - e1).abs() < 1e-14);
    assert!((f(&r[1]["y"][1][1]) - e2).abs() < 1e-14);
    // Initial state x0 = (1, 3), u = 0: y1 = e^(−t) + 3e^(−2t), states kept.
    let v = json(&[
        "response", "--plant", &p, "--t", "0 1", "--input", "none", "--x0", "1 3", "--states",
        "--json",
    ]);
    let r = &v["responses"][0];
    assert_eq!(r["kind"], "initial");
    let want = (-1f64).exp() + 3.0 * (-2f64).exp();
    assert!((f(&r["y"][0][1]) - want).abs() < 1e-14);
    assert!((f(&r["x"][1][1]) - 3.0 * (-2f64).exp()).abs() < 1e-14);
    // Impulse on input 1 of the text report: y1 = e^(−t) at t = 1, named columns.
    let s = stdout(&["response", "--plant", &p, "--t", "1", "--input", "impulse"]);
    assert!(s.contains("unit impulse on input force 1 [N]") && s.contains("difference [m]"));
    assert!(s.contains("0.3678794412"), "{s}");
}

#[test]
fn lsim_from_csv_matches_the_first_order_closed_form() {
    let d = dir("lsim");
    // ẋ = −x + u, y = x from x(0) = 0.
    let plant = ["--a", "-1", "--b", "1", "--c", "1"];
    // First-order hold of the ramp u = t is exact: y = t − 1 + e^(−t).
    let mut csv = String::from("t,u\n");
    for k in 0..=40 {
        let t = 0.05 * f64::from(k);
        csv.push_str(&format!("{t},{t}\n"));
    }
    let file = write(&d.join("ramp.csv"), &csv);
    let mut args = vec!["response"];
    args.extend(plant);
    args.extend(["--input-file", &file, "--hold", "foh", "--json"]);
    let v = json(&args);
    let r = &v["responses"][0];
    assert_eq!(r["kind"], "lsim");
    let (t, y) = (r["t"].as_array().unwrap(), r["y"][0].as_array().unwrap());
    assert_eq!(t.len(), 41);
    let worst = t
        .iter()
        .zip(y)
        .map(|(t, y)| (f(y) - (f(t) - 1.0 + (-f(t)).exp())).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-14, "max error {worst}");
    // Zero-order hold of a pulse (u = 1 on [0, 1), 0 after) is exact too:
    // y(2) = (1 − e^(−1)) e^(−1).
    let file = write(&d.join("pulse.csv"), "0,1\n1,0\n2,0\n");
    let mut args = vec!["response"];
    args.extend(plant);
    args.extend(["--input-file", &file, "--json"]);
    let v = json(&args);
    let y2 = f(&v["responses"][0]["y"][0][2]);
    assert!((y2 - (1.0 - (-1f64).exp()) * (-1f64).exp()).abs() < 1e-15);
}

#[test]
fn the_lattice_as_a_model() {
    // N = 4 periodic, ω0 = 1: eigenvalues ±j·2 sin(πk/4) (seed eq. 2.71): 0 (×2),
    // ±j√2 (×2 each), ±2j.
    let v = json(&[
        "analyze", "--model", "lattice", "--param", "N=4", "--param", "output=3", "--json",
    ]);
    assert_eq!(v["order"], 8);
    let top = v["poles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| f(&p[1]).abs())
        .fold(0.0, f64::max);
    assert!((top - 2.0).abs() < 1e-9, "{top}");
    let s = stdout(&["analyze", "--model", "lattice", "--param", "N=4"]);
    assert!(s.contains("lattice (N=4, periodic=1, w0=1"), "{s}");
    // In a plant file, with all displacements measured: a MIMO plant per channel.
    let d = dir("lattice");
    let p = write(
        &d.join("lattice.toml"),
        "name = \"ring\"\nmodel = \"lattice\"\n[params]\nN = 3\noutput = 0\n",
    );
    let v = json(&["analyze", "--plant", &p, "--json"]);
    assert_eq!(v["name"], "ring");
    assert_eq!(v["outputs"][2], "q3 [m]");
    assert_eq!(v["channels"].as_array().unwrap().len(), 3);
    let (e, code) = error(&["analyze", "--model", "lattice", "--param", "N=1"]);
    assert_eq!(code, 1);
    assert!(e.contains("parameter N = 1 is invalid"), "{e}");
    let (e, code) = error(&["analyze", "--model", "lattice", "--param", "w0=0"]);
    assert!(code == 1 && e.contains("w0 = 0"), "{e}");
    let (e, code) = error(&[
        "analyze", "--model", "lattice", "--param", "N=16", "--param", "input=17",
    ]);
    assert!(code == 1 && e.contains("input = 17"), "{e}");
    let (e, code) = error(&["analyze", "--model", "lattice", "--param", "N=2000"]);
    assert!(code == 1 && e.contains("N = 2000"), "{e}");
}

#[test]
fn linearised_gyroscope_channels_are_analysed() {
    let v = json(&["linearize", "gyroscope", "--json"]);
    let ch = v["equilibria"][0]["channels"].as_array().unwrap();
    // u2 → theta2 is 2/(s² + 1600): dc gain 2/1600, poles ±40j only.
    let c = ch
        .iter()
        .find(|c| c["input"] == "u2" && c["output"] == "theta2")
        .unwrap();
    assert!(
        (f(&c["analysis"]["dc_gain"]) - 2.0 / 1600.0).abs() < 1e-12,
        "{c}"
    );
    assert_eq!(c["analysis"]["poles"].as_array().unwrap().len(), 2);
    let s = stdout(&["linearize", "gyroscope"]);
    assert!(s.contains("poles ±40j; zeros none; dc gain 0.00125"), "{s}");
}

#[test]
fn bad_input_is_one_line() {
    let d = dir("bad");
    let p = mimo_file(&d);
    let (e, code) = error(&["analyze", "--plant", &p, "--channel", "3,1"]);
    assert_eq!(code, 1);
    assert!(e.contains("input 3"), "{e}");
    let (e, code) = error(&[
        "analyze",
        "--a",
        "0 1 2; 1 2 3",
        "--b",
        "1; 1",
        "--c",
        "1 1",
    ]);
    assert!(code == 1 && e.contains("square"), "{e}");
    let (e, code) = error(&["analyze", "--a", "0 1; 1", "--b", "1; 1", "--c", "1 1"]);
    assert_eq!(code, 1, "{e}");
    let bad = write(&d.join("bad.csv"), "t,u1,u2\n0,1,2\n1,2\n");
    let (e, code) = error(&["response", "--plant", &p, "--input-file", &bad]);
    assert!(
        code == 1 && e.contains("line 3: 2 values, expected 3"),
        "{e}"
    );
    let bad = write(&d.join("nan.csv"), "0,1,2\n1,x,2\n");
    let (e, code) = error(&["response", "--plant", &p, "--input-file", &bad]);
    assert!(
        code == 1 && e.contains("line 2: 'x' is not a number"),
        "{e}"
    );
    let ok = write(&d.join("ok.csv"), "0,1,2\n1,1,2\n");
    let (e, code) = error(&[
        "response",
        "--plant",
        &p,
        "--input-file",
        &ok,
        "--hold",
        "cubic",
    ]);
    assert!(code == 1 && e.contains("zoh or foh"), "{e}");
    let (e, code) = error(&["response", "--plant", &p, "--x0", "1 2 3"]);
    assert!(code == 1 && e.contains("3 values"), "{e}");
    let (e, code) = error(&["response", "--plant", &p, "--input", "ramp"]);
    assert!(code == 1 && e.contains("step, impulse or none"), "{e}");
}

#[test]
fn each_channel_is_factored_once() {
    use ltikit::analysis::factorizations_on_this_thread;
    let d = dir("counts");
    let p = mimo_file(&d);
    let png = d.join("count.png").display().to_string();
    let count = |args: &[&str]| {
        let before = factorizations_on_this_thread();
        let mut argv = vec!["ltikit"];
        argv.extend_from_slice(args);
        ltikit::cli::run_from(argv).unwrap();
        factorizations_on_this_thread() - before
    };
    // Four channels, each factored once; the state-space response factors nothing.
    assert_eq!(count(&["analyze", "--plant", &p, "--json"]), 4);
    assert_eq!(count(&["freq", "--plant", &p, "--json"]), 4);
    assert_eq!(count(&["margins", "--plant", &p]), 4);
    assert_eq!(count(&["bode", "--plant", &p, "-o", &png]), 4);
    assert_eq!(count(&["response", "--plant", &p, "--json"]), 0);
    assert_eq!(count(&["analyze", "--plant", &p, "--channel", "1,2"]), 1);
}

/// The README's two tanks (A = [[−1, 0.5], [0.5, −2]], B = C = I).
fn tanks_file(d: &Path) -> String {
    write(
        &d.join("tanks.toml"),
        "name = \"Two tanks\"\n\
         a = \"-1 0.5; 0.5 -2\"\n\
         b = [[1, 0], [0, 1]]\n\
         c = \"1 0; 0 1\"\n\
         inputs = [\"inflow 1 [m^3/s]\", \"inflow 2 [m^3/s]\"]\n\
         outputs = [\"level 1 [m]\", \"level 2 [m]\"]\n",
    )
}

/// The whole-model section of the two tanks, computed by hand: det A = 1.75, so
/// G(0) = −C·A⁻¹·B = −A⁻¹ = [[2, 0.5], [0.5, 1]]/1.75 = [[8/7, 2/7], [2/7, 4/7]];
/// eigenvalues (−3 ± √2)/2 (λ² + 3λ + 1.75 = 0); minimal; no invariant zeros
/// (det G = 1/det(sI − A)).
#[test]
fn whole_model_of_the_two_tanks() {
    let d = dir("tanks");
    let p = tanks_file(&d);
    let v = json(&["analyze", "--plant", &p, "--json"]);
    let ss = &v["state_space"];
    assert_eq!(v["state_space_note"], Value::Null);
    let keys: Vec<&str> = ss.as_object().unwrap().keys().map(String::as_str).collect();
    assert_eq!(
        keys,
        [
            "states",
            "inputs",
            "outputs",
            "eigenvalues",
            "controllability",
            "observability",
            "minimal_order",
            "uncontrollable_modes",
            "unobservable_modes",
            "invariant_zeros",
            "invariant_zeros_note",
            "system_pencil",
            "dc_gain",
            "bibo_stable",
            "internally_stable",
            "internal_reason",
            "modes"
        ]
    );
    assert_eq!(
        (ss["states"].as_u64(), ss["inputs"].as_u64()),
        (Some(2), Some(2))
    );
    let want = [[8.0 / 7.0, 2.0 / 7.0], [2.0 / 7.0, 4.0 / 7.0]];
    for (j, row) in want.iter().enumerate() {
        for (i, g) in row.iter().enumerate() {
            let x = f(&ss["dc_gain"][j][i]);
            assert!((x - g).abs() <= 4.0 * f64::EPSILON, "{j},{i}: {x} vs {g}");
        }
    }
    let s2 = 2f64.sqrt();
    let ev = ss["eigenvalues"].as_array().unwrap();
    assert_eq!(ev.len(), 2);
    assert!((f(&ev[0]["value"][0]) - (-3.0 + s2) / 2.0).abs() < 1e-15);
    assert!((f(&ev[1]["value"][0]) - (-3.0 - s2) / 2.0).abs() < 1e-15);
    assert_eq!(ev[0]["algebraic"], 1);
    assert_eq!(ev[0]["semisimple"], true);
    assert_eq!(ss["controllability"]["rank"], 2);
    assert!(f(&ss["controllability"]["tol"]) > 0.0);
    assert_eq!(ss["minimal_order"], 2);
    assert_eq!(ss["invariant_zeros"], serde_json::json!([]));
    assert_eq!(
        ss["bibo_stable"],
        serde_json::json!([[true, true], [true, true]])
    );
    assert_eq!(ss["internally_stable"], true);
    let md = &ss["modes"][0];
    assert_eq!(md["geometric"], 1);
    assert!(f(&md["residual_max"]) < 1e-15);
    // τ = −1/λ and ζ = 1 for a real stable mode; no shapes without --shapes.
    assert!((f(&md["time_constant"]) * (3.0 - s2) / 2.0 - 1.0).abs() < 1e-14);
    assert_eq!(md["zeta"], 1.0);
    assert!(md.get("shapes").is_none());
    // The text: after the plant header, before the first channel, with the signal names.
    let s = stdout(&["analyze", "--plant", &p]);
    let at = |needle: &str| {
        s.find(needle)
            .unwrap_or_else(|| panic!("{needle:?} not in\n{s}"))
    };
    assert!(at("states:  x1, x2") < at("State space (whole model)"));
    assert!(at("State space (whole model)") < at("── input inflow 1 [m^3/s] → output level 1 [m]"));
    assert!(
        s.contains("  eigenvalues of A:   -0.792893, -2.20711\n"),
        "{s}"
    );
    assert!(
        s.contains("  minimal order:      2 (minimal: nothing removed)\n"),
        "{s}"
    );
    assert!(s.contains("  invariant zeros:    none\n"), "{s}");
    assert!(s.contains(
        "internal stability: stable — every eigenvalue of A in the open left half plane"
    ));
    // Rows = outputs, columns = inputs: 8/7, 2/7 / 2/7, 4/7 to six digits.
    assert!(s.contains("inflow 1 [m^3/s]  inflow 2 [m^3/s]"), "{s}");
    assert!(
        s.contains("    level 1 [m]           1.14286          0.285714\n"),
        "{s}"
    );
    assert!(
        s.contains("    level 2 [m]          0.285714          0.571429\n"),
        "{s}"
    );
    assert!(
        s.contains("    level 1 [m]               yes               yes\n"),
        "{s}"
    );
    // The modes table (two modes: always printed for a small model).
    assert!(s.contains("eigenvalue") && s.contains("geometric") && s.contains("residual"));
    assert!(
        s.contains("    -0.792893                        0.792893          1"),
        "{s}"
    );
}

/// Two decoupled lags x1' = −x1 + 2u, x2' = −3x2, y = x: the input reaches only x1, so
/// the mode −3 is uncontrollable and the minimal order is 1; G1 = 2/(s + 1) (dc gain 2),
/// G2 = 0 (dc gain 0); one input, two outputs. By hand, P(λ) = [−1−λ 0 2; 0 −3−λ 0; 1 0 0;
/// 0 1 0] has the left null vector (0, 1, 0, 3 + λ) (left index 1) and the infinite zero of
/// G₁ (order 1): 2 + 2 rows, 1 + 2 columns — no finite zero (the uncontrollable −3 is
/// absorbed by the singular part: P(−3) keeps rank 3).
#[test]
fn whole_model_of_decoupled_lags() {
    let args = [
        "analyze",
        "--a",
        "-1 0; 0 -3",
        "--b",
        "2; 0",
        "--c",
        "1 0; 0 1",
        "--json",
    ];
    let v = json(&args);
    let ss = &v["state_space"];
    assert_eq!(ss["minimal_order"], 1);
    assert_eq!(ss["controllability"]["rank"], 1);
    assert_eq!(ss["observability"]["rank"], 2);
    let unc = ss["uncontrollable_modes"].as_array().unwrap();
    assert_eq!(unc.len(), 1);
    assert!((f(&unc[0][0]) + 3.0).abs() <= 8.0 * f64::EPSILON && f(&unc[0][1]) == 0.0);
    assert_eq!(ss["unobservable_modes"], serde_json::json!([]));
    assert!((f(&ss["dc_gain"][0][0]) - 2.0).abs() <= 8.0 * f64::EPSILON);
    assert!(f(&ss["dc_gain"][1][0]).abs() <= 8.0 * f64::EPSILON);
    assert_eq!(ss["invariant_zeros"], serde_json::json!([]));
    assert_eq!(ss["invariant_zeros_note"], Value::Null);
    assert_eq!(
        ss["system_pencil"],
        serde_json::json!({"normal_rank": 1, "infinite_zero_orders": [1],
            "left_kronecker_indices": [1], "right_kronecker_indices": []})
    );
    let s = stdout(&args[..args.len() - 1]);
    assert!(
        s.contains("  minimal order:      1 (1 mode removed)\n"),
        "{s}"
    );
    assert!(
        s.contains("    uncontrollable:   -3\n    unobservable:     none\n"),
        "{s}"
    );
    assert!(
        s.contains("  invariant zeros:    none\n  system pencil:      normal rank 1 of 1; infinite zeros of order 1; left indices 1; right indices none\n"),
        "{s}"
    );
    assert!(
        s.contains("    y1           2\n") && s.contains("    y2           0\n"),
        "{s}"
    );
}

/// Resonance x'' + x = z, z'' + z = u (y = x): ±j is a 2×2 Jordan block each — defective on
/// the axis, so A is unstable and G = 1/(s² + 1)² is not BIBO stable. Two identical
/// undamped oscillators instead (A = diag(J, J)): ±j semisimple of multiplicity 2,
/// marginally stable.
#[test]
fn defective_and_semisimple_eigenvalues_on_the_axis() {
    let jordan = [
        "analyze",
        "--a",
        "0 1 0 0; -1 0 1 0; 0 0 0 1; 0 0 -1 0",
        "--b",
        "0; 0; 0; 1",
        "--c",
        "1 0 0 0",
    ];
    let s = stdout(&jordan);
    assert!(
        s.contains("  eigenvalues of A:   ±1j (×2, defective: algebraic 2, geometric 1)\n"),
        "{s}"
    );
    assert!(
        s.contains(
            "internal stability: unstable — eigenvalue ±1j on the imaginary axis is defective"
        ),
        "{s}"
    );
    let mut with_json = jordan.to_vec();
    with_json.push("--json");
    let v = json(&with_json);
    let ss = &v["state_space"];
    assert_eq!(ss["internally_stable"], false);
    assert_eq!(ss["bibo_stable"], serde_json::json!([[false]]));
    for e in ss["eigenvalues"].as_array().unwrap() {
        assert_eq!(f(&e["value"][0]), 0.0, "{e}");
        assert_eq!(
            (e["algebraic"].as_u64(), e["geometric"].as_u64()),
            (Some(2), Some(1))
        );
        assert_eq!(e["semisimple"], false);
    }
    let twins = [
        "analyze",
        "--a",
        "0 1 0 0; -1 0 0 0; 0 0 0 1; 0 0 -1 0",
        "--b",
        "0 0; 1 0; 0 0; 0 1",
        "--c",
        "1 0 0 0; 0 0 1 0",
    ];
    let s = stdout(&twins);
    assert!(
        s.contains("  eigenvalues of A:   ±1j (×2, semisimple)\n"),
        "{s}"
    );
    assert!(
        s.contains("internal stability: marginally stable — eigenvalue ±1j on the imaginary axis (semisimple, multiplicity 2)"),
        "{s}"
    );
    // ζ = 0 and no time constant: "-" in the table.
    assert!(
        s.contains(
            "    ±1j (×2)                                1          0              -          2"
        ),
        "{s}"
    );
}

/// The periodic 16-ring (seed eq. 2.71, ωₚ = 2 sin(πp/16)): every eigenvalue but the
/// Jordan block at 0 exactly on the axis (real part 0, not ±1e-16); the fixed 16-chain
/// without damping: marginally stable.
#[test]
fn lattice_whole_model_on_the_axis() {
    let v = json(&[
        "analyze", "--model", "lattice", "--param", "N=16", "--param", "output=3", "--json",
    ]);
    let ss = &v["state_space"];
    assert_eq!(ss["states"], 32);
    let ev = ss["eigenvalues"].as_array().unwrap();
    assert_eq!(ev.len(), 17); // 0, ±2j and the 7 degenerate pairs
    for e in ev {
        assert_eq!(f(&e["value"][0]), 0.0, "{e}");
        let w = f(&e["value"][1]).abs();
        let p = ((w / 2.0).asin() * 16.0 / std::f64::consts::PI).round();
        assert!(
            (w - 2.0 * (std::f64::consts::PI * p / 16.0).sin()).abs() < 1e-14,
            "{e}"
        );
        let want = match p as u32 {
            0 => (2, 1),
            8 => (1, 1),
            _ => (2, 2),
        };
        assert_eq!(
            (e["algebraic"].as_u64(), e["geometric"].as_u64()),
            (Some(want.0), Some(want.1)),
            "{e}"
        );
    }
    assert!(
        ss["internal_reason"]
            .as_str()
            .unwrap()
            .starts_with("unstable: eigenvalue 0 on the imaginary axis is defective")
    );
    let fixed = json(&[
        "analyze",
        "--model",
        "lattice",
        "--param",
        "N=16",
        "--param",
        "periodic=0",
        "--param",
        "output=3",
        "--json",
    ]);
    let reason = fixed["state_space"]["internal_reason"].as_str().unwrap();
    assert!(reason.starts_with("marginally stable"), "{reason}");
    assert!(
        fixed["state_space"]["eigenvalues"]
            .as_array()
            .unwrap()
            .iter()
            .all(|e| f(&e["value"][0]) == 0.0)
    );
}

/// The 128-ring (256 states, 65 distinct eigenvalues up to conjugation): a summary instead
/// of the list, the modes table only with --modes; the 129-ring (258 states) is beyond
/// MAX_ANALYSIS_STATES: one line, and "state_space": null with the reason.
#[test]
fn large_models_summary_modes_flag_and_limit() {
    let args = [
        "analyze", "--model", "lattice", "--param", "N=128", "--param", "output=6",
    ];
    let s = stdout(&args);
    assert!(
        s.contains("65 distinct up to conjugation: 1 simple, 63 multiple semisimple, 1 defective"),
        "{s}"
    );
    assert!(s.contains("    defective:        0 (×2, defective: algebraic 2, geometric 1)\n"));
    assert!(
        s.contains("    on the axis:      ±2j, ±1.9994j (×2), "),
        "{s}"
    );
    assert!(s.contains("… and 45 more"), "{s}");
    assert!(s.contains("    right half plane: none\n"), "{s}");
    assert!(s.contains("65 modes: the table with --modes"), "{s}");
    assert!(!s.contains("  Modes:\n    eigenvalue"), "{s}");
    let mut modes = args.to_vec();
    modes.push("--modes");
    let t = stdout(&modes);
    let table = t.split("  Modes:\n").nth(1).expect("the modes table");
    let rows = table
        .lines()
        .skip(1)
        .take_while(|l| l.starts_with("    "))
        .count();
    assert_eq!(rows, 65, "{table}");
    // Beyond the limit.
    let big = [
        "analyze", "--model", "lattice", "--param", "N=129", "--param", "output=6",
    ];
    let s = stdout(&big);
    assert!(
        s.contains(&format!(
            "State space (whole model): not computed: 258 states exceed {}",
            ltikit::analysis::ss::MAX_ANALYSIS_STATES
        )),
        "{s}"
    );
    let mut bj = big.to_vec();
    bj.push("--json");
    let v = json(&bj);
    assert_eq!(v["state_space"], Value::Null);
    assert!(
        v["state_space_note"]
            .as_str()
            .unwrap()
            .contains("258 states exceed")
    );
}

/// --shapes with A = diag(−1, −2): the eigenvectors are e₁ and e₂, printed with the state
/// names and in the JSON as unit vectors.
#[test]
fn mode_shapes_with_state_names() {
    let d = dir("shapes");
    let p = write(
        &d.join("diag.toml"),
        "a = \"-1 0; 0 -2\"\nb = \"1; 1\"\nc = \"1 1\"\nstates = [\"position [m]\", \"speed [m/s]\"]\n",
    );
    let s = stdout(&["analyze", "--plant", &p, "--shapes"]);
    assert!(s.contains("  Mode shapes (unit eigenvectors;"), "{s}");
    assert!(s.contains("    -1: position [m] 1\n"), "{s}");
    assert!(s.contains("    -2: speed [m/s] 1\n"), "{s}");
    let v = json(&["analyze", "--plant", &p, "--json", "--shapes"]);
    let modes = v["state_space"]["modes"].as_array().unwrap();
    for (k, m) in modes.iter().enumerate() {
        let shape = m["shapes"][0].as_array().unwrap();
        for (i, z) in shape.iter().enumerate() {
            let want = if i == k { 1.0 } else { 0.0 };
            assert!((f(&z[0]).abs() - want).abs() <= 4.0 * f64::EPSILON, "{m}");
            assert_eq!(f(&z[1]), 0.0);
        }
    }
}

/// A transfer-function plant has no whole-model keys or section; --modes/--shapes with it
/// (or with one --channel) are a usage error, one line, exit 2. A square system whose
/// transfer matrix is singular for every s (B = [b b]) still gets its section.
#[test]
fn whole_model_only_for_state_space_plants() {
    let v = json(&["analyze", "--num", "1", "--den", "1 3 2", "--json"]);
    assert!(v.get("state_space").is_none() && v.get("state_space_note").is_none());
    let s = stdout(&["analyze", "--num", "1", "--den", "1 3 2"]);
    assert!(!s.contains("State space"), "{s}");
    let (e, code) = error(&["analyze", "--num", "1", "--den", "1 3 2", "--modes"]);
    assert!(code == 2 && e.contains("--modes and --shapes"), "{e}");
    let d = dir("only");
    let p = mimo_file(&d);
    let (e, code) = error(&["analyze", "--plant", &p, "--channel", "1,1", "--shapes"]);
    assert!(code == 2 && e.contains("one --channel"), "{e}");
    let s = stdout(&[
        "analyze",
        "--a",
        "-1 0; 0 -2",
        "--b",
        "1 1; 1 1",
        "--c",
        "1 0; 0 1",
    ]);
    assert!(
        s.contains("  invariant zeros:    none\n")
            && s.contains(
                "  system pencil:      normal rank 1 of 2; infinite zeros of order 1; left indices 1; right indices 0"
            ),
        "{s}"
    );
}

/// A non-square system (ControlSystems.jl's example 11, 3 outputs and 2 inputs, zeros 4 and
/// −3 to their tolerance 1e-5): the whole-model section lists the zeros with their residuals
/// and the pencil's structure (normal rank 2, one left index; the text line and the JSON keys).
#[test]
fn non_square_system_zeros_and_pencil_structure() {
    let args = [
        "analyze",
        "--a",
        "-2 -6 3 -7 6; 0 -5 4 -4 8; 0 2 0 2 -2; 0 6 -3 5 -6; 0 -2 2 -2 5",
        "--b",
        "-2 7; -8 -5; -3 0; 1 5; -8 0",
        "--c",
        "0 -1 2 -1 -1; 1 1 1 0 -1; 0 3 -2 3 -1",
    ];
    let s = stdout(&args);
    assert!(s.contains("  invariant zeros:    4, -3\n"), "{s}");
    assert!(
        s.contains("  system pencil:      normal rank 2 of 2; infinite zeros of order 1, 1; left indices 1; right indices none"),
        "{s}"
    );
    let mut with_json = args.to_vec();
    with_json.push("--json");
    let v = json(&with_json);
    let ss = &v["state_space"];
    let zeros = ss["invariant_zeros"].as_array().unwrap();
    let mut re: Vec<f64> = zeros
        .iter()
        .map(|z| z["value"][0].as_f64().unwrap())
        .collect();
    re.sort_by(f64::total_cmp);
    assert!(
        (re[0] + 3.0).abs() < 1e-5 && (re[1] - 4.0).abs() < 1e-5,
        "{re:?}"
    );
    for z in zeros {
        assert!(z["residual"].as_f64().unwrap() < 1e-14, "{z}");
    }
    let keys: Vec<&str> = ss["system_pencil"]
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    assert_eq!(
        keys,
        [
            "normal_rank",
            "infinite_zero_orders",
            "left_kronecker_indices",
            "right_kronecker_indices"
        ]
    );
    assert_eq!(
        ss["system_pencil"]["left_kronecker_indices"],
        serde_json::json!([1])
    );
}

#[test]
fn a_zero_at_the_origin_settles_to_zero_and_counts_read_in_the_singular() {
    // ẋ₁ = x₂, ẋ₂ = x₃ + u, ẋ₃ = −6x₁ − 11x₂ − 6x₃, y = x₂: G = s(s + 6)/((s + 1)(s + 2)(s + 3)).
    // The transmission zero at 0 is exactly 0 (the pencil gave −1.97e-31), the dc gain 0, and
    // the step response settles to 0 (no metrics relative to a zero final value; it used to
    // print an undershoot of 2.8e17 %).
    let s = stdout(&[
        "analyze",
        "--a",
        "0 1 0; 0 0 1; -6 -11 -6",
        "--b",
        "0; 1; 0",
        "--c",
        "0 1 0",
    ]);
    assert!(s.contains("Zeros:     0, -6"), "{s}");
    assert!(s.contains("dc gain:   0\n"), "{s}");
    assert!(s.contains("Step response: settles to 0"), "{s}");
    assert!(s.contains("(3 states, 1 input, 1 output)"), "{s}");
    let j = json(&[
        "analyze",
        "--json",
        "--a",
        "0 1 0; 0 0 1; -6 -11 -6",
        "--b",
        "0; 1; 0",
        "--c",
        "0 1 0",
    ]);
    assert_eq!(j["zeros"][0], serde_json::json!([0.0, 0.0]), "{j}");
    assert_eq!(j["dc_gain"], serde_json::json!(0.0));
    assert!(j["step_info"].is_null());
}

#[test]
fn a_large_mimo_channel_is_described_not_printed() {
    // The lattice (N = 16, 32 states) with all displacements measured: every channel has 32
    // poles, more than the 12 printed as a formula.
    let s = stdout(&[
        "analyze",
        "--model",
        "lattice",
        "--param",
        "N=16",
        "--param",
        "output=0",
        "--channel",
        "1,3",
    ]);
    assert!(s.contains("G(s): a channel of a 32-state model"), "{s}");
    // every channel of the 16-output model: described in words, never a 32-factor formula
    let s = stdout(&[
        "analyze", "--model", "lattice", "--param", "N=16", "--param", "output=0",
    ]);
    assert_eq!(
        s.matches("G(s): order 32, minimal order").count(),
        16,
        "{s}"
    );
    assert!(!s.contains("G(s) = "), "{s}");
    let s = stdout(&[
        "margins", "--model", "lattice", "--param", "N=4", "--param", "output=0",
    ]);
    // N = 4: 8 poles per channel, printed as a formula
    assert!(s.contains("G(s) = "), "{s}");
}

#[test]
fn warnings_come_after_success_and_never_beside_an_error() {
    // C = s − 1 cancels the plant's unstable pole at 1: the loop analysis succeeds with a
    // warning on stderr; the same loop with a bad time fails with its error line alone (the
    // fuzzer found "warning: … / error: …" on two lines, seed 11).
    let args = [
        "response",
        "--num",
        "1",
        "--den",
        "1 0 -1",
        "--controller",
        "pd:kp=-1,kd=1,tf=0",
        "--t",
        "0 1",
    ];
    let ok = ltikit(&args);
    assert!(ok.status.success());
    let err = String::from_utf8_lossy(&ok.stderr);
    assert!(
        err.starts_with("warning: the loop is internally unstable"),
        "{err}"
    );
    let mut bad = args.to_vec();
    bad[8] = "0 -1";
    let (line, code) = error(&bad);
    assert_eq!(code, 1);
    assert!(line.starts_with("error: time -1"), "{line}");
}
