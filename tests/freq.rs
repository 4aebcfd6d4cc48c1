//! Frequency response (magnitude, dB, continuous phase) and the automatic grids.
//!
//! References: the seed's exercise 3.2 (second-order M(ω), φ(ω) — with the true, negative
//! phase lag), the first-order tank (seed eq. 3.5), the phase conventions of DESIGN §1.3, and
//! a double-double Horner evaluation of the coefficients for random plants.

use ltikit::TransferFunction;
use ltikit::analysis::{auto_frequency_grid, auto_time_grid, auto_time_span};
use ltikit::numeric::dd::Dd;
use num_complex::Complex64;
use proptest::prelude::*;

mod common;
use common::{logspace, tf};

/// Wraps radians into (−π, π].
fn wrap(x: f64) -> f64 {
    let y = x - std::f64::consts::TAU * (x / std::f64::consts::TAU).round();
    if y <= -std::f64::consts::PI {
        y + std::f64::consts::TAU
    } else {
        y
    }
}

#[test]
fn seed_exercise_3_2_second_order_magnitude_and_phase() {
    // ẍ + 2ζωn ẋ + ωn² x = sin ωt: M = 1/√((ωn² − ω²)² + 4ζ²ωn²ω²),
    // φ = −atan2(2ζωnω, ωn² − ω²) (a lag; the seed prints it without the minus sign).
    for &wn in &[1.0, 3.0] {
        for &z in &[0.05, 0.5, 1.0, 2.0] {
            let g = tf(&[1.0], &[1.0, 2.0 * z * wn, wn * wn]);
            let w = logspace(-3.0, 3.0, 601);
            let r = g.freq_response(&w).unwrap();
            for (i, &x) in w.iter().enumerate() {
                let m = 1.0 / ((wn * wn - x * x).powi(2) + 4.0 * z * z * wn * wn * x * x).sqrt();
                let phi = -(2.0 * z * wn * x).atan2(wn * wn - x * x);
                assert!(
                    (r.magnitude[i] - m).abs() <= 1e-13 * m,
                    "ζ={z} ω={x}: {} vs {m}",
                    r.magnitude[i]
                );
                assert!((r.magnitude_db[i] - 20.0 * m.log10()).abs() < 1e-11);
                assert!(
                    (r.phase_deg[i] - phi.to_degrees()).abs() < 1e-11,
                    "ζ={z} ω={x}: {} vs {}",
                    r.phase_deg[i],
                    phi.to_degrees()
                );
            }
        }
    }
}

#[test]
fn seed_tank_first_order() {
    // A ḣ + r h = q_i (seed eq. 3.5): G = 1/(A s + r), M = 1/√(r² + A²ω²), φ = −atan(Aω/r).
    for &(a, r) in &[(2.0, 0.5), (0.1, 3.0)] {
        let g = tf(&[1.0], &[a, r]);
        let w = logspace(-4.0, 4.0, 81);
        let resp = g.freq_response(&w).unwrap();
        for (i, &x) in w.iter().enumerate() {
            let m = 1.0 / (r * r + a * a * x * x).sqrt();
            assert!((resp.magnitude[i] - m).abs() <= 1e-14 * m);
            assert!((resp.phase_deg[i] + (a * x / r).atan().to_degrees()).abs() < 1e-12);
        }
    }
}

#[test]
fn design_phase_conventions() {
    let at = |g: &TransferFunction, w: f64| g.freq_response(&[w]).unwrap().phase_deg[0];
    // 1/s³ starts (and stays) at −270°
    let g = tf(&[1.0], &[1.0, 0.0, 0.0, 0.0]);
    for w in [1e-6, 1.0, 1e6] {
        assert!((at(&g, w) + 270.0).abs() < 1e-12);
    }
    // an integrator starts at −90°, ω = 0 included
    let g = tf(&[1.0], &[1.0, 1.0, 0.0]);
    let r = g.freq_response(&[0.0, 1e-9]).unwrap();
    assert!((r.phase_deg[0] + 90.0).abs() < 1e-12 && r.magnitude[0].is_infinite());
    assert!(r.magnitude_db[0] == f64::INFINITY);
    assert!((r.phase_deg[1] + 90.0).abs() < 1e-6);
    // a negative gain starts at −180°
    let g = tf(&[-2.0], &[1.0, 1.0]);
    assert!((at(&g, 0.0) + 180.0).abs() < 1e-12);
    assert!((at(&g, 1.0) + 225.0).abs() < 1e-12);
    // 1/(s² + 1): 0° below ω = 1, −90° (midpoint, |G| = ∞) at 1, −180° above
    let g = tf(&[1.0], &[1.0, 0.0, 1.0]);
    let r = g.freq_response(&[0.999_999, 1.0, 1.000_001]).unwrap();
    assert!(r.phase_deg[0].abs() < 1e-12);
    assert!((r.phase_deg[1] + 90.0).abs() < 1e-12 && r.magnitude[1] == f64::INFINITY);
    assert!((r.phase_deg[2] + 180.0).abs() < 1e-12);
    // the same through a computed (not exactly real-part-zero) root: (s²+1)(s+2)
    let g = tf(&[2.0], &[1.0, 2.0, 1.0, 2.0]);
    let r = g.freq_response(&[0.999, 1.0, 1.001]).unwrap();
    let lag = |w: f64| (w / 2.0).atan().to_degrees();
    assert!((r.phase_deg[0] + lag(0.999)).abs() < 1e-9);
    assert!((r.phase_deg[1] + 90.0 + lag(1.0)).abs() < 1e-9);
    assert!(r.magnitude[1] == f64::INFINITY);
    assert!((r.phase_deg[2] + 180.0 + lag(1.001)).abs() < 1e-9);
    // an imaginary-axis zero pair raises the phase by 180°: (s² + 4)/(s + 1)³
    let g = tf(&[1.0, 0.0, 4.0], &[1.0, 3.0, 3.0, 1.0]);
    let r = g.freq_response(&[1.999, 2.0, 2.001]).unwrap();
    let base = |w: f64| -3.0 * w.atan().to_degrees();
    assert!((r.phase_deg[0] - base(1.999)).abs() < 1e-9);
    assert!((r.phase_deg[1] - base(2.0) - 90.0).abs() < 1e-9);
    assert!(r.magnitude[1] == 0.0 && r.magnitude_db[1] == f64::NEG_INFINITY);
    assert!((r.phase_deg[2] - base(2.001) - 180.0).abs() < 1e-9);
    // a right-half-plane zero adds lag: (1 − s)/(1 + s) goes 0° → −180°,
    // (1 + s)/(1 + s)… is not reduced away, so compare with the LHP version instead.
    let rhp = tf(&[-1.0, 1.0], &[1.0, 1.0]);
    let lhp = tf(&[1.0, 1.0], &[1.0, 2.0]);
    assert!((at(&rhp, 1e6) + 180.0).abs() < 1e-3);
    assert!((at(&rhp, 1.0) + 90.0).abs() < 1e-12);
    assert!(at(&lhp, 1e6).abs() < 1e-3);
    // (s − 1)/(s + 1): K = −1 → starts at −180°, the RHP zero lags → −360° at ∞
    let g = tf(&[1.0, -1.0], &[1.0, 1.0]);
    assert!((at(&g, 0.0) + 180.0).abs() < 1e-12);
    assert!((at(&g, 1e8) + 360.0).abs() < 1e-5);
}

#[test]
fn phase_is_grid_independent_and_continuous() {
    // Ten lightly damped pairs (ζ = 0.002) spread over two decades: the phase falls by 180° at
    // each (−1800° in all); a three-point grid must give the same values as a fine grid (ControlSystems.jl
    // #757 and python-control #467 unwrap on the grid and get these wrong).
    let mut roots = Vec::new();
    for k in 0..10 {
        let wn = 10f64.powf(-1.0 + 0.2 * k as f64);
        let z = 0.002;
        roots.push(Complex64::new(-z * wn, wn * (1.0 - z * z).sqrt()));
        roots.push(Complex64::new(-z * wn, -wn * (1.0 - z * z).sqrt()));
    }
    let g = TransferFunction::from_zpk(&[], &roots, 1.0).unwrap();
    let coarse = [0.05, 1.05, 200.0];
    let rc = g.freq_response(&coarse).unwrap();
    let fine = logspace(-2.0, 3.0, 20_001);
    let rf = g.freq_response(&fine).unwrap();
    for (i, &w) in coarse.iter().enumerate() {
        let single = g.freq_response(&[w]).unwrap();
        assert!((single.phase_deg[0] - rc.phase_deg[i]).abs() < 1e-12);
    }
    // continuity on the fine grid: no jump larger than the steepest true slope allows
    let max_jump = rf
        .phase_deg
        .windows(2)
        .map(|p| (p[1] - p[0]).abs())
        .fold(0.0, f64::max);
    assert!(max_jump < 90.0, "jump {max_jump}");
    assert!(rf.phase_deg[0].abs() < 1.0);
    assert!(
        (rf.phase_deg.last().unwrap() + 1800.0).abs() < 0.1,
        "{:?}",
        &rf.phase_deg[rf.phase_deg.len() - 3..]
    );
    assert!((rc.phase_deg[2] + 1800.0).abs() < 1.0);
}

/// G(jω) by Horner's rule in double-double arithmetic (the reference for random plants).
fn horner_dd(g: &TransferFunction, w: f64) -> Complex64 {
    let eval = |c: &[f64]| {
        let (mut re, mut im) = (Dd::from(0.0), Dd::from(0.0));
        let wd = Dd::from(w);
        for &a in c {
            // (re + j im)(jω) + a = (a − ω im) + j ω re
            let nre = Dd::from(a) - wd * im;
            let nim = wd * re;
            re = nre;
            im = nim;
        }
        Complex64::new(re.to_f64(), im.to_f64())
    };
    eval(g.num().coeffs()) / eval(g.den().coeffs())
}

/// A random real polynomial's roots: real ones and conjugate pairs, in both half planes,
/// magnitudes 10^[−1, 1], damping ratios ≥ 0.05.
fn roots_strategy(max: usize) -> impl Strategy<Value = Vec<Complex64>> {
    prop::collection::vec(
        (
            any::<bool>(),
            -1.0f64..1.0,
            0.05f64..1.0,
            any::<bool>(),
            0usize..5,
        ),
        0..=max,
    )
    .prop_map(|spec| {
        let mut out = Vec::new();
        for (pair, lm, zeta, rhp, rep) in spec {
            let m = 10f64.powf(lm);
            let sign = if rhp { 1.0 } else { -1.0 };
            let n = if rep == 0 { 2 } else { 1 }; // sometimes a repeated root
            for _ in 0..n {
                if pair {
                    let re = sign * zeta * m;
                    let im = m * (1.0 - zeta * zeta).sqrt();
                    out.push(Complex64::new(re, im));
                    out.push(Complex64::new(re, -im));
                } else {
                    out.push(Complex64::new(sign * m, 0.0));
                }
            }
        }
        out
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, .. ProptestConfig::default() })]

    /// Factored evaluation agrees with (double-double) Horner on the coefficients to 1e-10
    /// relative in magnitude and phase (mod 2π), orders up to ~20.
    #[test]
    fn factored_form_matches_horner(
        zeros in roots_strategy(3),
        poles in roots_strategy(5),
        lk in -2.0f64..2.0,
        neg in any::<bool>(),
    ) {
        let k = if neg { -(10f64.powf(lk)) } else { 10f64.powf(lk) };
        let g = TransferFunction::from_zpk(&zeros, &poles, k).unwrap();
        let w = logspace(-3.0, 3.0, 121);
        let r = g.freq_response(&w).unwrap();
        for (i, &x) in w.iter().enumerate() {
            let h = horner_dd(&g, x);
            let rel = (r.magnitude[i] - h.norm()).abs() / h.norm();
            prop_assert!(rel < 1e-10, "ω={} |G|={} Horner {} rel {:e}", x, r.magnitude[i], h.norm(), rel);
            // and against plain f64 Horner (`TransferFunction::eval`) within its own
            // rounding-error bound γ·eps·(Σ|nᵢ|ωⁱ + |G|·Σ|dᵢ|ωⁱ)/|D(jω)|
            let f = g.eval(Complex64::new(0.0, x));
            let d = g.den().eval_complex(Complex64::new(0.0, x)).norm();
            let n_abs = g.num().eval_abs(x);
            let d_abs = g.den().eval_abs(x);
            let n_deg = g.num().degree().max(g.den().degree()) as f64;
            let bound = 4.0 * (n_deg + 2.0) * f64::EPSILON * (n_abs + h.norm() * d_abs) / d;
            prop_assert!((r.magnitude[i] - f.norm()).abs() <= 1e-10 * h.norm() + bound);
            let dphi = wrap(r.phase_deg[i].to_radians() - h.arg());
            prop_assert!(dphi.abs() < 1e-9, "ω={} φ={} Horner {}", x, r.phase_deg[i], h.arg().to_degrees());
        }
        // ω = 0 is on the asymptote's branch: 0° or −180° by the sign of K = G(0), where
        // each real right-half-plane root flips the sign of k
        let rhp_count = |v: &[Complex64]| v.iter().filter(|p| p.re > 0.0 && p.im == 0.0).count();
        let flips = (rhp_count(&zeros) + rhp_count(&poles)) % 2 == 1;
        let start = if (k < 0.0) != flips { -180.0 } else { 0.0 };
        let r0 = g.freq_response(&[0.0, 1e-9]).unwrap();
        prop_assert!((r0.phase_deg[0] - start).abs() < 1e-12, "start {} vs {}", r0.phase_deg[0], start);
        prop_assert!((r0.phase_deg[1] - start).abs() < 1e-5);
    }
}

#[test]
fn high_order_high_frequency_magnitude_in_log_form() {
    // (s + 1)^-60 at ω = 1e10: |G| = (1 + 1e20)^-30 ≈ 1e-600 (below f64): 0 as a ratio, but
    // the dB value is exact: 20·log10((1 + ω²)^-30) = −600·log10(1 + ω²). The expanded
    // binomial coefficients (up to 1.2e17, rounded) make the 60-fold root hopelessly
    // ill-conditioned; the evaluation still matches the coefficients.
    let mut den = vec![1.0];
    for _ in 0..60 {
        let mut next = vec![0.0; den.len() + 1];
        for (i, &c) in den.iter().enumerate() {
            next[i] += c;
            next[i + 1] += c;
        }
        den = next;
    }
    let g = tf(&[1.0], &den);
    let r = g.freq_response(&[1e10, 1.0]).unwrap();
    let exact_db = -600.0 * (1.0 + 1e20f64).log10();
    assert!(
        (r.magnitude_db[0] - exact_db).abs() < 1e-9 * exact_db.abs(),
        "{} vs {exact_db}",
        r.magnitude_db[0]
    );
    assert_eq!(r.magnitude[0], 0.0);
    assert!((r.phase_deg[0] + 60.0 * (1e10f64).atan().to_degrees()).abs() < 1e-8);
    let h = horner_dd(&g, 1.0);
    assert!(
        (r.magnitude[1] - h.norm()).abs() < 1e-10 * h.norm(),
        "{} vs {}",
        r.magnitude[1],
        h.norm()
    );
    assert!((r.magnitude_db[1] + 600.0 * 2f64.log10()).abs() < 1e-6);
    assert!(
        (r.phase_deg[1] + 60.0 * 45.0).abs() < 1e-6,
        "{}",
        r.phase_deg[1]
    );
}

#[test]
fn improper_and_static_systems() {
    // s: |G| = ω, φ = +90°; 3: flat; 0: −∞ dB
    let d = tf(&[1.0, 0.0], &[1.0]);
    let r = d.freq_response(&[0.0, 2.0]).unwrap();
    assert_eq!(r.magnitude[0], 0.0);
    assert!((r.magnitude[1] - 2.0).abs() < 1e-15 && (r.phase_deg[1] - 90.0).abs() < 1e-12);
    let k = tf(&[3.0], &[1.0]);
    let r = k.freq_response(&[0.0, 5.0]).unwrap();
    assert!((r.magnitude[0] - 3.0).abs() < 1e-15 && (r.magnitude[1] - 3.0).abs() < 1e-15);
    let z = tf(&[0.0], &[1.0, 1.0]);
    let r = z.freq_response(&[1.0]).unwrap();
    assert_eq!(r.magnitude_db[0], f64::NEG_INFINITY);
    // cancelled factors: s(s+2)/(s(s+1)(s+2)) is 1/(s+1), finite at ω = 0
    let c = tf(&[1.0, 2.0, 0.0], &[1.0, 3.0, 2.0, 0.0]);
    let r = c.freq_response(&[0.0, 1.0]).unwrap();
    assert!((r.magnitude[0] - 1.0).abs() < 1e-14 && r.phase_deg[0].abs() < 1e-14);
    assert!((r.phase_deg[1] + 45.0).abs() < 1e-9);
}

#[test]
fn bad_frequencies_name_the_problem() {
    let g = tf(&[1.0], &[1.0, 1.0]);
    let e = g.freq_response(&[1.0, f64::NAN]).unwrap_err().to_string();
    assert!(e.contains("w[1]"), "{e}");
    let e = g.freq_response(&[0.5, -2.0]).unwrap_err().to_string();
    assert!(e.contains("w[1]") && e.contains("-2"), "{e}");
    assert!(g.freq_response(&[f64::NEG_INFINITY]).is_err());
}

// ---------------------------------------------------------------- automatic grids

#[test]
fn frequency_grid_draws_a_lightly_damped_peak_at_its_height() {
    // ζ = 0.01: Mr = 1/(2ζ√(1−ζ²)) ≈ 34 dB at ωr = ωn√(1−2ζ²).
    for &wn in &[1.0, 7.3] {
        let z = 0.01;
        let g = tf(&[wn * wn], &[1.0, 2.0 * z * wn, wn * wn]);
        let w = auto_frequency_grid(&g.factored().unwrap(), 100).unwrap();
        assert!(w.windows(2).all(|p| p[0] < p[1]), "sorted and unique");
        let r = g.freq_response(&w).unwrap();
        let mr_db = -20.0 * (2.0 * z * (1.0 - z * z).sqrt()).log10();
        let top = r
            .magnitude_db
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        assert!((top - mr_db).abs() < 0.1, "drawn {top} dB vs {mr_db} dB");
        assert!((top - mr_db).abs() < 1e-9, "ωr is on the grid");
        // and the piecewise-linear curve (in dB over ω) stays within 0.1 dB of the truth
        // around the peak
        let fine: Vec<f64> = (0..4001)
            .map(|i| wn * (1.0 + 0.5 * (i as f64 / 2000.0 - 1.0)))
            .collect();
        let rf = g.freq_response(&fine).unwrap();
        for (j, &x) in fine.iter().enumerate() {
            let k = w.partition_point(|&v| v <= x);
            if k == 0 || k == w.len() {
                continue;
            }
            let t = (x - w[k - 1]) / (w[k] - w[k - 1]);
            let interp = r.magnitude_db[k - 1] + t * (r.magnitude_db[k] - r.magnitude_db[k - 1]);
            assert!(
                (interp - rf.magnitude_db[j]).abs() < 0.1,
                "ω = {x}: drawn {interp} vs {}",
                rf.magnitude_db[j]
            );
        }
    }
}

#[test]
fn frequency_grid_range() {
    // corners 0.1 and 10 → 1e-3 … 1e3
    let g = tf(&[1.0], &[1.0, 10.1, 1.0]);
    let w = auto_frequency_grid(&g.factored().unwrap(), 61).unwrap();
    assert!((w[0] - 1e-3).abs() < 1e-18 && (w.last().unwrap() - 1e3).abs() < 1e-9);
    assert_eq!(w.len(), 61);
    // corner 3 → 10^floor(log10 0.03) = 0.01 … 10^ceil(log10 300) = 1000
    let g = tf(&[1.0], &[1.0, 3.0]);
    let w = auto_frequency_grid(&g.factored().unwrap(), 50).unwrap();
    assert!((w[0] - 1e-2).abs() < 1e-17 && (w.last().unwrap() - 1e3).abs() < 1e-9);
    // no corner: 1/s → 0.01 … 100
    let g = tf(&[1.0], &[1.0, 0.0]);
    let w = auto_frequency_grid(&g.factored().unwrap(), 5).unwrap();
    assert_eq!(w.len(), 5);
    assert!((w[0] - 0.01).abs() < 1e-17 && (w[4] - 100.0).abs() < 1e-12);
    // an undamped pair is approached but never hit (the curve stays finite)
    let g = tf(&[1.0], &[1.0, 0.0, 4.0]);
    let w = auto_frequency_grid(&g.factored().unwrap(), 100).unwrap();
    let r = g.freq_response(&w).unwrap();
    assert!(r.magnitude.iter().all(|m| m.is_finite()));
    assert!(w.iter().any(|&x| (x - 2.0).abs() < 1e-5));
    assert!(auto_frequency_grid(&g.factored().unwrap(), 1).is_err());
}

#[test]
fn time_span_covers_settling_and_bounds_growth() {
    // stable: the slowest envelope e^(σ t_end) has decayed below 2 %, and not absurdly far
    for (num, den) in [
        (vec![1.0], vec![1.0, 1.0]),
        (vec![1.0], vec![1.0, 0.2, 1.0]),               // ζ = 0.1
        (vec![1.0], vec![1.0, 3.0, 3.0, 1.0]),          // triple pole
        (vec![1.0, 1.0], vec![1.0, 100.5, 50.0]),       // poles −0.5, −100
        (vec![5.0], vec![1.0, 1e-3 * 2.0, 1.0 + 1e-6]), // ζ = 1e-3
    ] {
        let g = tf(&num, &den);
        let span = auto_time_span(&g.factored().unwrap()).unwrap();
        let slow = g
            .poles()
            .unwrap()
            .iter()
            .map(|p| p.value.re)
            .fold(f64::NEG_INFINITY, f64::max);
        let envelope = (slow * span.t_end).exp();
        assert!(
            envelope < 0.02,
            "{g}: e^(σt) = {envelope} at {}",
            span.t_end
        );
        assert!(span.t_end < 10.0 * 6.0 / slow.abs(), "{g}: {}", span.t_end);
        assert!(span.reason.contains("settling"), "{}", span.reason);
    }
    // undamped: at least five periods
    let g = tf(&[4.0], &[1.0, 0.0, 4.0]);
    let span = auto_time_span(&g.factored().unwrap()).unwrap();
    assert!(span.t_end >= 5.0 * std::f64::consts::PI && span.t_end < 20.0 * std::f64::consts::PI);
    // unstable: growth by a bounded factor, even with a very slow stable pole present
    // (python-control #384 drew a 3e15 s window)
    for (den, sigma) in [
        (vec![1.0, -2.0], 2.0),
        (vec![1.0, -1.0 + 1e-12, -1e-12], 1.0), // (s − 1)(s + 1e-12)
        (vec![1.0, -0.2, 4.01], 0.1),           // 0.1 ± 2j
    ] {
        let g = tf(&[1.0], &den);
        let span = auto_time_span(&g.factored().unwrap()).unwrap();
        let growth = (sigma * span.t_end).exp();
        assert!((1e3..=1e3f64.powf(2.5)).contains(&growth), "{g}: ×{growth}");
        assert!(span.reason.contains("unstable"), "{}", span.reason);
    }
    // integrators: the window is set by the other modes, or a default
    let g = tf(&[1.0], &[1.0, 2.0, 0.0]);
    assert_eq!(auto_time_span(&g.factored().unwrap()).unwrap().t_end, 5.0); // 1.5·ln50/2 = 2.93
    let g = tf(&[1.0], &[1.0, 0.0]);
    assert_eq!(auto_time_span(&g.factored().unwrap()).unwrap().t_end, 10.0);
    let g = tf(&[1.0, 0.5], &[1.0, 0.0, 0.0]);
    assert_eq!(auto_time_span(&g.factored().unwrap()).unwrap().t_end, 10.0); // 5/0.5
    let t = auto_time_grid(&g.factored().unwrap(), 101).unwrap();
    assert_eq!(t.len(), 101);
    assert!(t[0] == 0.0 && (t[100] - 10.0).abs() < 1e-15);
    assert!(t.windows(2).all(|p| (p[1] - p[0] - 0.1).abs() < 1e-12));
}

#[test]
fn a_cancelled_factor_costs_no_accuracy() {
    // (s + 2)² over a degree-7 denominator with the (numerically double) factor (s + 2)² and
    // five clustered small roots (found by testing against other projects' suites). The
    // exact |N/D| of these f64 coefficients at ω = 3.16e-4 is 17878954.752661815 (mpmath, 50
    // digits, the coefficients taken as their exact binary values); the dc gain is exactly
    // 4/2.2364516754719997e-07 = 17885474.762855344. Evaluating the reduced G rebuilt from
    // the computed common factor lost 1.3e-6 here.
    let g = tf(
        &[1.0, 4.0, 4.0],
        &[
            1.0,
            4.191699999999999,
            4.78116611,
            0.824786794293,
            0.0595628707474098,
            0.0021255273849310865,
            3.62779468067472e-05,
            2.2364516754719997e-07,
        ],
    );
    let f = g.factored().unwrap();
    assert_eq!(f.pole_zero().cancelled.len(), 1);
    let m = f.freq_response(&[0.000316]).unwrap().magnitude[0];
    let want = 17878954.752661815;
    assert!(((m - want) / want).abs() < 1e-13, "{m} vs {want}");
    let dc = f.dc_gain().unwrap();
    let want = 17885474.762855344;
    assert!(((dc - want) / want).abs() < 1e-15, "{dc} vs {want}");
}
