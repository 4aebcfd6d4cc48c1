//! The discrete-time bench inputs (issue 20) shared by `benches/ltikit.rs` (module
//! `discrete`) and the timing example behind the python comparison
//! (`examples/bench_discrete_json.rs`, read by `benches/compare/compare_discrete.py`): the
//! periods, the sample count and the order-8 discrete plant G(z) of
//! `benches/compare/inputs.toml` (`[discrete]`), so both sides time identical inputs.
#![allow(dead_code)] // each including target uses a different subset

use ltikit::TransferFunction;
use ltikit::analysis::Factored;
use ltikit::lti::Domain;
use serde::Deserialize;

const INPUTS: &str = include_str!("../compare/inputs.toml");

#[derive(Deserialize)]
struct Inputs {
    discrete: Discrete,
}

/// The `[discrete]` table of inputs.toml.
#[derive(Deserialize)]
pub struct Discrete {
    /// The period of the order-8 plant's c2d.
    pub dt_order8: f64,
    /// The period of the lattice's c2d.
    pub dt_lattice: f64,
    /// Samples of the discrete step response.
    pub samples: usize,
    /// The order-8 discrete plant G(z): its period, numerator and denominator (descending
    /// powers of z).
    pub dt_z: f64,
    pub num_z: Vec<f64>,
    pub den_z: Vec<f64>,
}

/// The `[discrete]` inputs.
pub fn inputs() -> Discrete {
    toml::from_str::<Inputs>(INPUTS)
        .expect("benches/compare/inputs.toml parses")
        .discrete
}

/// The order-8 discrete plant as a transfer function in z.
pub fn plant_z() -> TransferFunction {
    let d = inputs();
    TransferFunction::from_descending(&d.num_z, &d.den_z)
        .expect("the discrete order-8 plant is valid")
        .with_domain(Domain::discrete(d.dt_z).expect("a valid period"))
}

/// The order-8 discrete plant factored.
pub fn factored_z() -> Factored {
    plant_z()
        .factored()
        .expect("the discrete order-8 plant factors")
}

/// The sample times k·T, k = 0 … samples − 1 (`scipy.signal.dstep(…, n = samples)`).
pub fn sample_times() -> Vec<f64> {
    let d = inputs();
    (0..d.samples).map(|k| k as f64 * d.dt_z).collect()
}
