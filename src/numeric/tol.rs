//! Tolerances, named once so that every module decides "equal", "zero" and "on the axis" alike.

/// Machine epsilon of `f64`.
pub const EPS: f64 = f64::EPSILON;

/// Relative tolerance under which a root counts as *on* the imaginary axis:
/// |Re p| ≤ `AXIS_REL_TOL` · max(|p|, 1e-300). s² + 1 computed as −4e-16 ± 1j is on the axis.
pub const AXIS_REL_TOL: f64 = 1e-9;

/// Relative tolerance for matching a numerator root with a denominator root (cancellation).
pub const CANCEL_REL_TOL: f64 = 1e-8;

/// Relative size under which a coefficient or value is treated as exactly zero in
/// classification decisions (e.g. ζ = 0 when |Re p| is this small relative to |p|).
pub const ZERO_REL_TOL: f64 = 1e-12;

/// True when `a` and `b` agree to `rel` relative to the larger magnitude (or both are tiny
/// in absolute terms, below `abs`).
pub fn close(a: f64, b: f64, rel: f64, abs: f64) -> bool {
    let d = (a - b).abs();
    d <= abs || d <= rel * a.abs().max(b.abs())
}
