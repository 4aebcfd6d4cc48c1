//! System norms (issue 23 item 4): certified H∞/L∞ intervals against closed forms, an
//! independent dense-grid reference, the bilinear invariance in discrete time, and the loop
//! peaks Ms, Mt.

mod common;

#[path = "../benches/common/norms.rs"]
mod norms_input;

use common::tf;
use ltikit::StateSpace;
use ltikit::analysis::ClosedLoop;
use ltikit::analysis::norms::{CERTIFIED_GAP, PeakGain, hinf_norm, linf_norm, sigma_response};
use ltikit::lti::{Discretization, Domain};
use nalgebra::DMatrix;

/// `exact` lies in the certified interval (up to `slack` relative, the reference's own
/// rounding) and the lower bound is within `rel` of it.
fn check(n: &PeakGain, exact: f64, rel: f64, slack: f64, what: &str) {
    assert!(n.infinite.is_none(), "{what}: {n:?}");
    assert!(
        n.relative_gap() <= CERTIFIED_GAP,
        "{what}: gap {}",
        n.relative_gap()
    );
    assert!(
        n.lower <= exact * (1.0 + slack) && exact <= n.upper * (1.0 + slack),
        "{what}: {exact} outside [{}, {}]",
        n.lower,
        n.upper
    );
    assert!(
        (n.lower / exact - 1.0).abs() <= rel,
        "{what}: {} vs {exact} ({:e})",
        n.lower,
        n.lower / exact - 1.0
    );
}

/// Closed form: ‖1/(s² + 2ζs + 1)‖∞ = 1/(2ζ√(1 − ζ²)) for ζ < 1/√2 (at ω = √(1 − 2ζ²)), and
/// 1 (at ω = 0) otherwise — here through the transfer-function path (factored, realised).
#[test]
fn damping_family_from_coefficients() {
    for z in [0.5, 0.1, 1e-3, 1e-5] {
        let f = tf(&[1.0], &[1.0, 2.0 * z, 1.0]).factored().unwrap();
        let n = f.hinf_norm().unwrap();
        check(
            &n,
            1.0 / (2.0 * z * (1.0 - z * z).sqrt()),
            1e-12,
            1e-15,
            &format!("ζ = {z}"),
        );
        assert!(
            (n.w - (1.0 - 2.0 * z * z).sqrt()).abs() < 1e-6,
            "ζ = {z}: {}",
            n.w
        );
    }
    for z in [1.0 / 2f64.sqrt() + 1e-9, 2.0] {
        let n = tf(&[1.0], &[1.0, 2.0 * z, 1.0])
            .factored()
            .unwrap()
            .hinf_norm()
            .unwrap();
        assert!(
            (n.lower - 1.0).abs() < 1e-15 && n.w == 0.0,
            "ζ = {z}: {n:?}"
        );
    }
}

/// The random stable 2×2 model of 30 states (benches/common/norms.rs, seed 1) against the
/// reference of benches/compare/compare_norms.py: σ_max on 200 000 log-spaced frequencies
/// refined at every local maximum by scipy's bounded scalar minimiser, 30.916905508269178 at
/// ω = 1.2808418065666043 (python-control's `norm(sys, 'inf', tol=1e-10, method='scipy')`
/// gives 30.916905506744172).
#[test]
fn random_mimo_model_against_dense_grid_reference() {
    let ss = norms_input::random_stable(30, 2, 2, 1);
    let n = hinf_norm(&ss).unwrap();
    check(&n, 30.916905508269178, 1e-11, 1e-12, "random 30 states");
    assert!((n.w - 1.2808418065666043).abs() < 1e-6, "{}", n.w);
    // no sample of a sigma plot exceeds the upper bound
    let w: Vec<f64> = common::logspace(-3.0, 3.0, 20_001);
    let s = sigma_response(&ss, &w).unwrap();
    let top = s.sigma.iter().map(|v| v[0]).fold(0.0, f64::max);
    assert!(top <= n.upper && top > 0.99 * n.lower, "{top} vs {n:?}");
}

/// The bilinear map z = (1 + s)/(1 − s) (Tustin at T = 2) keeps the norm: discrete ζ family
/// against the closed form, peak at θ = 2·atan(ω_r), i.e. ω = atan(ω_r) rad/s at T = 2.
#[test]
fn discrete_models_by_bilinear_invariance() {
    let tustin = Discretization::Tustin { prewarp: None };
    for z in [0.1, 1e-3] {
        let g = tf(&[1.0], &[1.0, 2.0 * z, 1.0]).c2d(2.0, tustin).unwrap();
        let n = g.factored().unwrap().hinf_norm().unwrap();
        check(
            &n,
            1.0 / (2.0 * z * (1.0 - z * z).sqrt()),
            1e-11,
            1e-12,
            &format!("ζ = {z}"),
        );
        let wr = (1.0 - 2.0 * z * z).sqrt();
        assert!((n.w - wr.atan()).abs() < 1e-6, "{}", n.w);
    }
    // the random model mapped the same way: the continuous reference
    let ss = norms_input::random_stable(30, 2, 2, 1)
        .c2d(2.0, tustin)
        .unwrap();
    assert_eq!(ss.domain, Domain::discrete(2.0).unwrap());
    check(
        &hinf_norm(&ss).unwrap(),
        30.916905508269178,
        1e-10,
        1e-11,
        "random, z",
    );
    // 1/(z − a): |G| = 1/|e^(jθ) − a| peaks at θ = 0 (a > 0) or θ = π (a < 0) at 1/(1 − |a|)
    for (a, w) in [(0.5, 0.0), (-0.5, std::f64::consts::PI / 0.1)] {
        let g = tf(&[1.0], &[1.0, -a]).with_domain(Domain::discrete(0.1).unwrap());
        let n = g.factored().unwrap().hinf_norm().unwrap();
        check(&n, 2.0, 1e-15, 1e-15, &format!("a = {a}"));
        assert!((n.w - w).abs() < 1e-9, "a = {a}: {}", n.w);
    }
}

/// H∞ of an unstable model is infinite (MATLAB's `hinfnorm` returns Inf), its L∞ finite:
/// |1/((s − 1)(s + 2))| = 1/√((ω² + 1)(ω² + 4)) peaks at ω = 0 at 1/2.
#[test]
fn unstable_models() {
    let f = tf(&[1.0], &[1.0, 1.0, -2.0]).factored().unwrap();
    let h = f.hinf_norm().unwrap();
    let why = h.infinite.unwrap();
    assert!(why.contains("unstable") && why.contains("s = 1"), "{why}");
    check(&f.linf_norm().unwrap(), 0.5, 1e-15, 1e-15, "L∞");
    // a pole on the imaginary axis: both infinite, at its frequency
    let ss = StateSpace::new(
        DMatrix::from_row_slice(2, 2, &[0.0, 2.0, -2.0, 0.0]),
        DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
        DMatrix::from_row_slice(1, 2, &[1.0, 0.0]),
        DMatrix::zeros(1, 1),
    )
    .unwrap();
    let l = linf_norm(&ss).unwrap();
    assert!(l.upper.is_infinite() && (l.w - 2.0).abs() < 1e-14, "{l:?}");
}

/// Static gains and a peak at ω → ∞: G = (s + 3)/(s + 1) has |G| from 3 down to 1, G = s/(s+1)
/// rises to 1 without attaining it.
#[test]
fn peaks_at_zero_and_infinity() {
    let n = tf(&[1.0, 3.0], &[1.0, 1.0])
        .factored()
        .unwrap()
        .hinf_norm()
        .unwrap();
    check(&n, 3.0, 1e-15, 1e-15, "(s + 3)/(s + 1)");
    let n = tf(&[1.0, 0.0], &[1.0, 1.0])
        .factored()
        .unwrap()
        .hinf_norm()
        .unwrap();
    check(&n, 1.0, 1e-15, 1e-15, "s/(s + 1)");
    assert!(n.w.is_infinite());
    let d = DMatrix::from_row_slice(2, 2, &[3.0, 0.0, 0.0, -4.0]);
    let ss = StateSpace::new(
        DMatrix::zeros(0, 0),
        DMatrix::zeros(0, 2),
        DMatrix::zeros(2, 0),
        d,
    )
    .unwrap();
    assert_eq!(hinf_norm(&ss).unwrap().lower, 4.0);
}

/// Ms and Mt of a loop (polynomial local maxima, `ClosedLoop::robustness`) lie in the
/// certified intervals of ‖S‖∞ and ‖T‖∞.
#[test]
fn loop_peaks_agree_with_certified_norms() {
    use ltikit::lti::controller::LoopSystem;
    let c = tf(&[2.0, 1.0], &[1.0, 0.0]).factored().unwrap(); // PI: 2 + 1/s
    let g = tf(&[1.0], &[1.0, 0.8, 4.0, 0.0]).factored().unwrap();
    let cl = ClosedLoop::new(&c, &g).unwrap();
    let r = cl.robustness().unwrap();
    for (which, peak) in [
        (LoopSystem::Sensitivity, r.ms),
        (LoopSystem::ClosedLoop, r.mt),
    ] {
        let n = cl.system(which).unwrap().hinf_norm().unwrap();
        assert!(
            peak.value >= n.lower * (1.0 - 1e-12) && peak.value <= n.upper * (1.0 + 1e-12),
            "{which:?}: {} vs [{}, {}]",
            peak.value,
            n.lower,
            n.upper
        );
    }
}

/// No false certificate: for 40 random models (2 to 40 states, SISO to 3×2, seeds 1…40 of
/// benches/common/norms.rs) no σ_max sample of a 4001-point grid around the modes exceeds
/// the upper bound, and the interval is 1e-10 wide.
#[test]
fn certificates_hold_on_random_models() {
    let w = common::logspace(-2.0, 2.0, 4001);
    for seed in 1..=40u64 {
        let n = 2 * (1 + (seed as usize * 7) % 20);
        let (m, p) = (1 + seed as usize % 2, 1 + seed as usize % 3);
        let ss = norms_input::random_stable(n, m, p, seed);
        let h = hinf_norm(&ss).unwrap();
        assert!(h.relative_gap() <= CERTIFIED_GAP, "seed {seed}: {h:?}");
        let s = sigma_response(&ss, &w).unwrap();
        let top = s.sigma.iter().map(|v| v[0]).fold(0.0, f64::max);
        assert!(
            top <= h.upper,
            "seed {seed} (n = {n}): grid {top} > upper {}",
            h.upper
        );
    }
}
