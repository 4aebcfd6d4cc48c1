//! A root of a polynomial (a pole or a zero) with its multiplicity, and the decisions about
//! roots that every analysis must take alike: is it *on* the imaginary axis, and are two
//! computed roots the *same* root. The tolerances are named in [`crate::numeric::tol`].

use num_complex::Complex64;
use serde::Serialize;

use crate::numeric::tol::{AXIS_REL_TOL, CANCEL_REL_TOL};

/// A root and its multiplicity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Root {
    /// The root.
    pub value: Complex64,
    /// How many times it is repeated (≥ 1).
    pub multiplicity: usize,
}

/// Where a root lies relative to the imaginary axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum HalfPlane {
    /// Re p < 0.
    Left,
    /// On the imaginary axis (to the relative tolerance [`AXIS_REL_TOL`]).
    Axis,
    /// Re p > 0.
    Right,
}

/// Which half plane `p` is in: on the axis when |Re p| ≤ [`AXIS_REL_TOL`]·|p| (so s² + 1
/// computed as −4e-16 ± 1j is on the axis; p = 0 is on it).
///
/// ```
/// use ltikit::poly::{half_plane, HalfPlane};
/// use num_complex::Complex64 as C;
/// assert_eq!(half_plane(C::new(-4e-16, 1.0)), HalfPlane::Axis);
/// assert_eq!(half_plane(C::new(-1e-3, 1.0)), HalfPlane::Left);
/// assert_eq!(half_plane(C::new(0.0, 0.0)), HalfPlane::Axis);
/// ```
pub fn half_plane(p: Complex64) -> HalfPlane {
    if p.re.abs() <= AXIS_REL_TOL * p.norm() {
        HalfPlane::Axis
    } else if p.re < 0.0 {
        HalfPlane::Left
    } else {
        HalfPlane::Right
    }
}

/// True when two computed roots are the same root: equal, or within [`CANCEL_REL_TOL`]
/// relative to the larger magnitude (a zero cancels a pole, an input pole meets a system pole).
/// Roots at s = 0 are exact (deflated exactly), so 0 is only the same as 0.
///
/// ```
/// use ltikit::poly::same_root;
/// use num_complex::Complex64 as C;
/// assert!(same_root(C::new(-2.0, 0.0), C::new(-2.0 * (1.0 + 1e-12), 0.0)));
/// assert!(!same_root(C::new(-2.0, 0.0), C::new(-2.001, 0.0)));
/// ```
pub fn same_root(a: Complex64, b: Complex64) -> bool {
    a == b || (a - b).norm() <= CANCEL_REL_TOL * a.norm().max(b.norm())
}

impl Root {
    /// A root of multiplicity `multiplicity`.
    pub fn new(value: Complex64, multiplicity: usize) -> Root {
        Root {
            value,
            multiplicity,
        }
    }

    /// True when the root is exactly real (imaginary part 0).
    pub fn is_real(&self) -> bool {
        self.value.im == 0.0
    }

    /// True when the root is exactly s = 0 (zero roots are deflated exactly).
    pub fn is_origin(&self) -> bool {
        self.value.re == 0.0 && self.value.im == 0.0
    }

    /// The half plane of the root ([`half_plane`]).
    pub fn half_plane(&self) -> HalfPlane {
        half_plane(self.value)
    }

    /// True when the root is the same root as the point `v` ([`same_root`]).
    pub fn same_as(&self, v: Complex64) -> bool {
        same_root(self.value, v)
    }
}
