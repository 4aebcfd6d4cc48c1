//! Roots with exact multiplicities (issue 2, item 2; DESIGN §3).
//!
//! Reference values are exact: the polynomials are built from known roots with exactly
//! representable coefficients.

use ltikit::numeric::dd::Dd;
use ltikit::{Poly, Root};
use num_complex::Complex64 as C;
use proptest::prelude::*;

fn poly(c: &[f64]) -> Poly {
    Poly::from_descending(c).unwrap()
}

fn pow(base: &Poly, k: usize) -> Poly {
    (0..k).fold(Poly::constant(1.0), |acc, _| &acc * base)
}

/// Relative error of the closest computed root to `z`, and its multiplicity.
fn closest(roots: &[Root], z: C) -> (f64, usize) {
    let r = roots
        .iter()
        .min_by(|a, b| (a.value - z).norm().total_cmp(&(b.value - z).norm()))
        .unwrap();
    ((r.value - z).norm() / z.norm().max(1.0), r.multiplicity)
}

#[test]
fn s_plus_one_to_the_k() {
    let mut worst: f64 = 0.0;
    for k in 1..=6 {
        let r = pow(&poly(&[1.0, 1.0]), k).roots().unwrap();
        assert_eq!(r.len(), 1, "(s+1)^{k}: {r:?}");
        assert_eq!(r[0].multiplicity, k);
        assert_eq!(r[0].value.im, 0.0);
        worst = worst.max((r[0].value.re + 1.0).abs());
    }
    assert!(worst <= 1e-12, "worst error {worst:e}");
}

#[test]
fn complex_triple_pair() {
    // ((s+1)² + 4)³: roots −1 ± 2j, each of multiplicity 3.
    let r = pow(&poly(&[1.0, 2.0, 5.0]), 3).roots().unwrap();
    assert_eq!(r.len(), 2);
    for z in [C::new(-1.0, 2.0), C::new(-1.0, -2.0)] {
        let (e, m) = closest(&r, z);
        assert_eq!(m, 3);
        assert!(e <= 1e-12, "error {e:e}");
    }
}

#[test]
fn imaginary_double_pair_and_triple_zero() {
    let r = poly(&[1.0, 0.0, 2.0, 0.0, 1.0]).roots().unwrap(); // (s²+1)²
    assert_eq!(r.len(), 2);
    for z in [C::new(0.0, 1.0), C::new(0.0, -1.0)] {
        let (e, m) = closest(&r, z);
        assert_eq!(m, 2);
        assert!(e <= 1e-12);
    }
    let r = poly(&[1.0, 0.0, 0.0, 0.0]).roots().unwrap(); // s³
    assert_eq!(r.len(), 1);
    assert_eq!(r[0].multiplicity, 3);
    assert_eq!(r[0].value, C::new(0.0, 0.0));
}

#[test]
fn tiny_leading_coefficient_finds_the_huge_root() {
    // 1e-17 s³ + s² + 3s + 2 = 1e-17 (s + 1e17 + …)(s + 1)(s + 2) approximately.
    let r = poly(&[1e-17, 1.0, 3.0, 2.0]).roots().unwrap();
    assert_eq!(r.len(), 3);
    let (e1, _) = closest(&r, C::new(-1.0, 0.0));
    let (e2, _) = closest(&r, C::new(-2.0, 0.0));
    assert!(e1 <= 1e-14 && e2 <= 1e-14, "{r:?}");
    let big = r.iter().map(|x| x.value.re).fold(0.0, f64::min);
    assert!((big + 1e17).abs() <= 1e-9 * 1e17, "{big:e}");
}

#[test]
fn order_50_without_failure() {
    // A fixed-seed random order-50 polynomial and a Chebyshev-like product: no error, all 50
    // roots returned, each a root to rounding level (backward error).
    let mut seed = 7u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    };
    let c: Vec<f64> = (0..=50).map(|_| rnd()).collect();
    let p = poly(&c);
    let r = p.roots().unwrap();
    assert_eq!(r.iter().map(|x| x.multiplicity).sum::<usize>(), 50);
    for x in &r {
        let backward = p.eval_complex(x.value).norm() / p.eval_abs(x.value.norm());
        assert!(
            backward <= 1e-13,
            "backward error {backward:e} at {}",
            x.value
        );
    }
}

/// p(z) in double-double complex arithmetic (z exactly representable): accurate far below
/// f64 rounding, so p(z)/p'(z) is the forward error of z as a root of p *as given*.
fn eval_dd(p: &Poly, z: C) -> C {
    let (mut re, mut im) = (Dd::ZERO, Dd::ZERO);
    let (zr, zi) = (Dd::from(z.re), Dd::from(z.im));
    for &a in p.coeffs() {
        let nr = re * zr - im * zi + Dd::from(a);
        let ni = re * zi + im * zr;
        re = nr;
        im = ni;
    }
    C::new(re.to_f64(), im.to_f64())
}

#[test]
fn simple_roots_of_generic_polynomials_after_polishing() {
    // Random polynomials: every computed root's forward error (one Newton correction with a
    // double-double residual) is ~1e-14 relative for well-conditioned roots, and within a few
    // eps times the root's condition number for all.
    let mut seed = 11u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64) / ((1u64 << 53) as f64)
    };
    let (mut worst_well, mut worst_ratio): (f64, f64) = (0.0, 0.0);
    for _ in 0..300 {
        let n = 3 + (rnd() * 10.0) as usize;
        let c: Vec<f64> = (0..=n).map(|_| rnd() * 2.0 - 1.0).collect();
        let p = poly(&c);
        let dp = p.derivative();
        for r in p.roots().unwrap() {
            assert_eq!(r.multiplicity, 1);
            let z = r.value;
            let err = (eval_dd(&p, z) / dp.eval_complex(z)).norm() / z.norm();
            let kappa = p.eval_abs(z.norm()) / (dp.eval_complex(z).norm() * z.norm());
            worst_ratio = worst_ratio.max(err / (kappa * f64::EPSILON));
            if kappa < 10.0 {
                worst_well = worst_well.max(err);
            }
        }
    }
    eprintln!(
        "generic roots: worst well-conditioned {worst_well:e}, worst err/(kappa eps) {worst_ratio:.2}"
    );
    assert!(
        worst_well <= 1e-14,
        "well-conditioned roots: worst {worst_well:e}"
    );
    assert!(
        worst_ratio <= 8.0,
        "error / (kappa eps): worst {worst_ratio}"
    );
}

#[test]
fn close_distinct_poles_stay_distinct() {
    // scipy merges poles 5e-4 apart; they are distinct simple roots.
    let p =
        Poly::from_roots(&[C::new(-1.0, 0.0), C::new(-1.0005, 0.0), C::new(-3.0, 0.0)]).unwrap();
    let r = p.roots().unwrap();
    assert_eq!(r.len(), 3);
    assert!(r.iter().all(|x| x.multiplicity == 1));
}

#[test]
fn s_to_the_n_plus_minus_c_companions_do_not_hang() {
    // nalgebra's uncapped iteration never returns on these (DESIGN §5).
    for n in [4usize, 6, 8, 12, 20, 40] {
        for c in [1.0, -1.0] {
            let mut coeffs = vec![0.0; n + 1];
            coeffs[0] = 1.0;
            coeffs[n] = c;
            let r = poly(&coeffs).roots().unwrap();
            assert_eq!(r.len(), n);
            for x in &r {
                assert!((x.value.norm() - 1.0).abs() < 1e-12);
            }
        }
    }
}

/// A root drawn from the "nice" sets: integers, half-integers, Gaussian integers.
fn nice_root() -> impl Strategy<Value = C> {
    prop_oneof![
        (-6i32..=6).prop_map(|k| C::new(k as f64, 0.0)),
        (-12i32..=12).prop_map(|k| C::new(k as f64 / 2.0, 0.0)),
        (-5i32..=5, 1i32..=4).prop_map(|(a, b)| C::new(a as f64, b as f64)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Random conjugate-symmetric roots with multiplicities → from_roots → roots() recovers
    /// every root to 1e-12 relative with its multiplicity.
    #[test]
    fn from_roots_round_trip(spec in proptest::collection::vec((nice_root(), 1usize..=3), 1..=4)) {
        let mut distinct: Vec<(C, usize)> = Vec::new();
        for (z, m) in spec {
            if distinct.iter().all(|(w, _)| (w - z).norm() > 0.25 && (w.conj() - z).norm() > 0.25) {
                distinct.push((z, m));
            }
        }
        let mut flat = Vec::new();
        for (z, m) in &distinct {
            for _ in 0..*m {
                flat.push(*z);
                if z.im != 0.0 {
                    flat.push(z.conj());
                }
            }
        }
        prop_assume!(flat.len() <= 14);
        let p = Poly::from_roots(&flat).unwrap();
        // Only exactly representable polynomials carry the 1e-12 promise.
        prop_assume!(p.coeffs().iter().all(|c| c.abs() < 2f64.powi(52)));
        let r = p.roots().unwrap();
        let expected: usize = distinct.iter().map(|(z, _)| if z.im != 0.0 { 2 } else { 1 }).sum();
        prop_assert_eq!(r.len(), expected, "{:?} -> {:?}", distinct, r);
        for (z, m) in &distinct {
            for w in [*z, z.conj()] {
                let (e, mult) = closest(&r, w);
                prop_assert_eq!(mult, *m, "{:?} -> {:?}", distinct, r);
                prop_assert!(e <= 1e-12, "root {} error {:e}", w, e);
            }
        }
    }
}

#[test]
fn very_high_multiplicities() {
    // Scatter ~eps^(1/m) (0.16 for m = 20) exceeds the grouping distance; the derivative stage
    // recovers the structure. (s+1)^20 and (s−2)^12 have exactly representable coefficients.
    for (base, k, root) in [(poly(&[1.0, 1.0]), 20, -1.0), (poly(&[1.0, -2.0]), 12, 2.0)] {
        let r = pow(&base, k).roots().unwrap();
        assert_eq!(r.len(), 1, "{r:?}");
        assert_eq!(r[0].multiplicity, k);
        assert!((r[0].value.re - root).abs() <= 1e-12 * root.abs());
    }
}

#[test]
fn extreme_ranges_split_at_the_tropical_gaps() {
    // s³ − 1e308 s² + 1e100 (issue 14): the roots are 1e308 (1 + 1e-516·…) and ±1e-104·(1 + …)
    // to far below rounding: s = 1e308 + δ with δ ≈ −1e100/1e616, and s² ≈ 1e100/1e308 for the
    // small pair (the s³ term is 1e-312 relative there).
    let r = poly(&[1.0, -1e308, 0.0, 1e100]).roots().unwrap();
    assert_eq!(r.len(), 3, "{r:?}");
    let big = r.iter().find(|x| x.value.re > 1.0).unwrap();
    assert!((big.value.re - 1e308).abs() <= 2.0 * f64::EPSILON * 1e308);
    for want in [1e-104, -1e-104] {
        let (e, m) = closest(&r, C::new(want, 0.0));
        let rel = e * 1.0 / 1e-104; // closest() divides by max(|z|, 1)
        assert!(m == 1 && rel <= 4.0 * f64::EPSILON, "{want}: {rel:e}");
    }
    // s² + 1e200 s + 1: −1e200 and −1e-200 (product 1, sum −1e200, exactly to rounding).
    let r = poly(&[1.0, 1e200, 1.0]).roots().unwrap();
    assert_eq!(r.len(), 2);
    assert!(
        (r[0].value.re + 1e-200).abs() <= 4.0 * f64::EPSILON * 1e-200,
        "{r:?}"
    );
    assert!(
        (r[1].value.re + 1e200).abs() <= 4.0 * f64::EPSILON * 1e200,
        "{r:?}"
    );
    // Tiny coefficients: (s + 1)(s + 2)·1e-300 and a subnormal scale.
    for k in [1e-300, 1e-310] {
        let r = poly(&[k, 3.0 * k, 2.0 * k]).roots().unwrap();
        assert_eq!(r.len(), 2);
        for want in [-1.0, -2.0] {
            let (e, m) = closest(&r, C::new(want, 0.0));
            assert!(m == 1 && e <= 1e-15, "k = {k:e}: {r:?}");
        }
    }
    // A double root at −1e150 next to a simple one at −1 (tropical roots 2^498 and 2^0).
    let d =
        Poly::from_roots(&[C::new(-1e150, 0.0), C::new(-1e150, 0.0), C::new(-1.0, 0.0)]).unwrap();
    let r = d.roots().unwrap();
    assert_eq!(r.len(), 2, "{r:?}");
    let (e, m) = closest(&r, C::new(-1e150, 0.0));
    assert!(m == 2 && e / 1e150 <= 1e-14, "{r:?}");
}

#[test]
fn roots_beyond_f64_are_an_error_not_infinity() {
    // 1e-300 s + 1e300: the root −1e600 is not a double.
    assert!(poly(&[1e-300, 1e300]).roots().is_err());
}

#[test]
fn a_multiple_root_among_many_on_a_circle_is_still_found() {
    // (s + 1)⁴·(s + 3)²·Π(s² − 2·0.9·cos θₖ·s + 0.81) for 30 angles θₖ: 66 roots, the simple
    // ones 0.9·e^(±jθₖ) close enough that the grouping links the whole circle (the case the
    // derivative stage's work bound is for). The multiplicities must survive the bound.
    let mut p = &pow(&poly(&[1.0, 1.0]), 4) * &pow(&poly(&[1.0, 3.0]), 2);
    for k in 0..30 {
        let th = std::f64::consts::PI * (k as f64 + 0.5) / 31.0;
        p = &p * &poly(&[1.0, -1.8 * th.cos(), 0.81]);
    }
    let r = p.roots().unwrap();
    let (d1, m1) = closest(&r, C::new(-1.0, 0.0));
    let (d3, m3) = closest(&r, C::new(-3.0, 0.0));
    assert_eq!((m1, m3), (4, 2), "{r:?}");
    assert!(d1 < 1e-8 && d3 < 1e-8, "{d1} {d3}");
    assert_eq!(r.iter().map(|x| x.multiplicity).sum::<usize>(), 66);
}
