//! Discrete-time stability against the unit circle: the Jury table and the exact unit-circle
//! counts (textbook examples, each with the factorisation that proves its counts), the exact
//! decision of the factored core for plants typed as text, the stabilising gains of sampled
//! loops (derived by hand with Jury's conditions), the root locus in z against them, and the
//! CLI (`jury`, `routh --dt`, `rlocus --dt`, `pzmap --dt`).

mod common;

use common::{discrete_text, json, ltikit, poly, stdout};
use ltikit::analysis::jury::{circle_crossings, discrete_stable_gains_exact};
use ltikit::analysis::rlocus::{RootLocusOptions, root_locus_z};
use ltikit::analysis::{StabilityClass, StructurePath, discrete_stable_gains, jury, jury_exact};
use ltikit::poly::exact::ExactPoly;

fn exact(t: &[&str]) -> ExactPoly {
    ExactPoly::parse_descending(t).unwrap()
}

fn counts(t: &[&str]) -> (usize, usize, usize) {
    let c = exact(t).unit_circle_counts().unwrap();
    (c.inside, c.on, c.outside)
}

#[test]
fn textbook_jury_examples() {
    // Ogata, Discrete-Time Control Systems (2nd ed.), §4-3, Jury stability test, Example 4-3:
    // z⁴ − 1.2z³ + 0.07z² + 0.3z − 0.08 = (z² − 0.25)(z² − 1.2z + 0.32), roots ±0.5, 0.4,
    // 0.8: stable.
    let t = jury(&poly(&[1.0, -1.2, 0.07, 0.3, -0.08])).unwrap();
    assert_eq!((t.inside, t.on, t.outside), (4, 0, 0));
    assert!(t.singular_at.is_none() && t.stable());
    assert_eq!(counts(&["1", "-1.2", "0.07", "0.3", "-0.08"]), (4, 0, 0));
    // Ogata, ibid., Example 4-4: z³ − 1.1z² − 0.1z + 0.2 = (z − 1)(z − 0.5)(z + 0.4): a root
    // on the unit circle (critically stable). The table is singular; the counts come from the
    // bilinear map.
    let t = jury(&poly(&[1.0, -1.1, -0.1, 0.2])).unwrap();
    assert_eq!((t.inside, t.on, t.outside), (2, 1, 0));
    assert!(!t.stable());
    assert_eq!(counts(&["1", "-1.1", "-0.1", "0.2"]), (2, 1, 0));
    // Åström & Wittenmark, Computer-Controlled Systems (3rd ed.), §3.2, Example 3.3: the
    // second-order A(z) = z² + a₁z + a₂ is stable iff a₂ < 1, a₂ > −1 + a₁ and a₂ > −1 − a₁
    // (the stability triangle). On a grid of points off its edges:
    for i in -12..=12 {
        for j in -12..=12 {
            let (a1, a2) = (0.25 * f64::from(i) + 0.05, 0.125 * f64::from(j) + 0.03);
            let inside = a2 < 1.0 && a2 > -1.0 + a1 && a2 > -1.0 - a1;
            let t = jury(&poly(&[1.0, a1, a2])).unwrap();
            assert_eq!(t.stable(), inside, "a1 = {a1}, a2 = {a2}");
            assert_eq!(t.exact.unwrap().on, 0);
        }
    }
}

#[test]
fn simple_and_near_circle_counts_are_exact() {
    assert_eq!(counts(&["1", "0", "1"]), (0, 2, 0)); // z² + 1: ±j
    assert_eq!(counts(&["1", "-2", "1"]), (0, 2, 0)); // (z − 1)²
    assert_eq!(counts(&["1", "1"]), (0, 1, 0)); // z + 1
    assert_eq!(counts(&["2", "-1"]), (1, 0, 0)); // 2z − 1: z = 0.5
    assert_eq!(counts(&["1", "-2"]), (0, 0, 1)); // z − 2
    // z − (1 ± 1e-12) typed as text: decided exactly, although the f64 table sees 1 ± 1e-12
    assert_eq!(counts(&["1", "-1.000000000001"]), (0, 0, 1));
    assert_eq!(counts(&["1", "-0.999999999999"]), (1, 0, 0));
    // 1 − 1e-30 is the double 1: the f64 coefficients put the root on the circle, the text
    // inside it
    let t = jury_exact(&exact(&["1", "-0.999999999999999999999999999999"])).unwrap();
    assert_eq!(t.on, 1); // the table on the rounded coefficient
    assert_eq!(t.exact.unwrap().inside, 1);
    assert!(t.stable());
    // e^(±jπ/3) = 0.5 ± j√3/2: z² − z + 1, on the circle; (z² − z + 1)² repeated
    assert_eq!(counts(&["1", "-1", "1"]), (0, 2, 0));
    assert_eq!(counts(&["1", "-2", "3", "-2", "1"]), (0, 4, 0));
    // pairs z, 1/z̄ off the circle (a singular Jury table): (z − 2)(z − 0.5) = z² − 2.5z + 1
    let t = jury(&poly(&[1.0, -2.5, 1.0])).unwrap();
    assert!(t.singular_at.is_some());
    assert_eq!((t.inside, t.on, t.outside), (1, 0, 1));
    assert_eq!(counts(&["1", "-2.5", "1"]), (1, 0, 1));
}

#[test]
fn the_factored_core_decides_the_circle_exactly() {
    let st = |num: &str, den: &str| {
        let f = discrete_text(num, den, 0.1);
        assert_eq!(f.structure_path(), StructurePath::Exact, "{den}");
        f.stability()
    };
    let s = st("1", "1 0 1");
    assert_eq!(s.internal, StabilityClass::MarginallyStable);
    assert!(
        s.reason.contains("on the unit circle") && s.reason.ends_with("(decided exactly)"),
        "{}",
        s.reason
    );
    let s = st("1", "1 -1.0000000001");
    assert_eq!(s.internal, StabilityClass::Unstable);
    assert!(
        s.reason
            .contains("outside the unit circle (decided exactly)")
    );
    let s = st("1", "1 -0.999999999999");
    assert_eq!(s.internal, StabilityClass::Stable);
    assert!(s.reason.ends_with("(decided exactly)"));
    let s = st("1", "1 -1.000000000001");
    assert_eq!(s.internal, StabilityClass::Unstable);
    let s = st("1", "1 -2 1");
    assert_eq!(s.internal, StabilityClass::Unstable);
    assert!(
        s.reason.contains("repeated unit-circle poles"),
        "{}",
        s.reason
    );
    // (z − 1)/((z − 1)(z − 0.5)): BIBO stable, the cancelled z = 1 on the circle
    let s = st("1 -1", "1 -1.5 0.5");
    assert!(s.bibo_stable && !s.internally_stable);
    assert_eq!(s.internal, StabilityClass::MarginallyStable);
    // a pole 1e-20 inside beside ±j in one square-free factor: (z − (1 − 1e-20))(z² + 1)
    let s = st("1", "1 -0.99999999999999999999 1 -0.99999999999999999999");
    assert_eq!(s.internal, StabilityClass::MarginallyStable, "{}", s.reason);
}

#[test]
fn stable_gains_against_hand_derivations() {
    // K/((z − 1)(z − 0.5)): z² − 1.5z + 0.5 + K. Jury (n = 2): |a₂| < a₀ → |0.5 + K| < 1,
    // P(1) = K > 0, P(−1) = 3 + K > 0: 0 < K < 0.5 (at K = 0.5 the roots e^(±jθ), cos θ = 0.75).
    let k = discrete_stable_gains_exact(&exact(&["1"]), &exact(&["1", "-1.5", "0.5"])).unwrap();
    assert_eq!(k.len(), 1);
    assert_eq!(k[0].0, 0.0);
    assert!((k[0].1 - 0.5).abs() < 1e-15, "{k:?}");
    // K(z + 0.5)/(z(z − 1)): z² + (K − 1)z + 0.5K. |0.5K| < 1, P(1) = 1.5K > 0,
    // P(−1) = 2 − 0.5K > 0: 0 < K < 2.
    let k = discrete_stable_gains(&poly(&[1.0, 0.5]), &poly(&[1.0, -1.0, 0.0])).unwrap();
    assert_eq!(k.len(), 1);
    assert!(
        k[0].0.abs() < 1e-15 && (k[0].1 - 2.0).abs() < 1e-14,
        "{k:?}"
    );
    // Ogata, Discrete-Time Control Systems, §4-3 (the ZOH equivalent of 1/(s(s + 1)) at T = 1
    // under gain K): z² + (0.3679K − 1.3679)z + 0.3679 + 0.2642K. |0.3679 + 0.2642K| < 1 →
    // −5.1692 < K < 0.6321/0.2642; P(1) = 0.6321K > 0; P(−1) = 2.7358 − 0.1037K > 0: so
    // 0 < K < 0.6321/0.2642 = 2.3925…
    let n = exact(&["0.3679", "0.2642"]);
    let d = exact(&["1", "-1.3679", "0.3679"]);
    let k = discrete_stable_gains_exact(&n, &d).unwrap();
    assert_eq!(k.len(), 1, "{k:?}");
    assert!(k[0].0.abs() < 1e-15);
    assert!((k[0].1 - 0.6321 / 0.2642).abs() < 1e-14, "{k:?}");
    // K/(z − 1)²: |1 + K| < 1 and K > 0 contradict: no stabilising gain.
    assert!(
        discrete_stable_gains(&poly(&[1.0]), &poly(&[1.0, -2.0, 1.0]))
            .unwrap()
            .is_empty()
    );
    // K/(z + 0.5): z + 0.5 + K inside iff |0.5 + K| < 1: −1.5 < K < 0.5 (negative gains too).
    let k = discrete_stable_gains(&poly(&[1.0]), &poly(&[1.0, 0.5])).unwrap();
    assert_eq!(k, vec![(-1.5, 0.5)]);
    // K·z/(z − 0.5), deg N = deg D: (1 + K)z − 0.5, root 0.5/(1 + K), inside iff
    // |1 + K| > 0.5: K < −1.5 or K > −0.5 (K = −1 sends the root through infinity).
    let k = discrete_stable_gains(&poly(&[1.0, 0.0]), &poly(&[1.0, -0.5])).unwrap();
    assert_eq!(k, vec![(f64::NEG_INFINITY, -1.5), (-0.5, f64::INFINITY)]);
}

#[test]
fn locus_crossings_are_the_jury_boundaries() {
    // Ogata's loop above: the locus leaves the unit circle where the stable set ends.
    let n = poly(&[0.3679, 0.2642]);
    let d = poly(&[1.0, -1.3679, 0.3679]);
    let l = root_locus_z(&n, &d, 1.0, &RootLocusOptions::default()).unwrap();
    let k = discrete_stable_gains(&n, &d).unwrap();
    // two crossings: e^(±jθ) at the end of the stable set, and z = −1 where
    // P(−1) = 2.7358 − 0.1037K vanishes (hand derivation above)
    assert_eq!(l.crossings.len(), 2, "{:?}", l.crossings);
    let m1 = &l.crossings[1];
    assert_eq!(m1.z.unwrap(), common::c(-1.0, 0.0));
    assert!((m1.gain - 2.7358 / 0.1037).abs() < 1e-12 * m1.gain);
    let c = &l.crossings[0];
    assert!((c.gain - k[0].1).abs() < 1e-13 * k[0].1);
    let z = c.z.unwrap();
    assert!((z.norm() - 1.0).abs() < 1e-15);
    // the closed-loop poles at that gain are on the circle
    let q = &d + &n.scale(c.gain);
    for r in q.roots().unwrap() {
        assert!((r.value.norm() - 1.0).abs() < 1e-7, "{}", r.value);
    }
    // For a family of loops, every finite end of the stable-gain set is a crossing gain of
    // the locus of its sign (or the escape gain through infinity).
    let dens: [&[f64]; 5] = [
        &[1.0, -1.5, 0.5],
        &[1.0, -1.0, 0.0],
        &[1.0, -0.2, -0.35, 0.1],
        &[1.0, -2.2, 1.57, -0.36],
        &[1.0, 0.3, -0.4, 0.1, 0.05],
    ];
    let nums: [&[f64]; 3] = [&[1.0], &[1.0, 0.5], &[1.0, -0.9, 0.2]];
    for den in dens {
        for num in nums {
            let (n, d) = (poly(num), poly(den));
            if n.degree() > d.degree() {
                continue;
            }
            let mut gains: Vec<f64> = circle_crossings(&n, &d)
                .unwrap()
                .iter()
                .map(|c| c.1)
                .collect();
            if n.degree() == d.degree() {
                gains.push(-d.leading() / n.leading());
            }
            for (lo, hi) in discrete_stable_gains(&n, &d).unwrap() {
                for e in [lo, hi].into_iter().filter(|x| x.is_finite()) {
                    assert!(
                        gains
                            .iter()
                            .any(|g| (g - e).abs() <= 1e-9 * e.abs().max(1.0)),
                        "{num:?}/{den:?}: end {e} not among {gains:?}"
                    );
                }
                // inside the interval every closed-loop root is inside the circle
                let mid = if lo.is_finite() && hi.is_finite() {
                    0.5 * (lo + hi)
                } else if lo.is_finite() {
                    lo + 1.0
                } else {
                    hi - 1.0
                };
                let q = &d + &n.scale(mid);
                for r in q.roots().unwrap() {
                    assert!(r.value.norm() < 1.0, "{num:?}/{den:?} at K = {mid}");
                }
            }
        }
    }
}

#[test]
fn cli_jury_and_routh_on_a_discrete_plant() {
    let out = stdout(&[
        "jury",
        "--num",
        "1",
        "--den",
        "1 -1.5 0.5",
        "--dt",
        "0.1",
        "--gain-range",
    ]);
    assert!(out.contains("Jury table"), "{out}");
    assert!(
        out.contains("Roots: 1 strictly inside the unit circle, 1 on it, 0 outside"),
        "{out}"
    );
    assert!(out.contains("0 < K < 0.5"), "{out}");
    // routh on a discrete plant prints the same Jury report
    let r = stdout(&[
        "routh",
        "--num",
        "1",
        "--den",
        "1 -1.5 0.5",
        "--dt",
        "0.1",
        "--gain-range",
    ]);
    assert_eq!(r, out);
    // --gain K: the table of D + K·N; JSON with the exact counts
    let v = json(&[
        "jury",
        "--num",
        "1",
        "--den",
        "1 -1.5 0.5",
        "--dt",
        "0.1",
        "--gain",
        "0.25",
        "--json",
    ]);
    assert_eq!(v["dt"], 0.1);
    assert_eq!(v["polynomial"], serde_json::json!([1.0, -1.5, 0.75]));
    assert_eq!(v["exact"]["inside"], 2);
    assert_eq!(v["inside"], 2);
    assert!(v["singular_at"].is_null());
    // exact near the circle: the table's f64 cannot see 1 − 1e-30, the text can
    let v = json(&[
        "jury",
        "--den",
        "1 -0.999999999999999999999999999999",
        "--dt",
        "1",
        "--json",
    ]);
    assert_eq!(v["exact"]["inside"], 1);
    assert_eq!(v["on"], 1);
    // a continuous plant is pointed to routh
    let e = ltikit(&["jury", "--den", "1 2 3"]);
    assert_eq!(e.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&e.stderr).contains("ltikit routh"));
}

#[test]
fn cli_rlocus_and_pzmap_on_a_discrete_plant() {
    let args = ["rlocus", "--num", "1 0.5", "--den", "1 -1 0", "--dt", "0.1"];
    let out = stdout(&args);
    assert!(out.contains("Unit-circle crossings:"), "{out}");
    assert!(out.contains("z = -0.5 ± 0.8660254038j"), "{out}");
    assert!(
        out.contains("0 < K < 2 (every root strictly inside the unit circle"),
        "{out}"
    );
    let mut a = args.to_vec();
    a.push("--json");
    let v = json(&a);
    assert_eq!(v["dt"], 0.1);
    let c = v["crossings"].as_array().unwrap();
    assert_eq!(c.len(), 2);
    assert!((c[0]["gain"].as_f64().unwrap() - 2.0).abs() < 1e-13);
    assert!((c[0]["z"][0].as_f64().unwrap() + 0.5).abs() < 1e-15);
    assert_eq!(c[1]["z"], serde_json::json!([-1.0, 0.0]));
    assert!((c[1]["gain"].as_f64().unwrap() - 4.0).abs() < 1e-13);
    let s = &v["stable_gains"][0];
    assert!(s[0].as_f64().unwrap().abs() < 1e-15 && (s[1].as_f64().unwrap() - 2.0).abs() < 1e-14);
    // the continuous locus keeps its JSON (no "z" in a crossing)
    let v = json(&["rlocus", "--den", "1 3 2 0", "--json"]);
    assert!(v["crossings"][0].get("z").is_none());
    // the pictures
    let dir = std::env::temp_dir().join(format!("ltikit-jury-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (cmd, extra) in [("rlocus", vec!["--gain", "2"]), ("pzmap", vec![])] {
        let png = dir.join(format!("{cmd}.png"));
        let png_s = png.to_str().unwrap();
        let mut a = vec![
            cmd, "--num", "1 0.5", "--den", "1 -1 0", "--dt", "0.1", "-o", png_s,
        ];
        a.extend(extra);
        stdout(&a);
        let bytes = std::fs::read(&png).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    }
}
