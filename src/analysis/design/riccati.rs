//! The Riccati solvers the design functions use (one import to change at the merge).

pub(crate) use super::stub::{Riccati, care, dare};
