//! The Nyquist contour in z: G along the unit circle z = e^(jωT), arcs outside it around the
//! poles on it, and the criterion Z = N + P with P and Z counted outside the unit circle (N the
//! clockwise encirclements of −1, as in s). Each verdict is checked against the closed-loop
//! roots of D + K·N (and the hand-derived Jury conditions cited per plant), over sweeps of
//! the gain; then the CLI (`nyquist --dt`, `bode --dt`).

mod common;

use common::{json, ltikit, poly};
use ltikit::analysis::discrete::circle_side;
use ltikit::analysis::{ContourPart, Factored, HalfPlane, NyquistContour, jury};
use ltikit::lti::Domain;
use num_complex::Complex64;

/// K·num/den in z (descending powers) with period `dt`, factored.
fn loop_z(k: f64, num: &[f64], den: &[f64], dt: f64) -> Factored {
    let num: Vec<f64> = num.iter().map(|c| k * c).collect();
    ltikit::TransferFunction::from_descending(&num, den)
        .unwrap()
        .with_domain(Domain::discrete(dt).unwrap())
        .factored()
        .unwrap()
}

/// D + K·N (descending).
fn closed_loop(k: f64, num: &[f64], den: &[f64]) -> Vec<f64> {
    let mut c = den.to_vec();
    let off = den.len() - num.len();
    for (i, n) in num.iter().enumerate() {
        c[off + i] += k * n;
    }
    c
}

/// Closed-loop poles outside the unit circle, from the roots of D + K·N; `None` when one lies
/// within 1e-6 of the circle (the curve then passes through −1 or nearly so).
fn outside_by_roots(k: f64, num: &[f64], den: &[f64]) -> Option<i64> {
    let roots = poly(&closed_loop(k, num, den)).roots().unwrap();
    if roots.iter().any(|r| (r.value.norm() - 1.0).abs() < 1e-6) {
        return None;
    }
    Some(
        roots
            .iter()
            .filter(|r| circle_side(r.value) == HalfPlane::Right)
            .map(|r| r.multiplicity as i64)
            .sum(),
    )
}

fn contour(k: f64, num: &[f64], den: &[f64]) -> NyquistContour {
    loop_z(k, num, den, 0.1).nyquist().unwrap()
}

/// Gains from 0.01 to 10, log-spaced, and their negatives.
fn gains() -> Vec<f64> {
    let pos: Vec<f64> = (0..=60)
        .map(|i| 10f64.powf(-2.0 + 3.0 * f64::from(i) / 60.0))
        .collect();
    pos.iter().copied().chain(pos.iter().map(|k| -k)).collect()
}

#[test]
fn integrator_loop_matches_jury_and_the_roots() {
    // K/((z − 1)(z − 0.5)): closed loop z² − 1.5z + 0.5 + K. Jury's conditions (by hand):
    // P(1) = K > 0, P(−1) = 3 + K > 0, |0.5 + K| < 1: stable for 0 < K < 0.5.
    let (num, den) = ([1.0], [1.0, -1.5, 0.5]);
    let n = contour(0.3, &num, &den);
    assert_eq!(n.dt, Some(0.1));
    assert_eq!(n.axis_poles, vec![0.0]); // the integrator z = 1, ω = 0
    assert_eq!(
        (
            n.open_loop_rhp_poles,
            n.encirclements,
            n.closed_loop_rhp_poles
        ),
        (0, Some(0), Some(0))
    );
    // K = 0.8: z² − 1.5z + 1.3, a complex pair with |z|² = 1.3 > 1: two outside, N = 2.
    let n = contour(0.8, &num, &den);
    assert_eq!(
        (n.encirclements, n.closed_loop_rhp_poles),
        (Some(2), Some(2))
    );
    let jt = jury(&poly(&closed_loop(0.8, &num, &den))).unwrap();
    assert_eq!(jt.outside, 2);
    // the whole sweep: the criterion against the Jury table and the roots
    for k in gains() {
        let n = contour(k, &num, &den);
        let jt = jury(&poly(&closed_loop(k, &num, &den))).unwrap();
        if let Some(z) = outside_by_roots(k, &num, &den) {
            assert_eq!(
                n.closed_loop_rhp_poles,
                Some(z),
                "K = {k}: N = {:?}",
                n.encirclements
            );
            assert_eq!(z, jt.outside as i64, "K = {k}");
            assert_eq!(z == 0, k > 0.0 && k < 0.5, "K = {k}");
        }
    }
}

#[test]
fn the_arc_around_z_equal_one_is_outside_and_maps_to_the_large_clockwise_arc() {
    // near z = 1, G ≈ r/(z − 1) with the residue r = K/(1 − 0.5) = 2K: an arc of radius
    // 2K/ε sweeping clockwise as z goes round outside the circle.
    let k = 0.3;
    let n = contour(k, &[1.0], &[1.0, -1.5, 0.5]);
    let eps = n.indent_radius[0];
    // ε = 10⁻³ of the distance to the nearest other root (0.5, from z = 0.5)
    assert!((eps - 5e-4).abs() < 1e-15, "ε = {eps}");
    let arc: Vec<_> = n
        .points
        .iter()
        .filter(|p| p.part == ContourPart::Indentation)
        .collect();
    assert!(arc.len() >= 16);
    let one = Complex64::new(1.0, 0.0);
    for p in &arc {
        assert!(p.s.norm() >= 1.0 - 1e-12, "z = {} inside the circle", p.s);
        assert!(((p.s - one).norm() - eps).abs() < 1e-12);
        assert!(
            (p.g.norm() * eps / (2.0 * k) - 1.0).abs() < 2e-3,
            "|G|ε = {}",
            p.g.norm() * eps
        );
    }
    // clockwise: the angle of G decreases along the arc, from about +90° to −90°
    assert!(arc.windows(2).all(|w| (w[1].g / w[0].g).arg() <= 1e-12));
    let (first, last) = (
        arc[0].g.arg().to_degrees(),
        arc[arc.len() - 1].g.arg().to_degrees(),
    );
    assert!(first > 80.0 && last < -80.0, "{first}° … {last}°");
    // every other point is on the unit circle, and the curve is closed at z = −1
    for p in n
        .points
        .iter()
        .filter(|p| p.part == ContourPart::UnitCircle)
    {
        assert!((p.s.norm() - 1.0).abs() < 1e-12);
    }
    let (a, b) = (n.points[0], n.points[n.points.len() - 1]);
    assert!((a.s - b.s).norm() < 1e-12 && (a.s + one).norm() < 1e-12);
    // G(−1) = K/((−2)(−1.5)) = K/3
    assert!((b.g - Complex64::new(k / 3.0, 0.0)).norm() < 1e-12);
    assert!(n.display_radius.is_some());
}

#[test]
fn first_order_crosses_at_z_equal_minus_one() {
    // K/(z − 0.5): at θ = π, L(−1) = −K/1.5; the image of the circle is the circle through
    // K/0.5 and −K/1.5, so −1 is encircled once (clockwise) for K > 1.5: the closed-loop root
    // z = 0.5 − K leaves through z = −1 at K = 1.5.
    let (num, den) = ([1.0], [1.0, -0.5]);
    for (k, z) in [(1.0, 0), (1.4, 0), (1.6, 1), (2.0, 1), (10.0, 1), (0.2, 0)] {
        let n = contour(k, &num, &den);
        assert_eq!(n.open_loop_rhp_poles, 0);
        assert!(n.axis_poles.is_empty() && n.display_radius.is_none());
        assert_eq!(n.encirclements, Some(z), "K = {k}");
        assert_eq!(n.closed_loop_rhp_poles, Some(z), "K = {k}");
        let last = n.points[n.points.len() - 1];
        assert!((last.g - Complex64::new(-k / 1.5, 0.0)).norm() < 1e-12);
    }
    for k in gains() {
        if let Some(z) = outside_by_roots(k, &num, &den) {
            assert_eq!(
                contour(k, &num, &den).closed_loop_rhp_poles,
                Some(z),
                "K = {k}"
            );
        }
    }
}

#[test]
fn an_unstable_pole_stabilised_by_feedback() {
    // K/(z − 2): P = 1. The image of the circle is the circle through L(1) = −K and
    // L(−1) = −K/3; −1 lies inside for 1 < K < 3, where the curve goes round it
    // counterclockwise (N = −1) and Z = N + P = 0: the closed-loop root 2 − K is inside.
    let (num, den) = ([1.0], [1.0, -2.0]);
    let n = contour(1.5, &num, &den);
    assert_eq!(
        (
            n.open_loop_rhp_poles,
            n.encirclements,
            n.closed_loop_rhp_poles
        ),
        (1, Some(-1), Some(0))
    );
    for (k, nn, z) in [(0.5, 0, 1), (2.9, -1, 0), (3.5, 0, 1)] {
        let n = contour(k, &num, &den);
        assert_eq!(
            (n.encirclements, n.closed_loop_rhp_poles),
            (Some(nn), Some(z)),
            "K = {k}"
        );
    }
    for k in gains() {
        if let Some(z) = outside_by_roots(k, &num, &den) {
            assert_eq!(
                contour(k, &num, &den).closed_loop_rhp_poles,
                Some(z),
                "K = {k}"
            );
        }
    }
}

#[test]
fn criterion_matches_the_roots_on_plants_with_poles_on_the_circle() {
    // Each plant over the gain sweep; the verdict Z = N + P against the roots of D + K·N.
    let cases: [(&[f64], &[f64]); 7] = [
        // K(z − 0.8)/(z − 1)²: a double pole at z = 1 (hand Jury: 0 < K < 2/0.9)
        (&[1.0, -0.8], &[1.0, -2.0, 1.0]),
        // K/((z + 1)(z − 0.5)): a pole at z = −1, indented at the end of the half circle
        (&[1.0], &[1.0, 0.5, -0.5]),
        // K z/(z² + 1): poles ±j on the circle
        (&[1.0, 0.0], &[1.0, 0.0, 1.0]),
        // K/((z − 1)(z + 1)): poles at both ends
        (&[1.0], &[1.0, 0.0, -1.0]),
        // K(z + 0.5)/(z(z − 1)) (hand Jury: 0 < K < 2)
        (&[1.0, 0.5], &[1.0, -1.0, 0.0]),
        // an unstable pair 1.2e^(±j0.6) with a zero
        (&[1.0, -0.3], &[1.0, -2.4 * 0.6f64.cos(), 1.44]),
        // third order, a resonance near the circle: (z − 0.95e^(±j0.3))(z − 0.2)
        (
            &[1.0],
            &[
                1.0,
                -(1.9 * 0.3f64.cos() + 0.2),
                0.9025 + 0.38 * 0.3f64.cos(),
                -0.1805,
            ],
        ),
    ];
    let mut checked = 0;
    for (num, den) in cases {
        for k in gains() {
            let Some(z) = outside_by_roots(k, num, den) else {
                continue;
            };
            let n = contour(k, num, den);
            assert_eq!(
                n.closed_loop_rhp_poles,
                Some(z),
                "K·{num:?}/{den:?}, K = {k}: N = {:?}, P = {}",
                n.encirclements,
                n.open_loop_rhp_poles
            );
            checked += 1;
        }
    }
    assert!(checked > 700, "{checked}");
    // the arcs go round every pole on the circle, outside it
    let n = contour(0.5, &[1.0], &[1.0, 0.0, -1.0]);
    assert_eq!(n.axis_poles.len(), 2);
    assert!((n.axis_poles[1] - std::f64::consts::PI / 0.1).abs() < 1e-9);
    assert!(
        n.points
            .iter()
            .filter(|p| p.part == ContourPart::Indentation)
            .all(|p| p.s.norm() > 1.0 - 1e-12)
    );
}

#[test]
fn improper_and_ill_posed_loops() {
    // a non-causal G(z) (a pole at z = ∞) is refused
    let g = loop_z(1.0, &[1.0, 0.0, 0.0], &[1.0, 0.5], 0.1);
    assert!(g.nyquist().is_err());
    // 1 + G(∞) = 0: −z/(z − 0.5), the loop is not causal: N undefined
    let n = loop_z(-1.0, &[1.0, 0.0], &[1.0, -0.5], 0.1)
        .nyquist()
        .unwrap();
    assert_eq!(n.encirclements, None);
    // biproper and well posed: 2z/(z − 0.5), closed loop 3z − 0.5: stable
    let n = loop_z(2.0, &[1.0, 0.0], &[1.0, -0.5], 0.1)
        .nyquist()
        .unwrap();
    assert_eq!(n.closed_loop_rhp_poles, Some(0));
    assert!((n.g_at_infinity - 2.0).abs() < 1e-15);
}

#[test]
fn cli_nyquist_of_a_discrete_plant() {
    let dir = std::env::temp_dir().join(format!("ltikit-dnyq-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("n.png");
    let path = png.to_str().unwrap();
    let doc = json(&[
        "nyquist",
        "--num",
        "0.8",
        "--den",
        "1 -1.5 0.5",
        "--dt",
        "0.1",
        "-o",
        path,
        "--json",
    ]);
    assert_eq!(doc["dt"], 0.1);
    let p = &doc["plants"][0];
    assert_eq!(p["encirclements"], 2);
    assert_eq!(p["open_loop_rhp_poles"], 0);
    assert_eq!(p["closed_loop_rhp_poles"], 2);
    assert_eq!(p["region"], "outside the unit circle");
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    // a continuous plant keeps the half plane
    let doc = json(&[
        "nyquist", "--num", "2", "--den", "1 3 2 0", "-o", path, "--json",
    ]);
    assert_eq!(doc["plants"][0]["region"], "right half plane");
    // improper in z: one line, exit 1
    let out = ltikit(&[
        "nyquist", "--num", "1 0 0", "--den", "1 0.5", "--dt", "0.1", "-o", path,
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(out.stdout.is_empty());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bode_of_a_discrete_plant_marks_the_nyquist_frequency() {
    use ltikit::plot::{BodeSeries, PlotOptions, bode_png};
    let dir = std::env::temp_dir().join(format!("ltikit-dbode-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("b.png");
    let path = png.to_str().unwrap();
    // the response ends at π/T = 10π rad/s (T = 0.1), the marker stands there
    let doc = json(&[
        "bode",
        "--num",
        "1",
        "--den",
        "1 -1.5 0.5",
        "--dt",
        "0.1",
        "-o",
        path,
        "--json",
    ]);
    let hi = doc["w_range"][1].as_f64().unwrap();
    assert!((hi - std::f64::consts::PI / 0.1).abs() < 1e-12, "{hi}");
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    // through the library: the series carries π/T; a bad one is refused, no file left
    let g = loop_z(1.0, &[1.0], &[1.0, -0.5], 0.5);
    let w: Vec<f64> = (1..=50)
        .map(|i| f64::from(i) * std::f64::consts::PI / 0.5 / 50.0)
        .collect();
    let fr = g.freq_response(&w).unwrap();
    let s = BodeSeries::new(&fr)
        .label("1/(z - 0.5)")
        .sampling_period(0.5);
    assert!((s.nyquist_frequency.unwrap() - 2.0 * std::f64::consts::PI).abs() < 1e-12);
    let png2 = dir.join("lib.png");
    bode_png(&png2, &[s], &PlotOptions::default()).unwrap();
    assert!(std::fs::metadata(&png2).unwrap().len() > 1000);
    let mut bad = s;
    bad.nyquist_frequency = Some(f64::NAN);
    let png3 = dir.join("bad.png");
    assert!(bode_png(&png3, &[bad], &PlotOptions::default()).is_err());
    assert!(!png3.exists());
    std::fs::remove_dir_all(&dir).ok();
}
