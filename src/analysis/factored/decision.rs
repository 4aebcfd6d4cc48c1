//! How a factored plant's structure (multiplicities, cancellations, stability) was decided:
//! exactly, or numerically and why.

use num_complex::Complex64;
use serde::Serialize;

use crate::poly::HalfPlane;

/// Which path decided a plant's structure (multiplicities, cancellations, stability).
///
/// ```
/// use ltikit::analysis::StructurePath;
/// assert_eq!(StructurePath::Exact.as_str(), "exact");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StructurePath {
    /// Certified by rational arithmetic on the coefficients as typed: no tolerance.
    Exact,
    /// Found by the floating-point root finder (f64 input, or exact input beyond the budget).
    Numerical,
}

impl StructurePath {
    /// `"exact"` or `"numerical"` (the JSON value).
    pub fn as_str(self) -> &'static str {
        match self {
            StructurePath::Exact => "exact",
            StructurePath::Numerical => "numerical",
        }
    }
}

/// How the structure of a factored plant was decided.
#[derive(Debug, Clone, Default)]
pub(crate) struct Decision {
    /// The exactly decided half plane of every distinct root (exact path only).
    pub(super) sides: Option<Vec<(Complex64, HalfPlane)>>,
    /// Why exact input went the numerical way.
    pub(super) fallback: Option<String>,
}

impl Decision {
    /// Decided by the exact path, with the half plane of every distinct root.
    pub(super) fn exact(sides: Vec<(Complex64, HalfPlane)>) -> Decision {
        Decision {
            sides: Some(sides),
            fallback: None,
        }
    }

    /// Exact input that went the numerical way, and why.
    pub(super) fn fallback(reason: String) -> Decision {
        Decision {
            sides: None,
            fallback: Some(reason),
        }
    }
}
