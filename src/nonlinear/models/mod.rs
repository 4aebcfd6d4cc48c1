//! The seed's models (DESIGN §4): `pendulum`, `mems`, `lorenz`, `vanderpol`, the mechanical
//! systems of chapters 1–2 (`rigid-body`, `heavy-top`, `gyroscope`, `double-pendulum`), and
//! the linear textbook plants wrapped as [`LinearModel`].

pub mod double_pendulum;
pub mod gyroscope;
pub mod heavy_top;
pub mod linear;
pub mod lorenz;
pub mod mems;
pub mod pendulum;
pub mod rigid_body;
pub mod vanderpol;

pub use double_pendulum::{DOUBLE_PENDULUM_PARAMS, DoublePendulum};
pub use gyroscope::{GYROSCOPE_PARAMS, Gyroscope, GyroscopeDiscFrame};
pub use heavy_top::{HEAVY_TOP_PARAMS, HeavyTop};
pub use linear::LinearModel;
pub use lorenz::{LORENZ_PARAMS, Lorenz};
pub use mems::{MEMS_PARAMS, Mems};
pub use pendulum::{PENDULUM_PARAMS, Pendulum};
pub use rigid_body::{AxisKind, RIGID_BODY_PARAMS, RigidBody};
pub use vanderpol::VanDerPol;
