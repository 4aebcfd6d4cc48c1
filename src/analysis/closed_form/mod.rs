//! Closed-form time functions in real form: the inverse Laplace transform of a partial-fraction
//! expansion.
//!
//! A term r/(s − p)^k is r·t^(k−1)/(k−1)!·e^(pt). Terms are grouped by pole:
//! - the direct polynomial Σ cₖ sᵏ gives cₖ·δ^(k)(t);
//! - a real pole p of multiplicity m gives (c₀ + c₁t + … + c_{m−1}t^(m−1))·e^(pt);
//! - a conjugate pair σ ± jω gives e^(σt)·Σₖ Aₖ tᵏ cos(ωt + φₖ) (seed eq. 3.33), with
//!   Aₖ = 2|r_{k+1}|/k! and φₖ = arg r_{k+1}, normalised to φₖ ∈ [−π/2, π/2] by moving the sign
//!   into Aₖ (at ±π/2 the amplitude stays positive), so a step response reads
//!   `1 - 1.1547 e^(-0.5 t) cos(0.866025 t - 0.523599)` and sin t reads `cos(t - 1.5708)`.
//!
//! [`ClosedForm::eval`] is the smooth part for t ≥ 0 (δ terms excluded; 0 for t < 0: every
//! term carries 1(t)).
//!
//! A discrete-time response is a closed-form sequence y\[k\] instead ([`SequenceForm`], the
//! inverse z-transform of the partial fractions of Y(z)/z: sums of k^j·p^k terms and delayed
//! unit samples), held by the same [`ClosedForm`] type so that a response has one shape in s
//! and in z.

mod form;
mod sequence;
mod term;
mod text;
mod words;

pub use form::ClosedForm;
pub(crate) use sequence::sample_floor;
pub use sequence::{SequenceForm, SequenceTerm};
pub use term::ClosedFormTerm;
