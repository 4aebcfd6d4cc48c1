//! Plant files: TOML with a name, a description, units, and either the coefficients
//! (`num`, `den`, descending powers) or a textbook model with parameters.
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

use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;

use crate::error::{LtiError, Result};
use crate::lti::{TransferFunction, build_plant};

/// A parsed plant file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlantFile {
    /// Display name.
    pub name: String,
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
    /// Numerator, descending powers.
    #[serde(default)]
    pub num: Option<Vec<f64>>,
    /// Denominator, descending powers.
    #[serde(default)]
    pub den: Option<Vec<f64>>,
    /// A textbook model name instead of coefficients.
    #[serde(default)]
    pub model: Option<String>,
    /// Model parameters.
    #[serde(default)]
    pub params: BTreeMap<String, f64>,
}

impl PlantFile {
    /// Reads and parses a plant file.
    pub fn load(path: &Path) -> Result<PlantFile> {
        let text = std::fs::read_to_string(path).map_err(|e| LtiError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        Self::parse(&text).map_err(|e| match e {
            LtiError::Io { message, .. } => LtiError::Io {
                path: path.display().to_string(),
                message,
            },
            other => other,
        })
    }

    /// Parses plant-file text.
    ///
    /// ```
    /// use ltikit::lti::PlantFile;
    /// let f = PlantFile::parse("name = \"tank\"\nmodel = \"tank\"\n[params]\nA = 4.0\n").unwrap();
    /// assert_eq!(f.transfer_function().unwrap().den().coeffs(), &[4.0, 0.5]);
    /// ```
    pub fn parse(text: &str) -> Result<PlantFile> {
        let f: PlantFile = toml::from_str(text).map_err(|e| LtiError::Io {
            path: "plant file".into(),
            message: format!("invalid plant file: {}", e.message()),
        })?;
        match (&f.num, &f.den, &f.model) {
            (Some(_), Some(_), None) => Ok(f),
            (None, None, Some(_)) => Ok(f),
            _ => Err(LtiError::invalid(
                "a plant file needs either both `num` and `den`, or `model` (with optional [params])",
            )),
        }
    }

    /// The transfer function described by the file.
    pub fn transfer_function(&self) -> Result<TransferFunction> {
        match (&self.num, &self.den, &self.model) {
            (Some(n), Some(d), _) => TransferFunction::from_descending(n, d),
            (_, _, Some(m)) => {
                let p: Vec<(String, f64)> =
                    self.params.iter().map(|(k, v)| (k.clone(), *v)).collect();
                Ok(build_plant(m, &p)?.0)
            }
            _ => Err(LtiError::invalid(
                "plant file has neither coefficients nor a model",
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_malformed_files() {
        assert!(PlantFile::parse("name = 1").is_err());
        assert!(PlantFile::parse("name = \"x\"\nnum = [1.0]").is_err());
        assert!(PlantFile::parse("name = \"x\"\nnum = [1.0]\nden = [1.0]\ntypo = 3").is_err());
        let f = PlantFile::parse("name = \"x\"\nnum = [1.0]\nden = [0.0]").unwrap();
        assert!(f.transfer_function().is_err());
    }
}
