//! ltikit's side of the python-control/scipy comparison (`benches/compare/compare.py`): times
//! the operations compare.py times, on the same inputs (`benches/compare/inputs.toml`), and
//! prints one JSON object of seconds per call (median of repeats, each repeat long enough
//! for the clock), plus the order-8 coefficients so compare.py can check they are identical.
//!
//! Run with `cargo run --release --example bench_json`. Keys:
//! - `roots_deg4/10/50`: `Poly::roots` (exact multiplicities) — vs `numpy.roots`;
//! - `freq_order8_1000/1000000`: `freq_response` (|G|, dB, continuous phase) on
//!   logspace(−2, 3, n) — vs `ct.frequency_response` + `np.unwrap`;
//! - `horner_order8_1000000`: the bare f64 Horner loop for the complex G(jω) only;
//!   `horner_full_order8_1000000`: Horner + |G| + dB + atan2 (no unwrapping);
//! - `step_order8_1000/100000`: exact `step_response` on linspace(0, 60, n) — vs
//!   `scipy.signal.step`;
//! - `residue_order8`: `partial_fractions(num, den)` — vs `scipy.signal.residue`;
//!   `closed_form_order8`: `inverse_laplace(step)` (partial fractions of G/s and the closed
//!   form y(t), no python counterpart);
//! - `step_info_order8`: exact `step_info` — vs `ct.step_info`;
//! - `analyze_order8`: `analyze()` + `margins()` (what one batch line computes) — vs
//!   poles + zeros + dcgain + step_info + stability_margins;
//! - `bode_png`: one 1000 × 700 Bode PNG from the plant (grid, response, margins,
//!   asymptotes, drawing, PNG encoding, file write).

#[path = "../benches/common/mod.rs"]
mod common;

use std::hint::black_box;
use std::time::Instant;

use ltikit::Poly;
use ltikit::analysis::{Input, partial_fractions};
use serde_json::{Map, Value, json};

/// Median seconds per call over `repeat` batches, each at least ~`min_time`/5 long (the
/// same scheme as compare.py's `median_time`).
fn median_time<T>(repeat: usize, min_time: f64, mut f: impl FnMut() -> T) -> f64 {
    black_box(f()); // warm up
    let mut n = 1usize;
    loop {
        let t0 = Instant::now();
        for _ in 0..n {
            black_box(f());
        }
        let dt = t0.elapsed().as_secs_f64();
        if dt >= min_time / 5.0 || n > 1_000_000 {
            break;
        }
        n *= 4;
    }
    let mut samples: Vec<f64> = (0..repeat)
        .map(|_| {
            let t0 = Instant::now();
            for _ in 0..n {
                black_box(f());
            }
            t0.elapsed().as_secs_f64() / n as f64
        })
        .collect();
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut out = Map::new();
    let mut put = |k: &str, v: f64| {
        out.insert(k.to_string(), json!(v));
    };
    for deg in [4, 10, 50] {
        let p = Poly::from_descending(&common::root_poly(deg))?;
        put(
            &format!("roots_deg{deg}"),
            median_time(7, 0.2, || p.roots()),
        );
    }
    let g = common::order8();
    let (num, den) = common::order8_coeffs();
    for n in [1000, 1_000_000] {
        let w = common::freq_grid(n);
        let rep = if n > 10_000 { 5 } else { 7 };
        put(
            &format!("freq_order8_{n}"),
            median_time(rep, 0.2, || g.freq_response(black_box(&w))),
        );
        if n == 1_000_000 {
            put(
                &format!("horner_order8_{n}"),
                median_time(rep, 0.2, || {
                    common::horner_complex(&num, &den, black_box(&w))
                }),
            );
            put(
                &format!("horner_full_order8_{n}"),
                median_time(rep, 0.2, || common::horner_full(&num, &den, black_box(&w))),
            );
        }
    }
    for n in [1000, 100_000] {
        let t = common::time_grid(n);
        put(
            &format!("step_order8_{n}"),
            median_time(5, 0.2, || g.step_response(black_box(&t))),
        );
    }
    put(
        "residue_order8",
        median_time(7, 0.2, || partial_fractions(g.num(), g.den())),
    );
    put(
        "closed_form_order8",
        median_time(7, 0.2, || g.inverse_laplace(&Input::Step, &[])),
    );
    put("step_info_order8", median_time(7, 0.2, || g.step_info()));
    put(
        "analyze_order8",
        median_time(7, 0.2, || (g.analyze(), g.margins())),
    );
    let dir = std::env::temp_dir().join(format!("ltikit-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let png = dir.join("bode.png");
    put(
        "bode_png",
        median_time(5, 0.5, || common::bode_png_of(&g, &png)),
    );
    let _ = std::fs::remove_dir_all(&dir);
    out.insert("order8_num".into(), json!(num));
    out.insert("order8_den".into(), json!(den));
    println!("{}", Value::Object(out));
    Ok(())
}
