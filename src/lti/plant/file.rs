//! The plant record: the one schema of a plant file (TOML) and of a batch line (JSON), with a
//! name, a description, units, and either the coefficients (`num`, `den`, descending powers,
//! as a list of numbers or a string "1 0.8 4") or a textbook model with parameters.
//!
//! ```toml
//! name = "Quarter-car suspension"
//! description = "Body mass on the suspension spring and damper."
//! input = "road force [N]"
//! output = "body displacement [m]"
//! num = [1.0]
//! den = [250.0, 1000.0, 16000.0]
//! ```
//! or
//! ```toml
//! name = "Lightly damped mass"
//! model = "spring-mass-damper"
//! [params]
//! M = 1.0
//! C = 0.1
//! K = 4.0
//! ```
//! A batch line is the same record in JSON: `{"name": "p1", "num": [1], "den": [1, 2, 1]}`.

use serde::Deserialize;
use serde::de::{self, IgnoredAny, MapAccess, SeqAccess, Visitor};
use std::collections::BTreeMap;
use std::path::Path;

use super::located;
use super::text::{Coefficient, coefficients_of, parse_list};
use crate::error::{LtiError, Result};

/// Coefficients as a list of numbers or as one string "1 0.8 4" (exact decimal text); a
/// single number is a list of one.
#[derive(Debug, Clone, PartialEq)]
pub enum CoeffList {
    /// `[1.0, 0.8, 4.0]`
    List(Vec<f64>),
    /// `"1 0.8 4"`
    Text(String),
}

/// What `num` and `den` must hold, in words.
const COEFF_MUST: &str = "a list of numbers or a string of numbers";

impl<'de> Deserialize<'de> for CoeffList {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = CoeffList;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(COEFF_MUST)
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> std::result::Result<CoeffList, E> {
                Ok(CoeffList::List(vec![v as f64]))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> std::result::Result<CoeffList, E> {
                Ok(CoeffList::List(vec![v as f64]))
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> std::result::Result<CoeffList, E> {
                Ok(CoeffList::List(vec![v]))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> std::result::Result<CoeffList, E> {
                Ok(CoeffList::Text(v.to_string()))
            }
            fn visit_bool<E: de::Error>(self, v: bool) -> std::result::Result<CoeffList, E> {
                Err(located::wrong(COEFF_MUST, &v.to_string()))
            }
            fn visit_seq<A: SeqAccess<'de>>(
                self,
                seq: A,
            ) -> std::result::Result<CoeffList, A::Error> {
                located::numbers(seq, COEFF_MUST).map(CoeffList::List)
            }
            fn visit_map<A: MapAccess<'de>>(
                self,
                mut map: A,
            ) -> std::result::Result<CoeffList, A::Error> {
                while map.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
                Err(located::wrong(COEFF_MUST, "a table"))
            }
        }
        d.deserialize_any(V)
    }
}

impl CoeffList {
    /// The coefficients with their text.
    pub fn coefficients(&self, what: &str) -> Result<Vec<Coefficient>> {
        match self {
            CoeffList::List(v) if v.is_empty() => {
                Err(LtiError::invalid(format!("{what}: no numbers given")))
            }
            CoeffList::List(v) => Ok(coefficients_of(v)),
            CoeffList::Text(s) => parse_list(s, what),
        }
    }
}

/// A matrix as rows of numbers or as one string "0 1; -4 -0.8".
#[derive(Debug, Clone, PartialEq)]
pub enum MatrixSpec {
    /// `[[0, 1], [-4, -0.8]]`
    Rows(Vec<Vec<f64>>),
    /// `"0 1; -4 -0.8"`
    Text(String),
}

/// What a matrix key must hold, in words.
const MATRIX_MUST: &str =
    "a list of rows (lists of numbers) or a string of rows such as \"0 1; -4 -0.8\"";

impl<'de> Deserialize<'de> for MatrixSpec {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = MatrixSpec;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(MATRIX_MUST)
            }
            fn visit_str<E: de::Error>(self, v: &str) -> std::result::Result<MatrixSpec, E> {
                Ok(MatrixSpec::Text(v.to_string()))
            }
            fn visit_seq<A: SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> std::result::Result<MatrixSpec, A::Error> {
                let mut rows = Vec::new();
                while let Some(item) = seq.next_element::<located::Row>()? {
                    match item {
                        located::Row::Numbers(r) => rows.push(r),
                        located::Row::Bad(what) => {
                            return Err(de::Error::custom(format!(
                                "must be {MATRIX_MUST} (row {} {what})",
                                rows.len() + 1
                            )));
                        }
                    }
                }
                Ok(MatrixSpec::Rows(rows))
            }
        }
        d.deserialize_any(V)
    }
}

impl MatrixSpec {
    /// The matrix.
    pub fn matrix(&self, what: &str) -> Result<nalgebra::DMatrix<f64>> {
        match self {
            MatrixSpec::Rows(r) => super::text::matrix_of_rows(r.clone(), what),
            MatrixSpec::Text(s) => super::text::parse_matrix(s, what),
        }
    }
}

/// A parsed plant record (plant file or batch line).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlantFile {
    /// Display name (optional in a batch line).
    #[serde(default)]
    pub name: Option<String>,
    /// What the plant is.
    #[serde(default)]
    pub description: Option<String>,
    /// Input signal and unit.
    #[serde(default)]
    pub input: Option<String>,
    /// Output signal and unit.
    #[serde(default)]
    pub output: Option<String>,
    /// Where it comes from (seed equation, data sheet, …).
    #[serde(default)]
    pub source: Option<String>,
    /// Numerator, descending powers (1 when only `den` is given).
    #[serde(default)]
    pub num: Option<CoeffList>,
    /// Denominator, descending powers.
    #[serde(default)]
    pub den: Option<CoeffList>,
    /// A textbook model name instead of coefficients.
    #[serde(default)]
    pub model: Option<String>,
    /// Model parameters.
    #[serde(default)]
    pub params: BTreeMap<String, f64>,
    /// State matrix A (n × n) of a state-space plant.
    #[serde(default)]
    pub a: Option<MatrixSpec>,
    /// Input matrix B (n × m).
    #[serde(default)]
    pub b: Option<MatrixSpec>,
    /// Output matrix C (p × n).
    #[serde(default)]
    pub c: Option<MatrixSpec>,
    /// Feedthrough D (p × m; zero when absent).
    #[serde(default)]
    pub d: Option<MatrixSpec>,
    /// Names (with units) of the inputs of a state-space plant.
    #[serde(default)]
    pub inputs: Vec<String>,
    /// Names of the outputs.
    #[serde(default)]
    pub outputs: Vec<String>,
    /// Names of the states.
    #[serde(default)]
    pub states: Vec<String>,
    /// The sampling period of a discrete-time plant (seconds; absent: continuous time). With it
    /// `num`/`den` are in descending powers of z and `a`…`d` give x\[k+1\] = A x\[k\] + B u\[k\].
    #[serde(default)]
    pub dt: Option<f64>,
    /// A dead time (seconds) e^(−sT) on the plant (on every input of a state-space plant);
    /// in discrete time a whole number of periods, absorbed as z^(−d).
    #[serde(default)]
    pub delay: Option<f64>,
    /// Dead times (s) on each input of a state-space plant.
    #[serde(default)]
    pub input_delays: Vec<f64>,
    /// Dead times (s) on each output of a state-space plant.
    #[serde(default)]
    pub output_delays: Vec<f64>,
    /// A controller in front of the plant (unity negative feedback), as a `[controller]`
    /// section: `kind = "pid"` and the parameters of [`crate::lti::Controller`].
    #[serde(default)]
    pub controller: Option<ControllerSection>,
}

/// A plant file's `[controller]` section: the kind and its parameters
/// (`kind = "pid"`, `kp = 2`, `ki = 1`, `kd = 0.5`, `tf = 0.01`).
#[derive(Debug, Clone, PartialEq)]
pub struct ControllerSection {
    /// `p`, `pi`, `pd`, `pid`, `lead` or `lag`.
    pub kind: String,
    /// The parameters by name.
    pub params: BTreeMap<String, f64>,
}

impl<'de> Deserialize<'de> for ControllerSection {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = ControllerSection;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a table with `kind` and the controller's parameters")
            }
            fn visit_map<A: MapAccess<'de>>(
                self,
                mut map: A,
            ) -> std::result::Result<ControllerSection, A::Error> {
                let mut kind = None;
                let mut params = BTreeMap::new();
                while let Some(key) = map.next_key::<String>()? {
                    let item = map.next_value::<located::Item>()?;
                    let shown = crate::error::abbreviate(&key);
                    match (key.as_str(), item) {
                        ("kind", located::Item::Text(s)) => kind = Some(s),
                        ("kind", other) => {
                            return Err(de::Error::custom(format!(
                                "`controller.kind` must be a string such as \"pid\" (found {})",
                                other.describe()
                            )));
                        }
                        (_, located::Item::Number(x)) => {
                            params.insert(key, x);
                        }
                        (_, other) => {
                            return Err(de::Error::custom(format!(
                                "`controller.{shown}` must be a number (found {})",
                                other.describe()
                            )));
                        }
                    }
                }
                let kind = kind.ok_or_else(|| de::Error::custom("missing field `kind`"))?;
                Ok(ControllerSection { kind, params })
            }
        }
        d.deserialize_map(V)
    }
}

/// The coefficient lists of a batch line as raw JSON text.
#[derive(Deserialize)]
struct RawCoeffs<'a> {
    #[serde(default, borrow)]
    num: Option<&'a serde_json::value::RawValue>,
    #[serde(default, borrow)]
    den: Option<&'a serde_json::value::RawValue>,
}

/// The number tokens of a JSON array of numbers as typed, separated by spaces (`None` for
/// anything else).
fn raw_tokens(raw: &serde_json::value::RawValue) -> Option<String> {
    let inner = raw.get().trim().strip_prefix('[')?.strip_suffix(']')?;
    let tokens: Vec<&str> = inner.split(',').map(str::trim).collect();
    let numeric = |t: &&str| {
        !t.is_empty()
            && t.chars()
                .all(|c| c.is_ascii_digit() || matches!(c, '-' | '+' | '.' | 'e' | 'E'))
    };
    tokens.iter().all(numeric).then(|| tokens.join(" "))
}

pub use crate::limits::MAX_RECORD_BYTES;

impl PlantFile {
    /// Reads and parses a plant file (at most [`MAX_RECORD_BYTES`]). Errors name the file
    /// and, for a bad record, the line, the column and the key
    /// ([`LtiError::BadRecord`]).
    pub fn load(path: &Path) -> Result<PlantFile> {
        let text = read_text(path)?;
        Self::parse(&text).map_err(|e| in_file(path, e))
    }

    /// Parses plant-file text (TOML). Errors say where (line and column) and what, naming
    /// the key: a wrong type, an unknown key, a bad number, a missing key, no plant at all.
    ///
    /// ```
    /// use ltikit::lti::PlantFile;
    /// let f = PlantFile::parse("name = \"tank\"\nmodel = \"tank\"\n[params]\nA = 4.0\n").unwrap();
    /// assert_eq!(f.model.as_deref(), Some("tank"));
    /// assert!(PlantFile::parse("name = \"x\"\nnum = [1.0]").is_err()); // no den
    /// let e = PlantFile::parse("den = [1, \"a\"]").unwrap_err().to_string();
    /// assert_eq!(e, "line 1, column 7: `den` must be a list of numbers or a string of numbers \
    ///                (entry 2 is the string \"a\")");
    /// ```
    pub fn parse(text: &str) -> Result<PlantFile> {
        let f: PlantFile = toml::from_str(text).map_err(|e| {
            let (at, message) = located::toml_error(text, &e);
            located::bad_record(at.unwrap_or_default(), message)
        })?;
        f.validated()
    }

    /// Parses a batch line (JSON). Errors name the column and the key.
    ///
    /// ```
    /// use ltikit::lti::PlantFile;
    /// let f = PlantFile::parse_json(r#"{"name": "p", "den": "1 2 1"}"#).unwrap();
    /// assert_eq!(f.name.as_deref(), Some("p"));
    /// let e = PlantFile::parse_json(r#"{"den": [1], "typo": 2}"#).unwrap_err().to_string();
    /// assert!(e.starts_with("column 14: unknown key `typo` (known keys: name, "), "{e}");
    /// ```
    pub fn parse_json(text: &str) -> Result<PlantFile> {
        Self::parse_json_at(text, None)
    }

    /// [`PlantFile::parse_json`] for line `line` (1-based) of a batch file: errors say
    /// "line 3, column 9: …".
    pub fn parse_json_at(text: &str, line: Option<usize>) -> Result<PlantFile> {
        let at = |offset: usize| json_position(text, offset, line);
        let value: serde_json::Value = serde_json::from_str(text).map_err(|e| {
            let msg = e.to_string();
            let msg = msg
                .rsplit_once(" at line ")
                .map_or(msg.as_str(), |(m, _)| m);
            let column = e.column().saturating_sub(1);
            let offset = text
                .lines()
                .take(e.line().saturating_sub(1))
                .map(|l| l.len() + 1)
                .sum::<usize>()
                + column;
            located::bad_record(at(offset), located::plain(msg))
        })?;
        let Some(object) = value.as_object() else {
            return Err(located::bad_record(
                at(0),
                "a plant record is a JSON object, e.g. {\"den\": [1, 2, 1]}".into(),
            ));
        };
        let mut f: PlantFile = match serde_json::from_value(value.clone()) {
            Ok(f) => f,
            Err(e) => {
                // Which key: the first one that fails on its own.
                for (k, v) in object {
                    let one =
                        serde_json::Value::Object([(k.clone(), v.clone())].into_iter().collect());
                    if let Err(e) = serde_json::from_value::<PlantFile>(one) {
                        let msg = located::plain(&e.to_string());
                        // a table of numbers (`params`): the entry that is not one
                        let key = match v.as_object() {
                            Some(inner) if msg.starts_with("must be a number") => inner
                                .iter()
                                .find(|(_, x)| !x.is_number())
                                .map_or(k.clone(), |(k2, _)| format!("{k}.{k2}")),
                            _ => k.clone(),
                        };
                        let offset = located::json_key_offset(text, &key).unwrap_or(0);
                        let msg = if msg.starts_with("unknown key") || msg.starts_with('`') {
                            msg
                        } else if msg.starts_with("the key ") {
                            format!("[{}]: {msg}", crate::error::abbreviate(k))
                        } else {
                            format!("`{}` {msg}", crate::error::abbreviate(&key))
                        };
                        return Err(located::bad_record(at(offset), msg));
                    }
                }
                return Err(located::bad_record(at(0), located::plain(&e.to_string())));
            }
        };
        // Keep the numbers of `num`/`den` as typed (an f64 would lose 17-digit decimals).
        if let Ok(raw) = serde_json::from_str::<RawCoeffs>(text) {
            for (list, raw) in [(&mut f.num, raw.num), (&mut f.den, raw.den)] {
                if let (Some(CoeffList::List(_)), Some(t)) = (&*list, raw.and_then(raw_tokens)) {
                    *list = Some(CoeffList::Text(t));
                }
            }
        }
        f.validated()
    }

    fn validated(self) -> Result<PlantFile> {
        let coeffs = self.den.is_some() || self.num.is_some();
        let matrices = self.a.is_some() || self.b.is_some() || self.c.is_some() || self.d.is_some();
        let kinds = [coeffs, self.model.is_some(), matrices]
            .iter()
            .filter(|&&k| k)
            .count();
        let complete = (!coeffs || self.den.is_some())
            && (!matrices || (self.a.is_some() && self.b.is_some() && self.c.is_some()));
        if kinds == 1 && complete {
            Ok(self)
        } else {
            Err(located::bad_record(
                String::new(),
                "a plant needs exactly one of: `den` (with an optional `num`), `model` (with optional [params]), or `a`, `b`, `c` (with an optional `d`)".into(),
            ))
        }
    }
}

/// "line 3, column 9" of byte `offset` of batch line `line` ("column 9" when the line number
/// is not known).
fn json_position(text: &str, offset: usize, line: Option<usize>) -> String {
    let (_, column) = located::line_column(text, offset);
    match line {
        Some(l) => format!("line {l}, column {column}"),
        None => format!("column {column}"),
    }
}

/// The location of a record error (a key's line and column, or none) in a plant file, from
/// the key's position in `text`.
pub(super) fn at_key_in_file(path: &Path, text: &str, key: Option<&str>, e: LtiError) -> LtiError {
    let at = key
        .and_then(|k| located::toml_key_offset(text, k))
        .map(|o| located::position(text, o))
        .unwrap_or_default();
    in_file(path, located::bad_record(at, e.to_string()))
}

/// The same for batch line `line` (JSON).
pub(super) fn at_key_in_line(
    text: &str,
    line: Option<usize>,
    key: Option<&str>,
    e: LtiError,
) -> LtiError {
    let at = match key.and_then(|k| located::json_key_offset(text, k)) {
        Some(o) => json_position(text, o, line),
        None => line.map(|l| format!("line {l}")).unwrap_or_default(),
    };
    located::bad_record(at, e.to_string())
}

/// A record error with the file's name in front of its location (the name abbreviated).
pub(super) fn in_file(path: &Path, e: LtiError) -> LtiError {
    let name = crate::error::abbreviate(&path.display().to_string());
    match e {
        LtiError::BadRecord { location, message } => LtiError::BadRecord {
            location: if location.is_empty() {
                name
            } else {
                format!("{name}, {location}")
            },
            message,
        },
        other => other,
    }
}

/// A plant file's text (at most [`MAX_RECORD_BYTES`]); errors name the file.
pub(crate) fn read_text(path: &Path) -> Result<String> {
    read_bounded(path).map_err(|e| LtiError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}

/// Reads a file of at most [`MAX_RECORD_BYTES`] (a larger one, or a device that never ends,
/// is refused without reading it all).
fn read_bounded(path: &Path) -> std::io::Result<String> {
    use std::io::Read;
    let f = std::fs::File::open(path)?;
    let mut buf = Vec::new();
    f.take(MAX_RECORD_BYTES + 1).read_to_end(&mut buf)?;
    if buf.len() as u64 > MAX_RECORD_BYTES {
        return Err(std::io::Error::other(format!(
            "larger than the {} MiB a plant file may have",
            MAX_RECORD_BYTES >> 20
        )));
    }
    String::from_utf8(buf).map_err(|_| std::io::Error::other("not UTF-8 text"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_malformed_records() {
        assert!(PlantFile::parse("name = 1").is_err());
        assert!(PlantFile::parse("name = \"x\"\nnum = [1.0]\nden = [1.0]\ntypo = 3").is_err());
        assert!(PlantFile::parse("name = \"x\"\nden = [1.0]\nmodel = \"tank\"").is_err());
        assert!(PlantFile::parse_json("{}").is_err());
        assert!(PlantFile::parse_json(r#"{"a": [[1]], "b": [[1]]}"#).is_err()); // no c
        assert!(
            PlantFile::parse_json(r#"{"a": [[1]], "b": [[1]], "c": "1", "den": [1]}"#).is_err()
        );
        assert!(PlantFile::parse_json(r#"{"a": [[-1]], "b": [[1]], "c": "1"}"#).is_ok());
        assert!(PlantFile::parse_json("[1, 2]").is_err());
    }

    #[test]
    fn batch_numbers_keep_their_text() {
        // 1.00000000000000001 is 1.0 as an f64; its text is kept for the exact path.
        let f = PlantFile::parse_json(r#"{"den": [1, 2.00000000000000002, 1e-20]}"#).unwrap();
        let c = f.den.unwrap().coefficients("den").unwrap();
        let texts: Vec<&str> = c.iter().map(|c| c.text.as_str()).collect();
        assert_eq!(texts, ["1", "2.00000000000000002", "1e-20"]);
        assert_eq!(c[1].value.to_bits(), 2.0_f64.to_bits());
    }
}
