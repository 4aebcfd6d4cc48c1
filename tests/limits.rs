//! The limits table of docs/ARCHITECTURE.md ("Robustness: the limits") agrees with the
//! constants in the code: each row naming a constant states its value.

/// The documentation's row that names `constant` (the first table row containing it).
fn row(doc: &str, constant: &str) -> String {
    doc.lines()
        .find(|l| l.starts_with('|') && l.contains(constant))
        .unwrap_or_else(|| panic!("no row for {constant}"))
        .to_string()
}

/// 10000000 as "10 000 000" (thin groups of three, as the table writes numbers ≥ 10 000).
fn grouped(v: u64) -> String {
    let s = v.to_string();
    if v < 10_000 {
        return s;
    }
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i) % 3 == 0 {
            out.push(' ');
        }
        out.push(c);
    }
    out
}

#[test]
fn the_documented_limits_are_the_code_s() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/ARCHITECTURE.md"))
        .unwrap();
    let section = doc
        .split("## Robustness: the limits")
        .nth(1)
        .expect("the Robustness section");
    let cases: Vec<(&str, u64)> = vec![
        ("poly::MAX_ORDER", ltikit::MAX_ORDER as u64),
        (
            "analysis::MAX_FACTORED_ORDER",
            ltikit::analysis::MAX_FACTORED_ORDER as u64,
        ),
        ("lti::MAX_STATES", ltikit::lti::MAX_STATES as u64),
        (
            "analysis::ss::MAX_ANALYSIS_STATES",
            ltikit::analysis::ss::MAX_ANALYSIS_STATES as u64,
        ),
        (
            "lti::lattice::MAX_PARTICLES",
            ltikit::lti::lattice::MAX_PARTICLES as u64,
        ),
        (
            "analysis::grid::MAX_POINTS",
            ltikit::analysis::grid::MAX_POINTS as u64,
        ),
        ("plot::MAX_TEXT_CHARS", ltikit::plot::MAX_TEXT_CHARS as u64),
        ("plot::MAX_SIDE", ltikit::plot::MAX_SIDE as u64),
        (
            "numeric::balance::MAX_BALANCE_SWEEPS",
            ltikit::numeric::balance::MAX_BALANCE_SWEEPS as u64,
        ),
        (
            "numeric::expm::MAX_SQUARINGS",
            ltikit::numeric::expm::MAX_SQUARINGS as u64,
        ),
        (
            "numeric::linalg::francis::MAX_ITER_PER_ROW",
            ltikit::numeric::linalg::francis::MAX_ITER_PER_ROW as u64,
        ),
        (
            "numeric::lstsq::MAX_SVD_ITER",
            ltikit::numeric::lstsq::MAX_SVD_ITER as u64,
        ),
    ];
    for (name, value) in cases {
        let r = row(section, name);
        assert!(r.contains(&grouped(value)), "{name} = {value}: {r}");
    }
    assert!(row(section, "plot::MAX_PIXELS").contains(&grouped(ltikit::plot::MAX_PIXELS)));
    assert_eq!(ltikit::lti::plant::MAX_RECORD_BYTES, 1 << 20);
    assert!(row(section, "MAX_RECORD_BYTES").contains("1 MiB"));
    let exact = row(section, "MAX_EXACT_DEGREE");
    assert!(exact.contains(&format!(
        "{}, {}, {}, {}, {}",
        ltikit::poly::exact::MAX_DIGITS,
        ltikit::poly::exact::MAX_EXPONENT,
        ltikit::poly::exact::MAX_EXACT_DEGREE,
        ltikit::poly::exact::MAX_EXACT_BITS,
        grouped(ltikit::poly::exact::MAX_EXACT_WORK as u64)
    )));
}
