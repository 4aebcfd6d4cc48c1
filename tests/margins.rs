//! Gain/phase margins, bandwidth and resonant peak against closed forms.
//!
//! Every reference value is derived in the test from its closed form (cited), never copied
//! from another tool's output.

use ltikit::TransferFunction;
use num_complex::Complex64;

mod common;
use common::{real_root, rel, tf};

/// The positive real roots of x³ + a x² + b x + c (Cardano's formula; trigonometric form
/// when all three roots are real).
fn cubic_positive_roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    let p = b - a * a / 3.0;
    let q = 2.0 * a * a * a / 27.0 - a * b / 3.0 + c;
    let disc = (q / 2.0).powi(2) + (p / 3.0).powi(3);
    let roots = if disc > 0.0 {
        let s = disc.sqrt();
        vec![(-q / 2.0 + s).cbrt() + (-q / 2.0 - s).cbrt() - a / 3.0]
    } else {
        let r = 2.0 * (-p / 3.0).sqrt();
        let theta = (3.0 * q / (p * r)).acos() / 3.0;
        (0..3)
            .map(|k| r * (theta - 2.0 * std::f64::consts::PI * k as f64 / 3.0).cos() - a / 3.0)
            .collect()
    };
    roots.into_iter().filter(|&x| x > 0.0).collect()
}

#[test]
fn triple_lag_gain_margin_is_eight_at_sqrt3() {
    // 1/(s+1)³: φ = −3·atan ω = −180° at ω = tan 60° = √3; |G| = (1+3)^(−3/2) = 1/8.
    let g = tf(&[1.0], &[1.0, 3.0, 3.0, 1.0]);
    let m = g.margins().unwrap();
    let w = m.phase_crossover.unwrap();
    let gm = m.gain_margin.unwrap();
    assert!(rel(w, 3f64.sqrt()) < 1e-14, "ω_pc = {w}");
    assert!(rel(gm, 8.0) < 1e-14, "GM = {gm}");
    assert!((m.gain_margin_db.unwrap() - 20.0 * 8f64.log10()).abs() < 1e-12);
    assert_eq!(m.phase_crossings.len(), 1);
    // |G| < 1 for every ω > 0: no gain crossing, infinite phase margin.
    assert!(m.gain_crossings.is_empty());
    assert!(m.phase_margin_deg.is_none() && m.gain_crossover.is_none());
    // bandwidth: (1 + ω²)^(−3/2) = 10^(−3/20) ⇔ ω = √(10^(1/10) − 1)
    let wb = (10f64.powf(0.1) - 1.0).sqrt();
    assert!(rel(m.bandwidth.unwrap(), wb) < 1e-13);
    assert!(m.resonant_peak.is_none());
}

#[test]
fn type_one_third_order_margins() {
    // 2/(s(s+1)(s+2)): φ = −90° − atan ω − atan(ω/2) = −180° ⇔ ω² = 2; |G(j√2)| = 1/3.
    let g = tf(&[2.0], &[1.0, 3.0, 2.0, 0.0]);
    let m = g.margins().unwrap();
    assert!(rel(m.phase_crossover.unwrap(), 2f64.sqrt()) < 1e-14);
    assert!(rel(m.gain_margin.unwrap(), 3.0) < 1e-14);
    // |G| = 1 ⇔ u(1+u)(4+u) = 4 with u = ω²: u³ + 5u² + 4u − 4 = 0 (Cardano).
    let pos = cubic_positive_roots(5.0, 4.0, -4.0);
    assert_eq!(pos.len(), 1);
    let u = pos[0];
    let wgc = u.sqrt();
    let pm = 90.0 - wgc.atan().to_degrees() - (wgc / 2.0).atan().to_degrees();
    assert!(rel(m.gain_crossover.unwrap(), wgc) < 1e-13);
    assert!((m.phase_margin_deg.unwrap() - pm).abs() < 1e-10);
    // the brief's rounded values
    assert!((m.gain_crossover.unwrap() - 0.749368).abs() < 1e-6);
    assert!((m.phase_margin_deg.unwrap() - 32.6131).abs() < 1e-4);
    assert!(m.bandwidth.is_none(), "dc gain is infinite");
    assert!(m.resonant_peak.is_none());
}

#[test]
fn second_order_resonance_and_bandwidth_closed_forms() {
    // ωn²/(s² + 2ζωn s + ωn²): Mr = 1/(2ζ√(1−ζ²)), ωr = ωn√(1−2ζ²) for ζ < 1/√2;
    // bandwidth x = ω²/ωn² = (1−2ζ²) + √((1−2ζ²)² − 1 + 10^(3/10)).
    for &wn in &[0.01, 1.0, 3.0, 250.0] {
        for &z in &[0.001, 0.01, 0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0, 2.0] {
            let g = tf(&[wn * wn], &[1.0, 2.0 * z * wn, wn * wn]);
            let m = g.margins().unwrap();
            let a = 1.0 - 2.0 * z * z;
            let wb = wn * (a + (a * a - 1.0 + 10f64.powf(0.3)).sqrt()).sqrt();
            let b = m.bandwidth.unwrap();
            assert!(rel(b, wb) < 1e-12, "ωn={wn} ζ={z}: bw {b} vs {wb}");
            if z < std::f64::consts::FRAC_1_SQRT_2 {
                let mr = 1.0 / (2.0 * z * (1.0 - z * z).sqrt());
                let wr = wn * a.sqrt();
                let (gm, gw) = (m.resonant_peak.unwrap(), m.resonant_frequency.unwrap());
                assert!(rel(gm, mr) < 1e-12, "ωn={wn} ζ={z}: Mr {gm} vs {mr}");
                assert!(rel(gw, wr) < 1e-9, "ωn={wn} ζ={z}: ωr {gw} vs {wr}");
            } else {
                assert!(m.resonant_peak.is_none(), "ζ={z}");
            }
        }
    }
}

#[test]
fn undamped_plant_has_infinite_peak_and_zero_phase_margin() {
    // 1/(s²+1): |G| = 1 at ω = √2 where φ = −180° (PM = 0); G is real on the whole axis, so
    // there are no isolated phase crossings; the peak is infinite at ω = 1; bandwidth
    // |1 − ω²| = 10^(3/20) ⇔ ω = √(1 + 10^(3/20)).
    let g = tf(&[1.0], &[1.0, 0.0, 1.0]);
    let m = g.margins().unwrap();
    assert_eq!(m.gain_crossings.len(), 1);
    assert!(rel(m.gain_crossover.unwrap(), 2f64.sqrt()) < 1e-14);
    assert!(m.phase_margin_deg.unwrap().abs() < 1e-10);
    assert!(m.phase_crossings.is_empty());
    assert_eq!(m.resonant_peak, Some(f64::INFINITY));
    assert!(rel(m.resonant_frequency.unwrap(), 1.0) < 1e-15);
    assert!(rel(m.bandwidth.unwrap(), (1.0 + 10f64.powf(0.15)).sqrt()) < 1e-13);
}

#[test]
fn triple_integrator_has_negative_phase_margin() {
    // 1/s³: |G| = 1 at ω = 1 with φ = −270° ⇒ PM = −90°; the phase never equals −180°.
    let g = tf(&[1.0], &[1.0, 0.0, 0.0, 0.0]);
    let m = g.margins().unwrap();
    assert!(rel(m.gain_crossover.unwrap(), 1.0) < 1e-15);
    assert!((m.phase_margin_deg.unwrap() + 90.0).abs() < 1e-12);
    assert!(m.gain_margin.is_none());
}

/// Checks every reported crossing against Horner evaluation of G(jω).
fn check_crossings(g: &TransferFunction) -> ltikit::analysis::Margins {
    let m = g.margins().unwrap();
    for c in &m.gain_crossings {
        let v = g.eval(Complex64::new(0.0, c.w));
        assert!(
            (v.norm() - 1.0).abs() < 1e-12,
            "|G(j{})| = {}",
            c.w,
            v.norm()
        );
        let pm = 180.0 + v.arg().to_degrees();
        let pm = pm - 360.0 * (pm / 360.0).round();
        assert!((pm - c.phase_margin_deg).abs() < 1e-9);
    }
    for c in &m.phase_crossings {
        let v = g.eval(Complex64::new(0.0, c.w));
        assert!(
            v.re < 0.0 && v.im.abs() < 1e-12 * v.norm(),
            "G(j{}) = {v}",
            c.w
        );
        assert!(rel(c.gain_margin, 1.0 / v.norm()) < 1e-12);
    }
    m
}

/// Sign changes of f on a fine logarithmic grid (a brute-force count for comparison).
fn count_sign_changes(f: impl Fn(f64) -> f64, lo: f64, hi: f64, n: usize) -> usize {
    let mut prev = f(lo);
    let mut count = 0;
    for i in 1..=n {
        let w = lo * (hi / lo).powf(i as f64 / n as f64);
        let v = f(w);
        if v.signum() != prev.signum() {
            count += 1;
        }
        prev = v;
    }
    count
}

#[test]
fn plant_with_several_crossings() {
    // 0.5/(s+1) · 100/(s² + 0.2 s + 100): a resonance lifts |G| above 1 near ω = 10, giving
    // two gain crossings; the phase passes −180° just above the resonance.
    let g = tf(&[50.0], &[1.0, 1.2, 100.2, 100.0]);
    let m = check_crossings(&g);
    let mag = |w: f64| g.eval(Complex64::new(0.0, w)).norm() - 1.0;
    let im = |w: f64| g.eval(Complex64::new(0.0, w)).im;
    assert_eq!(m.gain_crossings.len(), 2);
    assert_eq!(
        m.gain_crossings.len(),
        count_sign_changes(mag, 1e-3, 1e3, 200_000)
    );
    assert_eq!(m.phase_crossings.len(), 1);
    assert!(count_sign_changes(im, 1e-3, 1e3, 200_000) >= 1);
    // the headline is the crossing closest to 0° / 0 dB
    let best = m
        .gain_crossings
        .iter()
        .map(|c| c.phase_margin_deg.abs())
        .fold(f64::INFINITY, f64::min);
    assert!((m.phase_margin_deg.unwrap().abs() - best).abs() < 1e-12);

    // conditionally stable loop: K (s+1)² / s³ · 1/(s/10 + 1)² — two phase crossings.
    let num = [100.0 * 20.0, 2.0 * 100.0 * 20.0, 100.0 * 20.0];
    let den = [1.0, 20.0, 100.0, 0.0, 0.0, 0.0];
    let g = tf(&num, &den);
    let m = check_crossings(&g);
    let im = |w: f64| {
        let v = g.eval(Complex64::new(0.0, w));
        if v.re < 0.0 { v.im } else { 1.0 }
    };
    assert_eq!(
        m.phase_crossings.len(),
        count_sign_changes(im, 1e-3, 1e4, 400_000)
    );
    assert!(m.phase_crossings.len() >= 2, "{m:?}");
    let best = m
        .phase_crossings
        .iter()
        .map(|c| c.gain_margin_db.abs())
        .fold(f64::INFINITY, f64::min);
    assert!((m.gain_margin_db.unwrap().abs() - best).abs() < 1e-12);
}

#[test]
fn zero_and_static_plants() {
    let m = tf(&[0.0], &[1.0, 1.0]).margins().unwrap();
    assert!(m.gain_margin.is_none() && m.phase_margin_deg.is_none() && m.bandwidth.is_none());
    // a static gain 2: |G| ≠ 1 anywhere, φ = 0: nothing is defined
    let m = tf(&[2.0], &[1.0]).margins().unwrap();
    assert!(m.gain_crossings.is_empty() && m.phase_crossings.is_empty());
    assert!(m.bandwidth.is_none() && m.resonant_peak.is_none());
    // −2: φ = −180° everywhere — not isolated crossings
    let m = tf(&[-2.0], &[1.0]).margins().unwrap();
    assert!(m.phase_crossings.is_empty());
}

#[test]
fn cancelled_factors_do_not_create_crossings() {
    // (s+3)/((s+3)(s+1)³) is 1/(s+1)³
    let g = tf(&[1.0, 3.0], &[1.0, 6.0, 12.0, 10.0, 3.0]);
    let m = g.margins().unwrap();
    assert!(rel(m.gain_margin.unwrap(), 8.0) < 1e-12);
    assert!(rel(m.phase_crossover.unwrap(), 3f64.sqrt()) < 1e-12);
}

/// A shallow resonance of an ill-conditioned order-10 plant (one of the random batch plants):
/// |G| rises 2.3e-6 above the dc gain at ω ≈ 0.0662. Reference: the maximum of |G(jω)| on a
/// fine grid (Horner on the coefficients).
#[test]
fn shallow_resonance_of_an_order_10_plant() {
    let num = [
        34.23913997766383,
        1275.6111062519974,
        18904.976397165203,
        139281.3110671061,
        510006.40588201844,
        742441.9772736663,
    ];
    let den = [
        1.0,
        44.79244757385845,
        840.2687201102128,
        8632.529748990331,
        53717.04422142902,
        213941.28576771013,
        567676.4328482284,
        1022523.8391660086,
        1226483.0132091339,
        908082.7583826012,
        331913.0058952744,
    ];
    let g = TransferFunction::from_descending(&num, &den).unwrap();
    let dc = num[5] / den[10];
    let (mut best_w, mut best) = (0.0, 0.0);
    for k in 0..=20000 {
        let w = 0.03 + 0.07 * k as f64 / 20000.0;
        let m = g.eval(num_complex::Complex64::new(0.0, w)).norm() / dc;
        if m > best {
            best = m;
            best_w = w;
        }
    }
    let m = g.margins().unwrap();
    let mr = m.resonant_peak.expect("the shallow peak is found");
    let wr = m.resonant_frequency.unwrap();
    assert!((mr - best).abs() < 1e-10, "Mr {mr} vs grid {best}");
    assert!((wr - best_w).abs() < 1e-4, "wr {wr} vs grid {best_w}");
    assert!(mr > 1.0 + 2e-6);
}

#[test]
fn negative_dc_gain_is_a_crossing_at_zero_frequency() {
    // (s + 1)/((s − 1)(s + 2)(s + 3)(s + 4)): the closed loop with gain K has the
    // characteristic polynomial s⁴ + 8s³ + 17s² + (K − 2)s + (K − 24). Routh–Hurwitz: stable
    // exactly for 24 < K < 90; at K = 24 a root crosses at s = 0 (G(0) = −1/24), at K = 90 the
    // auxiliary row 6s² + 66 puts a pair at ±j√11. Both gain margins are crossings.
    let g = tf(&[1.0, 1.0], &[1.0, 8.0, 17.0, -2.0, -24.0]);
    for f in [
        g.factored().unwrap(),
        ltikit::analysis::Factored::from_zpk(
            &[real_root(-1.0)],
            &[
                real_root(1.0),
                real_root(-2.0),
                real_root(-3.0),
                real_root(-4.0),
            ],
            1.0,
        )
        .unwrap(),
    ] {
        let m = f.margins().unwrap();
        assert_eq!(m.phase_crossings.len(), 2, "{m:?}");
        let (a, b) = (m.phase_crossings[0], m.phase_crossings[1]);
        assert_eq!(a.w, 0.0);
        assert!(rel(a.gain_margin, 24.0) < 1e-13, "{a:?}");
        assert!(rel(b.w, 11f64.sqrt()) < 1e-12, "{b:?}");
        assert!(rel(b.gain_margin, 90.0) < 1e-12, "{b:?}");
        // the headline is the one closest to 0 dB: 24
        assert_eq!(m.phase_crossover, Some(0.0));
    }
}
