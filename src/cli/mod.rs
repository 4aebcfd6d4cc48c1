//! The `ltikit` command line: argument parsing, text reports and JSON output. The only layer
//! that prints. Errors go to stderr as one line with exit code 1 (2 for usage errors).

mod analyze;
mod balred;
mod batch;
mod c2d;
mod channels;
mod commands;
mod connect;
mod delayed;
mod demo;
mod design;
mod equations;
mod eval;
mod exit;
mod freq;
mod gangof4;
mod gram;
mod help;
mod input_file;
mod jury;
mod linearize;
mod lqr;
mod margins;
mod norm;
mod output;
mod pade;
mod parse;
mod place;
mod plant;
mod plots;
mod pullin;
mod residue;
mod response;
mod rlocus;
mod routh;
mod sigma;
mod simulate;
mod table_args;
mod text;

pub use crate::lti::Plant;
pub(crate) use commands::png_path;
pub use commands::{Cli, command, run_from};
pub use exit::{FIELD_FLAGS, UsageError, error_line, flag_of, flags_for_fields, main};
pub(crate) use exit::{one_line, warn};
pub use plant::PlantArgs;
