//! Systems built from systems: `series`, `parallel`, `feedback` of two plant files, diagram
//! files (`connect`, and as `--plant` of any command), `eval` at a complex point and the gang
//! of four — against closed forms (products of transfer functions evaluated by Horner's rule,
//! matrix products of C(sI − A)⁻¹B + D by an independent complex solve), and every bad input.
#![cfg(feature = "cli")]

mod common;

use common::{json, json_matrix, ltikit};
use nalgebra::DMatrix;
use num_complex::Complex64;
use std::path::PathBuf;

fn scratch(name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("ltikit-connect-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p: PathBuf = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

/// p(s) by Horner's rule (descending coefficients).
fn horner(c: &[f64], s: Complex64) -> Complex64 {
    c.iter()
        .fold(Complex64::new(0.0, 0.0), |acc, &x| acc * s + x)
}

fn ratio(num: &[f64], den: &[f64], s: Complex64) -> Complex64 {
    horner(num, s) / horner(den, s)
}

fn nums(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// C(sI − A)⁻¹B + D by a complex LU solve (independent of the library's evaluation).
fn transfer(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    s: Complex64,
) -> DMatrix<Complex64> {
    let n = a.nrows();
    let cx = |m: &DMatrix<f64>| m.map(|x| Complex64::new(x, 0.0));
    let si = DMatrix::<Complex64>::identity(n, n) * s - cx(a);
    let x = si.lu().solve(&cx(b)).unwrap();
    cx(c) * x + cx(d)
}

/// A closed form G(s).
type Exact<'a> = Box<dyn Fn(Complex64) -> Complex64 + 'a>;

const POINTS: [(f64, f64); 4] = [(0.3, 1.7), (-2.5, 0.2), (1.0, 0.0), (0.0, 5.0)];

fn close(a: Complex64, b: Complex64, tol: f64) -> bool {
    (a - b).norm() <= tol * b.norm().max(1e-300)
}

/// The error line of a failing command (exit 1 unless `code` says otherwise).
fn error(args: &[&str], code: i32) -> String {
    let out = ltikit(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    err
}

#[test]
fn series_parallel_feedback_of_transfer_functions_are_the_closed_forms() {
    // G_A = (s + 2)/(s² + 3s + 1), G_B = 3/(s + 4)
    let (na, da) = ([1.0, 2.0], [1.0, 3.0, 1.0]);
    let (nb, db) = ([3.0], [1.0, 4.0]);
    let a = scratch("tf-a.toml", "num = [1, 2]\nden = [1, 3, 1]\n");
    let b = scratch("tf-b.toml", "num = [3]\nden = [1, 4]\n");
    let cases: [(&[&str], Exact); 5] = [
        // G_B·G_A
        (
            &["series"],
            Box::new(|s| ratio(&na, &da, s) * ratio(&nb, &db, s)),
        ),
        (
            &["parallel"],
            Box::new(|s| ratio(&na, &da, s) + ratio(&nb, &db, s)),
        ),
        (
            &["parallel", "--sign", "-1"],
            Box::new(|s| ratio(&na, &da, s) - ratio(&nb, &db, s)),
        ),
        // G/(1 + G·H), G/(1 − G·H)
        (
            &["feedback"],
            Box::new(|s| {
                let (g, h) = (ratio(&na, &da, s), ratio(&nb, &db, s));
                g / (1.0 + g * h)
            }),
        ),
        (
            &["feedback", "--sign", "+1"],
            Box::new(|s| {
                let (g, h) = (ratio(&na, &da, s), ratio(&nb, &db, s));
                g / (1.0 - g * h)
            }),
        ),
    ];
    for (cmd, exact) in cases.iter() {
        let mut args: Vec<&str> = vec![cmd[0], &a, &b, "--json"];
        args.extend(&cmd[1..]);
        let v = json(&args);
        assert_eq!(v["operation"], cmd[0]);
        let (num, den) = (nums(&v["num"]), nums(&v["den"]));
        for (re, im) in POINTS {
            let s = Complex64::new(re, im);
            assert!(
                close(ratio(&num, &den, s), exact(s), 1e-13),
                "{cmd:?} at {s}"
            );
        }
    }
    // the series connection's order: A then B, which for SISO commutes; the text report
    let out = common::stdout(&["series", &a, &b]);
    assert!(
        out.contains("G(s) = (3 s + 6) / (s^3 + 7 s^2 + 13 s + 4)"),
        "{out}"
    );
}

#[test]
fn mimo_series_is_the_matrix_product_and_mixed_models_become_state_space() {
    // A: 2 inputs, 2 outputs; B: 2 inputs, 1 output — series A then B is G_B·G_A (1 × 2)
    let a = scratch(
        "ss-a.toml",
        "a = \"-1 0.5; 0 -2\"\nb = \"1 0; 0.5 1\"\nc = \"1 0; 1 1\"\nd = \"0 0.1; 0 0\"\n",
    );
    let b = scratch(
        "ss-b.toml",
        "a = \"-3\"\nb = \"1 2\"\nc = \"1\"\nd = \"0.5 0\"\n",
    );
    let m = |t: &str| -> DMatrix<f64> {
        let rows: Vec<Vec<f64>> = t
            .split(';')
            .map(|r| r.split_whitespace().map(|x| x.parse().unwrap()).collect())
            .collect();
        DMatrix::from_fn(rows.len(), rows[0].len(), |i, j| rows[i][j])
    };
    let ga = (
        m("-1 0.5; 0 -2"),
        m("1 0; 0.5 1"),
        m("1 0; 1 1"),
        m("0 0.1; 0 0"),
    );
    let gb = (m("-3"), m("1 2"), m("1"), m("0.5 0"));
    let v = json(&["series", &a, &b, "--json"]);
    let (aa, bb, cc, dd) = (
        json_matrix(&v["a"]),
        json_matrix(&v["b"]),
        json_matrix(&v["c"]),
        json_matrix(&v["d"]),
    );
    assert_eq!((cc.nrows(), bb.ncols()), (1, 2));
    for (re, im) in POINTS {
        let s = Complex64::new(re, im);
        let want =
            transfer(&gb.0, &gb.1, &gb.2, &gb.3, s) * transfer(&ga.0, &ga.1, &ga.2, &ga.3, s);
        let got = transfer(&aa, &bb, &cc, &dd, s);
        for (x, y) in got.iter().zip(want.iter()) {
            assert!(close(*x, *y, 1e-13), "at {s}: {got} vs {want}");
        }
    }
    // B then A does not chain: 1 output into 2 inputs
    let e = error(&["series", &b, &a], 1);
    assert!(e.contains("1 outputs but the second 2 inputs"), "{e}");
    // a transfer function in feedback around a SISO state-space model: state space, closed form
    let g = scratch(
        "ss-g.toml",
        "a = \"0 1; -2 -3\"\nb = \"0; 1\"\nc = \"1 0\"\n",
    ); // 1/(s²+3s+2)
    let h = scratch("tf-h.toml", "num = [5]\nden = [1, 10]\n");
    let v = json(&["feedback", &g, &h, "--json"]);
    let (aa, bb, cc, dd) = (
        json_matrix(&v["a"]),
        json_matrix(&v["b"]),
        json_matrix(&v["c"]),
        json_matrix(&v["d"]),
    );
    for (re, im) in POINTS {
        let s = Complex64::new(re, im);
        let gs = ratio(&[1.0], &[1.0, 3.0, 2.0], s);
        let hs = ratio(&[5.0], &[1.0, 10.0], s);
        let got = transfer(&aa, &bb, &cc, &dd, s)[(0, 0)];
        assert!(close(got, gs / (1.0 + gs * hs), 1e-13), "at {s}");
    }
}

#[test]
fn results_written_with_o_are_plants() {
    let a = scratch("w-a.toml", "num = [2]\nden = [1, 3, 0]\n");
    let b = scratch("w-b.toml", "num = [3]\nden = [1, 4]\n");
    let out = scratch("w-out.toml", "");
    let text = common::stdout(&["feedback", &a, &b, "-o", &out]);
    assert!(text.contains("written:"), "{text}");
    // G/(1 + GH) = 2(s + 4)/(s³ + 7s² + 12s + 6): dc gain 8/6
    let v = json(&["analyze", "--plant", &out, "--json"]);
    assert!(
        (v["dc_gain"].as_f64().unwrap() - 8.0 / 6.0).abs() < 1e-14,
        "{v}"
    );
    // a diagram written as one state-space plant file keeps its signal names
    let p = scratch("w-p.toml", "num = [1]\nden = [1, 1]\n");
    let _ = p;
    let d = scratch(
        "w-loop.toml",
        "inputs = [\"r\"]\noutputs = [\"y\"]\n[blocks.P]\nplant = \"w-p.toml\"\ninput = \"e\"\noutput = \"y\"\n[sums]\ne = \"r - y\"\n",
    );
    let out2 = scratch("w-out2.toml", "");
    common::stdout(&["connect", &d, "-o", &out2]);
    let written = std::fs::read_to_string(&out2).unwrap();
    assert!(
        written.contains("inputs = [\"r\"]") && written.contains("states = [\"P.x1\"]"),
        "{written}"
    );
    let v = json(&["analyze", "--plant", &out2, "--json"]);
    assert!((v["dc_gain"].as_f64().unwrap() - 0.5).abs() < 1e-15, "{v}");
}

#[test]
fn a_unity_feedback_diagram_is_feedback_of_c_times_p() {
    // C = (s + 2)/s, P = 2/(s(s + 3)): T = CP/(1 + CP) = 2(s + 2)/(s³ + 3s² + 2s + 4)
    scratch(
        "motor.toml",
        "name = \"motor\"\nnum = [2]\nden = [1, 3, 0]\n",
    );
    let d = scratch(
        "unity.toml",
        "inputs = [\"r\"]\noutputs = [\"y\"]\n[blocks.C]\nnum = [1, 2]\nden = [1, 0]\ninput = \"e\"\noutput = \"u\"\n[blocks.P]\nplant = \"motor.toml\"\ninput = \"u\"\noutput = \"y\"\n[sums]\ne = \"r - y\"\n",
    );
    let plant = ltikit::lti::Plant::from_file(std::path::Path::new(&d)).unwrap();
    let f = plant.factored().unwrap();
    for (re, im) in POINTS {
        let s = Complex64::new(re, im);
        let l = ratio(&[1.0, 2.0], &[1.0, 0.0], s) * ratio(&[2.0], &[1.0, 3.0, 0.0], s);
        assert!(close(f.eval(s), l / (1.0 + l), 1e-12), "at {s}");
        assert!(close(
            f.eval(s),
            ratio(&[2.0, 4.0], &[1.0, 3.0, 2.0, 4.0], s),
            1e-12
        ));
    }
    // the same through the command line: `connect` and a diagram as --plant of `eval`
    let v = json(&["eval", "--plant", &d, "--s", "-1+2j", "--json"]);
    let g = &v["channels"][0]["value"];
    let got = Complex64::new(g[0].as_f64().unwrap(), g[1].as_f64().unwrap());
    let s = Complex64::new(-1.0, 2.0);
    assert!(close(
        got,
        ratio(&[2.0, 4.0], &[1.0, 3.0, 2.0, 4.0], s),
        1e-12
    ));
    let v = json(&["connect", &d, "--json"]);
    assert_eq!(v["poles"].as_array().unwrap().len(), 3);
    assert!((v["dc_gain"][0][0].as_f64().unwrap() - 1.0).abs() < 1e-14);
}

#[test]
fn a_two_loop_cascade_diagram_is_one_plant() {
    // inner velocity loop: PI 4 + 2/s around P₁ = 1/(s + 1) (u → v); outer position loop: P 2
    // around the inner loop and P₂ = 1/s (v → x). Inner T_v = (4s + 2)/(s² + 5s + 2), outer
    // T = 2·T_v/s / (1 + 2·T_v/s) = (8s + 4)/(s³ + 5s² + 10s + 4).
    let d = scratch(
        "cascade.toml",
        "name = \"cascade\"\ninputs = [\"r\"]\noutputs = [\"x\"]\n\
         [blocks.Kx]\ncontroller = \"p:kp=2\"\ninput = \"ex\"\noutput = \"vr\"\n\
         [blocks.Kv]\ncontroller = \"pi:kp=4,ki=2\"\ninput = \"ev\"\noutput = \"u\"\n\
         [blocks.P1]\nnum = 1\nden = [1, 1]\ninput = \"u\"\noutput = \"v\"\n\
         [blocks.P2]\nnum = 1\nden = [1, 0]\ninput = \"v\"\noutput = \"x\"\n\
         [sums]\nex = \"r - x\"\nev = \"vr - v\"\n",
    );
    let plant = ltikit::lti::Plant::from_file(std::path::Path::new(&d)).unwrap();
    assert_eq!(plant.name, "cascade");
    let f = plant.factored().unwrap();
    for (re, im) in POINTS {
        let s = Complex64::new(re, im);
        let want = ratio(&[8.0, 4.0], &[1.0, 5.0, 10.0, 4.0], s);
        assert!(
            close(f.eval(s), want, 1e-12),
            "at {s}: {} vs {want}",
            f.eval(s)
        );
    }
    // analysed as one plant: the poles are the roots of s³ + 5s² + 10s + 4, dc gain 1
    let v = json(&["analyze", "--plant", &d, "--json"]);
    assert!((v["dc_gain"].as_f64().unwrap() - 1.0).abs() < 1e-13, "{v}");
    for p in v["poles"].as_array().unwrap() {
        let z = Complex64::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
        assert!(horner(&[1.0, 5.0, 10.0, 4.0], z).norm() < 1e-11, "{z}");
    }
    assert_eq!(v["poles"].as_array().unwrap().len(), 3);
    // a MIMO diagram: two outputs of one state-space block, each fed back
    let m = scratch(
        "mimo-loop.toml",
        "inputs = [\"r1\", \"r2\"]\noutputs = [\"y1\", \"y2\"]\n[blocks.G]\na = \"-1 0; 0 -2\"\nb = \"1 0; 0 1\"\nc = \"1 0; 0 1\"\ninput = [\"e1\", \"e2\"]\noutput = [\"y1\", \"y2\"]\n[sums]\ne1 = \"r1 - y1\"\ne2 = \"r2 - 0.5*y2 + y1\"\n",
    );
    let v = json(&["connect", &m, "--json"]);
    // ẋ₁ = −2x₁ + r₁, ẋ₂ = −2.5x₂ + x₁ + r₂
    assert_eq!(
        json_matrix(&v["a"]),
        DMatrix::from_row_slice(2, 2, &[-2.0, 0.0, 1.0, -2.5])
    );
    assert_eq!(json_matrix(&v["b"]), DMatrix::identity(2, 2));
}

#[test]
fn eval_is_horner_at_every_channel_and_refuses_poles() {
    let (num, den) = ([1.0, -2.0, 0.5], [2.0, 1.0, 3.0, 0.25]);
    for (re, im) in POINTS {
        let point = format!("{re}{:+}j", im);
        let v = json(&[
            "eval",
            "--num",
            "1 -2 0.5",
            "--den",
            "2 1 3 0.25",
            "--s",
            &point,
            "--json",
        ]);
        let g = &v["channels"][0]["value"];
        let got = Complex64::new(g[0].as_f64().unwrap(), g[1].as_f64().unwrap());
        let s = Complex64::new(re, im);
        assert!(close(got, ratio(&num, &den, s), 1e-13), "at {s}");
    }
    // discrete time: --z
    let v = json(&[
        "eval", "--num", "0.5", "--den", "1 -0.5", "--dt", "0.1", "--z", "0.5+0.5j", "--json",
    ]);
    assert_eq!(v["variable"], "z");
    let g = &v["channels"][0]["value"];
    let want = 0.5 / Complex64::new(0.0, 0.5);
    assert!((Complex64::new(g[0].as_f64().unwrap(), g[1].as_f64().unwrap()) - want).norm() < 1e-15);
    // every channel of a MIMO plant
    let v = json(&[
        "eval",
        "--a",
        "-1 0; 0 -2",
        "--b",
        "1 0; 0 1",
        "--c",
        "1 1",
        "--s",
        "1",
        "--json",
    ]);
    let ch = v["channels"].as_array().unwrap();
    assert_eq!(ch.len(), 2);
    assert!((ch[0]["value"][0].as_f64().unwrap() - 0.5).abs() < 1e-15);
    assert!((ch[1]["value"][0].as_f64().unwrap() - 1.0 / 3.0).abs() < 1e-15);
    // at a pole: one line naming it
    let e = error(&["eval", "--num", "1", "--den", "1 3 2", "--s", "-2"], 1);
    assert!(e.contains("s = -2 is at the pole -2 of G"), "{e}");
    let e = error(
        &[
            "eval",
            "--a",
            "-1 0; 0 -2",
            "--b",
            "1 0; 0 1",
            "--c",
            "1 1",
            "--s",
            "-2",
        ],
        1,
    );
    assert!(
        e.contains("channel input 2 → output 1") && e.contains("pole -2"),
        "{e}"
    );
    // the wrong variable, a bad number: usage errors
    error(&["eval", "--num", "1", "--den", "1 1", "--z", "1"], 2);
    error(&["eval", "--num", "1", "--den", "1 1"], 2);
    let e = error(&["eval", "--num", "1", "--den", "1 1", "--s", "1+2k"], 1);
    assert!(e.contains("'1+2k' is not a complex number"), "{e}");
}

#[test]
fn the_gang_of_four_of_a_loop() {
    // G = 1/(s(s + 1)), C = 2: S = s(s+1)/(s²+s+2), PS = 1/(s²+s+2), CS = 2s(s+1)/(s²+s+2),
    // T = 2/(s²+s+2); max|T(jω)| = 2/√1.75 at ω² = 1.5 (the minimum of ω⁴ − 3ω² + 4)
    let v = json(&[
        "gangof4",
        "--num",
        "1",
        "--den",
        "1 1 0",
        "--controller",
        "p:kp=2",
        "--json",
    ]);
    assert_eq!(v["internally_stable"], true);
    let sys = v["systems"].as_array().unwrap();
    let names: Vec<&str> = sys.iter().map(|s| s["system"].as_str().unwrap()).collect();
    assert_eq!(names, ["S", "PS", "CS", "T"]);
    let dc: Vec<f64> = sys.iter().map(|s| s["dc_gain"].as_f64().unwrap()).collect();
    assert_eq!(dc[0], 0.0);
    assert!(
        (dc[1] - 0.5).abs() < 1e-15 && dc[2].abs() < 1e-15 && (dc[3] - 1.0).abs() < 1e-15,
        "{dc:?}"
    );
    let t = &sys[3];
    assert!(
        (t["peak"].as_f64().unwrap() - 2.0 / 1.75f64.sqrt()).abs() < 1e-12,
        "{t}"
    );
    assert!(
        (t["peak_w"].as_f64().unwrap() - 1.5f64.sqrt()).abs() < 1e-8,
        "{t}"
    );
    for s in sys {
        assert_eq!(s["poles"].as_array().unwrap().len(), 2, "{s}");
    }
    // |CS|² = 4x(1 + x)/(x² − 3x + 4) with x = ω²: d/dx = 0 at x² − 2x − 1 = 0, x = 1 + √2
    let x = 1.0 + 2f64.sqrt();
    let cs = (4.0 * x * (1.0 + x) / (x * x - 3.0 * x + 4.0)).sqrt();
    assert!(
        (sys[2]["peak"].as_f64().unwrap() - cs).abs() < 1e-12 * cs,
        "{}",
        sys[2]
    );
    assert!(
        (sys[2]["peak_w"].as_f64().unwrap() - x.sqrt()).abs() < 1e-8,
        "{}",
        sys[2]
    );
}

#[test]
fn bad_interconnections_are_one_line_each() {
    let dir_file = |n: &str, t: &str| scratch(n, t);
    let one = dir_file("one.toml", "num = 1\nden = 1\n");
    let tfz = dir_file("tfz.toml", "num = 1\nden = [1, -0.5]\ndt = 0.1\n");
    let tfz2 = dir_file("tfz2.toml", "num = 1\nden = [1, -0.5]\ndt = 0.2\n");
    let del = dir_file("delayed.toml", "num = 1\nden = [1, 1]\ndelay = 0.5\n");
    let ssd = dir_file("ss-d.toml", "a = \"-1\"\nb = \"1\"\nc = \"1\"\nd = \"1\"\n");
    let ssm = dir_file(
        "ss-minus.toml",
        "a = \"-1\"\nb = \"1\"\nc = \"1\"\nd = \"-1\"\n",
    );
    // ill posed: 1 − 1·1 = 0 (transfer functions) and I + D_G·D_H singular (state space)
    let e = error(&["feedback", &one, &one, "--sign", "+1"], 1);
    assert!(e.contains("not well posed"), "{e}");
    let e = error(&["feedback", &ssd, &ssm], 1);
    assert!(
        e.contains("singular") && e.contains("not well posed"),
        "{e}"
    );
    // sampling periods
    let e = error(&["series", &tfz, &tfz2], 1);
    assert!(e.contains("dt = 0.1") && e.contains("dt = 0.2"), "{e}");
    let e = error(&["parallel", &one, &tfz], 1);
    assert!(
        e.contains("continuous-time") && e.contains("discrete-time"),
        "{e}"
    );
    // a delay: series of transfer functions is exact (delays add), feedback is not
    let v = json(&["series", &del, &del, "--json"]);
    assert_eq!(v["delay"], 1.0);
    let e = error(&["feedback", &del, &one], 1);
    assert!(e.contains("feedback"), "{e}");
    let e = error(&["series", &del, &ssd], 1);
    assert!(e.contains("dead time"), "{e}");
    // usage: a sign other than ±1, an output that is not .toml
    error(&["feedback", &one, &one, "--sign", "2"], 2);
    error(&["series", &one, &one, "-o", "x.png"], 2);
    let e = error(&["series", &one, "/nonexistent/ltikit.toml"], 1);
    assert!(e.contains("/nonexistent/ltikit.toml"), "{e}");
}

#[test]
fn bad_diagrams_are_one_line_naming_the_signal_or_block() {
    scratch("d-p.toml", "num = [1]\nden = [1, 1]\n");
    let good = "inputs = [\"r\"]\noutputs = [\"y\"]\n[blocks.C]\nnum = 2\nden = 1\ninput = \"e\"\noutput = \"u\"\n[blocks.P]\nplant = \"d-p.toml\"\ninput = \"u\"\noutput = \"y\"\n[sums]\ne = \"r - y\"\n";
    let g = scratch("d-good.toml", good);
    assert!(ltikit(&["connect", &g]).status.success());
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            "twice",
            "output = \"u\"",
            "output = \"y\"",
            "the signal `y` is driven twice: by block `C` and by block `P`",
        ),
        (
            "never",
            "r - y",
            "r - w",
            "the signal `w` (in the sum `e`) is driven by nothing",
        ),
        (
            "input-twice",
            "[sums]\ne = \"r - y\"",
            "[sums]\nr = \"y\"\ne = \"r - y\"",
            "`r` is driven twice: by the diagram's inputs and by the sum `r`",
        ),
        (
            "output-unknown",
            "outputs = [\"y\"]",
            "outputs = [\"q\"]",
            "the signal `q` (a diagram output) is driven by nothing",
        ),
        (
            "sizes",
            "input = \"u\"",
            "input = [\"u\", \"e\"]",
            "block `P` has 1 inputs and 1 outputs, but 2 input and 1 output signals",
        ),
        (
            "kind",
            "num = 2\nden = 1\n",
            "",
            "block `C` needs exactly one of",
        ),
        (
            "unknown-key",
            "[blocks.C]",
            "[blocks.C]\ngain = 3",
            "unknown key `gain`",
        ),
        (
            "missing-plant",
            "d-p.toml",
            "d-missing.toml",
            "d-missing.toml",
        ),
        ("bad-sum", "r - y", "r - * y", "sum `e`"),
        (
            "signal-name",
            "output = \"u\"",
            "output = \"u v\"",
            "'u v' is not a signal name",
        ),
        (
            "ill-posed",
            "plant = \"d-p.toml\"",
            "num = -0.5\nden = 1",
            "the algebraic loop through",
        ),
        (
            "mixed-dt",
            "[blocks.P]\nplant = \"d-p.toml\"",
            "[blocks.P]\nplant = \"d-pz.toml\"",
            "discrete-time",
        ),
        (
            "delay",
            "d-p.toml",
            "d-pdelay.toml",
            "block `P` has a dead time",
        ),
        (
            "controller",
            "num = 2\nden = 1",
            "controller = \"pid:kp=1,kd=1\"",
            "block `C`",
        ),
        (
            "no-outputs",
            "outputs = [\"y\"]",
            "outputs = []",
            "at least one output",
        ),
    ];
    scratch("d-pz.toml", "num = [1]\nden = [1, -0.5]\ndt = 0.1\n");
    scratch("d-pdelay.toml", "num = [1]\nden = [1, 1]\ndelay = 0.2\n");
    for (name, from, to, want) in cases {
        assert!(good.contains(from), "{name}");
        let p = scratch(&format!("d-{name}.toml"), &good.replace(from, to));
        let e = error(&["connect", &p], 1);
        assert!(e.contains(want), "{name}: {e}");
        assert!(
            e.contains(&format!("d-{name}.toml")),
            "{name} names the file: {e}"
        );
        // the same error wherever the diagram is a plant
        let e2 = error(&["analyze", "--plant", &p], 1);
        assert!(e2.contains(want), "{name}: {e2}");
    }
    // the ill-posed loop names its signals: e = r − y, u = 2e, y = −0.5u ⇒ e = r + e
    let p = scratch(
        "d-ill.toml",
        &good.replace("plant = \"d-p.toml\"", "num = -0.5\nden = 1"),
    );
    let e = error(&["connect", &p], 1);
    assert!(
        e.contains("`e`") && e.contains("`u`") && e.contains("`y`"),
        "{e}"
    );
    // a diagram that includes itself stops at the depth limit
    let s = scratch(
        "d-self.toml",
        "inputs = [\"r\"]\noutputs = [\"y\"]\n[blocks.P]\nplant = \"d-self.toml\"\ninput = \"r\"\noutput = \"y\"\n",
    );
    let e = error(&["connect", &s], 1);
    assert!(e.contains("MAX_DIAGRAM_DEPTH"), "{e}");
}

#[test]
fn the_shipped_cascade_diagram_is_its_closed_form() {
    // data/diagrams/cascade.toml: motor 2/(0.5s + 1) = 4/(s + 2), inner PI 1.5 + 6/s, outer
    // P 4, shaft 1/s. Inner T_v = (6s + 24)/(s² + 8s + 24); outer T = (24s + 96)/(s³ + 8s² +
    // 48s + 96).
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/data/diagrams/cascade.toml");
    let plant = ltikit::lti::Plant::from_file(std::path::Path::new(path)).unwrap();
    let f = plant.factored().unwrap();
    for (re, im) in POINTS {
        let s = Complex64::new(re, im);
        let want = ratio(&[24.0, 96.0], &[1.0, 8.0, 48.0, 96.0], s);
        assert!(close(f.eval(s), want, 1e-12), "at {s}");
    }
    assert_eq!(plant.signals.inputs, ["r"]);
    assert_eq!(plant.signals.outputs, ["theta"]);
}
