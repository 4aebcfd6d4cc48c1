//! Controller and estimator design on state-space models: pole placement ([`place`]).
//!
//! | task | function | result |
//! |---|---|---|
//! | put the eigenvalues of A − BK at given places | [`place`], [`place_matrices`] | [`Placement`] |
//!
//! Sign convention: state feedback is u = −K x (MATLAB's `place`, `lqr`), so the closed loop
//! is A − BK. A discrete plant (x\[k+1\] = A x\[k\] + B u\[k\]) uses the same algebra.

pub(crate) mod knv;
pub mod place;
pub mod poles;

pub use place::{Placement, PlacementMethod, place, place_matrices};
pub use poles::parse_poles;
