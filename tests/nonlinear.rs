//! Nonlinear models: exact Jacobians, equilibria, linearisation, simulation (issue 4).
//!
//! Reference values are closed forms: seed eq. 2.18 (pendulum Jacobian), the Lorenz
//! eigenvalues at the origin −b and (−(σ+1) ± √((σ+1)² + 4σ(r−1)))/2, the MEMS cubic
//! l²(l0 − l) = εA v²/(2k) and pull-in voltage √(8 k l0³/(27 εA)) (seed exercise 2.11), the
//! elliptic period 4K(sin(θ₀/2))/ω (seed §2.3.1.1), the polar solution of the seed's van der
//! Pol form (ρ² = 1/(1 + (1/ρ₀² − 1)e^{−2t}), φ = φ₀ + t), and e^{At}x₀ (seed eq. 2.4).

use std::f64::consts::PI;

use ltikit::lti::plant_specs;
use ltikit::nonlinear::models::{LinearModel, Lorenz, Mems, Pendulum, VanDerPol};
use ltikit::nonlinear::*;
use ltikit::numeric::expm;
use ltikit::numeric::rk45::Rk45Options;
use ltikit::{LtiError, TransferFunction};
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;
use proptest::prelude::*;

fn tight() -> Rk45Options {
    Rk45Options {
        rtol: 1e-12,
        atol: 1e-14,
        ..Default::default()
    }
}

fn max_abs_diff(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    assert_eq!(a.shape(), b.shape());
    (a - b).amax()
}

// ---------------------------------------------------------------- Jacobians vs closed forms

#[test]
fn pendulum_jacobians_match_seed_eq_2_18() {
    let mut worst: f64 = 0.0;
    for (m, l, c) in [
        (1.0, 1.0, 0.5),
        (2.5, 0.3, 0.0),
        (0.1, 4.0, 1.7),
        (7.0, 0.9, 0.02),
    ] {
        let p = Pendulum::new(m, l, c, 9.81).unwrap();
        for theta in [0.0, PI] {
            let j = jacobians(&p, &[theta, 0.0], &[0.0]).unwrap();
            let exact_a = DMatrix::from_row_slice(
                2,
                2,
                &[
                    0.0,
                    1.0,
                    -(3.0 * 9.81 / (2.0 * l)) * theta.cos(),
                    -3.0 * c / (m * l * l),
                ],
            );
            let exact_b = DMatrix::from_row_slice(2, 1, &[0.0, 3.0 / (m * l * l)]);
            worst = worst
                .max(max_abs_diff(&j.a, &exact_a) / exact_a.amax())
                .max(max_abs_diff(&j.b, &exact_b) / exact_b.amax());
            assert_eq!(j.c, DMatrix::from_row_slice(1, 2, &[1.0, 0.0]));
            assert_eq!(j.d, DMatrix::zeros(1, 1));
        }
    }
    eprintln!("pendulum Jacobian vs seed eq. 2.18: max relative error {worst:.2e}");
    assert!(worst <= 2.0 * f64::EPSILON, "{worst:e}");
}

#[test]
fn lorenz_eigenvalues_at_the_origin() {
    let mut worst: f64 = 0.0;
    for (sigma, r, b) in [(10.0, 28.0, 8.0 / 3.0), (16.0, 45.92, 4.0), (3.0, 0.5, 1.0)] {
        let l = Lorenz::from_values(&[sigma, r, b]).unwrap();
        let lin = linearize(&l, None, &EquilibriumSearch::default()).unwrap();
        let origin = lin
            .equilibria
            .iter()
            .find(|e| e.x.iter().all(|v| *v == 0.0))
            .unwrap();
        let disc = (sigma + 1.0) * (sigma + 1.0) + 4.0 * sigma * (r - 1.0);
        let mut exact = [
            -b,
            (-(sigma + 1.0) + disc.sqrt()) / 2.0,
            (-(sigma + 1.0) - disc.sqrt()) / 2.0,
        ];
        exact.sort_by(|p, q| q.total_cmp(p));
        for (e, x) in origin.eigenvalues.iter().zip(exact) {
            assert_eq!(e.im, 0.0);
            worst = worst.max((e.re - x).abs() / x.abs());
        }
        let expect = if r > 1.0 {
            LocalStability::Unstable
        } else {
            LocalStability::AsymptoticallyStable
        };
        assert_eq!(origin.stability, expect);
        assert!(origin.tf.is_none());
        // C± for r > 1.
        assert_eq!(lin.equilibria.len(), if r > 1.0 { 3 } else { 1 });
        for e in &lin.equilibria {
            assert!(e.residual <= 1e-13 * r.max(1.0), "{:?}", e.residual);
        }
    }
    eprintln!("Lorenz eigenvalues at the origin: max relative error {worst:.2e}");
    assert!(worst < 1e-14, "{worst:e}");
}

#[test]
fn lorenz_c_plus_minus_values() {
    let l = Lorenz::default();
    let eq = equilibria(&l, &[], &EquilibriumSearch::default()).unwrap();
    let s = (8.0 / 3.0 * 27.0f64).sqrt();
    assert!((eq[0].x[0] + s).abs() < 1e-15 && (eq[0].x[2] - 27.0).abs() < 1e-15);
    assert!((eq[2].x[1] - s).abs() < 1e-15);
    // At σ = 10, b = 8/3, r = 28 C± are unstable (r exceeds the Hopf value 24.74).
    let lin = linearize(&l, None, &EquilibriumSearch::default()).unwrap();
    assert_eq!(lin.equilibria[0].stability, LocalStability::Unstable);
    let stable = Lorenz::from_values(&[10.0, 20.0, 8.0 / 3.0]).unwrap();
    let lin = linearize(&stable, None, &EquilibriumSearch::default()).unwrap();
    assert_eq!(
        lin.equilibria[0].stability,
        LocalStability::AsymptoticallyStable
    );
}

// ---------------------------------------------------------------- AD vs central differences

fn central_difference(sys: &dyn DynSystem, x: &[f64], u: &[f64]) -> (DMatrix<f64>, DMatrix<f64>) {
    let n = x.len();
    let m = u.len();
    let eval = |x: &[f64], u: &[f64]| {
        let mut dx = vec![0.0; n];
        sys.eval_f(x, u, &mut dx);
        DVector::from_vec(dx)
    };
    let mut a = DMatrix::zeros(n, n);
    let mut b = DMatrix::zeros(n, m);
    for j in 0..n + m {
        let (mut xp, mut xm, mut up, mut um) = (x.to_vec(), x.to_vec(), u.to_vec(), u.to_vec());
        let v = if j < n { x[j] } else { u[j - n] };
        let h = 1e-5 * (1.0 + v.abs());
        if j < n {
            xp[j] += h;
            xm[j] -= h;
        } else {
            up[j - n] += h;
            um[j - n] -= h;
        }
        let col = (eval(&xp, &up) - eval(&xm, &um)) / (2.0 * h);
        if j < n {
            a.set_column(j, &col);
        } else {
            b.set_column(j - n, &col);
        }
    }
    (a, b)
}

fn check_ad(sys: &dyn DynSystem, x: &[f64], u: &[f64]) -> std::result::Result<(), TestCaseError> {
    let j = jacobians(sys, x, u).unwrap();
    let (a, b) = central_difference(sys, x, u);
    let scale = 1.0 + j.a.amax().max(j.b.amax());
    prop_assert!(
        max_abs_diff(&j.a, &a) <= 1e-6 * scale,
        "A: AD {} vs FD {}",
        j.a,
        a
    );
    prop_assert!(max_abs_diff(&j.b, &b) <= 1e-6 * scale, "B");
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn ad_jacobians_equal_central_differences(
        x in proptest::collection::vec(-3.0f64..3.0, 3),
        u in -2.0f64..2.0,
        p in proptest::collection::vec(0.2f64..3.0, 4),
    ) {
        let pend = Pendulum::new(p[0], p[1], p[2], 9.81).unwrap();
        check_ad(&pend, &x[..2], &[u])?;
        let mems = Mems::from_values(&[p[0], p[1], p[2], p[3], 3.0, 0.02, p[1], u]).unwrap();
        let xm = [x[0].abs() + 0.5, x[1], x[2]];
        check_ad(&mems, &xm, &[u])?;
        let lor = Lorenz::from_values(&[10.0 * p[0], 28.0 * p[1], p[2]]).unwrap();
        check_ad(&lor, &x, &[])?;
        check_ad(&VanDerPol, &x[..2], &[])?;
    }
}

// ---------------------------------------------------------------- MEMS

#[test]
fn mems_equilibria_solve_the_cubic() {
    for (eps, area, k, l0, v) in [
        (1.0, 1.0, 1.0, 3.0, 1.5),
        (2.0, 0.5, 3.0, 1.0, 0.4),
        (1.0, 1.0, 1.0, 3.0, 2.8),
        (0.5, 3.0, 2.0, 2.0, -1.0),
    ] {
        let m = Mems::from_values(&[eps, area, 1.0, k, l0, 0.02, 1.0, v]).unwrap();
        let v_pi = m.pull_in_voltage();
        assert!((v_pi - (8.0 * k * l0 * l0 * l0 / (27.0 * eps * area)).sqrt()).abs() < 1e-15);
        let eq = equilibria(&m, &[v], &EquilibriumSearch::default()).unwrap();
        assert_eq!(eq.len(), 3, "below pull-in ({v} < {v_pi}): {eq:?}");
        assert_eq!(eq.iter().filter(|e| e.physical).count(), 2);
        let rhs = eps * area * v * v / (2.0 * k);
        for e in &eq {
            let l = e.x[0];
            assert!((l * l * (l0 - l) - rhs).abs() <= 1e-14 * rhs.max(l0.powi(3)));
            assert!((e.x[2] - eps * area * v / l).abs() <= 1e-14 * e.x[2].abs());
            assert!(e.residual <= 1e-13, "{e:?}");
            assert_eq!(e.physical, l > 0.0 && l <= l0);
        }
        // Stability: larger physical gap stable, smaller unstable, negative gap unstable.
        let lin = linearize(&m, Some(&[v]), &EquilibriumSearch::default()).unwrap();
        let by_gap = |pred: &dyn Fn(f64) -> bool| {
            lin.equilibria
                .iter()
                .filter(|e| pred(e.x[0]))
                .map(|e| e.stability)
                .collect::<Vec<_>>()
        };
        let lpi = 2.0 * l0 / 3.0;
        assert_eq!(
            by_gap(&|l| l > lpi),
            vec![LocalStability::AsymptoticallyStable]
        );
        assert_eq!(
            by_gap(&|l| l > 0.0 && l < lpi),
            vec![LocalStability::Unstable]
        );
        // Above pull-in: one (non-physical) equilibrium.
        let above = m.with_voltage(1.01 * v_pi).unwrap();
        let eq = equilibria(&above, &[1.01 * v_pi], &EquilibriumSearch::default()).unwrap();
        assert_eq!(eq.len(), 1);
        assert!(!eq[0].physical && eq[0].x[0] < 0.0);
    }
}

#[test]
fn mems_voltage_to_gap_transfer_function() {
    // dc gain of the linearisation at the stable equilibrium = dl/dv along the equilibrium
    // curve = εA v / (k l (2 l0 − 3 l)), from differentiating the cubic.
    let m = Mems::default();
    let lin = linearize(&m, None, &EquilibriumSearch::default()).unwrap();
    let stable = lin
        .equilibria
        .iter()
        .find(|e| e.stability == LocalStability::AsymptoticallyStable)
        .unwrap();
    let l = stable.x[0];
    let tf = stable.tf.as_ref().unwrap();
    let expected = m.ea() * m.v / (m.k * l * (2.0 * m.l0 - 3.0 * l));
    let dc = tf.dc_gain.unwrap();
    eprintln!("MEMS dl/dv: tf dc gain {dc} vs cubic {expected}");
    assert!((dc - expected).abs() <= 1e-12 * expected.abs());
    assert_eq!(tf.den.len(), 4);
    assert_eq!(tf.poles.iter().map(|r| r.multiplicity).sum::<usize>(), 3);
    assert!(tf.modes.iter().all(|md| md.zeta.unwrap() > 0.0));
}

#[test]
fn pull_in_voltage_found_matches_the_formula() {
    // (eps, A, k, l0, tolerance on v). The micro-scale device (εA = 8.85e-18, R = 1) is stiff:
    // the electrical pole −l/(RεA) ≈ −1.5e11 against mechanical ones ~0.1. Near the fold the
    // slow eigenvalues are then computed (balanced QR) with an absolute error ~0.1, so the
    // stability-based bisection stops ~6e-6 below v_pi — balancing is harmful for such
    // matrices (Watkins, ETNA 23, 2006); the formula-free value is still good to 1e-5.
    let mut worst: f64 = 0.0;
    for (eps, area, k, l0, tol) in [
        (1.0, 1.0, 1.0, 3.0, 1e-12),
        (2.0, 3.0, 0.5, 1.0, 1e-12),
        (8.85e-12, 1e-6, 2.0, 2e-6, 1e-5),
    ] {
        let m = Mems::from_values(&[eps, area, 1.0, k, l0, 0.02, 1.0, 0.0]).unwrap();
        let (v, l) = find_pull_in(&m).unwrap();
        let rel = (v - m.pull_in_voltage()).abs() / m.pull_in_voltage();
        let gap_rel = (l - m.pull_in_gap()).abs() / m.pull_in_gap();
        eprintln!(
            "  l0 = {l0:e}: v_pi found {v:.16e} formula {:.16e} (rel {rel:.1e}); gap rel error {gap_rel:.1e}",
            m.pull_in_voltage(),
        );
        assert!(rel < tol, "{rel:e}");
        assert!(
            gap_rel < 1e-2 * tol.sqrt(),
            "gap {l} vs {}",
            m.pull_in_gap()
        );
        if tol < 1e-10 {
            worst = worst.max(rel);
        }
    }
    eprintln!("pull-in voltage found vs formula (well-scaled): max relative error {worst:.2e}");
}

#[test]
fn pull_in_diagram_branches() {
    let m = Mems::default();
    let d = mems_pullin(&m, 4.0, 81).unwrap();
    assert!((d.pull_in_voltage - 8f64.sqrt()).abs() < 1e-15);
    assert!((d.pull_in_gap - 2.0).abs() < 1e-15);
    // Stable branch starts at (0, l0) and decreases to the pull-in point; unstable increases.
    assert_eq!(d.stable[0], [0.0, 3.0]);
    for w in d.stable.windows(2) {
        assert!(w[1][0] > w[0][0] && w[1][1] < w[0][1]);
    }
    for w in d.unstable.windows(2) {
        assert!(w[1][0] > w[0][0] && w[1][1] > w[0][1]);
    }
    assert_eq!(
        *d.stable.last().unwrap(),
        [d.pull_in_voltage, d.pull_in_gap]
    );
    assert!(d.stable.iter().all(|p| p[0] <= d.pull_in_voltage));
}

#[test]
fn mems_zero_voltage_has_charged_touching_states() {
    let m = Mems::default().with_voltage(0.0).unwrap();
    let eq = equilibria(&m, &[0.0], &EquilibriumSearch::default()).unwrap();
    // l = 0 with q = ±√(2εA k l0), and the rest state l = l0, q = 0.
    assert_eq!(eq.len(), 3);
    assert!(eq.iter().all(|e| e.residual < 1e-14));
    assert_eq!(eq.iter().filter(|e| e.physical).count(), 1);
}

#[test]
fn mems_simulation_below_and_above_pull_in() {
    let t = sample_times(60.0, 601).unwrap();
    let m = Mems::default();
    let x0 = [m.l0, 0.0, 0.0];
    let below = simulate(
        &m,
        &x0,
        &InputSignal::constant(vec![1.5]),
        &t,
        &Rk45Options::default(),
    )
    .unwrap();
    let eq = equilibria(&m, &[1.5], &EquilibriumSearch::default()).unwrap();
    let stable_l = eq.iter().map(|e| e.x[0]).fold(f64::MIN, f64::max);
    let end = below.states.last().unwrap();
    assert!((end[0] - stable_l).abs() < 0.05, "{} vs {stable_l}", end[0]);
    assert!(below.state(0).iter().all(|l| *l > 0.0));
    assert!(below.stop.is_none());
    // Above pull-in the gap closes: the simulation stops at contact, l = 0.
    let above = simulate(
        &m,
        &x0,
        &InputSignal::constant(vec![3.2]),
        &t,
        &Rk45Options::default(),
    )
    .unwrap();
    let stop = above.stop.as_ref().unwrap();
    let l_end = above.states.last().unwrap()[0];
    eprintln!("MEMS at v = 3.2: plates touch at t = {}", stop.t);
    assert!((0.0..1e-9).contains(&l_end), "{l_end}");
    assert_eq!(*above.t.last().unwrap(), stop.t);
    assert!(above.t.windows(2).all(|w| w[0] < w[1]));
}

// ---------------------------------------------------------------- linear plants

#[test]
fn linear_plants_linearise_back_to_themselves() {
    for spec in plant_specs() {
        let model = LinearModel::from_plant(spec.name, &[]).unwrap();
        let sys = build_model(spec.name, &[]).unwrap();
        let n = sys.nx();
        let x: Vec<f64> = (0..n).map(|i| 0.3 * i as f64 - 0.7).collect();
        let j = jacobians(sys.as_ref(), &x, &[1.3]).unwrap();
        let ss = model.ss();
        assert_eq!(j.a, ss.a, "{}", spec.name);
        assert_eq!(j.b, ss.b, "{}", spec.name);
        assert_eq!(j.c, ss.c, "{}", spec.name);
        assert_eq!(j.d, ss.d, "{}", spec.name);
        // And the transfer function of the linearisation is the plant's.
        let lin = linearize(sys.as_ref(), None, &EquilibriumSearch::default()).unwrap();
        assert_eq!(lin.equilibria.len(), 1);
        let g = &lin.equilibria[0].tf.as_ref().unwrap().g;
        let plant = spec.build(&spec.defaults()).unwrap();
        for w in [0.0, 0.1, 1.0, 3.0, 30.0] {
            let s = Complex64::new(0.0, w);
            let (p, q) = (plant.eval(s), g.eval(s));
            assert!(
                (p - q).norm() <= 1e-12 * p.norm(),
                "{} at {w}: {p} vs {q}",
                spec.name
            );
        }
        assert_eq!(
            lin.equilibria[0].stability,
            LocalStability::AsymptoticallyStable
        );
    }
}

#[test]
fn linear_simulation_matches_the_matrix_exponential() {
    // Spring–mass–damper with light damping, free response from x0 = [1, 0].
    let sys = build_model("spring-mass-damper", &[("C".into(), 0.1)]).unwrap();
    let model = LinearModel::from_plant("spring-mass-damper", &[("C".into(), 0.1)]).unwrap();
    let t = sample_times(30.0, 301).unwrap();
    let x0 = [1.0, -0.5];
    let sim = simulate(
        sys.as_ref(),
        &x0,
        &InputSignal::constant(vec![0.0]),
        &t,
        &tight(),
    )
    .unwrap();
    let a = &model.ss().a;
    let mut worst: f64 = 0.0;
    for (ti, x) in t.iter().zip(&sim.states) {
        let exact = expm(&(a * *ti)).unwrap() * DVector::from_column_slice(&x0);
        worst = worst.max((x[0] - exact[0]).abs().max((x[1] - exact[1]).abs()));
    }
    eprintln!(
        "simulate vs exp(At)x0: max error {worst:.2e} ({:?})",
        sim.stats
    );
    assert!(worst < 1e-9, "{worst:e}");
    assert_eq!(sim.state_names, vec!["y", "y'"]);
}

#[test]
fn step_input_restarts_at_the_jump() {
    // Tank A h' + r h = q: step of q from 0 to 1 at t = 2 → h = (1 − e^{−r(t−2)/A})/r.
    let sys = build_model("tank", &[]).unwrap();
    let (area, r) = (2.0, 0.5);
    let t = sample_times(20.0, 201).unwrap();
    let input = InputSignal::step(2.0, vec![0.0], vec![1.0]);
    let sim = simulate(sys.as_ref(), &[0.0], &input, &t, &tight()).unwrap();
    for (ti, y) in t.iter().zip(&sim.outputs) {
        let exact = if *ti < 2.0 {
            0.0
        } else {
            (1.0 - (-r * (ti - 2.0) / area).exp()) / r
        };
        assert!(
            (y[0] - exact).abs() < 1e-11,
            "t = {ti}: {} vs {exact}",
            y[0]
        );
    }
    // No rejected steps hunting for the discontinuity.
    assert!(sim.stats.rejections <= 2, "{:?}", sim.stats);
}

#[test]
fn shaped_inputs_match_the_closed_form_of_the_linear_analysis() {
    // One input enum: the tank A h' + r h = q (A = 2, r = 0.5) simulated under q(t) =
    // 0.3 + s(t − 1)·(1.3 − 0.3) for s = sin:2, ramp and exp:-0.7, against the exact closed
    // form of 1/(2 s + 0.5) for the same analysis::Input, shifted by 1 s, plus the response to
    // the constant 0.3 from h(0) = 0.
    use ltikit::analysis::Input;
    let sys = build_model("tank", &[]).unwrap();
    let g = TransferFunction::from_descending(&[1.0], &[2.0, 0.5]).unwrap();
    let t = sample_times(12.0, 121).unwrap();
    for shape in [
        Input::Sin(2.0),
        Input::Ramp,
        Input::Exp(-0.7),
        Input::Cos(3.0),
    ] {
        let u = InputSignal::shaped(vec![0.3], vec![1.3], shape, 1.0);
        let sim = simulate(sys.as_ref(), &[0.0], &u, &t, &tight()).unwrap();
        let shifted: Vec<f64> = t.iter().map(|x| (x - 1.0).max(0.0)).collect();
        let forced = g.response(&shape, &[], &shifted).unwrap();
        let base = g.response(&Input::Step, &[], &t).unwrap();
        let mut worst: f64 = 0.0;
        for (k, ti) in t.iter().enumerate() {
            let exact =
                0.3 * base.samples.y[k] + if *ti >= 1.0 { forced.samples.y[k] } else { 0.0 };
            worst = worst.max((sim.outputs[k][0] - exact).abs());
        }
        assert!(worst < 1e-10, "{shape}: worst {worst:e}");
    }
    // An impulse cannot be integrated.
    let imp = InputSignal::shaped(vec![0.0], vec![1.0], Input::Impulse, 0.0);
    assert!(simulate(sys.as_ref(), &[0.0], &imp, &t, &tight()).is_err());
}

// ---------------------------------------------------------------- pendulum period, van der Pol

#[test]
fn pendulum_period_matches_the_elliptic_integral() {
    let p = Pendulum::default();
    // (the demo's table's amplitudes among them)
    let amps = [0.1, 0.5, 1.0, 1.5, 2.0, 2.5, 2.8, 3.0, 3.1];
    let rows = pendulum_periods(&p, &amps, &tight()).unwrap();
    let mut worst: f64 = 0.0;
    for r in &rows {
        worst = worst.max(r.relative_error);
        assert!(r.exact > r.small_angle);
    }
    eprintln!("pendulum period: simulated vs 4K(k)/ω, max relative error {worst:.2e}");
    for r in &rows {
        eprintln!(
            "  θ0 = {:.2}: exact {:.12} simulated {:.12} small-angle {:.6}",
            r.amplitude, r.exact, r.simulated, r.small_angle
        );
    }
    assert!(worst < 1e-9, "{worst:e}");
    // Seed's small-energy expansion T ≈ (2π/ω)(1 + k²/4) at θ0 = 0.1.
    let k = (0.05f64).sin();
    let approx = rows[0].small_angle * (1.0 + k * k / 4.0);
    assert!((rows[0].exact - approx).abs() / approx < 1e-5);
}

#[test]
fn van_der_pol_follows_the_polar_closed_form() {
    let t = sample_times(15.0, 151).unwrap();
    let mut worst: f64 = 0.0;
    // (the demo's phase portrait's starts among them)
    for (x1, x2) in [
        (0.001, 0.0),
        (2.0, 0.0),
        (0.3, -0.4),
        (-1.5, 1.5),
        (0.0, -1.8),
        (0.3, 0.2),
    ] {
        let sim = simulate(&VanDerPol, &[x1, x2], &InputSignal::none(), &t, &tight()).unwrap();
        let s0: f64 = x1 * x1 + x2 * x2;
        let phi0 = f64::atan2(x2, x1);
        for (ti, x) in t.iter().zip(&sim.states) {
            let rho = (1.0 / (1.0 + (1.0 / s0 - 1.0) * (-2.0 * ti).exp())).sqrt();
            let (ex, ey) = (rho * (phi0 + ti).cos(), rho * (phi0 + ti).sin());
            worst = worst.max((x[0] - ex).abs().max((x[1] - ey).abs()));
        }
        // Converging to the unit circle: ρ(15) − 1 ≈ −(1/ρ₀² − 1)e^{−30}/2 (< 5e-8).
        let end = sim.states.last().unwrap();
        assert!((end[0].hypot(end[1]) - 1.0).abs() < 1e-7);
    }
    eprintln!("van der Pol vs polar closed form: max error {worst:.2e}");
    assert!(worst < 1e-9, "{worst:e}");
    let lin = linearize(&VanDerPol, None, &EquilibriumSearch::default()).unwrap();
    assert_eq!(lin.equilibria.len(), 1);
    let e = &lin.equilibria[0];
    assert_eq!(e.stability, LocalStability::Unstable);
    assert!(e.hyperbolic);
    assert_eq!(
        e.eigenvalues,
        vec![Complex64::new(1.0, 1.0), Complex64::new(1.0, -1.0)]
    );
}

// ---------------------------------------------------------------- stability classes

#[test]
fn non_hyperbolic_equilibria_are_undetermined() {
    // Undamped pendulum at θ = 0: ±jω.
    let p = Pendulum::new(1.0, 1.0, 0.0, 9.81).unwrap();
    let lin = linearize(&p, None, &EquilibriumSearch::default()).unwrap();
    assert!(!lin.equilibria[0].hyperbolic);
    assert_eq!(lin.equilibria[0].stability, LocalStability::Undetermined);
    assert!(lin.equilibria[0].stability_reason.contains("cannot"));
    assert_eq!(lin.equilibria[1].stability, LocalStability::Unstable);
    // Lorenz at r = 1: eigenvalue 0 at the origin (pitchfork).
    let l = Lorenz::from_values(&[10.0, 1.0, 8.0 / 3.0]).unwrap();
    let lin = linearize(&l, None, &EquilibriumSearch::default()).unwrap();
    assert_eq!(lin.equilibria.len(), 1);
    assert_eq!(lin.equilibria[0].stability, LocalStability::Undetermined);
    // MEMS exactly at pull-in: the two physical equilibria merge into a saddle-node.
    let m = Mems::default();
    let at = m.with_voltage(m.pull_in_voltage()).unwrap();
    let lin = linearize(&at, None, &EquilibriumSearch::default()).unwrap();
    let phys: Vec<_> = lin.equilibria.iter().filter(|e| e.physical).collect();
    assert_eq!(phys.len(), 1, "{:?}", lin.equilibria);
    assert!((phys[0].x[0] - 2.0).abs() < 1e-7);
    assert_eq!(phys[0].stability, LocalStability::Undetermined);
}

#[test]
fn pendulum_with_constant_torque() {
    let p = Pendulum::default();
    let tau = 2.0;
    let eq = equilibria(&p, &[tau], &EquilibriumSearch::default()).unwrap();
    assert_eq!(eq.len(), 2);
    for e in &eq {
        assert!((e.x[0].sin() - 2.0 * tau / (1.0 * 9.81 * 1.0)).abs() < 1e-15);
        assert!(e.residual < 1e-14);
    }
    // Beyond the largest static torque M g L/2 there is no equilibrium.
    assert!(
        equilibria(&p, &[5.0], &EquilibriumSearch::default())
            .unwrap()
            .is_empty()
    );
}

// ---------------------------------------------------------------- user models, Newton

struct DoubleWell;

impl SystemInfo for DoubleWell {
    fn nx(&self) -> usize {
        2
    }
    fn nu(&self) -> usize {
        1
    }
    fn ny(&self) -> usize {
        1
    }
}

impl NonlinearSystem for DoubleWell {
    // ẍ = x − x³ − 0.3 ẋ + u: equilibria x = 0, ±1 for u = 0.
    fn f<D: Scalar>(&self, x: &[D], u: &[D], dx: &mut [D]) {
        dx[0] = x[1];
        dx[1] = x[0] - x[0].powi(3) - x[1] * 0.3 + u[0];
    }
    fn h<D: Scalar>(&self, x: &[D], _u: &[D], y: &mut [D]) {
        y[0] = x[0];
    }
}

#[test]
fn user_model_gets_newton_equilibria_and_linearisation() {
    let lin = linearize(&DoubleWell, None, &EquilibriumSearch::default()).unwrap();
    let xs: Vec<f64> = lin.equilibria.iter().map(|e| e.x[0]).collect();
    assert_eq!(xs.len(), 3, "{xs:?}");
    for (x, e) in xs.iter().zip([-1.0, 0.0, 1.0]) {
        assert!((x - e).abs() < 1e-14);
    }
    let st: Vec<_> = lin.equilibria.iter().map(|e| e.stability).collect();
    assert_eq!(
        st,
        [
            LocalStability::AsymptoticallyStable,
            LocalStability::Unstable,
            LocalStability::AsymptoticallyStable
        ]
    );
    assert!(
        lin.equilibria
            .iter()
            .all(|e| e.method == EquilibriumMethod::Newton)
    );
    assert!(lin.equilibria.iter().all(|e| e.residual < 1e-14));
    // 1/(s² + 0.3 s + 2) at x = ±1.
    let g = &lin.equilibria[0].tf.as_ref().unwrap().g;
    let want = TransferFunction::from_descending(&[1.0], &[1.0, 0.3, 2.0]).unwrap();
    let s = Complex64::new(0.0, 1.0);
    assert!((g.eval(s) - want.eval(s)).norm() < 1e-14);
}

// ---------------------------------------------------------------- JSON contract

#[test]
fn linearize_json_contract() {
    let lin = linearize(&Pendulum::default(), None, &EquilibriumSearch::default()).unwrap();
    let v = serde_json::to_value(&lin).unwrap();
    assert_eq!(v["model"], "pendulum");
    assert_eq!(v["params"]["L"], 1.0);
    assert_eq!(v["params"]["g"], 9.81);
    let e = &v["equilibria"][0];
    for key in [
        "x",
        "u",
        "A",
        "B",
        "C",
        "D",
        "eigenvalues",
        "hyperbolic",
        "stability",
        "physical",
        "tf",
    ] {
        assert!(e.get(key).is_some(), "missing {key}");
    }
    assert_eq!(e["A"][0], serde_json::json!([0.0, 1.0]));
    assert_eq!(e["B"], serde_json::json!([[0.0], [3.0]]));
    assert_eq!(e["stability"], "asymptotically_stable");
    assert_eq!(v["equilibria"][1]["stability"], "unstable");
    assert!(e["eigenvalues"][0].as_array().unwrap().len() == 2);
    assert!(e["tf"]["num"].is_array() && e["tf"]["den"].is_array());
    let lor = serde_json::to_value(
        linearize(&Lorenz::default(), None, &EquilibriumSearch::default()).unwrap(),
    )
    .unwrap();
    assert!(lor["equilibria"][0]["tf"].is_null());
    assert_eq!(lor["equilibria"][0]["B"], serde_json::json!([[], [], []]));
}

// ---------------------------------------------------------------- registry and bad input

#[test]
fn registry_defaults_follow_design_section_4() {
    let get = |m: &str| {
        let s = build_model(m, &[]).unwrap();
        s.params()
    };
    let p = get("pendulum");
    assert_eq!(
        p,
        vec![
            ("M".to_string(), 1.0),
            ("L".to_string(), 1.0),
            ("C".to_string(), 0.5),
            ("g".to_string(), 9.81)
        ]
    );
    let m: Vec<f64> = get("mems").into_iter().map(|(_, v)| v).collect();
    assert_eq!(m, vec![1.0, 1.0, 1.0, 1.0, 3.0, 0.02, 1.0, 1.5]);
    let l: Vec<f64> = get("lorenz").into_iter().map(|(_, v)| v).collect();
    assert_eq!(l, vec![10.0, 28.0, 8.0 / 3.0]);
    assert!(get("vanderpol").is_empty());
    for name in model_names() {
        let info = model_info(name).unwrap();
        let sys = build_model(name, &[]).unwrap();
        assert_eq!(info.params.len(), sys.params().len(), "{name}");
        assert_eq!(sys.model_name(), name);
    }
}

#[test]
fn bad_input_gives_errors() {
    assert!(matches!(
        build_model("pendulm", &[]),
        Err(LtiError::UnknownModel { .. })
    ));
    assert!(matches!(
        build_model("lorenz", &[("rho".into(), 1.0)]),
        Err(LtiError::UnknownParameter { .. })
    ));
    assert!(matches!(
        build_model("vanderpol", &[("mu".into(), 1.0)]),
        Err(LtiError::UnknownParameter { .. })
    ));
    for (model, p, v) in [
        ("pendulum", "L", 0.0),
        ("pendulum", "M", -1.0),
        ("pendulum", "C", -0.1),
        ("mems", "eps", 0.0),
        ("mems", "R", -2.0),
        ("mems", "m", 0.0),
        ("mems", "v", f64::NAN),
        ("lorenz", "b", 0.0),
        ("spring-mass-damper", "M", 0.0),
    ] {
        let r = build_model(model, &[(p.into(), v)]);
        assert!(
            matches!(
                r,
                Err(LtiError::InvalidParameter { .. } | LtiError::NonFinite { .. })
            ),
            "{model} {p}={v}"
        );
    }
    let p = Pendulum::default();
    let o = Rk45Options::default();
    let c = InputSignal::constant(vec![0.0]);
    for t_end in [0.0, -1.0] {
        assert!(matches!(
            simulate(&p, &[0.1, 0.0], &c, &[0.0, t_end], &o),
            Err(LtiError::InvalidTime { .. })
        ));
        assert!(sample_times(t_end, 10).is_err());
    }
    assert!(simulate(&p, &[0.1], &c, &[1.0], &o).is_err());
    assert!(simulate(&p, &[0.1, 0.0], &InputSignal::none(), &[1.0], &o).is_err());
    assert!(simulate(&p, &[f64::INFINITY, 0.0], &c, &[1.0], &o).is_err());
    assert!(simulate(&p, &[0.1, 0.0], &c, &[], &o).is_err());
    assert!(jacobians(&p, &[0.0, f64::NAN], &[0.0]).is_err());
    assert!(pendulum_period_exact(1.0, PI).is_err());
    assert!(pendulum_period_exact(1.0, 0.0).is_err());
    assert!(mems_pullin(&Mems::default(), -1.0, 10).is_err());
}

struct Blowup;

impl SystemInfo for Blowup {
    fn nx(&self) -> usize {
        1
    }
    fn nu(&self) -> usize {
        0
    }
    fn ny(&self) -> usize {
        1
    }
}

impl NonlinearSystem for Blowup {
    fn f<D: Scalar>(&self, x: &[D], _u: &[D], dx: &mut [D]) {
        dx[0] = x[0] * x[0];
    }
    fn h<D: Scalar>(&self, x: &[D], _u: &[D], y: &mut [D]) {
        y[0] = x[0];
    }
}

#[test]
fn simulation_blow_up_and_step_limit() {
    let t = sample_times(2.0, 21).unwrap();
    match simulate(
        &Blowup,
        &[1.0],
        &InputSignal::none(),
        &t,
        &Rk45Options::default(),
    ) {
        Err(LtiError::Diverged { t, norm }) => {
            assert!(
                (t - 1.0).abs() < 1e-6 && norm > 1e6,
                "t = {t}, |x| = {norm:e}"
            )
        }
        other => panic!("expected Diverged, got {other:?}"),
    }
    let t = sample_times(100.0, 11).unwrap();
    let opts = Rk45Options {
        max_steps: 50,
        ..Default::default()
    };
    let r = simulate(
        &Lorenz::default(),
        &[1.0, 0.0, 0.0],
        &InputSignal::none(),
        &t,
        &opts,
    );
    assert!(
        matches!(r, Err(LtiError::StepLimit { steps: 50, .. })),
        "{r:?}"
    );
}

// ---------------------------------------------------------------- picture data

#[test]
fn lorenz_trajectories_separate() {
    let t = sample_times(40.0, 4001).unwrap();
    let d = lorenz_divergence(&Lorenz::default(), 1e-3, &t, &Rk45Options::default()).unwrap();
    assert!((d.distance[0] - 1e-3).abs() < 1e-15);
    let ts = d.separation_time(1.0).unwrap();
    eprintln!("Lorenz: trajectories 0.001 apart separate by 1 at t = {ts}");
    // The attractor is bounded (|x| < 60) while the two copies end up unrelated.
    assert!(d.a.states.iter().all(|x| x.iter().all(|v| v.abs() < 60.0)));
    assert!(d.distance.iter().copied().fold(0.0, f64::max) > 10.0);
}

#[test]
fn phase_portrait_of_the_undamped_pendulum_conserves_energy() {
    let p = Pendulum::new(1.0, 1.0, 0.0, 9.81).unwrap();
    let w = p.omega();
    let starts: Vec<Vec<f64>> = [0.5, 1.5, 3.0]
        .iter()
        .map(|&a| vec![a, 0.0])
        .chain([vec![-PI, 2.5 * w]])
        .collect();
    let t = sample_times(10.0, 501).unwrap();
    let tr = trajectories(&p, &starts, &InputSignal::constant(vec![0.0]), &t, &tight()).unwrap();
    for sim in &tr {
        let e0 = pendulum_energy(w, sim.states[0][0], sim.states[0][1]);
        for x in &sim.states {
            assert!((pendulum_energy(w, x[0], x[1]) - e0).abs() < 1e-9 * e0);
        }
    }
    // The rotating start (E > 2ω²) keeps θ̇ of one sign; the others oscillate.
    assert!(tr[3].state(1).iter().all(|v| *v > 0.0));
    let [up, _] = pendulum_separatrices(&p, -PI, PI, 3).unwrap();
    assert!((up[1][1] - 2.0 * w).abs() < 1e-15);
}
