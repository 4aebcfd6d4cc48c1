//! Dense linear-algebra kernels for state-space models, one algorithm per file.
//!
//! Everything here is a pure function (or a struct built once) on nalgebra matrices, with our
//! own implementations where nalgebra 0.35 has none or is too slow or too inaccurate. The
//! kernels that only serve the others (Householder reflectors, the Francis iteration, the
//! complex Schur form) are internal:
//!
//! | file | what | method |
//! |---|---|---|
//! | [`mod@hessenberg`] | H = QᵀAQ | Householder reflectors, column-major sweeps |
//! | [`francis`] (its iteration cap; the kernel is internal) | real Schur form of a Hessenberg matrix | double-shift QR (Francis), Ahues–Tisseur deflation, exceptional shifts, 2×2 blocks standardised |
//! | [`schur`] | A = D·Q·T·Qᵀ·D⁻¹ with eigenvalues | balancing + power-of-two scaling + the two above, capped, one retry after a Householder similarity |
//! | `complex_schur.rs` (internal) | complex triangular Schur form | one unitary rotation per 2×2 block |
//! | [`structure`] | multiplicities of eigenvalues | size-dependent clustering, dim null(A − λI) from a reduced m×m problem |
//! | [`eigvec`] | eigenvectors (mode shapes) with residuals | back-substitution on the Schur form |
//! | [`modal`] | block-diagonal (modal) form | clusters, reordering and Sylvester solves on the complex Schur form |
//! | [`second_order`] | mechanical structure [[0, I], [−G, −E]], and the eigenvalues, eigenvectors and modal form of its modes | symmetric eigenproblem of half the order (diagonal symmetrisation, classical damping) |
//! | [`state_matrix`] | a model's A with its recognised structure: the one place the recognition runs | the modes' kernels for a second-order A, the general ones otherwise |
//! | [`freqresp`] | C(sI − A)⁻¹B + D at many s | one Hessenberg reduction, then an O(n²) elimination per s |
//! | `lu.rs` (internal) | A·X = B, many right-hand sides | LU with partial pivoting blocked as LAPACK `dgetrf` (panel + matrix products) |
//! | [`rrqr`] | numerical rank | Householder QR with column pivoting |
//! | [`staircase`] | controllability / observability | orthogonal staircase (Van Dooren 1981, Varga) |
//! | [`minreal`] | minimal realisation | two staircases, removed modes reported |
//! | [`zeros`] | invariant and transmission zeros | Emami-Naeini & Van Dooren (1982) pencil reduction |
//! | `hessenberg_zeros.rs` (internal) | a SISO channel's zeros from the staircases' Hessenberg form | the Schur complement of the pencil's pivot: an upper Hessenberg zero dynamics, one Francis run; growth-bounded, else the pencil |
//! | [`lyapunov`] | Sylvester A·X + X·B = C, Lyapunov A·X + X·Aᵀ + Q = 0 and A·X·Aᵀ − X + Q = 0, with residual and condition estimate | Bartels–Stewart on the unbalanced real Schur form, real quasi-triangular solve (`dtrsyl` scheme, `trsyl.rs`, internal) |
//! | [`mod@hammarling`] | Cholesky factor L·Lᵀ = X of a Lyapunov solution with Q = B·Bᵀ (Gramians) | Hammarling (1982) on the complex Schur form, Givens updates |
//! | [`riccati`] | stabilising solutions of the continuous and discrete algebraic Riccati equations with a cross term, gain, closed-loop eigenvalues | care: ordered complex Schur form of the Hamiltonian; dare: structure-preserving doubling; then Newton (Kleinman / Hewer) defect correction |
//! | [`markov`] | relative degree, first non-zero Markov parameter | the same reduction, and CA^kB directly |
//! | `componentwise.rs` (internal) | a channel's relative degree and zeros below the pencil's normwise tolerance | C·A^k·B against its componentwise rounding bound, the reduction forced to that degree, zeros refined by Newton on G |
//!
//! Why not nalgebra's `Schur`: at n = 256 it takes ~180 ms for a random matrix with a
//! backward error ‖QTQᵀ − A‖_F/‖A‖_F of 2e-13 (7.6e-13 at n = 1000, 11 s); it hangs without
//! an iteration cap on cyclic matrices (DESIGN §5) and its 2×2 blocks are not standardised.

pub(crate) mod complex_schur;
pub(crate) mod componentwise;
pub mod eigvec;
pub mod francis;
pub mod freqresp;
pub mod hammarling;
pub mod hessenberg;
pub(crate) mod hessenberg_zeros;
pub(crate) mod householder;
pub(crate) mod lu;
pub mod lyapunov;
pub mod markov;
pub(crate) mod matvec;
pub mod minreal;
pub mod modal;
pub mod riccati;
pub mod rrqr;
pub mod schur;
pub mod second_order;
pub mod staircase;
pub mod state_matrix;
pub mod structure;
pub mod zeros;

pub(crate) mod checks;
pub(crate) mod norms;
pub(crate) mod trsyl;

pub use eigvec::EigenvectorSet;

/// M^e by binary powers (⌈log₂ e⌉ squarings): the map of e samples of a discrete-time model,
/// read by both marchers of discrete time (a transfer function's realisation with its input
/// generator, and a state-space model with held inputs).
pub(crate) fn matrix_power(m: &nalgebra::DMatrix<f64>, e: u64) -> nalgebra::DMatrix<f64> {
    let mut result = nalgebra::DMatrix::identity(m.nrows(), m.ncols());
    let mut base = m.clone();
    let mut e = e;
    while e > 0 {
        if e & 1 == 1 {
            result = &result * &base;
        }
        e >>= 1;
        if e > 0 {
            base = &base * &base;
        }
    }
    result
}
pub use freqresp::HessenbergResponse;
pub use hessenberg::{Hessenberg, hessenberg};
pub use lyapunov::{
    CholeskySolution, MatrixSolution, dlyap, dlyap_cholesky, lyap, lyap_cholesky, sylvester,
};
pub use markov::{RelativeDegree, markov_parameter, relative_degree};
pub use minreal::{MinimalRealization, minimal_realization};
pub use riccati::{Riccati, care, dare};
pub use schur::{RealSchur, SchurOptions, real_schur, schur_eigenvalues};
pub use staircase::{Staircase, controllability_staircase, observability_staircase};
pub use state_matrix::{StateMatrix, eigen_structure, eigenvectors};
pub use structure::{EigenCluster, EigenStructure};
pub use zeros::{InvariantZeros, KroneckerStructure, invariant_zeros, transmission_zeros};
