//! The seed's models (DESIGN §4): `pendulum`, `mems`, `lorenz`, `vanderpol`, and the linear
//! textbook plants wrapped as [`LinearModel`].

pub mod linear;
pub mod lorenz;
pub mod mems;
pub mod pendulum;
pub mod vanderpol;

pub use linear::LinearModel;
pub use lorenz::{LORENZ_PARAMS, Lorenz};
pub use mems::{MEMS_PARAMS, Mems};
pub use pendulum::{PENDULUM_PARAMS, Pendulum};
pub use vanderpol::VanDerPol;
