//! The options of the stability tables, shared by `ltikit routh` and `ltikit jury` (a leaf:
//! the two commands read them, neither reads the other's module for them).

use clap::Args;

use super::PlantArgs;

#[derive(Args, Debug)]
pub struct RouthArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// A gain K in unity negative feedback: the table of the closed loop's D + K·N.
    #[arg(long, value_name = "K", allow_hyphen_values = true)]
    pub gain: Option<f64>,
    /// Also the gains K for which the unity-feedback loop D + K·N is stable (open intervals;
    /// for a discrete plant: every root strictly inside the unit circle, each interval decided
    /// exactly).
    #[arg(long)]
    pub gain_range: bool,
    /// Print one JSON document: {"polynomial", "rows", "powers", "events", "rhp", "axis", "lhp",
    /// "exact"} (and "stable_gains": [[lo, hi], …] with --gain-range; null for an infinite end).
    /// For a discrete plant (the Jury table): {"polynomial", "rows", "alphas", "first",
    /// "singular_at", "inside", "on", "outside", "exact": {"inside", "on", "outside"}} and
    /// "stable_gains".
    #[arg(long)]
    pub json: bool,
}
