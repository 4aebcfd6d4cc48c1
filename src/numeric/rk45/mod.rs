//! Adaptive Dormand–Prince 5(4) integrator with dense output (MATLAB's `ode45`).
//!
//! # Method
//! The explicit Runge–Kutta pair of Dormand and Prince (1980), seven stages with the FSAL
//! property (the last stage of an accepted step is the first of the next, so a step costs six
//! evaluations of f), local extrapolation (the 5th-order solution is propagated, the embedded
//! 4th-order one only estimates the error), and the step-size controller of Hairer–Nørsett–
//! Wanner's `DOPRI5` (error in the root-mean-square norm scaled by `atol + rtol·|x|`, safety
//! factor 0.9, growth limited to ×10 and shrinkage to ×0.2 per step, Lund stabilisation
//! β = 0.04, no growth right after a rejection).
//!
//! **Dense output** is Hairer's 4th-order continuous extension of the same step (coefficients
//! `d₁ … d₇`, no extra evaluations of f): between the mesh points the solution is a quartic in
//! θ = (t − tₙ)/h that matches xₙ, xₙ₊₁ and both derivatives. Requested sample times are
//! interpolated, so they never shorten the steps — this is how `ode45` fills its `tspan`
//! (python-control and scipy do the same). Use [`integrate`] with an observer for events (zero
//! crossings are found by Brent's method on the interpolant).
//!
//! # Failure modes (errors, never panics)
//! - the state leaves the finite numbers or exceeds [`DIVERGENCE_LIMIT`] in magnitude →
//!   [`LtiError::Diverged`](crate::LtiError::Diverged) with the time and the size reached;
//! - the step size falls below 16·eps·|t| (MATLAB's minimum): at a finite-time singularity
//!   (ẋ = x² from x(0) = 1 blows up at t = 1) the state has grown by orders of magnitude and
//!   this is reported as [`LtiError::Diverged`](crate::LtiError::Diverged); otherwise (a discontinuous or non-finite right
//!   hand side) as [`LtiError::Undefined`](crate::LtiError::Undefined);
//! - more than `max_steps` attempted steps → [`LtiError::StepLimit`](crate::LtiError::StepLimit);
//! - bad options, non-finite initial state, `t_end ≤ t0` → `InvalidParameter`, `NonFinite`,
//!   `InvalidTime`.

mod dense;
mod integration;
mod options;
mod solve;
mod stepper;
mod tableau;

pub use dense::DenseStep;
pub use integration::{DIVERGENCE_LIMIT, Rk45Outcome, Rk45Stats, StepControl, integrate};
pub use options::{MIN_RTOL, Rk45Options};
pub use solve::{Rk45Solution, check_sample_times, solve};
