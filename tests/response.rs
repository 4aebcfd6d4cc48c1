//! Closed-form and exact time responses against the seed's analytic expressions.
//!
//! Run with `--nocapture` to see the worst error per case.

use ltikit::analysis::{ClosedFormTerm, Input};
use ltikit::lti::build_plant;

mod common;
use common::{grid, tf};

/// ÿ + 2ζẏ + y = 0 (ωₙ = 1) from y(0) = y0, ẏ(0) = v0.
/// ζ = 0: seed eq. 3.34; 0 < ζ < 1: eq. 3.33 (whose "+φ" is a typo: the phase is −φ,
/// φ = atan(ζ/√(1−ζ²)), r = 1/√(1−ζ²)); ζ = 1: eq. 3.35; ζ > 1: the overdamped form of
/// §3.2.2.1 with the poles λ₁,₂ = −ζ ± √(ζ²−1).
fn ic_analytic(zeta: f64, y0: f64, v0: f64, t: f64) -> f64 {
    #[allow(clippy::float_cmp)]
    if zeta == 0.0 {
        v0 * t.sin() + y0 * t.cos()
    } else if zeta < 1.0 {
        let wd = (1.0 - zeta * zeta).sqrt();
        let r = 1.0 / wd;
        let phi = (zeta / wd).atan();
        let e = (-zeta * t).exp();
        v0 / wd * e * (wd * t - std::f64::consts::FRAC_PI_2).cos()
            + y0 * r * e * (wd * t - phi).cos()
    } else if zeta == 1.0 {
        (-t).exp() * (v0 * t + y0 * (1.0 + t))
    } else {
        let b = (zeta * zeta - 1.0).sqrt();
        let (l1, l2) = (-zeta + b, -zeta - b);
        ((v0 - l2 * y0) * (l1 * t).exp() - (v0 - l1 * y0) * (l2 * t).exp()) / (l1 - l2)
    }
}

/// Unit-step response of 1/(s² + 2ζs + 1) from rest: 1 − (free response from y = 1, ẏ = 0)
/// (seed eqs. 3.41–3.48 for the forced part).
fn step_analytic(zeta: f64, t: f64) -> f64 {
    1.0 - ic_analytic(zeta, 1.0, 0.0, t)
}

#[test]
fn seed_damped_second_order_responses() {
    let t = grid(30.0, 600);
    let (y0, v0) = (0.8, -0.6);
    for zeta in [0.0, 0.1, 0.5, 1.0, 1.5, 2.0] {
        let g = tf(&[1.0], &[1.0, 2.0 * zeta, 1.0]);
        for (what, input, ics) in [
            ("initial-condition", Input::None, vec![y0, v0]),
            ("step", Input::Step, vec![]),
        ] {
            let want: Vec<f64> = t
                .iter()
                .map(|&x| {
                    if ics.is_empty() {
                        step_analytic(zeta, x)
                    } else {
                        ic_analytic(zeta, y0, v0, x)
                    }
                })
                .collect();
            let r = g.inverse_laplace(&input, &ics).unwrap();
            let closed = t
                .iter()
                .zip(&want)
                .map(|(&x, w)| (r.closed_form.eval(x) - w).abs())
                .fold(0.0, f64::max);
            let sim = g.time_response(&input, &ics, &t).unwrap();
            let exact = sim
                .y
                .iter()
                .zip(&want)
                .map(|(y, w)| (y - w).abs())
                .fold(0.0, f64::max);
            println!(
                "ζ = {zeta}: {what}: closed form {closed:.1e}, simulation {exact:.1e}   {}",
                r.closed_form
            );
            assert!(closed < 1e-10, "ζ = {zeta} {what}: closed form {closed:e}");
            assert!(exact < 1e-10, "ζ = {zeta} {what}: simulation {exact:e}");
        }
    }
}

#[test]
fn critical_damping_has_the_polynomial_times_exponential_form() {
    let g = tf(&[1.0], &[1.0, 2.0, 1.0]);
    let r = g.inverse_laplace(&Input::None, &[1.0, 0.5]).unwrap();
    // e^(−t)(0.5 t + 1 + t) = (1 + 1.5 t) e^(−t): one group, two coefficients.
    match r.closed_form.terms() {
        [ClosedFormTerm::Real { pole, coefficients }] => {
            assert_eq!(*pole, -1.0);
            assert_eq!(coefficients.len(), 2);
            assert!((coefficients[0] - 1.0).abs() < 1e-15);
            assert!((coefficients[1] - 1.5).abs() < 1e-15);
        }
        other => panic!("not the (c1 + c2 t) e^(-t) form: {other:?}"),
    }
    assert_eq!(r.closed_form.to_string(), "y(t) = (1 + 1.5 t) e^(-t)");
    let s = g.inverse_laplace(&Input::Step, &[]).unwrap();
    assert_eq!(s.closed_form.to_string(), "y(t) = 1 - (1 + t) e^(-t)");
    assert_eq!(s.steady_state.to_string(), "y(t) = 1");
    assert_eq!(s.transient.expression(), "-(1 + t) e^(-t)");
}

#[test]
fn underdamped_step_prints_in_real_form() {
    let g = tf(&[1.0], &[1.0, 1.0, 1.0]);
    let r = g.inverse_laplace(&Input::Step, &[]).unwrap();
    assert_eq!(
        r.closed_form.to_string(),
        "y(t) = 1 - 1.1547 e^(-0.5 t) cos(0.866025 t - 0.523599)"
    );
    // Undamped: the pair ±j with σ = 0 prints without an exponential.
    let g = tf(&[1.0], &[1.0, 0.0, 1.0]);
    let r = g.inverse_laplace(&Input::Step, &[]).unwrap();
    assert_eq!(r.closed_form.to_string(), "y(t) = 1 - cos(t)");
}

#[test]
fn near_coincident_poles() {
    // ζ = 1 ± 1e-9: poles 9e-5 apart, residues ~1e4 that cancel.
    let t = grid(40.0, 800);
    for zeta in [1.0 + 1e-9, 1.0 - 1e-9, 1.0 + 1e-13, 1.0 - 1e-13] {
        let g = tf(&[1.0], &[1.0, 2.0 * zeta, 1.0]);
        // Well-conditioned analytic forms: cosh/sinh(βt)/β (ζ > 1), cos/sin(ωt)/ω (ζ < 1),
        // with β² = (ζ − 1)(ζ + 1) formed without cancellation.
        let free = |y0: f64, v0: f64, x: f64| {
            let e = (-zeta * x).exp();
            let q = (zeta - 1.0) * (zeta + 1.0);
            let (c, s_over) = if q > 0.0 {
                let b = q.sqrt();
                ((b * x).cosh(), (b * x).sinh() / b)
            } else {
                let w = (-q).sqrt();
                ((w * x).cos(), (w * x).sin() / w)
            };
            e * (y0 * c + (v0 + zeta * y0) * s_over)
        };
        for (what, input, ics) in [
            ("step", Input::Step, vec![]),
            ("initial-condition", Input::None, vec![0.7, -1.3]),
        ] {
            let s = g.response(&input, &ics, &t).unwrap().samples;
            let want: Vec<f64> = t
                .iter()
                .map(|&x| {
                    if ics.is_empty() {
                        1.0 - free(1.0, 0.0, x)
                    } else {
                        free(ics[0], ics[1], x)
                    }
                })
                .collect();
            let scale = want.iter().map(|w| w.abs()).fold(0.0, f64::max);
            let err =
                s.y.iter()
                    .zip(&want)
                    .map(|(y, w)| (y - w).abs())
                    .fold(0.0, f64::max);
            println!(
                "ζ = 1 {:+.0e}: {what}: simulation {:.1e} of max|y|, closed form agrees to {:.1e}",
                zeta - 1.0,
                err / scale,
                s.closed_form_error / scale
            );
            assert!(err <= 1e-8 * scale, "ζ − 1 = {:e}: {err:e}", zeta - 1.0);
            assert!(s.closed_form_error <= 1e-6 * scale);
        }
    }
}

#[test]
fn first_order_tank() {
    // Seed eqs. 3.5–3.18: A ḣ + r h = qᵢ, p₁ = r/A, u = qᵢ/A.
    let (a, r) = (2.0, 0.5);
    let (g, _) = build_plant("tank", &[("A".into(), a), ("r".into(), r)]).unwrap();
    let p1 = r / a;
    let h0 = 1.2;
    let t = grid(20.0, 200);

    // Initial-condition response alone: h(0) e^(−p₁t) (eq. 3.13).
    let ic = g.inverse_laplace(&Input::None, &[h0]).unwrap();
    for &x in &t {
        assert!((ic.closed_form.eval(x) - h0 * (-p1 * x).exp()).abs() < 1e-15);
    }

    // Input qᵢ = e^(−3t): U(s) = (1/A)/(s + 3) for eq. 3.6; eq. 3.16:
    // α₁ = (1/A)/(3 − p₁) (transient, eq. 3.17), r₁ = (1/A)/(p₁ − 3) (steady state, eq. 3.18).
    let resp = g.inverse_laplace(&Input::Exp(-3.0), &[h0]).unwrap();
    let alpha1 = (1.0 / a) / (3.0 - p1);
    let r1 = (1.0 / a) / (p1 - 3.0);
    match resp.transient.terms() {
        [ClosedFormTerm::Real { pole, coefficients }] => {
            assert!((pole + p1).abs() < 1e-15);
            assert!((coefficients[0] - (h0 + alpha1)).abs() < 1e-15);
        }
        other => panic!("{other:?}"),
    }
    match resp.steady_state.terms() {
        [ClosedFormTerm::Real { pole, coefficients }] => {
            assert_eq!(*pole, -3.0);
            assert!((coefficients[0] - r1).abs() < 1e-15);
        }
        other => panic!("{other:?}"),
    }
    let sim = g.time_response(&Input::Exp(-3.0), &[h0], &t).unwrap();
    for (x, y) in t.iter().zip(&sim.y) {
        let want = h0 * (-p1 * x).exp() + alpha1 * (-p1 * x).exp() + r1 * (-3.0 * x).exp();
        assert!((resp.closed_form.eval(*x) - want).abs() < 1e-15);
        assert!((y - want).abs() < 1e-14, "t = {x}");
    }

    // Step inflow: h → 1/r.
    let sim = g.time_response(&Input::Step, &[h0], &t).unwrap();
    assert!((sim.final_value.unwrap() - 1.0 / r).abs() < 1e-15);
    for (x, y) in t.iter().zip(&sim.y) {
        let want = h0 * (-p1 * x).exp() + (1.0 / r) * (1.0 - (-p1 * x).exp());
        assert!((y - want).abs() < 1e-14);
    }
}

#[test]
fn every_input_into_a_first_order_lag() {
    // G = 1/(s + 1); analytic responses by hand.
    let g = tf(&[1.0], &[1.0, 1.0]);
    let t = grid(15.0, 300);
    let w: f64 = 2.0;
    let a: f64 = -0.4;
    type Case = (Input, Box<dyn Fn(f64) -> f64>, Box<dyn Fn(f64) -> f64>);
    let cases: Vec<Case> = vec![
        (
            Input::Impulse,
            Box::new(|x: f64| (-x).exp()),
            Box::new(|_| 0.0),
        ),
        (
            Input::Step,
            Box::new(|x: f64| 1.0 - (-x).exp()),
            Box::new(|_| 1.0),
        ),
        (
            Input::Ramp,
            Box::new(|x: f64| x - 1.0 + (-x).exp()),
            Box::new(|x| x - 1.0),
        ),
        (
            Input::Exp(a),
            Box::new(move |x: f64| ((a * x).exp() - (-x).exp()) / (a + 1.0)),
            Box::new(move |x| (a * x).exp() / (a + 1.0)),
        ),
        (
            Input::Sin(w),
            Box::new(move |x: f64| {
                ((w * x).sin() - w * (w * x).cos() + w * (-x).exp()) / (1.0 + w * w)
            }),
            Box::new(move |x| ((w * x).sin() - w * (w * x).cos()) / (1.0 + w * w)),
        ),
        (
            Input::Cos(w),
            Box::new(move |x: f64| {
                ((w * x).cos() + w * (w * x).sin() - (-x).exp()) / (1.0 + w * w)
            }),
            Box::new(move |x| ((w * x).cos() + w * (w * x).sin()) / (1.0 + w * w)),
        ),
    ];
    for (input, y, yss) in cases {
        let s = g.response(&input, &[], &t).unwrap().samples;
        for (k, &x) in t.iter().enumerate() {
            let (want, want_ss) = (y(x), yss(x));
            let tol = 1e-13 * (1.0 + want.abs());
            assert!((s.y[k] - want).abs() < tol, "{input} y({x})");
            assert!((s.closed_form[k] - want).abs() < tol, "{input} closed({x})");
            assert!((s.steady_state[k] - want_ss).abs() < tol, "{input} ss({x})");
            assert!((s.transient[k] - (want - want_ss)).abs() < tol, "{input}");
        }
    }
}

#[test]
fn impulse_into_biproper_excludes_the_delta_from_values() {
    // (2s + 3)/(s + 1) = 2 + 1/(s + 1): y = 2δ(t) + e^(−t)
    let g = tf(&[2.0, 3.0], &[1.0, 1.0]);
    let s = g
        .response(&Input::Impulse, &[], &[0.0, 1.0, 2.0])
        .unwrap()
        .samples;
    for (x, y) in s.t.iter().zip(&s.y) {
        assert!((y - (-x).exp()).abs() < 1e-15);
    }
    assert!(s.closed_form_error < 1e-15);
}

#[test]
fn hidden_unstable_mode_with_initial_conditions() {
    // (s − 1)/((s − 1)(s + 2)): ICs excite e^t, the input does not.
    let g = tf(&[1.0, -1.0], &[1.0, 1.0, -2.0]);
    let t = grid(5.0, 50);
    let s = g.response(&Input::Step, &[1.0, 0.0], &t).unwrap().samples;
    assert!(s.closed_form_error < 1e-12 * s.max_abs_y);
    // Without ICs: 1/(s + 2) step, bounded, no e^t even by rounding.
    let s = g
        .response(&Input::Step, &[], &grid(40.0, 40))
        .unwrap()
        .samples;
    for (x, y) in s.t.iter().zip(&s.y) {
        assert!((y - 0.5 * (1.0 - (-2.0 * x).exp())).abs() < 1e-15);
    }
}

#[test]
fn higher_order_agreement_closed_form_vs_exact() {
    // The MATLAB stepinfo example with ICs and a sine input: both methods agree.
    let g = tf(&[1.0, 5.0, 5.0], &[1.0, 1.65, 5.0, 6.5, 2.0]);
    let t = grid(30.0, 3000);
    for (input, ics) in [
        (Input::Step, vec![]),
        (Input::Sin(0.7), vec![0.3, -0.2, 1.0, 0.5]),
        (Input::Ramp, vec![1.0]),
    ] {
        let s = g.response(&input, &ics, &t).unwrap().samples;
        println!(
            "MATLAB example, {input}: closed form vs exact {:.1e} (max|y| {:.2})",
            s.closed_form_error, s.max_abs_y
        );
        assert!(s.closed_form_error < 1e-12 * s.max_abs_y.max(1.0));
    }
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let g = tf(&[1.0], &[1.0, 1.0]);
    for t in [vec![f64::NAN], vec![-1.0], vec![0.0, f64::INFINITY]] {
        assert!(matches!(
            g.step_response(&t),
            Err(ltikit::LtiError::InvalidTime { .. })
        ));
        assert!(g.impulse_response(&t).is_err());
        assert!(g.response(&Input::Step, &[], &t).is_err());
    }
    let improper = tf(&[1.0, 0.0, 0.0], &[1.0, 1.0]);
    for r in [
        improper.step_response(&[1.0]),
        improper.impulse_response(&[1.0]),
    ] {
        assert!(matches!(r, Err(ltikit::LtiError::Improper { .. })), "{r:?}");
    }
    assert!(improper.inverse_laplace(&Input::Impulse, &[]).is_err());
    // Too many initial conditions for a first-order system.
    let e = g
        .time_response(&Input::None, &[1.0, 2.0], &[1.0])
        .unwrap_err();
    assert!(e.to_string().contains("2 initial conditions"), "{e}");
    assert!(g.inverse_laplace(&Input::Step, &[f64::NAN]).is_err());
    assert!(g.time_response(&Input::Cos(0.0), &[], &[1.0]).is_err());
}
