//! Other projects' own state-space test values (issue 24, "Targets"): every pole, zero,
//! minimal order, dc gain and margin that their test suites state for a state-space model and
//! that ltikit supports, to their tolerance — or, where a stated value is itself only
//! approximate, to a 50-digit reference, with the stated value's own error recorded.
//!
//! Sources:
//! - python-control, `control/tests/statesp_test.py` and `margin_test.py` (commit e60e5ebc):
//!   `assert_array_almost_equal` (6 decimals) and `assert_allclose(atol=1.5e-2)`;
//! - harold, `harold/tests/test_system_funcs.py` `test_minimal_realization_State` (commit
//!   2b06ccc): exact orders (python-control's `minreal`, i.e. SLICOT's TB01PD, for comparison:
//!   slycot 0.7.1);
//! - ControlSystems.jl, `lib/ControlSystemsBase/test/test_analysis.jl` and
//!   `test_simplification.jl` (commit b2b7dc43): `≈` (rtol √ε) unless stated. The models of
//!   test_analysis.jl are copied verbatim into `tests/data/controlsystems_ss.json`; their
//!   50-digit references come from `tests/data/controlsystems_ss_reference.py` (mpmath on the
//!   stored doubles).

use nalgebra::DMatrix;
use num_complex::Complex64;
use serde_json::Value;

mod common;
use common::{json, json_matrix, rel};

use ltikit::numeric::linalg::{minimal_realization, transmission_zeros};

fn m(r: usize, c: usize, v: &[f64]) -> DMatrix<f64> {
    DMatrix::from_row_slice(r, c, v)
}

fn rows(m: &DMatrix<f64>) -> String {
    (0..m.nrows())
        .map(|i| {
            (0..m.ncols())
                .map(|j| format!("{:e}", m[(i, j)]))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// `ltikit <command> --json` on a state-space model.
fn run(
    command: &str,
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
) -> Value {
    let (a, b, c, d) = (
        format!("--a={}", rows(a)),
        format!("--b={}", rows(b)),
        format!("--c={}", rows(c)),
        format!("--d={}", rows(d)),
    );
    json(&[command, "--json", &a, &b, &c, &d])
}

fn values(v: &Value) -> Vec<Complex64> {
    let mut z: Vec<Complex64> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|e| {
            let x = e.get("value").unwrap_or(e);
            Complex64::new(x[0].as_f64().unwrap(), x[1].as_f64().unwrap())
        })
        .collect();
    z.sort_by(|a, b| a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im)));
    z
}

fn assert_close(got: &[Complex64], want: &[Complex64], tol: f64) {
    let mut want = want.to_vec();
    want.sort_by(|a, b| a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im)));
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).norm() <= tol, "{got:?} vs {want:?} (tol {tol:e})");
    }
}

fn re(v: &[f64]) -> Vec<Complex64> {
    v.iter().map(|&x| Complex64::new(x, 0.0)).collect()
}

/// python-control's tolerance: `assert_array_almost_equal`, 6 decimals.
const PC6: f64 = 1.5e-6;

/// python-control's `sys322`: 3 states, 2×2, D ≠ 0.
fn sys322() -> [DMatrix<f64>; 4] {
    [
        m(3, 3, &[-3., 4., 2., -1., -3., 0., 2., 5., 3.]),
        m(3, 2, &[1., 4., -3., -3., -2., 1.]),
        m(2, 3, &[4., 2., -3., 1., 4., 3.]),
        m(2, 2, &[-2., 4., 0., 1.]),
    ]
}

#[test]
fn python_control_poles_and_zeros() {
    let [a, b, c, d] = sys322();
    let r = run("analyze", &a, &b, &c, &d);
    let ss = &r["state_space"];
    // test_pole
    assert_close(
        &values(&ss["eigenvalues"]),
        &[
            Complex64::new(3.34747678408874, 0.0),
            Complex64::new(-3.17373839204437, 1.47492908003839),
            Complex64::new(-3.17373839204437, -1.47492908003839),
        ],
        PC6,
    );
    // test_zero_mimo_sys322_square
    assert_close(
        &values(&ss["invariant_zeros"]),
        &re(&[44.41465, -0.490252, -5.924398]),
        PC6,
    );
    // test_zero_mimo_sys222_square
    let r = run(
        "analyze",
        &m(2, 2, &[4., 1., 2., -3.]),
        &m(2, 2, &[5., 2., -3., -3.]),
        &m(2, 2, &[2., -4., 0., 1.]),
        &m(2, 2, &[3., 2., 1., -1.]),
    );
    assert_close(
        &values(&r["state_space"]["invariant_zeros"]),
        &re(&[-10.568501, 3.368501]),
        PC6,
    );
    // test_zero_mimo_sys623_non_square: 6 states, 3 outputs, 2 inputs.
    let mut a = DMatrix::zeros(6, 6);
    for (i, v) in [1., 1., 3., -4., -1., 3.].into_iter().enumerate() {
        a[(i, i)] = v;
    }
    let b = m(6, 2, &[0., -1., -1., 0., 1., -1., 0., 0., 0., 1., -1., -1.]);
    let c = m(
        3,
        6,
        &[
            1., 0., 0., 1., 0., 0., 0., 1., 0., 1., 0., 1., 0., 0., 1., 0., 0., 1.,
        ],
    );
    let r = run("analyze", &a, &b, &c, &DMatrix::zeros(3, 2));
    assert_close(
        &values(&r["state_space"]["invariant_zeros"]),
        &re(&[2., -1.]),
        PC6,
    );
    assert_eq!(r["state_space"]["system_pencil"]["normal_rank"], 2);
}

/// python-control's `test_minreal` (statesp_test.py and minreal_test.py `testMinrealSS`):
/// three states, minimal order 2 with eigenvalues −2.136154 and −0.1638459.
#[test]
fn python_control_minreal() {
    let a = m(3, 3, &[-2., 0.5, 0., 0.5, -0.3, 0., 0., 0., -0.1]);
    let b = m(3, 2, &[0.3, -1.3, 0.1, 0., 1., 0.]);
    let c = m(2, 3, &[0., 0.1, 0., -0.3, -0.2, 0.]);
    let d = m(2, 2, &[0., -0.8, -0.3, 0.]);
    let mr = minimal_realization(&a, &b, &c, &d, None).unwrap();
    assert_eq!(mr.order(), 2);
    let eig = ltikit::numeric::eigenvalues(&mr.a).unwrap();
    let mut eig: Vec<Complex64> = eig.into_iter().collect();
    eig.sort_by(|a, b| a.re.total_cmp(&b.re));
    assert_close(&eig, &re(&[-2.136154, -0.1638459]), PC6);
    let r = run("analyze", &a, &b, &c, &d);
    assert_eq!(r["state_space"]["minimal_order"], 2);
}

/// python-control's `test_dc_gain_cont` and `test_dc_gain_discr`. (Its
/// `test_dc_gain_integrator` is not taken over: it expects ∞ in *every* entry of a MIMO model
/// whose A is singular, while ltikit gives each channel its own dc gain — an entry that does
/// not see the integrator has a finite one.)
#[test]
fn python_control_dc_gain() {
    let one = |x: f64| m(1, 1, &[x]);
    let r = run("analyze", &one(-2.), &one(6.), &one(5.), &one(0.));
    assert!(rel(r["dc_gain"].as_f64().unwrap(), 15.0) < 1e-15);
    let r = run(
        "analyze",
        &one(-2.),
        &m(1, 2, &[6., 4.]),
        &m(3, 1, &[5., 7., 11.]),
        &DMatrix::zeros(3, 2),
    );
    let want = [[15., 10.], [21., 14.], [33., 22.]];
    for (i, row) in want.iter().enumerate() {
        for (j, w) in row.iter().enumerate() {
            let g = r["state_space"]["dc_gain"][i][j].as_f64().unwrap();
            assert!(rel(g, *w) < 1e-15, "{g} vs {w}");
        }
    }
    // An integrator: infinite (null in JSON, "∞"/"infinite" in words).
    let r = run("analyze", &one(0.), &one(1.), &one(1.), &one(0.));
    assert!(r["dc_gain"].is_null(), "{}", r["dc_gain"]);
    // Discrete (dt = 1): averaging filter 1, differencer 0, summer ∞.
    for (a, b, c, d, want) in [
        (0.5, 0.5, 1., 0., Some(1.0)),
        (0., 1., -1., 1., Some(0.0)),
        (1., 1., 1., 0., None),
    ] {
        let out = json(&[
            "analyze",
            "--json",
            "--dt",
            "1",
            &format!("--a={a}"),
            &format!("--b={b}"),
            &format!("--c={c}"),
            &format!("--d={d}"),
        ]);
        match want {
            Some(w) => assert!((out["dc_gain"].as_f64().unwrap() - w).abs() < 1e-15),
            None => assert!(out["dc_gain"].is_null(), "{}", out["dc_gain"]),
        }
    }
}

/// python-control's margin_test.py, the StateSpace case: no phase crossing (gain margin ∞),
/// phase margin 147.0743° at 2.5483 rad/s (`atol=1.5e-2`). The plant is
/// (s − 18)/((s − 5)(s + 2)); ltikit's crossing agrees with the closed form |G(jω)| = 1,
/// (ω² + 25)(ω² + 4) = ω² + 324 ⇒ ω⁴ + 28ω² − 224 = 0 ⇒ ω² = (√1680 − 28)/2, to rounding.
#[test]
fn python_control_state_space_margins() {
    let r = run(
        "margins",
        &m(2, 2, &[1., 4., 3., 2.]),
        &m(2, 1, &[1., -4.]),
        &m(1, 2, &[1., 0.]),
        &m(1, 1, &[0.]),
    );
    assert!(r["gain_margin"].is_null(), "{r}");
    assert!((r["phase_margin_deg"].as_f64().unwrap() - 147.0743).abs() < 1.5e-2);
    let w = r["gain_crossover"].as_f64().unwrap();
    assert!((w - 2.5483).abs() < 1.5e-2);
    // |G(jω)|² = (ω² + 324)/((ω² + 25)(ω² + 4)) = 1  ⇔  ω⁴ + 28ω² − 224 = 0.
    let w2 = (1680.0f64.sqrt() - 28.0) / 2.0;
    assert!(rel(w, w2.sqrt()) < 1e-14, "{w} vs {}", w2.sqrt());
}

fn cs_model(name: &str) -> [DMatrix<f64>; 4] {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/controlsystems_ss.json"
    ))
    .unwrap();
    let v: Value = serde_json::from_str(&text).unwrap();
    let mat = |key: &str| json_matrix(&v[name][key]);
    [mat("a"), mat("b"), mat("c"), mat("d")]
}

/// (w, margin) pairs.
type Pairs = Vec<(f64, f64)>;

/// (w, gain margin) of each phase crossing and (w, phase margin) of each gain crossing.
fn crossings(r: &Value) -> (Pairs, Pairs) {
    let pc = r["phase_crossings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| (x["w"].as_f64().unwrap(), x["gain_margin"].as_f64().unwrap()))
        .collect();
    let gc = r["gain_crossings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| {
            (
                x["w"].as_f64().unwrap(),
                x["phase_margin_deg"].as_f64().unwrap(),
            )
        })
        .collect();
    (pc, gc)
}

fn assert_pairs(got: &[(f64, f64)], want: &[(f64, f64)], tol: f64) {
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(want) {
        let e0 = if w.0 == 0.0 { g.0.abs() } else { rel(g.0, w.0) };
        assert!(
            e0 <= tol && rel(g.1, w.1) <= tol,
            "{got:?} vs {want:?} (tol {tol:e})"
        );
    }
}

/// ControlSystems.jl's `marginplottest` (18 states, a plant with a controller): the issue's
/// "margins through a state-space realisation lose digits" (1.6e-3 relative) was measured
/// against the values this test *states*. Against 50 digits on the same matrices, ltikit is
/// right to 1e-12 and the stated values are the approximate ones: 0.9788420039794175 rad/s
/// and 0.19398511072183675 (true 0.97871238717759325 and 0.19393629693478623, off by
/// 1.3e-4 and 2.5e-4), 21.96146912516854 / 11.886085245062574 (true 21.958472756828809 /
/// 11.882924806301116), 3.484166418318219 rad/s / 50.783187269018754° (true
/// 3.4833800272600187 / 50.781183985461914).
#[test]
fn controlsystems_marginplottest_against_fifty_digits() {
    let [a, b, c, d] = cs_model("marginplottest");
    let r = run("margins", &a, &b, &c, &d);
    let (pc, gc) = crossings(&r);
    assert_pairs(
        &pc,
        &[
            (0.978_712_387_177_593_2, 0.193_936_296_934_786_2),
            (21.958_472_756_828_81, 11.882_924_806_301_116),
        ],
        1e-12,
    );
    assert_pairs(
        &gc,
        &[(3.483_380_027_260_018_7, 50.781_183_985_461_914)],
        1e-12,
    );
    // The stated values, to the error they carry.
    assert_pairs(
        &pc,
        &[
            (0.978_842_003_979_417_5, 0.193_985_110_721_836_75),
            (21.961_469_125_168_54, 11.886_085_245_062_574),
        ],
        3e-4,
    );
}

/// ControlSystems.jl issue 1045 ("requires negative frequencies"): the phase crossings at
/// ω = 0 and ω ≈ 1.2311 with gain margins ≈ 0.8734 and ≈ 2.0051 (`atol=1e-3`); 50 digits
/// give 0.87336475646163444 and, at 1.2311698256015636, 2.0052464257102133.
#[test]
fn controlsystems_negative_frequency_margins() {
    let [a, b, c, d] = cs_model("negative_frequency");
    let r = run("margins", &a, &b, &c, &d);
    let (pc, gc) = crossings(&r);
    assert_pairs(
        &pc,
        &[
            (0.0, 0.873_364_756_461_634_4),
            (1.231_169_825_601_563_6, 2.005_246_425_710_213_3),
        ],
        1e-12,
    );
    // The stated values, at the test's atol = 1e-3.
    for (g, w) in pc.iter().zip([
        (0.0, 0.873_364_756_461_634_4),
        (1.231_103_882_989_177_8, 2.005_125_180_939_021),
    ]) {
        assert!((g.0 - w.0).abs() < 1e-3 && (g.1 - w.1).abs() < 1e-3);
    }
    assert_pairs(
        &gc,
        &[(0.383_055_279_058_836_95, 10.600_435_069_269_298)],
        1e-12,
    );
}

/// ControlSystems.jl's "system with RHP poles and zeros but stable in closed loop": phase
/// margin stated 27.406506322937503°; 50 digits give 27.40874987905145° at
/// 7.8132332779339543 rad/s (the stated value is 8e-5 low).
#[test]
fn controlsystems_rhp_loop_phase_margin() {
    let [a, b, c, d] = cs_model("rhp_stable_loop");
    let r = run("margins", &a, &b, &c, &d);
    let (pc, gc) = crossings(&r);
    assert_pairs(
        &gc,
        &[(7.813_233_277_933_954, 27.408_749_879_051_45)],
        1e-12,
    );
    assert_pairs(
        &pc,
        &[
            (1.020_050_859_472_174_8, 0.390_651_275_467_997),
            (15.620_502_848_738_085, 1.860_666_718_211_951_4),
        ],
        1e-12,
    );
    assert!((gc[0].1 - 27.406_506_322_937_503).abs() < 2.5e-3);
}

/// ControlSystems.jl's "difficult test case for zeros": 4 states, an input entry of 5e8 into
/// a state whose couplings are 1e-18. The test asks for three zeros equal (rtol √ε, norm-wise)
/// to those computed in BigFloat; 50 digits give 0.46272616859387398, −5.1e-33 (0 in
/// double) and −2.0315310359716338e-9.
///
/// Before the staircases balanced the system matrix, the channel's minimal realisation had
/// order 1 (three "uncontrollable" modes at the zeros), its zero near the origin came out as
/// −2.334e-7 and its dc gain as −42.16; the dc gain of the model as stored is 1493.22 (G(s)
/// at s = 1e-20 and 1e-25 in 60 digits: 1493.21956, 1493.22025).
#[test]
fn controlsystems_difficult_zeros() {
    let [a, b, c, d] = cs_model("difficult_zeros");
    let want = [-2.031_531_035_971_633_8e-9, 0.0, 0.462_726_168_593_874];
    let r = run("analyze", &a, &b, &c, &d);
    // The whole model's invariant zeros and the channel's zeros, each within 1e-13 absolute
    // (the model's norm is 5e8).
    for zs in [&r["state_space"]["invariant_zeros"], &r["zeros"]] {
        let got = values(zs);
        assert_close(&got, &re(&want), 1e-13);
    }
    assert_eq!(r["state_space"]["minimal_order"], 3);
    assert!(
        rel(r["dc_gain"].as_f64().unwrap(), 1493.22) < 1e-5,
        "{}",
        r["dc_gain"]
    );
    // The library's transmission zeros (of the minimal realisation): the zero at the origin
    // cancels the uncontrollable mode there.
    let tz = transmission_zeros(&a, &b, &c, &d, None).unwrap();
    let mut got = tz.zeros.clone();
    got.sort_by(|a, b| a.re.total_cmp(&b.re));
    assert_close(&got, &re(&[want[0], want[2]]), 1e-13);
}

/// ControlSystems.jl test_simplification.jl: P = [1/(s+1) 2/(s+3); 1/(s+1) 1/(s+1)] has a
/// minimal realisation of order 3 (from a 4-state one here: each entry its own state), and
/// example 5.5 of Lund's FRTN10 exercises, G = [1/(s+2) −1/(s+2); 1/(s+2) (s+1)/(s+2)], has
/// minimal A = [−2] and no transmission zeros.
#[test]
fn controlsystems_minreal() {
    let a = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![-1., -3., -1., -1.]));
    let b = m(4, 2, &[1., 0., 0., 1., 1., 0., 0., 1.]);
    let c = m(2, 4, &[1., 2., 0., 0., 0., 0., 1., 1.]);
    let mr = minimal_realization(&a, &b, &c, &DMatrix::zeros(2, 2), None).unwrap();
    assert_eq!(mr.order(), 3);

    let a = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![-2.; 4]));
    let b = m(4, 2, &[1., 0., 0., 1., 1., 0., 0., 1.]);
    let c = m(2, 4, &[1., -1., 0., 0., 0., 0., 1., -1.]);
    let d = m(2, 2, &[0., 0., 0., 1.]);
    let mr = minimal_realization(&a, &b, &c, &d, None).unwrap();
    assert_eq!(mr.order(), 1);
    assert!((mr.a[(0, 0)] + 2.0).abs() < 1e-14, "{}", mr.a);
    assert!(
        transmission_zeros(&a, &b, &c, &d, None)
            .unwrap()
            .zeros
            .is_empty()
    );
}

/// harold's `test_minimal_realization_State`: minimal orders 2 and 3 (the first has the
/// issue's defective eigenvalue: −6 of algebraic multiplicity 3, geometric 2, observability
/// rank 2; before the minimal realisation checked its order against that rank, ltikit said
/// 3, as SLICOT's TB01PD does).
#[test]
fn harold_minimal_realizations() {
    // M = [A B; C D] sliced with a 1×4 south-west corner: 4 states, 3 inputs, 1 output.
    let mm = m(
        5,
        7,
        &[
            -6.5, 0.5, 6.5, -6.5, 0., 1., 0., //
            -0.5, -5.5, -5.5, 5.5, 2., 1., 2., //
            -0.5, 0.5, 0.5, -6.5, 3., 4., 3., //
            -0.5, 0.5, -5.5, -0.5, 3., 2., 3., //
            1., 1., 0., 0., 0., 0., 0.,
        ],
    );
    let (a, b) = (
        mm.view((0, 0), (4, 4)).into_owned(),
        mm.view((0, 4), (4, 3)).into_owned(),
    );
    let (c, d) = (
        mm.view((4, 0), (1, 4)).into_owned(),
        mm.view((4, 4), (1, 3)).into_owned(),
    );
    assert_eq!(
        minimal_realization(&a, &b, &c, &d, None).unwrap().order(),
        2
    );
    let r = run("analyze", &a, &b, &c, &d);
    assert_eq!(r["state_space"]["minimal_order"], 2);

    // The second model: 5 states, exact minimal order 4 (sympy: the observability matrix has
    // rank 4 for every value of the entry −0.1; the eigenvalue 1 is unobservable). The
    // observability staircase meets a last block of 1.0e-13 against its tolerance
    // n²·ε·‖·‖ = 2.4e-14 (the subdiagonal 3.2e-3 before it amplifies the rounding) and keeps
    // 5, as SLICOT's TB01PD (python-control's `minreal`) does; the eigenvector test after the
    // staircases finds ‖C·v‖ = 1.1e-16 for the eigenvalue 1 and removes it (harold: 4, through
    // its cancellation distance with tol = 1e-6).
    let a = m(
        5,
        5,
        &[
            0., 1., 0., 0., 0., //
            -0.1, -0.5, 1., -1., 0., //
            0., 0., 0., 1., 0., //
            0., 0., 0., 0., 1., //
            0., 3.5, 1., -2., 2.,
        ],
    );
    let b = m(5, 1, &[0., 1., 0., 0., 1.]);
    let c = m(1, 5, &[0., 3.5, 1., -1., 0.]);
    let d = m(1, 1, &[1.]);
    let min = minimal_realization(&a, &b, &c, &d, None).unwrap();
    assert_eq!(min.order(), 4);
    assert!(min.uncontrollable.is_empty());
    assert_eq!(min.unobservable.len(), 1);
    assert!((min.unobservable[0] - Complex64::new(1.0, 0.0)).norm() < 1e-13);
    // the same transfer function: G of the 4-state realisation against the 5-state model
    for s in [
        Complex64::new(0.3, 0.7),
        Complex64::new(-2.0, 5.0),
        Complex64::new(10.0, 0.1),
    ] {
        let g = |a: &DMatrix<f64>, b: &DMatrix<f64>, c: &DMatrix<f64>| {
            let n = a.nrows();
            let m = DMatrix::<Complex64>::identity(n, n) * s - a.map(|x| Complex64::new(x, 0.0));
            let x = m.lu().solve(&b.map(|x| Complex64::new(x, 0.0))).unwrap();
            (c.map(|x| Complex64::new(x, 0.0)) * x)[(0, 0)] + 1.0
        };
        let (g5, g4) = (g(&a, &b, &c), g(&min.a, &min.b, &min.c));
        assert!((g5 - g4).norm() <= 1e-13 * g5.norm(), "{s}: {g5} {g4}");
    }
    let r = run("analyze", &a, &b, &c, &d);
    assert_eq!(r["state_space"]["minimal_order"], 4);
    assert_eq!(r["state_space"]["observability"]["rank"], 4);

    let a = m(
        4,
        4,
        &[
            -2., 0., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., -12., 4., 3.,
        ],
    );
    let b = m(4, 2, &[1., 0., 0., 0., 0., 0., 0., 1.]);
    let c = m(2, 4, &[1., -9., 0., 0., 0., -20., 0., 5.]);
    let d = m(2, 2, &[0., 0., 0., 1.]);
    assert_eq!(
        minimal_realization(&a, &b, &c, &d, None).unwrap().order(),
        3
    );
}
