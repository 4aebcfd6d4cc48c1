//! Routh–Hurwitz tables against textbook cases (root counts by numpy.roots, quoted) and
//! against the root finder on random polynomials.

mod common;

use common::ltikit;
use ltikit::Poly;
use ltikit::analysis::{RouthEvent, routh};

fn counts(c: &[f64]) -> (usize, usize, usize) {
    let t = routh(&Poly::from_descending(c).unwrap()).unwrap();
    (t.rhp, t.axis, t.lhp)
}

#[test]
fn textbook_tables() {
    // (rhp, axis, lhp) from numpy.roots.
    assert_eq!(counts(&[1.0, 1.0, 2.0, 8.0]), (2, 0, 1));
    assert_eq!(counts(&[1.0, 3.0, 3.0, 1.0]), (0, 0, 3));
    assert_eq!(counts(&[2.0, -1.0, 0.0, 3.0]), (2, 0, 1));
    // Zero first element (the s³ row of s⁵ + 2s⁴ + 2s³ + 4s² + 11s + 10).
    let t = routh(&Poly::from_descending(&[1.0, 2.0, 2.0, 4.0, 11.0, 10.0]).unwrap()).unwrap();
    assert_eq!((t.rhp, t.axis, t.lhp), (2, 0, 3));
    assert!(matches!(
        t.events[0],
        RouthEvent::ZeroFirstElement { power: 3, .. }
    ));
    // Rows of zeros: s⁵ + 2s⁴ + 24s³ + 48s² − 25s − 50 (auxiliary 2s⁴ + 48s² − 50: ±1, ±5j),
    // s⁴ + s³ + 3s² + 2s + 2 (auxiliary s² + 2: ±j√2), (s² + 1)(s² + 4).
    let t = routh(&Poly::from_descending(&[1.0, 2.0, 24.0, 48.0, -25.0, -50.0]).unwrap()).unwrap();
    assert_eq!((t.rhp, t.axis, t.lhp), (1, 2, 2));
    match &t.events[0] {
        RouthEvent::ZeroRow {
            power,
            auxiliary,
            axis_roots,
        } => {
            assert_eq!(*power, 3);
            assert_eq!(auxiliary, &vec![2.0, 0.0, 48.0, 0.0, -50.0]);
            assert_eq!(*axis_roots, 2);
        }
        e => panic!("{e:?}"),
    }
    assert_eq!(counts(&[1.0, 1.0, 3.0, 2.0, 2.0]), (0, 2, 2));
    assert_eq!(counts(&[1.0, 0.0, 5.0, 0.0, 4.0]), (0, 4, 0));
    // Roots at the origin, and a negative leading coefficient.
    assert_eq!(counts(&[1.0, 3.0, 2.0, 0.0]), (0, 1, 2));
    assert_eq!(counts(&[-1.0, -1.0, -2.0, -8.0]), (2, 0, 1));
    assert!(routh(&Poly::from_descending(&[3.0]).unwrap()).is_err());
}

#[test]
fn random_polynomials_agree_with_the_roots() {
    // Products of random real and complex-pair factors with real parts at least 0.1 from the
    // axis: the count of right-half-plane factors is known by construction.
    let mut state: u64 = 0x2545_F491_4F6C_DD1D;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..300 {
        let mut p = Poly::from_descending(&[1.0]).unwrap();
        let mut rhp = 0;
        let mut n = 0;
        for _ in 0..(1 + (next() * 4.0) as usize) {
            let re = (0.1 + 2.0 * next()) * if next() < 0.4 { 1.0 } else { -1.0 };
            if re > 0.0 {
                rhp += 1;
            }
            let f = if next() < 0.5 {
                n += 1;
                Poly::from_descending(&[1.0, -re]).unwrap()
            } else {
                let im = 0.1 + 3.0 * next();
                if re > 0.0 {
                    rhp += 1;
                }
                n += 2;
                Poly::from_descending(&[1.0, -2.0 * re, re * re + im * im]).unwrap()
            };
            p = &p * &f;
        }
        let t = routh(&p).unwrap();
        assert_eq!(
            (t.rhp, t.axis, t.lhp),
            (rhp, 0, n - rhp),
            "{:?}",
            p.coeffs()
        );
    }
}

#[test]
fn the_command_line() {
    let run = |args: &[&str]| {
        let mut v = vec!["ltikit", "routh"];
        v.extend_from_slice(args);
        ltikit::cli::run_from(v)
    };
    assert!(run(&["--den", "1 2 24 48 -25 -50", "--json"]).is_ok());
    // 1/(s(s + 1)(s + 2)) with K = 6: the closed loop s³ + 3s² + 2s + 6 has ±j√2 (the root
    // locus crosses the axis at K = 6).
    assert!(run(&["--num", "1", "--den", "1 3 2 0", "--gain", "6"]).is_ok());
    let t = routh(&Poly::from_descending(&[1.0, 3.0, 2.0, 6.0]).unwrap()).unwrap();
    assert_eq!((t.rhp, t.axis, t.lhp), (0, 2, 1));
    assert!(run(&["--num", "1", "--den", "1 3 2 0", "--gain", "nan"]).is_err());
    assert!(run(&["--num", "1", "--den", "1 4 1 -6", "--gain-range", "--json"]).is_ok());
    assert!(run(&["--num", "1 0 0 0 0", "--den", "1 3 2 0", "--gain-range"]).is_err());
    assert!(run(&["--a", "0 1; -4 -0.8", "--b", "0; 1", "--c", "1 0"]).is_err());
}

#[test]
fn stable_gain_sets_against_a_dense_scan() {
    use ltikit::analysis::stable_gains;
    // 1/(s(s+1)(s+2)): (0, 6); (s + 3)/(s(s − 1)): the closed loop s² + (K − 1)s + 3K is
    // stable for K > 1; 1/((s − 1)(s + 2)(s + 3)): s³ + 4s² + s − 6 + K, Hurwitz for
    // 6 < K < 10 (K − 6 > 0 and 4·1 > K − 6).
    let p = |c: &[f64]| Poly::from_descending(c).unwrap();
    let k = stable_gains(&p(&[1.0]), &p(&[1.0, 3.0, 2.0, 0.0])).unwrap();
    assert!(
        k.len() == 1 && k[0].0.abs() < 1e-12 && (k[0].1 - 6.0).abs() < 1e-12,
        "{k:?}"
    );
    let k = stable_gains(&p(&[1.0, 3.0]), &p(&[1.0, -1.0, 0.0])).unwrap();
    assert!(
        k.len() == 1 && (k[0].0 - 1.0).abs() < 1e-12 && k[0].1 == f64::INFINITY,
        "{k:?}"
    );
    let d = p(&[1.0, 4.0, 1.0, -6.0]);
    let k = stable_gains(&p(&[1.0]), &d).unwrap();
    assert!(
        k.len() == 1 && (k[0].0 - 6.0).abs() < 1e-12 && (k[0].1 - 10.0).abs() < 1e-12,
        "{k:?}"
    );
    // Dense scan: the closed-loop roots (by the root finder) agree with the set.
    for i in 0..400 {
        let g = -5.0 + 0.05 * i as f64;
        if k.iter()
            .any(|(lo, hi)| (g - lo).abs() < 1e-6 || (g - hi).abs() < 1e-6)
        {
            continue;
        }
        let q = &d + &p(&[1.0]).scale(g);
        let stable = q.roots().unwrap().iter().all(|r| r.value.re < 0.0);
        let inside = k.iter().any(|(lo, hi)| *lo < g && g < *hi);
        assert_eq!(stable, inside, "K = {g}");
    }
}

#[test]
fn repeated_axis_roots_are_counted_once() {
    // (s² + 1)²: two nested zero rows (auxiliaries s⁴ + 2s² + 1, then s² + 1); 4 axis roots,
    // not 6. (s² + 1)²(s + 1) and (s² + 4)(s² + 1)² likewise (root counts by construction).
    assert_eq!(counts(&[1.0, 0.0, 2.0, 0.0, 1.0]), (0, 4, 0));
    assert_eq!(counts(&[1.0, 1.0, 2.0, 2.0, 1.0, 1.0]), (0, 4, 1));
    assert_eq!(counts(&[1.0, 0.0, 6.0, 0.0, 9.0, 0.0, 4.0]), (0, 6, 0));
}

#[test]
fn the_float_table_agrees_with_exact_counts() {
    // Integer polynomials, many with repeated factors on the axis ((s² + a)^k) and at the
    // origin: the f64 table against the exact rational Routh–Hurwitz counts
    // (ExactPoly::half_plane_counts, Cauchy indices in exact arithmetic).
    use ltikit::poly::exact::ExactPoly;
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = |m: i64| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed % (2 * m as u64 + 1)) as i64 - m
    };
    let mul = |a: &[f64], b: &[f64]| {
        let mut out = vec![0.0; a.len() + b.len() - 1];
        for (i, x) in a.iter().enumerate() {
            for (j, y) in b.iter().enumerate() {
                out[i + j] += x * y;
            }
        }
        out
    };
    let mut disagree = Vec::new();
    for case in 0..400 {
        let mut p = vec![1.0];
        for _ in 0..(1 + next(2).unsigned_abs()) {
            let q: Vec<f64> = match next(3) {
                -3 | -2 => vec![1.0, 0.0, (1 + next(4).abs()) as f64],
                -1 => vec![1.0, 0.0],
                _ => vec![1.0, next(5) as f64, next(6) as f64],
            };
            p = mul(&p, &q);
        }
        let e = ExactPoly::from_f64_descending(&p)
            .unwrap()
            .half_plane_counts()
            .unwrap();
        let t = routh(&Poly::from_descending(&p).unwrap()).unwrap();
        if (t.rhp, t.axis, t.lhp) != (e.rhp, e.axis, e.lhp) {
            disagree.push((case, p));
        }
    }
    assert!(
        disagree.is_empty(),
        "{} cases: {:?}",
        disagree.len(),
        &disagree[..disagree.len().min(5)]
    );
}

#[test]
fn the_command_line_confirms_in_exact_arithmetic() {
    let out = ltikit(&["routh", "--den", "1 0 2.00000002 0 1.00000002", "--json"]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // s⁴ + 2.00000002 s² + 1.00000002 = (s² + 1)(s² + 1.00000002): four distinct roots on the
    // axis, decided on the typed decimals
    assert_eq!(v["exact"]["axis"], 4);
    assert_eq!(v["exact"]["rhp"], 0);
    let out = ltikit(&["routh", "--den", "1 1 2 8"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("Confirmed in exact rational arithmetic"),
        "{text}"
    );
}
