//! `ltikit c2d` and `ltikit d2c`: text, JSON, plant files written and read back, refusals.
#![cfg(feature = "cli")]

mod common;

use common::{json, ltikit, stdout};

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("ltikit-cli-c2d-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn nums(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn c2d_prints_the_discrete_plant_and_its_poles() {
    let out = stdout(&[
        "c2d", "--num", "1", "--den", "1 1", "--dt", "0.1", "--method", "zoh",
    ]);
    assert!(out.contains("G(z) = 0.0951626 / (z - 0.904837)"), "{out}");
    assert!(
        out.contains("dt = 0.1 s") && out.contains("method: zoh"),
        "{out}"
    );
    assert!(out.contains("poles (z): 0.904837"), "{out}");
    // a triple pole keeps its multiplicity
    let v = json(&[
        "c2d", "--den", "1 3 3 1", "--dt", "0.2", "--method", "zoh", "--json",
    ]);
    assert_eq!(v["dt"], 0.2);
    assert_eq!(v["method"], "zoh");
    let poles = v["poles"].as_array().unwrap();
    assert_eq!(poles.len(), 3);
    for p in poles {
        assert_eq!(p[0].as_f64().unwrap(), (-0.2f64).exp());
    }
    let den = nums(&v["den"]);
    assert_eq!(den.len(), 4);
    assert!((den[3] + (-0.6f64).exp()).abs() < 1e-14, "{den:?}");
}

#[test]
fn a_textbook_model_is_sampled() {
    // the textbook models refuse a period of their own; c2d samples them
    let v = json(&[
        "c2d", "--model", "tank", "--dt", "0.5", "--method", "zoh", "--json",
    ]);
    assert_eq!(v["dt"], 0.5);
    assert_eq!(v["poles"].as_array().unwrap().len(), 1);
}

#[test]
fn mimo_state_space_is_sampled_as_matrices() {
    let v = json(&[
        "c2d",
        "--a",
        "-1 2 0; -2 -1 1; 0.5 0 -3",
        "--b",
        "1 0; 0 1; 1 -1",
        "--c",
        "1 0 1; 0 1 0",
        "--d",
        "0 0.5; 0 0",
        "--dt",
        "0.1",
        "--method",
        "tustin",
        "--json",
    ]);
    // scipy.signal.cont2discrete(…, 0.1, 'bilinear') (see tests/c2d.rs)
    assert!((v["a"][0][0].as_f64().unwrap() - 0.8878248974008207).abs() < 1e-14);
    assert!((v["d"][0][1].as_f64().unwrap() - 0.46091459839749854).abs() < 1e-14);
    assert_eq!(v["poles"].as_array().unwrap().len(), 3);
    let text = stdout(&[
        "c2d",
        "--a",
        "-1 2 0; -2 -1 1; 0.5 0 -3",
        "--b",
        "1 0; 0 1; 1 -1",
        "--c",
        "1 0 1; 0 1 0",
        "--dt",
        "0.1",
        "--method",
        "zoh",
    ]);
    assert!(
        text.contains("A =") && text.contains("D =") && text.contains("poles (z)"),
        "{text}"
    );
}

#[test]
fn the_plant_file_reads_back() {
    for (args, method) in [
        (vec!["--num", "4", "--den", "1 0.8 4"], "zoh"),
        (vec!["--num", "11", "--den", "1 1 0"], "matched"),
        (
            vec!["--a", "0 1; -4 -0.8", "--b", "0; 1", "--c", "4 0"],
            "tustin",
        ),
    ] {
        let path = scratch(&format!("{method}.toml"));
        let p = path.to_str().unwrap();
        let mut cmd = vec!["c2d"];
        cmd.extend(&args);
        cmd.extend(["--dt", "0.1", "--method", method, "-o", p, "--json"]);
        let v = json(&cmd);
        // the file is the same discrete plant: d2c reads it, and c2d refuses it (discrete)
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains("dt = 0.1"), "{text}");
        let out = ltikit(&["c2d", "--plant", p, "--dt", "0.1", "--method", "zoh"]);
        assert_eq!(out.status.code(), Some(1));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("discrete"), "{err}");
        if method == "matched" {
            continue; // a pole at z = 1 is fine, but matched has no d2c
        }
        let back = json(&["d2c", "--plant", p, "--method", method, "--json"]);
        assert_eq!(back["dt"], serde_json::Value::Null);
        assert_eq!(back["period"], 0.1);
        if v["den"].is_array() {
            let den_s = nums(&back["den"]);
            assert!(
                (den_s[1] - 0.8).abs() < 1e-12 && (den_s[2] - 4.0).abs() < 1e-11,
                "{den_s:?}"
            );
        } else {
            let a = &back["a"];
            assert!((a[1][0].as_f64().unwrap() + 4.0).abs() < 1e-12, "{a}");
        }
    }
}

#[test]
fn d2c_inverts_c2d_on_the_command_line() {
    let v = json(&[
        "c2d",
        "--num",
        "1 3",
        "--den",
        "1 3 2",
        "--dt",
        "0.05",
        "--method",
        "tustin",
        "--prewarp",
        "2",
        "--json",
    ]);
    assert_eq!(v["prewarp"], 2.0);
    let num: Vec<String> = nums(&v["num"]).iter().map(|x| format!("{x:?}")).collect();
    let den: Vec<String> = nums(&v["den"]).iter().map(|x| format!("{x:?}")).collect();
    let back = json(&[
        "d2c",
        "--num",
        &num.join(" "),
        "--den",
        &den.join(" "),
        "--dt",
        "0.05",
        "--method",
        "tustin",
        "--prewarp",
        "2",
        "--json",
    ]);
    let den_s = nums(&back["den"]);
    assert!(
        (den_s[1] - 3.0).abs() < 1e-12 && (den_s[2] - 2.0).abs() < 1e-12,
        "{den_s:?}"
    );
    let text = stdout(&[
        "d2c", "--num", "0.5", "--den", "1 -0.5", "--dt", "0.1", "--method", "zoh",
    ]);
    assert!(
        text.contains("G(s) =") && text.contains("continuous time"),
        "{text}"
    );
}

#[test]
fn bad_input_is_one_line_and_leaves_no_file() {
    let path = scratch("never.toml");
    let p = path.to_str().unwrap();
    for (args, code, needle) in [
        (
            vec![
                "c2d", "--num", "1", "--den", "1 1", "--dt", "0.1", "--method", "euler", "-o", p,
            ],
            1,
            "known: zoh, foh, tustin",
        ),
        (
            vec![
                "c2d", "--num", "1", "--den", "1 1", "--dt", "0", "--method", "zoh", "-o", p,
            ],
            1,
            "sampling period",
        ),
        (
            vec![
                "c2d", "--num", "1", "--den", "1 1", "--dt", "NaN", "--method", "zoh", "-o", p,
            ],
            1,
            "sampling period",
        ),
        (
            vec![
                "c2d", "--num", "1", "--den", "1 1", "--dt", "inf", "--method", "zoh",
            ],
            1,
            "sampling period",
        ),
        (
            vec!["c2d", "--num", "1", "--den", "1 1", "--method", "zoh"],
            2,
            "--dt",
        ),
        (
            vec![
                "c2d",
                "--num",
                "1",
                "--den",
                "1 1",
                "--dt",
                "0.1",
                "--method",
                "tustin",
                "--prewarp",
                "31.5",
                "-o",
                p,
            ],
            1,
            "prewarp",
        ),
        (
            vec![
                "c2d",
                "--num",
                "1",
                "--den",
                "1 1",
                "--dt",
                "0.1",
                "--method",
                "zoh",
                "--prewarp",
                "1",
            ],
            1,
            "--prewarp is for the tustin method",
        ),
        (
            vec![
                "c2d", "--num", "1", "--den", "1 1", "--dt", "0.1", "--method", "impulse", "--num",
                "1 0", "--den", "1 1",
            ],
            2,
            "one plant",
        ),
        (
            vec![
                "c2d", "--num", "1", "--den", "1 1", "--dt", "0.1", "--method", "zoh", "-o",
                "x.png",
            ],
            2,
            "FILE.toml",
        ),
        (
            vec![
                "c2d",
                "--num",
                "1",
                "--den",
                "1 1",
                "--dt",
                "0.1",
                "--method",
                "zoh",
                "--controller",
                "p:kp=2",
            ],
            2,
            "--controller",
        ),
        (
            vec![
                "c2d", "--num", "1 0", "--den", "1 1", "--dt", "0.1", "--method", "impulse", "-o",
                p,
            ],
            1,
            "D = 0",
        ),
        (
            vec![
                "d2c", "--num", "1", "--den", "1 0.5", "--dt", "0.1", "--method", "zoh", "-o", p,
            ],
            1,
            "z = -0.5",
        ),
        (
            vec![
                "d2c", "--num", "1", "--den", "1 0", "--dt", "0.1", "--method", "zoh", "-o", p,
            ],
            1,
            "z = 0",
        ),
        (
            vec![
                "d2c", "--num", "1", "--den", "1 1", "--dt", "0.1", "--method", "tustin",
            ],
            1,
            "z = -1",
        ),
        (
            vec!["d2c", "--num", "1", "--den", "1 0.5", "--method", "zoh"],
            1,
            "continuous",
        ),
        (
            vec![
                "d2c", "--num", "1", "--den", "1 -0.5", "--dt", "0.1", "--method", "matched",
            ],
            1,
            "zoh and tustin",
        ),
    ] {
        let out = ltikit(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
        assert!(!path.exists(), "{args:?} left a file");
    }
}
