//! The command table: the `ltikit` parser (one variant per command, each with its own
//! arguments) and the dispatch to each command's `run`.

use anyhow::Result;
use clap::{Parser, Subcommand};

use super::{
    analyze, balred, c2d, connect, delayed, demo, equations, eval, freq, gangof4, gram, help, jury,
    linearize, lqr, margins, norm, pade, place, plots, pullin, residue, response, rlocus, routh,
    sigma, simulate,
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
    /// A discrete plant (--dt T) gets the Jury table (as `ltikit jury`).
    Routh(routh::RouthArgs),
    /// Jury table of a discrete plant's characteristic polynomial in z (or of D + K·N with
    /// --gain K): roots inside, on and outside the unit circle, exact for typed coefficients;
    /// the exact set of stabilising gains with --gain-range.
    Jury(routh::RouthArgs),
    /// Root locus of 1 + K·L (L = G, or C·G with --controller): asymptotes, break points,
    /// imaginary-axis crossings (unit-circle crossings for a discrete plant, --dt T),
    /// departure/arrival angles, stable gains; PNG with -o.
    Rlocus(rlocus::RlocusArgs),
    /// Bode diagram PNG (magnitude and continuous phase, margins marked); several plants with
    /// repeated --num/--den or --plant.
    Bode(plots::BodeArgs),
    /// Step (or impulse, ramp) response PNG with rise time, settling band, peak and overshoot.
    Step(plots::StepArgs),
    /// Pole-zero map PNG (multiplicities, cancelled pairs, stable half plane).
    Pzmap(plots::PzmapArgs),
    /// Nyquist diagram PNG (−∞ < ω < ∞, indentations around imaginary-axis poles; in z the
    /// unit circle, arcs outside it around poles on it).
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
    /// Sample a continuous-time plant at --dt T: zoh, foh, tustin (with --prewarp), matched
    /// pole-zero or impulse invariance; the discrete plant, its mapped poles; -o F.toml.
    C2d(c2d::C2dArgs),
    /// The continuous-time plant whose zoh or tustin sampling is the given discrete plant
    /// (matrix logarithm; a pole at 0 or on the negative real axis has no zoh preimage).
    D2c(c2d::D2cArgs),
    /// The [N/N] Padé approximant of a dead time e^(−sT): coefficients, poles, and the phase
    /// error against −ωT (what --pade N puts in place of a plant's delay).
    Pade(pade::PadeArgs),
    /// Series connection of two plant files: A first, then B (the result is B·A); transfer
    /// functions stay transfer functions, otherwise state space; -o F.toml.
    Series(connect::SeriesArgs),
    /// Parallel connection A + B (--sign -1: A − B); -o F.toml.
    Parallel(connect::ParallelArgs),
    /// Feedback around G with H in the loop: G/(1 + G·H) (--sign +1: G/(1 − G·H)); -o F.toml.
    Feedback(connect::FeedbackArgs),
    /// A diagram file (named blocks, signals, sums) closed into one state-space model;
    /// -o F.toml.
    Connect(connect::ConnectArgs),
    /// G at a complex point, every channel: --s "-1+2j" (--z for a discrete plant).
    Eval(eval::EvalArgs),
    /// The gang of four of the loop L = C·G (--controller): S, P·S, C·S, T with poles, dc
    /// gain and peak; Bode PNG with -o.
    Gangof4(gangof4::GangArgs),
    /// State feedback u = -K x placing the eigenvalues of A - BK at --poles (Ackermann for
    /// one input, with its conditioning; Kautsky–Nichols–Van Dooren for several): the gain,
    /// the achieved poles and their distance to the requested ones.
    Place(place::PlaceArgs),
    /// Linear-quadratic regulator: the state feedback u = -K x minimising the quadratic cost
    /// with weights --q, --r (--s), from the Riccati equation (discrete for --dt T): K, X,
    /// the closed-loop poles, the residual.
    Lqr(lqr::LqrArgs),
    /// Kalman estimator gain L from process and measurement noise covariances --qn, --rn
    /// (noise on every state or through the inputs): L, the error covariance, eig(A - LC).
    #[command(alias = "kalman")]
    Lqe(lqr::LqeArgs),
    /// LQG controller: an LQR on a Kalman estimate, as a state-space model H for negative
    /// feedback u = -H y (the closed loop has the poles of A - BK and A - LC); -o F.toml.
    Lqg(lqr::LqgArgs),
    /// Lyapunov equation A·X + X·Aᵀ + Q = 0 (--discrete: A·X·Aᵀ − X + Q = 0; --b B for
    /// Q = B·Bᵀ with the Cholesky factor): X, relative residual, condition estimate.
    Lyap(equations::LyapArgs),
    /// Sylvester equation A·X + X·B = C: X, relative residual, condition estimate.
    Sylvester(equations::SylvesterArgs),
    /// Continuous algebraic Riccati equation (LQR) with weights --q, --r and cross term --s:
    /// stabilising X, gain K, closed-loop eigenvalues, residual, condition estimate.
    Care(equations::RiccatiArgs),
    /// Discrete algebraic Riccati equation: stabilising X, gain K, closed-loop eigenvalues,
    /// residual, condition estimate.
    Dare(equations::RiccatiArgs),
    /// Certified H∞ norm (--hinf, default) or L∞ norm (--linf): an interval [lower, upper]
    /// with upper/lower − 1 ≤ 1e-10 and the peak frequency (∞ for an unstable model).
    Norm(norm::NormArgs),
    /// Singular values σᵢ(G(jω)) of a MIMO plant over a frequency grid: a table, JSON, or a
    /// sigma plot PNG with -o; the certified peak marked.
    Sigma(sigma::SigmaArgs),
    /// Controllability (--kind c) or observability (--kind o) Gramian of a stable plant, or
    /// its Cholesky factor (--cholesky), with the residual of its Lyapunov equation.
    Gram(gram::GramArgs),
    /// Hankel singular values of a stable plant, with the truncation bound 2·Σ_{j>i} σⱼ.
    Hsv(gram::HsvArgs),
    /// Balanced truncation (square-root method) to --order K or --error E: the a priori bound
    /// beside the certified measured H∞ error; -o F.toml writes the reduced plant.
    Balred(balred::BalredArgs),
}

/// The command line's definition: the derived one, with each command's help ending in the
/// limits of its options and, for `linearize` and `simulate`, the models with their
/// parameters (both generated: from [`crate::limits::LIMITS`] and the model registry).
pub fn command() -> clap::Command {
    use clap::CommandFactory;
    let mut cmd = Cli::command();
    let names: Vec<String> = cmd
        .get_subcommands()
        .map(|c| c.get_name().to_string())
        .collect();
    for name in names.clone() {
        let others: Vec<&String> = names.iter().filter(|n| **n != name).collect();
        cmd = cmd.mut_subcommand(&name, |sub| {
            let flags: Vec<String> = sub
                .get_arguments()
                .filter_map(|a| a.get_long().map(|l| format!("--{l}")))
                .collect();
            let mut help = String::new();
            if matches!(name.as_str(), "linearize" | "simulate") {
                help.push_str(&help::models_text());
                help.push('\n');
            }
            help.push_str(&help::limits_text(&name, &others, &flags));
            // `--gain -1`, `--t-end -5`: a negative number is a value, not an option
            sub.after_help(help).allow_negative_numbers(true)
        });
    }
    cmd.after_help(help::limits_text("", &[], &[]))
}

/// The value of `-o`: a file name ending in `.png` (any case). ltikit writes PNG pictures
/// only; a picture under another name (`x.jpg`) would be a PNG in disguise, so it is refused
/// (a usage error, exit 2).
pub(crate) fn png_path(text: &str) -> std::result::Result<std::path::PathBuf, String> {
    let path = std::path::PathBuf::from(text);
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("png") => Ok(path),
        Some(other) => Err(format!(
            "ltikit writes PNG pictures only, not .{}: name the file FILE.png",
            crate::error::abbreviate(other)
        )),
        None => Err("ltikit writes PNG pictures: name the file FILE.png".into()),
    }
}

/// Parses a command line (program name first) with [`command`].
pub(crate) fn parse<I, T>(args: I) -> std::result::Result<Cli, clap::Error>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    use clap::FromArgMatches;
    let mut cmd = command();
    let matches = cmd.try_get_matches_from_mut(args)?;
    Cli::from_arg_matches(&matches).map_err(|e| e.format(&mut cmd))
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
    run(parse(args)?)
}

pub(crate) fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Analyze(a) => delayed::analyze_command(&a),
        Command::Residue(a) => residue::run(&a),
        Command::Response(a) => response::run(&a),
        Command::Freq(a) => freq::run(&a),
        Command::Margins(a) => margins::run(&a),
        Command::Routh(a) => routh::run(&a),
        Command::Jury(a) => jury::run_jury(&a),
        Command::Rlocus(a) => rlocus::run(&a),
        Command::Bode(a) => plots::bode(&a),
        Command::Step(a) => delayed::step_command(&a),
        Command::Pzmap(a) => plots::pzmap(&a),
        Command::Nyquist(a) => plots::nyquist(&a),
        Command::Demo(a) => demo::run(&a),
        Command::Linearize(a) => linearize::run(&a),
        Command::Simulate(a) => simulate::run(&a),
        Command::MemsPullin(a) => pullin::run(&a),
        Command::C2d(a) => c2d::run_c2d(&a),
        Command::D2c(a) => c2d::run_d2c(&a),
        Command::Pade(a) => pade::run(&a),
        Command::Series(a) => connect::run_series(&a),
        Command::Parallel(a) => connect::run_parallel(&a),
        Command::Feedback(a) => connect::run_feedback(&a),
        Command::Connect(a) => connect::run_connect(&a),
        Command::Eval(a) => eval::run(&a),
        Command::Gangof4(a) => gangof4::run(&a),
        Command::Place(a) => place::run(&a),
        Command::Lqr(a) => lqr::run_lqr(&a),
        Command::Lqe(a) => lqr::run_lqe(&a),
        Command::Lqg(a) => lqr::run_lqg(&a),
        Command::Lyap(a) => equations::run_lyap(&a),
        Command::Sylvester(a) => equations::run_sylvester(&a),
        Command::Care(a) => equations::run_riccati(&a, false),
        Command::Dare(a) => equations::run_riccati(&a, true),
        Command::Norm(a) => norm::run(&a),
        Command::Sigma(a) => sigma::run(&a),
        Command::Gram(a) => gram::run_gram(&a),
        Command::Hsv(a) => gram::run_hsv(&a),
        Command::Balred(a) => balred::run(&a),
    }
}
