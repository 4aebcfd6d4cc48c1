//! Controller and estimator design on state-space models: pole placement, the
//! linear-quadratic regulator, the Kalman filter gain and the LQG controller.
//!
//! | task | function | result |
//! |---|---|---|
//! | put the eigenvalues of A − BK at given places | [`place()`], [`place_matrices`] | [`Placement`] |
//! | state feedback minimising a quadratic cost (CARE, or DARE for a discrete plant) | [`lqr()`] | [`Lqr`] |
//! | the Kalman estimator gain from noise covariances (the dual Riccati equation) | [`lqe`] | [`Kalman`] |
//! | an LQR on a Kalman estimate, as a state-space controller | [`lqg()`] | [`Lqg`] |
//!
//! Sign convention: state feedback is u = −K x (MATLAB's `place`, `lqr`), so the closed loop
//! is A − BK; the estimator's error dynamics are A − LC; the LQG controller H is used in
//! negative feedback, u = −H y. A discrete plant (x\[k+1\] = A x\[k\] + B u\[k\]) uses the
//! same algebra (pole placement) or the discrete Riccati equation (LQR, Kalman).

pub mod kalman;
pub(crate) mod knv;
pub mod lqg;
pub mod lqr;
pub mod place;
pub mod poles;
mod riccati;
mod weights;

pub use kalman::{Kalman, NoiseInput, lqe};
pub use lqg::{Lqg, compensator, lqg};
pub use lqr::{Lqr, lqr};
pub use place::{Placement, PlacementMethod, place, place_matrices};
pub use poles::parse_poles;
