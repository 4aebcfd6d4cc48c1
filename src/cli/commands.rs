//! The command table: the `ltikit` parser (one variant per command, each with its own
//! arguments) and the dispatch to each command's `run`.

use anyhow::Result;
use clap::{Parser, Subcommand};

use super::{
    analyze, demo, freq, linearize, margins, plots, pullin, residue, response, rlocus, routh,
    simulate,
};

/// ltikit — LTI input-output models from ODE coefficients: exact poles and zeros, stability,
/// partial fractions and closed-form responses, frequency response, plots, nonlinear models.
///
/// Coefficients are given in descending powers of s: --den "1 0.8 4" is s^2 + 0.8 s + 4.
/// Frequencies in rad/s, phases in degrees, magnitudes as ratios and dB.
#[derive(Parser, Debug)]
#[command(name = "ltikit", version, about, long_about = None, max_term_width = 100)]
pub struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand, Debug)]
pub(crate) enum Command {
    /// Poles and zeros with multiplicities, cancellations, dc gain, stability with the reason,
    /// modes (wn, zeta, time constant), second-order class and step metrics.
    Analyze(analyze::AnalyzeArgs),
    /// Partial fractions r/(s − p)^k (repeated and complex poles) and the direct polynomial.
    Residue(residue::ResidueArgs),
    /// Closed-form y(t) for a standard input and ODE initial conditions; transient and
    /// steady-state parts; exact values at --t.
    Response(response::ResponseArgs),
    /// Frequency response: M(w), dB and the continuous phase at --w or on a log grid.
    Freq(freq::FreqArgs),
    /// Gain and phase margins (all crossings), bandwidth, resonant peak.
    Margins(margins::MarginsArgs),
    /// Routh–Hurwitz table of the characteristic polynomial (or of D + K·N with --gain K):
    /// right-half-plane and imaginary-axis root counts, zero-first-element and zero-row cases.
    Routh(routh::RouthArgs),
    /// Root locus of 1 + K·L (L = G, or C·G with --controller): asymptotes, break points,
    /// imaginary-axis crossings, departure/arrival angles, stable gains; PNG with -o.
    Rlocus(rlocus::RlocusArgs),
    /// Bode diagram PNG (magnitude and continuous phase, margins marked); several plants with
    /// repeated --num/--den or --plant.
    Bode(plots::BodeArgs),
    /// Step (or impulse, ramp) response PNG with rise time, settling band, peak and overshoot.
    Step(plots::StepArgs),
    /// Pole-zero map PNG (multiplicities, cancelled pairs, stable half plane).
    Pzmap(plots::PzmapArgs),
    /// Nyquist diagram PNG (−∞ < ω < ∞, indentations around imaginary-axis poles).
    Nyquist(plots::NyquistArgs),
    /// The main job: the textbook tour — analyses every plant and nonlinear model of the
    /// lecture notes, checks the results, writes out/report.md with its PNGs.
    Demo(demo::DemoArgs),
    /// Equilibria of a nonlinear model, A, B, C, D at each (exact Jacobians), eigenvalues,
    /// local stability and the linearised input→output transfer function.
    Linearize(linearize::LinearizeArgs),
    /// Simulate a nonlinear model (adaptive Dormand–Prince 5(4)); CSV or JSON, and a time
    /// plot or phase portrait with -o.
    Simulate(simulate::SimulateArgs),
    /// The MEMS pull-in diagram PNG: equilibrium gap against voltage.
    #[command(name = "mems-pullin")]
    MemsPullin(pullin::PullinArgs),
}

/// Runs a command line in this process — `args` as `main` would see them, the program name
/// first — and returns its error instead of printing it (for tests and embedding; the output
/// goes to stdout as usual).
///
/// ```no_run
/// ltikit::cli::run_from(["ltikit", "analyze", "--den", "1 2 1"]).unwrap();
/// ```
pub fn run_from<I, T>(args: I) -> Result<()>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    run(Cli::try_parse_from(args)?)
}

pub(crate) fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Analyze(a) => analyze::run(&a),
        Command::Residue(a) => residue::run(&a),
        Command::Response(a) => response::run(&a),
        Command::Freq(a) => freq::run(&a),
        Command::Margins(a) => margins::run(&a),
        Command::Routh(a) => routh::run(&a),
        Command::Rlocus(a) => rlocus::run(&a),
        Command::Bode(a) => plots::bode(&a),
        Command::Step(a) => plots::step(&a),
        Command::Pzmap(a) => plots::pzmap(&a),
        Command::Nyquist(a) => plots::nyquist(&a),
        Command::Demo(a) => demo::run(&a),
        Command::Linearize(a) => linearize::run(&a),
        Command::Simulate(a) => simulate::run(&a),
        Command::MemsPullin(a) => pullin::run(&a),
    }
}
