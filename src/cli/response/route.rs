//! The one dispatch of `ltikit response`: what the plant is and what is asked decide, before
//! anything is computed, whether the closed form of the factored plant or the exact
//! discretisation of its state-space model answers.

use anyhow::{Result, bail};

use super::args::ResponseArgs;
use super::{closed_form, state_space};
use crate::analysis::MAX_FACTORED_ORDER;
use crate::cli::{Plant, UsageError};
use crate::lti::{MAX_STATES, Model};

// Every state-space model lti accepts can be factored (`Factored::from_state_space` takes up
// to MAX_FACTORED_ORDER states), so no plant needs the state-space way for its size alone; a
// failure to factor is reported as the error it is. Raising MAX_STATES beyond it needs a route.
const _: () = assert!(MAX_STATES <= MAX_FACTORED_ORDER);

/// How `response` computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Route {
    /// The closed form and exact samples of a SISO plant (a transfer function, one channel,
    /// or a loop) from its factored form; ODE initial conditions with `--ic`.
    ClosedForm,
    /// Exact discretisation of the state-space model (a transfer function is realised first):
    /// a MIMO model as a whole, initial states (`--x0`), the states (`--states`), an input
    /// signal from a file (`--input-file`).
    StateSpace,
}

/// The route for `plant` and the options `a`: the state-space way when an option only it
/// answers is given or a MIMO state-space model is asked as a whole; the closed form
/// otherwise. Errors: `--ic` on the state-space way; state-space options with a loop (they
/// would simulate the plant without its controller).
fn route(a: &ResponseArgs, plant: &Plant) -> Result<Route> {
    let state_options = a.x0.is_some() || a.states || a.input_file.is_some();
    if let Some(which) = plant.selection {
        if state_options {
            return Err(UsageError(format!(
                "--x0, --states and --input-file simulate the plant's own state-space model, \
                 not the loop {}: leave them out for the loop's closed-form response",
                which.formula()
            ))
            .into());
        }
        return Ok(Route::ClosedForm);
    }
    let whole_mimo =
        matches!(plant.model, Model::Ss(_)) && !plant.model.is_siso() && a.plant.channel.is_none();
    if !(state_options || whole_mimo) {
        return Ok(Route::ClosedForm);
    }
    if a.ic.is_some() {
        bail!("--ic gives ODE initial conditions of a transfer function; for state space use --x0");
    }
    Ok(Route::StateSpace)
}

/// Runs `ltikit response`.
pub fn run(a: &ResponseArgs) -> Result<()> {
    let plant = a.plant.single()?;
    if let Some(dl) = crate::cli::delayed::of(&a.plant, &plant)? {
        if a.ic.is_some() || a.x0.is_some() || a.states || a.input_file.is_some() {
            bail!(
                "a loop around a dead time responds from rest to a standard input: leave out \
                 --ic, --x0, --states and --input-file"
            );
        }
        let input: crate::analysis::Input = a.input.parse()?;
        let t =
            a.t.as_deref()
                .map(|s| crate::cli::parse::numbers(s, "--t"))
                .transpose()?;
        return crate::cli::delayed::response(&plant, &dl, &input, t, a.json);
    }
    match route(a, &plant)? {
        Route::ClosedForm => closed_form::run(a, &plant),
        Route::StateSpace => state_space::run(a, &plant),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        a: ResponseArgs,
    }

    /// The route of a command line: the arguments after `response`, given as groups.
    fn route_of(groups: &[&[&str]]) -> Result<Route> {
        let args = groups.iter().flat_map(|g| g.iter().copied());
        let cli = Cli::try_parse_from(std::iter::once("response").chain(args))?;
        let plant = cli.a.plant.single()?;
        route(&cli.a, &plant)
    }

    #[test]
    fn one_dispatch_on_the_plant_and_the_options() {
        use Route::{ClosedForm, StateSpace};
        let tf: &[&str] = &["--den", "1 2 1"];
        let siso: &[&str] = &["--a", "0 1; -4 -0.8", "--b", "0; 4", "--c", "1 0"];
        let mimo: &[&str] = &[
            "--a",
            "-1 0.5; 0.5 -2",
            "--b",
            "1 0; 0 1",
            "--c",
            "1 0; 0 1",
        ];
        let cases: [(&[&[&str]], Route); 7] = [
            (&[tf], ClosedForm),
            (&[tf, &["--ic", "1 0"]], ClosedForm),
            (&[tf, &["--x0", "1 0"]], StateSpace),
            (&[siso], ClosedForm),
            (&[siso, &["--states"]], StateSpace),
            (&[mimo], StateSpace),
            (&[mimo, &["--channel", "1,2"]], ClosedForm),
        ];
        for (args, want) in cases {
            assert_eq!(route_of(args).unwrap(), want, "{args:?}");
        }
        // --ic on the state-space way is refused, not ignored
        let e = route_of(&[mimo, &["--ic", "1"]]).unwrap_err();
        assert!(e.to_string().contains("--x0"), "{e}");
        // a loop is answered in closed form; the plant's own states would drop the controller
        let pid: &[&str] = &["--controller", "p:kp=5"];
        assert_eq!(route_of(&[tf, pid]).unwrap(), ClosedForm);
        let e = route_of(&[tf, pid, &["--states"]]).unwrap_err();
        assert!(e.downcast_ref::<UsageError>().is_some(), "{e}");
        assert!(e.to_string().contains("T = L/(1 + L)"), "{e}");
    }
}
