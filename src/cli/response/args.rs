//! The options of `ltikit response`.

use clap::Args;

use crate::cli::PlantArgs;

/// `ltikit response`: the plant, the input (a standard one, or a signal from a file), initial
/// conditions (ODE or states), the times, and what to print.
#[derive(Args, Debug)]
pub struct ResponseArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// Input: impulse, step, ramp, exp:A (e^(A t)), sin:W, cos:W, or none (initial conditions
    /// only).
    #[arg(long, default_value = "step", allow_hyphen_values = true)]
    pub input: String,
    /// ODE initial conditions "y(0) y'(0) …" (input zero for t < 0; missing ones are 0); for a
    /// discrete-time plant (--dt) those of its difference equation, `y[-1] y[-2] …`.
    #[arg(long, value_name = "VALUES", allow_hyphen_values = true)]
    pub ic: Option<String>,
    /// Times (s, ≥ 0) at which to report values, e.g. --t "0 0.5 1 2" (a discrete-time plant:
    /// the sample at or before each time). Default: 11 points over an automatic window.
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub t: Option<String>,
    /// Print one JSON document: {"closed_form", "t", "y", "transient", "steady_state"} (a
    /// state-space response: see docs/ARCHITECTURE.md, "MIMO plants").
    #[arg(long)]
    pub json: bool,
    /// Initial state x(0) of a state-space plant, "x1 x2 …" (added to the response; with
    /// --input none the free response).
    #[arg(long, value_name = "VALUES", allow_hyphen_values = true)]
    pub x0: Option<String>,
    /// Include the state trajectories (state-space plants).
    #[arg(long)]
    pub states: bool,
    /// Simulate an input signal from a CSV file (lsim): columns t, u1 … um, one sample a line
    /// (an optional header line); values at the file's times. At most 1 000 000 samples.
    #[arg(long, value_name = "FILE.csv", conflicts_with = "t")]
    pub input_file: Option<std::path::PathBuf>,
    /// How the --input-file signal moves between samples: zoh (held) or foh (linear).
    #[arg(long, default_value = "zoh", value_name = "zoh|foh")]
    pub hold: String,
}
