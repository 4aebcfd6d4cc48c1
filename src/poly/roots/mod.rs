//! Roots of a real polynomial with exact multiplicities.
//!
//! # Method
//! 1. Exact zero roots (trailing zero coefficients) are deflated exactly; coefficients of
//!    extreme range are split at wide gaps between the tropical roots and each piece is centred
//!    by an exact power of two (`scale.rs`).
//! 2. Candidates: degree 1 and 2 by stable closed forms; otherwise the eigenvalues of the
//!    balanced companion matrix (Francis double-shift QR directly on the Hessenberg companion
//!    matrix, capped, with [`crate::numeric::eigenvalues`] as the fallback). Simple roots come out to
//!    ~eps, but an m-fold root scatters by ~eps^(1/m) (numpy gives (s+1)⁴ as −1 ± 2e-4).
//! 3. Clustering on the closed upper half plane (each upper candidate stands for a conjugate
//!    pair): candidates closer than a generous relative distance form a group; a group is
//!    *accepted* as one root of multiplicity m when Newton's method on p^(m−1) (where an m-fold
//!    root is simple) from the group mean converges to a point c at which p, p′, …, p^(m−2)
//!    vanish to rounding level (|p^(j)(c)| ≤ γ·eps·Σ|aᵢ^(j)||c|ⁱ): i.e. a polynomial within
//!    rounding of p has an exact m-fold root at c. A group that is not accepted is split at the
//!    longest edge of its minimum spanning tree and each part is tried again. Groups that touch
//!    the real axis are tried as a real root first (multiplicity = #real + 2·#upper).
//! 4. Simple roots get a guarded Newton polish on p (accepted only while |p| decreases and the
//!    step stays inside the root's neighbourhood).
//! 5. The result must reproduce the coefficients (lead·Π(s − rₖ)^mₖ against p, componentwise
//!    to a small multiple of eps); if it does not, the polished candidates are returned as
//!    simple roots — no multiplicity is ever claimed that the coefficients do not support.
//!
//! When a multiple root is found, all roots are refined together by Gauss–Newton with the
//! structure fixed and a double-double residual (`refine.rs`); when the checks of step 5 fail,
//! a second stage takes the structure from the derivatives (`derivatives.rs`).
//!
//! Files, by step: `scale.rs` (1), `candidates.rs` and `companion.rs` (2), `group.rs` and
//! `newton.rs` (3, 4), `refine.rs`, `checks.rs` (5) and `derivatives.rs`.
//!
//! Two simple roots closer than about 2e-7 relative are indistinguishable from a double root
//! perturbed by rounding of the coefficients and are reported as one double root; roots
//! 5e-4 apart (which scipy's `residue` merges) stay distinct.

mod bound;
mod candidates;
mod checks;
mod companion;
mod derivatives;
mod found;
mod group;
mod newton;
mod order;
mod refine;
mod scale;
mod solve;

pub(crate) use bound::snap_to_axis;
pub(crate) use candidates::candidates;
pub(crate) use companion::balanced_companion;
pub use order::{flatten, sort_roots};
pub use solve::roots;
