//! The limits: every size a user controls, in one table.
//!
//! No input may exhaust the machine. Each size that reaches an allocation — grid points,
//! samples, orders, states, picture sizes, gain counts, file sizes — is checked against one
//! of these limits **before** anything is allocated, where the allocation is (the library
//! function that allocates checks it; the command line only passes the number on). Beyond a
//! limit the user gets one error line naming the field, the number and the limit
//! ([`LtiError::LimitExceeded`]).
//!
//! [`LIMITS`] is the table; docs/ARCHITECTURE.md ("Robustness: the limits") prints it and
//! `tests/limits.rs` checks that the two agree; the command line's `--help` lists the limits
//! of each command's options from it.
//!
//! ```
//! use ltikit::limits::{LIMITS, POINTS};
//! assert!(LIMITS.iter().any(|l| l.name == "MAX_POINTS"));
//! assert!(POINTS.check("`points`", 1000).is_ok());
//! let e = POINTS.check("`points`", 1_000_000_000).unwrap_err().to_string();
//! assert_eq!(
//!     e,
//!     "`points`: 1000000000 exceeds the limit of 1 000 000 sample points (MAX_POINTS)"
//! );
//! ```

use crate::error::{LtiError, Result};

/// One limit: its name, its value, the input fields it bounds and what it counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limit {
    /// The constant's name, e.g. `MAX_POINTS`.
    pub name: &'static str,
    /// The largest accepted value.
    pub max: u64,
    /// What is counted, in the plural ("sample points", "bytes", "px a side"; empty for a
    /// bare number such as an order).
    pub unit: &'static str,
    /// The input fields it bounds (`points`, `size`, …; the command line names them by its
    /// flags); empty for sizes no single option sets (a grid the program chooses).
    pub fields: &'static [&'static str],
    /// Where it applies, in a few words.
    pub applies_to: &'static str,
}

impl Limit {
    /// `Ok(())` when `value ≤ max`, otherwise [`LtiError::LimitExceeded`] naming `field` (a
    /// field name in backquotes, e.g. "`points`", or a description of a product such as
    /// "`points` × 4 values per sample").
    ///
    /// ```
    /// use ltikit::limits::SIDE;
    /// assert!(SIDE.check("`size`", 800).is_ok());
    /// assert!(SIDE.check("`size`", u128::from(u64::MAX)).is_err());
    /// ```
    pub fn check(&self, field: &str, value: u128) -> Result<()> {
        if value <= u128::from(self.max) {
            Ok(())
        } else {
            Err(self.exceeded(field, value))
        }
    }

    /// [`Limit::check`] for a `usize`, which it returns.
    pub fn check_usize(&self, field: &str, value: usize) -> Result<usize> {
        self.check(field, value as u128)?;
        Ok(value)
    }

    /// The error for `value` beyond this limit.
    pub fn exceeded(&self, field: &str, value: u128) -> LtiError {
        LtiError::LimitExceeded {
            field: field.to_string(),
            value,
            max: self.max,
            unit: self.unit.to_string(),
            limit: self.name.to_string(),
        }
    }
}

pub use crate::fmt::{amount, grouped};

macro_rules! limits {
    ($($(#[$doc:meta])* $item:ident, $konst:ident: $ty:ty = $value:expr, $unit:expr,
       [$($field:expr),*], $applies:expr;)*) => {
        $(
            $(#[$doc])*
            pub const $konst: $ty = $value;
            #[doc = concat!("The table entry of [`", stringify!($konst), "`].")]
            pub const $item: Limit = Limit {
                name: stringify!($konst),
                max: $value as u64,
                unit: $unit,
                fields: &[$($field),*],
                applies_to: $applies,
            };
        )*
        /// Every limit, in the order of docs/ARCHITECTURE.md's table.
        pub const LIMITS: &[Limit] = &[$($item),*];
    };
}

limits! {
    /// Highest polynomial degree (system order) on the coefficient path.
    ORDER, MAX_ORDER: usize = 200, "", ["num", "den"],
        "order of a plant given by coefficients";
    /// Highest order (poles with multiplicity) of a factored plant: a zero-pole-gain plant or
    /// a state-space channel.
    FACTORED_ORDER, MAX_FACTORED_ORDER: usize = 4096, "", [],
        "order of a factored plant (state-space channel)";
    /// Largest number of states of a state-space model (the seed's 128-particle lattice has
    /// 256; dense O(n³) kernels stay well under a second up to this size).
    STATES, MAX_STATES: usize = 2048, "states", ["a", "b", "c", "d"],
        "states of a state-space model";
    /// Largest number of inputs or outputs of a state-space model.
    SIGNALS, MAX_SIGNALS: usize = 256, "inputs or outputs", ["b", "c", "d"],
        "inputs, outputs of a state-space model";
    /// The largest lattice (particles; the state has twice as many components). Every
    /// command stays within seconds up to it; the Nyquist contour, which indents around each
    /// of the N undamped modes, took 4.5 s of CPU at N = 512 and 19.6 s at N = 1024.
    PARTICLES, MAX_PARTICLES: usize = 512, "particles", ["model"],
        "particles `N` of the lattice model";
    /// Largest order for which `ltikit analyze` adds the whole-model analysis of a
    /// state-space plant (beyond it the section says "not computed"; the channels are still
    /// analysed).
    ANALYSIS_STATES, MAX_ANALYSIS_STATES: usize = 256, "states", [],
        "whole-model section of `analyze`";
    /// Largest model whose H∞/L∞ norm, Gramians or balanced truncation are computed: the
    /// H∞ iteration solves eigenvalue problems of twice this order (dense O(n³)).
    NORM_STATES, MAX_NORM_STATES: usize = 256, "states", [],
        "states of a model for `norm`, `gram`, `hsv`, `balred`, `sigma`";
    /// Most work of a sigma plot: frequencies × states² (each frequency is an O(n²)
    /// Hessenberg solve; 2·10⁹ is about two seconds).
    SIGMA_WORK, MAX_SIGMA_WORK: u64 = 2_000_000_000, "frequencies × states²", ["points", "w"],
        "frequencies × states² of `sigma`";
    /// Largest number of states for pole placement: the robust method forms an n × n kernel
    /// basis per pole (O(n⁴) in all).
    PLACE_STATES, MAX_PLACE_STATES: usize = 200, "states", [],
        "states of a plant for `place`";
    /// Largest number of states for `lqr`, `lqe`, `lqg`: each solves a Riccati equation
    /// through a 2n × 2n Schur form or doubling (a 256-state LQG, two equations, took 29 s of
    /// CPU in the unoptimised dev build).
    DESIGN_STATES, MAX_DESIGN_STATES: usize = 256, "states", [],
        "states of a plant for `lqr`, `lqe`, `lqg`, and of `care`, `dare`";
    /// Largest order of a Lyapunov or Sylvester equation: Bartels–Stewart is O(n³) on two
    /// Schur forms (n = 100: 6.6 ms in release; 512 is about a second).
    EQUATION_STATES, MAX_EQUATION_STATES: usize = 512, "states", [],
        "order of `lyap`, `sylvester` (and the Gramians' Lyapunov equations)";
    /// Most channels analysed at once without a chosen channel.
    CHANNELS, MAX_CHANNELS: usize = 64, "channels", ["channel"],
        "channels of a MIMO plant analysed at once";
    /// Most points of a grid or a sampled response: frequency grids, time lists, simulation
    /// samples (8 MB of times; the outputs are streamed). A million points is more than any
    /// picture or table needs, and the slowest output at the limit — `freq`'s text table —
    /// takes about a second (10⁷ took 10 s of CPU).
    POINTS, MAX_POINTS: usize = 1_000_000, "sample points", ["points", "t", "w"],
        "points of a frequency grid, time list or simulation";
    /// Most values of a per-channel frequency response (frequencies × channels), computed
    /// whole rather than streamed.
    CHANNEL_VALUES, MAX_CHANNEL_VALUES: usize = 1_000_000, "values", ["points", "w", "channel"],
        "frequencies × channels of a MIMO `freq`";
    /// Most values (samples × signals) of a state-space time response.
    RESPONSE_VALUES, MAX_RESPONSE_VALUES: usize = 10_000_000, "values", ["t", "input_file"],
        "samples × signals of a state-space `response`";
    /// Most values a simulation keeps (samples × (1 + states + outputs)) for a JSON document or
    /// a picture; the CSV is streamed and only bounded by [`MAX_POINTS`].
    SIMULATION_VALUES, MAX_SIMULATION_VALUES: usize = 10_000_000, "values", ["points"],
        "samples × (1 + states + outputs) kept by `simulate` for JSON or a picture";
    /// Most integration steps (accepted plus rejected) a simulation may be allowed: 5·10⁶
    /// steps of the double pendulum, the costliest model, take about 2.5 s.
    SIMULATION_STEPS, MAX_SIMULATION_STEPS: usize = 5_000_000, "steps", ["max_steps"],
        "integration steps of a simulation";
    /// Largest input file of a simulated response (bytes).
    INPUT_BYTES, MAX_INPUT_BYTES: u64 = 64 << 20, "bytes", ["input_file"],
        "input signal file";
    /// Most samples (lines) of an input file.
    INPUT_SAMPLES, MAX_INPUT_SAMPLES: usize = 1_000_000, "samples", ["input_file"],
        "samples of an input signal file";
    /// Largest plant file or batch line accepted (bytes).
    RECORD_BYTES, MAX_RECORD_BYTES: u64 = 1 << 20, "bytes", ["plant", "batch"],
        "plant file, batch line";
    /// Most traced gains of a root locus.
    GAINS, MAX_GAINS: usize = 100_000, "gains", ["max_gains"],
        "traced gains of a root locus";
    /// Longest accepted title, label, legend text or note, in characters.
    TEXT_CHARS, MAX_TEXT_CHARS: usize = 16_384, "characters", ["title"],
        "text of titles and labels";
    /// Largest accepted image side (px).
    SIDE, MAX_SIDE: u32 = 16_384, "px a side", ["size"], "picture width and height";
    /// Largest accepted image area (px²).
    PIXELS, MAX_PIXELS: u64 = 36_000_000, "pixels", ["size"], "picture area";
    /// The largest lattice trajectory stored: particles × samples values per matrix.
    TRAJECTORY_VALUES, MAX_TRAJECTORY_VALUES: usize = 4_000_000, "values", [],
        "particles × samples of a lattice motion";
    /// Most cells of a heat map.
    HEATMAP_CELLS, MAX_HEATMAP_CELLS: usize = 16_000_000, "cells", [], "heat map cells";
    /// Most digits one decimal number may have (digits of the mantissa, leading zeros
    /// included).
    DIGITS, MAX_DIGITS: usize = 1000, "digits", ["num", "den"], "digits of a number";
    /// Largest |exponent| accepted in `1.5e±E`. Together with [`MAX_DIGITS`] this bounds every
    /// number read from text to about 2000 decimal digits (≈ 6700 bits) of numerator and
    /// denominator.
    EXPONENT, MAX_EXPONENT: i64 = 1000, "", ["num", "den"],
        "decimal exponent of a number";
    /// Longest dead time (s). Beyond it the phase −ωT of e^(−jωT) at the frequencies a plot
    /// or a margin reads (ω up to ~10⁶ rad/s) exceeds 10¹², where an f64 keeps fewer than
    /// four digits of its angle modulo 2π: the delay would carry no information.
    DELAY, MAX_DELAY: u64 = 1_000_000, "s", ["delay"], "a dead time e^(−sT)";
    /// Most signals of a diagram (block inputs, block outputs, sums and external inputs): the
    /// algebraic loop is solved densely, O(signals³).
    DIAGRAM_SIGNALS, MAX_DIAGRAM_SIGNALS: usize = 1024, "signals", ["plant"],
        "signals of a diagram file";
    /// Deepest nesting of diagram files (a diagram's block may be a diagram file): a file
    /// that includes itself stops here.
    DIAGRAM_DEPTH, MAX_DIAGRAM_DEPTH: usize = 16, "levels", ["plant"],
        "nesting of diagram files";
    /// Highest order of a Padé approximant of a dead time (its coefficients (2n−k)!/k!…
    /// span 10⁴⁰ at n = 20; beyond it the rational approximant itself is ill-conditioned).
    PADE_ORDER, MAX_PADE_ORDER: usize = 20, "", ["pade", "order"],
        "order of a Padé approximant";
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_values_positive() {
        for (i, l) in LIMITS.iter().enumerate() {
            assert!(l.max > 0, "{}", l.name);
            assert!(
                LIMITS[..i].iter().all(|o| o.name != l.name),
                "{} twice",
                l.name
            );
        }
        assert_eq!(POINTS.max, MAX_POINTS as u64);
        assert_eq!(RECORD_BYTES.max, 1 << 20);
    }

    #[test]
    fn the_error_names_field_value_and_limit() {
        let e = SIDE.check("`size`", 20_000).unwrap_err().to_string();
        assert_eq!(
            e,
            "`size`: 20000 exceeds the limit of 16 384 px a side (MAX_SIDE)"
        );
        assert!(POINTS.check("`points`", u128::MAX).is_err());
        assert_eq!(POINTS.check_usize("`points`", 2).unwrap(), 2);
    }
}
