//! The `ltikit` command line: argument parsing, text reports and JSON output. The only layer
//! that prints. Errors go to stderr as one line with exit code 1 (2 for usage errors).

mod analyze;
mod batch;
mod channels;
mod demo;
mod freq;
mod input_file;
mod linearize;
mod margins;
mod output;
mod parse;
mod plant;
mod plots;
mod pullin;
mod residue;
mod response;
mod rlocus;
mod routh;
mod simulate;
mod ss_response;
mod text;

use anyhow::Result;
use clap::{Parser, Subcommand};

pub use crate::lti::Plant;
pub use plant::PlantArgs;

/// A usage error (exit code 2): a missing or inconsistent option, as opposed to bad values.
#[derive(Debug)]
pub struct UsageError(pub String);

impl std::fmt::Display for UsageError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for UsageError {}

/// ltikit — LTI input-output models from ODE coefficients: exact poles and zeros, stability,
/// partial fractions and closed-form responses, frequency response, plots, nonlinear models.
///
/// Coefficients are given in descending powers of s: --den "1 0.8 4" is s^2 + 0.8 s + 4.
/// Frequencies in rad/s, phases in degrees, magnitudes as ratios and dB.
#[derive(Parser, Debug)]
#[command(name = "ltikit", version, about, long_about = None, max_term_width = 100)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
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

/// Entry point of the binary: parses the arguments, runs the command, returns the exit code.
pub fn main() -> i32 {
    install_panic_hook();
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) if e.use_stderr() => {
            eprintln!("error: {}", usage_line(&e.to_string()));
            return 2;
        }
        Err(e) => {
            // --help, --version
            let _ = e.print();
            return 0;
        }
    };
    let result = run(cli);
    let warnings = take_warnings();
    match result {
        Ok(()) => {
            for w in warnings {
                eprintln!("warning: {w}");
            }
            0
        }
        Err(e) => {
            // a failing command says one line: the error (its warnings are dropped)
            eprintln!("error: {}", one_line(&e));
            if e.downcast_ref::<UsageError>().is_some() {
                2
            } else {
                1
            }
        }
    }
}

/// Warnings of the running command, printed to stderr after it succeeds (a failing command
/// prints only its error line).
static WARNINGS: std::sync::Mutex<Vec<String>> = std::sync::Mutex::new(Vec::new());

/// Records a warning for the end of the command.
pub(crate) fn warn(message: String) {
    if let Ok(mut w) = WARNINGS.lock() {
        w.push(message);
    }
}

/// The recorded warnings, emptied.
fn take_warnings() -> Vec<String> {
    WARNINGS
        .lock()
        .map(|mut w| std::mem::take(&mut *w))
        .unwrap_or_default()
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

fn run(cli: Cli) -> Result<()> {
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

/// A usage error of the argument parser on one line: its first line, its tip if it has one,
/// and where to look, with offending text abbreviated.
fn usage_line(text: &str) -> String {
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    let first = lines
        .next()
        .unwrap_or("invalid arguments")
        .trim_start_matches("error:")
        .trim();
    let mut out = abbreviate_quoted(first);
    if let Some(tip) = lines.find(|l| l.starts_with("tip:")) {
        out.push_str(&format!(" ({})", abbreviate_quoted(tip)));
    }
    out.push_str("; see --help");
    out
}

/// `text` with every quoted part cut to [`crate::error::TOKEN_SHOWN`] characters.
fn abbreviate_quoted(text: &str) -> String {
    let mut out = String::new();
    for (i, part) in text.split('\'').enumerate() {
        if i > 0 {
            out.push('\'');
        }
        if i % 2 == 1 {
            out.push_str(&crate::error::abbreviate(part));
        } else {
            out.push_str(part);
        }
    }
    out
}

/// The error and its causes on one line.
pub(crate) fn one_line(e: &anyhow::Error) -> String {
    let mut parts: Vec<String> = Vec::new();
    for cause in e.chain() {
        let s = cause.to_string();
        if !parts.iter().any(|p| p.contains(&s)) {
            parts.push(s);
        }
    }
    parts.join(": ").replace('\n', " ")
}

/// A panic is a bug; print one line instead of a trace.
fn install_panic_hook() {
    std::panic::set_hook(Box::new(|info| {
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown".into());
        let at = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        eprintln!("error: internal error (a bug, please report it): {msg}{at}");
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn usage_errors_fit_on_one_line() {
        let e = Cli::try_parse_from(["ltikit", "analyze", "--bogus"]).unwrap_err();
        let l = usage_line(&e.to_string());
        assert!(
            !l.contains('\n') && l.contains("--bogus") && l.ends_with("see --help"),
            "{l}"
        );
        let long = format!("--{}", "x".repeat(10_000));
        let e = Cli::try_parse_from(["ltikit", "analyze", &long]).unwrap_err();
        let l = usage_line(&e.to_string());
        assert!(l.len() < 300, "{l}");
        let e = Cli::try_parse_from(["ltikit", "analyze", "--den"]).unwrap_err();
        assert!(usage_line(&e.to_string()).contains("--den"));
    }
}
