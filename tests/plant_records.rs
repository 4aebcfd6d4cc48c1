//! Plant-file and batch-line errors (issue 25: "plant-file errors give no line and serde
//! jargon: data did not match any variant of untagged enum CoeffList"): every kind of bad
//! record — wrong type, unknown key, bad number, missing key, no plant — names the file, the
//! line and column and the key, in plain words. The expected positions are counted by hand
//! from the texts below (1-based, in characters).

use ltikit::lti::{Plant, PlantFile};

/// The error of plant file `text` (written to a temporary file named `name`).
fn file_error(name: &str, text: &str) -> String {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("plant_records");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let e = Plant::from_file(&path).unwrap_err().to_string();
    let shown = path.display().to_string();
    e.strip_prefix(&shown)
        .map(|r| format!("{name}{r}"))
        .unwrap_or(e)
}

#[test]
fn every_kind_of_bad_plant_file() {
    let cases = [
        // wrong type of a list
        (
            "name = \"x\"\nden = true\n",
            "p.toml, line 2, column 7: `den` must be a list of numbers or a string of numbers (found true)",
        ),
        // a bad entry of a list
        (
            "den = [1, \"a\"]\n",
            "p.toml, line 1, column 7: `den` must be a list of numbers or a string of numbers (entry 2 is the string \"a\")",
        ),
        // a bad number in a string
        (
            "name = \"x\"\nden = \"1 2 x\"\n",
            "p.toml, line 2, column 1: `den`: 'x' is not a number",
        ),
        // wrong type of a scalar
        (
            "name = 3\nden = [1]\n",
            "p.toml, line 1, column 8: `name` must be a string (in quotes) (found the number 3)",
        ),
        // a parameter that is not a number
        (
            "model = \"tank\"\n[params]\nA = \"x\"\n",
            "p.toml, line 3, column 5: `params.A` must be a number (found the string \"x\")",
        ),
        // an unknown parameter, placed at its key
        (
            "model = \"tank\"\n[params]\nQ = 3\n",
            "p.toml, line 3, column 1: model 'tank' has no parameter 'Q' (parameters: A, r)",
        ),
        // a missing key
        (
            "den = [1, 1]\n[controller]\nkp = 1\n",
            "p.toml, line 2, column 1: [controller]: the key `kind` is missing",
        ),
        // a controller parameter that is not a number, placed at its key
        (
            "den = [1, 1]\n[controller]\nkind = \"pi\"\nkp = \"x\"\n",
            "p.toml, line 4, column 1: `controller.kp` must be a number (found the string \"x\")",
        ),
        // a matrix row that is not a row
        (
            "a = [[1, 2], 3]\nb = \"1; 1\"\nc = \"1 0\"\n",
            "p.toml, line 1, column 5: `a` must be a list of rows (lists of numbers) or a string of rows such as \"0 1; -4 -0.8\" (row 2 is the number 3)",
        ),
        // broken TOML
        (
            "den = [1,\n",
            "p.toml, line 1, column 10: unclosed array, expected `]`",
        ),
        // no plant at all
        (
            "name = \"x\"\n",
            "p.toml: a plant needs exactly one of: `den` (with an optional `num`), `model` (with optional [params]), or `a`, `b`, `c` (with an optional `d`)",
        ),
    ];
    for (text, want) in cases {
        assert_eq!(file_error("p.toml", text), want, "{text:?}");
    }
    // an unknown key, with the known ones
    let e = file_error("p.toml", "den = [1]\ntypo = 2\n");
    assert!(
        e.starts_with(
            "p.toml, line 2, column 1: unknown key `typo` (known keys: name, description,"
        ),
        "{e}"
    );
    // nothing of the reader's jargon anywhere
    for (text, _) in cases {
        let e = file_error("p.toml", text);
        for jargon in [
            "untagged",
            "variant",
            "invalid type",
            "f64",
            "sequence",
            "struct",
        ] {
            assert!(!e.contains(jargon), "{e}");
        }
    }
}

#[test]
fn a_single_number_is_a_list_of_one() {
    let f = PlantFile::parse("num = 4\nden = [1, 0.8, 4]\n").unwrap();
    let p = Plant::from_record(&f).unwrap();
    assert_eq!(p.tf().unwrap().num().coeffs(), &[4.0]);
}

#[test]
fn batch_lines_name_line_column_and_key() {
    let e = |text: &str| {
        Plant::from_json_line_at(text, Some(7))
            .unwrap_err()
            .to_string()
    };
    assert_eq!(
        e(r#"{"den": true}"#),
        "line 7, column 2: `den` must be a list of numbers or a string of numbers (found true)"
    );
    assert_eq!(
        e(r#"{"name": "p", "den": "1 x"}"#),
        "line 7, column 15: `den`: 'x' is not a number"
    );
    assert!(
        e(r#"{"den": [1], "typo": 2}"#)
            .starts_with("line 7, column 14: unknown key `typo` (known keys:"),
        "{}",
        e(r#"{"den": [1], "typo": 2}"#)
    );
    assert_eq!(
        e(r#"{"den": [1, 2"#),
        "line 7, column 13: EOF while parsing a list"
    );
    assert!(e("[1, 2]").starts_with("line 7, column 1: a plant record is a JSON object"));
    // the line number is optional
    let e = Plant::from_json_line(r#"{"model": "tank", "params": {"A": "x"}}"#)
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "column 30: `params.A` must be a number (found the string \"x\")"
    );
    let e = Plant::from_json_line(r#"{"den": [1, 1], "controller": {"kp": 1}}"#)
        .unwrap_err()
        .to_string();
    assert_eq!(e, "column 17: [controller]: the key `kind` is missing");
}
