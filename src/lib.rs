//! # ltikit
//!
//! Linear time-invariant input-output models from ODE coefficients: poles and zeros with exact
//! multiplicities, stability with the reason, partial fractions and closed-form responses,
//! frequency response and margins, headless PNG plots, and the exact linearisation of
//! nonlinear models. The `ltikit` command line (feature `cli`) is a thin layer over this
//! library; the README shows it.
//!
//! ## Quick start
//!
//! The ODE y‴ + 3y″ + 2y′ = 2u is the loop G(s) = 2 / (s³ + 3s² + 2s): its coefficients go in
//! as written, in descending powers of s. One factorisation gives the poles and zeros that
//! every analysis reads; the plots only read the data the analyses return.
//!
//! ```
//! # #[cfg(feature = "plot")]
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! use ltikit::TransferFunction;
//! use ltikit::analysis::auto_frequency_grid;
//! use ltikit::plot::{BodeSeries, PlotOptions, bode_png};
//!
//! let g = TransferFunction::from_descending(&[2.0], &[1.0, 3.0, 2.0, 0.0])?;
//! let f = g.factored()?; // poles 0, −1, −2: found once, read by everything below
//!
//! // Order, poles and zeros, dc gain, stability with the reason, modes, step metrics.
//! let a = f.analyze()?;
//! assert_eq!(a.order, 3);
//! assert!(!a.stability.bibo_stable); // the pole at the origin: an integrator
//!
//! // Margins by root-finding on G(jω). Closed form: the phase crosses −180° at ω = √2, where
//! // |G| = 2/(√2·√3·√6) = 1/3, so the gain margin is 3.
//! let m = f.margins()?;
//! assert!((m.gain_margin.unwrap() - 3.0).abs() < 1e-12);
//! assert!((m.phase_crossover.unwrap() - 2f64.sqrt()).abs() < 1e-12);
//!
//! // A Bode diagram on a grid chosen from the corner frequencies, with the margins marked.
//! let fr = f.freq_response(&auto_frequency_grid(&f, 400)?)?;
//! let label = g.to_string(); // "2 / (s^3 + 3 s^2 + 2 s)"
//! let png = std::env::temp_dir().join(format!("ltikit-quick-start-{}.png", std::process::id()));
//! bode_png(&png, &[BodeSeries::new(&fr).label(&label).margins(&m)], &PlotOptions::default())?;
//! assert!(std::fs::read(&png)?.starts_with(b"\x89PNG"));
//! # std::fs::remove_file(&png)?;
//! # Ok(())
//! # }
//! # #[cfg(not(feature = "plot"))]
//! # fn main() {}
//! ```
//!
//! Where to go next: [`TransferFunction`] (constructors and algebra), [`analysis::Factored`]
//! (every SISO analysis on one factorisation), [`StateSpace`] (SISO and MIMO models), [`lti::Plant`]
//! (plant files, textbook models, batch lines), [`nonlinear`] (models, linearisation,
//! simulation), `plot` (PNG files from the data structs).
//!
//! ## Features
//!
//! | feature | default | adds | pulls in |
//! |---|---|---|---|
//! | (none) | | polynomials, transfer functions, state space, every analysis, nonlinear models and simulation | nalgebra, num-complex, num-dual, dashu-int, serde, serde_json, toml, thiserror |
//! | `plot` | on | the `plot` module: headless PNG plots, font compiled in | ab_glyph, ttf-noto-sans, png |
//! | `cli` | on | the `ltikit` binary and the `cli` module; implies `plot` | clap, anyhow, rayon, indicatif |
//!
//! A library user who does not want the command line's dependencies turns the defaults off:
//!
//! ```toml
//! [dependencies]
//! ltikit = { path = "../ltikit", default-features = false, features = ["plot"] }
//! ```
//!
//! ## Conventions
//! - Polynomial coefficients are given in **descending** powers of s, as in MATLAB,
//!   python-control and ControlSystems.jl: `[1.0, 0.8, 4.0]` is s² + 0.8 s + 4.
//! - Frequencies are in rad/s, phases in degrees, magnitudes as ratios or in dB (20 log₁₀).
//! - Complex numbers in JSON are `[re, im]`; roots are listed with repetition.
#![deny(clippy::float_cmp)]
#![warn(missing_docs)]

pub mod analysis;
#[cfg(feature = "cli")]
pub mod cli;
pub mod error;
pub mod fmt;
pub mod limits;
pub mod lti;
pub mod nonlinear;
pub mod numeric;
#[cfg(feature = "plot")]
pub mod plot;
pub mod poly;

pub use analysis::Factored;
pub use error::{LtiError, Result};
pub use lti::{Plant, StateSpace, TransferFunction};
pub use poly::{MAX_ORDER, Poly, Root};

/// The README's Rust example, compiled and run as a doctest.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
