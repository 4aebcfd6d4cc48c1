//! State-space plants on the command line: MIMO plants per channel (text and JSON contract),
//! the Bode grid, time responses (step per input, --x0, --states, lsim from CSV), the lattice
//! as a model, the per-channel linearisation, and bad input. Runs the real binary.
//!
//! The MIMO test plant is ẋ = diag(−1, −2) x + u, y = [[1, 1], [1, −1]] x (inputs "force 1
//! [N]", "force 2 [N]", outputs "sum [m]", "difference [m]"), whose channels are, in closed
//! form, G11 = G12 = 1/(s + 1) and G21 = 1/(s + 2), G22 = −1/(s + 2) (Gij: input i → output
//! j); the mode s = −2 is uncontrollable from input 1, s = −1 from input 2.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn ltikit(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ltikit"))
        .args(args)
        .output()
        .expect("the ltikit binary runs")
}

fn stdout(args: &[&str]) -> String {
    let out = ltikit(args);
    assert!(
        out.status.success(),
        "ltikit {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn json(args: &[&str]) -> Value {
    let text = stdout(args);
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("invalid JSON ({e}): {text}"))
}

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
    assert_eq!(
        keys,
        ["model", "name", "states", "inputs", "outputs", "channels"]
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
