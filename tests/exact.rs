//! The exact path (issue 11): families with a known exact structure, typed as decimal text.
//!
//! Every reference is a closed form: the polynomials are products of the listed factors,
//! expanded exactly here (integer arithmetic on scaled decimals) and handed over as the
//! decimal text a user would type; the expected roots, multiplicities, cancellations and
//! half-plane counts are read off the factor list.

mod common;

use dashu_int::IBig;
use ltikit::LtiError;
use ltikit::poly::Root;
use ltikit::poly::exact::{ExactPoly, HalfPlaneCounts, Side, certify};
use num_complex::Complex64;
use proptest::prelude::*;

/// A decimal string as (integer mantissa, number of decimals).
fn dec(s: &str) -> (IBig, usize) {
    let neg = s.starts_with('-');
    let t = s.trim_start_matches(['-', '+']);
    let (int, frac) = t.split_once('.').unwrap_or((t, ""));
    let m: IBig = format!("{int}{frac}").parse().unwrap();
    (if neg { -m } else { m }, frac.len())
}

/// m·10^−k as decimal text.
fn text(m: &IBig, k: usize) -> String {
    let neg = *m < IBig::ZERO;
    let digits = if neg { (-m).to_string() } else { m.to_string() };
    let digits = format!("{digits:0>width$}", width = k + 1);
    let (a, b) = digits.split_at(digits.len() - k);
    let body = if k == 0 {
        a.to_string()
    } else {
        format!("{a}.{b}")
    };
    if neg { format!("-{body}") } else { body }
}

/// The product of factors (each a list of descending decimal coefficients) raised to their
/// multiplicities, expanded exactly, as descending decimal text.
fn expand(factors: &[(&[&str], usize)]) -> Vec<String> {
    let mut acc: Vec<IBig> = vec![IBig::ONE]; // descending, scaled by 10^−scale
    let mut scale = 0;
    for (f, m) in factors {
        let parsed: Vec<(IBig, usize)> = f.iter().map(|s| dec(s)).collect();
        let k = parsed.iter().map(|p| p.1).max().unwrap();
        let ints: Vec<IBig> = parsed
            .iter()
            .map(|(v, d)| v * IBig::from(10u8).pow(k - d))
            .collect();
        for _ in 0..*m {
            let mut out = vec![IBig::ZERO; acc.len() + ints.len() - 1];
            for (i, a) in acc.iter().enumerate() {
                for (j, b) in ints.iter().enumerate() {
                    out[i + j] += a * b;
                }
            }
            acc = out;
            scale += k;
        }
    }
    acc.iter().map(|c| text(c, scale)).collect()
}

fn poly(factors: &[(&[&str], usize)]) -> ExactPoly {
    let t = expand(factors);
    ExactPoly::parse_descending(&t).unwrap()
}

/// Roots with multiplicities match the expected list: same count, same multiplicities,
/// values within `ulps` units in the last place (relative to |root|).
fn assert_roots(got: &[Root], want: &[(Complex64, usize)], ulps: f64) {
    assert_eq!(got.len(), want.len(), "got {got:?}");
    for (z, m) in want {
        let hit = got
            .iter()
            .find(|r| (r.value - z).norm() <= ulps * f64::EPSILON * z.norm().max(1e-300))
            .unwrap_or_else(|| panic!("no root near {z} in {got:?}"));
        assert_eq!(hit.multiplicity, *m, "multiplicity of {z}");
    }
}

fn c(re: f64, im: f64) -> Complex64 {
    Complex64::new(re, im)
}

#[test]
fn clustered_multiple_roots_come_out_exact() {
    // (s+3)^6 (s+3.03)^6: neighbours 1 % apart, each ×6 (the numerical path splits these).
    let p = poly(&[(&["1", "3"], 6), (&["1", "3.03"], 6)]);
    assert_roots(
        &p.roots().unwrap(),
        &[(c(-3.0, 0.0), 6), (c(-3.03, 0.0), 6)],
        1.0,
    );
    let p = poly(&[(&["1", "3"], 6), (&["1", "3.5"], 6)]);
    assert_roots(
        &p.roots().unwrap(),
        &[(c(-3.0, 0.0), 6), (c(-3.5, 0.0), 6)],
        1.0,
    );
    let p = poly(&[(&["1", "1"], 12)]);
    assert_roots(&p.roots().unwrap(), &[(c(-1.0, 0.0), 12)], 0.0);
    // Three neighbours 1 % apart with multiplicities 4, 4, 4 and a double complex pair.
    let p = poly(&[
        (&["1", "2"], 4),
        (&["1", "2.02"], 4),
        (&["1", "2.04"], 4),
        (&["1", "0.2", "1.01"], 2), // (s + 0.1)² + 1
    ]);
    let want = [
        (c(-2.0, 0.0), 4),
        (c(-2.02, 0.0), 4),
        (c(-2.04, 0.0), 4),
        (c(-0.1, 1.0), 2),
        (c(-0.1, -1.0), 2),
    ];
    assert_roots(&p.roots().unwrap(), &want, 2.0);
}

#[test]
fn simple_roots_1e12_apart_stay_distinct() {
    // Real: (s + 1)(s + 1.000000000001).
    let p = poly(&[(&["1", "1"], 1), (&["1", "1.000000000001"], 1)]);
    let r = p.roots().unwrap();
    assert_roots(&r, &[(c(-1.0, 0.0), 1), (c(-1.000000000001, 0.0), 1)], 1.0);
    assert!(r.iter().all(|x| x.value.im == 0.0));
    // On the axis: (s² + 1)(s² + 1.000000000002) = poles ±j, ±j·√1.000000000002.
    let p = poly(&[(&["1", "0", "1"], 1), (&["1", "0", "1.000000000002"], 1)]);
    let w = 1.000000000002f64.sqrt();
    let r = p.roots().unwrap();
    assert_roots(
        &r,
        &[
            (c(0.0, 1.0), 1),
            (c(0.0, -1.0), 1),
            (c(0.0, w), 1),
            (c(0.0, -w), 1),
        ],
        1.0,
    );
    assert!(r.iter().all(|x| x.value.re == 0.0));
    // Complex pairs 1e-12 apart: (s² + 2s + 2)(s² + 2s + 2.000000000002).
    let p = poly(&[(&["1", "2", "2"], 1), (&["1", "2", "2.000000000002"], 1)]);
    let b = (1.000000000002f64).sqrt(); // s = −1 ± j√(1 + 2e-12)
    assert_roots(
        &p.roots().unwrap(),
        &[
            (c(-1.0, 1.0), 1),
            (c(-1.0, -1.0), 1),
            (c(-1.0, b), 1),
            (c(-1.0, -b), 1),
        ],
        2.0,
    );
}

#[test]
fn controlsystems_plant_with_four_simple_axis_poles_is_marginally_stable() {
    // zpk([1], [j(1+1e-8), j, −j(1+1e-8), −j], 1) from ControlSystems.jl's tests:
    // denominator s⁴ + 2.00000002 s² + 1.00000002 (the numerical path merges the poles).
    let n = ExactPoly::parse_descending(&["1", "-1"]).unwrap();
    let d = ExactPoly::parse_descending(&["1", "0", "2.00000002", "0", "1.00000002"]).unwrap();
    let s = certify(&n, &d).unwrap();
    let poles = s.poles();
    assert_eq!(poles.len(), 4);
    assert!(
        poles
            .iter()
            .all(|p| p.multiplicity == 1 && p.value.re == 0.0)
    );
    let w = 1.00000002f64.sqrt(); // the exact poles are ±j·√1.00000002 ≈ ±j(1 + 1e-8)
    assert_roots(
        &poles,
        &[
            (c(0.0, 1.0), 1),
            (c(0.0, -1.0), 1),
            (c(0.0, w), 1),
            (c(0.0, -w), 1),
        ],
        1.0,
    );
    let h = s.reduced_denominator_counts();
    assert_eq!(
        h,
        HalfPlaneCounts {
            lhp: 0,
            axis: 4,
            rhp: 0
        }
    );
    assert!(s.cancelled().is_empty());
}

#[test]
fn roots_on_the_axis_versus_1e20_off_it() {
    let counts = |t: &[&str]| {
        let h = ExactPoly::parse_descending(t)
            .unwrap()
            .half_plane_counts()
            .unwrap();
        (h.lhp, h.axis, h.rhp)
    };
    // s² + 1: on the axis.
    assert_eq!(counts(&["1", "0", "1"]), (0, 2, 0));
    // (s ± 1e-20)² + 1 = s² ± 2e-20 s + 1 + 1e-40: just off it.
    assert_eq!(
        counts(&["1", "2e-20", "1.0000000000000000000000000000000000000001"]),
        (2, 0, 0)
    );
    assert_eq!(
        counts(&["1", "-2e-20", "1.0000000000000000000000000000000000000001"]),
        (0, 0, 2)
    );
    // A root 1e-30 to the right of the axis: (s − 1e-30)(s + 1).
    assert_eq!(
        counts(&["1", "0.999999999999999999999999999999", "-1e-30"]),
        (1, 0, 1)
    );
    // (s² + 1)² and (s² + 1)²(s + 2): repeated axis roots, counted with multiplicity.
    assert_eq!(counts(&["1", "0", "2", "0", "1"]), (0, 4, 0));
    let p = poly(&[(&["1", "0", "1"], 2), (&["1", "2"], 1)]);
    let h = p.half_plane_counts().unwrap();
    assert_eq!((h.lhp, h.axis, h.rhp), (1, 4, 0));
    let r = p.roots().unwrap();
    assert_roots(
        &r,
        &[(c(0.0, 1.0), 2), (c(0.0, -1.0), 2), (c(-2.0, 0.0), 1)],
        0.0,
    );
    // The perturbed pair's roots: −1e-20 ± j, the side decided exactly.
    let p =
        ExactPoly::parse_descending(&["1", "2e-20", "1.0000000000000000000000000000000000000001"])
            .unwrap();
    let s = certify(&ExactPoly::parse_descending(&["1"]).unwrap(), &p).unwrap();
    let f = &s.factors()[0];
    assert!(f.roots.iter().all(|r| r.side == Side::Left));
    assert_roots(
        &s.poles(),
        &[(c(-1e-20, 1.0), 1), (c(-1e-20, -1.0), 1)],
        1.0,
    );
    assert!(s.poles().iter().all(|r| r.value.re < 0.0));
}

#[test]
fn routh_singular_cases() {
    let counts = |t: &[&str]| {
        let h = ExactPoly::parse_descending(t)
            .unwrap()
            .half_plane_counts()
            .unwrap();
        (h.lhp, h.axis, h.rhp)
    };
    // Zero first element: s⁵ + 2s⁴ + 2s³ + 4s² + 11s + 10 (the classic ε example of Routh
    // tables): two RHP roots (numpy.roots: 0.895 ± 1.456j, −1.241 ± 1.038j, −1.309).
    assert_eq!(counts(&["1", "2", "2", "4", "11", "10"]), (3, 0, 2));
    // Zero row: s⁴ + s³ + 3s² + 2s + 2 = (s² + 2)(s² + s + 1).
    assert_eq!(counts(&["1", "1", "3", "2", "2"]), (2, 2, 0));
    // s³ + s² + 2s + 8 = (s + 2)(s² − s + 4): two RHP roots.
    assert_eq!(counts(&["1", "1", "2", "8"]), (1, 0, 2));
    // Zero row whose auxiliary polynomial has RHP roots: s⁴ − 1, and s⁴ + 4.
    assert_eq!(counts(&["1", "0", "0", "0", "-1"]), (1, 2, 1));
    assert_eq!(counts(&["1", "0", "0", "0", "4"]), (2, 0, 2));
    // Roots at s = 0 with others: s²(s + 1)(s − 3).
    assert_eq!(counts(&["1", "-2", "-3", "0", "0"]), (1, 2, 1));
}

#[test]
fn exact_cancellations_with_decimal_coefficients() {
    // (s + 0.1)(s + 0.3) / ((s + 0.1)(s + 0.7))
    let n = poly(&[(&["1", "0.1"], 1), (&["1", "0.3"], 1)]);
    let d = poly(&[(&["1", "0.1"], 1), (&["1", "0.7"], 1)]);
    let s = certify(&n, &d).unwrap();
    assert_roots(&s.cancelled(), &[(c(-0.1, 0.0), 1)], 0.0);
    assert_roots(&s.reduced_poles(), &[(c(-0.7, 0.0), 1)], 0.0);
    assert_roots(&s.reduced_zeros(), &[(c(-0.3, 0.0), 1)], 0.0);
    assert_eq!(s.reduced_denominator().to_string(), "s + 7/10");
    assert_eq!(s.reduced_numerator().to_string(), "s + 3/10");
    // Multiplicities: (s + 0.1)²(s + 0.2) / (s + 0.1)³(s² + 0.2 s + 1.01).
    let n = poly(&[(&["1", "0.1"], 2), (&["1", "0.2"], 1)]);
    let d = poly(&[(&["1", "0.1"], 3), (&["1", "0.2", "1.01"], 1)]);
    let s = certify(&n, &d).unwrap();
    assert_roots(&s.cancelled(), &[(c(-0.1, 0.0), 2)], 0.0);
    assert_roots(
        &s.reduced_poles(),
        &[(c(-0.1, 0.0), 1), (c(-0.1, 1.0), 1), (c(-0.1, -1.0), 1)],
        2.0,
    );
    assert_eq!(
        s.denominator_counts(),
        HalfPlaneCounts {
            lhp: 5,
            axis: 0,
            rhp: 0
        }
    );
    assert_eq!(
        s.reduced_denominator_counts(),
        HalfPlaneCounts {
            lhp: 3,
            axis: 0,
            rhp: 0
        }
    );
    // An integrator that cancels: s(s + 1) over s²(s + 2).
    let n = ExactPoly::parse_descending(&["1", "1", "0"]).unwrap();
    let d = ExactPoly::parse_descending(&["1", "2", "0", "0"]).unwrap();
    let s = certify(&n, &d).unwrap();
    assert_roots(&s.cancelled(), &[(c(0.0, 0.0), 1)], 0.0);
    assert_eq!(
        s.reduced_denominator_counts(),
        HalfPlaneCounts {
            lhp: 1,
            axis: 1,
            rhp: 0
        }
    );
    // The f64 [1, 0.2, 0.01] is not (s + 0.1)² exactly: typed as text it is.
    let t = ExactPoly::parse_descending(&["1", "0.2", "0.01"]).unwrap();
    assert_roots(&t.roots().unwrap(), &[(c(-0.1, 0.0), 2)], 0.0);
}

#[test]
fn degree_50_products_of_decimal_factors() {
    // Ten distinct decimal roots, each ×5.
    let roots = [
        "0.1", "0.25", "0.5", "0.75", "1.1", "1.5", "2.25", "3", "4.5", "6.1",
    ];
    let f: Vec<[&str; 2]> = roots.iter().map(|r| ["1", *r]).collect();
    let factors: Vec<(&[&str], usize)> = f.iter().map(|x| (&x[..], 5)).collect();
    let p = poly(&factors);
    assert_eq!(p.degree(), 50);
    let want: Vec<(Complex64, usize)> = roots
        .iter()
        .map(|r| (c(-r.parse::<f64>().unwrap(), 0.0), 5))
        .collect();
    assert_roots(&p.roots().unwrap(), &want, 0.0);
    // Fifty simple roots −0.1, −0.2, …, −5.0 (the square-free part is the whole polynomial).
    let tenths: Vec<String> = (1..=50).map(|k| text(&IBig::from(k), 1)).collect();
    let f: Vec<[&str; 2]> = tenths.iter().map(|r| ["1", r.as_str()]).collect();
    let factors: Vec<(&[&str], usize)> = f.iter().map(|x| (&x[..], 1)).collect();
    let p = poly(&factors);
    let want: Vec<(Complex64, usize)> = (1..=50).map(|k| (c(-(k as f64) / 10.0, 0.0), 1)).collect();
    assert_roots(&p.roots().unwrap(), &want, 1.0);
    // Complex pairs with multiplicity: ((s + 0.5)² + k²)^m for k = 1..5, m = 5 (degree 50).
    let quads: Vec<[String; 3]> = (1..=5)
        .map(|k: i64| {
            [
                "1".into(),
                "1".into(),
                text(&IBig::from(25 + 100 * k * k), 2),
            ]
        })
        .collect();
    let q: Vec<[&str; 3]> = quads.iter().map(|x| [&*x[0], &*x[1], &*x[2]]).collect();
    let factors: Vec<(&[&str], usize)> = q.iter().map(|x| (&x[..], 5)).collect();
    let p = poly(&factors);
    assert_eq!(p.degree(), 50);
    let want: Vec<(Complex64, usize)> = (1..=5)
        .flat_map(|k| [(c(-0.5, k as f64), 5), (c(-0.5, -(k as f64)), 5)])
        .collect();
    assert_roots(&p.roots().unwrap(), &want, 2.0);
    assert_eq!(
        p.half_plane_counts().unwrap(),
        HalfPlaneCounts {
            lhp: 50,
            axis: 0,
            rhp: 0
        }
    );
}

#[test]
fn malformed_tokens_are_errors_naming_the_token() {
    for (tok, why) in [
        ("1/0", "division by zero"),
        ("1/", "no denominator"),
        ("/2", "no numerator"),
        ("", "empty"),
        ("1e999999", "exponent beyond"),
        ("nan", "NaN and infinity"),
        ("inf", "NaN and infinity"),
        ("two", "unexpected character"),
    ] {
        let err = ExactPoly::parse_descending(&["1", tok, "3"]).unwrap_err();
        match &err {
            LtiError::BadNumber { token, reason, .. } => {
                assert_eq!(token, tok);
                assert!(reason.contains(why), "{tok}: {reason}");
            }
            other => panic!("{tok}: {other:?}"),
        }
        assert!(err.to_string().contains(&format!("'{tok}'")));
    }
    let long = "9".repeat(1500);
    let err = ExactPoly::parse_descending(&["1", long.as_str()]).unwrap_err();
    assert!(err.to_string().contains("more than 1000 digits"));
    assert!(err.to_string().len() < 200, "{err}");
    let empty: [&str; 0] = [];
    assert!(ExactPoly::parse_descending(&empty).is_err());
}

#[test]
fn beyond_the_budget_is_a_clear_result() {
    let big: Vec<String> = (0..=101).map(|k| (k + 1).to_string()).collect();
    let p = ExactPoly::parse_descending(&big).unwrap();
    match p.roots() {
        Err(LtiError::BeyondExactBudget { reason }) => assert!(reason.contains("degree 101")),
        other => panic!("{other:?}"),
    }
}

/// A random factor: a real root a (as text with up to 2 decimals) or a quadratic
/// s² + b s + c with complex roots −b/2 ± j√(c − b²/4).
#[derive(Debug, Clone)]
enum F {
    Real(i64),      // root = −k/100 … factor s + k/100
    Pair(i64, i64), // s² + (b/10) s + c/100 with c/100 > (b/10)²/4
}

fn factor_strategy() -> impl Strategy<Value = F> {
    prop_oneof![
        (-500i64..500).prop_map(F::Real),
        ((-30i64..30), (1i64..400)).prop_map(|(b, extra)| F::Pair(b, 25 * b * b + extra)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random factor lists with random multiplicities → expand exactly → the certified
    /// structure equals the factor list: same distinct roots, 0 wrong multiplicities, and
    /// half-plane counts equal to those read off the factors.
    #[test]
    fn certified_structure_equals_the_factor_list(
        fs in prop::collection::vec((factor_strategy(), 1usize..4), 1..6)
    ) {
        // Distinct factors only.
        let mut seen = std::collections::HashSet::new();
        let fs: Vec<(F, usize)> = fs.into_iter().filter(|(f, _)| seen.insert(format!("{f:?}"))).collect();
        let texts: Vec<(Vec<String>, usize)> = fs.iter().map(|(f, m)| match f {
            F::Real(k) => (vec!["1".into(), text(&IBig::from(*k), 2)], *m),
            F::Pair(b, c) => (vec!["1".into(), text(&IBig::from(*b), 1), text(&IBig::from(*c), 2)], *m),
        }).collect();
        let refs: Vec<Vec<&str>> = texts.iter().map(|(t, _)| t.iter().map(String::as_str).collect()).collect();
        let factors: Vec<(&[&str], usize)> = refs.iter().zip(&texts).map(|(r, (_, m))| (&r[..], *m)).collect();
        let p = poly(&factors);
        let mut want = Vec::new();
        let mut counts = HalfPlaneCounts::default();
        for (f, m) in &fs {
            let side = |re: f64| if re < 0.0 { 0 } else if re == 0.0 { 1 } else { 2 };
            match f {
                F::Real(k) => {
                    let re = -(*k as f64) / 100.0;
                    want.push((c(re, 0.0), *m));
                    match side(re) { 0 => counts.lhp += m, 1 => counts.axis += m, _ => counts.rhp += m }
                }
                F::Pair(b, cc) => {
                    let re = -(*b as f64) / 20.0;
                    let im = ((*cc as f64) / 100.0 - re * re).sqrt();
                    want.push((c(re, im), *m));
                    want.push((c(re, -im), *m));
                    match side(re) { 0 => counts.lhp += 2 * m, 1 => counts.axis += 2 * m, _ => counts.rhp += 2 * m }
                }
            }
        }
        let got = p.roots().unwrap();
        prop_assert_eq!(got.len(), want.len());
        for (z, m) in &want {
            let hit = got.iter().find(|r| (r.value - z).norm() <= 1e-12 * z.norm().max(1e-3));
            prop_assert!(hit.is_some(), "no root near {} in {:?}", z, got);
            prop_assert_eq!(hit.unwrap().multiplicity, *m);
        }
        prop_assert_eq!(p.half_plane_counts().unwrap(), counts);
        // The sides of the certified roots agree with the exact counts.
        let s = certify(&p, &ExactPoly::parse_descending(&["1"]).unwrap()).unwrap();
        let mut by_side = HalfPlaneCounts::default();
        for f in s.factors() {
            for r in &f.roots {
                match r.side {
                    Side::Left => by_side.lhp += f.in_numerator,
                    Side::Axis => by_side.axis += f.in_numerator,
                    Side::Right => by_side.rhp += f.in_numerator,
                }
            }
        }
        prop_assert_eq!(by_side, counts);
    }

    /// Shared factors cancel with multiplicity min(m_N, m_D).
    #[test]
    fn cancellations_have_the_minimum_multiplicity(
        shared in -300i64..300, mn in 1usize..4, md in 1usize..4,
        other_n in -300i64..300, other_d in -300i64..300,
    ) {
        prop_assume!(other_n != shared && other_d != shared && other_n != other_d);
        let sh = text(&IBig::from(shared), 2);
        let on = text(&IBig::from(other_n), 2);
        let od = text(&IBig::from(other_d), 2);
        let n = poly(&[(&["1", sh.as_str()], mn), (&["1", on.as_str()], 1)]);
        let d = poly(&[(&["1", sh.as_str()], md), (&["1", od.as_str()], 2)]);
        let s = certify(&n, &d).unwrap();
        let can = s.cancelled();
        prop_assert_eq!(can.len(), 1);
        prop_assert_eq!(can[0].multiplicity, mn.min(md));
        prop_assert_eq!(can[0].value.re, -(shared as f64) / 100.0);
        prop_assert_eq!(s.reduced_denominator().degree(), 2 + md - mn.min(md));
    }
}

// ---------------------------------------------------------------------------------------
// Stage 2: the exact structure reaches the user — through `Plant` (coefficients as text),
// `Factored::from_exact` and the command line.

mod through_the_plant {
    use super::common::{ltikit, ltikit_with_stdin};
    use super::{c, expand, text};
    use dashu_int::IBig;
    use ltikit::analysis::{Factored, StabilityClass, StructurePath};
    use ltikit::lti::Plant;
    use ltikit::poly::Root;
    use ltikit::poly::exact::ExactPoly;
    use num_complex::Complex64;
    use proptest::prelude::*;

    fn plant(num: &str, den: &str) -> Factored {
        let f = Plant::from_text(Some(num), den)
            .unwrap()
            .factored()
            .unwrap();
        assert_eq!(f.structure_path(), StructurePath::Exact, "{num} / {den}");
        f
    }

    fn joined(factors: &[(&[&str], usize)]) -> String {
        expand(factors).join(" ")
    }

    /// Same roots (to `ulps` relative), same multiplicities.
    fn same(got: &[Root], want: &[(Complex64, usize)], ulps: f64) {
        super::assert_roots(got, want, ulps);
    }

    #[test]
    fn controlsystems_plant_is_marginally_stable_with_four_simple_poles() {
        // zpk([1], [±j(1+1e-8), ±j], 1): (s − 1)/(s⁴ + 2.00000002 s² + 1.00000002).
        let f = plant("1 -1", "1 0 2.00000002 0 1.00000002");
        assert_eq!(f.poles().len(), 4);
        assert!(f.poles().iter().all(|p| p.multiplicity == 1));
        let st = f.stability();
        assert_eq!(st.bibo, StabilityClass::MarginallyStable);
        assert_eq!(st.internal, StabilityClass::MarginallyStable);
        assert!(
            st.reason.ends_with("marginally stable (decided exactly)"),
            "{}",
            st.reason
        );
        // The same through the library constructor from exact values.
        let n = ExactPoly::parse_descending(&["1", "-1"]).unwrap();
        let d = ExactPoly::parse_descending(&["1", "0", "2.00000002", "0", "1.00000002"]).unwrap();
        let g = Factored::from_exact(&n, &d).unwrap();
        assert_eq!(g.poles(), f.poles());
        assert_eq!(g.stability(), st);
    }

    #[test]
    fn close_real_poles_stay_apart() {
        // (s + 1)(s + 1.0000001) = s² + 2.0000001 s + 1.0000001
        let f = plant("1", "1 2.0000001 1.0000001");
        same(
            f.poles(),
            &[(c(-1.0, 0.0), 1), (c(-1.0000001, 0.0), 1)],
            1.0,
        );
        // 1e-12 relative apart on the real line and on the axis (closed forms).
        let p = joined(&[(&["1", "1"], 1), (&["1", "1.000000000001"], 1)]);
        same(
            plant("1", &p).poles(),
            &[(c(-1.0, 0.0), 1), (c(-1.000000000001, 0.0), 1)],
            1.0,
        );
        let p = joined(&[
            (&["1", "0", "1"], 1),
            (&["1", "0", "1.000000000002000000000001"], 1),
        ]);
        let f = plant("1", &p);
        assert_eq!(f.poles().len(), 4);
        assert_eq!(f.stability().bibo, StabilityClass::MarginallyStable);
    }

    #[test]
    fn clustered_sixfold_poles_are_exact() {
        for b in ["3.03", "3.5"] {
            let p = joined(&[(&["1", "3"], 6), (&["1", b], 6)]);
            let f = plant("1", &p);
            let want = -b.parse::<f64>().unwrap();
            same(f.poles(), &[(c(-3.0, 0.0), 6), (c(want, 0.0), 6)], 0.0);
            assert_eq!(f.modes().len(), 2);
            assert!(f.stability().bibo_stable);
        }
    }

    #[test]
    fn axis_versus_1e20_off_it() {
        // s² + 1: on the axis, marginally stable.
        assert_eq!(
            plant("1", "1 0 1").stability().bibo,
            StabilityClass::MarginallyStable
        );
        // (s − 1e-20)(s + 1) = s² + 0.99999999999999999999 s − 1e-20: unstable.
        let st = plant("1", "1 0.99999999999999999999 -1e-20").stability();
        assert_eq!(st.bibo, StabilityClass::Unstable, "{}", st.reason);
        // (s + 1e-20)(s + 1): stable.
        let st = plant("1", "1 1.00000000000000000001 1e-20").stability();
        assert_eq!(st.bibo, StabilityClass::Stable, "{}", st.reason);
        // (s + 1e-20)² + 1 = s² + 2e-20 s + (1 + 1e-40): poles −1e-20 ± j, stable.
        let st = plant("1", "1 2e-20 1.0000000000000000000000000000000000000001").stability();
        assert_eq!(st.bibo, StabilityClass::Stable, "{}", st.reason);
        // (s − 1e-20)² + 1: unstable, and (s² + 1)²: repeated axis poles, unstable.
        let st = plant("1", "1 -2e-20 1.0000000000000000000000000000000000000001").stability();
        assert_eq!(st.bibo, StabilityClass::Unstable, "{}", st.reason);
        let st = plant("1", "1 0 2 0 1").stability();
        assert!(
            st.reason.contains("repeated imaginary-axis"),
            "{}",
            st.reason
        );
    }

    #[test]
    fn exact_cancellations_with_decimal_coefficients() {
        // (s + 0.1)(s + 0.3) / ((s + 0.1)(s + 0.7))
        let f = plant("1 0.4 0.03", "1 0.8 0.07");
        assert_eq!(f.pole_zero().cancelled, vec![Root::new(c(-0.1, 0.0), 1)]);
        assert_eq!(f.reduced_poles(), &[Root::new(c(-0.7, 0.0), 1)]);
        assert_eq!(f.reduced_zeros(), &[Root::new(c(-0.3, 0.0), 1)]);
        assert_eq!(f.reduced_tf().unwrap().num().coeffs(), &[1.0, 0.3]);
        // (s − 0.1)(s + 0.3) / ((s − 0.1)(s + 0.7)): BIBO stable, internally unstable.
        let st = plant("1 0.2 -0.03", "1 0.6 -0.07").stability();
        assert!(st.bibo_stable && !st.internally_stable, "{}", st.reason);
        assert!(st.reason.contains("decided exactly"), "{}", st.reason);
        // The dc gain of the reduced G: 0.3/0.7.
        let g = f.dc_gain().unwrap();
        assert!((g - 0.3 / 0.7).abs() <= 2.0 * f64::EPSILON * g, "{g}");
    }

    #[test]
    fn degree_50_products_of_decimal_factors() {
        let roots = [
            "0.1", "0.25", "0.5", "0.75", "1.1", "1.5", "2.25", "3", "4.5", "6.1",
        ];
        let f: Vec<[&str; 2]> = roots.iter().map(|r| ["1", *r]).collect();
        let factors: Vec<(&[&str], usize)> = f.iter().map(|x| (&x[..], 5)).collect();
        let fac = plant("1", &joined(&factors));
        assert_eq!(fac.order(), 50);
        let want: Vec<(Complex64, usize)> = roots
            .iter()
            .map(|r| (c(-r.parse::<f64>().unwrap(), 0.0), 5))
            .collect();
        same(fac.poles(), &want, 0.0);
        assert!(fac.stability().bibo_stable);
    }

    #[test]
    fn beyond_the_budget_falls_back_and_says_so() {
        // s¹²⁰ + 1: degree above the exact budget (100), within MAX_ORDER (200).
        let mut den = vec!["0"; 121];
        den[0] = "1";
        den[120] = "1";
        let f = Plant::from_text(None, &den.join(" "))
            .unwrap()
            .factored()
            .unwrap();
        assert_eq!(f.structure_path(), StructurePath::Numerical);
        let why = f.exact_fallback().unwrap();
        assert!(why.contains("degree 120"), "{why}");
        assert!(!f.stability().reason.contains("decided exactly"));
        // f64 input keeps the numerical path: [1, 0.2, 0.01] is still (s + 0.1)².
        let g = ltikit::TransferFunction::from_descending(&[1.0], &[1.0, 0.2, 0.01]).unwrap();
        let f = g.factored().unwrap();
        assert_eq!(f.structure_path(), StructurePath::Numerical);
        assert_eq!(f.exact_fallback(), None);
        assert_eq!(f.poles().len(), 1);
        assert_eq!(f.poles()[0].multiplicity, 2);
    }

    #[test]
    fn bad_tokens_are_named() {
        let long = "1".repeat(1001);
        for (tok, shown) in [
            ("1/0", "'1/0'"),
            ("1/", "'1/'"),
            ("/2", "'/2'"),
            ("1e999999", "'1e999999'"),
            (long.as_str(), "'111"),
        ] {
            let e = Plant::from_text(None, &format!("1 {tok}"))
                .unwrap_err()
                .to_string();
            assert!(e.contains(shown) && e.contains("`den`"), "{tok}: {e}");
            assert!(e.len() < 300, "{e}");
        }
    }

    fn cli(args: &[&str], stdin: Option<&str>) -> (i32, String, String) {
        let out = match stdin {
            Some(s) => ltikit_with_stdin(args, s.as_bytes()),
            None => ltikit(args),
        };
        (
            out.status.code().unwrap_or(-1),
            String::from_utf8_lossy(&out.stdout).into_owned(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    }

    #[test]
    fn cli_reports_the_exact_path() {
        let (code, out, _) = cli(
            &[
                "analyze",
                "--num",
                "1 -1",
                "--den",
                "1 0 2.00000002 0 1.00000002",
                "--json",
            ],
            None,
        );
        assert_eq!(code, 0);
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(v["structure"], "exact");
        assert_eq!(v["poles"].as_array().unwrap().len(), 4);
        let r = v["stability_reason"].as_str().unwrap();
        assert!(r.ends_with("marginally stable (decided exactly)"), "{r}");
        let (code, out, _) = cli(&["analyze", "--den", "1 0.2 0.01"], None);
        assert_eq!(code, 0);
        assert!(out.contains("\nStructure: exact ("), "{out}");
        // A model computed from parameters is numerical (its coefficients are f64 results).
        let (_, out, _) = cli(
            &["analyze", "--model", "spring-mass-damper", "--json"],
            None,
        );
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(v["structure"], "numerical");
    }

    #[test]
    fn cli_batch_keeps_the_text_of_numbers() {
        // (s + 1)(s + 1.00000000000000025) = s² + 2.00000000000000025 s + 1.00000000000000025.
        // Rounded to f64 the coefficients are 2 + 2 ulp and 1 + 1 ulp, whose roots are
        // −1 ± 1.5e-8; kept as text they give −1 and −1.00000000000000025 (to 1 ulp).
        let lines = "{\"name\": \"a\", \"den\": [1, 2.00000000000000025, 1.00000000000000025]}\n\
                     {\"name\": \"b\", \"den\": \"1 0 1e999999\"}\n\
                     {\"name\": \"c\", \"den\": \"1 1/0\"}\n";
        let (code, out, _) = cli(&["analyze", "--batch", "-"], Some(lines));
        assert_eq!(code, 0, "{out}");
        let v: Vec<serde_json::Value> = out
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        assert_eq!(v[0]["structure"], "exact");
        assert_eq!(v[0]["poles"].as_array().unwrap().len(), 2);
        for (p, want) in v[0]["poles"]
            .as_array()
            .unwrap()
            .iter()
            .zip([-1.0, -(1.0 + 2.5e-16)])
        {
            let re = p[0].as_f64().unwrap();
            assert!((re - want).abs() <= f64::EPSILON, "{re} vs {want}");
        }
        let e = v[1]["error"].as_str().unwrap();
        assert!(e.contains("1e999999"), "{e}");
        let e = v[2]["error"].as_str().unwrap();
        assert!(e.contains("'1/0'"), "{e}");
    }

    #[test]
    fn cli_bad_tokens_exit_1_with_one_line() {
        for tok in ["1/0", "1/", "/2", "1e999999"] {
            let (code, _, err) = cli(&["analyze", "--den", &format!("1 {tok}")], None);
            assert_eq!(code, 1, "{tok}");
            assert_eq!(err.trim().lines().count(), 1, "{err}");
            assert!(err.contains(&format!("'{tok}'")), "{err}");
        }
    }

    #[derive(Debug, Clone)]
    enum F {
        Real(i64),
        Pair(i64, i64),
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// Random factor lists with random multiplicities, expanded exactly and typed as text
        /// into a plant: the factored form lists exactly those poles with those multiplicities,
        /// and its stability class is the one read off the factor list.
        #[test]
        fn plant_structure_equals_the_factor_list(
            fs in prop::collection::vec((prop_oneof![
                (-300i64..300).prop_map(F::Real),
                ((-20i64..20), (1i64..300)).prop_map(|(b, e)| F::Pair(b, 25 * b * b + e)),
            ], 1usize..4), 1..5)
        ) {
            let mut seen = std::collections::HashSet::new();
            let fs: Vec<(F, usize)> =
                fs.into_iter().filter(|(f, _)| seen.insert(format!("{f:?}"))).collect();
            let texts: Vec<(Vec<String>, usize)> = fs.iter().map(|(f, m)| match f {
                F::Real(k) => (vec!["1".into(), text(&IBig::from(*k), 2)], *m),
                F::Pair(b, cc) => {
                    (vec!["1".into(), text(&IBig::from(*b), 1), text(&IBig::from(*cc), 2)], *m)
                }
            }).collect();
            let refs: Vec<Vec<&str>> =
                texts.iter().map(|(t, _)| t.iter().map(String::as_str).collect()).collect();
            let factors: Vec<(&[&str], usize)> =
                refs.iter().zip(&texts).map(|(r, (_, m))| (&r[..], *m)).collect();
            let f = Plant::from_text(None, &joined(&factors)).unwrap().factored().unwrap();
            prop_assert_eq!(f.structure_path(), StructurePath::Exact);
            let mut want = Vec::new();
            let (mut rhp, mut axis_repeated, mut axis) = (false, false, false);
            for (fa, m) in &fs {
                let (re, im) = match fa {
                    F::Real(k) => (-(*k as f64) / 100.0, 0.0),
                    F::Pair(b, cc) => {
                        let re = -(*b as f64) / 20.0;
                        (re, ((*cc as f64) / 100.0 - re * re).sqrt())
                    }
                };
                want.push((c(re, im), *m));
                if im != 0.0 { want.push((c(re, -im), *m)); }
                rhp |= re > 0.0;
                axis |= re == 0.0;
                axis_repeated |= re == 0.0 && *m > 1;
            }
            let got = f.poles();
            prop_assert_eq!(got.len(), want.len());
            for (z, m) in &want {
                let hit = got.iter().find(|r| (r.value - z).norm() <= 1e-12 * z.norm().max(1e-3));
                prop_assert!(hit.is_some(), "no pole near {} in {:?}", z, got);
                prop_assert_eq!(hit.unwrap().multiplicity, *m);
            }
            let class = if rhp || axis_repeated {
                StabilityClass::Unstable
            } else if axis {
                StabilityClass::MarginallyStable
            } else {
                StabilityClass::Stable
            };
            prop_assert_eq!(f.stability().bibo, class);
        }
    }
}
