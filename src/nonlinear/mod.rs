//! Nonlinear models ẋ = f(x, u), y = h(x, u): equilibria, exact linearisation, local
//! stability, simulation (seed chapter 2).
//!
//! # Conventions
//! - States, inputs and outputs are plain `f64` slices in the model's declared order
//!   ([`SystemInfo::state_names`]); the seed's models fix these orders (DESIGN §4):
//!   `pendulum` x = [θ, θ̇], u = \[τ\], y = θ; `mems` x = [l, l̇, q], u = \[v\], y = l; `lorenz`
//!   x = [x₁, x₂, x₃], no input, y = x; `vanderpol` x = [x₁, x₂], no input, y = x;
//!   `rigid-body` x = Π; `heavy-top` x = [Γ, Ω]; `gyroscope` x = [θ₁, θ₂, θ̇₁, θ̇₂, Ω₃],
//!   u = [u₁, u₂, u₃], y = [θ₁, θ₂]; `double-pendulum` x = [θ₁, θ₂, θ̇₁, θ̇₂], u = \[τ\],
//!   y = [θ₁, θ₂].
//! - Angles in rad, time in s, SI units for parameters ([`ModelParam::unit`]).
//! - Jacobians are exact: models are generic over the scalar type ([`Scalar`]) and are
//!   differentiated by forward-mode automatic differentiation (num-dual), like ForwardDiff in
//!   ControlSystems.jl — never by finite differences.
//! - Matrices in JSON are arrays of rows; complex numbers `[re, im]`.
//!
//! # Pieces
//! | concept | items |
//! |---|---|
//! | model traits | [`SystemInfo`], [`NonlinearSystem`], [`DynSystem`], [`jacobians`] |
//! | seed models | [`models`](mod@models): [`models::Pendulum`], [`models::Mems`], [`models::Lorenz`], [`models::VanDerPol`], [`models::LinearModel`] |
//! | mechanics (seed ch. 1–2) | [`models::RigidBody`], [`models::HeavyTop`], [`models::Gyroscope`], [`models::DoublePendulum`]; closed-form rigid-body motion [`FreeRigidMotion`] |
//! | conserved quantities | [`SystemInfo::conserved_names`], [`conserved_quantities`], [`energy_casimir()`] (Lyapunov stability of centres), drift along [`Simulation::conserved`] |
//! | special functions | [`elliptic`](mod@elliptic): K, F, Carlson's R_F, Jacobi sn/cn/dn |
//! | sensitivity | [`lyapunov_exponent`], [`finite_time_exponent`], [`divergence`] |
//! | registry | [`model_names`], [`model_info`], [`build_model`] |
//! | equilibria | [`equilibria()`], [`newton_equilibria`] |
//! | linearisation | [`linearize()`], [`linearize_at`], [`local_stability`] |
//! | feedback | [`StateFeedback`]: a model under u = ū + v − K(x − x̄), optionally saturated |
//! | simulation | [`simulate()`], [`InputSignal`] (built on [`crate::analysis::Input`]), [`sample_times`] (Dormand–Prince in [`crate::numeric::rk45`]) |
//! | picture data | [`trajectories`], [`pendulum_separatrices`], [`lorenz_divergence`], [`mems_pullin`], [`pendulum_periods`] |

pub mod chaos;
pub mod elliptic;
pub mod energy_casimir;
pub mod equilibria;
pub mod feedback;
pub mod linearize;
pub mod models;
pub mod period;
pub mod portraits;
pub mod pullin;
pub mod registry;
pub mod rigid_motion;
pub mod signal;
pub mod simulate;
pub mod system;

pub use crate::lti::params::{Constraint, ModelParam};
pub use chaos::{ExponentFit, LyapunovEstimate, finite_time_exponent, lyapunov_exponent};
pub use energy_casimir::{EnergyCasimir, Extremum, energy_casimir};
pub use equilibria::{
    Equilibrium, EquilibriumMethod, EquilibriumSearch, equilibria, newton_equilibria, residual,
};
pub use feedback::StateFeedback;
pub use linearize::{
    ChannelTf, Linearization, LinearizedEquilibrium, LinearizedTf, LocalStability,
    analyze_equilibrium, linearize, linearize_at, local_stability,
};
pub use period::{
    PeriodPoint, agm, elliptic_k, pendulum_period_exact, pendulum_period_simulated,
    pendulum_periods,
};
pub use portraits::{
    Divergence, divergence, lorenz_divergence, pendulum_energy, pendulum_separatrices, trajectories,
};
pub use pullin::{PullInDiagram, find_pull_in, mems_pullin};
pub use registry::{ModelInfo, ModelKind, build_model, model_info, model_names, models};
pub use rigid_motion::FreeRigidMotion;
pub use signal::InputSignal;
pub use simulate::{
    ConservedDrift, SampleSink, Simulation, SimulationStop, SimulationSummary, check_kept_values,
    sample_times, simulate, simulate_each,
};
pub use system::{
    BoxedSystem, Derivatives2, DynSystem, Jacobians, NonlinearSystem, Scalar, SystemInfo,
    check_point, conserved_quantities, derivative, jacobians,
};
