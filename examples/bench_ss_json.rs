//! Timings of ltikit's state-space kernels on the seed's lattice (N = 128, 256 states), as
//! JSON on stdout, for `benches/compare/compare_ss.py` (which times python-control on the same
//! model in the same run). Medians of repeated runs, in seconds. The `general_*` keys time the
//! same model with interleaved states, which the second-order recognition does not take; the
//! `random_*` keys a random dense stable 256-state model (`random_dense`), piece by piece.

#[path = "../benches/common/ss.rs"]
mod lattice;

use std::time::Instant;

use ltikit::analysis::Factored;
use ltikit::numeric::linalg::modal::ModalForm;
use ltikit::numeric::linalg::{
    HessenbergResponse, SchurOptions, eigen_structure, minimal_realization, real_schur,
    schur_eigenvalues, transmission_zeros,
};
use num_complex::Complex64;

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
    let ss = lattice::lattice();
    let general = lattice::lattice_interleaved();
    let random = lattice::random_dense();
    let s: Vec<Complex64> = lattice::freq_grid(10_000)
        .iter()
        .map(|&w| Complex64::new(0.0, w))
        .collect();
    let (p, r) = lattice::modal_form();
    let w = lattice::freq_grid(10_000);
    let t = lattice::time_grid(10_000);
    // Accuracy of the timed frequency response against the modal sum (printed, not timed).
    let h = HessenbergResponse::new(&ss.a, &ss.b, &ss.c, &ss.d)?;
    let g = h.eval_siso_many(&s)?;
    let m = lattice::modal_sum(&p, &r, &w);
    let max_rel = g
        .iter()
        .zip(&m)
        .map(|(a, b)| (a - b).norm() / b.norm())
        .fold(0.0, f64::max);
    let mf = ModalForm::new(&ss.a, &ss.b, &ss.c, &ss.d)?.ok_or("the lattice's modal form")?;
    let ch = mf.channel(0, 0);
    let out = serde_json::json!({
        "eigenvalues": median(7, || eigen_structure(&ss.a)),
        "channel_factored": median(7, || Factored::from_state_space(&ss)),
        "freq_hessenberg_10k": median(5, || {
            HessenbergResponse::new(&ss.a, &ss.b, &ss.c, &ss.d).and_then(|h| h.eval_siso_many(&s))
        }),
        "freq_modal_sum_10k": median(7, || lattice::modal_sum(&p, &r, &w)),
        // the public entry (the channel's factored form and its Bode kernel, the one engine):
        // factorisation + evaluation
        "freq_response_mimo_10k": median(5, || ss.freq_response_mimo(&w)),
        "freq_modal_decomposition": median(7, || ModalForm::new(&ss.a, &ss.b, &ss.c, &ss.d)),
        "freq_modal_eval_10k": median(7, || s.iter().map(|&x| ch.eval(x)).collect::<Vec<_>>()),
        "step_10k": median(5, || ss.step_response_from(0, &t, false)),
        // the same model with interleaved states: the general (Schur) path
        "general_eigenvalues": median(7, || eigen_structure(&general.a)),
        "general_channel_factored": median(7, || Factored::from_state_space(&general)),
        "general_freq_response_mimo_10k": median(5, || general.freq_response_mimo(&w)),
        "general_step_10k": median(5, || general.step_response_from(0, &t, false)),
        // a random dense stable model without any structure (benches/common/ss.rs
        // `random_dense`, the same numbers in compare_ss.py): where the general path's time goes
        "random_real_schur_with_q": median(5, || real_schur(&random.a, SchurOptions::default())),
        "random_schur_eigenvalues": median(5, || schur_eigenvalues(&random.a)),
        "random_modal_form": median(5, || ModalForm::new(&random.a, &random.b, &random.c, &random.d)),
        "random_eigenvalues": median(5, || eigen_structure(&random.a)),
        "random_minimal_realization": median(5, || {
            minimal_realization(&random.a, &random.b, &random.c, &random.d, None)
        }),
        "random_transmission_zeros": median(5, || {
            transmission_zeros(&random.a, &random.b, &random.c, &random.d, None)
        }),
        "random_channel_factored": median(5, || Factored::from_state_space(&random)),
        "random_step_10k": median(5, || random.step_response_from(0, &t, false)),
        "random_step_y_end": random.step_response_from(0, &t, false)?.y[0][t.len() - 1],
        "freq_max_rel_diff_vs_modal": max_rel,
    });
    println!("{out}");
    Ok(())
}
