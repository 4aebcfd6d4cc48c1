//! `ltikit response`: one command, one dispatch ([`route`]). A SISO plant (a transfer function,
//! one channel of a state-space model, or a loop with a controller) gets the closed-form y(t)
//! for a standard input and ODE initial conditions, its transient and steady-state parts and
//! exact values ([`closed_form`]); a MIMO state-space model as a whole, initial states, the
//! states and input signals from a file are answered by exact discretisation of the
//! state-space model ([`state_space`]).

mod args;
mod closed_form;
mod route;
mod state_space;

pub use args::ResponseArgs;
pub use route::run;
