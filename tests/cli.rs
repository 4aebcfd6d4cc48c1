//! The command line: JSON contracts (DESIGN §1.2), exit codes, error messages. Runs the real
//! binary.

mod common;

use common::{ltikit, ltikit_with_stdin};
use serde_json::Value;

fn json(args: &[&str]) -> Value {
    let out = ltikit(args);
    assert!(
        out.status.success(),
        "ltikit {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        !text.contains("NaN") && !text.contains("Infinity"),
        "{text}"
    );
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("invalid JSON ({e}): {text}"))
}

fn keys(v: &Value) -> Vec<&str> {
    v.as_object().unwrap().keys().map(|k| k.as_str()).collect()
}

fn close(v: &Value, want: f64, tol: f64) -> bool {
    (v.as_f64().unwrap() - want).abs() <= tol * want.abs().max(1.0)
}

#[test]
fn analyze_contract() {
    let v = json(&["analyze", "--num", "4", "--den", "1 0.8 4", "--json"]);
    assert_eq!(
        keys(&v),
        [
            "dt",
            "order",
            "relative_degree",
            "poles",
            "zeros",
            "zeros_at_infinity",
            "cancelled",
            "near_cancellations",
            "dc_gain",
            "bibo_stable",
            "internally_stable",
            "stability_reason",
            "structure",
            "structure_note",
            "modes",
            "second_order",
            "step_info"
        ]
    );
    // coefficients typed as text: the exact path decided (issue 11)
    assert_eq!(v["structure"], "exact");
    assert_eq!(v["order"], 2);
    assert_eq!(v["zeros_at_infinity"], 2);
    assert_eq!(v["poles"].as_array().unwrap().len(), 2);
    assert!(close(&v["poles"][0][0], -0.4, 1e-14));
    assert_eq!(v["bibo_stable"], true);
    assert!(close(&v["dc_gain"], 1.0, 1e-15));
    assert_eq!(v["second_order"]["class"], "underdamped");
    assert!(close(&v["second_order"]["zeta"], 0.2, 1e-15));
    let si = &v["step_info"];
    assert_eq!(
        keys(si),
        [
            "rise_time",
            "settling_time",
            "overshoot_percent",
            "peak",
            "peak_time",
            "steady_state",
            "transient_time",
            "settling_min",
            "settling_max",
            "undershoot_percent"
        ]
    );
    // Overshoot e^(−πζ/√(1−ζ²)) for ζ = 0.2; peak time π/ω_d.
    let z: f64 = 0.2;
    let os = 100.0 * (-std::f64::consts::PI * z / (1.0 - z * z).sqrt()).exp();
    assert!(close(&si["overshoot_percent"], os, 1e-9));
    assert!(close(
        &si["peak_time"],
        std::f64::consts::PI / (2.0 * (1.0 - z * z).sqrt()),
        1e-9
    ));
}

#[test]
fn analyze_critical_damping_and_cancellation() {
    let v = json(&["analyze", "--den", "1 2 1", "--json"]);
    assert_eq!(v["second_order"]["class"], "critically_damped");
    assert_eq!(v["second_order"]["zeta"], 1.0);
    // Listed with repetition: the double pole appears twice, exactly −1.
    assert_eq!(v["poles"], serde_json::json!([[-1.0, 0.0], [-1.0, 0.0]]));
    assert_eq!(v["modes"].as_array().unwrap().len(), 1);
    assert_eq!(v["modes"][0]["multiplicity"], 2);

    // s/(s(s+1)): dc gain 1 of the reduced form, the pole at 0 cancelled.
    let v = json(&["analyze", "--num", "1 0", "--den", "1 1 0", "--json"]);
    assert_eq!(v["cancelled"], serde_json::json!([[0.0, 0.0]]));
    assert_eq!(v["dc_gain"], 1.0);
    assert_eq!(v["bibo_stable"], true);
    // 1/s: infinite dc gain is null, no step metrics.
    let v = json(&["analyze", "--den", "1 0", "--json"]);
    assert!(v["dc_gain"].is_null());
    assert!(v["step_info"].is_null());
}

#[test]
fn negative_coefficients_with_equals_and_commas() {
    let v = json(&["analyze", "--num=-3,-12", "--den", "1 9 -10.75", "--json"]);
    assert_eq!(v["zeros"], serde_json::json!([[-4.0, 0.0]]));
    assert_eq!(v["bibo_stable"], false);
    assert!(
        v["stability_reason"]
            .as_str()
            .unwrap()
            .contains("right half plane")
    );
}

#[test]
fn model_and_plant_file() {
    let v = json(&[
        "analyze",
        "--model",
        "spring-mass-damper",
        "--param",
        "M=1",
        "--param",
        "C=0.4",
        "--param",
        "K=4",
        "--json",
    ]);
    assert!(close(&v["second_order"]["wn"], 2.0, 1e-15));
    assert!(close(&v["second_order"]["zeta"], 0.1, 1e-15));
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/data/plants/suspension.toml");
    let v = json(&["analyze", "--plant", file, "--json"]);
    assert!(close(&v["second_order"]["wn"], 8.0, 1e-15));
    assert!(close(&v["second_order"]["zeta"], 0.25, 1e-15));
}

#[test]
fn residue_contract_and_recomposition() {
    // (s + 3)/(s + 1)^3 = 1/(s+1)^2 + 2/(s+1)^3.
    let v = json(&["residue", "--num", "1 3", "--den", "1 3 3 1", "--json"]);
    assert_eq!(keys(&v), ["dt", "terms", "direct"]);
    let terms = v["terms"].as_array().unwrap();
    assert_eq!(keys(&terms[0]), ["pole", "power", "residue"]);
    for t in terms {
        assert_eq!(t["pole"], serde_json::json!([-1.0, 0.0]));
        let want = [0.0, 1.0, 2.0][t["power"].as_u64().unwrap() as usize - 1];
        assert!(close(&t["residue"][0], want, 1e-14));
    }
    assert_eq!(v["direct"], serde_json::json!([]));
}

#[test]
fn response_contract_and_values() {
    // Step into 1/(s+1)^2: y = 1 − (1 + t) e^(−t).
    let v = json(&[
        "response", "--num", "1", "--den", "1 2 1", "--t", "0 1 2.5", "--json",
    ]);
    assert_eq!(
        keys(&v),
        ["dt", "closed_form", "t", "y", "transient", "steady_state"]
    );
    assert_eq!(v["closed_form"], "y(t) = 1 - (1 + t) e^(-t)");
    for (i, t) in [0.0f64, 1.0, 2.5].iter().enumerate() {
        let y = 1.0 - (1.0 + t) * (-t).exp();
        assert!((v["y"][i].as_f64().unwrap() - y).abs() < 1e-14);
        assert!((v["steady_state"][i].as_f64().unwrap() - 1.0).abs() < 1e-14);
        assert!((v["transient"][i].as_f64().unwrap() - (y - 1.0)).abs() < 1e-14);
    }
    // Initial conditions only (seed eq. 3.35 with ζ = ωn = 1): y = e^(−t)(ẏ0 t + y0(1 + t)).
    let v = json(&[
        "response", "--den", "1 2 1", "--input", "none", "--ic", "2 -1", "--t", "1.5", "--json",
    ]);
    let t: f64 = 1.5;
    let want = (-t).exp() * (-t + 2.0 * (1.0 + t));
    assert!((v["y"][0].as_f64().unwrap() - want).abs() < 1e-14);
}

#[test]
fn freq_contract_and_phase_branch() {
    let v = json(&["freq", "--den", "1 0 0 0", "--w", "0.1 1 10", "--json"]);
    let pts = v["points"].as_array().unwrap();
    assert_eq!(
        keys(&pts[0]),
        ["w", "magnitude", "magnitude_db", "phase_deg"]
    );
    for p in pts {
        assert_eq!(p["phase_deg"], -270.0); // 1/s³ starts (and stays) at −270°
    }
    assert!(close(&pts[0]["magnitude"], 1000.0, 1e-14));
    // At the pole of 1/(s²+1) the magnitude is infinite: null, never a NaN token.
    let v = json(&["freq", "--den", "1 0 1", "--w", "1", "--json"]);
    assert!(v["points"][0]["magnitude"].is_null());
}

#[test]
fn margins_json() {
    let v = json(&["margins", "--num", "2", "--den", "1 3 2 0", "--json"]);
    assert!(close(&v["gain_margin"], 3.0, 1e-12));
    assert!(close(&v["phase_margin_deg"], 32.6131, 1e-5));
    assert!(close(&v["gain_crossover"], 0.749368, 1e-6));
    let v = json(&["margins", "--num", "1", "--den", "1 3 3 1", "--json"]);
    assert!(v["phase_margin_deg"].is_null()); // infinite: |G| < 1 everywhere
    assert!(close(&v["phase_crossover"], 3f64.sqrt(), 1e-14));
}

#[test]
fn linearize_contract() {
    let v = json(&["linearize", "pendulum", "--json"]);
    assert_eq!(keys(&v), ["model", "params", "equilibria"]);
    let e = &v["equilibria"][0];
    assert_eq!(
        keys(e),
        [
            "x",
            "u",
            "A",
            "B",
            "C",
            "D",
            "eigenvalues",
            "hyperbolic",
            "stability",
            "physical",
            "tf"
        ]
    );
    assert_eq!(e["stability"], "asymptotically_stable");
    assert_eq!(v["equilibria"][1]["stability"], "unstable");
    // Seed eq. 2.18 at θ = 0 with M = L = 1, g = 9.81: A = [[0, 1], [−3g/(2L), −3C/(ML²)]].
    assert!(close(&e["A"][1][0], -14.715, 1e-15));
    assert_eq!(keys(&e["tf"]), ["num", "den"]);
    let v = json(&["linearize", "lorenz", "--json"]);
    assert!(v["equilibria"][0]["tf"].is_null()); // no input
}

#[test]
fn simulate_csv_and_json() {
    let out = ltikit(&[
        "simulate",
        "vanderpol",
        "--x0",
        "2 0",
        "--t-end",
        "1",
        "--points",
        "3",
    ]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].starts_with("t,"));
    assert_eq!(lines.len(), 4);
    let v = json(&[
        "simulate", "lorenz", "--x0", "1 0 0", "--t-end", "0.5", "--points", "6", "--json",
    ]);
    assert_eq!(v["t"].as_array().unwrap().len(), 6);
}

/// Exit code and the one-line stderr message.
fn fails(args: &[&str]) -> (i32, String) {
    let out = ltikit(args);
    assert!(out.stdout.is_empty(), "no partial output for {args:?}");
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(!err.contains("panicked"), "{err}");
    (out.status.code().unwrap(), err)
}

#[test]
fn bad_input_is_a_clear_error() {
    let cases: &[(&[&str], i32, &str)] = &[
        (&["analyze", "--num", "1", "--den", "1 nan"], 1, "NaN"),
        (&["analyze", "--num", "inf", "--den", "1 1"], 1, "inf"),
        (&["analyze", "--den", "0 0"], 1, "zero polynomial"),
        (&["analyze", "--den", "1 x"], 1, "'x' is not a number"),
        (&["response", "--num", "1 0 0", "--den", "1 1"], 1, "proper"),
        (&["response", "--den", "1 1", "--t", "-1"], 1, "time -1"),
        (
            &["analyze", "--plant", "no/such/file.toml"],
            1,
            "no/such/file.toml",
        ),
        (&["analyze", "--model", "nope"], 1, "unknown model"),
        (
            &["analyze", "--model", "tank", "--param", "Q=1"],
            1,
            "no parameter 'Q'",
        ),
        (&["linearize", "pendulum", "--param", "L=-1"], 1, "L = -1"),
        (
            &["simulate", "lorenz", "--x0", "1 0 0", "--t-end", "0"],
            1,
            "end time",
        ),
        (&["analyze"], 2, "no plant given"),
        (&["analyze", "--bogus"], 2, "--bogus"),
    ];
    for (args, code, needle) in cases {
        let (c, err) = fails(args);
        assert_eq!(c, *code, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(err.starts_with("error:"), "{args:?}: {err}");
    }
    let order300 = format!("1{}", " 0".repeat(299) + " 1");
    let (c, err) = fails(&["analyze", "--den", &order300]);
    assert_eq!(c, 1);
    assert!(err.contains("order 300"), "{err}");
}

/// A fresh empty directory under the target dir for files written by a test.
fn scratch_dir(name: &str) -> std::path::PathBuf {
    let d = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn is_png(path: &std::path::Path) -> bool {
    std::fs::read(path)
        .map(|b| b.len() > 1000 && b.starts_with(b"\x89PNG\r\n\x1a\n"))
        .unwrap_or(false)
}

#[test]
fn plot_commands_write_pngs() {
    let d = scratch_dir("cli-plots");
    let p = |f: &str| d.join(f).to_string_lossy().into_owned();
    let runs: Vec<Vec<String>> = vec![
        vec![
            "bode".into(),
            "--num".into(),
            "2".into(),
            "--den".into(),
            "1 3 2 0".into(),
            "--asymptotes".into(),
            "-o".into(),
            p("b.png"),
        ],
        vec![
            "bode".into(),
            "--den".into(),
            "1 0.2 1".into(),
            "--den".into(),
            "1 2 1".into(),
            "-o".into(),
            p("b2.png"),
            "--size".into(),
            "640x480".into(),
        ],
        vec![
            "step".into(),
            "--den".into(),
            "1 0.8 4".into(),
            "--num".into(),
            "4".into(),
            "-o".into(),
            p("s.png"),
        ],
        vec![
            "step".into(),
            "--den".into(),
            "1 1".into(),
            "--input".into(),
            "impulse".into(),
            "-o".into(),
            p("i.png"),
        ],
        vec![
            "step".into(),
            "--den".into(),
            "1 -0.5 4".into(),
            "-o".into(),
            p("u.png"),
        ],
        vec![
            "pzmap".into(),
            "--num".into(),
            "1 1".into(),
            "--den".into(),
            "1 3 2 0".into(),
            "--guides".into(),
            "-o".into(),
            p("pz.png"),
        ],
        vec![
            "nyquist".into(),
            "--num".into(),
            "2".into(),
            "--den".into(),
            "1 3 2 0".into(),
            "-o".into(),
            p("n.png"),
        ],
        vec!["mems-pullin".into(), "-o".into(), p("pull.png")],
        vec![
            "simulate".into(),
            "pendulum".into(),
            "--x0".into(),
            "2 0".into(),
            "--t-end".into(),
            "5".into(),
            "--points".into(),
            "101".into(),
            "-o".into(),
            p("ph.png"),
            "--phase".into(),
            "1,2".into(),
        ],
    ];
    for args in &runs {
        let a: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
        let out = ltikit(&a);
        assert!(
            out.status.success(),
            "{a:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let file = args[args.iter().position(|s| s == "-o").unwrap() + 1].clone();
        assert!(is_png(std::path::Path::new(&file)), "{file}");
    }
}

#[test]
fn plot_errors_leave_no_file() {
    let d = scratch_dir("cli-plot-errors");
    let target = d.join("x.png");
    let t = target.to_string_lossy().into_owned();
    let cases: &[(&[&str], &str)] = &[
        (
            &["bode", "--den", "1 1", "--size", "0x100", "-o", &t],
            "empty",
        ),
        (
            &["step", "--num", "1 0 0", "--den", "1 1", "-o", &t],
            "proper",
        ),
        (
            &["bode", "--den", "1 1", "-o", "/nonexistent-dir/x.png"],
            "nonexistent-dir",
        ),
    ];
    for (args, needle) in cases {
        let (code, err) = fails(args);
        assert_eq!(code, 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!target.exists(), "{args:?} left a file");
    }
    assert_eq!(
        std::fs::read_dir(&d).unwrap().count(),
        0,
        "no temporary files left"
    );
}

#[test]
fn infinite_margins_are_reported_not_errors() {
    // 1/(s + 1): |G| < 1 for ω > 0 and the phase never reaches −180°.
    let v = json(&["margins", "--den", "1 1", "--json"]);
    assert!(v["gain_margin"].is_null() && v["phase_margin_deg"].is_null());
    let out = ltikit(&["margins", "--den", "1 1"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains('∞'));
}

#[test]
fn simulation_limits_are_clean_errors() {
    let (code, err) = fails(&[
        "simulate",
        "lorenz",
        "--x0",
        "1 0 0",
        "--t-end",
        "100",
        "--max-steps",
        "50",
    ]);
    assert_eq!(code, 1);
    assert!(err.contains("step limit"), "{err}");
    // Above pull-in the MEMS plates touch: the simulation stops there and says when.
    let v = json(&[
        "simulate", "mems", "--param", "v=3.2", "--x0", "3 0 0", "--t-end", "20", "--json",
    ]);
    let t = v["stopped"]["t"].as_f64().unwrap();
    assert!(t > 1.0 && t < 20.0, "{t}");
}

#[test]
fn batch_keeps_order_and_reports_bad_lines() {
    let out = ltikit_with_stdin(
        &["analyze", "--batch", "-"],
        b"{\"name\":\"a\",\"num\":[1],\"den\":[1,2,1]}\n{\"den\":[0]}\nnot json\n{\"name\":\"d\",\"den\":\"1 0.8 4\"}\n",
    );
    assert!(out.status.success());
    let lines: Vec<Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 4);
    assert_eq!(lines[0]["name"], "a");
    assert_eq!(lines[0]["second_order"]["class"], "critically_damped");
    assert!(lines[0]["margins"].is_object());
    assert!(
        lines[1]["error"]
            .as_str()
            .unwrap()
            .contains("zero polynomial")
    );
    assert_eq!(lines[2]["line"], 3);
    assert!(lines[2]["error"].is_string());
    assert_eq!(lines[3]["name"], "d");
    assert!(close(&lines[3]["dc_gain"], 0.25, 1e-15));
}

#[test]
fn demo_writes_the_report_and_its_figures() {
    let d = scratch_dir("cli-demo");
    let out = ltikit(&["demo", "--out", d.to_str().unwrap(), "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["checks"], v["checks_passed"]);
    let report = std::fs::read_to_string(d.join("report.md")).unwrap();
    assert!(report.contains("## Verification"));
    let figures = v["figures"].as_array().unwrap();
    assert!(figures.len() >= 25);
    for f in figures {
        let name = f.as_str().unwrap();
        assert!(report.contains(&format!("]({name})")), "{name} not linked");
        assert!(is_png(&d.join(name)), "{name}");
    }
}
