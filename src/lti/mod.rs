//! LTI models: transfer functions, state space, the textbook plants and plant files.

pub mod connect;
pub mod controller;
pub mod delay;
pub mod discretize;
pub mod domain;
pub mod interconnect;
pub mod lattice;
pub mod model;
pub mod params;
pub mod plant;
pub mod plants;
pub mod realize;
pub mod ss;
pub mod tf;

pub use controller::Controller;
pub use discretize::Discretization;
pub use domain::Domain;
pub use model::{MAX_STATES, Model, Signals};
pub use params::{Constraint, ModelParam};
pub use plant::{Plant, PlantFile};
pub use plants::{PlantSpec, build_plant, plant_spec, plant_specs};
pub use ss::StateSpace;
pub use tf::TransferFunction;
