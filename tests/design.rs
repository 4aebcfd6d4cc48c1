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
        assert!(
            best <= tol * scale,
            "{want}: nearest eigenvalue {best} away; {ev:?}"
        );
    }
    assert!(p.relative_error <= tol, "{}", p.relative_error);
    assert!(p.condition.is_finite() && p.condition >= 1.0);
}

#[test]
fn mimo_placement_reaches_the_poles() {
    let (a, b) = knv_example();
    // the poles of scipy's example (real), a complex pair, a repeated pole (twice = rank B)
    check_achieved(
        &a,
        &b,
        &[c(-0.2, 0.0), c(-0.5, 0.0), c(-5.0566, 0.0), c(-8.6659, 0.0)],
        1e-10,
    );
    check_achieved(
        &a,
        &b,
        &[c(-1.0, 1.0), c(-1.0, -1.0), c(-2.0, 0.0), c(-3.0, 0.0)],
        1e-10,
    );
    check_achieved(
        &a,
        &b,
        &[c(-2.0, 0.0), c(-2.0, 0.0), c(-3.0, 1.0), c(-3.0, -1.0)],
        1e-10,
    );
    check_achieved(
        &a,
        &b,
        &[c(-1.0, 2.0), c(-1.0, -2.0), c(-3.0, 1.0), c(-3.0, -1.0)],
        1e-10,
    );
    let p = place_matrices(
        &a,
        &b,
        &[c(-0.2, 0.0), c(-0.5, 0.0), c(-5.0566, 0.0), c(-8.6659, 0.0)],
    )
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
    assert!(
        e.contains("3 poles requested for a plant with 4 states"),
        "{e}"
    );
    let e = err(
        &a,
        &b,
        &[c(-1.0, 1.0), c(-1.0, 1.0), c(-2.0, 0.0), c(-3.0, 0.0)],
    );
    assert!(e.contains("not closed under conjugation"), "{e}");
    let e = err(
        &a,
        &b,
        &[c(-1.0, 0.0), c(-1.0, 0.0), c(-1.0, 0.0), c(-3.0, 0.0)],
    );
    assert!(e.contains("requested 3 times but B has rank 2"), "{e}");
    let e = err(
        &a,
        &b,
        &[c(f64::NAN, 0.0), c(-1.0, 0.0), c(-2.0, 0.0), c(-3.0, 0.0)],
    );
    assert!(
        e.contains("NaN") || e.contains("not finite") || e.contains("non-finite"),
        "{e}"
    );
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
        "place",
        "--a",
        "0 1; 0 0",
        "--b",
        "0; 1",
        "--c",
        "1 0",
        "--poles",
        "-1+1j, -1-1j",
        "--json",
    ]);
    assert_eq!(v["dt"], serde_json::Value::Null);
    assert_eq!(v["method"], "ackermann");
    assert_eq!(v["k"][0][0].as_f64(), Some(2.0));
    assert_eq!(v["k"][0][1].as_f64(), Some(2.0));
    let keys: Vec<&String> = v.as_object().unwrap().keys().collect();
    assert_eq!(
        keys,
        [
            "dt",
            "method",
            "k",
            "requested",
            "achieved",
            "distance",
            "relative_error",
            "condition",
            "iterations",
            "note"
        ]
    );
    let text = common::stdout(&[
        "place", "--num", "1", "--den", "1 0 0", "--dt", "0.1", "--poles", "0.5 0.6",
    ]);
    assert!(
        text.contains("discrete time, dt = 0.1 s") && text.contains("requested (z)"),
        "{text}"
    );
    let out = common::ltikit(&["place", "--den", "1 3 2", "--poles", "-1+1j,-1-2j"]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.starts_with("error: --poles:") && err.lines().count() == 1,
        "{err}"
    );
    let out = common::ltikit(&["place", "--den", "1 3 2", "--poles", "-1", "--loop"]);
    assert_eq!(out.status.code(), Some(2));
}

// ---------------------------------------------------------------------------------------
// LQR, Kalman, LQG

use ltikit::analysis::design::{NoiseInput, lqe, lqg, lqr};

fn ss(a: DMatrix<f64>, b: DMatrix<f64>, c: DMatrix<f64>) -> StateSpace {
    let d = DMatrix::zeros(c.nrows(), b.ncols());
    StateSpace::new(a, b, c, d).unwrap()
}

fn m(r: usize, c: usize, v: &[f64]) -> DMatrix<f64> {
    DMatrix::from_row_slice(r, c, v)
}

fn double_integrator() -> StateSpace {
    ss(
        m(2, 2, &[0.0, 1.0, 0.0, 0.0]),
        m(2, 1, &[0.0, 1.0]),
        m(1, 2, &[1.0, 0.0]),
    )
}

fn max_diff(a: &DMatrix<f64>, b: &[f64]) -> f64 {
    a.transpose()
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Issue 23's target: the double integrator with Q = I, R = 1 has K = [1, √3] to 1e-14
/// (closed form: X = [[√3, 1], [1, √3]], K = BᵀX).
#[test]
fn lqr_double_integrator_to_1e14() {
    let d = lqr(
        &double_integrator(),
        &DMatrix::identity(2, 2),
        &DMatrix::identity(1, 1),
        None,
    )
    .unwrap();
    let r3 = 3f64.sqrt();
    let ek = max_diff(&d.gain, &[1.0, r3]);
    let ex = max_diff(&d.x, &[r3, 1.0, 1.0, r3]);
    println!(
        "double integrator: |K − [1, √3]| = {ek:.2e}, |X − X*| = {ex:.2e}, residual {:.2e}",
        d.residual
    );
    assert!(ek <= 1e-14, "{ek:e}: K = {}", d.gain);
    assert!(ex <= 1e-14, "{ex:e}: X = {}", d.x);
    // closed loop s² + √3 s + 1: −√3/2 ± j/2
    for p in &d.closed_loop {
        assert!(
            (p.re + r3 / 2.0).abs() < 1e-14 && (p.im.abs() - 0.5).abs() < 1e-14,
            "{p}"
        );
    }
}

/// ẋ = a x + b u, cost q x² + r u²: X = (a + √(a² + b²q/r))·r/b², K = bX/r (closed form).
#[test]
fn lqr_scalar_closed_form() {
    for &(a, b, q, r) in &[
        (1.0, 2.0, 3.0, 4.0),
        (-2.0, 0.5, 1.0, 10.0),
        (0.0, 1.0, 1e-4, 1.0),
        (5.0, 1e-2, 1.0, 1.0),
    ] {
        let one = |v: f64| m(1, 1, &[v]);
        let d = lqr(&ss(one(a), one(b), one(1.0)), &one(q), &one(r), None).unwrap();
        let x = (a + (a * a + b * b * q / r).sqrt()) * r / (b * b);
        assert!(
            common::rel(d.x[(0, 0)], x) < 1e-13,
            "{a} {b} {q} {r}: {} vs {x}",
            d.x[(0, 0)]
        );
        assert!(common::rel(d.gain[(0, 0)], b * x / r) < 1e-13);
    }
    // a cross term: q x² + 2 s x u + r u² is (q − s²/r) x² + r (u + s x / r)²
    let one = |v: f64| m(1, 1, &[v]);
    let (a, b, q, r, s) = (1.0, 1.0, 2.0, 1.0, 0.5);
    let d = lqr(
        &ss(one(a), one(b), one(1.0)),
        &one(q),
        &one(r),
        Some(&one(s)),
    )
    .unwrap();
    let (a2, q2) = (a - b * s / r, q - s * s / r);
    let x = (a2 + (a2 * a2 + b * b * q2 / r).sqrt()) * r / (b * b);
    assert!(
        common::rel(d.x[(0, 0)], x) < 1e-13,
        "{} vs {x}",
        d.x[(0, 0)]
    );
    assert!(common::rel(d.gain[(0, 0)], (b * x + s) / r) < 1e-13);
}

/// Discrete LQR: the scalar DARE in closed form, and python-control 0.10.2 `dlqr` on the
/// sampled double integrator (T = 0.1, Q = I, R = 1).
#[test]
fn lqr_discrete() {
    let dt = ltikit::lti::Domain::discrete(0.1).unwrap();
    let one = |v: f64| m(1, 1, &[v]);
    // x⁺ = a x + b u: b²X² + (r − a²r − qb²)X − qr = 0, positive root; K = abX/(r + b²X)
    let (a, b, q, r) = (1.2, 0.5, 1.0, 2.0);
    let d = lqr(
        &ss(one(a), one(b), one(1.0)).with_domain(dt),
        &one(q),
        &one(r),
        None,
    )
    .unwrap();
    let (p2, p1, p0) = (b * b, r - a * a * r - q * b * b, -q * r);
    let x = (-p1 + (p1 * p1 - 4.0 * p2 * p0).sqrt()) / (2.0 * p2);
    assert!(
        common::rel(d.x[(0, 0)], x) < 1e-13,
        "{} vs {x}",
        d.x[(0, 0)]
    );
    assert!(common::rel(d.gain[(0, 0)], a * b * x / (r + b * b * x)) < 1e-13);
    assert!(d.closed_loop[0].norm() < 1.0);
    // control.dlqr([[1, 0.1], [0, 1]], [[0.005], [0.1]], eye(2), 1)
    let plant = ss(
        m(2, 2, &[1.0, 0.1, 0.0, 1.0]),
        m(2, 1, &[0.005, 0.1]),
        m(1, 2, &[1.0, 0.0]),
    )
    .with_domain(dt);
    let d = lqr(&plant, &DMatrix::identity(2, 2), &one(1.0), None).unwrap();
    assert!(
        max_diff(&d.gain, &[0.9170745631140932, 1.6355961850466294]) < 1e-12,
        "{}",
        d.gain
    );
    let xs = [
        17.83493132218894,
        10.012492197250374,
        10.012492197250374,
        17.856586460328806,
    ];
    assert!(max_diff(&d.x, &xs) < 1e-11, "{}", d.x);
}

/// Kalman gains against python-control 0.10.2 `lqe`/`dlqe` (A = [[0, 1], [−2, −3]],
/// C = [1, 0]; noise on the states with Qn = diag(1, 2), Rn = 0.5, or through B = [0; 1] with
/// Qn = 3, Rn = 0.1).
#[test]
fn kalman_gain_matches_python_control() {
    let plant = ss(
        m(2, 2, &[0.0, 1.0, -2.0, -3.0]),
        m(2, 1, &[0.0, 1.0]),
        m(1, 2, &[1.0, 0.0]),
    );
    let k = lqe(
        &plant,
        &m(2, 2, &[1.0, 0.0, 0.0, 2.0]),
        &m(1, 1, &[0.5]),
        None,
        None,
    )
    .unwrap();
    assert_eq!(k.noise_input, NoiseInput::States);
    assert!(
        max_diff(&k.gain, &[1.1470518476606446, -0.3421360293891504]) < 1e-13,
        "{}",
        k.gain
    );
    let ps = [
        0.5735259238303223,
        -0.1710680146945752,
        -0.1710680146945752,
        0.437623921245869,
    ];
    assert!(max_diff(&k.p, &ps) < 1e-13, "{}", k.p);
    let k = lqe(&plant, &m(1, 1, &[3.0]), &m(1, 1, &[0.1]), None, None).unwrap();
    assert_eq!(k.noise_input, NoiseInput::Inputs);
    assert!(
        max_diff(&k.gain, &[1.0818995320427225, 0.5852532987171319]) < 1e-13,
        "{}",
        k.gain
    );
    for e in &k.estimator_poles {
        assert!(
            (e.re + 2.0409497660213614).abs() < 1e-13
                && (e.im.abs() - 1.2905332027587086).abs() < 1e-13,
            "{e}"
        );
    }
    // discrete: the predictor gain L = APCᵀ(Rn + CPCᵀ)⁻¹ of control.dlqe
    let dplant = ss(
        m(2, 2, &[1.0, 0.1, 0.0, 1.0]),
        m(2, 1, &[0.005, 0.1]),
        m(1, 2, &[1.0, 0.0]),
    )
    .with_domain(ltikit::lti::Domain::discrete(0.1).unwrap());
    let k = lqe(
        &dplant,
        &m(2, 2, &[1.0, 0.0, 0.0, 2.0]),
        &m(1, 1, &[0.5]),
        None,
        None,
    )
    .unwrap();
    assert!(
        max_diff(&k.gain, &[0.8628757411285517, 0.9671356043658736]) < 1e-12,
        "{}",
        k.gain
    );
}

/// The cross covariance: ẋ = a x + w, y = x + v with E{wv} = N gives (P + N)² − 2aRP − QR = 0,
/// so P + N = aR + √(a²R² − 2aRN + QR) and L = (P + N)/R (closed form of the dual CARE).
#[test]
fn kalman_with_cross_covariance() {
    let one = |v: f64| m(1, 1, &[v]);
    for &(a, q, r, nn) in &[(1.0, 2.0, 0.5, 0.3), (-2.0, 1.0, 1.0, -0.4)] {
        let plant = ss(one(a), one(1.0), one(1.0));
        let k = lqe(
            &plant,
            &one(q),
            &one(r),
            Some(&one(nn)),
            Some(NoiseInput::States),
        )
        .unwrap();
        let u = a * r + (a * a * r * r - 2.0 * a * r * nn + q * r).sqrt();
        assert!(
            common::rel(k.p[(0, 0)], u - nn) < 1e-13,
            "{} vs {}",
            k.p[(0, 0)],
            u - nn
        );
        assert!(common::rel(k.gain[(0, 0)], u / r) < 1e-13);
        assert!(common::rel(k.estimator_poles[0].re, a - u / r) < 1e-13);
    }
}

/// Separation principle: the closed loop of plant and LQG controller (negative feedback)
/// has the eigenvalues of A − BK and of A − LC; a MIMO plant and a discrete one.
#[test]
fn lqg_closed_loop_separates() {
    let (a, b) = knv_example();
    let c = m(2, 4, &[1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    let mut plants = vec![ss(a, b, c)];
    plants.push(
        ss(
            m(2, 2, &[1.0, 0.1, 0.0, 1.0]),
            m(2, 1, &[0.005, 0.1]),
            m(1, 2, &[1.0, 0.0]),
        )
        .with_domain(ltikit::lti::Domain::discrete(0.1).unwrap()),
    );
    for plant in plants {
        let (n, mm, p) = (plant.order(), plant.b.ncols(), plant.c.nrows());
        let d = lqg(
            &plant,
            &DMatrix::identity(n, n),
            &DMatrix::identity(mm, mm),
            &(DMatrix::identity(n, n) * 0.5),
            &DMatrix::identity(p, p),
            Some(NoiseInput::States),
        )
        .unwrap();
        let cl = plant.feedback(&d.controller, -1.0).unwrap();
        assert_eq!(cl.domain, plant.domain);
        let ev = ltikit::numeric::eigenvalues(&cl.a).unwrap();
        let mut want = d.regulator.closed_loop.clone();
        want.extend(&d.estimator.estimator_poles);
        assert_eq!(ev.len(), want.len());
        let scale = want.iter().map(|z| z.norm()).fold(0.0, f64::max);
        for w in &want {
            let best = ev
                .iter()
                .map(|z| (z - w).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(best < 1e-9 * scale, "{w}: {best:e} from {ev:?}");
        }
    }
}

#[test]
fn bad_design_inputs() {
    let di = double_integrator();
    let id = |k| DMatrix::<f64>::identity(k, k);
    let e = |r: ltikit::error::Result<ltikit::analysis::design::Lqr>| r.unwrap_err().to_string();
    assert!(e(lqr(&di, &id(3), &id(1), None)).contains("`q` must be 2×2"));
    assert!(e(lqr(&di, &id(2), &m(1, 1, &[0.0]), None)).contains("`r` must be positive definite"));
    assert!(e(lqr(&di, &id(2), &m(1, 1, &[-1.0]), None)).contains("`r` must be positive definite"));
    assert!(
        e(lqr(&di, &m(2, 2, &[1.0, 2.0, 0.0, 1.0]), &id(1), None))
            .contains("`q` must be symmetric")
    );
    assert!(e(lqr(&di, &m(2, 2, &[f64::NAN, 0.0, 0.0, 1.0]), &id(1), None)).contains("`q`"));
    assert!(e(lqr(&di, &id(2), &id(1), Some(&id(2)))).contains("`s` must be 2×1"));
    // not stabilisable: an unstable mode the input does not reach
    let p = ss(
        m(2, 2, &[1.0, 0.0, 0.0, -1.0]),
        m(2, 1, &[0.0, 1.0]),
        m(1, 2, &[1.0, 1.0]),
    );
    let e = lqr(&p, &id(2), &id(1), None).unwrap_err().to_string();
    assert!(e.contains("not stabilisable") && e.contains("λ = 1"), "{e}");
    // not detectable: the estimator's error names (A, C)
    let p = ss(
        m(2, 2, &[1.0, 0.0, 0.0, -1.0]),
        m(2, 1, &[0.0, 1.0]),
        m(1, 2, &[0.0, 1.0]),
    );
    let e = lqe(&p, &id(2), &id(1), None, None).unwrap_err().to_string();
    assert!(
        e.contains("(A, C) is not detectable") && e.contains("unobservable mode λ = 1"),
        "{e}"
    );
    // Kalman: ambiguous noise input, wrong sizes
    let sq = ss(
        m(2, 2, &[0.0, 1.0, -2.0, -3.0]),
        id(2),
        m(1, 2, &[1.0, 0.0]),
    );
    let k = lqe(&sq, &id(2), &id(1), None, None)
        .unwrap_err()
        .to_string();
    assert!(
        k.contains("as many inputs as states (2): say where the process noise enters"),
        "{k}"
    );
    assert!(lqe(&sq, &id(2), &id(1), None, Some(NoiseInput::Inputs)).is_ok());
    let k = lqe(&di, &id(3), &id(1), None, None)
        .unwrap_err()
        .to_string();
    assert!(
        k.contains("`qn` must be 2×2 (noise on every state) or 1×1"),
        "{k}"
    );
    let k = lqe(&di, &id(2), &id(2), None, None)
        .unwrap_err()
        .to_string();
    assert!(k.contains("`rn` must be 1×1"), "{k}");
    // the size limits, before any work
    let big = |n: usize| {
        ss(
            DMatrix::identity(n, n) * -1.0,
            DMatrix::from_element(n, 1, 1.0),
            DMatrix::from_element(1, n, 1.0),
        )
    };
    let e = lqr(&big(257), &id(257), &id(1), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("MAX_DESIGN_STATES"), "{e}");
    let e = place(&big(201), &vec![c(-1.0, 0.0); 201])
        .unwrap_err()
        .to_string();
    assert!(e.contains("MAX_PLACE_STATES"), "{e}");
}

#[test]
fn lqr_lqe_lqg_commands() {
    let plant = ["--a", "0 1; 0 0", "--b", "0; 1", "--c", "1 0"];
    let run = |extra: &[&str]| {
        let mut args: Vec<&str> = vec![extra[0]];
        args.extend(plant);
        args.extend(&extra[1..]);
        common::json(&args)
    };
    let v = run(&["lqr", "--q", "1", "--r", "1", "--json"]);
    let keys: Vec<&String> = v.as_object().unwrap().keys().collect();
    assert_eq!(
        keys,
        [
            "dt",
            "equation",
            "k",
            "x",
            "closed_loop",
            "residual",
            "condition"
        ]
    );
    assert_eq!(v["equation"], "care");
    assert!((v["k"][0][1].as_f64().unwrap() - 3f64.sqrt()).abs() < 1e-14);
    // `kalman` is `lqe`; one input, two states: a 1×1 Qn is noise through the input
    let v = run(&["kalman", "--qn", "1", "--rn", "1", "--json"]);
    assert_eq!(v["noise_input"], "inputs");
    assert!(
        (v["l"][0][0].as_f64().unwrap() - 2f64.sqrt()).abs() < 1e-13,
        "{v}"
    );
    let v = run(&[
        "lqe",
        "--qn",
        "1",
        "--rn",
        "1",
        "--noise-input",
        "states",
        "--json",
    ]);
    assert_eq!(v["noise_input"], "states");
    // LQG: the controller file is a plant that `analyze` reads, and as the loop controller
    // it gives the closed loop the poles of A − BK and A − LC
    let dir = std::env::temp_dir().join(format!("ltikit-design-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("ctrl.toml");
    let f = file.to_str().unwrap();
    let v = run(&[
        "lqg", "--q", "1", "--r", "1", "--qn", "1", "--rn", "1", "--json", "-o", f,
    ]);
    assert_eq!(v["controller"]["a"].as_array().unwrap().len(), 2);
    let a = common::json(&["analyze", "--plant", f, "--json"]);
    assert!(a.to_string().contains("poles"), "{a}");
    let text = common::stdout(&[
        "lqg", "--a", "0 1; 0 0", "--b", "0; 1", "--c", "1 0", "--q", "1", "--r", "1", "--qn", "1",
        "--rn", "1",
    ]);
    let spec = text
        .lines()
        .find_map(|l| l.strip_prefix("as a loop controller: --controller "))
        .unwrap()
        .trim_matches('"')
        .to_string();
    let cl = common::json(&[
        "analyze",
        "--a",
        "0 1; 0 0",
        "--b",
        "0; 1",
        "--c",
        "1 0",
        "--controller",
        &spec,
        "--json",
    ]);
    let poles: Vec<Complex64> = cl["poles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| c(p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
        .collect();
    // eig(A − BK) = −√3/2 ± j/2, eig(A − LC) = −1/√2 ± j/√2 (Q = I, R = 1; Qn = 1 through B, Rn = 1)
    let h = std::f64::consts::FRAC_1_SQRT_2;
    for w in [
        c(-0.75f64.sqrt(), 0.5),
        c(-0.75f64.sqrt(), -0.5),
        c(-h, h),
        c(-h, -h),
    ] {
        assert!(
            poles.iter().any(|p| (p - w).norm() < 1e-9),
            "{w} not in {poles:?}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
    // bad input: one line, exit 1; a missing weight is a usage error
    let out = common::ltikit(&["lqr", "--den", "1 0 0", "--q", "1 2; 3 4", "--r", "1"]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.starts_with("error: --q must be symmetric") && err.lines().count() == 1,
        "{err}"
    );
    let out = common::ltikit(&["lqr", "--den", "1 0 0", "--q", "1"]);
    assert_eq!(out.status.code(), Some(2));
    let out = common::ltikit(&[
        "lqe",
        "--a",
        "0 1; -2 -3",
        "--b",
        "1 0; 0 1",
        "--c",
        "1 0",
        "--qn",
        "1",
        "--rn",
        "1",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--noise-input"), "{err}");
}
