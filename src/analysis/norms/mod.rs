//! System norms of state-space models and model reduction: the certified H∞ and L∞ norms
//! ([`hinf`]), the singular values of the frequency response ([`sigma`]), the Gramians and
//! Hankel singular values ([`mod@gramian`]), the H2 norm ([`h2`]) and balanced truncation
//! ([`balred`]).
//!
//! | file | what | method |
//! |---|---|---|
//! | [`hinf`] | H∞ / L∞ norm as a certified interval, peak frequency | Boyd–Balakrishnan / Bruinsma–Steinbuch iteration on the Hamiltonian's imaginary eigenvalues, gains confirmed by evaluation |
//! | `hamiltonian.rs` (internal) | H(γ) and its imaginary eigenvalues | real Schur form, tolerance relative to ‖H‖ |
//! | `gain.rs` (internal) | σ_max(G(jω)) | Hessenberg solve, complex SVD |
//! | [`sigma`] | σᵢ(G(jω)) on a grid | the same evaluation |
//! | [`mod@gramian`] | controllability/observability Gramians as Cholesky factors, Hankel singular values | Hammarling (`numeric::linalg::lyap_cholesky`), SVD of L_oᵀ·L_c |
//! | [`h2`] | H2 norm | ‖C·L_c‖_F (+ ‖D‖_F² in discrete time) |
//! | [`balred`] | balanced truncation to an order or an error, a priori bound and measured error | square-root method (Laub; Tombs–Postlethwaite), the certified H∞ norm of G − G_r |
//! | `factored.rs` (internal) | the norms of a SISO factored plant | cascade realisation of its reduced zeros and poles |

pub mod balred;
mod factored;
mod gain;
pub mod gramian;
pub mod h2;
mod hamiltonian;
pub mod hinf;
pub mod sigma;

pub use balred::{BalancedTruncation, ReducedOrder, balanced_truncation};
pub use gramian::{Gramian, GramianKind, HankelSingularValues, gramian, hankel_singular_values};
pub use h2::{H2Norm, h2_norm};
pub use hinf::{CERTIFIED_GAP, NormKind, PeakGain, hinf_norm, linf_norm};
pub use sigma::{SigmaResponse, sigma_grid, sigma_response};
