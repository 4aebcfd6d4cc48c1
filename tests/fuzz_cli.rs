//! A fuzzer of our own, at the command line: random extreme-but-finite plants (coefficients
//! of 1e±300, subnormals, mixed scales, orders up to MAX_ORDER, hostile tokens) thrown at
//! every command of the real binary. Every run must end within a time budget with exit code
//! 0, 1 or 2; a failure is one line on stderr and never a panic; a success with `--json` is
//! valid JSON without NaN/Infinity/-0.0 tokens; a picture either is a whole PNG or does not
//! exist.
//!
//! CI runs a fixed seed and a bounded number of cases. The long campaign:
//! `LTIKIT_FUZZ_CASES=20000 LTIKIT_FUZZ_SEED=7 cargo test --release --test fuzz_cli -- --nocapture`
//! (see docs/ARCHITECTURE.md, "Robustness").

use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// xorshift64*: a fixed-seed generator (no dependency, reproducible across platforms).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n.max(1)
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn pick<'a>(&mut self, xs: &[&'a str]) -> &'a str {
        xs[self.below(xs.len() as u64) as usize]
    }
}

/// One coefficient: mostly ordinary, sometimes extreme.
fn coefficient(r: &mut Rng) -> String {
    match r.below(12) {
        0 => "0".into(),
        1 => format!(
            "{:e}",
            (r.unit() + 0.1) * 10f64.powi(300 - r.below(10) as i32)
        ),
        2 => format!(
            "-{:e}",
            (r.unit() + 0.1) * 10f64.powi(-300 + r.below(10) as i32)
        ),
        3 => format!("{:e}", 5e-324 * (1 + r.below(1000)) as f64), // subnormal
        4 => format!(
            "{:e}",
            (r.unit() - 0.5) * 10f64.powi(r.below(600) as i32 - 300)
        ),
        5 => format!("{}", r.below(7) as i64 - 3),
        _ => format!(
            "{:.6}",
            (r.unit() - 0.3) * 10f64.powi(r.below(7) as i32 - 3)
        ),
    }
}

fn poly(r: &mut Rng, max_degree: u64) -> String {
    let n = 1 + r.below(max_degree + 1) as usize;
    let mut c: Vec<String> = (0..n).map(|_| coefficient(r)).collect();
    if c[0] == "0" {
        c[0] = "1".into();
    }
    c.join(" ")
}

/// A plant: coefficients (sometimes of high order), a hostile token, or a state-space model.
fn plant(r: &mut Rng) -> Vec<String> {
    let degree = match r.below(20) {
        0 => 200,
        1 => 120 + r.below(80),
        2..=4 => 20 + r.below(40),
        _ => 1 + r.below(8),
    };
    match r.below(25) {
        0 => vec![
            "--den".into(),
            r.pick(&["", "nan", "1 inf", "1/0", "--", "1e999999", "0 0"])
                .into(),
        ],
        1 => vec!["--den".into(), format!("1 {}", "9".repeat(2000))],
        2 => vec![
            "--a".into(),
            format!(
                "{} {}; {} {}",
                coefficient(r),
                coefficient(r),
                coefficient(r),
                coefficient(r)
            ),
            "--b".into(),
            "0; 1".into(),
            "--c".into(),
            "1 0".into(),
        ],
        3 | 4 => state_space(r),
        5 | 6 => model(r),
        _ => {
            let den = poly(r, degree);
            let num_degree = degree.min(4 + r.below(degree + 1));
            let num = poly(r, num_degree);
            vec![format!("--num={num}"), format!("--den={den}")]
        }
    }
}

/// A state-space plant: random sizes (sometimes mismatched), entries from the hostile
/// coefficient generator, MIMO at times.
fn state_space(r: &mut Rng) -> Vec<String> {
    let n = 1 + r.below(6) as usize;
    let (m, p) = (1 + r.below(3) as usize, 1 + r.below(3) as usize);
    fn rows(r: &mut Rng, rows: usize, cols: usize) -> String {
        (0..rows)
            .map(|_| {
                (0..cols)
                    .map(|_| coefficient(r))
                    .collect::<Vec<_>>()
                    .join(" ")
            })
            .collect::<Vec<_>>()
            .join("; ")
    }
    let a = rows(r, n, n);
    // one in five with a size that does not fit
    let bad = r.below(5) == 0;
    let b = rows(r, if bad { n + 1 } else { n }, m);
    let c = rows(r, p, n);
    let d = rows(r, p, m);
    let mut v = vec![format!("--a={a}"), format!("--b={b}"), format!("--c={c}")];
    if r.below(2) == 0 {
        v.push(format!("--d={d}"));
    }
    if r.below(3) == 0 {
        v.push(format!(
            "--channel={},{}",
            1 + r.below(m as u64 + 1),
            1 + r.below(p as u64 + 1)
        ));
    }
    v
}

/// A textbook model with extreme, negative, unknown or missing parameters.
fn model(r: &mut Rng) -> Vec<String> {
    let (name, params): (&str, &[&str]) = match r.below(7) {
        0 => ("spring-mass-damper", &["M", "C", "K"]),
        1 => ("second-order", &["wn", "zeta"]),
        2 => ("tank", &["A", "r"]),
        3 => ("rc", &["R", "C"]),
        4 => ("rlc", &["R", "L", "C"]),
        5 => ("two-dof", &["M1", "M2", "K1", "K2", "C"]),
        _ => (
            "lattice",
            &["N", "alpha", "beta", "m", "input", "output", "periodic"],
        ),
    };
    let mut v = vec!["--model".into(), name.into()];
    for _ in 0..r.below(4) {
        let key = if r.below(8) == 0 {
            "Q".to_string()
        } else {
            r.pick(params).to_string()
        };
        let val = match r.below(6) {
            0 => coefficient(r),
            1 => r
                .pick(&["0", "-1", "1e300", "1e-300", "nan", "inf", "3000", "2.5"])
                .into(),
            _ => format!("{}", 1 + r.below(20)),
        };
        v.push(format!("--param={key}={val}"));
    }
    v
}

/// A controller spec: valid kinds with hostile values, unknown kinds and parameters.
fn controller(r: &mut Rng) -> String {
    let v = || ["0", "1", "-1", "2.5", "1e300", "1e-300", "nan", "-0.01"];
    let kind = r.pick(&["p", "pi", "pd", "pid", "lead", "lag", "pidd", "", "pid:"]);
    let keys: &[&str] = match kind {
        "p" => &["kp"],
        "pi" => &["kp", "ki"],
        "pd" => &["kp", "kd", "tf"],
        "pid" => &["kp", "ki", "kd", "tf"],
        "lead" | "lag" => &["k", "z", "p"],
        _ => &["kp", "x"],
    };
    let mut parts: Vec<String> = Vec::new();
    for k in keys {
        if r.below(6) != 0 {
            parts.push(format!("{k}={}", r.pick(&v())));
        }
    }
    format!("{kind}:{}", parts.join(","))
}

/// The command line of case `k`, and the picture it may write.
fn case(r: &mut Rng, dir: &std::path::Path, k: usize) -> (Vec<String>, Option<PathBuf>) {
    let png = dir.join(format!("case{k}.png"));
    let mut args: Vec<String> = Vec::new();
    let mut out = None;
    let cmd = r.pick(&[
        "analyze", "residue", "response", "freq", "margins", "bode", "step", "pzmap", "nyquist",
        "routh", "rlocus",
    ]);
    args.push(cmd.into());
    args.extend(plant(r));
    if r.below(6) == 0 {
        args.push(format!("--controller={}", controller(r)));
    }
    match cmd {
        "response" => {
            args.push("--json".into());
            args.push(format!(
                "--input={}",
                r.pick(&[
                    "step",
                    "impulse",
                    "ramp",
                    "exp:-1e20",
                    "sin:1e300",
                    "cos:3",
                    "exp:1e-300"
                ])
            ));
            if r.below(2) == 0 {
                args.push("--t=0 1 10 1e6".into());
            }
        }
        "freq" => {
            args.push("--json".into());
            if r.below(2) == 0 {
                args.push("--w=0 1e-300 1 1e300".into());
            }
        }
        "routh" => {
            args.push("--json".into());
            if r.below(2) == 0 {
                args.push("--gain-range".into());
            }
            if r.below(3) == 0 {
                args.push(format!("--gain={}", coefficient(r)));
            }
        }
        "rlocus" => {
            if r.below(3) == 0 {
                args.push(format!("--gain={}", coefficient(r)));
            }
            if r.below(4) == 0 {
                args.push("--negative".into());
            }
            if r.below(2) == 0 {
                args.push("--json".into());
            } else {
                args.push("-o".into());
                args.push(png.display().to_string());
                out = Some(png);
            }
        }
        "bode" | "step" | "pzmap" | "nyquist" => {
            args.push("-o".into());
            args.push(png.display().to_string());
            out = Some(png);
        }
        _ => args.push("--json".into()),
    }
    (args, out)
}

/// Runs the binary with a time budget; (exit code, stdout, stderr, seconds).
fn run(args: &[String], budget: Duration) -> (Option<i32>, String, String, f64) {
    let start = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_ltikit"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the ltikit binary runs");
    // read the pipes on threads so a large output cannot block the child
    let mut so = child.stdout.take().expect("piped");
    let mut se = child.stderr.take().expect("piped");
    let to = std::thread::spawn(move || {
        let mut s = String::new();
        std::io::Read::read_to_string(&mut so, &mut s).ok();
        s
    });
    let te = std::thread::spawn(move || {
        let mut s = String::new();
        std::io::Read::read_to_string(&mut se, &mut s).ok();
        s
    });
    let code = loop {
        if let Ok(Some(status)) = child.try_wait() {
            break status.code();
        }
        if start.elapsed() > budget {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let secs = start.elapsed().as_secs_f64();
    (
        code,
        to.join().unwrap_or_default(),
        te.join().unwrap_or_default(),
        secs,
    )
}

#[test]
fn hostile_plants_at_every_command() {
    let cases: usize = std::env::var("LTIKIT_FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(150);
    let seed: u64 = std::env::var("LTIKIT_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2026);
    // a hang shows as a budget overrun; the debug binary is slower than the release one
    let budget = Duration::from_secs(60);
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("fuzz_cli_{seed}"));
    std::fs::create_dir_all(&dir).unwrap();
    let mut r = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let mut failures = Vec::new();
    let mut slowest = (0.0, Vec::new());
    let mut by_code = [0usize; 3];
    for k in 0..cases {
        let (args, png) = case(&mut r, &dir, k);
        if let Some(p) = &png {
            let _ = std::fs::remove_file(p);
        }
        let (code, out, err, secs) = run(&args, budget);
        if secs > slowest.0 {
            slowest = (secs, args.clone());
        }
        if secs > 5.0 {
            // slow cases in full, to reproduce
            use std::io::Write;
            if let Ok(mut f) = std::fs::OpenOptions::new()
                .create(true)
                .append(true)
                .open(dir.join("slow.jsonl"))
            {
                let _ = writeln!(
                    f,
                    "{secs:.2} {}",
                    serde_json::to_string(&args).unwrap_or_default()
                );
            }
        }
        let short: Vec<String> = args.iter().map(|a| a.chars().take(120).collect()).collect();
        let full = serde_json::to_string(&args).unwrap_or_default();
        let log = dir.join("failures.jsonl");
        let mut fail = |why: String| {
            // the whole command line, to reproduce (the report abbreviates it)
            use std::io::Write;
            if let Ok(mut f) = std::fs::OpenOptions::new()
                .create(true)
                .append(true)
                .open(&log)
            {
                let _ = writeln!(f, "{full}");
            }
            failures.push(format!("{short:?}: {why}"));
        };
        match code {
            None => fail(format!("no exit within {budget:?}")),
            Some(c @ 0..=2) => by_code[c as usize] += 1,
            Some(c) => fail(format!("exit code {c}")),
        }
        if err.contains("internal error") || err.contains("panicked") {
            fail(format!("panic: {err}"));
        }
        if code.is_some_and(|c| c != 0) && err.trim_end().lines().count() != 1 {
            fail(format!("error not on one line: {err:?}"));
        }
        if code == Some(0) && args.iter().any(|a| a == "--json") {
            for bad in ["NaN", "Infinity", "-0.0,", "-0.0\n", "-0.0]"] {
                if out.contains(bad) {
                    fail(format!("JSON holds {bad}"));
                }
            }
            if serde_json::from_str::<serde_json::Value>(&out).is_err() {
                fail("invalid JSON".into());
            }
        }
        if let Some(p) = &png {
            // a MIMO pole-zero map writes one file per channel, FILE-i-j.png
            let channel_files: Vec<PathBuf> = std::fs::read_dir(&dir)
                .map(|d| {
                    d.filter_map(|e| e.ok().map(|e| e.path()))
                        .filter(|f| {
                            f.file_name()
                                .and_then(|n| n.to_str())
                                .is_some_and(|n| n.starts_with(&format!("case{k}-")))
                        })
                        .collect()
                })
                .unwrap_or_default();
            let is_png =
                |f: &PathBuf| std::fs::read(f).is_ok_and(|b| b.starts_with(b"\x89PNG\r\n\x1a\n"));
            match (code, std::fs::read(p)) {
                (Some(0), Ok(bytes)) if bytes.starts_with(b"\x89PNG\r\n\x1a\n") => {}
                (Some(0), Err(_))
                    if !channel_files.is_empty() && channel_files.iter().all(is_png) => {}
                (Some(0), _) => fail("success without a whole PNG".into()),
                (_, Ok(_)) => fail("a failed plot left a file".into()),
                _ if !channel_files.is_empty() => fail("a failed plot left channel files".into()),
                _ => {}
            }
            for f in channel_files {
                let _ = std::fs::remove_file(f);
            }
        }
    }
    println!(
        "{cases} cases (seed {seed}): exit 0: {}, 1: {}, 2: {}; slowest {:.2} s: {:?}",
        by_code[0],
        by_code[1],
        by_code[2],
        slowest.0,
        slowest
            .1
            .iter()
            .map(|a| a.chars().take(60).collect::<String>())
            .collect::<Vec<_>>()
    );
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
