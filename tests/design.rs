//! Controller and estimator design (`analysis::design`, `ltikit place`): pole placement by
//! Ackermann (one input) and Kautsky–Nichols–Van Dooren (several inputs).

mod common;

use common::c;
use ltikit::StateSpace;
use ltikit::analysis::design::{PlacementMethod, place, place_matrices};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// The 4-state, 2-input example of Kautsky, Nichols and Van Dooren (1985), also in the
/// documentation of `scipy.signal.place_poles`.
fn knv_example() -> (DMatrix<f64>, DMatrix<f64>) {
    let a = DMatrix::from_row_slice(
        4,
        4,
        &[
            1.380, -0.2077, 6.715, -5.676, -0.5814, -4.290, 0.0, 0.6750, 1.067, 4.273, -6.654,
            5.893, 0.0480, 4.273, 1.343, -2.104,
        ],
    );
    let b = DMatrix::from_row_slice(4, 2, &[0.0, 0.0, 5.679, 0.0, 1.136, -3.146, 1.136, 0.0]);
    (a, b)
}

/// Every achieved pole within `tol` of its requested pole, relative to the largest |pole|;
/// and the achieved poles are the eigenvalues of A − BK, computed here again.
fn check_achieved(a: &DMatrix<f64>, b: &DMatrix<f64>, poles: &[Complex64], tol: f64) {
    let p = place_matrices(a, b, poles).unwrap();
    let scale = poles.iter().map(|z| z.norm()).fold(0.0, f64::max);
    let ev = ltikit::numeric::eigenvalues(&(a - b * &p.gain)).unwrap();
    for want in poles {
        let best = ev
            .iter()
            .map(|z| (z - want).norm())
            .fold(f64::INFINITY, f64::min);
        assert!(best <= tol * scale, "{want}: nearest eigenvalue {best} away; {ev:?}");
    }
    assert!(p.relative_error <= tol, "{}", p.relative_error);
    assert!(p.condition.is_finite() && p.condition >= 1.0);
}

#[test]
fn mimo_placement_reaches_the_poles() {
    let (a, b) = knv_example();
    // the poles of scipy's example (real), a complex pair, a repeated pole (twice = rank B)
    check_achieved(&a, &b, &[c(-0.2, 0.0), c(-0.5, 0.0), c(-5.0566, 0.0), c(-8.6659, 0.0)], 1e-10);
    check_achieved(&a, &b, &[c(-1.0, 1.0), c(-1.0, -1.0), c(-2.0, 0.0), c(-3.0, 0.0)], 1e-10);
    check_achieved(&a, &b, &[c(-2.0, 0.0), c(-2.0, 0.0), c(-3.0, 1.0), c(-3.0, -1.0)], 1e-10);
    check_achieved(&a, &b, &[c(-1.0, 2.0), c(-1.0, -2.0), c(-3.0, 1.0), c(-3.0, -1.0)], 1e-10);
    let p = place_matrices(&a, &b, &[c(-0.2, 0.0), c(-0.5, 0.0), c(-5.0566, 0.0), c(-8.6659, 0.0)])
        .unwrap();
    assert_eq!(p.method, PlacementMethod::Knv0);
    // scipy 1.17 place_poles(method="KNV0") reaches κ(X) = 4.28 on this example (unit
    // columns); ours must be as well conditioned within a small factor
    assert!(p.condition < 8.0, "κ(X) = {}", p.condition);
}

#[test]
fn siso_placement_matches_the_closed_form() {
    // ẍ = u: A − BK = [[0, 1], [−k1, −k2]], characteristic s² + k2 s + k1 = (s − p1)(s − p2)
    let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
    let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
    let p = place_matrices(&a, &b, &[c(-3.0, 4.0), c(-3.0, -4.0)]).unwrap();
    assert_eq!(p.method, PlacementMethod::Ackermann);
    assert_eq!((p.gain[(0, 0)], p.gain[(0, 1)]), (25.0, 6.0));
    // a 6-state chain of integrators with distinct poles
    let n = 6;
    let mut a = DMatrix::<f64>::zeros(n, n);
    for i in 0..n - 1 {
        a[(i, i + 1)] = 1.0;
    }
    let mut b = DMatrix::<f64>::zeros(n, 1);
    b[(n - 1, 0)] = 1.0;
    let poles: Vec<Complex64> = [-1.0, -2.0, -3.0]
        .iter()
        .flat_map(|&r| [c(r, 0.5 * r), c(r, -0.5 * r)])
        .collect();
    check_achieved(&a, &b, &poles, 1e-10);
}

#[test]
fn discrete_placement_is_the_same_algebra() {
    // deadbeat control of a sampled double integrator (T = 1): A = [[1, 1], [0, 1]],
    // B = [0.5, 1]; both poles at z = 0 give K = [1, 1.5] (closed form: (A − BK)² = 0)
    let ss = StateSpace::new(
        DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 0.0, 1.0]),
        DMatrix::from_row_slice(2, 1, &[0.5, 1.0]),
        DMatrix::from_row_slice(1, 2, &[1.0, 0.0]),
        DMatrix::zeros(1, 1),
    )
    .unwrap()
    .with_domain(ltikit::lti::Domain::discrete(1.0).unwrap());
    let p = place(&ss, &[c(0.0, 0.0), c(0.0, 0.0)]).unwrap();
    assert!((p.gain[(0, 0)] - 1.0).abs() < 1e-15 && (p.gain[(0, 1)] - 1.5).abs() < 1e-15);
    let cl = &ss.a - &ss.b * &p.gain;
    assert!((&cl * &cl).norm() < 1e-15);
}

#[test]
fn bad_placement_requests() {
    let (a, b) = knv_example();
    let err = |a: &DMatrix<f64>, b: &DMatrix<f64>, p: &[Complex64]| {
        place_matrices(a, b, p).unwrap_err().to_string()
    };
    let e = err(&a, &b, &[c(-1.0, 0.0), c(-2.0, 0.0), c(-3.0, 0.0)]);
    assert!(e.contains("3 poles requested for a plant with 4 states"), "{e}");
    let e = err(&a, &b, &[c(-1.0, 1.0), c(-1.0, 1.0), c(-2.0, 0.0), c(-3.0, 0.0)]);
    assert!(e.contains("not closed under conjugation"), "{e}");
    let e = err(&a, &b, &[c(-1.0, 0.0), c(-1.0, 0.0), c(-1.0, 0.0), c(-3.0, 0.0)]);
    assert!(e.contains("requested 3 times but B has rank 2"), "{e}");
    let e = err(&a, &b, &[c(f64::NAN, 0.0), c(-1.0, 0.0), c(-2.0, 0.0), c(-3.0, 0.0)]);
    assert!(e.contains("NaN") || e.contains("not finite") || e.contains("non-finite"), "{e}");
    // uncontrollable: the second mode (−2) is reached by neither input
    let a2 = DMatrix::from_row_slice(3, 3, &[-1.0, 0.0, 0.0, 0.0, -2.0, 0.0, 0.0, 0.0, -3.0]);
    let b2 = DMatrix::from_row_slice(3, 2, &[1.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
    let e = err(&a2, &b2, &[c(-4.0, 0.0), c(-5.0, 0.0), c(-6.0, 0.0)]);
    assert!(e.contains("not controllable") && e.contains("at -2"), "{e}");
    // dependent inputs
    let b3 = DMatrix::from_row_slice(3, 2, &[1.0, 2.0, 1.0, 2.0, 1.0, 2.0]);
    let a3 = DMatrix::from_row_slice(3, 3, &[0.0, 1.0, 0.0, 0.0, 0.0, 1.0, -1.0, -2.0, -3.0]);
    let e = err(&a3, &b3, &[c(-4.0, 0.0), c(-5.0, 0.0), c(-6.0, 0.0)]);
    assert!(e.contains("rank 1 but 2 columns"), "{e}");
    // sizes
    let e = err(&a, &DMatrix::zeros(3, 2), &[c(-1.0, 0.0); 4]);
    assert!(e.contains("inconsistent dimensions"), "{e}");
}

#[test]
fn place_command() {
    let v = common::json(&[
        "place", "--a", "0 1; 0 0", "--b", "0; 1", "--c", "1 0", "--poles", "-1+1j, -1-1j",
        "--json",
    ]);
    assert_eq!(v["dt"], serde_json::Value::Null);
    assert_eq!(v["method"], "ackermann");
    assert_eq!(v["k"][0][0].as_f64(), Some(2.0));
    assert_eq!(v["k"][0][1].as_f64(), Some(2.0));
    let keys: Vec<&String> = v.as_object().unwrap().keys().collect();
    assert_eq!(
        keys,
        ["dt", "method", "k", "requested", "achieved", "distance", "relative_error",
         "condition", "iterations", "note"]
    );
    let text = common::stdout(&["place", "--num", "1", "--den", "1 0 0", "--dt", "0.1", "--poles", "0.5 0.6"]);
    assert!(text.contains("discrete time, dt = 0.1 s") && text.contains("requested (z)"), "{text}");
    let out = common::ltikit(&["place", "--den", "1 3 2", "--poles", "-1+1j,-1-2j"]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.starts_with("error: --poles:") && err.lines().count() == 1, "{err}");
    let out = common::ltikit(&["place", "--den", "1 3 2", "--poles", "-1", "--loop"]);
    assert_eq!(out.status.code(), Some(2));
}
