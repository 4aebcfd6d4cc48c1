//! Sampling (c2d) and its inverse (d2c): closed forms, scipy and mpmath references, round
//! trips, multiplicities, and the refusals.

mod common;

use common::{c, rel, tf};
use ltikit::analysis::Factored;
use ltikit::lti::{Discretization, Domain};
use ltikit::{LtiError, Root, StateSpace, TransferFunction};
use nalgebra::DMatrix;
use proptest::prelude::*;

const ZOH: Discretization = Discretization::Zoh;
const TUSTIN: Discretization = Discretization::Tustin { prewarp: None };

fn m(rows: &[&[f64]]) -> DMatrix<f64> {
    let cols = rows.first().map_or(0, |r| r.len());
    DMatrix::from_fn(rows.len(), cols, |i, j| rows[i][j])
}

/// Largest |a − b| over the entries, relative to max |b| (and at least the absolute error
/// for a zero reference).
fn mat_err(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    assert_eq!(a.shape(), b.shape());
    let scale = b.abs().max().max(1e-300);
    (a - b).abs().max() / scale
}

/// The 3-state, 2-input, 2-output model of the scipy references.
fn mimo(d: &[&[f64]]) -> StateSpace {
    StateSpace::new(
        m(&[&[-1.0, 2.0, 0.0], &[-2.0, -1.0, 1.0], &[0.5, 0.0, -3.0]]),
        m(&[&[1.0, 0.0], &[0.0, 1.0], &[1.0, -1.0]]),
        m(&[&[1.0, 0.0, 1.0], &[0.0, 1.0, 0.0]]),
        m(d),
    )
    .unwrap()
}

const D_MIMO: &[&[f64]] = &[&[0.0, 0.5], &[0.0, 0.0]];

#[test]
fn zoh_of_a_first_order_lag_is_its_closed_form() {
    // 1/(s + a) → ((1 − e^(−aT))/a) / (z − e^(−aT)) (the ZOH equivalent, exact)
    let mut worst = 0.0f64;
    for (a, t) in [
        (2.0f64, 0.1f64),
        (0.5, 0.01),
        (10.0, 0.3),
        (1.0, 1e-4),
        (3.0, 2.0),
    ] {
        let want_pole = (-a * t).exp();
        let want_gain = -(-a * t).exp_m1() / a;
        let g = tf(&[1.0], &[1.0, a]).c2d(t, ZOH).unwrap();
        assert_eq!(g.domain(), Domain::discrete(t).unwrap());
        assert_eq!(g.den().degree(), 1);
        let e1 = rel(g.den().coeff(0), -want_pole);
        let e2 = rel(g.num().coeff(0), want_gain);
        assert!(
            e1 <= 1e-15 && e2 <= 1e-15,
            "a = {a}, T = {t}: {e1:e} {e2:e}"
        );
        // the factored form maps the pole exactly
        let f = tf(&[1.0], &[1.0, a])
            .factored()
            .unwrap()
            .c2d(t, ZOH)
            .unwrap();
        assert_eq!(f.poles()[0].value, c(want_pole, 0.0));
        let e3 = rel(f.gain(), want_gain);
        assert!(e3 <= 1e-15, "{e3:e}");
        worst = worst.max(e1).max(e2).max(e3);
    }
    println!("ZOH 1/(s + a): worst relative error {worst:.1e}");
}

#[test]
fn zoh_of_an_underdamped_second_order_plant_is_its_closed_form() {
    // wn²/(s² + 2ζwn s + wn²) with σ = ζwn, wd = wn√(1 − ζ²) (Franklin, Powell & Workman,
    // Digital Control of Dynamic Systems, table of ZOH equivalents):
    //   a1 = −2e^(−σT)cos(wd T), a0 = e^(−2σT),
    //   b1 = 1 − e^(−σT)(cos wd T + (σ/wd) sin wd T),
    //   b0 = e^(−2σT) + e^(−σT)((σ/wd) sin wd T − cos wd T)
    let mut worst = 0.0f64;
    for (wn, zeta, t) in [(2.0, 0.2, 0.1), (10.0, 0.05, 0.02), (1.0, 0.7, 0.5)] {
        let (sigma, wd) = (zeta * wn, wn * (1.0f64 - zeta * zeta).sqrt());
        let (e, (s, co)) = ((-sigma * t).exp(), (wd * t).sin_cos());
        let a1 = -2.0 * e * co;
        let a0 = e * e;
        let b1 = 1.0 - e * (co + sigma / wd * s);
        let b0 = e * e + e * (sigma / wd * s - co);
        let g = tf(&[wn * wn], &[1.0, 2.0 * zeta * wn, wn * wn])
            .c2d(t, ZOH)
            .unwrap();
        let errs = [
            rel(g.den().coeff(1), a1),
            rel(g.den().coeff(0), a0),
            rel(g.num().coeff(1), b1),
            rel(g.num().coeff(0), b0),
        ];
        let e = errs.iter().copied().fold(0.0, f64::max);
        assert!(e <= 1e-13, "wn = {wn}, ζ = {zeta}: {errs:?}");
        // the factored form: poles e^((−σ ± j wd)T) exactly, the same zero and gain
        let f = tf(&[wn * wn], &[1.0, 2.0 * zeta * wn, wn * wn])
            .factored()
            .unwrap()
            .c2d(t, ZOH)
            .unwrap();
        assert!(rel(f.gain(), b1) <= 1e-13, "{} {b1}", f.gain());
        assert!((f.zeros()[0].value.re + b0 / b1).abs() <= 1e-12 * (b0 / b1).abs());
        worst = worst.max(e);
    }
    println!("ZOH second order: worst relative coefficient error {worst:.1e}");
}

// Reference values: scipy.signal.cont2discrete (scipy 1.17.1, numpy float64) on the model of
// `mimo`, T = 0.1, printed with repr() — run in a throwaway venv:
//   python3 -m venv /tmp/v && /tmp/v/bin/pip install scipy mpmath
//   cont2discrete((A, B, C, D), 0.1, method=…)   (D = 0 for 'impulse')
const SCIPY_AD: &[&[f64]] = &[
    &[
        0.8869438879077807,
        0.17977067330052918,
        0.008445329197696283,
    ],
    &[-0.1776593410011051, 0.8869438879077806, 0.08144000745256831],
    &[
        0.04072000372628415,
        0.0042226645988481405,
        0.7409545313980365,
    ],
];
const SCIPY_ZOH_BD: &[&[f64]] = &[
    &[0.0948428056947249, 0.009033172754186023],
    &[-0.004883988599899098, 0.09017925842850946],
    &[0.08858228924101391, -0.0862505156079062],
];
const SCIPY_FOH_BD: &[&[f64]] = &[
    &[0.08947764266551964, 0.016698359654382548],
    &[-0.009523429652407479, 0.08065876290824188],
    &[0.0785978226800354, -0.07418838280139653],
];
const SCIPY_FOH_DD: &[&[f64]] = &[
    &[0.09440148255761369, 0.4577733540115186],
    &[-0.0016392086573783092, 0.04671085033600067],
];
const SCIPY_TUSTIN: [&[&[f64]]; 4] = [
    &[
        &[
            0.8878248974008207,
            0.17979284737150675,
            0.007817080320500292,
        ],
        &[
            -0.17783857729138164,
            0.8878248974008208,
            0.08207934336525308,
        ],
        &[
            0.041039671682626545,
            0.003908540160250148,
            0.7393003713113153,
        ],
    ],
    &[
        &[0.09478209888606605, 0.008598788352550322],
        &[-0.0047879616963064295, 0.09028727770177838],
        &[0.0890170021496971, -0.08676959155755327],
    ],
    &[
        &[0.9644322845417236, 0.09185069376587844, 0.8735587258159079],
        &[
            -0.08891928864569083,
            0.9439124487004105,
            0.04103967168262655,
        ],
    ],
    &[
        &[0.09189955051788157, 0.46091459839749854],
        &[-0.0023939808481532147, 0.04514363885088919],
    ],
];
// Tustin prewarped at ω = 5 rad/s: scipy has no prewarp option; its 'bilinear' at the
// period T' = 2·tan(ωT/2)/ω = 0.1021367684884145 is the same map (2/T' = ω/tan(ωT/2)).
const SCIPY_PREWARP: [&[&[f64]]; 4] = [
    &[
        &[0.8852210201376126, 0.1831949145932549, 0.0081125793340972],
        &[-0.1811667697597306, 0.8852210201376126, 0.08348487796253025],
        &[
            0.04174243898126513,
            0.004056289667048601,
            0.7344764228807467,
        ],
    ],
    &[
        &[0.09668948776028927, 0.008941171971387779],
        &[-0.004988456384000504, 0.09201175361527272],
        &[0.0907086273393777, -0.08836976026686943],
    ],
    &[
        &[0.9634817295594389, 0.09362560213015175, 0.8712945011074221],
        &[-0.0905833848798653, 0.9426105100688063, 0.04174243898126513],
    ],
    &[
        &[0.09369905754983349, 0.46028570585225914],
        &[-0.002494228192000252, 0.04600587680763636],
    ],
];
const SCIPY_IMPULSE_BD: &[&[f64]] = &[
    &[0.0895389217105477, 0.01713253441028329],
    &[-0.009621933354853677, 0.08055038804552123],
    &[0.07816745351243208, -0.07367318667991885],
];
const SCIPY_IMPULSE_DD: &[&[f64]] = &[&[0.2, -0.1], &[0.0, 0.1]];

// ZOH of the same model to 30 digits: mpmath 1.3 (mp.dps = 30), mp.expm of the augmented
// matrix [[A, B], [0, 0]]·T with T = mpf('0.1'); the first three rows are [A_d, B_d].
const MPMATH_ZOH: [[&str; 5]; 3] = [
    [
        "0.886943887907780613860589077591",
        "0.179770673300529174986957839837",
        "0.00844532919769628181539642250249",
        "0.0948428056947249048681203262536",
        "0.00903317275418602298895097856952",
    ],
    [
        "-0.177659341001105104533108734211",
        "0.886943887907780613860589077591",
        "0.081440007452568305678082497416",
        "-0.00488398859989909972794708682665",
        "0.0901792584285094580802561979521",
    ],
    [
        "0.040720003726284152839041248708",
        "0.00422266459884814090769821125125",
        "0.740954531398036566135216927764",
        "0.0885822892410139111532673288851",
        "-0.0862505156079061877593352647343",
    ],
];

#[test]
fn mimo_zoh_matches_scipy_and_a_30_digit_reference() {
    let d = mimo(D_MIMO).c2d(0.1, ZOH).unwrap();
    let e_scipy = mat_err(&d.a, &m(SCIPY_AD)).max(mat_err(&d.b, &m(SCIPY_ZOH_BD)));
    assert!(e_scipy <= 1e-14, "{e_scipy:e}");
    assert_eq!(d.c, mimo(D_MIMO).c);
    assert_eq!(d.d, mimo(D_MIMO).d);
    // the 30-digit reference: the target is 1e-13
    let mut worst = 0.0f64;
    for (i, row) in MPMATH_ZOH.iter().enumerate() {
        for (j, text) in row.iter().enumerate() {
            let want: f64 = text.parse().unwrap();
            let got = if j < 3 { d.a[(i, j)] } else { d.b[(i, j - 3)] };
            worst = worst.max((got - want).abs());
        }
    }
    assert!(worst <= 1e-15, "{worst:e}");
    println!(
        "MIMO ZOH: {e_scipy:.1e} from scipy, {worst:.1e} (absolute) from the 30-digit reference"
    );
}

#[test]
fn mimo_foh_tustin_and_impulse_match_scipy() {
    let d = mimo(D_MIMO).c2d(0.1, Discretization::Foh).unwrap();
    let foh = [
        mat_err(&d.a, &m(SCIPY_AD)),
        mat_err(&d.b, &m(SCIPY_FOH_BD)),
        mat_err(&d.d, &m(SCIPY_FOH_DD)),
    ];
    assert!(foh.iter().all(|e| *e <= 1e-14), "FOH {foh:?}");
    for (method, want) in [
        (TUSTIN, SCIPY_TUSTIN),
        (Discretization::Tustin { prewarp: Some(5.0) }, SCIPY_PREWARP),
    ] {
        let d = mimo(D_MIMO).c2d(0.1, method).unwrap();
        let errs = [
            mat_err(&d.a, &m(want[0])),
            mat_err(&d.b, &m(want[1])),
            mat_err(&d.c, &m(want[2])),
            mat_err(&d.d, &m(want[3])),
        ];
        assert!(errs.iter().all(|e| *e <= 1e-14), "{method:?} {errs:?}");
    }
    let zero_d: &[&[f64]] = &[&[0.0, 0.0], &[0.0, 0.0]];
    let d = mimo(zero_d).c2d(0.1, Discretization::Impulse).unwrap();
    let imp = [
        mat_err(&d.a, &m(SCIPY_AD)),
        mat_err(&d.b, &m(SCIPY_IMPULSE_BD)),
        mat_err(&d.d, &m(SCIPY_IMPULSE_DD)),
    ];
    assert!(imp.iter().all(|e| *e <= 1e-14), "impulse {imp:?}");
    // scipy refuses D ≠ 0 for 'impulse'; so do we
    let e = mimo(D_MIMO)
        .c2d(0.1, Discretization::Impulse)
        .unwrap_err()
        .to_string();
    assert!(e.contains("D = 0") && e.contains("0.5"), "{e}");
}

#[test]
fn mapped_poles_are_exponentials_of_the_factored_poles() {
    // (s + 1)(s + 2)(s² + 2s + 5) and a zero at −3: ZOH poles e^(pT) to 1e-15 relative
    let g = tf(&[1.0, 3.0], &[1.0, 5.0, 13.0, 19.0, 10.0]);
    let f = g.factored().unwrap();
    let t = 0.05;
    let d = f.c2d(t, ZOH).unwrap();
    assert_eq!(d.domain(), Domain::discrete(t).unwrap());
    let mut worst = 0.0f64;
    assert_eq!(f.poles().len(), d.poles().len());
    for p in f.poles() {
        let want = (p.value * t).exp();
        let q = d
            .poles()
            .iter()
            .min_by(|a, b| (a.value - want).norm().total_cmp(&(b.value - want).norm()))
            .unwrap();
        assert_eq!(p.multiplicity, q.multiplicity);
        worst = worst.max((q.value - want).norm() / want.norm());
    }
    assert!(worst <= 1e-15, "{worst:e}");
    println!("ZOH poles against e^(pT): {worst:.1e} relative");
    // G(z) of the factored form agrees with the ZOH realisation evaluated directly; the
    // coefficients in z carry the conditioning of poles crowded near z = 1 (e^(pT) ≈ 1 + pT)
    let gd = g.c2d(t, ZOH).unwrap();
    let sd = StateSpace::from_tf(&g).unwrap().c2d(t, ZOH).unwrap();
    let (mut e_factored, mut e_coefficients) = (0.0f64, 0.0f64);
    for z in [c(0.3, 0.8), c(-0.5, 0.1), c(1.5, 0.0)] {
        let want = sd.eval_siso(z);
        e_factored = e_factored.max((d.eval(z) - want).norm() / want.norm());
        e_coefficients = e_coefficients.max((gd.eval(z) - want).norm() / want.norm());
    }
    assert!(e_factored <= 1e-12, "{e_factored:e}");
    assert!(e_coefficients <= 1e-9, "{e_coefficients:e}");
    println!(
        "G(z) against the realisation: {e_factored:.1e} (factored), {e_coefficients:.1e} (coefficients)"
    );
}

#[test]
fn a_triple_pole_stays_triple_after_zoh() {
    let f = tf(&[2.0], &[1.0, 3.0, 3.0, 1.0]).factored().unwrap();
    assert_eq!(f.poles()[0].multiplicity, 3);
    let d = f.c2d(0.2, ZOH).unwrap();
    assert_eq!(d.poles().len(), 1);
    assert_eq!(d.poles()[0].multiplicity, 3);
    assert_eq!(d.poles()[0].value, c((-0.2f64).exp(), 0.0));
    // G(z = 1) = G(s = 0) = 2
    assert!((d.eval(c(1.0, 0.0)).re - 2.0).abs() < 1e-12);
    // and back: a triple pole at −1
    let back = d.d2c(ZOH).unwrap();
    assert_eq!(back.poles()[0].multiplicity, 3);
    assert!((back.poles()[0].value - c(-1.0, 0.0)).norm() < 1e-15);
    assert!((back.eval(c(0.0, 0.0)).re - 2.0).abs() < 1e-11);
}

#[test]
fn matched_pole_zero_follows_matlab() {
    // MATLAB: c2d(tf(11, [1 1 0]), 0.1, 'matched') = 0.052339 (z + 1)/((z − 1)(z − 0.9048))
    // (MATLAB Answers 2175248): one of the two zeros at infinity goes to z = −1, and the
    // integrator's gain is matched: 11·T·(1 − e^(−T))/2.
    let want = 11.0 * 0.1 * -(-0.1f64).exp_m1() / 2.0;
    let g = tf(&[11.0], &[1.0, 1.0, 0.0]);
    let d = g.c2d(0.1, Discretization::Matched).unwrap();
    assert_eq!(d.num().degree(), 1);
    assert!(rel(d.num().coeff(1), want) <= 1e-15, "{}", d.num().coeff(1));
    assert!(rel(d.num().coeff(0), want) <= 1e-15);
    assert!((want - 0.052339).abs() < 5e-7);
    let f = g
        .factored()
        .unwrap()
        .c2d(0.1, Discretization::Matched)
        .unwrap();
    assert!(rel(f.gain(), want) <= 1e-15);
    assert_eq!(f.zeros(), &[Root::new(c(-1.0, 0.0), 1)]);
    // the dc gain of a plant without integrators is kept; a biproper plant gets no zero at −1
    let g = tf(&[0.81, 0.162], &[1.0, 2.0]);
    let d = g
        .c2d(2.0 * std::f64::consts::PI / 6.0, Discretization::Matched)
        .unwrap();
    assert!((d.eval(c(1.0, 0.0)).re - 0.081).abs() < 1e-15);
    assert_eq!(d.num().degree(), 1);
    // state space goes through the factored form (SISO only)
    let ss = StateSpace::from_tf(&tf(&[11.0], &[1.0, 1.0, 0.0])).unwrap();
    let sd = ss.c2d(0.1, Discretization::Matched).unwrap();
    let h = sd.to_tf().unwrap();
    assert!((h.eval(c(0.5, 0.2)) - f.eval(c(0.5, 0.2))).norm() < 1e-12);
    assert!(mimo(D_MIMO).c2d(0.1, Discretization::Matched).is_err());
}

#[test]
fn tustin_of_a_transfer_function_is_the_substitution() {
    // 1/(s + 1), T = 0.5: (1/5)(z + 1)/(z − 3/5)
    let g = tf(&[1.0], &[1.0, 1.0]).c2d(0.5, TUSTIN).unwrap();
    assert!((g.num().coeff(1) - 0.2).abs() < 3e-16 && (g.den().coeff(0) + 0.6).abs() < 3e-16);
    // prewarped at ω: G(e^(jωT)) = G(jω)
    let plant = tf(&[4.0, 1.0], &[1.0, 0.8, 4.0]);
    let (t, w) = (0.2, 2.0);
    for g in [
        plant
            .c2d(t, Discretization::Tustin { prewarp: Some(w) })
            .unwrap(),
        StateSpace::from_tf(&plant)
            .unwrap()
            .c2d(t, Discretization::Tustin { prewarp: Some(w) })
            .unwrap()
            .to_tf()
            .unwrap(),
    ] {
        let z = c(0.0, w * t).exp();
        let (a, b) = (g.eval(z), plant.eval(c(0.0, w)));
        assert!((a - b).norm() <= 1e-13 * b.norm(), "{a} {b}");
    }
    let f = plant.factored().unwrap();
    let fd = f
        .c2d(t, Discretization::Tustin { prewarp: Some(w) })
        .unwrap();
    let (a, b) = (fd.eval(c(0.0, w * t).exp()), plant.eval(c(0.0, w)));
    assert!((a - b).norm() <= 1e-13 * b.norm(), "{a} {b}");
}

/// Plants for the round trips: stable, unstable, oscillatory, with zeros, biproper.
fn round_trip_plants() -> Vec<TransferFunction> {
    vec![
        tf(&[1.0], &[1.0, 2.0]),
        tf(&[4.0], &[1.0, 0.8, 4.0]),
        tf(&[1.0, 3.0], &[1.0, 5.0, 13.0, 19.0, 10.0]),
        tf(&[2.0, 1.0, 5.0], &[1.0, 1.0, 4.0, 2.0]),
        tf(&[1.0, -1.0], &[1.0, 0.5, -2.0]),
        tf(&[3.0, 2.0], &[1.0, 7.0]),
    ]
}

#[test]
fn d2c_inverts_c2d() {
    let mut worst = (0.0f64, 0.0f64);
    let mut worst_tf = (0.0f64, 0.0f64);
    for g in round_trip_plants() {
        for (k, method) in [ZOH, TUSTIN, Discretization::Tustin { prewarp: Some(3.0) }]
            .into_iter()
            .enumerate()
        {
            let t = 0.1;
            // state space: the matrices come back
            let ss = StateSpace::from_tf(&g).unwrap();
            let back = ss.c2d(t, method).unwrap().d2c(method).unwrap();
            assert_eq!(back.domain, Domain::Continuous);
            let e = [
                mat_err(&back.a, &ss.a),
                mat_err(&back.b, &ss.b),
                mat_err(&back.c, &ss.c),
                (&back.d - &ss.d).abs().max(),
            ]
            .into_iter()
            .fold(0.0, f64::max);
            assert!(e <= 1e-12, "{g} {method:?}: {e:e}");
            // transfer function: the coefficients come back
            let h = g.c2d(t, method).unwrap().d2c(method).unwrap();
            let lead = g.den().leading();
            let mut ec = 0.0f64;
            for (x, y) in [(h.num(), g.num()), (h.den(), g.den())] {
                let n = x.degree().max(y.degree());
                let scale = y.coeffs().iter().fold(0.0f64, |a, b| a.max(b.abs())) / lead;
                for i in 0..=n {
                    ec = ec.max((x.coeff(i) - y.coeff(i) / lead).abs() / scale);
                }
            }
            // coefficients in z are ill-conditioned data for d2c (poles near z = 1 at
            // T = 0.1): their rounding alone moves the s-coefficients by up to ~1e-11
            assert!(ec <= 5e-11, "{g} {method:?}: {ec:e}: {h}");
            for s in [c(0.1, 1.0), c(-0.3, 4.0)] {
                let (a, b) = (h.eval(s), g.eval(s));
                assert!(
                    (a - b).norm() <= 1e-10 * b.norm(),
                    "{g} {method:?} at {s}: {a} {b}"
                );
            }
            // factored form: G(s) comes back
            let f = g.factored().unwrap();
            let fb = f.c2d(t, method).unwrap().d2c(method).unwrap();
            for s in [c(0.1, 1.0), c(-0.3, 4.0)] {
                let (a, b) = (fb.eval(s), f.eval(s));
                assert!(
                    (a - b).norm() <= 1e-12 * b.norm(),
                    "{g} {method:?} at {s}: {a} {b}"
                );
            }
            let w = if k == 0 { &mut worst.0 } else { &mut worst.1 };
            *w = w.max(e);
            let wc = if k == 0 {
                &mut worst_tf.0
            } else {
                &mut worst_tf.1
            };
            *wc = wc.max(ec);
        }
    }
    println!(
        "d2c(c2d(G)): state space worst {:.1e} (ZOH), {:.1e} (Tustin); coefficients {:.1e} (ZOH), {:.1e} (Tustin)",
        worst.0, worst.1, worst_tf.0, worst_tf.1
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn zoh_and_tustin_round_trips(
        a in prop::collection::vec(-2.0..2.0f64, 9),
        b in prop::collection::vec(-1.0..1.0f64, 3),
        c in prop::collection::vec(-1.0..1.0f64, 3),
        shift in 0.5..3.0f64,
        t in 0.01..0.5f64,
    ) {
        // A − shift·I: eigenvalues within |λ| ≲ 9 (|Im λ|·T < π, so the ZOH log is principal)
        let mut am = DMatrix::from_row_slice(3, 3, &a);
        for i in 0..3 {
            am[(i, i)] -= shift;
        }
        let ss = StateSpace::new(
            am,
            DMatrix::from_row_slice(3, 1, &b),
            DMatrix::from_row_slice(1, 3, &c),
            DMatrix::from_element(1, 1, 0.25),
        )
        .unwrap();
        for method in [ZOH, TUSTIN] {
            let back = ss.c2d(t, method).unwrap().d2c(method).unwrap();
            let e = mat_err(&back.a, &ss.a).max(mat_err(&back.b, &ss.b));
            prop_assert!(e <= 1e-12, "{:?}: {:e}", method, e);
            prop_assert!((&back.d - &ss.d).abs().max() <= 1e-12);
        }
    }
}

#[test]
fn poles_without_a_preimage_are_named() {
    let dt = Domain::discrete(0.1).unwrap();
    for (pole, named) in [(-0.5, "z = -0.5"), (0.0, "z = 0")] {
        let g = tf(&[1.0], &[1.0, -pole]).with_domain(dt);
        let e = g.d2c(ZOH).unwrap_err();
        assert!(matches!(e, LtiError::NoPreimage { .. }), "{e:?}");
        assert!(e.to_string().contains(named), "{e}");
        let ss = StateSpace::from_tf(&g).unwrap();
        let e = ss.d2c(ZOH).unwrap_err().to_string();
        assert!(e.contains(named) && e.contains("preimage"), "{e}");
        let f = Factored::from_zpk(&[], &[Root::new(c(pole, 0.0), 1)], 1.0)
            .unwrap()
            .with_domain(dt);
        let e = f.d2c(ZOH).unwrap_err().to_string();
        assert!(e.contains(named), "{e}");
    }
    // Tustin: a pole at −1
    let g = tf(&[1.0], &[1.0, 1.0]).with_domain(dt);
    let e = g.d2c(TUSTIN).unwrap_err().to_string();
    assert!(e.contains("z = -1") && e.contains("Tustin"), "{e}");
    let e = StateSpace::from_tf(&g)
        .unwrap()
        .d2c(TUSTIN)
        .unwrap_err()
        .to_string();
    assert!(e.contains("z = -1"), "{e}");
    // d2c inverts zoh and tustin only, and needs a discrete model
    let e = tf(&[1.0], &[1.0, -0.5])
        .with_domain(dt)
        .d2c(Discretization::Foh);
    assert!(e.unwrap_err().to_string().contains("zoh and tustin"));
    assert!(tf(&[1.0], &[1.0, 1.0]).d2c(ZOH).is_err());
}

#[test]
fn bad_input_is_refused_with_the_numbers() {
    let e = Discretization::parse("euler", None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("'euler'") && e.contains("zoh, foh, tustin (or bilinear), matched, impulse"),
        "{e}"
    );
    assert!(Discretization::parse("zoh", Some(1.0)).is_err());
    for name in ["zoh", "FOH", "tustin", "bilinear", "matched", "impulse"] {
        assert!(Discretization::parse(name, None).is_ok(), "{name}");
    }
    let g = tf(&[1.0], &[1.0, 1.0]);
    let ss = StateSpace::from_tf(&g).unwrap();
    let f = g.factored().unwrap();
    for dt in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        let errs = [
            g.c2d(dt, ZOH).unwrap_err().to_string(),
            ss.c2d(dt, ZOH).unwrap_err().to_string(),
            f.c2d(dt, ZOH).unwrap_err().to_string(),
        ];
        for e in errs {
            assert!(e.contains("sampling period"), "{dt}: {e}");
        }
    }
    // prewarp at or beyond π/T, or ≤ 0
    let nyquist = std::f64::consts::PI / 0.1;
    for w in [nyquist, 2.0 * nyquist, 0.0, -1.0, f64::NAN] {
        let m = Discretization::Tustin { prewarp: Some(w) };
        let e = g.c2d(0.1, m).unwrap_err().to_string();
        assert!(e.contains("prewarp") && e.contains("31.4159"), "{w}: {e}");
        assert!(ss.c2d(0.1, m).is_err() && f.c2d(0.1, m).is_err());
    }
    // already discrete
    let gd = g.c2d(0.1, ZOH).unwrap();
    let e = gd.c2d(0.1, ZOH).unwrap_err().to_string();
    assert!(e.contains("discrete"), "{e}");
    // improper
    assert!(tf(&[1.0, 0.0, 0.0], &[1.0, 1.0]).c2d(0.1, ZOH).is_err());
}

#[test]
fn foh_and_impulse_through_the_factored_form() {
    // the factored FOH and impulse equivalents agree with the state-space ones
    let g = tf(&[4.0], &[1.0, 0.8, 4.0]);
    let ss = StateSpace::from_tf(&g).unwrap();
    for method in [Discretization::Foh, Discretization::Impulse] {
        let f = g.factored().unwrap().c2d(0.1, method).unwrap();
        let h = ss.c2d(0.1, method).unwrap().to_tf().unwrap();
        for z in [c(0.3, 0.8), c(-0.5, 0.1)] {
            let (a, b) = (f.eval(z), h.eval(z));
            assert!((a - b).norm() <= 1e-12 * b.norm(), "{method:?}: {a} {b}");
        }
    }
    // impulse invariance: h_d[k] = T·h(kT); for 1/(s + 1): T·e^(−kT) ⇒ T·z/(z − e^(−T))
    let d = tf(&[1.0], &[1.0, 1.0])
        .c2d(0.1, Discretization::Impulse)
        .unwrap();
    assert!((d.num().coeff(1) - 0.1).abs() < 1e-16 && d.num().coeff(0).abs() < 1e-16);
    assert!((d.den().coeff(0) + (-0.1f64).exp()).abs() < 1e-16);
}

#[test]
fn zoh_of_a_second_order_model_from_its_modes_equals_the_dense_exponential() {
    // The seed's periodic lattice (N = 64, 128 states: free translation, degenerate pairs)
    // and a Rayleigh-damped copy: c2d(ZOH) takes the modes' path (one 4×4 exponential per
    // mode); the reference is the exponential of the whole augmented matrix
    // [[A·T, B·T], [0, 0]] (the path every other model takes).
    use ltikit::lti::lattice::{Boundary, Lattice, Output};
    let lattice = Lattice::new(64, Boundary::Periodic, 1.0)
        .and_then(|l| l.with_input(1))
        .and_then(|l| l.with_output(Output::Particle(6)))
        .and_then(|l| l.state_space())
        .unwrap();
    let mut damped = lattice.clone();
    let d = 64;
    for i in 0..d {
        for j in 0..d {
            let g = -lattice.a[(d + i, j)];
            let identity = if i == j { 1.0 } else { 0.0 };
            damped.a[(d + i, d + j)] = -(0.02 * identity + 0.05 * g);
        }
    }
    for ss in [&lattice, &damped] {
        let (n, m) = (ss.order(), ss.b.ncols());
        for dt in [0.01, 0.1, 2.0] {
            let zoh = ss.c2d(dt, ZOH).unwrap();
            let mut aug = DMatrix::zeros(n + m, n + m);
            aug.view_mut((0, 0), (n, n)).copy_from(&(&ss.a * dt));
            aug.view_mut((0, n), (n, m)).copy_from(&(&ss.b * dt));
            let e = ltikit::numeric::expm(&aug).unwrap();
            let phi = e.view((0, 0), (n, n)).into_owned();
            let gamma = e.view((0, n), (n, m)).into_owned();
            let (ep, eg) = (mat_err(&zoh.a, &phi), mat_err(&zoh.b, &gamma));
            assert!(ep < 1e-13 && eg < 1e-13, "T = {dt}: Φ {ep:.1e}, Γ {eg:.1e}");
        }
    }
}

/// max |a − b| / max |b| over the coefficients (b: the reference, its leading zeros dropped as
/// ltikit drops them), and the largest per-coefficient |a − b| / |b|.
fn coeff_errors(got: &[f64], want: &[f64]) -> (f64, f64) {
    let want: Vec<f64> = want.iter().copied().skip_while(|&x| x == 0.0).collect();
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    let big = want.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let (mut norm, mut per) = (0.0f64, 0.0f64);
    for (a, b) in got.iter().zip(&want) {
        norm = norm.max((a - b).abs() / big);
        per = per.max(common::rel(*a, *b));
    }
    (norm, per)
}

#[test]
fn zoh_of_transfer_functions_against_a_30_digit_reference() {
    // tests/data/c2d_tf_reference.py: 50-digit exponential of the augmented matrix, the
    // characteristic polynomials by Faddeev–LeVerrier, 30 digits printed. TransferFunction::c2d
    // (poles e^(pT), numerator from the Markov parameters) against it, and against the
    // realisation's characteristic polynomials (StateSpace::c2d then to_tf: the method it
    // replaced, 2.5e-3 relative on the order-8 numerator at T = 0.01): never worse
    let text = std::fs::read_to_string("tests/data/c2d_tf_reference.json").unwrap();
    let plants: serde_json::Value = serde_json::from_str(&text).unwrap();
    let floats = |v: &serde_json::Value| -> Vec<f64> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|x| match x {
                serde_json::Value::String(s) => s.parse().unwrap(),
                other => other.as_f64().unwrap(),
            })
            .collect()
    };
    assert_eq!(plants.as_array().unwrap().len(), 8);
    for p in plants.as_array().unwrap() {
        let name = p["name"].as_str().unwrap();
        let g = tf(&floats(&p["num"]), &floats(&p["den"]));
        let dt = p["dt"].as_f64().unwrap();
        let (want_num, want_den) = (floats(&p["num_z"]), floats(&p["den_z"]));
        let gd = g.c2d(dt, ZOH).unwrap();
        let (dn, dp) = coeff_errors(gd.den().coeffs(), &want_den);
        let (nn, np) = coeff_errors(gd.num().coeffs(), &want_num);
        let old = StateSpace::from_tf(&g)
            .unwrap()
            .c2d(dt, ZOH)
            .unwrap()
            .to_tf()
            .unwrap();
        let lead = old.den().leading();
        let monic = |c: &[f64]| c.iter().map(|x| x / lead).collect::<Vec<_>>();
        let (odn, _) = coeff_errors(&monic(old.den().coeffs()), &want_den);
        let (onn, _) = coeff_errors(&monic(old.num().coeffs()), &want_num);
        println!(
            "{name}: den {dn:.1e} (per coefficient {dp:.1e}), num {nn:.1e} ({np:.1e}); \
             characteristic polynomials: den {odn:.1e}, num {onn:.1e}"
        );
        assert!(dp < 1e-14, "{name}: denominator {dp:.1e}");
        assert!(
            nn < 5e-12,
            "{name}: numerator {nn:.1e} of the largest coefficient"
        );
        let floor = 4.0 * f64::EPSILON;
        assert!(dn <= odn.max(floor), "{name}: den {dn:.1e} vs {odn:.1e}");
        assert!(nn <= onn.max(floor), "{name}: num {nn:.1e} vs {onn:.1e}");
    }
}
