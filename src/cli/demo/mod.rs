//! `ltikit demo`: the textbook tour. Analyses every textbook plant and the seed's nonlinear
//! models, verifies the results at run time, and writes `report.md` with its PNGs.
//!
//! [`tour`] runs the sections in order with a shared [`context`] (output directory, figures,
//! checks); each section renders its part of the report from the library's results and
//! records the checks that are the report's own ([`verify`]); [`md`] writes the Markdown.

mod cascade;
mod closed_loop;
mod context;
mod dead_time;
mod design;
mod digital;
mod lattice;
mod lattice_channel;
mod linear;
mod md;
mod mechanics;
mod nonlinear;
mod rlocus;
mod seed;
mod tour;
mod verify;

pub use tour::{DemoArgs, run};
