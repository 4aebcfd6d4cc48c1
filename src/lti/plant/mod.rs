//! The one way in: a plant from ODE coefficients typed as text, from a plant file, from a
//! textbook model with parameters, or from a batch line — parsed here, once, for every command
//! and for the batch mode.
//!
//! ```
//! use ltikit::lti::Plant;
//! let p = Plant::from_text(Some("4"), "1 0.8 4").unwrap();
//! assert_eq!(p.name, "4 / (s^2 + 0.8 s + 4)");
//! let q = Plant::from_model("spring-mass-damper", &[("C".into(), 0.8)]).unwrap();
//! assert_eq!(q.tf.den().coeffs(), &[1.0, 0.8, 4.0]);
//! assert_eq!(q.name, "spring-mass-damper (M=1, C=0.8, K=4)");
//! let r = Plant::from_json_line(r#"{"name": "p1", "den": [1, 2, 1]}"#).unwrap();
//! assert_eq!(r.name, "p1");
//! ```

mod file;
mod text;

use std::path::Path;

pub use file::{CoeffList, MAX_RECORD_BYTES, PlantFile};
pub use text::{
    Coefficient, coefficients_of, parse_list, parse_number, parse_param, parse_params, parse_values,
};

use crate::error::Result;
use crate::lti::{TransferFunction, build_plant};
use crate::poly::fmt_num;

/// A plant as the user gave it: a name, a description, the transfer function, and the
/// coefficients as typed when it was given by them.
#[derive(Debug, Clone, PartialEq)]
pub struct Plant {
    /// Display name (the file's name, the model with its parameters, or G itself).
    pub name: String,
    /// What it is, with its input and output when known.
    pub description: Option<String>,
    /// The transfer function.
    pub tf: TransferFunction,
    /// Numerator and denominator coefficients as typed (text kept), when given by them.
    pub typed: Option<(Vec<Coefficient>, Vec<Coefficient>)>,
}

impl Plant {
    /// From coefficient lists typed as text (descending powers; the numerator defaults to 1).
    ///
    /// Errors: a token that is not a number, an empty list, and those of
    /// [`TransferFunction::from_descending`].
    pub fn from_text(num: Option<&str>, den: &str) -> Result<Plant> {
        let den = parse_list(den, "--den")?;
        let num = match num {
            Some(n) => parse_list(n, "--num")?,
            None => coefficients_of(&[1.0]),
        };
        Self::from_coefficients(num, den, None)
    }

    /// From coefficients (numerator, denominator) with their text.
    pub fn from_coefficients(
        num: Vec<Coefficient>,
        den: Vec<Coefficient>,
        name: Option<String>,
    ) -> Result<Plant> {
        let values = |c: &[Coefficient]| c.iter().map(|x| x.value).collect::<Vec<_>>();
        let tf = TransferFunction::from_descending(&values(&num), &values(&den))?;
        Ok(Plant {
            name: name.unwrap_or_else(|| tf.to_string()),
            description: None,
            tf,
            typed: Some((num, den)),
        })
    }

    /// A textbook model ([`crate::lti::plant_specs`]) with parameter overrides.
    ///
    /// Errors: an unknown model or parameter, an invalid value.
    pub fn from_model(name: &str, params: &[(String, f64)]) -> Result<Plant> {
        let (tf, used) = build_plant(name, params)?;
        let list = used
            .iter()
            .map(|(k, v)| format!("{k}={}", fmt_num(*v)))
            .collect::<Vec<_>>()
            .join(", ");
        Ok(Plant {
            name: format!("{name} ({list})"),
            description: None,
            tf,
            typed: None,
        })
    }

    /// From a plant record (see [`PlantFile`]).
    pub fn from_record(f: &PlantFile) -> Result<Plant> {
        let mut plant = match (&f.den, &f.model) {
            (Some(den), _) => {
                let num = match &f.num {
                    Some(n) => n.coefficients("num")?,
                    None => coefficients_of(&[1.0]),
                };
                Self::from_coefficients(num, den.coefficients("den")?, None)?
            }
            (None, Some(m)) => {
                let params: Vec<(String, f64)> =
                    f.params.iter().map(|(k, v)| (k.clone(), *v)).collect();
                Self::from_model(m, &params)?
            }
            (None, None) => {
                return Err(crate::LtiError::invalid(
                    "a plant needs either `den` or `model`",
                ));
            }
        };
        if let Some(n) = &f.name {
            plant.name = n.clone();
        }
        let mut desc = f.description.clone().unwrap_or_default();
        if let (Some(i), Some(o)) = (&f.input, &f.output) {
            if !desc.is_empty() {
                desc.push(' ');
            }
            desc.push_str(&format!("Input: {i}; output: {o}."));
        }
        plant.description = (!desc.is_empty()).then_some(desc);
        Ok(plant)
    }

    /// A plant file (TOML, see [`PlantFile`]); errors name the file.
    pub fn from_file(path: &Path) -> Result<Plant> {
        let f = PlantFile::load(path)?;
        Self::from_record(&f).map_err(|e| crate::LtiError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })
    }

    /// A batch line (JSON, the plant-file schema).
    pub fn from_json_line(text: &str) -> Result<Plant> {
        Self::from_record(&PlantFile::parse_json(text)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_source_gives_the_same_plant() {
        let a = Plant::from_text(Some("1"), "1 0.4 4").unwrap();
        let b = Plant::from_json_line(r#"{"num": [1], "den": "1 0.4 4"}"#).unwrap();
        let c = Plant::from_record(
            &PlantFile::parse("name = \"x\"\nnum = \"1\"\nden = [1, 0.4, 4]").unwrap(),
        )
        .unwrap();
        let d = Plant::from_model("spring-mass-damper", &[]).unwrap();
        for p in [&b, &c, &d] {
            assert_eq!(p.tf, a.tf);
        }
        assert_eq!(c.name, "x");
        assert_eq!(a.typed.as_ref().unwrap().1[1].text, "0.4");
    }

    #[test]
    fn errors_name_the_problem() {
        let e = Plant::from_text(None, "1 nan").unwrap_err().to_string();
        assert!(e.contains("NaN"), "{e}");
        let e = Plant::from_json_line(r#"{"den": [1], "model": "tank"}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("either"), "{e}");
        let e = Plant::from_model("tank", &[("Q".into(), 1.0)])
            .unwrap_err()
            .to_string();
        assert!(e.contains("'Q'"), "{e}");
    }
}
