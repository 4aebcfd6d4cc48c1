//! Second-order (mechanical) structure: A = [[0, I], [−G, −E]] — positions q, then velocities
//! q̇, with q̈ = −G·q − E·q̇ + … — where one positive diagonal similarity makes the stiffness G
//! and the damping E symmetric, and they commute (classical damping: none, Rayleigh
//! E = αI + βG, or any E with the same modes). Such a model is a set of uncoupled modes
//! η̈ₖ + γₖ·η̇ₖ + λₖ·ηₖ = …, found by a *symmetric* eigenproblem of half the order, whose
//! eigenvalues and vectors are accurate to ε‖G‖ whatever their multiplicity.
//!
//! MATLAB keeps such models apart as M, C, K (`mechss`); here the structure is recognised in
//! A itself, so a model built by hand, from a plant file or by the seed's lattice model gets
//! it without asking.
//!
//! # Recognition
//! 1. A is 2d×2d, its upper-left d×d block is exactly zero and its upper-right block exactly
//!    the identity (the states are positions, then their velocities).
//! 2. G = −A₂₁ and E = −A₂₂ are symmetric, or become symmetric under one diagonal similarity
//!    S = Δ·G·Δ⁻¹ (Δ = diag(δ), δ > 0: the square roots of the masses when G = M⁻¹K with M
//!    diagonal), found along a spanning forest of the coupling graph (δⱼ² = δᵢ²·gᵢⱼ/gⱼᵢ) and
//!    then checked on every entry: |sᵢⱼ − sⱼᵢ| ≤ [`SYM_REL`]·max(|sᵢⱼ|, |sⱼᵢ|).
//! 3. S_G = V·Λ·Vᵀ: when S_G and S_E are symmetric circulants (Δ = I: a periodic ring of
//!    identical cells, the seed's lattice) from the real Fourier basis and the transform of
//!    the first column (`circulant.rs`), else by nalgebra's `SymmetricEigen` (capped). Within
//!    each group of equal λ (single linkage at [`snap_tol`]) the damping VᵀS_E·V is
//!    diagonalised as well; the model is accepted when what is left off the diagonal of
//!    VᵀS_E·V is at most the same tolerance (the damping does not couple the modes) and the
//!    residual ‖S_G·V − V·Λ‖ is too (for the Fourier modes: the residuals ‖S_G·V − V·Λ‖ and
//!    ‖S_E·V − V·Γ‖, each within the tolerance of its matrix).
//!
//! # The modes
//! Mode k has stiffness λₖ and damping γₖ; both are snapped within [`snap_tol`] — to 0, and
//! the members of a group of equal values to their mean (a matrix within that distance of A
//! has them exactly: a free translation, degenerate pairs). Its eigenvalues are the roots of
//! μ² + γμ + λ = 0 from the discriminant rounded once (a fused multiply-add); when they are
//! closer than the cluster diameter of [`super::structure`]
//! (2·ν·(64nε)^(1/2)) the mode is *critical*: one double
//! eigenvalue −γ/2 with a single eigenvector (the 2×2 block is a companion matrix, never
//! diagonal): a Jordan block, like the rigid-body mode λ = γ = 0.
//!
//! # What the modes give
//! A recognised model needs no Schur form: its eigen structure ([`SecondOrder::eigen_structure`]:
//! clusters across modes, semisimple, one eigenvector per critical mode), its eigenvectors
//! ([`SecondOrder::eigenvectors`]: (x, μx) per mode) and its modal form
//! ([`SecondOrder::modal_form`]: 1×1 blocks except for critical modes) come from the modes.
//!
//! # Where the recognition runs
//! Once per model, at the edge: [`super::StateMatrix::recognise`] runs [`SecondOrder::detect`]
//! and hands the result (or its absence) to the kernels that can use it. The general kernels
//! ([`super::structure`], [`super::eigvec`], [`super::modal`]) know nothing of this module; it
//! builds on their types.
//!
//! Files: `recognise.rs` (the recognition and the modes), `circulant.rs` (the Fourier modes
//! of a periodic ring and its circulant blocks), `eigen.rs` (eigenvalues and
//! eigenvectors from the modes), `modal.rs` (the modal form from the modes), `zoh.rs` (the
//! zero-order-hold discretisation from the modes: [`SecondOrder::zoh`]), `sparse.rs` (G and E
//! by columns when sparse, for the residual of step 3 and the lower blocks of the ZOH).

mod circulant;
mod eigen;
mod modal;
mod recognise;
mod sparse;
mod zoh;

pub use recognise::{SPARSE_PER_COLUMN, SYM_REL, SecondOrder, SecondOrderMode, snap_tol};
