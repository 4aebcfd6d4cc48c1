//! Parameter specifications of the models: name, default, unit, meaning, constraint.

use serde::Serialize;

use crate::error::{LtiError, Result, check_finite};

/// What values a parameter may take.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Constraint {
    /// Must be > 0 (a mass, a length, a resistance).
    Positive,
    /// Must be ≥ 0 (a damping coefficient).
    NonNegative,
    /// Any finite value (a voltage).
    Any,
}

impl Constraint {
    /// The rule in symbols: "> 0", "≥ 0", "any".
    pub fn symbol(&self) -> &'static str {
        match self {
            Constraint::Positive => "> 0",
            Constraint::NonNegative => "≥ 0",
            Constraint::Any => "any",
        }
    }

    /// True when `v` satisfies the constraint (NaN never does).
    pub fn admits(&self, v: f64) -> bool {
        v.is_finite()
            && match self {
                Constraint::Positive => v > 0.0,
                Constraint::NonNegative => v >= 0.0,
                Constraint::Any => true,
            }
    }
}

/// One model parameter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ModelParam {
    /// Name used on the command line (`--param NAME=VALUE`).
    pub name: &'static str,
    /// Default value.
    pub default: f64,
    /// SI unit ("1" for dimensionless).
    pub unit: &'static str,
    /// What it is.
    pub description: &'static str,
    /// Admissible values.
    pub constraint: Constraint,
}

impl ModelParam {
    /// Checks one value, naming the parameter in the error.
    ///
    /// ```
    /// use ltikit::nonlinear::{Constraint, ModelParam};
    /// let l = ModelParam { name: "L", default: 1.0, unit: "m", description: "length",
    ///                      constraint: Constraint::Positive };
    /// assert!(l.check(0.5).is_ok());
    /// assert!(l.check(0.0).is_err());
    /// assert!(l.check(f64::NAN).is_err());
    /// ```
    pub fn check(&self, v: f64) -> Result<f64> {
        check_finite(|| format!("parameter {}", self.name), v)?;
        if self.constraint.admits(v) {
            Ok(v)
        } else {
            Err(LtiError::InvalidParameter {
                name: self.name.into(),
                value: v,
                reason: format!(
                    "the {} must be {} ({})",
                    self.description,
                    self.constraint.symbol(),
                    self.unit
                ),
            })
        }
    }
}

/// Checks a full list of values against the specs (same order and length).
pub fn check_values(specs: &[ModelParam], values: &[f64]) -> Result<()> {
    if specs.len() != values.len() {
        return Err(LtiError::invalid(format!(
            "expected {} parameter values, got {}",
            specs.len(),
            values.len()
        )));
    }
    for (p, &v) in specs.iter().zip(values) {
        p.check(v)?;
    }
    Ok(())
}

/// The defaults of a spec list.
pub fn defaults(specs: &[ModelParam]) -> Vec<f64> {
    specs.iter().map(|p| p.default).collect()
}

/// The defaults of `specs` with `overrides` (name, value) applied, in declaration order.
/// An unknown name is [`LtiError::UnknownParameter`] naming `model` and the known parameters;
/// the values themselves are checked by the model's constructor.
///
/// ```
/// use ltikit::nonlinear::models::MEMS_PARAMS;
/// use ltikit::lti::params::with_overrides;
/// let v = with_overrides("mems", MEMS_PARAMS, &[("v".into(), 2.5)]).unwrap();
/// assert_eq!(v[7], 2.5);
/// assert!(with_overrides("mems", MEMS_PARAMS, &[("Q".into(), 1.0)]).is_err());
/// ```
pub fn with_overrides(
    model: &str,
    specs: &[ModelParam],
    overrides: &[(String, f64)],
) -> Result<Vec<f64>> {
    let mut values = defaults(specs);
    for (k, v) in overrides {
        let i =
            specs
                .iter()
                .position(|p| p.name == k)
                .ok_or_else(|| LtiError::UnknownParameter {
                    model: model.into(),
                    name: k.clone(),
                    known: if specs.is_empty() {
                        "none".into()
                    } else {
                        specs.iter().map(|p| p.name).collect::<Vec<_>>().join(", ")
                    },
                })?;
        values[i] = *v;
    }
    Ok(values)
}

/// `(name, value)` pairs for reporting.
pub fn named(specs: &[ModelParam], values: &[f64]) -> Vec<(String, f64)> {
    specs
        .iter()
        .zip(values)
        .map(|(p, v)| (p.name.to_string(), *v))
        .collect()
}

/// Shorthand constructor for the static tables.
pub(crate) const fn param(
    name: &'static str,
    default: f64,
    unit: &'static str,
    description: &'static str,
    constraint: Constraint,
) -> ModelParam {
    ModelParam {
        name,
        default,
        unit,
        description,
        constraint,
    }
}
