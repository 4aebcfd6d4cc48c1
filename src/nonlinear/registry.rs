//! Models by name: the nonlinear models of the seed and the linear textbook plants, with their
//! parameter specifications, built with `(name, value)` overrides of the defaults.

use serde::Serialize;

use crate::error::{LtiError, Result};
use crate::lti::params::{ModelParam, with_overrides};
use crate::lti::plant_specs;
use crate::nonlinear::models::{
    DOUBLE_PENDULUM_PARAMS, DoublePendulum, GYROSCOPE_PARAMS, Gyroscope, HEAVY_TOP_PARAMS,
    HeavyTop, LORENZ_PARAMS, LinearModel, Lorenz, MEMS_PARAMS, Mems, PENDULUM_PARAMS, Pendulum,
    RIGID_BODY_PARAMS, RigidBody, VanDerPol,
};
use crate::nonlinear::system::BoxedSystem;

/// Whether a model is nonlinear or a linear plant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ModelKind {
    /// One of the seed's nonlinear models.
    Nonlinear,
    /// A linear textbook plant (`lti::plant_specs`).
    Linear,
}

/// What the registry knows about a model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelInfo {
    /// Registry name.
    pub name: &'static str,
    /// One-line title.
    pub title: &'static str,
    /// Where it comes from in the seed.
    pub source: &'static str,
    /// The equations in words.
    pub equations: &'static str,
    /// Nonlinear model or linear plant.
    pub kind: ModelKind,
    /// Parameters in order.
    pub params: Vec<ModelParam>,
}

struct NonlinearSpec {
    name: &'static str,
    title: &'static str,
    source: &'static str,
    equations: &'static str,
    params: &'static [ModelParam],
    build: fn(&[f64]) -> Result<BoxedSystem>,
}

static NONLINEAR: &[NonlinearSpec] = &[
    NonlinearSpec {
        name: "pendulum",
        title: "Rigid pendulum with viscous friction and torque input",
        source: "seed eqs. 2.15–2.18",
        equations: "theta'' = -(3C/(M L^2)) theta' - (3g/(2L)) sin(theta) + 3 tau/(M L^2); x = [theta, theta'], u = [tau], y = theta",
        params: PENDULUM_PARAMS,
        build: |v| Ok(Box::new(Pendulum::from_values(v)?)),
    },
    NonlinearSpec {
        name: "mems",
        title: "Electrostatic MEMS mirror driven through a resistor",
        source: "seed exercises 1.4, 2.11",
        equations: "m l'' = -k (l - l0) - b l' - q^2/(2 eps A), R q' = v - q l/(eps A); x = [l, l', q], u = [v], y = l",
        params: MEMS_PARAMS,
        build: |v| Ok(Box::new(Mems::from_values(v)?)),
    },
    NonlinearSpec {
        name: "lorenz",
        title: "Lorenz weather model",
        source: "seed eqs. 2.38–2.40, exercise 2.10",
        equations: "x1' = sigma (x2 - x1), x2' = r x1 - x2 - x1 x3, x3' = x1 x2 - b x3; no input, y = x",
        params: LORENZ_PARAMS,
        build: |v| Ok(Box::new(Lorenz::from_values(v)?)),
    },
    NonlinearSpec {
        name: "vanderpol",
        title: "Oscillator with the unit circle as limit cycle (the seed's van der Pol form)",
        source: "seed eqs. 2.36–2.37, exercise 2.9",
        equations: "x1' = -x2 - x1 (x1^2 + x2^2 - 1), x2' = x1 - x2 (x1^2 + x2^2 - 1); no input, y = x",
        params: &[],
        build: |_| Ok(Box::new(VanDerPol)),
    },
    NonlinearSpec {
        name: "rigid-body",
        title: "Free rigid body in body angular momentum",
        source: "seed eqs. 2.44, 2.48–2.53, 2.82–2.87",
        equations: "Pi' = Pi x I^-1 Pi, I = diag(I1, I2, I3): Pi1' = (I2-I3)/(I2 I3) Pi2 Pi3, cyclic; x = Pi, no input, y = Pi; conserved E = sum Pi_i^2/(2 I_i), |Pi|^2",
        params: RIGID_BODY_PARAMS,
        build: |v| Ok(Box::new(RigidBody::from_values(v)?)),
    },
    NonlinearSpec {
        name: "heavy-top",
        title: "Axi-symmetric heavy top",
        source: "seed eqs. 1.101–1.102, 2.63–2.67",
        equations: "Gamma' = Gamma x Omega, I Omega' = I Omega x Omega + m g l Gamma x e3, I = diag(I1, I1, I3); x = [Gamma, Omega], no input, y = Gamma",
        params: HEAVY_TOP_PARAMS,
        build: |v| Ok(Box::new(HeavyTop::from_values(v)?)),
    },
    NonlinearSpec {
        name: "gyroscope",
        title: "Gimbal gyroscope (gimbal torques in, gimbal angles out)",
        source: "seed eqs. 1.103–1.107, exercise 2.14",
        equations: "Il s2^2 theta1'' = u1 - u3 c2 - 2 Il theta1' theta2' s2 c2 + Iz Omega3 theta2' s2, Il theta2'' = u2 + Il theta1'^2 s2 c2 - Iz Omega3 theta1' s2, Iz Omega3' = u3; x = [theta1, theta2, theta1', theta2', Omega3], u = [u1, u2, u3], y = [theta1, theta2]",
        params: GYROSCOPE_PARAMS,
        build: |v| Ok(Box::new(Gyroscope::from_values(v)?)),
    },
    NonlinearSpec {
        name: "double-pendulum",
        title: "Planar double pendulum (point masses on massless rods)",
        source: "seed example 1.1, fig. 1.4 (equations derived: §2.3.3 is blank)",
        equations: "M(theta) theta'' = r(theta, theta', tau) from the Lagrangian of two point masses (see the model docs); x = [theta1, theta2, theta1', theta2'], u = [tau] at the pivot, y = [theta1, theta2]",
        params: DOUBLE_PENDULUM_PARAMS,
        build: |v| Ok(Box::new(DoublePendulum::from_values(v)?)),
    },
];

/// All model names: the nonlinear models first, then the linear plants.
///
/// ```
/// let names = ltikit::nonlinear::model_names();
/// assert!(names.contains(&"pendulum") && names.contains(&"spring-mass-damper"));
/// ```
pub fn model_names() -> Vec<&'static str> {
    NONLINEAR
        .iter()
        .map(|s| s.name)
        .chain(plant_specs().iter().map(|p| p.name))
        .collect()
}

fn unknown(name: &str) -> LtiError {
    LtiError::UnknownModel {
        name: name.into(),
        known: model_names().join(", "),
    }
}

/// Name, source, equations and parameter specs of a model.
///
/// ```
/// let info = ltikit::nonlinear::model_info("mems").unwrap();
/// assert_eq!(info.params.iter().map(|p| p.name).collect::<Vec<_>>(),
///            ["eps", "A", "m", "k", "l0", "b", "R", "v"]);
/// assert!(ltikit::nonlinear::model_info("pendulum2").is_err());
/// ```
pub fn model_info(name: &str) -> Result<ModelInfo> {
    if let Some(s) = NONLINEAR.iter().find(|s| s.name == name) {
        return Ok(ModelInfo {
            name: s.name,
            title: s.title,
            source: s.source,
            equations: s.equations,
            kind: ModelKind::Nonlinear,
            params: s.params.to_vec(),
        });
    }
    let p = plant_specs()
        .iter()
        .find(|p| p.name == name)
        .ok_or_else(|| unknown(name))?;
    Ok(ModelInfo {
        name: p.name,
        title: p.title,
        source: p.source,
        equations: p.ode,
        kind: ModelKind::Linear,
        params: p.params.to_vec(),
    })
}

/// Every model's info.
pub fn models() -> Vec<ModelInfo> {
    model_names()
        .into_iter()
        .filter_map(|n| model_info(n).ok())
        .collect()
}

/// Builds model `name` from its defaults overridden by `overrides` (a later override of the
/// same name wins). Unknown model or parameter, non-finite or non-physical values → error.
///
/// ```
/// use ltikit::nonlinear::{build_model, SystemInfo};
/// let p = build_model("pendulum", &[("L".into(), 2.0)]).unwrap();
/// assert_eq!(p.params()[1], ("L".to_string(), 2.0));
/// assert!(build_model("pendulum", &[("L".into(), -1.0)]).is_err());
/// assert!(build_model("pendulum", &[("Q".into(), 1.0)]).is_err());
/// let smd = build_model("spring-mass-damper", &[]).unwrap();
/// assert_eq!(smd.nx(), 2);
/// ```
pub fn build_model(name: &str, overrides: &[(String, f64)]) -> Result<BoxedSystem> {
    let Some(spec) = NONLINEAR.iter().find(|s| s.name == name) else {
        if plant_specs().iter().any(|p| p.name == name) {
            return Ok(Box::new(LinearModel::from_plant(name, overrides)?));
        }
        return Err(unknown(name));
    };
    let values = with_overrides(spec.name, spec.params, overrides)?;
    (spec.build)(&values)
}
