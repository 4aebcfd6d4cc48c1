//! The Riccati solvers the design functions use: `numeric::linalg::{care, dare}`.

pub(crate) use crate::numeric::linalg::{Riccati, care, dare};
