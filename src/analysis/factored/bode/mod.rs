//! The evaluation form of the frequency kernels ([`BodeForm`]): a factored plant's reduced
//! zeros and poles as real first- and second-order factors with the low-frequency asymptote
//! K·s^k, checked against double-double Horner on the coefficients when the plant came with
//! them. The factored core builds it once per plant, at the first frequency response, margin
//! or grid, and caches it; the frequency response, the margins and the grids evaluate it. The
//! method (branch tracking, exact power-of-two rescaling, the logarithmic path, the Horner
//! fallback) is described in [`crate::analysis::freq`].
//!
//! Files: `form.rs` (the form, its construction and check, scalar evaluation), `factors.rs`
//! (real factors and their products), `horner.rs` (the double-double reference), `corners.rs`
//! (corner frequencies, lightly damped pairs, plotting ranges), `kernel.rs` (the fused
//! many-frequency kernel), `fastmath.rs` (`atan2` and `ln`), `avx2.rs` and `avx512.rs` (the
//! same kernel in SIMD, `cfg(ltikit_simd)`).

#[cfg(all(target_arch = "x86_64", ltikit_simd))]
mod avx2;
#[cfg(all(target_arch = "x86_64", ltikit_simd))]
mod avx512;
mod corners;
mod factors;
mod fastmath;
mod form;
mod horner;
mod kernel;

pub(crate) use factors::mul_pow2;
pub(crate) use form::BodeForm;
