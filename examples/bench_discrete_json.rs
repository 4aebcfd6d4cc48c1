//! Timings of ltikit's discrete-time paths (issue 20), as JSON on stdout, for
//! `benches/compare/compare_discrete.py` (which times scipy/python-control on the same inputs
//! in the same run). Medians of repeated runs, in seconds, plus the values the script checks
//! against scipy (the discretised coefficients, the step samples) and the closed form's
//! agreement with the recursion. Keys:
//! - `c2d_lattice`: `StateSpace::c2d(T, Zoh)` of the 256-state lattice — vs
//!   `scipy.signal.cont2discrete((A, B, C, D), T, method='zoh')`;
//! - `c2d_tf_order8`: `TransferFunction::c2d(T, Zoh)` of the order-8 plant — vs
//!   `cont2discrete((num, den), T)`; `c2d_factored_order8`: `Factored::c2d` (poles e^(pT) with
//!   their multiplicities, zeros and gain of the discretised realisation), factorisation
//!   outside the timing;
//! - `dstep_order8`: `Factored::step_response` of the discrete order-8 plant at the `samples`
//!   sample times (the one marcher) — vs `scipy.signal.dstep((num, den, T), n = samples)`;
//!   `dstep_tf_order8`: the same from the transfer function (factorisation included);
//! - `matmul_257`: one dense 257 × 257 matrix product, `lu_solve_257`: one LU solve with 257
//!   right-hand sides (the Padé denominator's) — sub-steps of `c2d_lattice`;
//! - `closed_form_order8`: `Factored::response(Step)` at those samples: the partial fractions
//!   of Y(z)/z, the closed form y[k] evaluated at every sample, and the recursion beside it.

#[path = "../benches/common/mod.rs"]
mod common;

use std::hint::black_box;
use std::time::Instant;

use ltikit::analysis::Input;
use ltikit::lti::Discretization;

/// Median seconds per call over `repeat` batches, each at least ~`min_time`/5 long (the
/// scheme of examples/bench_json.rs and compare.py's `median_time`).
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
    let d = common::discrete::inputs();
    let lattice = common::ss::lattice();
    let g = common::order8();
    let f = g.factored()?;
    let gz = common::discrete::plant_z();
    let fz = gz.factored()?;
    let t = common::discrete::sample_times();
    let zoh = Discretization::Zoh;

    // values for the accuracy checks (not timed)
    let gd = g.c2d(d.dt_order8, zoh)?;
    let step = fz.step_response(&t)?;
    let resp = fz.response(&Input::Step, &[], &t)?;

    // sub-step of the lattice's c2d: one dense 257 × 257 product (the exponential's Padé
    // approximant and squarings are made of these, plus one LU solve)
    let n = lattice.order() + 1;
    let m = nalgebra::DMatrix::<f64>::from_fn(n, n, |i, j| {
        if i < n - 1 && j < n - 1 {
            lattice.a[(i, j)] * d.dt_lattice
        } else {
            0.0
        }
    });
    let out = serde_json::json!({
        "matmul_257": median_time(7, 0.2, || &m * &m),
        "lu_solve_257": median_time(7, 0.2, || {
            let id = nalgebra::DMatrix::<f64>::identity(n, n);
            (&id - &m).lu().solve(&(&id + &m))
        }),
        "c2d_lattice": median_time(5, 0.5, || lattice.c2d(d.dt_lattice, zoh)),
        "c2d_tf_order8": median_time(7, 0.2, || g.c2d(d.dt_order8, zoh)),
        "c2d_factored_order8": median_time(7, 0.2, || f.c2d(d.dt_order8, zoh)),
        "dstep_order8": median_time(7, 0.2, || fz.step_response(&t)),
        "dstep_tf_order8": median_time(7, 0.2, || gz.factored().and_then(|f| f.step_response(&t))),
        "closed_form_order8": median_time(5, 0.2, || fz.response(&Input::Step, &[], &t)),
        "c2d_tf_order8_num": gd.num().coeffs(),
        "c2d_tf_order8_den": gd.den().coeffs(),
        "plant_z_num": gz.num().coeffs(),
        "plant_z_den": gz.den().coeffs(),
        "dstep_y": step.y,
        "closed_form_error": resp.samples.closed_form_error,
        "closed_form_max_abs_y": resp.samples.max_abs_y,
    });
    println!("{out}");
    Ok(())
}
