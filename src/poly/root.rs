//! A root of a polynomial (a pole or a zero) with its multiplicity.

use num_complex::Complex64;
use serde::Serialize;

/// A root and its multiplicity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Root {
    /// The root.
    pub value: Complex64,
    /// How many times it is repeated (≥ 1).
    pub multiplicity: usize,
}

impl Root {
    /// True when the root is exactly real (imaginary part 0).
    pub fn is_real(&self) -> bool {
        self.value.im == 0.0
    }
}
