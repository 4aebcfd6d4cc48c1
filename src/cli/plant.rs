//! The plant options shared by every command that takes a transfer function: coefficients
//! (`--num/--den`, repeatable for several plants), plant files (`--plant`), or a textbook model
//! (`--model NAME --param K=V`).

use anyhow::{Context, Result};
use clap::Args;
use std::path::PathBuf;

use super::UsageError;
use super::parse;
use crate::TransferFunction;
use crate::lti::{PlantFile, build_plant};

/// Plant selection.
#[derive(Args, Debug, Clone, Default)]
pub struct PlantArgs {
    /// Numerator coefficients in descending powers of s ("4" or "1 3" or "1,3"; use
    /// --num=-3,-12 for negative values). Repeat with --den for several plants. Default 1.
    #[arg(long, value_name = "COEFFS", allow_hyphen_values = true)]
    pub num: Vec<String>,
    /// Denominator (characteristic polynomial) coefficients in descending powers of s.
    #[arg(long, value_name = "COEFFS", allow_hyphen_values = true)]
    pub den: Vec<String>,
    /// A plant file (TOML with num/den or model/params; see data/plants/). Repeatable.
    #[arg(long, value_name = "FILE.toml")]
    pub plant: Vec<PathBuf>,
    /// A textbook model: spring-mass-damper, second-order, tank, rc, rlc, two-dof.
    #[arg(long, value_name = "NAME")]
    pub model: Option<String>,
    /// A model parameter, NAME=VALUE (repeatable), e.g. --param M=1 --param C=0.4.
    #[arg(long = "param", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub params: Vec<String>,
}

/// A resolved plant.
#[derive(Debug, Clone)]
pub struct Plant {
    /// Display name (the file's name, the model name, or the transfer function itself).
    pub name: String,
    /// The transfer function.
    pub tf: TransferFunction,
    /// Description, input and output, when known.
    pub description: Option<String>,
}

impl PlantArgs {
    /// All plants selected, in the order: coefficient pairs, files, model.
    pub fn resolve(&self) -> Result<Vec<Plant>> {
        let mut out = Vec::new();
        if !self.num.is_empty() || !self.den.is_empty() {
            if self.den.is_empty() {
                return Err(UsageError("--num needs --den (the denominator)".into()).into());
            }
            if !self.num.is_empty() && self.num.len() != self.den.len() {
                return Err(UsageError(format!(
                    "{} --num but {} --den: give one numerator per denominator (or none for 1)",
                    self.num.len(),
                    self.den.len()
                ))
                .into());
            }
            for (i, d) in self.den.iter().enumerate() {
                let den = parse::numbers(d, "--den")?;
                let num = match self.num.get(i) {
                    Some(n) => parse::numbers(n, "--num")?,
                    None => vec![1.0],
                };
                let tf = TransferFunction::from_descending(&num, &den)?;
                out.push(Plant {
                    name: tf.to_string(),
                    tf,
                    description: None,
                });
            }
        }
        for path in &self.plant {
            let f = PlantFile::load(path)?;
            let tf = f
                .transfer_function()
                .with_context(|| format!("plant file {}", path.display()))?;
            let mut desc = f.description.clone().unwrap_or_default();
            if let (Some(i), Some(o)) = (&f.input, &f.output) {
                if !desc.is_empty() {
                    desc.push(' ');
                }
                desc.push_str(&format!("Input: {i}; output: {o}."));
            }
            out.push(Plant {
                name: f.name.clone(),
                tf,
                description: (!desc.is_empty()).then_some(desc),
            });
        }
        if let Some(m) = &self.model {
            let params = parse::params(&self.params)?;
            let (tf, used) = build_plant(m, &params)?;
            let list = used
                .iter()
                .map(|(k, v)| format!("{k}={}", crate::poly::fmt_num(*v)))
                .collect::<Vec<_>>()
                .join(", ");
            out.push(Plant {
                name: format!("{m} ({list})"),
                tf,
                description: None,
            });
        } else if !self.params.is_empty() {
            return Err(UsageError("--param needs --model".into()).into());
        }
        if out.is_empty() {
            return Err(UsageError(
                "no plant given: use --num/--den, --plant FILE.toml or --model NAME".into(),
            )
            .into());
        }
        Ok(out)
    }

    /// Exactly one plant.
    pub fn single(&self) -> Result<Plant> {
        let mut v = self.resolve()?;
        if v.len() != 1 {
            return Err(UsageError(format!(
                "this command takes one plant, {} were given",
                v.len()
            ))
            .into());
        }
        Ok(v.remove(0))
    }
}
