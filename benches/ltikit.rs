//! `cargo bench`: divan benchmarks of ltikit's hot paths on the inputs of the python
//! comparison (`benches/compare/inputs.toml`; see docs/PERFORMANCE.md for what each measures).
//!
//! `cargo bench -- freq` runs the benches whose path contains "freq".

mod common;

use divan::{Bencher, black_box};
use ltikit::analysis::{Input, partial_fractions};
use ltikit::{Poly, TransferFunction};

fn main() {
    divan::main();
}

/// `Poly::roots` (exact multiplicities) of the fixed random polynomials.
#[divan::bench(args = [4, 10, 50])]
fn roots(bencher: Bencher, deg: usize) {
    let p = Poly::from_descending(&common::root_poly(deg)).unwrap();
    bencher.bench(|| black_box(&p).roots().unwrap());
}

/// Frequency response of the order-8 plant on logspace(−2, 3, n), next to the bare loops.
mod freq {
    use super::*;

    /// `freq_response`: |G|, dB and the continuous phase (factored form, branch tracking).
    #[divan::bench(args = [1_000, 1_000_000], sample_count = 20)]
    fn freq_response(bencher: Bencher, n: usize) {
        let g = common::order8();
        let w = common::freq_grid(n);
        bencher.bench(|| g.freq_response(black_box(&w)).unwrap());
    }

    /// The factored form's response (factorisation outside the timing) without and with a
    /// dead time of 0.5 s (issue 21's target: the delay costs at most 1.2×; its phase −ωT is
    /// one multiply-add per frequency).
    #[divan::bench(args = [0.0, 0.5], sample_count = 20)]
    fn factored_with_delay(bencher: Bencher, delay: f64) {
        let f = common::order8()
            .with_delay(delay)
            .unwrap()
            .factored()
            .unwrap();
        let w = common::freq_grid(100_000);
        f.freq_response(&w).unwrap(); // the evaluation form is built once, outside the timing
        bencher.bench(|| f.freq_response(black_box(&w)).unwrap());
    }

    /// Reference limit: f64 Horner for the complex G(jω) = N(jω)/D(jω) only.
    #[divan::bench(args = [1_000, 1_000_000], sample_count = 20)]
    fn horner_complex_only(bencher: Bencher, n: usize) {
        let (num, den) = common::order8_coeffs();
        let w = common::freq_grid(n);
        bencher.bench(|| common::horner_complex(&num, &den, black_box(&w)));
    }

    /// Reference loop with the same outputs: f64 Horner, then |G|, dB and atan2 (principal
    /// phase, not unwrapped).
    #[divan::bench(args = [1_000, 1_000_000], sample_count = 20)]
    fn horner_mag_db_atan2(bencher: Bencher, n: usize) {
        let (num, den) = common::order8_coeffs();
        let w = common::freq_grid(n);
        bencher.bench(|| common::horner_full(&num, &den, black_box(&w)));
    }
}

/// Exact step response of the order-8 plant on linspace(0, 60, n).
#[divan::bench(args = [1_000, 100_000], sample_count = 50)]
fn step_response(bencher: Bencher, n: usize) {
    let g = common::order8();
    let t = common::time_grid(n);
    bencher.bench(|| g.step_response(black_box(&t)).unwrap());
}

/// Partial fractions and closed forms of the order-8 plant.
mod closed_form {
    use super::*;

    /// `partial_fractions(num, den)` (roots of den included), as `scipy.signal.residue`.
    #[divan::bench]
    fn partial_fractions_order8(bencher: Bencher) {
        let g = common::order8();
        bencher.bench(|| partial_fractions(black_box(g.num()), black_box(g.den())).unwrap());
    }

    /// `inverse_laplace` of the step response: partial fractions of G(s)/s and the closed
    /// form y(t) with its transient/steady-state split.
    #[divan::bench]
    fn step_closed_form_order8(bencher: Bencher) {
        let g = common::order8();
        bencher.bench(|| black_box(&g).inverse_laplace(&Input::Step, &[]).unwrap());
    }
}

/// Exact step metrics of the order-8 plant.
#[divan::bench]
fn step_info(bencher: Bencher) {
    let g = common::order8();
    bencher.bench(|| black_box(&g).step_info().unwrap());
}

/// Step metrics of a lightly damped resonator 1/(s² + 2ζs + 1) typed as text (exact path: the
/// pair is decided in the left half plane), ζ = 1e-3 … 1e-12: 10² … 10¹¹ periods before it
/// settles; issue 25's target is ≤ 10 ms each. The factorisation is outside the timing.
#[divan::bench(args = ["2e-3", "2e-6", "2e-9", "2e-12"])]
fn step_info_resonator(bencher: Bencher, two_zeta: &str) {
    use ltikit::analysis::Factored;
    use ltikit::poly::exact::ExactPoly;
    let n = ExactPoly::parse_descending(&["1"]).unwrap();
    let d = ExactPoly::parse_descending(&["1", two_zeta, "1"]).unwrap();
    let f = Factored::from_exact(&n, &d).unwrap();
    bencher.bench(|| black_box(&f).step_info().unwrap());
}

/// `analyze()` plus `margins()` of the order-8 plant: one line of `ltikit analyze --batch`.
#[divan::bench]
fn analyze(bencher: Bencher) {
    let g = common::order8();
    bencher.bench(|| {
        let g: &TransferFunction = black_box(&g);
        (g.analyze().unwrap(), g.margins().unwrap())
    });
}

/// One 1000 × 700 Bode PNG of the order-8 plant from scratch (grid, response, margins,
/// asymptotes, drawing, encoding, atomic file write).
#[divan::bench(sample_count = 30)]
fn bode_png(bencher: Bencher) {
    let g = common::order8();
    let dir = std::env::temp_dir().join(format!("ltikit-divan-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bode.png");
    bencher.bench(|| common::bode_png_of(black_box(&g), &path).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Root locus of an order-10 plant (the fixed degree-10 polynomial over the degree-4 one):
/// roots of D + K·N at 1000 fixed gains, matched into branches (issue 13's target: < 20 ms),
/// and the whole `root_locus` (features + adaptive trace).
mod rlocus {
    use crate::common;
    use divan::{Bencher, black_box};
    use ltikit::Poly;
    use ltikit::analysis::rlocus::{RootLocusOptions, root_locus, trace_at_gains};

    fn plant() -> (Poly, Poly) {
        (
            Poly::from_descending(&common::root_poly(4)).unwrap(),
            Poly::from_descending(&common::root_poly(10)).unwrap(),
        )
    }

    #[divan::bench(sample_count = 20)]
    fn order10_1000_gains(bencher: Bencher) {
        let (n, d) = plant();
        let gains: Vec<f64> = (0..1000)
            .map(|i| 10f64.powf(-3.0 + 6.0 * i as f64 / 999.0))
            .collect();
        bencher.bench(|| trace_at_gains(black_box(&n), black_box(&d), &gains).unwrap());
    }

    #[divan::bench(sample_count = 20)]
    fn order10_full(bencher: Bencher) {
        let (n, d) = plant();
        bencher.bench(|| {
            root_locus(black_box(&n), black_box(&d), &RootLocusOptions::default()).unwrap()
        });
    }
}

/// State space at scale: the seed's periodic lattice, N = 128 (256 states), one channel.
mod ss {
    use crate::common::ss as lattice;
    use divan::{Bencher, black_box};
    use ltikit::analysis::Factored;
    use ltikit::numeric::linalg::modal::ModalForm;
    use ltikit::numeric::linalg::{HessenbergResponse, eigen_structure};
    use num_complex::Complex64;

    /// Eigenvalues of A with their multiplicity structure.
    #[divan::bench(sample_count = 10)]
    fn eigenvalues(bencher: Bencher) {
        let ss = lattice::lattice();
        bencher.bench(|| eigen_structure(black_box(&ss.a)).unwrap());
    }

    /// Poles, transmission zeros and minimal realisation of the channel (the factored form).
    #[divan::bench(sample_count = 10)]
    fn channel_factored(bencher: Bencher) {
        let ss = lattice::lattice();
        bencher.bench(|| Factored::from_state_space(black_box(&ss)).unwrap());
    }

    /// G(jω) at 10 000 frequencies: one Hessenberg reduction, one O(n²) solve each.
    #[divan::bench(sample_count = 10)]
    fn freq_hessenberg(bencher: Bencher) {
        let ss = lattice::lattice();
        let s: Vec<Complex64> = lattice::freq_grid(10_000)
            .iter()
            .map(|&w| Complex64::new(0.0, w))
            .collect();
        bencher.bench(|| {
            let h = HessenbergResponse::new(&ss.a, &ss.b, &ss.c, &ss.d).unwrap();
            h.eval_siso_many(black_box(&s)).unwrap()
        });
    }

    /// The modal form: decomposition (once per model) and G(jω) at 10 000 frequencies.
    #[divan::bench(sample_count = 10)]
    fn freq_modal_decomposition(bencher: Bencher) {
        let ss = lattice::lattice();
        bencher.bench(|| ModalForm::new(black_box(&ss.a), &ss.b, &ss.c, &ss.d).unwrap());
    }

    /// G(jω) at 10 000 frequencies from the modal form (sums of simple fractions).
    #[divan::bench(sample_count = 10)]
    fn freq_modal_eval(bencher: Bencher) {
        let ss = lattice::lattice();
        let m = ModalForm::new(&ss.a, &ss.b, &ss.c, &ss.d).unwrap().unwrap();
        let ch = m.channel(0, 0);
        let s: Vec<Complex64> = lattice::freq_grid(10_000)
            .iter()
            .map(|&w| Complex64::new(0.0, w))
            .collect();
        bencher.bench(|| {
            black_box(&s)
                .iter()
                .map(|&x| ch.eval(x))
                .collect::<Vec<_>>()
        });
    }

    /// Reference loop: the modal sum (2N − 1 complex terms) at the same 10 000 frequencies.
    #[divan::bench(sample_count = 10)]
    fn freq_modal_sum_reference(bencher: Bencher) {
        let (p, r) = lattice::modal_form();
        let w = lattice::freq_grid(10_000);
        bencher.bench(|| lattice::modal_sum(&p, &r, black_box(&w)));
    }

    /// Step response, 10 000 samples, by exact discretisation of the 256-state model.
    #[divan::bench(sample_count = 10)]
    fn step_state_space(bencher: Bencher) {
        let ss = lattice::lattice();
        let t = lattice::time_grid(10_000);
        bencher.bench(|| ss.step_response_from(0, black_box(&t), false).unwrap());
    }

    /// The general (Schur) path: the same model with interleaved states.
    mod general {
        use super::*;

        #[divan::bench(sample_count = 10)]
        fn eigenvalues(bencher: Bencher) {
            let ss = lattice::lattice_interleaved();
            bencher.bench(|| eigen_structure(black_box(&ss.a)).unwrap());
        }

        #[divan::bench(sample_count = 10)]
        fn channel_factored(bencher: Bencher) {
            let ss = lattice::lattice_interleaved();
            bencher.bench(|| Factored::from_state_space(black_box(&ss)).unwrap());
        }

        #[divan::bench(sample_count = 10)]
        fn step_state_space(bencher: Bencher) {
            let ss = lattice::lattice_interleaved();
            let t = lattice::time_grid(10_000);
            bencher.bench(|| ss.step_response_from(0, black_box(&t), false).unwrap());
        }
    }
}

/// Discrete time (issue 20), on the inputs of `benches/compare/compare_discrete.py`
/// (`[discrete]` in inputs.toml): c2d (ZOH) of the lattice and of the order-8 plant, the
/// discrete step response of the order-8 discrete plant at 10⁵ samples and its closed form.
mod discrete {
    use crate::common;
    use divan::{Bencher, black_box};
    use ltikit::analysis::Input;
    use ltikit::lti::Discretization;

    /// `StateSpace::c2d` (ZOH: exponential of the 257 × 257 augmented matrix) of the
    /// 256-state lattice.
    #[divan::bench(sample_count = 10)]
    fn c2d_lattice(bencher: Bencher) {
        let ss = common::ss::lattice();
        let dt = common::discrete::inputs().dt_lattice;
        bencher.bench(|| black_box(&ss).c2d(dt, Discretization::Zoh).unwrap());
    }

    /// `TransferFunction::c2d` (ZOH) of the order-8 plant.
    #[divan::bench]
    fn c2d_tf_order8(bencher: Bencher) {
        let g = common::order8();
        let dt = common::discrete::inputs().dt_order8;
        bencher.bench(|| black_box(&g).c2d(dt, Discretization::Zoh).unwrap());
    }

    /// `Factored::c2d` (ZOH: poles e^(pT), zeros and gain of the discretised realisation).
    #[divan::bench]
    fn c2d_factored_order8(bencher: Bencher) {
        let f = common::order8().factored().unwrap();
        let dt = common::discrete::inputs().dt_order8;
        bencher.bench(|| black_box(&f).c2d(dt, Discretization::Zoh).unwrap());
    }

    /// The step response of the order-8 discrete plant at 10⁵ samples (the one marcher).
    #[divan::bench(sample_count = 20)]
    fn step_order8(bencher: Bencher) {
        let f = common::discrete::factored_z();
        let t = common::discrete::sample_times();
        bencher.bench(|| black_box(&f).step_response(black_box(&t)).unwrap());
    }

    /// The closed form y[k] (partial fractions of Y(z)/z) at the same 10⁵ samples, with the
    /// recursion beside it (`Factored::response`).
    #[divan::bench(sample_count = 20)]
    fn step_closed_form_order8(bencher: Bencher) {
        let f = common::discrete::factored_z();
        let t = common::discrete::sample_times();
        bencher.bench(|| {
            black_box(&f)
                .response(&Input::Step, &[], black_box(&t))
                .unwrap()
        });
    }
}

/// The delayed closed loop by the method of steps (`analysis::delay`): PI (Kp = 0.5,
/// Ti = 1.5) around e^(−s)/(s + 1), the loop of `tests/delay_steps.rs`.
mod delay {
    use super::*;
    use ltikit::Root;
    use ltikit::analysis::Factored;
    use num_complex::Complex64;

    fn pi_fopdt() -> Factored {
        let r = |x: f64| Root::new(Complex64::new(x, 0.0), 1);
        Factored::from_zpk(&[r(-1.0 / 1.5)], &[r(0.0), r(-1.0)], 0.5).unwrap()
    }

    /// Exact closed-loop step over 10 delays at 10⁴ samples: the 10 pieces' closed forms,
    /// each piece marched exactly, the closed form evaluated as the cross-check.
    #[divan::bench(sample_count = 20)]
    fn step_10_delays_10k_samples(bencher: Bencher) {
        let l = pi_fopdt();
        let t: Vec<f64> = (0..10_000).map(|i| i as f64 * 10.0 / 9_999.0).collect();
        bencher.bench(|| {
            black_box(&l)
                .delayed_feedback_response(1.0, &Input::Step, black_box(&t))
                .unwrap()
        });
    }

    /// The closed form alone over 10 delays, evaluated at the same 10⁴ samples.
    #[divan::bench(sample_count = 20)]
    fn closed_form_10_delays_10k_evals(bencher: Bencher) {
        let l = pi_fopdt();
        let t: Vec<f64> = (0..10_000).map(|i| i as f64 * 10.0 / 9_999.0).collect();
        bencher.bench(|| {
            let y = ltikit::analysis::DelayedClosedForm::new(&l, 1.0, &Input::Step, 10.0).unwrap();
            t.iter().map(|&x| y.eval(x)).sum::<f64>()
        });
    }

    /// The collocation march alone over the same 10 delays at 10⁴ samples (what the pieces'
    /// path above costs against it).
    #[divan::bench(sample_count = 20)]
    fn march_10_delays_10k_evals(bencher: Bencher) {
        let l = pi_fopdt();
        let t: Vec<f64> = (0..10_000).map(|i| i as f64 * 10.0 / 9_999.0).collect();
        bencher.bench(|| {
            let m =
                ltikit::analysis::delay::DelayMarch::new(black_box(&l), 1.0, &Input::Step, 10.0)
                    .unwrap();
            t.iter().map(|&x| m.eval(x)).sum::<f64>()
        });
    }

    /// Over 1000 delays (T = 0.01 s, horizon 10 s) at 10⁴ samples: the Chebyshev collocation
    /// march of the delay equation (`analysis::delay::march`), with the first 10 pieces'
    /// closed form as its cross-check.
    #[divan::bench(sample_count = 20)]
    fn step_1000_delays_10k_samples(bencher: Bencher) {
        let l = pi_fopdt();
        let t: Vec<f64> = (0..10_000).map(|i| i as f64 * 10.0 / 9_999.0).collect();
        bencher.bench(|| {
            black_box(&l)
                .delayed_feedback_response(0.01, &Input::Step, black_box(&t))
                .unwrap()
        });
    }

    /// Step metrics over 1000 delays (T = 0.01 s, horizon 10 s) on the collocation march.
    #[divan::bench(sample_count = 20)]
    fn step_info_1000_delays(bencher: Bencher) {
        let l = pi_fopdt();
        bencher.bench(|| {
            black_box(&l)
                .delayed_step_info(0.01, 10.0, true, &Default::default())
                .unwrap()
        });
    }
}

/// The matrix equations at n = 100 (random stable A, 3 inputs; `benches/common/equations.rs`),
/// the problems `benches/compare/compare_equations.py` gives scipy.
mod equations {
    use super::*;
    use ltikit::numeric::linalg::{care, lyap, lyap_cholesky};
    use nalgebra::DMatrix;

    /// `lyap`: A·X + X·Aᵀ + B·Bᵀ = 0 (Bartels–Stewart).
    #[divan::bench(args = [100], sample_count = 20)]
    fn lyap_bartels_stewart(bencher: Bencher, n: usize) {
        let (a, b) = common::equations::problem(n);
        let q = &b * b.transpose();
        bencher.bench(|| lyap(black_box(&a), black_box(&q)).unwrap());
    }

    /// `lyap_cholesky`: the same equation's Cholesky factor (Hammarling).
    #[divan::bench(args = [100], sample_count = 20)]
    fn lyap_hammarling(bencher: Bencher, n: usize) {
        let (a, b) = common::equations::problem(n);
        bencher.bench(|| lyap_cholesky(black_box(&a), black_box(&b)).unwrap());
    }

    /// `care` with Q = I, R = I.
    #[divan::bench(args = [100], sample_count = 20)]
    fn care_schur_newton(bencher: Bencher, n: usize) {
        let (a, b) = common::equations::problem(n);
        let q = DMatrix::identity(n, n);
        let r = DMatrix::identity(3, 3);
        bencher.bench(|| care(black_box(&a), &b, &q, &r, None).unwrap());
    }
}
