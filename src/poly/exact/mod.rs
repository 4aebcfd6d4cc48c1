//! The exact path: polynomials with exact rational coefficients (as typed: `0.2` is 1/5) and
//! their structure decided without any tolerance.
//!
//! - [`Rational`]: exact numbers from text (decimals, exponents, fractions) with clear errors.
//! - [`ExactPoly`]: polynomials over ℚ (descending at the interface), exact arithmetic and
//!   division, gcd, square-free factorisation (Yun), exact half-plane counts, conversion to
//!   [`Poly`](crate::poly::Poly) (correctly rounded per coefficient).
//! - [`certify`]: the certified structure of N/D — a coprime basis of square-free factors with
//!   exact multiplicities in N and D, the exact gcd (cancellations), the reduced N and D, exact
//!   half-plane counts, and every root to full double precision.
//! - [`ExactPoly::unit_circle_counts`] and [`Factor::circle_sides`]: the same decided against
//!   the unit circle (discrete time), by the bilinear map z = (1 + w)/(1 − w).
//!
//! # Methods
//! - **gcd**: modular (Brown): gcds modulo 31-bit primes, Chinese remaindering, certified by
//!   trial division in ℤ\[s\]. One prime proves coprimality, the common case.
//! - **Square-free factorisation**: Yun's algorithm on the primitive integer polynomial, all
//!   divisions exact in ℤ\[s\]. Numerator and denominator factors are merged into a pairwise
//!   coprime basis, so every distinct root is computed once and cancels exactly.
//! - **Half planes**: for each square-free factor b = E(s²) + s·O(s²): the roots symmetric about
//!   the origin are those of g(s²), g = gcd(E, O) (the Routh "zero row"), counted by a Sturm
//!   sequence of g on (−∞, 0); the rest by the Cauchy index of Ẽ/Õ computed with a subresultant
//!   remainder sequence (degree drops — Routh's "zero first element" — need no ε). Root values
//!   never enter the counts.
//! - **Roots**: each square-free factor's roots are simple: Aberth–Ehrlich iteration in
//!   complex double-double from the companion eigenvalues, then Braess–Hadeler inclusion disks
//!   with rigorous error bounds prove that every disk holds exactly one root and which roots
//!   are real; conjugates are made exact, real roots exactly real, axis roots exactly
//!   imaginary (they come from the negative real roots of g).
//!
//! # Budget
//! Degree ≤ [`MAX_EXACT_DEGREE`], coefficients of the primitive integer polynomial ≤
//! [`MAX_EXACT_BITS`] bits, gcd coefficients within the modular prime table (~3900 bits) and
//! roots separable in double-double (relative separation above ~10⁻²⁸). Beyond it the functions
//! return [`LtiError::BeyondExactBudget`](crate::LtiError::BeyondExactBudget): use the
//! numerical path.

mod budget;
mod cdd;
mod certify;
mod circle;
mod disk;
mod modular;
mod mp;
mod number;
mod qpoly;
mod refine;
mod sqfree;
mod sturm;
mod zpoly;

pub use budget::{MAX_EXACT_BITS, MAX_EXACT_DEGREE, MAX_EXACT_WORK};
pub use certify::{CertifiedRoot, Factor, Side, Structure, certify};
pub use circle::{CircleCounts, CircleSide};
pub use number::{MAX_DIGITS, MAX_EXPONENT, Rational};
pub use qpoly::ExactPoly;
pub use sturm::HalfPlaneCounts;
