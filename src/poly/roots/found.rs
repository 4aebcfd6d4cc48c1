//! What the grouping finds: a root on the closed upper half plane with its multiplicity (a
//! non-real one stands for a conjugate pair), and the distance under which candidates group.

use num_complex::Complex64;

use crate::poly::Root;

/// Generous relative distance under which candidates are grouped for the multiplicity test.
/// The scatter of an m-fold root is ~eps^(1/m) relative: 2.5e-3 for m = 6, 0.03 for m = 10.
pub(super) const GROUP_REL: f64 = 0.1;

/// A root found in the closed upper half plane; a non-real one stands for a conjugate pair.
#[derive(Debug, Clone, Copy)]
pub(super) struct Found {
    pub(super) value: Complex64,
    pub(super) multiplicity: usize,
}

/// The roots with their conjugates added (each non-real root stands for a pair).
pub(super) fn expand_conjugates(found: &[Found]) -> Vec<Root> {
    let mut out = Vec::new();
    for f in found {
        out.push(Root {
            value: f.value,
            multiplicity: f.multiplicity,
        });
        if f.value.im != 0.0 {
            out.push(Root {
                value: f.value.conj(),
                multiplicity: f.multiplicity,
            });
        }
    }
    out
}
