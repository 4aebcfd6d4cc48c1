//! The textbook plants (DESIGN §4) and the shipped plant files.

use ltikit::TransferFunction;
use ltikit::analysis::{DampingClass, second_order};
use ltikit::lti::{Plant, build_plant, plant_specs};
use std::path::Path;

#[test]
fn shipped_plant_files_parse_and_build() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/plants");
    let mut n = 0;
    for e in std::fs::read_dir(&dir).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "toml") {
            let g = Plant::from_file(&p).unwrap().tf().unwrap().clone();
            assert!(g.order() >= 1, "{}", p.display());
            n += 1;
        }
    }
    assert!(n >= 6, "expected the six textbook plant files, found {n}");
    // Every textbook model has a file.
    for spec in plant_specs().iter().filter(|s| s.name != "second-order") {
        assert!(
            dir.join(format!("{}.toml", spec.name)).exists(),
            "no plant file for {}",
            spec.name
        );
    }
}

fn so(g: &TransferFunction) -> ltikit::analysis::SecondOrder {
    second_order(g.den(), &g.poles().unwrap()).unwrap()
}

#[test]
fn rlc_natural_frequency_and_damping() {
    // Exercise 2.6: ωn = 1/√(LC), ζ = (R/2)√(C/L).
    let (r, l, c) = (10.0, 0.1, 1e-3);
    let (g, _) = build_plant("rlc", &[("R".into(), r), ("L".into(), l), ("C".into(), c)]).unwrap();
    let s = so(&g);
    assert!((s.wn.unwrap() - 1.0 / f64::sqrt(l * c)).abs() < 1e-12);
    assert!((s.zeta.unwrap() - r / 2.0 * f64::sqrt(c / l)).abs() < 1e-12);
    assert_eq!(s.class, DampingClass::Underdamped);
}

#[test]
fn spring_mass_damper_matches_eq_3_20() {
    // ωn² = K/M, 2ζωn = C/M (seed eq. 3.20).
    let (m, c, k) = (2.0, 1.2, 8.0);
    let (g, _) = build_plant(
        "spring-mass-damper",
        &[("M".into(), m), ("C".into(), c), ("K".into(), k)],
    )
    .unwrap();
    let s = so(&g);
    let wn = f64::sqrt(k / m);
    assert!((s.wn.unwrap() - wn).abs() < 1e-14);
    assert!((s.zeta.unwrap() - c / (2.0 * m * wn)).abs() < 1e-14);
    // Critical damping C = 2√(KM) is recognised exactly.
    let (g, _) = build_plant(
        "spring-mass-damper",
        &[
            ("M".into(), m),
            ("C".into(), 2.0 * f64::sqrt(k * m)),
            ("K".into(), k),
        ],
    )
    .unwrap();
    assert_eq!(so(&g).class, DampingClass::CriticallyDamped);
}

#[test]
fn tank_time_constant() {
    // A h' + r h = q: pole −r/A (seed eq. 3.6, p1 = r/A).
    let (g, _) = build_plant("tank", &[("A".into(), 3.0), ("r".into(), 1.5)]).unwrap();
    let p = g.poles().unwrap();
    assert_eq!(p.len(), 1);
    assert!((p[0].value.re + 0.5).abs() < 1e-15);
}

#[test]
fn two_dof_is_real_negative_at_the_first_mass_frequency() {
    // At ω² = K1/M1 the first mass's spring force cancels its inertia and
    // G(jω) = −M1/(K1·M2) exactly (from Δ(s) = (K2 + Cs)(−M2ω²) there): phase −180°.
    let (m1, m2, k1, k2, c) = (1.5, 2.0, 3.0, 1.5, 0.3);
    let (g, _) = build_plant(
        "two-dof",
        &[
            ("M1".into(), m1),
            ("M2".into(), m2),
            ("K1".into(), k1),
            ("K2".into(), k2),
            ("C".into(), c),
        ],
    )
    .unwrap();
    let w = f64::sqrt(k1 / m1);
    let v = g.eval(num_complex::Complex64::new(0.0, w));
    assert!(
        (v.re + m1 / (k1 * m2)).abs() < 1e-14 && v.im.abs() < 1e-14,
        "{v}"
    );
    let m = g.margins().unwrap();
    let gm = m
        .phase_crossings
        .iter()
        .find(|pc| (pc.w - w).abs() < 1e-12)
        .expect("a phase crossing at sqrt(K1/M1)");
    assert!((gm.gain_margin - k1 * m2 / m1).abs() < 1e-12);
}
