//! The limits table of docs/ARCHITECTURE.md ("Robustness: the limits") agrees with the
//! constants in the code: each row naming a constant states its value.

/// The documentation's row that names `constant` (the first table row containing it).
fn row(doc: &str, constant: &str) -> String {
    doc.lines()
        .find(|l| l.starts_with('|') && l.contains(constant))
        .unwrap_or_else(|| panic!("no row for {constant}"))
        .to_string()
}

#[test]
fn the_documented_limits_are_the_code_s() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/ARCHITECTURE.md"))
        .unwrap();
    let section = doc
        .split("## Robustness: the limits")
        .nth(1)
        .expect("the Robustness section");
    // Every limit of the one table has a row naming its constant and its value.
    for l in ltikit::limits::LIMITS {
        let r = section
            .lines()
            .find(|line| {
                line.starts_with("| `")
                    && line
                        .split('|')
                        .nth(1)
                        .is_some_and(|c| c.contains(&format!("`{}`", l.name)))
            })
            .unwrap_or_else(|| panic!("no row for {}", l.name));
        let value = match l.name {
            "MAX_INPUT_BYTES" => "64 MiB".to_string(),
            "MAX_RECORD_BYTES" => "1 MiB".to_string(),
            _ => ltikit::limits::grouped(l.max),
        };
        assert!(r.contains(&value), "{} = {}: {r}", l.name, l.max);
    }
    assert_eq!(ltikit::limits::MAX_INPUT_BYTES, 64 << 20);
    assert_eq!(ltikit::limits::MAX_RECORD_BYTES, 1 << 20);
    // The modules' names are the table's.
    assert_eq!(ltikit::MAX_ORDER, ltikit::limits::MAX_ORDER);
    assert_eq!(
        ltikit::analysis::grid::MAX_POINTS,
        ltikit::limits::MAX_POINTS
    );
    assert_eq!(ltikit::lti::MAX_STATES, ltikit::limits::MAX_STATES);
    assert_eq!(
        ltikit::plot::MAX_HEATMAP_CELLS,
        ltikit::limits::MAX_HEATMAP_CELLS
    );
    assert_eq!(ltikit::plot::MAX_TEXT_CHARS, ltikit::limits::MAX_TEXT_CHARS);
    // The caps inside the algorithms.
    let cases: Vec<(&str, u64)> = vec![
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
        (
            "analysis::delay::MAX_DELAY_EVENTS",
            ltikit::analysis::delay::MAX_DELAY_EVENTS as u64,
        ),
    ];
    for (name, value) in cases {
        let r = row(section, name);
        assert!(
            r.contains(&ltikit::limits::grouped(value)),
            "{name} = {value}: {r}"
        );
    }
    let exact = row(section, "MAX_EXACT_DEGREE");
    assert!(exact.contains(&format!(
        "{}, {}, {}",
        ltikit::poly::exact::MAX_EXACT_DEGREE,
        ltikit::poly::exact::MAX_EXACT_BITS,
        ltikit::limits::grouped(ltikit::poly::exact::MAX_EXACT_WORK as u64)
    )));
}
