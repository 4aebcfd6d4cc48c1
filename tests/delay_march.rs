//! The delayed closed loop over long horizons: the Chebyshev collocation march of the delay
//! equation (`DelayMarch`, and `Factored::delayed_feedback_response` /
//! `Factored::delayed_step_info` beyond `CLOSED_FORM_PIECES` delays) against references
//! derived independently.
//!
//! Long-horizon reference (first-order loop L = K/(s + a), K = 2, a = 1, T = 1/10, 1000
//! delays), exact method of steps in rational form, evaluated with mpmath at 400 digits (the
//! constants c_k grow like (K/a)^k = 2^1000 ≈ 1e301 and cancel, so 400 digits leave ~100):
//!
//! ```text
//! # y' = -a y + K (1 - y(t - T)), y = 0 on [0, T]; on interval k, local u in [0, T]:
//! # y_k(u) = c_k + e^(-a u) p_k(u), p_k a polynomial, since (e^(-au) p)' + a e^(-au) p = e^(-au) p':
//! #   c_k = K (1 - c_(k-1))/a,  p_k' = -K p_(k-1),  p_k(0) = y_(k-1)(T) - c_k  (continuity)
//! from mpmath import mp, mpf, exp
//! mp.dps = 400
//! K, a, T = mpf(2), mpf(1), mpf(1)/10
//! c, p = mpf(0), [mpf(0)]
//! for k in range(1, 1001):
//!     yend = c + exp(-a*T) * sum(pj * T**j for j, pj in enumerate(p))
//!     ck = K*(1 - c)/a
//!     q = [yend - ck] + [-K*pj/(j+1) for j, pj in enumerate(p)]
//!     c, p = ck, q
//!     # y(t) for k T <= t < (k + 1) T: c + exp(-a (t - kT)) * sum(p_j (t - kT)^j)
//! ```

#![allow(clippy::excessive_precision)] // the references are quoted as the script printed them

mod common;

use common::real_root;
use ltikit::analysis::delay::{DelayMarch, DelayMethod};
use ltikit::analysis::{Factored, Input, StepInfoOptions};

/// L = K/(s + a).
fn first_order(k: f64, a: f64) -> Factored {
    Factored::from_zpk(&[], &[real_root(-a)], k).unwrap()
}

/// L = (Kp/tau)·(s + 1/Ti)/(s (s + 1/tau)): PI around 1/(tau s + 1).
fn pi_fopdt(kp: f64, ti: f64, tau: f64) -> Factored {
    Factored::from_zpk(
        &[real_root(-1.0 / ti)],
        &[real_root(0.0), real_root(-1.0 / tau)],
        kp / tau,
    )
    .unwrap()
}

#[test]
fn march_agrees_with_the_closed_form_where_it_is_exact() {
    // PI/FOPDT (Kp = 1/2, Ti = 3/2, tau = 1, T = 1) over 10 delays, the first-order loop
    // K = 2, a = 1, T = 1/2 over 6 delays: the pieces' closed form is accurate to ~1e-14
    // there (tests/delay_steps.rs, against sympy).
    for (l, delay, horizon) in [
        (pi_fopdt(0.5, 1.5, 1.0), 1.0, 10.95),
        (first_order(2.0, 1.0), 0.5, 3.2),
        (first_order(1.0, 1.0), 1.0, 9.9),
        // bi-proper: L = 0.5(s + 2)/(s + 1) = 0.5 + 0.5/(s + 1): y jumps at every kT, and
        // an impulse returns as δ every delay (the state's jumps (−D)^(k−1)·B)
        (
            Factored::from_zpk(&[real_root(-2.0)], &[real_root(-1.0)], 0.5).unwrap(),
            0.7,
            6.9,
        ),
    ] {
        for input in [Input::Step, Input::Ramp, Input::Sin(2.0), Input::Impulse] {
            let t: Vec<f64> = (0..=400).map(|i| horizon * i as f64 / 400.0).collect();
            let exact = l.delayed_feedback_response(delay, &input, &t).unwrap();
            assert_eq!(exact.method, DelayMethod::Pieces);
            let m = DelayMarch::new(&l, delay, &input, horizon).unwrap();
            let worst = t
                .iter()
                .zip(&exact.y)
                .map(|(&x, v)| (m.eval(x) - v).abs())
                .fold(0.0, f64::max);
            eprintln!(
                "{input:?} T = {delay}: march − closed form {worst:.2e}, estimate {:.2e}",
                m.estimated_error
            );
            assert!(worst <= 1e-12, "{input:?}: {worst:.2e}");
            assert!(m.estimated_error < 1e-12, "{:.2e}", m.estimated_error);
        }
    }
}

#[test]
fn first_order_loop_over_a_thousand_delays() {
    // K = 2, a = 1, T = 0.1: the mpmath script of the module docs, values rounded to 20 digits.
    let refs = [
        (0.25, 0.27374763005288322373),
        (1.03, 0.64893303790894071497),
        (2.51, 0.66661737819184521564),
        (5.05, 0.66666666464361447223),
        (10.37, 0.66666666666666666535),
        (25.0, 2.0 / 3.0),
        (49.95, 2.0 / 3.0),
        (99.99, 2.0 / 3.0),
    ];
    let l = first_order(2.0, 1.0);
    let t: Vec<f64> = refs.iter().map(|r| r.0).collect();
    let r = l.delayed_feedback_response(0.1, &Input::Step, &t).unwrap();
    assert_eq!(r.method, DelayMethod::CollocationMarch);
    let worst =
        r.y.iter()
            .zip(&refs)
            .map(|(v, (_, want))| (v - want).abs())
            .fold(0.0, f64::max);
    eprintln!(
        "1000 delays: worst {worst:.2e}, estimated {:.2e}, cross-check on the first pieces {:.2e}",
        r.estimated_error, r.closed_form_error
    );
    assert!(worst <= 1e-10, "{worst:.2e}");
    assert!(r.estimated_error < 1e-10 && r.closed_form_error < 1e-12);
}

#[test]
fn integrating_loop_over_long_horizons() {
    // L = 2/s (PI kp = ki = 2 around 1/(s + 1), the pole cancelled), T = 0.1: y' = 2(1 −
    // y(t − T)); y∞ = 1 and the decay is that of the rightmost root of s + 2e^(−0.1 s).
    let l = Factored::from_zpk(&[], &[real_root(0.0)], 2.0).unwrap();
    let roots = l.closed_loop_delay_roots(0.1, 2).unwrap();
    let s1 = roots.roots[0].value;
    assert!(s1.re < 0.0);
    let t: Vec<f64> = (0..=2000).map(|i| 0.05 * i as f64).collect(); // to 1000 delays
    let r = l.delayed_feedback_response(0.1, &Input::Step, &t).unwrap();
    assert_eq!(r.method, DelayMethod::CollocationMarch);
    // y(t) − 1 ∝ e^(s₁ t) for large t (s₁ ≈ −2.6 is real: 2·0.1 < 1/e; the next root lies
    // beyond −30, its share e^(−27·3) below rounding): |y(6) − 1|/|y(3) − 1| = e^(3 s₁)
    let err_at = |x: f64| (r.y[(x / 0.05).round() as usize] - 1.0).abs();
    assert!(err_at(100.0) < 1e-12, "{:.2e}", err_at(100.0));
    assert_eq!(s1.im, 0.0);
    let ratio = err_at(6.0) / err_at(3.0);
    let want = (3.0 * s1.re).exp();
    eprintln!("decay ratio {ratio:.12e} against e^(3 s1) = {want:.12e}");
    assert!((ratio / want - 1.0).abs() < 1e-7, "{ratio} {want}");
}

#[test]
fn stiff_loop_stays_accurate() {
    // L = 1/((s + 1)(s + 1000)), T = 0.5: |λ|T = 500 → 63 sub-intervals per delay. The closed
    // form is accurate over 8 delays (|L(0)| = 1e-3: the pieces shrink).
    let l = Factored::from_zpk(&[], &[real_root(-1.0), real_root(-1000.0)], 1.0).unwrap();
    let horizon = 4.2;
    let t: Vec<f64> = (0..=300).map(|i| horizon * i as f64 / 300.0).collect();
    let exact = l.delayed_feedback_response(0.5, &Input::Step, &t).unwrap();
    let m = DelayMarch::new(&l, 0.5, &Input::Step, horizon).unwrap();
    assert!(m.sub >= 60, "{}", m.sub);
    let worst = t
        .iter()
        .zip(&exact.y)
        .map(|(&x, v)| (m.eval(x) - v).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "stiff: {worst:.2e} (y ~ 1e-3), estimate {:.2e}",
        m.estimated_error
    );
    assert!(worst <= 1e-15, "{worst:.2e}");
    // and a long horizon: y∞ = L(0)/(1 + L(0)) = 1/1001
    let r = l
        .delayed_feedback_response(0.5, &Input::Step, &[200.0])
        .unwrap();
    assert!((r.y[0] - 1.0 / 1001.0).abs() < 1e-15, "{}", r.y[0]);
}

#[test]
fn step_metrics_over_a_long_horizon_match_a_dense_evaluation() {
    // PI kp = ki = 2 around 1/(s + 1) with T = 0.1: L = 2/s; 80 delays.
    let l = pi_fopdt(2.0, 1.0, 1.0);
    let horizon = 8.0;
    let s = l
        .delayed_step_info(0.1, horizon, true, &StepInfoOptions::default())
        .unwrap()
        .unwrap();
    let t: Vec<f64> = (0..=80_000)
        .map(|i| horizon * i as f64 / 80_000.0)
        .collect();
    let r = l.delayed_feedback_response(0.1, &Input::Step, &t).unwrap();
    let (mut peak, mut tp) = (0.0f64, 0.0);
    for (&x, &v) in t.iter().zip(&r.y) {
        if v > peak {
            peak = v;
            tp = x;
        }
    }
    let last_out = t
        .iter()
        .zip(&r.y)
        .filter(|(_, v)| (*v - 1.0).abs() > 0.02)
        .map(|(x, _)| *x)
        .fold(0.0, f64::max);
    let rise_start = t.iter().zip(&r.y).find(|(_, v)| **v >= 0.1).unwrap().0;
    eprintln!("{s:?}\ndense: peak {peak} at {tp}, last out {last_out}, rise start {rise_start}");
    assert!((s.peak.unwrap() - peak).abs() < 1e-8);
    assert!((s.peak_time.unwrap() - tp).abs() < 2e-3);
    assert!((s.settling_time.unwrap() - last_out).abs() < 2e-4);
    assert!((s.rise_start.unwrap() - rise_start).abs() < 2e-4);
    // 2·T < 1/e: the roots are real, y rises monotonically (dense max at the horizon)
    assert_eq!(s.overshoot_percent, Some(0.0));
    assert!(peak < 1.0);
}

#[test]
fn cli_analyze_gives_step_metrics_for_a_short_delay() {
    let out = common::ltikit(&[
        "analyze",
        "--num",
        "1",
        "--den",
        "1 1",
        "--delay",
        "0.1",
        "--controller",
        "pi:kp=2,ki=2",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    let err = String::from_utf8_lossy(&out.stderr);
    eprintln!("{text}\n{err}");
    assert!(out.status.success(), "{err}");
    assert!(!text.contains("lost their accuracy"), "{text}");
    // "settling time 1.625185 s (2 %)": against the last exit from the 2 % band of a dense
    // evaluation (10⁻⁴ s) of the same loop, L = C·G = 2(s + 1)/(s(s + 1)) = 2/s
    let settling: f64 = text
        .split("settling time ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|v| v.parse().ok())
        .expect("a settling time in the report");
    let l = pi_fopdt(2.0, 1.0, 1.0);
    let t: Vec<f64> = (0..=30_000).map(|i| 1e-4 * i as f64).collect();
    let r = l.delayed_feedback_response(0.1, &Input::Step, &t).unwrap();
    let last_out = t
        .iter()
        .zip(&r.y)
        .filter(|(_, v)| (*v - 1.0).abs() > 0.02)
        .map(|(x, _)| *x)
        .fold(0.0, f64::max);
    eprintln!("CLI settling {settling}, dense last exit {last_out}");
    assert!(
        settling > last_out && settling - last_out < 1.1e-4,
        "{settling} {last_out}"
    );
}

#[test]
fn limits_are_errors() {
    let l = first_order(2.0, 1.0);
    assert!(DelayMarch::new(&l, 1e-6, &Input::Step, 10.0).is_err()); // 10⁷ intervals
    assert!(DelayMarch::new(&l, 0.0, &Input::Step, 10.0).is_err());
    assert!(DelayMarch::new(&l, 0.1, &Input::Step, f64::NAN).is_err());
    // unstable at the delay (K = 2, a = 1 loses stability at T ≈ 1.2): overflow in the end
    let e = DelayMarch::new(&l, 2.0, &Input::Step, 190_000.0);
    assert!(e.is_err());
}
