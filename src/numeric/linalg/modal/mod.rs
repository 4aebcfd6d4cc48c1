//! The modal (block-diagonal) form of a state-space system: A = X·Λ·X⁻¹ with Λ block diagonal,
//! each block upper triangular and holding one cluster of close eigenvalues, so that
//! G(s) = D + Σᵢ Ĉᵢ·(sI − Λᵢ)⁻¹·B̂ᵢ (Ĉ = C·X, B̂ = X⁻¹·B) costs O(Σ nᵢ²) per point instead
//! of the Hessenberg solve's O(n²), and a time step costs O(Σ nᵢ²) instead of a dense n×n
//! product.
//!
//! # Method (Golub–Van Loan §7.6.3, Bavely–Stewart)
//! 1. The complex Schur form A = D·Q·Z·S·Zᴴ·Qᵀ·D⁻¹ (`complex_schur.rs`).
//! 2. Clusters: eigenvalues closer than [`CLUSTER_REL`]·‖A‖ (single linkage) — repeated
//!    eigenvalues, semisimple or defective (a 2×2 Jordan block splits by ~√ε·‖A‖), stay in one
//!    block. S is reordered by adjacent swaps (unitary rotations, as LAPACK `ztrexc`) so each
//!    cluster is contiguous.
//! 3. The off-diagonal blocks are removed by a unit upper-triangular Y from the Sylvester
//!    equations Sᵢᵢ·Z − Z·Sⱼⱼ = −Sᵢⱼ (triangular, solved by substitution).
//!
//! This is the general path ([`ModalForm::from_schur`]), whatever the structure of A. A model
//! with the mechanical structure of [`super::second_order`] gets its modal form from its modes
//! instead ([`SecondOrder::modal_form`](super::second_order::SecondOrder::modal_form): no Schur
//! form, 1×1 blocks except for critical modes); [`ModalForm::new`] (with the model's
//! [`StateMatrix`](super::StateMatrix)) chooses.
//!
//! The form is **used only when it is safe**: blocks of at most [`MAX_BLOCK`], a transformation
//! whose condition estimate ‖Y‖_F·‖Y⁻¹‖_F is at most [`MAX_COND`], and agreement with the
//! Hessenberg evaluation to [`CHECK_REL`] at probe points; otherwise [`ModalForm::from_schur`]
//! returns `None` and the caller keeps the Hessenberg path.
//!
//! Files: `form.rs` (the form and its evaluation), `schur_path.rs` (the general path),
//! `channel.rs` (one channel as simple fractions), `cluster.rs` (single linkage).

mod channel;
mod cluster;
mod form;
pub(crate) mod schur_path;

pub use channel::ModalChannel;
pub(crate) use cluster::single_linkage;
pub use form::{CHECK_REL, CLUSTER_REL, MAX_BLOCK, MAX_COND, ModalBlock, ModalForm};
