//! Real polynomials in s, with coefficients in **descending** powers at the interface.
//!
//! `Poly::from_descending(&[1.0, 3.0, 2.0])` is s² + 3s + 2 — the order MATLAB, python-control
//! and ControlSystems.jl use. Leading zeros are trimmed; the zero polynomial is `[0]` and has
//! degree 0 (check [`Poly::is_zero`]). Storage is descending too, so `coeffs()` is what was given
//! minus leading zeros.
//!
//! Roots come with exact multiplicities ([`Poly::roots`], see [`roots`] for the method).

pub mod exact;
mod polynomial;
mod root;
pub mod roots;

pub use polynomial::{MAX_ORDER, Poly, format_poly};
pub use root::{HalfPlane, Root, half_plane, same_root};
