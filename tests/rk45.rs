//! The Dormand–Prince integrator against closed forms (issue 4, item 5; DESIGN §3).
//!
//! References: x(t) = e^{At}x₀ (seed eq. 2.4, evaluated with the matrix exponential); the
//! logistic equation's x(t) = 1/(1 + (1/x₀ − 1)e^{−t}); ẋ = x², x(0) = 1 has x = 1/(1 − t) and
//! blows up at t = 1.

use ltikit::LtiError;
use ltikit::numeric::expm;
use ltikit::numeric::rk45::{Rk45Options, StepControl, integrate, solve};
use nalgebra::{DMatrix, DVector};

fn tight() -> Rk45Options {
    Rk45Options {
        rtol: 1e-12,
        atol: 1e-14,
        ..Default::default()
    }
}

/// Two coupled damped oscillators, one lightly damped (ζ ≈ 0.01), one fast.
fn coupled() -> DMatrix<f64> {
    DMatrix::from_row_slice(
        4,
        4,
        &[
            0.0, 1.0, 0.0, 0.0, //
            -4.0, -0.04, 1.0, 0.0, //
            0.0, 0.0, 0.0, 1.0, //
            0.5, 0.0, -25.0, -3.0,
        ],
    )
}

#[test]
fn linear_system_matches_the_matrix_exponential() {
    let a = coupled();
    let x0 = [1.0, 0.0, -0.5, 2.0];
    let times: Vec<f64> = (0..=400).map(|k| k as f64 * 0.05).collect();
    let sol = solve(
        |_t, x, dx| {
            let v = &a * DVector::from_column_slice(x);
            dx.copy_from_slice(v.as_slice());
        },
        0.0,
        &x0,
        20.0,
        &times,
        &tight(),
    )
    .unwrap();
    let mut worst: f64 = 0.0;
    for (t, x) in sol.t.iter().zip(&sol.x) {
        let exact = expm(&(&a * *t)).unwrap() * DVector::from_column_slice(&x0);
        for (p, q) in x.iter().zip(exact.iter()) {
            worst = worst.max((p - q).abs());
        }
    }
    eprintln!(
        "rk45 vs exp(At)x0 (rtol 1e-12): max error {worst:.2e}, {:?}",
        sol.stats
    );
    assert!(worst < 1e-9, "max error {worst:e}");
}

#[test]
fn error_follows_the_tolerance() {
    // Logistic ẋ = x(1 − x): the global error shrinks with rtol (tolerance proportionality).
    let exact = |t: f64| 1.0 / (1.0 + 9.0 * (-t).exp());
    let times: Vec<f64> = (0..=100).map(|k| k as f64 * 0.1).collect();
    let mut prev = f64::INFINITY;
    for rtol in [1e-4, 1e-7, 1e-10] {
        let opts = Rk45Options {
            rtol,
            atol: rtol * 1e-3,
            ..Default::default()
        };
        let sol = solve(
            |_t, x, dx| dx[0] = x[0] * (1.0 - x[0]),
            0.0,
            &[0.1],
            10.0,
            &times,
            &opts,
        )
        .unwrap();
        let err = sol
            .t
            .iter()
            .zip(&sol.x)
            .map(|(t, x)| (x[0] - exact(*t)).abs())
            .fold(0.0, f64::max);
        assert!(err < 50.0 * rtol, "rtol {rtol:e}: error {err:e}");
        assert!(err < prev);
        prev = err;
    }
}

#[test]
fn evaluation_count_is_six_per_attempt_plus_start() {
    let sol = solve(
        |_t, x, dx| dx[0] = -x[0],
        0.0,
        &[1.0],
        5.0,
        &[5.0],
        &Rk45Options::default(),
    )
    .unwrap();
    let s = sol.stats;
    // f(t0) once, one for the automatic initial step, then six per attempted step (FSAL).
    assert_eq!(s.evaluations, 2 + 6 * (s.steps + s.rejections));
    assert!((sol.x[0][0] - (-5.0f64).exp()).abs() < 1e-10);
    assert_eq!(sol.x_end, sol.x[0]);
}

#[test]
fn finite_time_blow_up_stops_cleanly_at_t_one() {
    let err = solve(
        |_t, x, dx| dx[0] = x[0] * x[0],
        0.0,
        &[1.0],
        2.0,
        &[0.5, 2.0],
        &Rk45Options::default(),
    )
    .unwrap_err();
    match err {
        LtiError::Diverged { t, norm } => {
            eprintln!("x' = x^2 blow-up reported at t = {t} with |x| = {norm:e}");
            assert!((t - 1.0).abs() < 1e-6, "t = {t}");
            assert!(norm > 1e6);
        }
        e => panic!("expected Diverged, got {e:?}"),
    }
}

#[test]
fn overflow_to_infinity_is_divergence() {
    // ẋ = x³ from 10: blow-up at t = 1/200; also with loose tolerances.
    let opts = Rk45Options {
        rtol: 1e-3,
        atol: 1e-6,
        ..Default::default()
    };
    let err = integrate(
        |_t, x, dx| dx[0] = x[0] * x[0] * x[0],
        0.0,
        &[10.0],
        1.0,
        &opts,
        |_| StepControl::Continue,
    )
    .unwrap_err();
    assert!(
        matches!(err, LtiError::Diverged { t, .. } if (t - 0.005).abs() < 1e-4),
        "{err:?}"
    );
}

#[test]
fn step_limit_is_reported() {
    let opts = Rk45Options {
        max_steps: 20,
        ..Default::default()
    };
    let err = solve(
        |_t, x, dx| {
            dx[0] = x[1];
            dx[1] = -x[0];
        },
        0.0,
        &[1.0, 0.0],
        1000.0,
        &[1000.0],
        &opts,
    )
    .unwrap_err();
    assert!(
        matches!(err, LtiError::StepLimit { steps: 20, t } if t > 0.0 && t < 1000.0),
        "{err:?}"
    );
}

#[test]
fn non_finite_right_hand_side_is_an_error_not_a_panic() {
    // √(1 − x) is NaN beyond x = 1, which ẋ = 1 reaches at t = 1 − x₀.
    let err = solve(
        |_t, x, dx| {
            dx[0] = 1.0 + (1.0 - x[0]).sqrt() * 0.0 + if x[0] > 1.0 { f64::NAN } else { 0.0 }
        },
        0.0,
        &[0.5],
        2.0,
        &[2.0],
        &Rk45Options::default(),
    )
    .unwrap_err();
    assert!(
        matches!(err, LtiError::Undefined { .. } | LtiError::Diverged { .. }),
        "{err:?}"
    );
    let err = solve(
        |_t, _x, dx| dx[0] = f64::NAN,
        0.0,
        &[0.5],
        2.0,
        &[2.0],
        &Rk45Options::default(),
    )
    .unwrap_err();
    assert!(matches!(err, LtiError::NonFinite { .. }), "{err:?}");
}

#[test]
fn bad_times_are_rejected() {
    let f = |_t: f64, x: &[f64], dx: &mut [f64]| dx[0] = -x[0];
    let o = Rk45Options::default();
    for t_end in [0.0, -1.0, f64::NAN] {
        assert!(solve(f, 0.0, &[1.0], t_end, &[], &o).is_err());
    }
    assert!(solve(f, 0.0, &[1.0], 1.0, &[-0.5], &o).is_err());
    assert!(solve(f, 0.0, &[1.0], 1.0, &[0.2, f64::NAN], &o).is_err());
}

#[test]
fn samples_at_mesh_points_and_repeated_times() {
    let times = [0.0, 0.0, 0.25, 0.25, 1.0];
    let sol = solve(
        |_t, x, dx| dx[0] = -x[0],
        0.0,
        &[1.0],
        1.0,
        &times,
        &tight(),
    )
    .unwrap();
    assert_eq!(sol.x.len(), 5);
    for (t, x) in times.iter().zip(&sol.x) {
        assert!((x[0] - (-t).exp()).abs() < 1e-12, "t = {t}: {}", x[0]);
    }
}
