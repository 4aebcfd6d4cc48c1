//! The linear textbook plants of the seed (DESIGN §4) as transfer functions of their physical
//! parameters.
//!
//! | name | seed | input → output | G(s) |
//! |---|---|---|---|
//! | `spring-mass-damper` | eq. 3.19 | force f → position y | 1 / (M s² + C s + K) |
//! | `second-order` | eq. 3.20 (M = 1) | u → y | 1 / (s² + 2ζωₙ s + ωₙ²) |
//! | `tank` | eq. 3.5 | inflow qᵢ → level h | 1 / (A s + r) |
//! | `rc` | eq. 2.7 | source v → capacitor voltage | 1 / (R C s + 1) |
//! | `rlc` | exercise 2.6 | source v → capacitor voltage | 1 / (L C s² + R C s + 1) |
//! | `two-dof` | exercise 3.3 | force f on m₁ → position x₂ | (C s + K₂) / Δ(s) |
//!
//! For `two-dof` (fig. 3.6 is not reproduced in the notes) we take the usual arrangement:
//! m₁ is tied to the wall by K₁, the masses are coupled by K₂ in parallel with the damper C
//! (force proportional to the separation velocity, as the exercise says), the force acts on m₁:
//! m₁ẍ₁ = f − K₁x₁ − K₂(x₁ − x₂) − C(ẋ₁ − ẋ₂), m₂ẍ₂ = K₂(x₁ − x₂) + C(ẋ₁ − ẋ₂), so
//! Δ(s) = (m₁s² + Cs + K₁ + K₂)(m₂s² + Cs + K₂) − (Cs + K₂)².

use crate::error::{LtiError, Result};
use crate::lti::TransferFunction;
use crate::lti::params::{
    Constraint, ModelParam, check_values, defaults, named, param, with_overrides,
};
use crate::poly::Poly;

/// A named linear plant.
#[derive(Debug, Clone, Copy)]
pub struct PlantSpec {
    /// Name (`--model NAME`).
    pub name: &'static str,
    /// One-line title.
    pub title: &'static str,
    /// Where it comes from in the seed.
    pub source: &'static str,
    /// The ODE in words.
    pub ode: &'static str,
    /// Input signal and unit.
    pub input: &'static str,
    /// Output signal and unit.
    pub output: &'static str,
    /// Parameters in order.
    pub params: &'static [ModelParam],
    build: fn(&[f64]) -> Result<TransferFunction>,
}

impl PlantSpec {
    /// Builds the transfer function from parameter values given in the order of `params`.
    pub fn build(&self, values: &[f64]) -> Result<TransferFunction> {
        check_values(self.params, values)?;
        (self.build)(values)
    }

    /// The default parameter values.
    pub fn defaults(&self) -> Vec<f64> {
        defaults(self.params)
    }
}

const fn p(
    name: &'static str,
    default: f64,
    unit: &'static str,
    description: &'static str,
    positive: bool,
) -> ModelParam {
    param(
        name,
        default,
        unit,
        description,
        if positive {
            Constraint::Positive
        } else {
            Constraint::NonNegative
        },
    )
}

fn tf(num: &[f64], den: &[f64]) -> Result<TransferFunction> {
    TransferFunction::from_descending(num, den)
}

static PLANTS: &[PlantSpec] = &[
    PlantSpec {
        name: "spring-mass-damper",
        title: "Forced spring–mass–damper",
        source: "seed eq. 3.19 (and 2.10)",
        ode: "M y'' + C y' + K y = f",
        input: "force f [N]",
        output: "position y [m]",
        params: &[
            p("M", 1.0, "kg", "mass", true),
            p("C", 0.4, "N·s/m", "viscous damping", false),
            p("K", 4.0, "N/m", "spring stiffness", true),
        ],
        build: |v| tf(&[1.0], &[v[0], v[1], v[2]]),
    },
    PlantSpec {
        name: "second-order",
        title: "Standard second-order system",
        source: "seed eq. 3.20 with M = 1 (and 2.11)",
        ode: "y'' + 2 zeta wn y' + wn^2 y = u",
        input: "u",
        output: "y",
        params: &[
            p("wn", 1.0, "rad/s", "natural frequency", true),
            p("zeta", 0.5, "1", "damping ratio", false),
        ],
        build: |v| tf(&[1.0], &[1.0, 2.0 * v[1] * v[0], v[0] * v[0]]),
    },
    PlantSpec {
        name: "tank",
        title: "Single water tank",
        source: "seed eq. 3.5",
        ode: "A h' + r h = q_i",
        input: "inflow q_i [m³/s]",
        output: "level h [m]",
        params: &[
            p("A", 2.0, "m²", "cross-sectional area", true),
            p("r", 0.5, "m²/s", "outflow coefficient (q_o = r h)", true),
        ],
        build: |v| tf(&[1.0], &[v[0], v[1]]),
    },
    PlantSpec {
        name: "rc",
        title: "RC circuit",
        source: "seed eq. 2.7 (exercise 2.5 values)",
        ode: "R C v_c' + v_c = v",
        input: "source voltage v [V]",
        output: "capacitor voltage v_c = q/C [V]",
        params: &[
            p("R", 1.0, "Ω", "resistance", true),
            p("C", 2.0, "F", "capacitance", true),
        ],
        build: |v| tf(&[1.0], &[v[0] * v[1], 1.0]),
    },
    PlantSpec {
        name: "rlc",
        title: "Series RLC circuit",
        source: "seed exercise 2.6 (fig. 2.19)",
        ode: "L C v_c'' + R C v_c' + v_c = v",
        input: "source voltage v [V]",
        output: "capacitor voltage v_c [V]",
        params: &[
            p("R", 10.0, "Ω", "resistance", false),
            p("L", 0.1, "H", "inductance", true),
            p("C", 1e-3, "F", "capacitance", true),
        ],
        build: |v| tf(&[1.0], &[v[1] * v[2], v[0] * v[2], 1.0]),
    },
    PlantSpec {
        name: "two-dof",
        title: "Two-degree-of-freedom spring–mass–damper",
        source: "seed exercise 3.3 (fig. 3.6)",
        ode: "M1 x1'' = f - K1 x1 - K2 (x1 - x2) - C (x1' - x2'), M2 x2'' = K2 (x1 - x2) + C (x1' - x2')",
        input: "force f on m1 [N]",
        output: "position x2 [m]",
        params: &[
            p("M1", 1.0, "kg", "first mass", true),
            p("M2", 2.0, "kg", "second mass", true),
            p("K1", 1.0, "N/m", "wall spring", true),
            p("K2", 1.5, "N/m", "coupling spring", true),
            p("C", 0.3, "N·s/m", "coupling damper", false),
        ],
        build: |v| {
            let (m1, m2, k1, k2, c) = (v[0], v[1], v[2], v[3], v[4]);
            let a = Poly::from_descending(&[m1, c, k1 + k2])?;
            let b = Poly::from_descending(&[m2, c, k2])?;
            let coupling = Poly::from_descending(&[c, k2])?;
            let den = &(&a * &b) - &(&coupling * &coupling);
            TransferFunction::new(coupling, den)
        },
    },
];

/// All linear textbook plants.
pub fn plant_specs() -> &'static [PlantSpec] {
    PLANTS
}

/// The plant called `name`, or [`LtiError::UnknownModel`].
pub fn plant_spec(name: &str) -> Result<&'static PlantSpec> {
    PLANTS
        .iter()
        .find(|p| p.name == name)
        .ok_or_else(|| LtiError::UnknownModel {
            name: name.into(),
            known: PLANTS.iter().map(|p| p.name).collect::<Vec<_>>().join(", "),
        })
}

/// Builds plant `name` from its defaults overridden by `overrides` (name, value); returns the
/// transfer function and the parameter values used, in order.
///
/// ```
/// use ltikit::lti::build_plant;
/// let (g, used) = build_plant("spring-mass-damper", &[("C".into(), 0.8)]).unwrap();
/// assert_eq!(g.den().coeffs(), &[1.0, 0.8, 4.0]);
/// assert_eq!(used[1], ("C".to_string(), 0.8));
/// assert!(build_plant("spring-mass-damper", &[("Q".into(), 1.0)]).is_err());
/// ```
pub fn build_plant(
    name: &str,
    overrides: &[(String, f64)],
) -> Result<(TransferFunction, Vec<(String, f64)>)> {
    let spec = plant_spec(name)?;
    let values = with_overrides(spec.name, spec.params, overrides)?;
    let g = spec.build(&values)?;
    Ok((g, named(spec.params, &values)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_plant_builds_with_defaults() {
        for spec in plant_specs() {
            let g = spec.build(&spec.defaults()).unwrap();
            assert!(g.order() >= 1, "{}", spec.name);
            assert!(g.is_strictly_proper(), "{}", spec.name);
        }
    }

    #[test]
    fn two_dof_static_gain() {
        // At s = 0: X2/F = K2 / ((K1+K2) K2 − K2²) = 1/K1.
        let (g, _) = build_plant("two-dof", &[("K1".into(), 2.0), ("K2".into(), 3.0)]).unwrap();
        let g0 = g.eval(num_complex::Complex64::new(0.0, 0.0)).re;
        assert!((g0 - 0.5).abs() < 1e-15);
        assert_eq!(g.order(), 4);
    }

    #[test]
    fn parameter_validation() {
        assert!(matches!(
            build_plant("tank", &[("A".into(), -1.0)]),
            Err(LtiError::InvalidParameter { .. })
        ));
        assert!(build_plant("spring-mass-damper", &[("C".into(), 0.0)]).is_ok());
        assert!(build_plant("spring-mass-damper", &[("M".into(), f64::NAN)]).is_err());
        assert!(matches!(
            build_plant("pendulum-x", &[]),
            Err(LtiError::UnknownModel { .. })
        ));
    }
}
