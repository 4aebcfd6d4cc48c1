//! The `lattice` model's parameters (`--param NAME=VALUE`) and their rules.

use super::{Boundary, Lattice, MAX_PARTICLES, Output, bad, integer};
use crate::error::{LtiError, Result};
use crate::lti::params::{Constraint, ModelParam, param, with_overrides};

/// The parameters of the `lattice` model (`--param NAME=VALUE`), in this order.
///
/// Non-numeric and integer parameters: `periodic` is 1 (periodic) or 0 (fixed ends); `N`,
/// `input` and `output` must be integers; `output = 0` measures all N displacements. ω0 comes
/// from `w0`, or from ω0² = αβ/m when `alpha` or `beta` is given (then `w0` must not be);
/// `m` also converts the force into an acceleration.
pub const LATTICE_PARAMS: &[ModelParam] = &[
    param(
        "N",
        128.0,
        "1",
        "number of moving particles (integer 2…512)",
        Constraint::Positive,
    ),
    param(
        "periodic",
        1.0,
        "1",
        "boundary: 1 periodic (ring), 0 fixed ends",
        Constraint::Any,
    ),
    param(
        "w0",
        1.0,
        "rad/s",
        "natural frequency ω0 = √(αβ/m)",
        Constraint::Positive,
    ),
    param(
        "alpha",
        1.0,
        "1",
        "α of φ(r) = αβr²/2 (αβ > 0)",
        Constraint::Any,
    ),
    param(
        "beta",
        1.0,
        "N/m",
        "β of φ(r) = αβr²/2 (αβ > 0)",
        Constraint::Any,
    ),
    param("m", 1.0, "kg", "particle mass", Constraint::Positive),
    param(
        "gamma",
        0.0,
        "1/s",
        "damping to the ground per unit mass",
        Constraint::NonNegative,
    ),
    param(
        "eta",
        0.0,
        "s",
        "spring-parallel damping time",
        Constraint::NonNegative,
    ),
    param(
        "input",
        1.0,
        "1",
        "particle the force acts on (1…N)",
        Constraint::Positive,
    ),
    param(
        "output",
        1.0,
        "1",
        "particle measured (1…N; 0 = all)",
        Constraint::NonNegative,
    ),
];

impl Lattice {
    /// The lattice from `--param` style overrides of [`LATTICE_PARAMS`] (the defaults for
    /// the rest).
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice, Output};
    /// let p = |k: &str, v: f64| (k.to_string(), v);
    /// let lat = Lattice::from_params(&[p("N", 16.0), p("periodic", 0.0), p("alpha", 2.0),
    ///                                  p("beta", 8.0), p("m", 4.0), p("output", 5.0)]).unwrap();
    /// assert_eq!((lat.n(), lat.boundary(), lat.w0()), (16, Boundary::Fixed, 2.0));
    /// assert_eq!(lat.output(), Output::Particle(5));
    /// let err = Lattice::from_params(&[p("N", 16.0), p("input", 17.0)]).unwrap_err();
    /// assert_eq!(err.to_string(), "parameter input = 17 is invalid: \
    ///                              the particle the force acts on must be an integer 1…16");
    /// ```
    pub fn from_params(overrides: &[(String, f64)]) -> Result<Lattice> {
        let v = with_overrides("lattice", LATTICE_PARAMS, overrides)?;
        let given = |name: &str| overrides.iter().any(|(k, _)| k == name);
        let n = integer("N", v[0], 2, MAX_PARTICLES, "the number of particles")?;
        let boundary = Boundary::from_flag(v[1])?;
        for (i, p) in LATTICE_PARAMS.iter().enumerate() {
            if !matches!(
                p.name,
                "N" | "periodic" | "alpha" | "beta" | "input" | "output"
            ) {
                p.check(v[i])?;
            }
        }
        let mass = v[5];
        let w0 = if given("alpha") || given("beta") {
            if given("w0") {
                return Err(LtiError::invalid(
                    "lattice: give either w0 or alpha and beta (ω0² = αβ/m), not both",
                ));
            }
            let (alpha, beta) = (v[3], v[4]);
            let ab = alpha * beta;
            if !(ab.is_finite() && ab > 0.0) {
                return Err(bad(
                    if given("alpha") { "alpha" } else { "beta" },
                    if given("alpha") { alpha } else { beta },
                    format!("αβ = {ab} must be > 0 (the springs must hold the lattice together)"),
                ));
            }
            (ab / mass).sqrt()
        } else {
            v[2]
        };
        let input = integer("input", v[8], 1, n, "the particle the force acts on")?;
        let output = if v[9] == 0.0 {
            Output::All
        } else {
            Output::Particle(integer(
                "output",
                v[9],
                1,
                n,
                "the measured particle (0 = all)",
            )?)
        };
        Lattice::new(n, boundary, w0)?
            .with_mass(mass)?
            .with_damping(v[6], v[7])?
            .with_input(input)?
            .with_output(output)
    }

    /// The parameters as (name, value) pairs for reports, in the order of [`LATTICE_PARAMS`]
    /// without `alpha` and `beta` (ω0 is reported as `w0`), so that
    /// [`Lattice::from_params`] rebuilds the same lattice from them.
    pub fn params(&self) -> Vec<(String, f64)> {
        let flag = f64::from(u8::from(self.boundary == Boundary::Periodic));
        let out = match self.output {
            Output::All => 0.0,
            Output::Particle(i) => i as f64,
        };
        [
            ("N", self.n as f64),
            ("periodic", flag),
            ("w0", self.w0),
            ("m", self.mass),
            ("gamma", self.gamma),
            ("eta", self.eta),
            ("input", self.input as f64),
            ("output", out),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect()
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // parameters are set exactly
    use super::*;

    fn p(k: &str, v: f64) -> (String, f64) {
        (k.to_string(), v)
    }

    #[test]
    fn errors_name_the_parameter() {
        let msg = |o: &[(String, f64)]| Lattice::from_params(o).unwrap_err().to_string();
        assert!(msg(&[p("N", 1.0)]).starts_with("parameter N = 1 is invalid"));
        assert!(msg(&[p("N", 4.5)]).contains("integer 2…512"));
        assert!(msg(&[p("w0", 0.0)]).starts_with("parameter w0 = 0 is invalid"));
        assert!(msg(&[p("w0", -1.0)]).starts_with("parameter w0 = -1 is invalid"));
        assert!(msg(&[p("periodic", 2.0)]).contains("1 (periodic) or 0 (fixed)"));
        assert!(msg(&[p("N", 8.0), p("output", 9.0)]).starts_with("parameter output = 9"));
        assert!(msg(&[p("input", 0.0)]).starts_with("parameter input = 0"));
        assert!(msg(&[p("alpha", -1.0)]).contains("αβ = -1 must be > 0"));
        assert!(msg(&[p("w0", 2.0), p("beta", 2.0)]).contains("not both"));
        assert!(msg(&[p("gamma", -0.1)]).starts_with("parameter gamma = -0.1"));
        assert!(msg(&[p("k", 1.0)]).contains("has no parameter 'k'"));
        assert!(msg(&[p("w0", 1e200)]).contains("normal"));
    }

    #[test]
    fn alpha_beta_give_w0_and_params_round_trip() {
        let lat = Lattice::from_params(&[p("alpha", 3.0), p("beta", 12.0), p("m", 4.0)]).unwrap();
        assert_eq!(lat.w0(), 3.0);
        let again = Lattice::from_params(&lat.params()).unwrap();
        assert_eq!(again, lat);
        let all = Lattice::from_params(&[p("output", 0.0)]).unwrap();
        assert_eq!(all.output(), Output::All);
    }
}
