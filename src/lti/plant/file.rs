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
use std::collections::BTreeMap;
use std::path::Path;

use super::text::{Coefficient, coefficients_of, parse_list};
use crate::error::{LtiError, Result};

/// Coefficients as a list of numbers or as one string "1 0.8 4" (exact decimal text).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum CoeffList {
    /// `[1.0, 0.8, 4.0]`
    List(Vec<f64>),
    /// `"1 0.8 4"`
    Text(String),
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
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum MatrixSpec {
    /// `[[0, 1], [-4, -0.8]]`
    Rows(Vec<Vec<f64>>),
    /// `"0 1; -4 -0.8"`
    Text(String),
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
}

/// Largest plant file or batch line accepted (bytes).
pub const MAX_RECORD_BYTES: u64 = 1 << 20;

impl PlantFile {
    /// Reads and parses a plant file (at most [`MAX_RECORD_BYTES`]).
    pub fn load(path: &Path) -> Result<PlantFile> {
        let io = |message: String| LtiError::Io {
            path: path.display().to_string(),
            message,
        };
        let text = read_bounded(path).map_err(|e| io(e.to_string()))?;
        Self::parse(&text).map_err(|e| match e {
            LtiError::Io { message, .. } => io(message),
            other => other,
        })
    }

    /// Parses plant-file text (TOML).
    ///
    /// ```
    /// use ltikit::lti::PlantFile;
    /// let f = PlantFile::parse("name = \"tank\"\nmodel = \"tank\"\n[params]\nA = 4.0\n").unwrap();
    /// assert_eq!(f.model.as_deref(), Some("tank"));
    /// assert!(PlantFile::parse("name = \"x\"\nnum = [1.0]").is_err()); // no den
    /// ```
    pub fn parse(text: &str) -> Result<PlantFile> {
        let f: PlantFile = toml::from_str(text).map_err(|e| LtiError::Io {
            path: "plant file".into(),
            message: format!("invalid plant file: {}", e.message()),
        })?;
        f.validated()
    }

    /// Parses a batch line (JSON).
    ///
    /// ```
    /// use ltikit::lti::PlantFile;
    /// let f = PlantFile::parse_json(r#"{"name": "p", "den": "1 2 1"}"#).unwrap();
    /// assert_eq!(f.name.as_deref(), Some("p"));
    /// assert!(PlantFile::parse_json(r#"{"den": [1], "typo": 2}"#).is_err());
    /// ```
    pub fn parse_json(text: &str) -> Result<PlantFile> {
        let f: PlantFile = serde_json::from_str(text)
            .map_err(|e| LtiError::invalid(format!("not a plant record: {e}")))?;
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
            Err(LtiError::invalid(
                "a plant needs exactly one of: `den` (with an optional `num`), `model` (with optional [params]), or `a`, `b`, `c` (with an optional `d`)",
            ))
        }
    }
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
}
