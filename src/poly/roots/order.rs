//! The order of root lists: sorted by decreasing real part, then decreasing imaginary part,
//! and listed with repetition.

use num_complex::Complex64;

use crate::poly::Root;

/// Roots listed with repetition (a double root appears twice), in the order of [`roots`](super::roots).
pub fn flatten(roots: &[Root]) -> Vec<Complex64> {
    roots
        .iter()
        .flat_map(|r| std::iter::repeat_n(r.value, r.multiplicity))
        .collect()
}

/// Sorts by decreasing real part, then decreasing imaginary part.
pub fn sort_roots(r: &mut [Root]) {
    r.sort_by(|a, b| {
        b.value
            .re
            .total_cmp(&a.value.re)
            .then(b.value.im.total_cmp(&a.value.im))
    });
}
