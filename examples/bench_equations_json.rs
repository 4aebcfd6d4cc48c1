//! Timings of ltikit's matrix equations at n = 100 (the problems of
//! `benches/common/equations.rs`), as JSON on stdout, for
//! `benches/compare/compare_equations.py` (which times scipy on the same matrices in the same
//! run). Medians of repeated runs, in seconds, with the relative residuals.

#[path = "../benches/common/equations.rs"]
mod equations;

use std::time::Instant;

use ltikit::numeric::linalg::{care, lyap};
use nalgebra::DMatrix;

/// Median seconds per call over `reps` calls (after one warm-up call).
fn median<T>(reps: usize, mut f: impl FnMut() -> T) -> f64 {
    std::hint::black_box(f());
    let mut times: Vec<f64> = (0..reps)
        .map(|_| {
            let t0 = Instant::now();
            std::hint::black_box(f());
            t0.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n = 100;
    let (a, b) = equations::problem(n);
    let q_lyap = &b * b.transpose();
    let q = DMatrix::identity(n, n);
    let r = DMatrix::identity(3, 3);
    let l = lyap(&a, &q_lyap)?;
    let c = care(&a, &b, &q, &r, None)?;
    let t_lyap = median(21, || lyap(&a, &q_lyap));
    let t_care = median(21, || care(&a, &b, &q, &r, None));
    // x[0][0] lets the script check that both sides solved the same problem.
    println!(
        "{{\"n\": {n}, \"lyap\": {t_lyap:e}, \"care\": {t_care:e}, \"lyap_residual\": {:e}, \"care_residual\": {:e}, \"lyap_x00\": {:e}, \"care_x00\": {:e}}}",
        l.residual,
        c.residual,
        l.x[(0, 0)],
        c.x[(0, 0)]
    );
    Ok(())
}
