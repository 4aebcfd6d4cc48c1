//! Partial fractions: recomposition, distinct close poles, exact powers of repeated poles.
//!
//! Run with `--nocapture` to see the measured recomposition errors.

use ltikit::analysis::{PartialFractions, partial_fractions};
use ltikit::{Poly, TransferFunction};
use num_complex::Complex64;

mod common;
use common::{c, poly};

/// Over test points at distance ≥ `gap` from every pole: the largest |Σ terms − N/D| relative
/// to |N/D|, and relative to the size of the terms Σ|rₖ|/|s − pₖ|^k + |direct(s)| (the
/// rounding of the residues alone gives ~eps in this second measure; where the terms cancel,
/// as for poles 5e-4 apart with residues ±1000, the first is larger by the cancellation
/// factor whatever the method).
fn recomposition_errors(num: &Poly, den: &Poly, pf: &PartialFractions, gap: f64) -> (f64, f64) {
    let poles: Vec<Complex64> = pf.terms.iter().map(|t| t.pole).collect();
    let mut worst: f64 = 0.0;
    let mut worst_terms: f64 = 0.0;
    let mut tested = 0;
    for re in [-7.3, -2.9, -1.7, -0.35, 0.0, 0.45, 2.1, 6.0] {
        for im in [0.0, 0.37, 1.3, 2.6, 5.5, 11.0] {
            let s = c(re, im);
            if poles.iter().any(|p| (s - p).norm() < gap) {
                continue;
            }
            let g = num.eval_complex(s) / den.eval_complex(s);
            let diff = (pf.eval(s) - g).norm();
            let size: f64 = pf
                .terms
                .iter()
                .map(|t| t.residue.norm() / (s - t.pole).norm().powi(t.power as i32))
                .sum::<f64>()
                + pf.direct_poly().eval_complex(s).norm();
            worst = worst.max(diff / g.norm());
            worst_terms = worst_terms.max(diff / size.max(g.norm()));
            tested += 1;
        }
    }
    assert!(tested > 10, "too few test points");
    (worst, worst_terms)
}

#[test]
fn recomposes_to_1e12() {
    let cases: Vec<(&str, Vec<f64>, Vec<f64>)> = vec![
        ("(s+3)/((s+1)(s+2))", vec![1.0, 3.0], vec![1.0, 3.0, 2.0]),
        (
            "MATLAB stepinfo example",
            vec![1.0, 5.0, 5.0],
            vec![1.0, 1.65, 5.0, 6.5, 2.0],
        ),
        // (s+1)^3 (s^2+4s+13)
        (
            "triple real + pair",
            vec![2.0, -1.0, 0.5, 3.0],
            vec![1.0, 7.0, 28.0, 52.0, 43.0, 13.0],
        ),
        // ((s+1)^2+4)^3 = (s^2+2s+5)^3
        (
            "triple complex pair",
            vec![1.0, 0.0, -3.0, 2.0, 1.0],
            vec![1.0, 6.0, 27.0, 68.0, 135.0, 150.0, 125.0],
        ),
        // (s+1)^6
        (
            "(s+1)^6",
            vec![1.0, 2.0, 3.0, 4.0],
            vec![1.0, 6.0, 15.0, 20.0, 15.0, 6.0, 1.0],
        ),
        // improper: (s^4 + 1)/(s^2 + 0.8 s + 4)
        (
            "improper",
            vec![1.0, 0.0, 0.0, 0.0, 1.0],
            vec![1.0, 0.8, 4.0],
        ),
        // s^2 (s^2+1)^2 (s + 10): repeated poles on the axis and at 0
        (
            "axis poles",
            vec![1.0, 1.0, 1.0],
            vec![1.0, 10.0, 2.0, 20.0, 1.0, 10.0, 0.0, 0.0],
        ),
    ];
    let mut overall: f64 = 0.0;
    for (name, n, d) in cases {
        let (num, den) = (poly(&n), poly(&d));
        let pf = partial_fractions(&num, &den).unwrap();
        let (e, et) = recomposition_errors(&num, &den, &pf, 0.3);
        println!("recomposition {name}: {e:.2e} of |G|, {et:.2e} of the terms");
        assert!(e < 1e-12, "{name}: {e:e}");
        overall = overall.max(e);
    }
    println!("worst recomposition error: {overall:.2e} of |G|");
}

#[test]
fn poles_5e4_apart_stay_distinct() {
    // (s + 1)(s + 1.0005)(s + 2): scipy's residue merges the first two (tolerance 1e-3).
    let (a, b, d3) = (-1.0, -1.0005, -2.0);
    let den = &(&poly(&[1.0, 1.0]) * &poly(&[1.0, 1.0005])) * &poly(&[1.0, 2.0]);
    let num = poly(&[1.0, 0.5]);
    let pf = partial_fractions(&num, &den).unwrap();
    assert_eq!(pf.terms.len(), 3, "{pf:?}");
    assert!(pf.terms.iter().all(|t| t.power == 1));
    // Residues N(p)/Π(p − q), analytic.
    let want = [
        (a, (a + 0.5) / ((a - b) * (a - d3))),
        (b, (b + 0.5) / ((b - a) * (b - d3))),
        (d3, (d3 + 0.5) / ((d3 - a) * (d3 - b))),
    ];
    for (p, r) in want {
        let t = pf
            .terms
            .iter()
            .find(|t| (t.pole.re - p).abs() < 1e-9)
            .unwrap_or_else(|| panic!("pole {p} missing in {pf:?}"));
        assert!(
            (t.residue.re - r).abs() <= 1e-8 * r.abs(),
            "pole {p}: {} vs {r}",
            t.residue.re
        );
        assert_eq!(t.residue.im, 0.0);
    }
    let (e, et) = recomposition_errors(&num, &den, &pf, 0.3);
    println!(
        "5e-4-apart poles: residues ≈ ±1000, recomposition {e:.2e} of |G|, {et:.2e} of the terms"
    );
    assert!(et < 1e-14, "{et:e}");
    assert!(e < 1e-11, "{e:e}");
    // With a pair added the cancellation at |s| ≈ 10 is ~5e4: still ~eps of the terms.
    let den5 = &den * &poly(&[1.0, 1.0, 3.0]);
    let pf = partial_fractions(&num, &den5).unwrap();
    assert_eq!(pf.terms.len(), 5);
    let (e, et) = recomposition_errors(&num, &den5, &pf, 0.3);
    println!("  with s² + s + 3: {e:.2e} of |G|, {et:.2e} of the terms");
    assert!(et < 1e-14, "{et:e}");
}

#[test]
fn powers_of_repeated_poles_are_exact() {
    for k in 1..=6usize {
        // (s + 1)^k, coefficients binomial (exact); numerator s² + 3.
        let mut d = Poly::constant(1.0);
        for _ in 0..k {
            d = &d * &poly(&[1.0, 1.0]);
        }
        let num = poly(&[1.0, 0.0, 3.0]);
        let pf = partial_fractions(&num, &d).unwrap();
        let powers: Vec<usize> = pf.terms.iter().map(|t| t.power).collect();
        assert_eq!(powers, (1..=k).collect::<Vec<_>>(), "k = {k}");
        assert!(pf.terms.iter().all(|t| t.pole == c(-1.0, 0.0)), "k = {k}");
        // N(−1 + h) = 4 − 2h + h²: residue of power k − j is the h^j coefficient.
        let taylor = [4.0, -2.0, 1.0];
        for t in &pf.terms {
            let j = k - t.power;
            let want = taylor.get(j).copied().unwrap_or(0.0);
            assert_eq!(t.residue, c(want, 0.0), "k = {k}, power {}", t.power);
        }
        if k <= 2 {
            assert!(!pf.direct.is_empty());
        }
    }
}

#[test]
fn repeated_complex_pair_structure() {
    // 1/(s² + 2s + 5)³: a triple pair at −1 ± 2j.
    let g = TransferFunction::from_descending(&[1.0], &[1.0, 6.0, 27.0, 68.0, 135.0, 150.0, 125.0])
        .unwrap();
    let pf = g.partial_fractions().unwrap();
    assert_eq!(pf.terms.len(), 6);
    let upper: Vec<_> = pf.terms.iter().filter(|t| t.pole.im > 0.0).collect();
    let lower: Vec<_> = pf.terms.iter().filter(|t| t.pole.im < 0.0).collect();
    assert_eq!(upper.len(), 3);
    for (u, l) in upper.iter().zip(&lower) {
        assert_eq!(u.pole, l.pole.conj());
        assert_eq!(u.power, l.power);
        assert_eq!(u.residue, l.residue.conj());
    }
    // Leading coefficient: 1/(p − p̄)³ = 1/(4j)³ = j/64.
    let top = upper.iter().find(|t| t.power == 3).unwrap();
    assert!((top.residue - c(0.0, 1.0 / 64.0)).norm() < 1e-15);
}

#[test]
fn cancelled_pairs_are_removed_by_the_tf_method() {
    // (s² + 1)/((s² + 1)(s + 3)): the free function keeps ±j with ~0 residue, the TF method
    // works on 1/(s + 3).
    let g = TransferFunction::from_descending(&[1.0, 0.0, 1.0], &[1.0, 3.0, 1.0, 3.0]).unwrap();
    let pf = g.partial_fractions().unwrap();
    assert_eq!(pf.terms.len(), 1);
    assert!((pf.terms[0].residue - c(1.0, 0.0)).norm() < 1e-14);
    let raw = partial_fractions(g.num(), g.den()).unwrap();
    assert_eq!(raw.terms.len(), 3);
    for t in raw.terms.iter().filter(|t| t.pole.im != 0.0) {
        assert!(t.residue.norm() < 1e-15, "{t:?}");
    }
}

#[test]
fn json_contract() {
    let g = TransferFunction::from_descending(&[1.0], &[1.0, 2.0, 5.0]).unwrap();
    let v = serde_json::to_value(g.partial_fractions().unwrap()).unwrap();
    let t = &v["terms"][0];
    assert_eq!(t["pole"], serde_json::json!([-1.0, 2.0]));
    assert_eq!(t["power"], 1);
    assert_eq!(t["residue"], serde_json::json!([0.0, -0.25]));
    assert_eq!(v["direct"], serde_json::json!([]));
}
