//! Stability in the delay (issue 21, part 4): D(s) + N(s)·e^(−sT) for a loop L = N/D with a
//! dead time T in negative unity feedback. Every reference is a closed form derived in the
//! comments or a 40-digit mpmath value (script and output quoted).

#![allow(clippy::excessive_precision)] // references are quoted to the digits they were computed with

mod common;

use std::f64::consts::{PI, TAU};

use common::{c, rel, tf};
use ltikit::analysis::{CrossingDirection, DelayStability, Factored};
use ltikit::{LtiError, Root};

fn loop_of(num: &[f64], den: &[f64]) -> Factored {
    tf(num, den).factored().unwrap()
}

fn stability(num: &[f64], den: &[f64]) -> DelayStability {
    loop_of(num, den).delay_stability().unwrap()
}

// ---------------------------------------------------------------------------------------
// K e^(−sT)/(s + 1)
//
// Δ = s + 1 + K e^(−sT). W(x) = |jω + 1|² − K² = x + 1 − K²: a crossing frequency iff K > 1,
// ω_c = √(K² − 1), and there W′ = 1 > 0 (destabilizing). At ω_c, e^(−jω_c T) = −(1 + jω_c)/K,
// so cos(ω_c T) = −1/K and sin(ω_c T) = ω_c/K > 0: ω_c T = arccos(−1/K) ∈ (π/2, π), hence
// T_k = (arccos(−1/K) + 2πk)/√(K² − 1). Without delay the root is −1 − K < 0, so the loop is
// stable iff T < T₀ (and 2k roots are unstable between T_{k−1} and T_k).
// For K < 1, W > 0 for every ω: stable for every T. For K = 1, W = x: |L(jω)| = 1 only at
// ω = 0, where L(0) = +1 and e^0 = −1/L(0) = −1 is impossible: no crossing, stable for all T.
// ---------------------------------------------------------------------------------------

fn first_order_crossing(k: f64, j: usize) -> f64 {
    ((-1.0 / k).acos() + TAU * j as f64) / (k * k - 1.0).sqrt()
}

#[test]
fn first_order_loop_below_unit_gain_is_stable_for_every_delay() {
    for k in [0.5, 1.0] {
        let d = stability(&[k], &[1.0, 1.0]);
        assert!(d.crossings.is_empty(), "K = {k}: {:?}", d.crossings);
        assert_eq!(d.unstable_at_zero, 0);
        assert!(d.stable_without_delay);
        assert_eq!(d.critical_delay, Some(f64::INFINITY));
        assert_eq!(d.stable_intervals.len(), 1);
        assert_eq!(d.stable_intervals[0].from, 0.0);
        assert_eq!(d.stable_intervals[0].to, f64::INFINITY);
        for t in [0.0, 0.1, 1.0, 10.0, 1e6] {
            assert!(d.is_stable_at(t).unwrap(), "K = {k}, T = {t}");
        }
    }
    // K = 1 touches |L| = 1 at ω = 0 only: said so
    let d = stability(&[1.0], &[1.0, 1.0]);
    assert!(
        d.notes.iter().any(|n| n.contains("L(0) = +1")),
        "{:?}",
        d.notes
    );
}

#[test]
fn first_order_loop_critical_delay_in_closed_form() {
    for k in [2.0, 5.0, 10.0] {
        let d = stability(&[k], &[1.0, 1.0]);
        assert_eq!(d.crossings.len(), 1, "K = {k}");
        let cr = d.crossings[0];
        assert_eq!(cr.direction, CrossingDirection::Destabilizing);
        assert!(rel(cr.frequency, (k * k - 1.0).sqrt()) < 1e-15);
        let t0 = first_order_crossing(k, 0);
        let t1 = first_order_crossing(k, 1);
        let tc = d.critical_delay.unwrap();
        assert!(rel(tc, t0) < 1e-12, "K = {k}: {tc} vs {t0}");
        assert!(rel(cr.delay(1), t1) < 1e-12);
        // mpmath 1.3, mp.dps = 40: acos(-1/K)/sqrt(K*K - 1) = 1.2091995761561452337 (K = 2),
        // 0.36173947100747126721 (K = 5), 0.16793817546235016522 (K = 10)
        let mp = match k as u32 {
            2 => 1.2091995761561452337,
            5 => 0.36173947100747126721,
            _ => 0.16793817546235016522,
        };
        assert!(rel(tc, mp) < 1e-12);
        assert_eq!(d.stable_intervals.len(), 1);
        assert!(!d.stability_switches);
        // 0 below T₀, 2 just above, 4 above T₁
        assert_eq!(d.unstable_roots_at(0.999 * t0).unwrap(), 0);
        assert_eq!(d.unstable_roots_at(1.001 * t0).unwrap(), 2);
        assert_eq!(d.unstable_roots_at(0.999 * t1).unwrap(), 2);
        assert_eq!(d.unstable_roots_at(1.001 * t1).unwrap(), 4);
        assert!(d.is_stable_at(0.999 * t0).unwrap());
        assert!(!d.is_stable_at(1.001 * t0).unwrap());
        // the independent count (delayed Nyquist criterion) agrees
        let f = loop_of(&[k], &[1.0, 1.0]);
        for t in [
            0.5 * t0,
            0.999 * t0,
            1.001 * t0,
            0.5 * (t0 + t1),
            1.001 * t1,
        ] {
            assert_eq!(
                f.delayed_nyquist_count(t).unwrap(),
                d.unstable_roots_at(t).unwrap(),
                "K = {k}, T = {t}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------
// K e^(−sT)/s: Δ = s + K e^(−sT). W = x − K², ω_c = K; e^(−jKT) = −jK/K = −j, so KT = π/2:
// critical delay π/(2K), crossings every 2π/K.
// ---------------------------------------------------------------------------------------

#[test]
fn integrator_loop_critical_delay() {
    for k in [0.1, 1.0, 3.0, 250.0] {
        let d = stability(&[k], &[1.0, 0.0]);
        let tc = PI / (2.0 * k);
        assert!(rel(d.critical_delay.unwrap(), tc) < 1e-14, "K = {k}");
        assert!(rel(d.crossings[0].period(), TAU / k) < 1e-15);
        assert_eq!(d.unstable_roots_at(1.01 * tc).unwrap(), 2);
        assert_eq!(d.unstable_roots_at(0.99 * tc).unwrap(), 0);
    }
}

// ---------------------------------------------------------------------------------------
// K e^(−sT)/(s(s + 1)): |jω(jω + 1)| = K ⇔ ω⁴ + ω² − K² = 0, ω_c² = (√(1 + 4K²) − 1)/2;
// θ = arg(−L(jω_c)) = π − π/2 − arctan ω_c, so T₀ = (π/2 − arctan ω_c)/ω_c: the phase margin
// over the crossover frequency. Without delay s² + s + K is stable.
// ---------------------------------------------------------------------------------------

#[test]
fn type_one_loop_critical_delay_is_phase_margin_over_crossover() {
    for k in [0.2, 1.0, 10.0] {
        let d = stability(&[k], &[1.0, 1.0, 0.0]);
        let w = ((1.0f64 + 4.0 * k * k).sqrt() - 1.0) / 2.0;
        let w = w.sqrt();
        assert!(rel(d.crossings[0].frequency, w) < 1e-14, "K = {k}");
        let tc = (PI / 2.0 - w.atan()) / w;
        assert!(rel(d.critical_delay.unwrap(), tc) < 1e-13, "K = {k}");
        let f = loop_of(&[k], &[1.0, 1.0, 0.0]);
        for t in [0.9 * tc, 1.1 * tc] {
            assert_eq!(
                f.delayed_nyquist_count(t).unwrap(),
                d.unstable_roots_at(t).unwrap()
            );
            assert!(f.closed_loop_delay_roots(t, 2).unwrap().agrees);
        }
    }
}

#[test]
fn a_tangency_is_reported_and_not_counted() {
    // L = 3s/((s + 1)(s + 2)): W(x) = (x + 1)(x + 4) − 9x = (x − 2)², a double root at
    // ω = √2 where |L(jω)| touches 1 from below (|L| ≤ 1 everywhere). Without delay
    // s² + 6s + 2 is stable, and no root can cross: stable for every delay.
    let f = loop_of(&[3.0, 0.0], &[1.0, 3.0, 2.0]);
    let d = f.delay_stability().unwrap();
    assert_eq!(d.crossings.len(), 1, "{:?}", d.crossings);
    assert_eq!(d.crossings[0].direction, CrossingDirection::Tangential);
    assert!(rel(d.crossings[0].frequency, 2f64.sqrt()) < 1e-15);
    assert!(
        d.notes.iter().any(|n| n.contains("touches 1")),
        "{:?}",
        d.notes
    );
    assert_eq!(d.critical_delay, Some(f64::INFINITY));
    let touch = d.crossings[0].delay(0);
    for t in [0.5 * touch, 1.5 * touch, 10.0] {
        assert_eq!(d.unstable_roots_at(t).unwrap(), 0);
        assert_eq!(f.delayed_nyquist_count(t).unwrap(), 0, "T = {t}");
    }
}

#[test]
fn extreme_delays_stay_bounded_and_say_what_they_missed() {
    // 3/(s + 1): at T = 1e300 the count is a closed form (saturated), the root search lists
    // roots near ln 3/T + j(θ + 2πk)/T (|L(jω)| → 3 as ω → 0) and says it did not find them all
    let f = loop_of(&[3.0], &[1.0, 1.0]);
    let d = f.delay_stability().unwrap();
    assert_eq!(d.unstable_roots_at(1e300).unwrap(), usize::MAX);
    let r = f.closed_loop_delay_roots(1e300, 2).unwrap();
    assert!(!r.agrees && r.note.is_some());
    assert!(
        rel(r.roots[0].value.re, 3f64.ln() / 1e300) < 1e-9,
        "{:?}",
        r.roots[0]
    );
    // the Nyquist count refuses a contour that long, by name
    let e = f.delayed_nyquist_count(1e300).unwrap_err().to_string();
    assert!(
        e.contains("`delay`") && e.contains("exceeds the limit"),
        "{e}"
    );
    // a tiny delay is the loop without delay: the root −4
    let r = f.closed_loop_delay_roots(1e-300, 1).unwrap();
    assert!(r.agrees);
    assert_eq!(r.roots[0].value, c(-4.0, 0.0));
}

// ---------------------------------------------------------------------------------------
// Stability switches (Cooke & Grossman 1982, "Discrete delay, distributed delay and stability
// switches", J. Math. Anal. Appl. 86): s² + a s + b + c e^(−sT), a = 0.1, b = 1, c = 0.5.
// W(x) = (b − x)² + a²x − c² = x² + (a² − 2b)x + b² − c² = x² − 1.99x + 0.75, two positive
// roots x± = (1.99 ± √(1.99² − 3))/2; W′(x₊) > 0 (destabilizing), W′(x₋) < 0 (stabilizing).
// At ω, e^(−jωT) = −(b − ω² + jaω)/c: cos ωT = (ω² − b)/c, sin ωT = aω/c > 0, so
// T_k = (arccos((ω² − b)/c) + 2πk)/ω. Without delay: s² + 0.1s + 1.5, stable.
// mpmath 1.3 (mp.dps = 40: the same closed forms, delays for k < 12 merged, printed to 8
// digits): stable for T in [0, 0.20203477) ∪ (4.2198192, 5.358212).
// ---------------------------------------------------------------------------------------

fn switch_delays(a: f64, b: f64, cc: f64) -> Vec<(f64, i64)> {
    let aa = a * a - 2.0 * b;
    let bb = b * b - cc * cc;
    let disc = (aa * aa - 4.0 * bb).sqrt();
    let mut ev = Vec::new();
    for (x, step) in [((-aa + disc) / 2.0, 2), ((-aa - disc) / 2.0, -2)] {
        let w = f64::sqrt(x);
        let th = ((x - b) / cc).acos();
        for k in 0..60 {
            ev.push(((th + TAU * k as f64) / w, step));
        }
    }
    ev.sort_by(|p, q| p.0.total_cmp(&q.0));
    ev
}

/// Stable intervals from the merged closed-form delays (the test's own sweep).
fn expected_intervals(ev: &[(f64, i64)]) -> Vec<(f64, f64)> {
    let mut n = 0;
    let mut start = Some(0.0);
    let mut out = Vec::new();
    for &(t, s) in ev {
        n += s;
        match (start, n == 0) {
            (Some(from), false) => {
                out.push((from, t));
                start = None;
            }
            (None, true) => start = Some(t),
            _ => {}
        }
    }
    out
}

#[test]
fn cooke_grossman_stability_switches() {
    for (a, b, cc, count) in [(0.1, 1.0, 0.5, 2), (0.1, 4.0, 0.5, 6), (0.2, 2.0, 0.5, 4)] {
        let d = stability(&[cc], &[1.0, a, b]);
        let ev = switch_delays(a, b, cc);
        let want = expected_intervals(&ev);
        assert_eq!(want.len(), count, "a = {a}, b = {b}, c = {cc}");
        assert!(d.complete);
        assert_eq!(
            d.stable_intervals.len(),
            want.len(),
            "{:?}",
            d.stable_intervals
        );
        for (got, w) in d.stable_intervals.iter().zip(&want) {
            assert!((got.from - w.0).abs() <= 1e-12 * w.1, "{got:?} vs {w:?}");
            assert!(rel(got.to, w.1) < 1e-12, "{got:?} vs {w:?}");
        }
        assert!(d.stability_switches);
        // the directions: the upper frequency destabilizes
        assert_eq!(d.crossings[1].direction, CrossingDirection::Destabilizing);
        assert_eq!(d.crossings[0].direction, CrossingDirection::Stabilizing);
        // counts between the intervals and the Nyquist count
        let f = loop_of(&[cc], &[1.0, a, b]);
        for w in want.windows(2) {
            let mid = 0.5 * (w[0].1 + w[1].0);
            assert!(d.unstable_roots_at(mid).unwrap() >= 2);
            assert!(!d.is_stable_at(mid).unwrap());
            let inside = 0.5 * (w[1].0 + w[1].1);
            assert!(d.is_stable_at(inside).unwrap());
            assert_eq!(
                f.delayed_nyquist_count(mid).unwrap(),
                d.unstable_roots_at(mid).unwrap()
            );
            assert_eq!(f.delayed_nyquist_count(inside).unwrap(), 0);
        }
    }
    // the mpmath values of the first case
    let d = stability(&[0.5], &[1.0, 0.1, 1.0]);
    let iv = &d.stable_intervals;
    assert!(rel(iv[0].to, 0.20203477) < 5e-8);
    assert!(rel(iv[1].from, 4.2198192) < 5e-8);
    assert!(rel(iv[1].to, 5.358212) < 5e-7);
}

// ---------------------------------------------------------------------------------------
// Rightmost roots against Lambert W: s + 1 + K e^(−sT) = 0 ⇔ (s + 1)T·e^((s+1)T) = −KT·e^T,
// so s = −1 + W_k(−K T e^T)/T. mpmath 1.3, mp.dps = 40:
// `[-1 + lambertw(-K*T*exp(T), k)/T for k in range(-6, 7)]` (residuals < 1e-38), branches
// k = −6…6 sorted by real part, the first three (upper members):
// ---------------------------------------------------------------------------------------

/// (K, T, the three rightmost upper roots as (re, im)).
type LambertCase = (f64, f64, [(f64, f64); 3]);

const LAMBERT: &[LambertCase] = &[
    (
        2.0,
        0.5,
        [
            (-0.9310186622288393076, 3.1849035750475891727),
            (-4.1107933644079072454, 15.306969768434307419),
            (-5.2992733101340052357, 27.969293332533513557),
        ],
    ),
    (
        2.0,
        2.0,
        [
            (0.10883499779585629629, 1.1656172221091613168),
            (-0.35385700823585967675, 4.006930817216348359),
            (-0.63374286779510976975, 7.0943737847872557879),
        ],
    ),
    (
        5.0,
        1.0,
        [
            (0.60682644565652878212, 2.2013310474255503156),
            (-0.46246896641125392901, 7.9217330103453699707),
            (-1.0391771309671031363, 14.134395189684423805),
        ],
    ),
    (
        1.0,
        1.0,
        [
            (-0.60502091729270661113, 1.7881880413836292023),
            (-2.0528264820715919562, 7.7184137887709177921),
            (-2.6473552235298248574, 14.020204573895337054),
        ],
    ),
    (
        0.5,
        3.0,
        [
            (-0.25568727261042905377, 0.77801897067917401468),
            (-0.56305926287507997422, 2.6720237652124232984),
            (-0.749492797904780694, 4.7300261894081058004),
        ],
    ),
    (
        10.0,
        0.2,
        [
            (0.58641624417260797474, 8.7506941052213073463),
            (-6.7993518797462853297, 38.522801641454151247),
            (-9.7729417100006710948, 70.063001086700887226),
        ],
    ),
];

#[test]
fn rightmost_roots_of_the_first_order_loop_match_lambert_w() {
    for &(k, t, refs) in LAMBERT {
        let f = loop_of(&[k], &[1.0, 1.0]);
        let r = f.closed_loop_delay_roots(t, 6).unwrap();
        assert!(r.agrees, "K = {k}, T = {t}: {:?}", r.note);
        assert_eq!(r.roots.len(), 6, "K = {k}, T = {t}: {:?}", r.roots);
        for (i, &(re, im)) in refs.iter().enumerate() {
            let upper = r.roots[2 * i];
            let lower = r.roots[2 * i + 1];
            let want = c(re, im);
            assert!(
                (upper.value - want).norm() <= 1e-12 * want.norm(),
                "K = {k}, T = {t}, root {i}: {} vs {want}",
                upper.value
            );
            assert_eq!(lower.value, upper.value.conj());
            assert!(upper.relative_residual <= 1e-12, "{upper:?}");
        }
        let expected = f.delay_stability().unwrap().unstable_roots_at(t).unwrap();
        assert_eq!(r.unstable_expected, expected);
        assert_eq!(r.unstable_found, expected);
    }
}

#[test]
fn long_delays_find_every_unstable_root() {
    // 10 e^(−sT)/(s + 1) at T = 20 and 60: T_k = (arccos(−0.1) + 2πk)/√99 < T for
    // k < (T√99 − arccos(−0.1))/2π, i.e. 32 and 95 crossings: 64 and 190 unstable roots
    let f = loop_of(&[10.0], &[1.0, 1.0]);
    let d = f.delay_stability().unwrap();
    for (t, n) in [(20.0, 64), (60.0, 190)] {
        let k = ((t * 99f64.sqrt() - (-0.1f64).acos()) / TAU).ceil() as usize;
        assert_eq!(2 * k, n);
        assert_eq!(d.unstable_roots_at(t).unwrap(), n);
        assert_eq!(f.delayed_nyquist_count(t).unwrap(), n);
        let r = f.closed_loop_delay_roots(t, 10).unwrap();
        assert!(r.agrees, "{:?}", r.note);
        assert_eq!(r.unstable_found, n);
        assert!(r.roots.iter().all(|q| q.relative_residual <= 1e-12));
    }
}

#[test]
fn neutral_loop_with_small_high_frequency_gain() {
    // L = 0.5(s − 3)/(s + 1): bi-proper, |L(∞)| = 0.5 < 1 (neutral type, analysed).
    // W(x) = x + 1 − 0.25(x + 9) = 0.75x − 1.25: ω_c = √(5/3), W′ > 0 (destabilizing).
    // L(0) = −1.5: D + N = 1.5s − 0.5 has the root 1/3: unstable without delay (1 root).
    // Counts: 1, plus 2 per crossing delay passed (each pair adds to the real root): never stable.
    let f = loop_of(&[0.5, -1.5], &[1.0, 1.0]);
    let d = f.delay_stability().unwrap();
    assert_eq!(d.neutral, Some(0.5));
    assert!(d.notes.iter().any(|n| n.contains("neutral")));
    assert_eq!(d.unstable_at_zero, 1);
    assert_eq!(d.crossings.len(), 1);
    let w = (5.0f64 / 3.0).sqrt();
    assert!(rel(d.crossings[0].frequency, w) < 1e-15);
    // θ = arg(−L(jω)) = π + arg(jω − 3) − arg(jω + 1)
    let theta = (PI + (w).atan2(-3.0) - w.atan()).rem_euclid(TAU);
    assert!(rel(d.crossings[0].delay(0), theta / w) < 1e-14);
    assert!(d.stable_intervals.is_empty() && d.critical_delay.is_none());
    for t in [0.3, 0.99 * theta / w, 1.01 * theta / w, 10.0] {
        let n = d.unstable_roots_at(t).unwrap();
        let passed = usize::from(t > theta / w) + usize::from(t > (theta + TAU) / w);
        assert_eq!(n, 1 + 2 * passed, "T = {t}");
        assert_eq!(f.delayed_nyquist_count(t).unwrap(), n, "T = {t}");
        let r = f.closed_loop_delay_roots(t, 4).unwrap();
        assert!(r.agrees, "T = {t}: {:?}", r.note);
    }
}

#[test]
fn root_at_the_origin_and_hidden_modes_are_reported() {
    // L = −1/(s + 1): L(0) = −1, so D(0) + N(0) = 0 and s = 0 is a root for every T
    let f = loop_of(&[-1.0], &[1.0, 1.0]);
    let d = f.delay_stability().unwrap();
    assert!(d.root_at_origin && !d.stable_without_delay);
    assert!(d.stable_intervals.is_empty() && d.critical_delay.is_none());
    assert!(!d.is_stable_at(0.5).unwrap());
    let r = f.closed_loop_delay_roots(3.0, 3).unwrap();
    assert_eq!(r.roots[0].value, c(0.0, 0.0));
    assert!(r.agrees);
    // L = (s − 2)/((s − 2)(s + 1)) · 2: the mode s = 2 cancels; 2/(s + 1) is analysed and the
    // hidden mode listed (unstable whatever the delay)
    let f = loop_of(&[2.0, -4.0], &[1.0, -1.0, -2.0]);
    let d = f.delay_stability().unwrap();
    assert_eq!(d.hidden_modes.len(), 1);
    assert!((d.hidden_modes[0].value - c(2.0, 0.0)).norm() < 1e-12);
    assert!(d.notes.iter().any(|n| n.contains("cancels the modes")));
    assert!(rel(d.critical_delay.unwrap(), first_order_crossing(2.0, 0)) < 1e-12);
}

#[test]
fn unstable_for_every_delay_without_crossings() {
    // L = 0.5/(s − 1): D + N = s − 0.5, one unstable root; W = x + 1 − 0.25 > 0: no crossing,
    // so the count is 1 for every delay
    let d = stability(&[0.5], &[1.0, -1.0]);
    assert!(d.crossings.is_empty());
    assert_eq!(d.critical_delay, None);
    for t in [0.0, 1.0, 100.0] {
        assert_eq!(d.unstable_roots_at(t).unwrap(), 1);
    }
    // 1/s²: D + N = s² + 1 on the axis at T = 0, the pair at ω = 1 (θ = 0) leaves to the
    // right at once: 2 unstable roots for every T > 0
    let d = stability(&[1.0], &[1.0, 0.0, 0.0]);
    assert_eq!(d.crossings[0].phase, 0.0);
    assert_eq!(d.unstable_roots_at(1e-6).unwrap(), 2);
    assert!(d.stable_intervals.is_empty());
}

#[test]
fn nearly_equal_crossing_frequencies_stop_the_merge_at_its_limit() {
    // s² + 0.1s + 1 + c e^(−sT) with c² = 0.009975 + 1e-12: W = x² − 1.99x + 1 − c² has the
    // discriminant 4e-12, so ω₊ − ω₋ ≈ 1e-6 and the destabilizing delays outrun the
    // stabilizing ones only after ~10⁶ s: more than MAX_DELAY_EVENTS delays to merge.
    let cc = (0.009975f64 + 1e-12).sqrt();
    let d = stability(&[cc], &[1.0, 0.1, 1.0]);
    assert_eq!(d.crossings.len(), 2);
    assert!(!d.complete);
    assert!(d.horizon.is_finite() && d.horizon > 0.0);
    assert!(
        d.notes.iter().any(|n| n.contains("MAX_DELAY_EVENTS")),
        "{:?}",
        d.notes
    );
    // the counts stay closed forms beyond the horizon: 2 more per destabilizing delay, 2 less
    // per stabilizing one
    let t = 10.0 * d.horizon;
    let passed = |w: f64, th: f64| ((t * w - th) / TAU).ceil();
    let (lo, hi) = (d.crossings[0], d.crossings[1]);
    let want = 2.0 * (passed(hi.frequency, hi.phase) - passed(lo.frequency, lo.phase));
    assert_eq!(d.unstable_roots_at(t).unwrap() as f64, want);
}

// ---------------------------------------------------------------------------------------
// Bad input
// ---------------------------------------------------------------------------------------

#[test]
fn bad_inputs_give_one_clear_error_each() {
    let f = loop_of(&[2.0], &[1.0, 1.0]);
    let d = f.delay_stability().unwrap();
    for t in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let e = d.unstable_roots_at(t).unwrap_err();
        assert!(matches!(e, LtiError::NonFinite { .. }), "{e}");
        assert!(e.to_string().contains("`delay`"), "{e}");
        assert!(f.closed_loop_delay_roots(t, 3).is_err());
        assert!(d.is_stable_at(t).is_err());
    }
    let e = f.closed_loop_delay_roots(-1.0, 3).unwrap_err().to_string();
    assert!(e.contains("`delay`") && e.contains("negative"), "{e}");
    let e = f.closed_loop_delay_roots(1.0, 0).unwrap_err().to_string();
    assert!(e.contains("`count`"), "{e}");
    // the zero loop
    let zero = Factored::from_zpk(&[], &[Root::new(c(-1.0, 0.0), 1)], 0.0).unwrap();
    let e = zero.delay_stability().unwrap_err().to_string();
    assert!(e.contains("zero"), "{e}");
    // improper
    let e = loop_of(&[1.0, 0.0, 1.0], &[1.0, 1.0])
        .delay_stability()
        .unwrap_err();
    assert!(matches!(e, LtiError::Improper { .. }), "{e}");
    // neutral with |L(∞)| ≥ 1
    for num in [[2.0, 1.0], [1.0, 3.0], [-1.0, 0.5]] {
        let e = loop_of(&num, &[1.0, 1.0])
            .delay_stability()
            .unwrap_err()
            .to_string();
        assert!(e.contains("neutral") && e.contains("|L(∞)|"), "{e}");
    }
    // all-pass (s − 1)/(s + 1): |L(jω)| = 1 everywhere, refused as neutral with |L(∞)| = 1
    let e = loop_of(&[1.0, -1.0], &[1.0, 1.0])
        .delay_stability()
        .unwrap_err()
        .to_string();
    assert!(e.contains("approaches the imaginary axis"), "{e}");
    // discrete time
    let dz = loop_of(&[1.0], &[1.0, -0.5]).with_domain(ltikit::lti::Domain::discrete(0.1).unwrap());
    assert!(
        dz.delay_stability()
            .unwrap_err()
            .to_string()
            .contains("continuous")
    );
    // huge order: 300 poles from factors
    let big = Factored::from_zpk(&[], &[Root::new(c(-1.0, 0.0), 300)], 1.0).unwrap();
    assert!(matches!(
        big.delay_stability().unwrap_err(),
        LtiError::OrderTooHigh { order: 300, .. }
    ));
}
