//! Where a plant record went wrong, in plain words: the line and column of a plant file (TOML)
//! or the column of a batch line (JSON), the key, and what the key must hold — never the
//! reader's jargon ("data did not match any variant of untagged enum CoeffList", "invalid
//! type: string, expected f64").
//!
//! ```
//! use ltikit::lti::PlantFile;
//! let e = PlantFile::parse("name = \"x\"\nden = true\n").unwrap_err().to_string();
//! assert_eq!(
//!     e,
//!     "line 2, column 7: `den` must be a list of numbers or a string of numbers (found true)"
//! );
//! let e = PlantFile::parse("den = [1]\ntypo = 2\n").unwrap_err().to_string();
//! assert!(e.starts_with("line 2, column 1: unknown key `typo` (known keys: name, "), "{e}");
//! ```

use serde::de::{self, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use std::fmt;

use crate::error::{LtiError, abbreviate};

/// A value as a record holds it, classified for a message ("the string \"a\"", "true",
/// "a table").
pub(super) enum Item {
    /// A number (integer or float).
    Number(f64),
    /// A string.
    Text(String),
    /// Anything else, described in words.
    Other(String),
}

impl<'de> de::Deserialize<'de> for Item {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Item, D::Error> {
        d.deserialize_any(ItemVisitor)
    }
}

struct ItemVisitor;

impl<'de> Visitor<'de> for ItemVisitor {
    type Value = Item;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a value")
    }
    fn visit_bool<E: de::Error>(self, v: bool) -> Result<Item, E> {
        Ok(Item::Other(v.to_string()))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Item, E> {
        Ok(Item::Number(v as f64))
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Item, E> {
        Ok(Item::Number(v as f64))
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Item, E> {
        Ok(Item::Number(v))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<Item, E> {
        Ok(Item::Text(v.to_string()))
    }
    fn visit_unit<E: de::Error>(self) -> Result<Item, E> {
        Ok(Item::Other("nothing (null)".into()))
    }
    fn visit_none<E: de::Error>(self) -> Result<Item, E> {
        self.visit_unit()
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Item, A::Error> {
        while seq.next_element::<IgnoredAny>()?.is_some() {}
        Ok(Item::Other("a list".into()))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Item, A::Error> {
        while map.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
        Ok(Item::Other("a table".into()))
    }
}

impl Item {
    /// The value in words.
    pub(super) fn describe(&self) -> String {
        match self {
            Item::Number(x) => format!("the number {x}"),
            Item::Text(s) => format!("the string \"{}\"", abbreviate(s)),
            Item::Other(s) => s.clone(),
        }
    }
}

/// One row of a matrix given as rows: its numbers, or what is wrong with it
/// ("is the number 3", "entry 2 is the string \"a\"").
pub(super) enum Row {
    /// A list of numbers.
    Numbers(Vec<f64>),
    /// Not a list of numbers, in words.
    Bad(String),
}

impl<'de> de::Deserialize<'de> for Row {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Row, D::Error> {
        struct R;
        impl<'de> Visitor<'de> for R {
            type Value = Row;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a list of numbers")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Row, A::Error> {
                let mut out = Vec::new();
                let mut bad = None;
                while let Some(item) = seq.next_element::<Item>()? {
                    match item {
                        Item::Number(x) => out.push(x),
                        other if bad.is_none() => {
                            bad = Some(format!("entry {} is {}", out.len() + 1, other.describe()));
                        }
                        _ => {}
                    }
                }
                Ok(bad.map_or(Row::Numbers(out), Row::Bad))
            }
            fn visit_bool<E: de::Error>(self, v: bool) -> Result<Row, E> {
                Ok(Row::Bad(format!("is {v}")))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Row, E> {
                Ok(Row::Bad(format!("is the number {v}")))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Row, E> {
                Ok(Row::Bad(format!("is the number {v}")))
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Row, E> {
                Ok(Row::Bad(format!("is the number {v}")))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Row, E> {
                Ok(Row::Bad(format!("is the string \"{}\"", abbreviate(v))))
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Row, A::Error> {
                while map.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
                Ok(Row::Bad("is a table".into()))
            }
        }
        d.deserialize_any(R)
    }
}

/// The numbers of a list, or an error naming the first entry that is not one
/// ("entry 2 is the string \"a\"").
pub(super) fn numbers<'de, A: SeqAccess<'de>>(
    mut seq: A,
    must: &str,
) -> Result<Vec<f64>, A::Error> {
    let mut out = Vec::new();
    while let Some(item) = seq.next_element::<Item>()? {
        match item {
            Item::Number(x) => out.push(x),
            other => {
                return Err(de::Error::custom(format!(
                    "must be {must} (entry {} is {})",
                    out.len() + 1,
                    other.describe()
                )));
            }
        }
    }
    Ok(out)
}

/// The error for a value that is not what a key must hold.
pub(super) fn wrong<E: de::Error>(must: &str, found: &str) -> E {
    E::custom(format!("must be {must} (found {found})"))
}

/// A serde message in plain words: "unknown field `x`, expected one of `a`, `b`" becomes
/// "unknown key `x` (known keys: a, b)", "invalid type: string \"x\", expected f64" becomes
/// "must be a number (found the string \"x\")", "missing field `k`" becomes
/// "the key `k` is missing".
///
/// ```
/// use ltikit::lti::plant::plain;
/// assert_eq!(plain("invalid type: string \"x\", expected f64"),
///            "must be a number (found the string \"x\")");
/// assert_eq!(plain("missing field `kind`"), "the key `kind` is missing");
/// ```
pub fn plain(message: &str) -> String {
    let m = message.trim();
    if let Some(rest) = m.strip_prefix("unknown field ") {
        let (key, known) = match rest.split_once(", expected one of ") {
            Some((k, known)) => (k, known.replace('`', "")),
            None => (rest.split(',').next().unwrap_or(rest), "none".to_string()),
        };
        return format!("unknown key {} (known keys: {known})", abbreviate(key));
    }
    if let Some(key) = m.strip_prefix("missing field ") {
        return format!("the key {key} is missing");
    }
    for prefix in ["invalid type: ", "invalid value: "] {
        if let Some(rest) = m.strip_prefix(prefix) {
            if let Some((found, expected)) = rest.rsplit_once(", expected ") {
                return format!(
                    "must be {} (found {})",
                    expected_words(expected),
                    found_words(found)
                );
            }
        }
    }
    abbreviate_long(m)
}

/// serde's name of an expected type in words.
fn expected_words(e: &str) -> String {
    match e {
        "f64" | "f32" | "i64" | "u64" | "usize" | "a number" => "a number".into(),
        "a sequence" => "a list".into(),
        "a map" => "a table".into(),
        "a string" => "a string (in quotes)".into(),
        e if e.starts_with("struct ") => "a table of keys".into(),
        e if e.starts_with("a sequence") || e.starts_with("a map") => e
            .replace("a sequence", "a list")
            .replace("a map", "a table"),
        e => e.into(),
    }
}

/// serde's description of a found value in words.
fn found_words(f: &str) -> String {
    let unquote = |s: &str| s.trim_matches('`').to_string();
    if let Some(v) = f.strip_prefix("string ") {
        return format!("the string {}", abbreviate(v));
    }
    for p in ["integer ", "floating point "] {
        if let Some(v) = f.strip_prefix(p) {
            return format!("the number {}", unquote(v));
        }
    }
    if let Some(v) = f.strip_prefix("boolean ") {
        return unquote(v);
    }
    match f {
        "sequence" => "a list".into(),
        "map" => "a table".into(),
        "unit value" | "null" => "nothing (null)".into(),
        f => abbreviate(f),
    }
}

/// `text` with every word longer than the shown length cut (a message may quote input).
fn abbreviate_long(text: &str) -> String {
    text.split(' ')
        .map(|w| {
            if w.chars().count() > crate::error::TOKEN_SHOWN {
                abbreviate(w)
            } else {
                w.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// 1-based line and column (in characters) of byte offset `at` of `text`.
pub(super) fn line_column(text: &str, at: usize) -> (usize, usize) {
    let at = at.min(text.len());
    let at = (0..=at)
        .rev()
        .find(|&i| text.is_char_boundary(i))
        .unwrap_or(0);
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[start..].chars().count() + 1)
}

/// "line 3, column 7" of byte offset `at` (the column alone for a one-line text, as a batch
/// line: its line number is the file's).
pub(super) fn position(text: &str, at: usize) -> String {
    let (line, column) = line_column(text, at);
    format!("line {line}, column {column}")
}

/// A plant-file (TOML) reading error as (where, what): the position and the key from the
/// reader's error, its message in plain words.
pub(super) fn toml_error(text: &str, e: &toml::de::Error) -> (Option<String>, String) {
    let at = e.span().map(|s| position(text, s.start));
    // The key path: the reader prints it as "in `a.b`" when it has no input to quote.
    let mut bare = e.clone();
    bare.set_input(None);
    let shown = bare.to_string();
    let key = shown
        .lines()
        .find_map(|l| l.strip_prefix("in `"))
        .map(|k| k.trim_end_matches('`').to_string());
    let msg = plain(e.message());
    // A message that names its own key (`controller.kp`) is placed at that key.
    let at = msg
        .strip_prefix('`')
        .and_then(|m| m.split_once('`'))
        .and_then(|(k, _)| toml_key_offset(text, k))
        .map(|o| position(text, o))
        .or(at);
    let msg = match key {
        Some(k) if msg.starts_with("the key ") => {
            let section = k.split('.').next().unwrap_or(&k);
            format!("[{section}]: {msg}")
        }
        Some(k) if !msg.starts_with("unknown key") && !msg.starts_with('`') => {
            format!("`{k}` {msg}")
        }
        _ => msg,
    };
    (at, msg)
}

/// The byte offset of `key` (a dotted path such as `params.M`) in a plant file, from the
/// document's spans; `None` when the text does not parse or lacks the key.
pub(super) fn toml_key_offset(text: &str, key: &str) -> Option<usize> {
    let doc = toml::de::DeTable::parse(text).ok()?;
    let mut table = doc.get_ref();
    let mut parts = key.split('.').peekable();
    while let Some(part) = parts.next() {
        let (k, v) = table.iter().find(|(k, _)| k.get_ref().as_ref() == part)?;
        if parts.peek().is_none() {
            return Some(k.span().start);
        }
        table = v.get_ref().as_table()?;
    }
    None
}

/// The byte offset of `key` in a JSON record (the first `"key"` followed by a colon; for a
/// dotted path the last part after the first).
pub(super) fn json_key_offset(text: &str, key: &str) -> Option<usize> {
    let mut from = 0;
    for part in key.split('.') {
        let needle = format!("\"{part}\"");
        let mut search = from;
        loop {
            let i = text[search..].find(&needle)? + search;
            let after = text[i + needle.len()..].trim_start();
            if after.starts_with(':') {
                from = i;
                break;
            }
            search = i + needle.len();
        }
    }
    Some(from)
}

/// A record error at `location` (empty: none known).
pub(super) fn bad_record(location: String, message: String) -> LtiError {
    LtiError::BadRecord { location, message }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_count_characters() {
        let t = "a = 1\nμ = \"x\"\n";
        assert_eq!(line_column(t, 0), (1, 1));
        assert_eq!(line_column(t, t.find("\"x").unwrap()), (2, 5));
        assert_eq!(line_column(t, 10_000), (3, 1));
    }

    #[test]
    fn key_offsets() {
        let t = "den = [1]\n[params]\nM = 2\n";
        assert_eq!(toml_key_offset(t, "params.M"), t.find("M ="));
        assert_eq!(toml_key_offset(t, "den"), Some(0));
        assert_eq!(toml_key_offset(t, "num"), None);
        let j = r#"{"name": "den", "den": [1]}"#;
        assert_eq!(json_key_offset(j, "den"), j.find("\"den\":"));
    }

    #[test]
    fn serde_words_become_plain() {
        assert_eq!(
            plain("unknown field `typo`, expected one of `name`, `den`"),
            "unknown key `typo` (known keys: name, den)"
        );
        assert_eq!(
            plain("invalid type: integer `3`, expected a string"),
            "must be a string (in quotes) (found the number 3)"
        );
        assert_eq!(
            plain("invalid type: sequence, expected a map"),
            "must be a table (found a list)"
        );
        let long = format!("bad {}", "x".repeat(500));
        assert!(plain(&long).len() < 150);
    }
}
