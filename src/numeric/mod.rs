//! Numerical building blocks shared by the upper layers: tolerances, overflow-safe balancing
//! and power-of-two scaling, safe eigenvalues, scalar root bracketing, the matrix exponential and logarithm
//! and the Dormand–Prince integrator, and the one time-marching skeleton of the exact responses.
//!
//! Nothing here knows about transfer functions; everything works on plain `f64`,
//! [`Complex64`](num_complex::Complex64) and nalgebra matrices.

pub mod balance;
pub(crate) mod complex;
pub mod dd;
pub mod eig;
pub mod expm;
pub mod linalg;
pub mod logm;
pub mod lstsq;
pub(crate) mod march;
pub(crate) mod parallel;
pub mod rk45;
pub(crate) mod scalar;
#[cfg(test)]
pub(crate) mod test_rng;
pub mod tol;

pub use eig::{eigenvalues, eigenvalues_checked};
pub use expm::expm;
pub use logm::logm;
