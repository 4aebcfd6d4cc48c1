//! Root locus: features against closed forms, the traced branches against the characteristic
//! polynomial, the crossings against the Routh stable-gain set, the CLI.

mod common;

use common::{ltikit, poly, rel};
use ltikit::Poly;
use ltikit::analysis::rlocus::{BreakKind, RootLocusOptions, root_locus, trace_at_gains};
use ltikit::analysis::{axis_crossings, stable_gains};
use num_complex::Complex64;

fn locus(num: &[f64], den: &[f64], negative: bool) -> ltikit::analysis::rlocus::RootLocus {
    root_locus(
        &poly(num),
        &poly(den),
        &RootLocusOptions {
            negative,
            ..Default::default()
        },
    )
    .unwrap()
}

#[test]
fn third_order_type_one_closed_forms() {
    // L = 1/(s(s + 1)(s + 2)). N·D′ − N′·D = 3s² + 6s + 2: σ = −1 ± 1/√3; on the locus
    // σ = −1 + 1/√3 with K = −σ(σ + 1)(σ + 2) = 2/(3√3). D(jω) + K = 0: ω² = 2, K = 6.
    // Centroid (0 − 1 − 2)/3 = −1, angles ±60°, 180°.
    let l = locus(&[1.0], &[1.0, 3.0, 2.0, 0.0], false);
    let r3 = 3f64.sqrt();
    assert_eq!(l.break_points.len(), 1);
    let b = &l.break_points[0];
    assert!(rel(b.s, -1.0 + 1.0 / r3) < 1e-10, "{}", b.s);
    assert!(rel(b.gain, 2.0 / (3.0 * r3)) < 1e-10, "{}", b.gain);
    assert_eq!(b.kind, BreakKind::BreakAway);
    assert_eq!(b.branches, 2);
    assert_eq!(l.crossings.len(), 1);
    assert!(rel(l.crossings[0].omega, 2f64.sqrt()) < 1e-10);
    assert!(rel(l.crossings[0].gain, 6.0) < 1e-10);
    let a = l.asymptotes.as_ref().unwrap();
    assert_eq!(a.count, 3);
    assert!(rel(a.centroid, -1.0) < 1e-15);
    assert_eq!(a.angles_deg, vec![-60.0, 60.0, 180.0]);
    // the complementary locus: the other root of 3s² + 6s + 2, K = −2/(3√3); asymptotes at
    // 0°, ±120°
    let n = locus(&[1.0], &[1.0, 3.0, 2.0, 0.0], true);
    assert_eq!(n.break_points.len(), 1);
    assert!(rel(n.break_points[0].s, -1.0 - 1.0 / r3) < 1e-10);
    assert!(rel(n.break_points[0].gain, -2.0 / (3.0 * r3)) < 1e-10);
    assert!(n.crossings.is_empty());
    assert_eq!(
        n.asymptotes.as_ref().unwrap().angles_deg,
        vec![-120.0, 0.0, 120.0]
    );
}

#[test]
fn break_in_and_break_away_between_zeros_and_poles() {
    // L = (s + 2)(s + 3)/(s(s + 1)): N·D′ − N′·D = 2(2s² + 6s + 3), σ = (−3 ± √3)/2 with
    // K = −D(σ)/N(σ) = 7 ∓ 4√3 (sympy: simplify(-s*(s+1)/((s+2)*(s+3))) at the roots).
    let l = locus(&[1.0, 5.0, 6.0], &[1.0, 1.0, 0.0], false);
    let r3 = 3f64.sqrt();
    assert_eq!(l.break_points.len(), 2);
    let (bin, baway) = (&l.break_points[0], &l.break_points[1]);
    assert_eq!(bin.kind, BreakKind::BreakIn);
    assert_eq!(baway.kind, BreakKind::BreakAway);
    assert!(rel(bin.s, (-3.0 - r3) / 2.0) < 1e-10);
    assert!(rel(bin.gain, 7.0 + 4.0 * r3) < 1e-10);
    assert!(rel(baway.s, (-3.0 + r3) / 2.0) < 1e-10);
    assert!(rel(baway.gain, 7.0 - 4.0 * r3) < 1e-10);
    assert!(l.asymptotes.is_none());
    // at the break gains, D + K·N has a double real root there (the root finder's own
    // multiplicity decision, an independent check)
    for b in &l.break_points {
        let q = &poly(&[1.0, 1.0, 0.0]) + &poly(&[1.0, 5.0, 6.0]).scale(b.gain);
        let r = q.roots().unwrap();
        assert_eq!(r.len(), 1, "{r:?}");
        assert_eq!(r[0].multiplicity, 2);
        assert!(rel(r[0].value.re, b.s) < 1e-10);
    }
}

#[test]
fn departure_and_arrival_angles() {
    // L = (s + 2)/(s(s² + 2s + 5)): at p = −1 + 2j, θ = 180° + ∠(p + 2) − ∠p − ∠(p − p̄)
    // = 180° + atan 2 − (180° − atan 2) − 90° ≡ atan(3/4) = 36.8699° (mod 360°).
    let l = locus(&[1.0, 2.0], &[1.0, 2.0, 5.0, 0.0], false);
    let d = l.departures.iter().find(|a| a.at.im > 1.0).unwrap();
    assert!((d.angles_deg[0] - 0.75f64.atan().to_degrees()).abs() < 1e-10);
    let z = &l.arrivals[0];
    assert!(z.angles_deg[0].abs() < 1e-12, "{:?}", z.angles_deg);
    // L = (s² + 2s + 2)/(s(s + 1)): arrival at z = −1 + j: ψ = ∠(z − z̄) − ∠z − ∠(z + 1)
    // = 90° − 135° − 90° = −135°; θ = 180° + 135° = 315° ≡ −45°.
    let l = locus(&[1.0, 2.0, 2.0], &[1.0, 1.0, 0.0], false);
    let a = l.arrivals.iter().find(|a| a.at.im > 0.5).unwrap();
    assert!((a.angles_deg[0] + 45.0).abs() < 1e-10, "{:?}", a.angles_deg);
}

#[test]
fn the_sign_of_the_gain_of_g_flips_the_locus() {
    // L = (1 − s)/((s + 1)(s + 2)): k = −1, so K > 0 is the 0° locus. D + K·N =
    // s² + (3 − K)s + 2 + K: crossing at ω = √5 for K = 3 (stable for 0 < K < 3).
    let l = locus(&[-1.0, 1.0], &[1.0, 3.0, 2.0], false);
    assert_eq!(l.crossings.len(), 1);
    assert!(rel(l.crossings[0].omega, 5f64.sqrt()) < 1e-10);
    assert!(rel(l.crossings[0].gain, 3.0) < 1e-10);
    assert_eq!(l.asymptotes.as_ref().unwrap().angles_deg, vec![0.0]);
}

#[test]
fn cancelled_roots_are_fixed_poles() {
    // L = (s + 1)/(s(s + 1)): −1 is a closed-loop pole for every K.
    let l = locus(&[1.0, 1.0], &[1.0, 1.0, 0.0], false);
    assert_eq!(l.fixed.len(), 1);
    assert!(rel(l.fixed[0].value.re, -1.0) < 1e-15);
    let on = l
        .branches
        .paths
        .iter()
        .filter(|p| p.iter().all(|z| (z + 1.0).norm() < 1e-12))
        .count();
    assert_eq!(on, 1);
}

/// Every traced point is a root of D + K·N to rounding, the branches start at the poles and
/// reach the zeros or infinity, and no step jumps (except through the budget's last step).
fn check_branches(num: &[f64], den: &[f64], negative: bool) {
    let (n, d) = (poly(num), poly(den));
    let l = locus(num, den, negative);
    let b = &l.branches;
    assert_eq!(b.gains[0], 0.0);
    assert!(b.gains.windows(2).all(|w| w[1].abs() > w[0].abs()));
    for (i, k) in b.gains.iter().enumerate() {
        for p in &b.paths {
            let s = p[i];
            let scale = d.eval_abs(s.norm()) + k.abs() * n.eval_abs(s.norm());
            let res = (d.eval_complex(s) + n.eval_complex(s) * *k).norm();
            assert!(res <= 1e-9 * scale, "K = {k}, s = {s}: {res} vs {scale}");
        }
    }
    // each pole starts as many branches as its multiplicity
    for r in &l.poles {
        let starting = b
            .paths
            .iter()
            .filter(|p| (p[0] - r.value).norm() < 1e-6)
            .count();
        assert!(starting >= r.multiplicity, "{r:?}");
    }
    // branches end at a zero or far out
    let scale = l
        .poles
        .iter()
        .chain(&l.zeros)
        .map(|r| r.value.norm())
        .fold(1.0, f64::max);
    for p in &b.paths {
        let end = p[p.len() - 1];
        let at_zero = l
            .zeros
            .iter()
            .any(|z| (end - z.value).norm() < 0.05 * scale);
        assert!(at_zero || end.norm() > 4.0 * scale, "branch ends at {end}");
    }
}

#[test]
fn traced_branches_solve_the_characteristic_equation() {
    check_branches(&[1.0], &[1.0, 3.0, 2.0, 0.0], false);
    check_branches(&[1.0], &[1.0, 3.0, 2.0, 0.0], true);
    check_branches(&[1.0, 5.0, 6.0], &[1.0, 1.0, 0.0], false);
    check_branches(&[1.0, 2.0], &[1.0, 2.0, 5.0, 0.0], false);
    check_branches(&[1.0], &[1.0, 0.0, 0.0], false);
    // (s + 1)⁴ against (s + 3): four branches from one pole
    check_branches(&[1.0, 3.0], &[1.0, 4.0, 6.0, 4.0, 1.0], false);
    // biproper with a branch escaping through infinity at K = 2: (2 − s)... D + K·N with
    // N = −0.5 s + 1, D = s + 1: leading 1 − K/2 vanishes at K = 2
    let l = locus(&[-0.5, 1.0], &[1.0, 1.0], false);
    assert!(rel(l.escape_gain.unwrap(), 2.0) < 1e-15);
    assert!(l.asymptotes.is_none());
}

#[test]
fn crossings_are_the_ends_of_the_stable_gain_set() {
    // For random plants, every finite end of the Routh stable-gain intervals is a crossing
    // gain (either locus) or the gain at which the degree drops.
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut ends_checked = 0;
    for _ in 0..300 {
        let nd = 2 + (next().abs() * 4.0) as usize;
        let nn = (next().abs() * nd as f64) as usize;
        let den: Vec<f64> = std::iter::once(1.0)
            .chain((0..nd).map(|_| 3.0 * next()))
            .collect();
        let num: Vec<f64> = (0..=nn).map(|_| 2.0 * next()).collect();
        let (n, d) = (poly(&num), poly(&den));
        if n.is_zero() {
            continue;
        }
        let cross: Vec<f64> = axis_crossings(&n, &d)
            .unwrap()
            .iter()
            .map(|c| c.1)
            .collect();
        for (lo, hi) in stable_gains(&n, &d).unwrap() {
            for k in [lo, hi] {
                if !k.is_finite() {
                    continue;
                }
                let drop = n.degree() == d.degree() && rel(k, -d.leading() / n.leading()) < 1e-9;
                assert!(
                    drop || cross
                        .iter()
                        .any(|c| (c - k).abs() <= 1e-9 * k.abs().max(1.0)),
                    "end {k} of {num:?}/{den:?} not among {cross:?}"
                );
                ends_checked += 1;
            }
        }
    }
    assert!(ends_checked > 50, "{ends_checked}");
}

#[test]
fn fixed_gains_are_traced_in_order() {
    // 1/(s(s + 2)): s² + 2s + K; the roots at K = 1 + c² are −1 ± jc.
    let gains: Vec<f64> = (0..1000).map(|i| i as f64 * 0.01).collect();
    let b = trace_at_gains(&poly(&[1.0]), &poly(&[1.0, 2.0, 0.0]), &gains).unwrap();
    for (i, k) in gains.iter().enumerate() {
        if *k > 1.0 {
            let c = (k - 1.0).sqrt();
            let mut got: Vec<Complex64> = b.paths.iter().map(|p| p[i]).collect();
            got.sort_by(|a, b| a.im.total_cmp(&b.im));
            assert!((got[0] - Complex64::new(-1.0, -c)).norm() < 1e-12);
            assert!((got[1] - Complex64::new(-1.0, c)).norm() < 1e-12);
        }
    }
    // continuity: one branch stays in the upper half plane once it has left the axis
    let upper: Vec<usize> = (0..2).filter(|&j| b.paths[j][999].im > 0.0).collect();
    assert_eq!(upper.len(), 1);
    assert!(b.paths[upper[0]][101..].iter().all(|z| z.im > 0.0));
}

#[test]
fn bad_loops_are_refused() {
    let opts = RootLocusOptions::default();
    assert!(root_locus(&Poly::zero(), &poly(&[1.0, 1.0]), &opts).is_err());
    assert!(root_locus(&poly(&[1.0, 0.0, 0.0]), &poly(&[1.0, 1.0]), &opts).is_err());
    assert!(root_locus(&poly(&[2.0]), &poly(&[3.0]), &opts).is_err());
}

#[test]
fn cli_text_json_and_png() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("rlocus_cli");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("l.png");
    let out = ltikit(&[
        "rlocus",
        "--den",
        "1 3 2 0",
        "--gain",
        "6",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for needle in [
        "Asymptotes: 3 from σ = -1 at -60°, 60°, 180°",
        "σ = -0.4226497308 (break-away, 2 branches) at K = 0.3849001795",
        "s = ±1.414213562j at K = 6",
        "Closed loop stable for: 0 < K < 6",
        // at K = 6: s³ + 3s² + 2s + 6 = (s + 3)(s² + 2)
        "Closed-loop poles at K = 6: ±1.41421j, -3",
    ] {
        assert!(text.contains(needle), "{needle}\n{text}");
    }
    let b = std::fs::read(&png).unwrap();
    assert!(b.len() > 1000 && b.starts_with(b"\x89PNG\r\n\x1a\n"));
    // JSON: the features, the stable gains, the branches as [re, im] per gain
    let out = ltikit(&["rlocus", "--den", "1 3 2 0", "--json", "--gain", "1"]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let gains = v["gains"].as_array().unwrap();
    let branches = v["branches"].as_array().unwrap();
    assert_eq!(branches.len(), 3);
    assert!(
        branches
            .iter()
            .all(|b| b.as_array().unwrap().len() == gains.len())
    );
    assert_eq!(v["stable_gains"][0][0].as_f64(), Some(0.0));
    assert!(rel(v["stable_gains"][0][1].as_f64().unwrap(), 6.0) < 1e-10);
    assert_eq!(v["at_gain"]["poles"].as_array().unwrap().len(), 3);
    assert_eq!(v["break_points"][0]["kind"], "break_away");
    // a controller: the locus of 1 + K·C·G
    let out = ltikit(&[
        "rlocus",
        "--den",
        "1 1 0",
        "--controller",
        "pd:kp=1,kd=0.5,tf=0",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // L = (0.5 s + 1)/(s² + s): one zero at −2
    assert!(rel(v["zeros"][0]["value"][0].as_f64().unwrap(), -2.0) < 1e-12);
}

#[test]
fn cli_errors_are_one_line_and_leave_no_file() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("rlocus_bad");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("bad.png");
    let cases: &[(&[&str], &str)] = &[
        (&["--num", "0", "--den", "1 2"], "nonzero numerator"),
        (&["--num", "1 0 0", "--den", "1 2"], "proper"),
        (&["--num", "2", "--den", "3"], "degree ≥ 1"),
        (&["--den", "1 3 2 0", "--gain", "nan"], "finite"),
        (&["--den", "1 3 2 0", "--max-gains", "3"], "--max-gains"),
        (&["--den", "1 3 2 0", "--closed-loop"], "do not apply"),
        // deg N = deg D: at K = 2 the leading term of (s + 1) + K·(−0.5 s + 1) vanishes
        (
            &["--num", "-0.5 1", "--den", "1 1", "--gain", "2"],
            "infinity",
        ),
    ];
    for (args, needle) in cases {
        let mut all = vec!["rlocus"];
        all.extend_from_slice(args);
        all.extend_from_slice(&["-o", png.to_str().unwrap()]);
        let out = ltikit(&all);
        assert_eq!(out.status.code(), Some(1), "{all:?}");
        assert!(out.stdout.is_empty());
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(
            err.starts_with("error:") && err.contains(needle),
            "{all:?}: {err}"
        );
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(!png.exists(), "{all:?} left a file");
    }
}

#[test]
fn extreme_gains_do_not_stall_the_trace() {
    // Found by the CLI fuzzer: with K·N tiny next to D the first gains are ~1e-295, the
    // geometric mean ka·kb underflowed to 0 and the step subdivision never ended. Now the
    // trace finishes within its gain budget.
    for (num, den) in [
        (vec![1.1859678500658364e293], vec![-0.026768, 0.0, -1.0]),
        (
            vec![1.0, -1.013351772014754e-192],
            vec![-3.203955378494507e-295, -0.273849],
        ),
        (vec![3.990219], vec![4.57e-321, -3.4038723315191824e-296]),
    ] {
        let opts = RootLocusOptions {
            negative: false,
            max_gains: 500,
        };
        // finishing is the point: every case traces (299, 461 and 499 gains when written)
        let l = root_locus(&poly(&num), &poly(&den), &opts)
            .unwrap_or_else(|e| panic!("{num:?} / {den:?}: {e}"));
        assert!(
            (2..=500).contains(&l.branches.gains.len()),
            "{}",
            l.branches.gains.len()
        );
    }
}
