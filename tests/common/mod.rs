//! Helpers shared by the integration tests: plants from coefficients, grids, reference
//! arithmetic that does not use the library (bisection), error measures, and the runner of
//! the `ltikit` binary ([`ltikit`], [`ltikit_with_stdin`]).
#![allow(dead_code)] // each test file uses its own subset

use ltikit::{Poly, Root, TransferFunction};
use num_complex::Complex64;

/// G = num/den from descending coefficients (the test's plant; panics on bad input).
pub fn tf(num: &[f64], den: &[f64]) -> TransferFunction {
    TransferFunction::from_descending(num, den).unwrap()
}

/// A polynomial from descending coefficients.
pub fn poly(c: &[f64]) -> Poly {
    Poly::from_descending(c).unwrap()
}

/// A complex number.
pub fn c(re: f64, im: f64) -> Complex64 {
    Complex64::new(re, im)
}

/// A simple real root.
pub fn real_root(re: f64) -> Root {
    Root::new(c(re, 0.0), 1)
}

/// `n` log-spaced points from 10^a to 10^b inclusive.
pub fn logspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| 10f64.powf(a + (b - a) * i as f64 / (n - 1) as f64))
        .collect()
}

/// n + 1 equally spaced times from 0 to `t_end`.
pub fn grid(t_end: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|k| t_end * k as f64 / n as f64).collect()
}

/// |a − b| / |b| (|a − b| when b = 0).
pub fn rel(a: f64, b: f64) -> f64 {
    if b == 0.0 {
        (a - b).abs()
    } else {
        ((a - b) / b).abs()
    }
}

/// Plain bisection for f(x) = 0 on [a, b] with f(a)·f(b) ≤ 0 (independent of the library).
pub fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let fa = f(a);
    assert!(fa * f(b) <= 0.0, "no sign change on [{a}, {b}]");
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if (f(m) > 0.0) == (fa > 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// A second-order model [[0, I], [−G, −E]] with its states interleaved (q₁, q̇₁, q₂, q̇₂, …):
/// the same system, no longer in the block pattern, so every kernel takes the general (Schur)
/// path — the reference the second-order path is compared with.
pub fn interleaved(ss: &ltikit::StateSpace) -> ltikit::StateSpace {
    use nalgebra::DMatrix;
    let n = ss.order();
    let d = n / 2;
    // new state 2i is q_i (old i), 2i + 1 is q̇_i (old d + i)
    let old = |k: usize| if k % 2 == 0 { k / 2 } else { d + k / 2 };
    ltikit::StateSpace::new(
        DMatrix::from_fn(n, n, |i, j| ss.a[(old(i), old(j))]),
        DMatrix::from_fn(n, ss.b.ncols(), |i, j| ss.b[(old(i), j)]),
        DMatrix::from_fn(ss.c.nrows(), n, |i, j| ss.c[(i, old(j))]),
        ss.d.clone(),
    )
    .unwrap()
}

/// Runs the `ltikit` binary built for these tests with `args` and returns its exit status,
/// stdout and stderr (nothing on stdin). The integration tests' one way to run the binary;
/// `tests/fuzz_cli.rs` keeps its own runner, which adds a time budget.
#[cfg(feature = "cli")]
pub fn ltikit(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_ltikit"))
        .args(args)
        .stdin(std::process::Stdio::null())
        .output()
        .expect("the ltikit binary runs")
}

/// [`ltikit`] with `stdin` written to the binary's standard input, which is then closed.
#[cfg(feature = "cli")]
pub fn ltikit_with_stdin(args: &[&str], stdin: &[u8]) -> std::process::Output {
    use std::io::Write;
    use std::process::Stdio;
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_ltikit"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the ltikit binary starts");
    let mut pipe = child.stdin.take().expect("stdin is piped");
    // written from a thread: a large input must not block on a child that is busy filling
    // its stdout pipe
    let data = stdin.to_vec();
    let writer = std::thread::spawn(move || pipe.write_all(&data));
    let out = child.wait_with_output().expect("the ltikit binary runs");
    // the child may exit before reading everything (a usage error): a broken pipe is fine
    let _ = writer.join().expect("the stdin writer does not panic");
    out
}

/// The standard output of a successful run of the binary (the test fails otherwise).
pub fn stdout(args: &[&str]) -> String {
    let out = ltikit(args);
    assert!(
        out.status.success(),
        "ltikit {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// The JSON document a successful run prints (the test fails on invalid JSON).
pub fn json(args: &[&str]) -> serde_json::Value {
    let text = stdout(args);
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("invalid JSON ({e}): {text}"))
}

/// The factored form of a discrete plant typed as text (`num`/`den` in descending powers of
/// z, sampling period `dt`): the exact path, as `ltikit … --dt` reads it.
pub fn discrete_text(num: &str, den: &str, dt: f64) -> ltikit::analysis::Factored {
    ltikit::lti::Plant::from_text(Some(num), den)
        .unwrap()
        .with_domain(ltikit::lti::Domain::discrete(dt).unwrap())
        .unwrap()
        .factored()
        .unwrap()
}

/// A matrix stored in JSON as a list of rows of numbers (panics on anything else).
pub fn json_matrix(v: &serde_json::Value) -> nalgebra::DMatrix<f64> {
    let rows: Vec<Vec<f64>> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            r.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect();
    let (r, c) = (rows.len(), rows.first().map_or(0, Vec::len));
    nalgebra::DMatrix::from_fn(r, c, |i, j| rows[i][j])
}
