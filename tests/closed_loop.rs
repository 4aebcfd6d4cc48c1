//! Interconnections, controllers and the closed loop (issue 13, items 1, 2, 5).
//!
//! References: direct evaluation of the factors at random points (interconnections); sympy
//! (`cancel(together(C·G/(1 + C·G)))` and `Poly.nroots(n=30)`) for the PID loop; mpmath at 40
//! digits (a 2001-point scan of |S|, |T| followed by `findroot` on d|·|²/dω, and `findroot`
//! on |L| = 1) for Ms, Mt and the delay margin.

// the reference digits are quoted as the references printed them
#![allow(clippy::excessive_precision)]

mod common;

use common::{c, tf};
use ltikit::analysis::{ClosedLoop, Factored, LoopSystem};
use ltikit::lti::{Controller, Domain, Plant, controller::LoopSystem as Sel};
use ltikit::{Root, StateSpace};
use num_complex::Complex64;

/// Deterministic pseudo-random points s = x + jy in [−3, 3]² (xorshift).
fn points(n: usize) -> Vec<Complex64> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 * 6.0 - 3.0
    };
    (0..n).map(|_| c(next(), next())).collect()
}

fn close(a: Complex64, b: Complex64, tol: f64) {
    assert!((a - b).norm() <= tol * b.norm().max(1e-300), "{a} vs {b}");
}

#[test]
fn series_parallel_feedback_against_direct_evaluation() {
    let g1 = tf(&[2.0, 1.0], &[1.0, 3.0, 5.0]); // (2s + 1)/(s² + 3s + 5)
    let g2 = tf(&[1.0, -0.5, 2.0], &[1.0, 1.0, 4.0, 2.0]); // biproper-ish, order 3
    let h = tf(&[3.0], &[1.0, 4.0]);
    let (s1, s2, sh) = (
        StateSpace::from_tf(&g1).unwrap(),
        StateSpace::from_tf(&g2).unwrap(),
        StateSpace::from_tf(&h).unwrap(),
    );
    let f1 = g1.factored().unwrap();
    let f2 = g2.factored().unwrap();
    let fh = h.factored().unwrap();
    let ser = g1.series(&g2).unwrap();
    let par = g1.parallel(&g2).unwrap();
    let fbn = g1.feedback(&h, -1.0).unwrap();
    let fbp = g2.feedback(&h, 1.0).unwrap();
    let ss_ser = s1.series(&s2).unwrap().to_tf().unwrap();
    let ss_par = s1.parallel(&s2).unwrap().to_tf().unwrap();
    let ss_fbn = s1.feedback(&sh, -1.0).unwrap().to_tf().unwrap();
    let ss_fbp = s2.feedback(&sh, 1.0).unwrap().to_tf().unwrap();
    let f_ser = f1.series(&f2).unwrap();
    let f_par = f1.parallel(&f2).unwrap();
    let f_fbn = f1.feedback(&fh, -1.0).unwrap().closed;
    let f_fbp = f2.feedback(&fh, 1.0).unwrap().closed;
    for s in points(50) {
        let (a, b, k) = (g1.eval(s), g2.eval(s), h.eval(s));
        let want = [a * b, a + b, a / (1.0 + a * k), b / (1.0 - b * k)];
        let tfs = [ser.eval(s), par.eval(s), fbn.eval(s), fbp.eval(s)];
        let sss = [
            ss_ser.eval(s),
            ss_par.eval(s),
            ss_fbn.eval(s),
            ss_fbp.eval(s),
        ];
        let fs = [f_ser.eval(s), f_par.eval(s), f_fbn.eval(s), f_fbp.eval(s)];
        for i in 0..4 {
            close(tfs[i], want[i], 1e-12);
            close(sss[i], want[i], 1e-10);
            close(fs[i], want[i], 1e-10);
        }
    }
}

/// The three interconnections of one model type in one shape: (series, parallel, feedback)
/// of `g` and `h`, each `Ok` or the error's text.
type Connect<'a, T> = &'a dyn Fn(&T, &T) -> [Result<ltikit::lti::Domain, String>; 3];

/// Every interconnection of every model type joins the two domains: two discrete models of
/// the same period give that period; a continuous and a discrete model, or two periods, are
/// an error naming the operation and both domains.
#[test]
fn interconnections_join_the_domains() {
    let z = |dt: f64| Domain::discrete(dt).unwrap();
    // G = 0.5/(z − 0.5), H = 0.2/(z − 0.8) read in each domain
    let (g, h) = (tf(&[0.5], &[1.0, -0.5]), tf(&[0.2], &[1.0, -0.8]));
    let ops = ["series", "parallel", "feedback"];
    let check = |name: &str, results: [[Result<Domain, String>; 3]; 3]| {
        let [same, mixed, periods] = results;
        for (k, op) in ops.iter().enumerate() {
            assert_eq!(same[k], Ok(z(0.1)), "{name} {op}");
            let e = mixed[k].clone().unwrap_err();
            assert!(
                e.contains(op) && e.contains("continuous-time") && e.contains("dt = 0.1 s"),
                "{name}: {e}"
            );
            let e = periods[k].clone().unwrap_err();
            assert!(
                e.contains(op) && e.contains("dt = 0.1 s") && e.contains("dt = 0.2 s"),
                "{name}: {e}"
            );
        }
    };
    let tfs: Connect<ltikit::TransferFunction> = &|a, b| {
        [
            a.series(b).map(|r| r.domain()),
            a.parallel(b).map(|r| r.domain()),
            a.feedback(b, -1.0).map(|r| r.domain()),
        ]
        .map(|r| r.map_err(|e| e.to_string()))
    };
    let sss: Connect<StateSpace> = &|a, b| {
        [
            a.series(b).map(|r| r.domain),
            a.parallel(b).map(|r| r.domain),
            a.feedback(b, -1.0).map(|r| r.domain),
        ]
        .map(|r| r.map_err(|e| e.to_string()))
    };
    let fs: Connect<Factored> = &|a, b| {
        [
            a.series(b).map(|r| r.domain()),
            a.parallel(b).map(|r| r.domain()),
            a.feedback(b, -1.0).map(|r| r.closed.domain()),
        ]
        .map(|r| r.map_err(|e| e.to_string()))
    };
    let tf_in = |t: &ltikit::TransferFunction, d: Domain| t.clone().with_domain(d);
    let pairs = [
        (z(0.1), z(0.1)),
        (Domain::Continuous, z(0.1)),
        (z(0.1), z(0.2)),
    ];
    check(
        "transfer function",
        pairs.map(|(a, b)| tfs(&tf_in(&g, a), &tf_in(&h, b))),
    );
    check(
        "state space",
        pairs.map(|(a, b)| {
            sss(
                &StateSpace::from_tf(&tf_in(&g, a)).unwrap(),
                &StateSpace::from_tf(&tf_in(&h, b)).unwrap(),
            )
        }),
    );
    check(
        "factored",
        pairs.map(|(a, b)| {
            fs(
                &tf_in(&g, a).factored().unwrap(),
                &tf_in(&h, b).factored().unwrap(),
            )
        }),
    );
    // the controller–plant loop of the analyses joins them too
    let (fg, fh) = (
        tf_in(&g, z(0.1)).factored().unwrap(),
        tf_in(&h, z(0.1)).factored().unwrap(),
    );
    let cl = ClosedLoop::new(&fh, &fg).unwrap();
    for which in [
        LoopSystem::Loop,
        LoopSystem::ClosedLoop,
        LoopSystem::Sensitivity,
    ] {
        assert_eq!(cl.system(which).unwrap().domain(), z(0.1));
    }
    let e = ClosedLoop::new(&h.factored().unwrap(), &fg)
        .unwrap_err()
        .to_string();
    assert!(e.contains("C·G") && e.contains("continuous-time"), "{e}");
    // the discrete loop's values: T = G/(1 + GH) at z = 1.3 + 0.4j, whatever the model type
    let (gz, hz) = (tf_in(&g, z(0.1)), tf_in(&h, z(0.1)));
    let p = c(1.3, 0.4);
    let want = gz.eval(p) / (1.0 + gz.eval(p) * hz.eval(p));
    close(gz.feedback(&hz, -1.0).unwrap().eval(p), want, 1e-13);
    let (sg, sh) = (
        StateSpace::from_tf(&gz).unwrap(),
        StateSpace::from_tf(&hz).unwrap(),
    );
    close(
        sg.feedback(&sh, -1.0).unwrap().to_tf().unwrap().eval(p),
        want,
        1e-12,
    );
}

#[test]
fn series_keeps_the_factors_of_a_twenty_fold_pole() {
    let p10 = Factored::from_zpk(&[], &[Root::new(c(-1.0, 0.0), 10)], 1.0).unwrap();
    let p20 = p10.series(&p10).unwrap();
    assert_eq!(p20.poles(), &[Root::new(c(-1.0, 0.0), 20)]);
    assert_eq!(p20.order(), 20);
    // exactly 1/(s + 1)^20: at s = 1 it is 2^-20, exact in binary
    assert_eq!(p20.eval(c(1.0, 0.0)), c(2f64.powi(-20), 0.0));
    assert_eq!(p20.dc_gain(), Some(1.0));
}

#[test]
fn pid_on_a_second_order_plant_matches_the_closed_form() {
    // G = 1/(s² + 0.4 s + 4) (the spring–mass–damper M = 1, C = 0.4, K = 4),
    // C = 2 + 1/s + 0.5 s/(0.01 s + 1). sympy: T = (260 s² + 1005 s + 500) /
    // (5 s⁴ + 502 s³ + 480 s² + 3005 s + 500).
    let mut p = Plant::from_model("spring-mass-damper", &[]).unwrap();
    p.controller = Some(Controller::parse("pid:kp=2,ki=1,kd=0.5,tf=0.01").unwrap());
    p.selection = Some(Sel::ClosedLoop);
    let (t, cl) = ltikit::analysis::closed_loop::select(&p, p.factored().unwrap()).unwrap();
    let cl = cl.unwrap();
    let want_den = [5.0, 502.0, 480.0, 3005.0, 500.0];
    for (a, b) in cl.characteristic().coeffs().iter().zip(want_den) {
        assert!((a - b / 5.0).abs() <= 1e-13 * (b / 5.0).abs(), "{a} {b}");
    }
    // sympy nroots(n=30)
    let want = [
        c(-0.170_194_043_267_096_26, 0.0),
        c(-0.367_031_073_417_110_26, 2.402_230_829_360_823),
        c(-0.367_031_073_417_110_26, -2.402_230_829_360_823),
        c(-99.495_743_809_898_683, 0.0),
    ];
    for w in want {
        let got = cl
            .poles()
            .iter()
            .map(|r| (r.value - w).norm())
            .fold(f64::INFINITY, f64::min);
        assert!(got <= 1e-13 * w.norm(), "{w}: {got}");
    }
    // T at two points (sympy, 20 digits)
    close(
        t.eval(c(0.3, 1.7)),
        c(0.517_046_283_199_605_35, -0.208_268_825_090_353_75),
        1e-14,
    );
    close(
        t.eval(c(0.0, 2.0)),
        c(0.819_791_823_323_577_58, -0.280_100_824_099_094_26),
        1e-14,
    );
    assert_eq!(t.dc_gain(), Some(1.0)); // integral action
    assert!(cl.internal_stability().stable);
}

#[test]
fn a_cancelled_unstable_pole_makes_the_loop_internally_unstable() {
    // G = 1/((s − 1)(s + 2)), C = 10 (s − 1)/s: L = 10/(s(s + 2)) looks fine,
    // T = 10/(s² + 2s + 10) is stable, but s = 1 is a hidden mode.
    let g = tf(&[1.0], &[1.0, 1.0, -2.0]).factored().unwrap();
    let c_ = Controller::parse("pi:kp=10,ki=-10")
        .unwrap()
        .tf()
        .unwrap()
        .factored()
        .unwrap();
    let cl = ClosedLoop::new(&c_, &g).unwrap();
    assert_eq!(cl.hidden(), &[Root::new(c(1.0, 0.0), 1)]);
    let st = cl.internal_stability();
    assert!(!st.stable);
    assert!(st.reason.contains("hidden mode"), "{}", st.reason);
    assert!(st.reason.contains("s = 1 "), "{}", st.reason);
    let t = cl.system(LoopSystem::ClosedLoop).unwrap();
    assert!(t.stability().bibo_stable);
    assert!(!t.stability().internally_stable);
    // the input-disturbance path G·S shows the unstable mode
    assert!(!cl.plant_sensitivity().unwrap().stability().bibo_stable);
    // and on the command line: the analysis succeeds, the verdict is internal instability
    ltikit::cli::run_from([
        "ltikit",
        "margins",
        "--num",
        "1",
        "--den",
        "1 1 -2",
        "--controller",
        "pi:kp=10,ki=-10",
    ])
    .unwrap();
}

#[test]
fn robustness_margins_of_a_textbook_loop() {
    // L = 2/(s(s + 1)(s + 2)). mpmath (40 digits): Ms = 2.312314014627773516 at
    // ω = 0.925290006210063886; Mt = 1.837117307087383574 at ω = 0.816496580927726033;
    // gain crossing ω_c = 0.749368275822262358, PM = 32.61309704777443129°,
    // delay margin PM/ω_c = 0.759581024605733916 s.
    let one = tf(&[1.0], &[1.0]).factored().unwrap();
    let g = tf(&[2.0], &[1.0, 3.0, 2.0, 0.0]).factored().unwrap();
    let r = ClosedLoop::new(&one, &g).unwrap().robustness().unwrap();
    let rel = |a: f64, b: f64| (a - b).abs() / b;
    assert!(
        rel(r.ms.value, 2.312_314_014_627_773_5) < 1e-13,
        "{:?}",
        r.ms
    );
    assert!(rel(r.ms.w, 0.925_290_006_210_063_9) < 1e-8, "{:?}", r.ms);
    assert!(
        rel(r.mt.value, 1.837_117_307_087_383_6) < 1e-13,
        "{:?}",
        r.mt
    );
    assert!(rel(r.mt.w, 0.816_496_580_927_726) < 1e-8, "{:?}", r.mt);
    assert!(
        rel(r.delay_margin, 0.759_581_024_605_733_9) < 1e-12,
        "{r:?}"
    );
    assert!(
        rel(r.delay_margin_w, 0.749_368_275_822_262_4) < 1e-12,
        "{r:?}"
    );
    assert!(r.closed_loop_stable);
}

fn cli_error(args: &[&str]) -> String {
    let mut argv = vec!["ltikit"];
    argv.extend_from_slice(args);
    format!("{:#}", ltikit::cli::run_from(argv).unwrap_err())
}

#[test]
fn bad_controllers_and_loops_are_named() {
    let e = cli_error(&["margins", "--den", "1 1", "--controller", "pdi:kp=1"]);
    assert!(e.contains("known: p, pi, pd, pid, lead, lag"), "{e}");
    let e = cli_error(&["margins", "--den", "1 1", "--controller", "pid:kp=1,kx=2"]);
    assert!(e.contains("parameters: kp, ki, kd, tf"), "{e}");
    let e = cli_error(&[
        "step",
        "--den",
        "1 1",
        "--controller",
        "pid:kp=1,kd=1,tf=-0.1",
        "-o",
        "x.png",
    ]);
    assert!(e.contains("tf = -0.1") && e.contains("≥ 0"), "{e}");
    // an unfiltered derivative on a plant without roll-off: L is improper
    let e = cli_error(&[
        "analyze",
        "--num",
        "1",
        "--den",
        "1",
        "--controller",
        "pid:kp=1,ki=1,kd=1",
    ]);
    assert!(
        e.contains("unfiltered derivative") && e.contains("tf="),
        "{e}"
    );
    // |L| < 1 everywhere: no gain crossing, the delay margin is undefined
    let e = cli_error(&["margins", "--den", "1 1", "--controller", "p:kp=0.5"]);
    assert!(e.contains("no finite gain crossing"), "{e}");
}

#[test]
fn plant_file_controller_section() {
    let f = ltikit::lti::PlantFile::parse(
        "name = \"smd\"\nmodel = \"spring-mass-damper\"\n[controller]\nkind = \"pid\"\nkp = 2\nki = 1\nkd = 0.5\ntf = 0.01\n",
    )
    .unwrap();
    let p = Plant::from_record(&f).unwrap();
    assert_eq!(
        p.controller.as_ref().unwrap().to_string(),
        "pid:kp=2,ki=1,kd=0.5,tf=0.01"
    );
    let bad = ltikit::lti::PlantFile::parse("den = [1, 1]\n[controller]\nkind = \"pi\"\nkd = 1\n")
        .unwrap();
    let e = Plant::from_record(&bad).unwrap_err().to_string();
    assert!(e.contains("parameters: kp, ki"), "{e}");
}

/// A digital controller given in z (`tf:NUM/DEN`) is used as given in front of a discrete
/// plant, not discretised: G(z) = 0.1/(z − 0.9), C(z) = (0.5 z − 0.4)/(z − 1) close to
/// (z − 0.9)(z − 1) + 0.1(0.5 z − 0.4) = z² − 1.85 z + 0.86, poles 0.925 ± j·√0.0175/2
/// (|z|² = 0.86). In front of a continuous plant the same spec is C(s).
#[test]
fn a_controller_given_in_z_is_used_as_given() {
    use ltikit::analysis::LoopSystem;
    use ltikit::analysis::closed_loop::select;
    use ltikit::lti::{Controller, Domain, Plant};
    let mut p = Plant::from_text(Some("0.1"), "1 -0.9")
        .unwrap()
        .with_domain(Domain::discrete(0.1).unwrap())
        .unwrap();
    p.controller = Some(Controller::parse("tf:0.5 -0.4/1 -1").unwrap());
    p.selection = Some(LoopSystem::ClosedLoop);
    let (t, _) = select(&p, p.factored().unwrap()).unwrap();
    let pole = t.poles().iter().find(|r| r.value.im > 0.0).unwrap().value;
    assert!((pole.re - 0.925).abs() < 1e-14);
    assert!((pole.im - 0.0175f64.sqrt() / 2.0).abs() < 1e-14);
    assert!((pole.norm_sqr() - 0.86).abs() < 1e-14);
    // bad specs name the problem
    for bad in ["tf:1 2", "tf:1/0", "tf:x/1", "tf:1/nan"] {
        assert!(Controller::parse(bad).is_err(), "{bad}");
    }
}
