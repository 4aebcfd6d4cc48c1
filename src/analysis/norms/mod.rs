//! System norms of state-space models: the certified H∞ and L∞ norms ([`hinf`]) and the
//! singular values of the frequency response ([`sigma`]).
//!
//! | file | what | method |
//! |---|---|---|
//! | [`hinf`] | H∞ / L∞ norm as a certified interval, peak frequency | Boyd–Balakrishnan / Bruinsma–Steinbuch iteration on the Hamiltonian's imaginary eigenvalues, gains confirmed by evaluation |
//! | `hamiltonian.rs` (internal) | H(γ) and its imaginary eigenvalues | real Schur form, tolerance relative to ‖H‖ |
//! | `gain.rs` (internal) | σ_max(G(jω)) | Hessenberg solve, complex SVD |
//! | [`sigma`] | σᵢ(G(jω)) on a grid | the same evaluation |

mod factored;
mod gain;
mod hamiltonian;
pub mod hinf;
pub mod sigma;

pub use hinf::{CERTIFIED_GAP, NormKind, PeakGain, hinf_norm, linf_norm};
pub use sigma::{SigmaResponse, sigma_grid, sigma_response};
