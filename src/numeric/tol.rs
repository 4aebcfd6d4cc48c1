//! Tolerances, named once so that every module decides "equal", "zero" and "on the axis" alike.

/// Machine epsilon of `f64`.
pub const EPS: f64 = f64::EPSILON;

/// Relative tolerance under which a root counts as *on* the imaginary axis:
/// |Re p| ≤ `AXIS_REL_TOL` · max(|p|, 1e-300). s² + 1 computed as −4e-16 ± 1j is on the axis.
pub const AXIS_REL_TOL: f64 = 1e-9;

/// Relative tolerance under which two computed roots are the same root: a numerator root
/// cancels a denominator root, an input pole coincides with a system pole.
pub const CANCEL_REL_TOL: f64 = 1e-8;

/// Relative size under which a computed coefficient is rounding noise in a display (a
/// linearised transfer function's structurally zero terms).
pub const ZERO_REL_TOL: f64 = 1e-12;
