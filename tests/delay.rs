//! Dead time e^(−sT) kept exact through the one seam (issue 21): the model types carry it,
//! the frequency response loses ωT of phase, the margins list the delayed crossings, the
//! responses are the rational ones shifted, the Nyquist spiral counts encirclements, the
//! discrete models absorb whole samples as z^(−d). References are closed forms derived in the
//! comments (or plain bisection, `common::bisect`, independent of the library).

mod common;

use std::f64::consts::{FRAC_PI_2, PI};

use common::{bisect, rel, tf};
use ltikit::analysis::Input;
use ltikit::lti::{Domain, Plant, delay};
use ltikit::{StateSpace, TransferFunction};
use nalgebra::DMatrix;
use num_complex::Complex64;

fn delayed(num: &[f64], den: &[f64], t: f64) -> TransferFunction {
    tf(num, den).with_delay(t).unwrap()
}

#[test]
fn the_phase_loses_omega_t_and_the_magnitude_is_unchanged() {
    // e^(−2s)/(s + 1): |G| = 1/√(1 + ω²), φ = −atan ω − 2ω (rad), continuous (no wrapping)
    let g = delayed(&[1.0], &[1.0, 1.0], 2.0);
    let w = [0.0, 0.1, 1.0, 10.0, 1000.0];
    let r = g.freq_response(&w).unwrap();
    for (i, &x) in w.iter().enumerate() {
        let phase = (-(x.atan()) - 2.0 * x).to_degrees();
        assert!(
            (r.phase_deg[i] - phase).abs() <= 1e-12 * phase.abs().max(1.0),
            "ω = {x}: {} vs {phase}",
            r.phase_deg[i]
        );
        assert!(rel(r.magnitude[i], 1.0 / (1.0 + x * x).sqrt()) < 1e-15);
    }
    // G(s)e^(−sT) at a complex point
    let f = g.factored().unwrap();
    let s = Complex64::new(0.3, 2.0);
    let want = (-s * 2.0).exp() / (s + 1.0);
    assert!((f.eval_delayed(s) - want).norm() < 1e-15 * want.norm());
}

#[test]
fn margins_of_a_first_order_loop_with_dead_time() {
    // L = K e^(−sT)/(s + 1), K = 2, T = 0.5: |L| = 1 at ω_c = √(K² − 1) = √3, where the phase
    // margin is 180° − atan √3 − √3·T (rad → deg) = 120° − 49.6214…°; the delay margin that
    // remains is (2π/3)/√3 − T (the critical delay arccos(−1/K)/√(K² − 1) minus T).
    let (k, t) = (2.0, 0.5);
    let m = delayed(&[k], &[1.0, 1.0], t).margins().unwrap();
    let wc = 3f64.sqrt();
    assert!(rel(m.gain_crossover.unwrap(), wc) < 1e-14);
    let pm = 120.0 - (wc * t).to_degrees();
    assert!(rel(m.phase_margin_deg.unwrap(), pm) < 1e-13, "{m:?}");
    let critical = (-1.0 / k).acos() / (k * k - 1.0).sqrt();
    assert!(rel(m.delay_margin.unwrap(), critical - t) < 1e-13);
    // the phase crossings solve atan ω + ωT = (2j + 1)π; gain margin √(1 + ω²)/K there
    assert!(m.crossings_listed_to.is_some());
    let listed_to = m.crossings_listed_to.unwrap();
    assert!(
        listed_to >= 6.0 * PI / t,
        "at least three turns of the delay: {listed_to}"
    );
    let mut expected = Vec::new();
    for j in 0.. {
        let level = (2 * j + 1) as f64 * PI;
        let f = |w: f64| w.atan() + w * t - level;
        let hi = level / t;
        if hi > listed_to * 1.5 {
            break;
        }
        let w = bisect(f, 0.0, hi);
        if w <= listed_to {
            expected.push(w);
        }
    }
    let got: Vec<f64> = m.phase_crossings.iter().map(|c| c.w).collect();
    assert_eq!(got.len(), expected.len(), "{got:?} vs {expected:?}");
    for (g, e) in got.iter().zip(&expected) {
        assert!(rel(*g, *e) < 1e-12, "{g} vs {e}");
    }
    let first = &m.phase_crossings[0];
    assert!(rel(first.gain_margin, (1.0 + first.w * first.w).sqrt() / k) < 1e-13);
    // the headline gain margin is the one closest to 0 dB: the first crossing
    assert_eq!(m.phase_crossover, Some(first.w));
}

#[test]
fn an_integrator_with_dead_time() {
    // L = K e^(−sT)/s: ω_c = K, PM = 90° − KT (rad → deg), delay margin π/(2K) − T; the first
    // phase crossing at ω = π/(2T) with gain margin π/(2KT).
    let (k, t) = (0.8, 0.25);
    let m = delayed(&[k], &[1.0, 0.0], t).margins().unwrap();
    assert!(rel(m.gain_crossover.unwrap(), k) < 1e-14);
    assert!(rel(m.phase_margin_deg.unwrap(), 90.0 - (k * t).to_degrees()) < 1e-13);
    assert!(rel(m.delay_margin.unwrap(), FRAC_PI_2 / k - t) < 1e-13);
    let first = &m.phase_crossings[0];
    assert!(rel(first.w, FRAC_PI_2 / t) < 1e-13);
    assert!(rel(first.gain_margin, FRAC_PI_2 / (k * t)) < 1e-13);
}

#[test]
fn responses_are_the_rational_ones_shifted() {
    // e^(−sT)/(s + 1), step: y = 0 for t < T, 1 − e^(−(t − T)) after
    let t0 = 0.7;
    let g = delayed(&[1.0], &[1.0, 1.0], t0);
    let f = g.factored().unwrap();
    let times = [0.0, 0.3, 0.7, 0.71, 1.0, 5.0, 30.0];
    let r = f.step_response(&times).unwrap();
    for (&t, &y) in times.iter().zip(&r.y) {
        let want = if t < t0 { 0.0 } else { 1.0 - (-(t - t0)).exp() };
        assert!((y - want).abs() < 1e-15, "t = {t}: {y} vs {want}");
    }
    assert_eq!(r.final_value, Some(1.0));
    // the closed form says so, and agrees with the samples
    let resp = f.response(&Input::Step, &[], &times).unwrap();
    assert_eq!(
        resp.closed_form.to_string(),
        "y(t) = f(t - 0.7)·1(t - 0.7), f(t) = 1 - e^(-t)"
    );
    assert!(resp.samples.closed_form_error < 1e-15);
    assert_eq!(resp.closed_form.eval(0.5), 0.0);
    // impulse: e^(−(t − T)) after T
    let r = f.impulse_response(&[0.5, 1.7]).unwrap();
    assert_eq!(r.y[0], 0.0);
    assert!((r.y[1] - (-1f64).exp()).abs() < 1e-15);
    // initial conditions of a delayed plant are refused (its past input is not an ODE state)
    assert!(f.time_response(&Input::Step, &[1.0], &[1.0]).is_err());
}

#[test]
fn step_metrics_move_by_the_delay() {
    // 1/(s + 1): settling (2 %) at ln 50, rise 10–90 % ln 9; with T = 1.5 the instants move
    let g = tf(&[1.0], &[1.0, 1.0]);
    let d = g.with_delay(1.5).unwrap().step_info().unwrap().unwrap();
    assert!(rel(d.settling_time.unwrap(), 50f64.ln() + 1.5) < 1e-13);
    assert!(rel(d.rise_time.unwrap(), 9f64.ln()) < 1e-13);
    assert!(rel(d.rise_start.unwrap(), (1.0 / 0.9f64).ln() + 1.5) < 1e-13);
}

#[test]
fn the_nyquist_spiral_counts_the_closed_loop_roots() {
    // K e^(−sT)/(s + 1), K = 2: stable in unity feedback iff T < arccos(−1/2)/√3 = 1.2092 s;
    // above it one pair of roots is in the right half plane (two encirclements), above
    // the second crossing delay (2π/3 + 2π)/√3 = 4.8368 s two pairs.
    let count = |t: f64| {
        let n =
            ltikit::analysis::nyquist_contour(&delayed(&[2.0], &[1.0, 1.0], t).factored().unwrap())
                .unwrap();
        n.closed_loop_rhp_poles.unwrap()
    };
    assert_eq!(count(0.5), 0);
    assert_eq!(count(1.1), 0);
    assert_eq!(count(1.3), 2);
    assert_eq!(count(4.5), 2);
    assert_eq!(count(5.2), 4);
    // a biproper loop's curve never closes: refused with a reason
    let e = ltikit::analysis::nyquist_contour(
        &delayed(&[1.0, 2.0], &[1.0, 1.0], 1.0).factored().unwrap(),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("never closes"), "{e}");
}

#[test]
fn pade_approximants() {
    // [2/2]: (1 − sT/2 + (sT)²/12)/(1 + sT/2 + (sT)²/12); T = 1: monic 12 + 6s + s²
    let p = delay::pade(1.0, 2).unwrap();
    let lead = p.den().coeffs()[0];
    let den: Vec<f64> = p.den().coeffs().iter().map(|c| c / lead).collect();
    let num: Vec<f64> = p.num().coeffs().iter().map(|c| c / lead).collect();
    assert_eq!(den, [1.0, 6.0, 12.0]);
    assert_eq!(num, [1.0, -6.0, 12.0]);
    // --pade on a plant: rational, order + n, same magnitude at every ω, phase error small at
    // low ωT and growing with it
    let f = delayed(&[1.0], &[1.0, 1.0], 0.5).factored().unwrap();
    let a = f.pade(5).unwrap();
    assert_eq!((a.delay(), a.order()), (0.0, 6));
    let w = [0.1, 1.0, 4.0];
    let (exact, approx) = (f.freq_response(&w).unwrap(), a.freq_response(&w).unwrap());
    for i in 0..w.len() {
        assert!(rel(approx.magnitude[i], exact.magnitude[i]) < 1e-12);
    }
    assert!((approx.phase_deg[0] - exact.phase_deg[0]).abs() < 1e-12);
    assert!((approx.phase_deg[2] - exact.phase_deg[2]).abs() < 1.0);
    // bad orders and delays
    assert!(delay::pade(1.0, 0).is_err() && delay::pade(1.0, 21).is_err());
    assert!(f.pade(0).is_err());
}

#[test]
fn discrete_delays_are_whole_samples_absorbed_as_poles_at_zero() {
    // G(z) = 0.5/(z − 0.5), dt = 0.1, delay 0.2 s = 2 samples: 0.5/(z³ − 0.5 z²); its impulse
    // response is the undelayed one two samples later
    let dtm = Domain::discrete(0.1).unwrap();
    let g = tf(&[0.5], &[1.0, -0.5]).with_domain(dtm);
    let d = g.clone().with_delay(0.2).unwrap();
    assert_eq!(d.den().coeffs(), &[1.0, -0.5, 0.0, 0.0]);
    assert_eq!(d.delay(), 0.0);
    let t: Vec<f64> = (0..10).map(|k| k as f64 * 0.1).collect();
    let a = g.factored().unwrap().impulse_response(&t).unwrap();
    let b = d.factored().unwrap().impulse_response(&t).unwrap();
    for k in 2..10 {
        assert!((b.y[k] - a.y[k - 2]).abs() < 1e-15, "k = {k}");
    }
    assert_eq!((b.y[0], b.y[1]), (0.0, 0.0));
    // not a whole number of samples
    let e = g.with_delay(0.25).unwrap_err().to_string();
    assert!(e.contains("whole number of sampling periods"), "{e}");
}

#[test]
fn sampling_a_delay_of_whole_periods_is_exact_at_the_samples() {
    // ZOH is exact at the samples for a step input: the c2d of e^(−0.3 s)/(s + 1) at
    // dt = 0.1 has the step response 1 − e^(−(kT − 0.3)) from k = 3 on, 0 before.
    let f = delayed(&[1.0], &[1.0, 1.0], 0.3).factored().unwrap();
    let z = f.c2d(0.1, ltikit::lti::Discretization::Zoh).unwrap();
    assert_eq!(z.delay(), 0.0);
    let t: Vec<f64> = (0..20).map(|k| k as f64 * 0.1).collect();
    let r = z.step_response(&t).unwrap();
    for (k, (&tk, &y)) in t.iter().zip(&r.y).enumerate() {
        let want = if k < 3 {
            0.0
        } else {
            1.0 - (-(tk - 0.3)).exp()
        };
        assert!((y - want).abs() < 1e-14, "k = {k}: {y} vs {want}");
    }
    // a fraction of a period: zoh samples it (the modified z-transform, below), not matched
    assert!(f.c2d(0.07, ltikit::lti::Discretization::Zoh).is_ok());
    assert!(f.c2d(0.07, ltikit::lti::Discretization::Matched).is_err());
}

#[test]
fn state_space_channels_carry_their_input_and_output_delays() {
    // two decoupled first-order channels ẋᵢ = −xᵢ + uᵢ, yᵢ = xᵢ, plus a cross term y₁ += x₂;
    // input delays [0.5, 1.0], output delays [0.25, 0]
    let ss = StateSpace::new(
        DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -1.0]),
        DMatrix::identity(2, 2),
        DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 0.0, 1.0]),
        DMatrix::zeros(2, 2),
    )
    .unwrap()
    .with_delays(vec![0.5, 1.0], vec![0.25, 0.0])
    .unwrap();
    assert_eq!(ss.channel_delay(1, 0), 1.25);
    let ch = ss.channel(1, 0).unwrap();
    let f = ltikit::analysis::Factored::from_state_space(&ch).unwrap();
    assert_eq!(f.delay(), 1.25);
    // the step on input 2 reaches output 1 after 1.25 s and output 2 after 1.0 s
    let t = [0.5, 1.1, 2.0, 3.0];
    let r = ss.step_response_from(1, &t, false).unwrap();
    for (k, &tk) in t.iter().enumerate() {
        let y1 = if tk < 1.25 {
            0.0
        } else {
            1.0 - (-(tk - 1.25)).exp()
        };
        let y2 = if tk < 1.0 {
            0.0
        } else {
            1.0 - (-(tk - 1.0)).exp()
        };
        assert!((r.y[0][k] - y1).abs() < 1e-14 && (r.y[1][k] - y2).abs() < 1e-14);
    }
    // whole-model operations that would need the delays inside the matrices say so
    assert!(ss.series(&ss).is_err());
    assert!(ss.c2d(0.1, ltikit::lti::Discretization::Zoh).is_err());
    assert!(ss.clone().with_delays(vec![0.1], vec![]).is_err()); // wrong length
}

#[test]
fn interconnections_add_or_refuse_delays() {
    let a = delayed(&[1.0], &[1.0, 1.0], 0.5);
    let b = delayed(&[1.0], &[1.0, 2.0], 0.25);
    assert_eq!(a.series(&b).unwrap().delay(), 0.75);
    let fa = a.factored().unwrap();
    let fb = b.factored().unwrap();
    assert_eq!(fa.series(&fb).unwrap().delay(), 0.75);
    assert!(a.parallel(&b).is_err() && fa.parallel(&fb).is_err());
    assert_eq!(a.parallel(&a).unwrap().delay(), 0.5);
    let e = a
        .feedback(&TransferFunction::constant(1.0), -1.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("dead time"), "{e}");
    assert!(fa.feedback(&fb, -1.0).is_err());
}

#[test]
fn plants_with_delays_from_files_and_text() {
    let dir = std::env::temp_dir().join(format!("ltikit-delay-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("fopdt.toml");
    std::fs::write(&p, "num = [2]\nden = [3, 1]\ndelay = 0.5\n").unwrap();
    let plant = Plant::from_file(&p).unwrap();
    assert_eq!(plant.delay(), 0.5);
    assert_eq!(plant.factored().unwrap().delay(), 0.5);
    let q = dir.join("mimo.toml");
    std::fs::write(
        &q,
        "a = [[-1, 0], [0, -2]]\nb = [[1, 0], [0, 1]]\nc = [[1, 1]]\ninput_delays = [0.1, 0.2]\noutput_delays = [0.3]\n",
    )
    .unwrap();
    let plant = Plant::from_file(&q).unwrap();
    assert!((plant.factored_channel(1, 0).unwrap().delay() - 0.5).abs() < 1e-15);
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "num = [1]\nden = [1, 1]\ndelay = -1\n").unwrap();
    let e = Plant::from_file(&bad).unwrap_err().to_string();
    assert!(e.contains("delay") && e.contains("line 3"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_delays_are_one_clear_error() {
    let g = tf(&[1.0], &[1.0, 1.0]);
    for t in [-1.0, f64::NAN, f64::INFINITY, 1e300, 2e6] {
        let e = g.clone().with_delay(t).unwrap_err().to_string();
        assert!(e.contains("`delay`"), "{t}: {e}");
    }
    assert!(g.clone().with_delay(1e6).is_ok());
}

#[test]
fn a_fraction_of_a_period_is_sampled_by_the_modified_z_transform() {
    // e^(−0.25 s)/(s + 1) at dt = 0.1: two whole periods and τ = 0.05. With a ZOH the step
    // is exact at the samples: y[k] = 1 − e^(−(kT − 0.25)) for kT ≥ 0.25, 0 before (k ≤ 2).
    let f = delayed(&[1.0], &[1.0, 1.0], 0.25).factored().unwrap();
    let z = f.c2d(0.1, ltikit::lti::Discretization::Zoh).unwrap();
    // poles: e^(−0.1) and z = 0 for the held input, two more for z^(−2)
    assert_eq!(z.order(), 4);
    let t: Vec<f64> = (0..30).map(|k| k as f64 * 0.1).collect();
    let r = z.step_response(&t).unwrap();
    for (k, (&tk, &y)) in t.iter().zip(&r.y).enumerate() {
        let want = if tk < 0.25 {
            0.0
        } else {
            1.0 - (-(tk - 0.25)).exp()
        };
        assert!((y - want).abs() < 1e-14, "k = {k}: {y} vs {want}");
    }
    // the transfer-function path agrees
    let g = delayed(&[1.0], &[1.0, 1.0], 0.25)
        .c2d(0.1, ltikit::lti::Discretization::Zoh)
        .unwrap();
    let r2 = g.factored().unwrap().step_response(&t).unwrap();
    for (a, b) in r.y.iter().zip(&r2.y) {
        assert!((a - b).abs() < 1e-13);
    }
    // other methods take whole periods only
    let e = f
        .c2d(0.1, ltikit::lti::Discretization::Tustin { prewarp: None })
        .unwrap_err()
        .to_string();
    assert!(e.contains("only zoh"), "{e}");
}

/// The command line on a loop around a dead time: the delayed loop is analysed exactly —
/// stability in the delay (K = 2, T = 0.5 in L = 2/(s + 1): critical delay
/// arccos(−1/2)/√3 = 1.2092 s), the closed-loop response by the method of steps (on
/// [T, 2T] the first piece 2(1 − e^(−(t − T)))), and the margins of L·e^(−sT).
#[cfg(feature = "cli")]
#[test]
fn the_command_line_closes_the_loop_around_the_delay_exactly() {
    let plant = [
        "--num",
        "2",
        "--den",
        "1 1",
        "--delay",
        "0.5",
        "--controller",
        "p:kp=1",
    ];
    let run = |extra: &[&str]| {
        let mut args = extra.to_vec();
        args.extend_from_slice(&plant);
        let out = common::ltikit(&args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let doc: serde_json::Value = serde_json::from_str(&run(&["analyze", "--json"])).unwrap();
    assert_eq!(doc["delay"], 0.5);
    let st = &doc["stability_in_delay"];
    let critical = st["critical_delay"].as_f64().unwrap();
    assert!(rel(critical, (-0.5f64).acos() / 3f64.sqrt()) < 1e-12);
    assert_eq!(st["stable"], true);
    let y_inf = doc["step_info"]["steady_state"].as_f64().unwrap();
    assert!(rel(y_inf, 2.0 / 3.0) < 1e-14);
    let r: serde_json::Value =
        serde_json::from_str(&run(&["response", "--json", "--t", "0.2 0.8"])).unwrap();
    assert_eq!(r["y"][0], 0.0);
    let y = r["y"][1].as_f64().unwrap();
    assert!((y - 2.0 * (1.0 - (-0.3f64).exp())).abs() < 1e-14, "{y}");
    // unstable beyond the critical delay; the margins are those of L·e^(−sT)
    let out = common::ltikit(&[
        "analyze",
        "--num",
        "2",
        "--den",
        "1 1",
        "--delay",
        "1.3",
        "--controller",
        "p:kp=1",
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("unstable: 2 characteristic roots"), "{text}");
    let m: serde_json::Value = serde_json::from_str(&run(&["margins", "--json"])).unwrap();
    assert!(rel(m["delay_margin"].as_f64().unwrap(), critical - 0.5) < 1e-12);
    // C·S is refused with the way out, and a picture is drawn
    let out = common::ltikit(&[
        "analyze",
        "--num",
        "2",
        "--den",
        "1 1",
        "--delay",
        "0.5",
        "--controller",
        "p:kp=1",
        "--control-sensitivity",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--pade"));
    let png = std::env::temp_dir().join(format!("ltikit-delay-step-{}.png", std::process::id()));
    let mut args = vec!["step", "-o", png.to_str().unwrap()];
    args.extend_from_slice(&plant);
    assert!(common::ltikit(&args).status.success());
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    std::fs::remove_file(&png).ok();
    // `ltikit pade`
    let p: serde_json::Value = serde_json::from_str(
        &String::from_utf8(
            common::ltikit(&["pade", "--delay", "1", "--order", "2", "--json"]).stdout,
        )
        .unwrap(),
    )
    .unwrap();
    assert_eq!(
        p["den"][2].as_f64().unwrap() / p["den"][0].as_f64().unwrap(),
        12.0
    );
}

/// A batch line takes `delay` and its document says so; the settling time includes it
/// (1/(s + 1): ln 50 + T).
#[cfg(feature = "cli")]
#[test]
fn batch_lines_carry_the_delay() {
    let out = common::ltikit_with_stdin(
        &["analyze", "--batch", "-"],
        b"{\"num\": [1], \"den\": [1, 1], \"delay\": 0.5}\n{\"num\": [1], \"den\": [1, 1], \"delay\": -1}\n",
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    let doc: serde_json::Value = serde_json::from_str(lines.next().unwrap()).unwrap();
    assert_eq!(doc["delay"], 0.5);
    let ts = doc["step_info"]["settling_time"].as_f64().unwrap();
    assert!(rel(ts, 50f64.ln() + 0.5) < 1e-12, "{ts}");
    let bad: serde_json::Value = serde_json::from_str(lines.next().unwrap()).unwrap();
    assert!(bad["error"].as_str().unwrap().contains("`delay`"));
}
