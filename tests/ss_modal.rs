//! The modal (block-diagonal) form of state-space models against the Hessenberg evaluation and
//! closed forms: the seed's lattice (fixed: simple eigenvalues; periodic: degenerate pairs and
//! a Jordan block at 0), random stable systems, and defective matrices that must fall back.

mod common;
use common::interleaved;
use ltikit::StateSpace;
use ltikit::analysis::{Factored, MimoFreqResponse};
use ltikit::lti::lattice::{Boundary, Lattice, Output};
use ltikit::numeric::linalg::HessenbergResponse;
use ltikit::numeric::linalg::modal::ModalForm;
use nalgebra::DMatrix;
use num_complex::Complex64 as C;

fn lattice(b: Boundary) -> StateSpace {
    Lattice::new(128, b, 1.0)
        .and_then(|l| l.with_input(1))
        .and_then(|l| l.with_output(Output::Particle(6)))
        .and_then(|l| l.state_space())
        .unwrap()
}

/// Largest relative errors of the modal and the Hessenberg evaluations of the channel against
/// the lattice's closed-form modal sum (`Lattice::modal_sum`, weights in closed form), on the
/// axis, skipping ω within 1e-6 (relative) of an eigenvalue (where every evaluation is
/// conditioned by 1/dist).
fn axis_errors(b: Boundary, ss: &StateSpace, m: &ModalForm) -> (f64, f64) {
    let h = HessenbergResponse::new(&ss.a, &ss.b, &ss.c, &ss.d).unwrap();
    let exact = Lattice::new(128, b, 1.0).unwrap().modal_sum(6, 1).unwrap();
    let ch = m.channel(0, 0);
    let ev = m.eigenvalues();
    let mut worst = (0.0f64, 0.0f64);
    // up to ω = 2.5: beyond the band edge (ω = 2) the response is evanescent and every f64
    // evaluation, the closed form's included, loses digits to cancellation (see below)
    for k in 0..3000 {
        let w = 10f64.powf(-2.0 + 2.4 * k as f64 / 2999.0);
        let s = C::new(0.0, w);
        if ev.iter().any(|l| (s - l).norm() <= 1e-6 * w) {
            continue;
        }
        let e = exact.eval(s);
        worst.0 = worst.0.max((ch.eval(s) - e).norm() / e.norm());
        worst.1 = worst.1.max((h.eval_siso(s) - e).norm() / e.norm());
    }
    worst
}

#[test]
fn lattice_fixed_and_periodic() {
    // Fixed: 256 simple eigenvalues ±j·2 sin(πk/258) — 256 blocks of size 1, by either path.
    let ss = lattice(Boundary::Fixed);
    for (path, model) in [("second order", ss.clone()), ("Schur", interleaved(&ss))] {
        let m = ModalForm::new(&model.a, &model.b, &model.c, &model.d)
            .unwrap()
            .expect("safe");
        assert!(m.blocks.iter().all(|b| b.lambda.nrows() == 1));
        // Near a pole a modal sum is as accurate as its eigenvalue and residue over the
        // distance (here 1.6e-14 at ω₁ = 0.0244, 4.7e-5 away: 1.4e-8 second order, 8.2e-9
        // Schur) while the Hessenberg solve is backward stable in A (5.2e-10 second order,
        // 3.2e-9 on the interleaved states; 4.6e-9 when the reflectors summed their dot
        // products in one running sum): both within 1.5× of those figures.
        let (em, eh) = axis_errors(Boundary::Fixed, &model, &m);
        assert!(
            em <= 2e-8 && eh <= 5e-9,
            "{path}: modal {em}, Hessenberg {eh}"
        );
        eprintln!("fixed, {path}: modal {em:e}, Hessenberg {eh:e}");
    }
    // Periodic: the pairs k, N − k share ±j·2 sin(πk/N) (semisimple), and the rigid-body
    // mode is a Jordan block at 0. The Schur path keeps each degenerate pair in one 2×2 block
    // (126 of them) besides the Jordan block; the second-order path has one 1×1 block per
    // eigenvalue of a mode (the pairs are different modes) and the Jordan block.
    let ss = lattice(Boundary::Periodic);
    for (path, model, twos) in [
        ("second order", ss.clone(), 1),
        ("Schur", interleaved(&ss), 127),
    ] {
        let m = ModalForm::new(&model.a, &model.b, &model.c, &model.d)
            .unwrap()
            .expect("safe");
        let n2 = m.blocks.iter().filter(|b| b.lambda.nrows() == 2).count();
        // ±jω_k for k = 1…63 (shared with N − k), the Jordan block at 0; ±2j (k = 64) simple
        assert_eq!(n2, twos, "{path}");
        assert_eq!(
            m.blocks.iter().map(|b| b.lambda.nrows()).sum::<usize>(),
            256
        );
        let (em, eh) = axis_errors(Boundary::Periodic, &model, &m);
        eprintln!("periodic (ω ≤ 2.5), {path}: modal {em:e}, Hessenberg {eh:e}");
        assert!(
            em <= 4.0 * eh.max(1e-9),
            "{path}: modal {em}, Hessenberg {eh}"
        );
        // Against 40-digit values of e₆ᵀ(Ω − ω²I)⁻¹e₁ (mpmath lu_solve of the 128×128
        // circulant): at ω = 10, beyond the band edge 2, |G| = 1.13e-12 is ~10⁻⁸ of the modal
        // terms — every f64 evaluation loses digits there (real parts: modal (Schur, states in
        // the model's order) 2.8e-8, Hessenberg 3.2e-7, the closed-form modal sum 3.8e-7; the
        // whole complex value: second order 1.0e-6, Schur on the interleaved states 2.5e-5 —
        // absolute errors of ~3e-17 against terms of ~1e-4).
        let ch = m.channel(0, 0);
        for (w, want, tol) in [
            (0.5, 0.037_257_226_609_299_33, 1e-11),
            (1.3, 0.238_472_405_157_496_9, 1e-11),
            (10.0, 1.129_692_228_637_488_3e-12, 1e-4),
        ] {
            let g = ch.eval(C::new(0.0, w));
            let r = (g - want).norm() / want;
            eprintln!("  {path}: ω = {w}: relative error {r:e}");
            assert!(r < tol, "{path}: ω = {w}: {r}");
        }
    }
}

#[test]
fn random_stable_systems_agree_with_hessenberg() {
    let mut seed = 0x1234_5678_9abc_def1u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for n in [3usize, 10, 40] {
        let mut a = DMatrix::from_fn(n, n, |_, _| next());
        // shift into the left half plane
        let shift = 1.0 + a.norm() / (n as f64).sqrt();
        for i in 0..n {
            a[(i, i)] -= shift;
        }
        let b = DMatrix::from_fn(n, 2, |_, _| next());
        let c = DMatrix::from_fn(3, n, |_, _| next());
        let d = DMatrix::from_fn(3, 2, |_, _| next());
        let m = ModalForm::new(&a, &b, &c, &d).unwrap().expect("safe");
        let h = HessenbergResponse::new(&a, &b, &c, &d).unwrap();
        for k in 0..50 {
            let s = C::new(0.0, 10f64.powf(-2.0 + 4.0 * k as f64 / 49.0));
            let (gm, gh) = (m.eval(s), h.eval(s));
            for j in 0..3 {
                for i in 0..2 {
                    let ch = m.channel(i, j).eval(s);
                    let r = (gm[(j, i)] - gh[(j, i)]).norm() / gh[(j, i)].norm();
                    assert!(r < 1e-11, "n = {n}: {r}");
                    assert!((ch - gm[(j, i)]).norm() <= 1e-11 * gm[(j, i)].norm());
                }
            }
        }
    }
}

#[test]
fn a_defective_triple_falls_back_or_agrees() {
    // 1/(s + 1)³ as a 3×3 Jordan block: its computed eigenvalues split by ~ε^(1/3) (beyond the
    // cluster distance), so the form is refused or, if accepted, exact to the check.
    let a = DMatrix::from_row_slice(3, 3, &[-1.0, 1.0, 0.0, 0.0, -1.0, 1.0, 0.0, 0.0, -1.0]);
    let b = DMatrix::from_row_slice(3, 1, &[0.0, 0.0, 1.0]);
    let c = DMatrix::from_row_slice(1, 3, &[1.0, 0.0, 0.0]);
    let d = DMatrix::zeros(1, 1);
    if let Some(m) = ModalForm::new(&a, &b, &c, &d).unwrap() {
        let s = C::new(0.3, 1.0);
        let want = 1.0 / ((s + 1.0) * (s + 1.0) * (s + 1.0));
        assert!((m.channel(0, 0).eval(s) - want).norm() < 1e-10 * want.norm());
    }
    // through the public entry: many frequencies (the modal path when safe), against the
    // closed form |G| = 1/(1 + ω²)^(3/2), φ = −3·atan ω
    let ss = StateSpace::new(a, b, c, d).unwrap();
    let w: Vec<f64> = (0..200).map(|k| 0.01 * 1.05f64.powi(k)).collect();
    let r = ss.freq_response_mimo(&w).unwrap();
    for (k, x) in w.iter().enumerate() {
        let mag = 1.0 / (1.0 + x * x).powf(1.5);
        assert!((r.magnitude[0][0][k] - mag).abs() < 1e-12 * mag.max(1e-300) + 1e-300);
        assert!((r.phase_deg[0][0][k] + 3.0 * x.atan().to_degrees()).abs() < 1e-9);
    }
}

/// Every channel of `ss` at `w`: the MIMO response against the SISO factored response of the
/// channel (`Factored::from_state_space(&ss.channel(i, j))`) — the same magnitude and the same
/// continuous phase to 1e-9 degrees.
fn assert_channels_are_siso(ss: &StateSpace, w: &[f64]) -> MimoFreqResponse {
    let r = ss.freq_response_mimo(w).unwrap();
    for j in 0..ss.n_outputs() {
        for i in 0..ss.n_inputs() {
            let siso = Factored::from_state_space(&ss.channel(i, j).unwrap())
                .unwrap()
                .freq_response(w)
                .unwrap();
            for (k, x) in w.iter().enumerate() {
                let (a, b) = (r.phase_deg[j][i][k], siso.phase_deg[k]);
                assert!((a - b).abs() < 1e-9, "{i} → {j}, ω = {x}: {a} {b}");
                let (a, b) = (r.magnitude[j][i][k], siso.magnitude[k]);
                assert!(a == b || (a - b).abs() <= 1e-12 * b, "{i} → {j}: {a} {b}");
            }
        }
    }
    r
}

#[test]
fn mimo_phase_is_the_siso_channel_phase() {
    // A right-half-plane zero and a negative gain: A = diag(−1, −2), B = [1 0; 1 1],
    // C = [2 −3; 1 1]: G11 = (1 − s)/((s + 1)(s + 2)), G21 = (2s + 3)/((s + 1)(s + 2)),
    // G12 = −3/(s + 2), G22 = 1/(s + 2).
    let ss = StateSpace::new(
        DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -2.0]),
        DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 1.0, 1.0]),
        DMatrix::from_row_slice(2, 2, &[2.0, -3.0, 1.0, 1.0]),
        DMatrix::zeros(2, 2),
    )
    .unwrap();
    // a coarse grid: the phase does not depend on it (unwrapping samples would put G11 at
    // ω = 1000 on +90°, not −270°)
    let w = [0.0, 0.01, 1.0, 1000.0];
    let r = assert_channels_are_siso(&ss, &w);
    for (k, &x) in w.iter().enumerate() {
        let (a1, a2) = (x.atan().to_degrees(), (x / 2.0).atan().to_degrees());
        let want = [
            (0, 0, -2.0 * a1 - a2),
            (1, 0, (2.0 * x / 3.0).atan().to_degrees() - a1 - a2),
            (0, 1, -180.0 - a2),
            (1, 1, -a2),
        ];
        for (j, i, ph) in want {
            let got = r.phase_deg[j][i][k];
            assert!((got - ph).abs() < 1e-9, "{i} → {j}, ω = {x}: {got} vs {ph}");
        }
    }
    // Poles on the imaginary axis: an undamped oscillator (±2j) and an integrator, all three
    // states measured: G1 = 1/(s² + 4), G2 = s/(s² + 4), G3 = 1/s.
    let ss = StateSpace::new(
        DMatrix::from_row_slice(3, 3, &[0.0, 1.0, 0.0, -4.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
        DMatrix::from_row_slice(3, 1, &[0.0, 1.0, 1.0]),
        DMatrix::identity(3, 3),
        DMatrix::zeros(3, 1),
    )
    .unwrap();
    let w = [0.01, 1.0, 1.99, 2.01, 10.0];
    let r = assert_channels_are_siso(&ss, &w);
    // the pair drops the phase by 180° as ω passes 2 (the eigenvalue computed as
    // ±2.0000000000000004j: on the axis, not exactly at ω = 2)
    let want = [
        [0.0, 0.0, 0.0, -180.0, -180.0],
        [90.0, 90.0, 90.0, -90.0, -90.0],
        [-90.0; 5],
    ];
    for (j, row) in want.iter().enumerate() {
        for (k, ph) in row.iter().enumerate() {
            let got = r.phase_deg[j][0][k];
            assert!((got - ph).abs() < 1e-9, "output {j}, ω = {}: {got}", w[k]);
        }
    }
    // The lattice channel (256 states, every pole on the axis): the same phase on a few
    // frequencies and on the same ones among many (no unwrapping along the grid).
    let ss = lattice(Boundary::Fixed);
    let few = [0.05, 0.3, 1.7];
    let many: Vec<f64> = few
        .iter()
        .copied()
        .chain((0..2000).map(|k| 3.0 + k as f64 * 1e-3))
        .collect();
    let rf = assert_channels_are_siso(&ss, &few);
    let rm = ss.freq_response_mimo(&many).unwrap();
    for k in 0..3 {
        let (a, b) = (rf.magnitude[0][0][k], rm.magnitude[0][0][k]);
        assert!((a - b).abs() <= 1e-12 * a, "{a} {b}");
        let (a, b) = (rf.phase_deg[0][0][k], rm.phase_deg[0][0][k]);
        assert!((a - b).abs() < 1e-9, "{a} {b}");
    }
}

/// Largest difference between two response sets, relative to the largest value.
fn max_rel(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    let scale = b.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .flatten()
        .zip(b.iter().flatten())
        .map(|(x, y)| (x - y).abs() / scale)
        .fold(0.0, f64::max)
}

#[test]
fn modal_time_responses_agree_with_the_dense_march() {
    // The modal path (order ≥ 32, no states) against the dense exact discretisation (asked
    // for the states, which keeps it dense), on the lattice and a random stable system.
    let t: Vec<f64> = (0..400).map(|k| 0.25 * k as f64).collect();
    for ss in [lattice(Boundary::Fixed), lattice(Boundary::Periodic)] {
        let m = ss.step_response_from(0, &t, false).unwrap();
        let d = ss.step_response_from(0, &t, true).unwrap();
        assert!(m.x.is_none() && d.x.is_some());
        let e = max_rel(&m.y, &d.y);
        assert!(e < 1e-10, "step {e}");
        let m = ss.impulse_response_from(0, &t, false).unwrap();
        let d = ss.impulse_response_from(0, &t, true).unwrap();
        let e = max_rel(&m.y, &d.y);
        assert!(e < 1e-10, "impulse {e}");
        let x0: Vec<f64> = (0..256)
            .map(|k| ((k * 7) % 13) as f64 / 13.0 - 0.5)
            .collect();
        let m = ss.initial_response(&x0, &t, false).unwrap();
        let d = ss.initial_response(&x0, &t, true).unwrap();
        let e = max_rel(&m.y, &d.y);
        assert!(e < 1e-10, "initial {e}");
    }
    let mut seed = 0x5eed_1234_u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let n = 40;
    let mut a = DMatrix::from_fn(n, n, |_, _| next());
    let shift = 0.5 + a.norm() / (n as f64).sqrt();
    for i in 0..n {
        a[(i, i)] -= shift;
    }
    let ss = StateSpace::new(
        a,
        DMatrix::from_fn(n, 2, |_, _| next()),
        DMatrix::from_fn(3, n, |_, _| next()),
        DMatrix::from_fn(3, 2, |_, _| next()),
    )
    .unwrap();
    // unsorted, repeated and non-uniform times
    let t = [0.0, 3.0, 0.5, 0.5, 1.25, 10.0, 2.0];
    for input in 0..2 {
        let m = ss.step_response_from(input, &t, false).unwrap();
        let d = ss.step_response_from(input, &t, true).unwrap();
        let e = max_rel(&m.y, &d.y);
        assert!(e < 1e-11, "random step {e}");
    }
}

/// Damped lattices through the second-order path (Rayleigh damping: γ to the ground and η in
/// the springs; with η = 1 the periodic lattice's zone-edge mode ω = 2 has c = ηω² = 2ω: it is
/// critically damped, a Jordan block; the stiffer-damped modes near it are overdamped) with all
/// N displacements as outputs: modal step, impulse and initial responses against the dense
/// exact march, and the same models with interleaved states (the Schur path).
#[test]
fn damped_second_order_lattices_agree_with_the_dense_march() {
    let t: Vec<f64> = (0..200).map(|k| 0.3 * k as f64).collect();
    for (b, gamma, eta) in [
        (Boundary::Fixed, 0.02, 0.01),
        (Boundary::Periodic, 0.0, 1.0),
        (Boundary::Periodic, 0.05, 0.0),
    ] {
        let ss = Lattice::new(40, b, 1.0)
            .and_then(|l| l.with_damping(gamma, eta))
            .and_then(|l| l.with_input(3))
            .and_then(|l| l.with_output(Output::All))
            .and_then(|l| l.state_space())
            .unwrap();
        let so = ltikit::numeric::linalg::second_order::SecondOrder::detect(&ss.a)
            .expect("Rayleigh damping is classical");
        if eta == 1.0 {
            // the zone-edge mode, besides the free translation (λ = γ = 0)
            let crit = so
                .modes
                .iter()
                .filter(|m| m.critical && m.stiffness > 0.0)
                .count();
            assert_eq!(crit, 1, "the zone-edge mode is critical");
        }
        for model in [ss.clone(), interleaved(&ss)] {
            let what = format!("{b:?} γ = {gamma} η = {eta}");
            let m = model.step_response_from(0, &t, false).unwrap();
            let d = model.step_response_from(0, &t, true).unwrap();
            assert!(max_rel(&m.y, &d.y) < 1e-10, "{what}: step");
            let m = model.impulse_response_from(0, &t, false).unwrap();
            let d = model.impulse_response_from(0, &t, true).unwrap();
            assert!(max_rel(&m.y, &d.y) < 1e-10, "{what}: impulse");
            let x0: Vec<f64> = (0..80)
                .map(|k| ((k * 5) % 11) as f64 / 11.0 - 0.5)
                .collect();
            let m = model.initial_response(&x0, &t, false).unwrap();
            let d = model.initial_response(&x0, &t, true).unwrap();
            assert!(max_rel(&m.y, &d.y) < 1e-10, "{what}: initial");
        }
    }
}
