//! Issue 25 at the command line: sizes refused before anything is allocated, echoed text
//! abbreviated, missing arguments named, pictures only as PNG, `--json` on every picture
//! command (one document describing what was drawn), the models' parameters in `--help`.

use serde_json::Value;
use std::time::Instant;

mod common;

/// Runs the binary (the shared runner): (exit code, stdout, stderr).
fn ltikit(args: &[&str]) -> (i32, String, String) {
    let out = common::ltikit(args);
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn tmp(name: &str) -> String {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli_robust");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).display().to_string()
}

/// Measured before: `--points 1000000000 --json` grew to 24 GB and was killed after 87 s;
/// `--points 18446744073709551615` panicked with "capacity overflow".
#[test]
fn huge_sizes_are_refused_at_once() {
    for points in ["1000000000", "18446744073709551615"] {
        let start = Instant::now();
        let (code, out, err) = ltikit(&[
            "simulate", "pendulum", "--x0", "0.5 0", "--t-end", "1", "--points", points, "--json",
        ]);
        assert_eq!(code, 1, "{err}");
        assert!(out.is_empty());
        assert_eq!(
            err,
            format!(
                "error: --points: {points} exceeds the limit of 1 000 000 sample points (MAX_POINTS)\n"
            )
        );
        assert!(start.elapsed().as_secs_f64() < 5.0);
    }
    // a long time list within the limit is read
    let many = "0 ".repeat(60_000);
    let (code, _, err) = ltikit(&["response", "--den", "1 1", "--t", &many]);
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = ltikit(&["freq", "--den", "1 1", "--points", "1000001"]);
    assert_eq!(code, 1);
    assert!(err.contains("--points: 1000001 exceeds"), "{err}");
    let (code, _, err) = ltikit(&["simulate", "pendulum", "--max-steps", "99999999999"]);
    assert_eq!(code, 1);
    assert!(err.contains("--max-steps: 99999999999 exceeds"), "{err}");
    let (code, _, err) = ltikit(&["freq", "--den", "1 1", "--points", "18446744073709551615"]);
    assert_eq!(code, 1);
    assert!(
        err.contains("--points: 18446744073709551615 exceeds"),
        "{err}"
    );
    let (code, _, err) = ltikit(&["rlocus", "--den", "1 1", "--max-gains", "1000000000"]);
    assert_eq!(code, 1);
    assert!(err.contains("--max-gains: 1000000000 exceeds"), "{err}");
    let png = tmp("huge.png");
    let (code, _, err) = ltikit(&["bode", "--den", "1 1", "-o", &png, "--size", "99999x99999"]);
    assert_eq!(code, 1);
    assert!(
        err.contains("--size: 99999 exceeds the limit of 16 384 px a side"),
        "{err}"
    );
    assert!(!std::path::Path::new(&png).exists());
}

/// Measured before: an unknown model name of 5000 characters was echoed whole.
#[test]
fn echoed_text_is_abbreviated() {
    let long = "x".repeat(5000);
    let param = format!("{long}=1");
    let file = format!("{long}.toml");
    for args in [
        vec!["simulate", long.as_str()],
        vec!["linearize", long.as_str()],
        vec!["analyze", "--model", long.as_str()],
        vec!["analyze", "--model", "tank", "--param", param.as_str()],
        vec!["analyze", "--den", long.as_str()],
        vec!["analyze", "--plant", file.as_str()],
        vec!["analyze", "--den", "1 1", "--controller", long.as_str()],
        vec![
            "bode",
            "--den",
            "1 1",
            "-o",
            "x.png",
            "--size",
            long.as_str(),
        ],
    ] {
        let (code, _, err) = ltikit(&args);
        assert!(code == 1 || code == 2, "{args:?}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.len() < 600 && err.contains(" characters)"),
            "{:?}: {err}",
            &args[..1]
        );
    }
}

/// Measured before: "the following required arguments were not provided:; see --help".
#[test]
fn missing_arguments_are_named() {
    let (code, _, err) = ltikit(&["bode", "--den", "1 1"]);
    assert_eq!(code, 2);
    assert_eq!(
        err,
        "error: a required argument was not given: --output <FILE.png>; see --help\n"
    );
    let (code, _, err) = ltikit(&["linearize"]);
    assert_eq!(code, 2);
    assert_eq!(
        err,
        "error: a required argument was not given: <MODEL>; see --help\n"
    );
}

/// Measured before: `-o x.jpg` wrote a PNG under a .jpg name.
#[test]
fn only_png_names_are_written() {
    let jpg = tmp("x.jpg");
    let (code, _, err) = ltikit(&["step", "--den", "1 1", "-o", &jpg]);
    assert_eq!(code, 2);
    assert!(
        err.contains("ltikit writes PNG pictures only, not .jpg"),
        "{err}"
    );
    assert!(!std::path::Path::new(&jpg).exists());
}

/// One JSON document on stdout, nothing else.
fn json(args: &[&str]) -> Value {
    let (code, out, err) = ltikit(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: {e}: {out}"))
}

fn close(v: &Value, want: f64, tol: f64) -> bool {
    v.as_f64()
        .is_some_and(|x| (x - want).abs() <= tol * want.abs().max(1.0))
}

/// The README says every command takes `--json`; the picture commands refused it.
#[test]
fn picture_commands_describe_what_they_drew() {
    // Bode of 2/(s(s+1)(s+2)): Routh gives the critical gain 6, so the gain margin is 3 at
    // ω = √2 (README "A five-minute tour").
    let png = tmp("bode.png");
    let v = json(&[
        "bode", "--num", "2", "--den", "1 3 2 0", "-o", &png, "--json",
    ]);
    assert_eq!(v["file"], png.as_str());
    let m = &v["plants"][0]["margins"];
    assert!(close(&m["gain_margin"], 3.0, 1e-12), "{m}");
    assert!(close(&m["phase_crossover"], 2f64.sqrt(), 1e-12), "{m}");
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));

    // Step of 4/(s² + 0.8 s + 4): ζ = 0.2, overshoot e^(−πζ/√(1−ζ²)), peak at π/ωd.
    let png = tmp("step.png");
    let v = json(&[
        "step", "--num", "4", "--den", "1 0.8 4", "-o", &png, "--json",
    ]);
    let i = &v["plants"][0]["step_info"];
    let (z, wn) = (0.2f64, 2.0f64);
    let wd = wn * (1.0 - z * z).sqrt();
    let os = 100.0 * (-std::f64::consts::PI * z / (1.0 - z * z).sqrt()).exp();
    assert!(close(&i["overshoot_percent"], os, 1e-9), "{i}");
    assert!(
        close(&i["peak_time"], std::f64::consts::PI / wd, 1e-9),
        "{i}"
    );
    assert_eq!(v["plants"][0]["diverges"], false);

    // Pole-zero map of (s + 1)/(s + 1)²: a double pole at −1, one cancelled with the zero.
    let png = tmp("pz.png");
    let v = json(&[
        "pzmap", "--num", "1 1", "--den", "1 2 1", "-o", &png, "--json",
    ]);
    assert_eq!(v["poles"], serde_json::json!([[-1.0, 0.0], [-1.0, 0.0]]));
    assert_eq!(v["cancelled"], serde_json::json!([[-1.0, 0.0]]));

    // Nyquist of 1/(s − 1) with gain 2: P = 1, one counter-clockwise encirclement (N = −1),
    // Z = N + P = 0: the closed loop 2/(s + 1) is stable.
    let png = tmp("nyquist.png");
    let v = json(&[
        "nyquist", "--num", "2", "--den", "1 -1", "-o", &png, "--json",
    ]);
    let p = &v["plants"][0];
    assert_eq!(
        (
            &p["open_loop_rhp_poles"],
            &p["encirclements"],
            &p["closed_loop_rhp_poles"]
        ),
        (&Value::from(1), &Value::from(-1), &Value::from(0)),
        "{p}"
    );

    // MEMS pull-in: the stable branch ends at √(8 k l0³/(27 εA)) (seed exercise 2.11).
    let png = tmp("pullin.png");
    let v = json(&["mems-pullin", "-o", &png, "--json"]);
    let formula = v["pull_in_voltage"].as_f64().unwrap();
    assert!(close(&v["pull_in_voltage_found"], formula, 1e-9), "{v}");
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
}

/// `linearize --help` did not list the models' parameters.
#[test]
fn help_lists_models_parameters_and_limits() {
    for cmd in ["linearize", "simulate"] {
        let (code, out, _) = ltikit(&[cmd, "--help"]);
        assert_eq!(code, 0);
        for m in ltikit::nonlinear::models() {
            assert!(
                out.contains(&format!("  {} — ", m.name)),
                "{cmd}: {}",
                m.name
            );
            for p in &m.params {
                assert!(
                    out.contains(&format!("      {} = ", p.name)),
                    "{cmd}: {}.{}",
                    m.name,
                    p.name
                );
            }
        }
    }
    let (_, out, _) = ltikit(&["simulate", "--help"]);
    assert!(
        out.contains("--points: at most 1 000 000 sample points"),
        "{out}"
    );
    let (_, out, _) = ltikit(&["freq", "--help"]);
    assert!(out.contains("--num, --den: at most 200"), "{out}");
}
