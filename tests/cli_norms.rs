//! The norm and reduction commands (`norm`, `sigma`, `gram`, `hsv`, `balred`) end to end:
//! closed-form values in the JSON documents, infinite norms said in words, a reduced plant
//! file read back, bad input as one line with exit 1.
#![cfg(feature = "cli")]

mod common;

use common::{json, ltikit, stdout};

/// 1/(s² + 0.2s + 1): ‖G‖∞ = 1/(2ζ√(1 − ζ²)) with ζ = 0.1, ‖G‖₂ = 1/√(4ζ) = √2.5.
#[test]
fn norm_documents() {
    let d = json(&["norm", "--den", "1 0.2 1", "--json"]);
    let exact = 1.0 / (0.2 * 0.99f64.sqrt());
    let (lo, hi) = (d["lower"].as_f64().unwrap(), d["upper"].as_f64().unwrap());
    assert!(
        lo <= exact * (1.0 + 1e-13) && exact <= hi && hi / lo - 1.0 <= 1e-10,
        "{d}"
    );
    assert_eq!(d["norm"], "hinf");
    let keys: Vec<&str> = d.as_object().unwrap().keys().map(|k| k.as_str()).collect();
    assert_eq!(&keys[..4], &["dt", "norm", "value", "lower"]);
    let h2 = json(&["norm", "--den", "1 0.2 1", "--h2", "--json"]);
    assert!(
        (h2["value"].as_f64().unwrap() - 2.5f64.sqrt()).abs() < 1e-14,
        "{h2}"
    );
    // unstable: ∞ with the eigenvalue, exit 0; L∞ finite
    let text = stdout(&["norm", "--den", "1 1 -2"]);
    assert!(
        text.contains("∞ — the model is unstable (eigenvalue s = 1"),
        "{text}"
    );
    let l = json(&["norm", "--den", "1 1 -2", "--linf", "--json"]);
    assert_eq!(l["lower"].as_f64(), Some(0.5));
    // MIMO state space and a loop selection
    let m = json(&[
        "norm",
        "--a",
        "-1 0; 0 -2",
        "--b",
        "1 0; 0 2",
        "--c",
        "1 0; 0 1",
        "--json",
    ]);
    assert_eq!(
        (m["inputs"].as_u64(), m["lower"].as_f64()),
        (Some(2), Some(1.0))
    );
    let s = json(&[
        "norm",
        "--den",
        "1 3 2",
        "--controller",
        "p:kp=1",
        "--sensitivity",
        "--json",
    ]);
    // S = (s² + 3s + 2)/(s² + 3s + 3): |S|² = (x² + 5x + 4)/(x² + 3x + 9) with x = ω², whose
    // derivative vanishes at −2x² + 10x + 33 = 0, x = (5 + √91)/2
    let x = (5.0 + 91f64.sqrt()) / 2.0;
    let ms = ((x * x + 5.0 * x + 4.0) / (x * x + 3.0 * x + 9.0)).sqrt();
    assert!(
        (s["lower"].as_f64().unwrap() / ms - 1.0).abs() < 1e-13,
        "{s} vs {ms}"
    );
    assert!((s["w"].as_f64().unwrap() - x.sqrt()).abs() < 1e-6, "{s}");
}

#[test]
fn sigma_table_json_and_picture() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli_norms");
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("sigma.png");
    let _ = std::fs::remove_file(&png);
    let args = [
        "sigma",
        "--a",
        "-1 1; -1 -0.1",
        "--b",
        "1 0; 0 2",
        "--c",
        "1 0; 0 1",
    ];
    let mut with_o: Vec<&str> = args.to_vec();
    let p = png.to_str().unwrap();
    with_o.extend(["-o", p, "--json"]);
    let d = json(&with_o);
    assert!(std::fs::metadata(&png).unwrap().len() > 10_000);
    let w = d["w"].as_array().unwrap();
    let s = d["sigma"].as_array().unwrap();
    assert_eq!(w.len(), s.len());
    let peak = d["peak"]["upper"].as_f64().unwrap();
    for v in s {
        let v = v.as_array().unwrap();
        assert_eq!(v.len(), 2);
        assert!(v[0].as_f64().unwrap() >= v[1].as_f64().unwrap());
        assert!(v[0].as_f64().unwrap() <= peak);
    }
    let mut listed: Vec<&str> = args.to_vec();
    listed.extend(["--w", "0 1"]);
    let text = stdout(&listed);
    assert!(
        text.contains("sigma1") && text.lines().count() >= 6,
        "{text}"
    );
}

/// gram, hsv: 1/(s + 1) has P = Q = 1/2 and σ = 1/2; balred -o writes a plant file that
/// `norm --plant` reads.
#[test]
fn gramians_hsv_and_balred_round_trip() {
    // (the realisation's scaling of b and c is its own: P·Q = σ² is not)
    let g = json(&["gram", "--den", "1 1", "--json"]);
    let p = g["matrix"][0][0].as_f64().unwrap();
    let l = json(&[
        "gram",
        "--den",
        "1 1",
        "--kind",
        "o",
        "--cholesky",
        "--json",
    ]);
    let lo = l["matrix"][0][0].as_f64().unwrap();
    assert!((p * lo * lo - 0.25).abs() < 1e-15, "P = {p}, L_o = {lo}");
    let h = json(&["hsv", "--den", "1 1", "--json"]);
    assert!((h["hsv"][0].as_f64().unwrap() - 0.5).abs() < 4e-16, "{h}");
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli_norms");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("reduced.toml");
    let f = file.to_str().unwrap();
    let lattice = [
        "--model",
        "lattice",
        "--param",
        "N=8",
        "--param",
        "gamma=0.1",
        "--param",
        "periodic=0",
        "--param",
        "output=3",
    ];
    let mut args = vec!["balred"];
    args.extend(lattice);
    args.extend(["--order", "6", "-o", f, "--json"]);
    let d = json(&args);
    let (bound, err) = (
        d["bound"].as_f64().unwrap(),
        d["error"]["upper"].as_f64().unwrap(),
    );
    assert!(err <= bound, "{d}");
    assert_eq!(d["order"].as_u64(), Some(6));
    let back = json(&["norm", "--plant", f, "--json"]);
    assert_eq!(back["states"].as_u64(), Some(6));
    // the reduced norm is within the measured error of the full one
    let mut full_args = vec!["norm"];
    full_args.extend(lattice);
    full_args.push("--json");
    let full = json(&full_args)["lower"].as_f64().unwrap();
    assert!((back["lower"].as_f64().unwrap() - full).abs() <= err * (1.0 + 1e-9));
}

#[test]
fn bad_input_is_one_line() {
    for args in [
        &["balred", "--den", "1 -1", "--order", "1"][..],
        &["gram", "--den", "1 1", "--kind", "x"],
        &[
            "hsv",
            "--model",
            "lattice",
            "--param",
            "N=4",
            "--param",
            "gamma=0.1",
        ],
        &["balred", "--den", "1 3 2", "--order", "5"],
        &["balred", "--den", "1 3 2", "--error", "-1"],
    ] {
        let out = ltikit(args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    }
    // a required choice: usage error, exit 2
    assert_eq!(ltikit(&["balred", "--den", "1 1"]).status.code(), Some(2));
}
