//! The plant options shared by every command that takes a plant: coefficients (`--num/--den`,
//! repeatable for several plants), plant files (`--plant`), or a textbook model
//! (`--model NAME --param K=V`). The values are read by the one plant-specification module,
//! [`crate::lti::plant`]; this module only checks the combination of options.

use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

use super::UsageError;
use crate::lti::Plant;

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
    /// State matrix A of a state-space plant, rows separated by ';': --a "0 1; -4 -0.8".
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true, requires_all = ["b", "c"])]
    pub a: Option<String>,
    /// Input matrix B (n × m): --b "0; 1".
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true, requires = "a")]
    pub b: Option<String>,
    /// Output matrix C (p × n): --c "1 0".
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true, requires = "a")]
    pub c: Option<String>,
    /// Feedthrough D (p × m; zero when absent).
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true, requires = "a")]
    pub d: Option<String>,
    /// The channel of a MIMO plant to analyse: INPUT,OUTPUT (1-based), e.g. --channel 1,2.
    #[arg(long, value_name = "INPUT,OUTPUT")]
    pub channel: Option<String>,
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
                out.push(Plant::from_text(self.num.get(i).map(String::as_str), d)?);
            }
        }
        if let (Some(a), Some(b), Some(c)) = (&self.a, &self.b, &self.c) {
            out.push(Plant::from_matrices_text(a, b, c, self.d.as_deref())?);
        }
        for path in &self.plant {
            out.push(Plant::from_file(path)?);
        }
        if let Some(m) = &self.model {
            let params = crate::lti::plant::parse_params(&self.params)?;
            out.push(Plant::from_model(m, &params)?);
        } else if !self.params.is_empty() {
            return Err(UsageError("--param needs --model".into()).into());
        }
        if out.is_empty() {
            return Err(UsageError(
                "no plant given: use --num/--den, --a/--b/--c, --plant FILE.toml or --model NAME"
                    .into(),
            )
            .into());
        }
        Ok(out)
    }

    /// The channel chosen with `--channel` (0-based input, output), if any.
    pub fn channel(&self) -> Result<Option<(usize, usize)>> {
        let Some(text) = &self.channel else {
            return Ok(None);
        };
        let bad = || {
            UsageError(format!(
                "--channel '{}': expected INPUT,OUTPUT with 1-based indices, e.g. --channel 1,2",
                crate::error::abbreviate(text)
            ))
        };
        let (i, o) = text.split_once(',').ok_or_else(bad)?;
        let i: usize = i.trim().parse().map_err(|_| bad())?;
        let o: usize = o.trim().parse().map_err(|_| bad())?;
        if i == 0 || o == 0 {
            return Err(bad().into());
        }
        Ok(Some((i - 1, o - 1)))
    }

    /// The factored form of a plant: the chosen channel, or the plant itself when SISO.
    pub fn factored(&self, plant: &Plant) -> Result<crate::analysis::Factored> {
        Ok(match self.channel()? {
            Some((i, o)) => plant.factored_channel(i, o)?,
            None => plant.factored()?,
        })
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
