//! Root locus of D(s) + K·N(s) = 0 — the closed-loop poles of unity negative feedback around
//! K·G(s), G = N/D — for K from 0 to ∞ (or from 0 to −∞ on request).
//!
//! Everything a user reads off the locus is computed by root-finding on polynomials, not from
//! the traced curve:
//! - **asymptotes**: n − m of them, centroid (Σp − Σz)/(n − m) from the two leading
//!   coefficients of N and D, angles (180° + 360°·l)/(n − m) (l·360°/(n − m) for the
//!   complementary locus);
//! - **break-away and break-in points**: the real roots σ of N·D′ − N′·D at which
//!   K = −D(σ)/N(σ) has the locus's sign; break-away where |K| has a local maximum along the
//!   real axis, break-in at a local minimum (decided by the sign of the first non-vanishing
//!   derivative of N·D′ − N′·D);
//! - **imaginary-axis crossings**: [`axis_crossings`](super::routh::axis_crossings), the same
//!   polynomial the Routh stable-gain set is built on; in discrete time ([`root_locus_z`]) the
//!   **unit-circle crossings** instead ([`circle_crossings`](super::jury::circle_crossings):
//!   z = ±1 and the axis crossings of the bilinear images, the ends of the Jury stable-gain
//!   set);
//! - **departure and arrival angles** at every pole and zero of G in lowest terms from the
//!   angle condition (with multiplicity μ: μ angles 360°/μ apart); roots that N and D share
//!   are closed-loop poles for every K and listed as fixed.
//!
//! The branches (`trace.rs`) are the roots of D + K·N at adaptively chosen gains, matched
//! from one gain to the next.

mod features;
mod locus;
mod trace;

pub use features::{Asymptotes, BreakKind, BreakPoint, LocusAngle, LocusCrossing};
pub use locus::{DEFAULT_MAX_GAINS, RootLocus, RootLocusOptions, root_locus, root_locus_z};
pub use trace::{Branches, locus_roots, trace_at_gains};
