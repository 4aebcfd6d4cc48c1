//! Poles, zeros and the common roots that cancel (the pole/zero part of the factored form).

use num_complex::Complex64;
use serde::Serialize;

use crate::poly::Root;

/// Highest order (number of poles with multiplicity) of a factored plant. Polynomial
/// coefficients stop at [`crate::MAX_ORDER`]; a factored plant (a state-space channel) may be
/// larger.
pub const MAX_FACTORED_ORDER: usize = crate::limits::MAX_FACTORED_ORDER;

/// Everything about the roots of a SISO plant.
///
/// The *characteristic* roots ([`PoleZero::poles`]) are those of the plant as given — the
/// denominator of the ODE, or the eigenvalues of a state matrix — and decide internal
/// stability; the *reduced* roots are those of the input→output map in lowest terms and decide
/// BIBO stability, the dc gain, the frequency and step responses.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PoleZero {
    /// Characteristic roots (the denominator as given), with multiplicities.
    pub poles: Vec<Root>,
    /// Finite zeros as given (empty for G ≡ 0).
    pub zeros: Vec<Root>,
    /// Common roots of numerator and denominator, with the multiplicity that cancels.
    pub cancelled: Vec<Root>,
    /// Poles of the reduced (lowest-terms) transfer function.
    pub reduced_poles: Vec<Root>,
    /// Zeros of the reduced transfer function.
    pub reduced_zeros: Vec<Root>,
    /// Zeros at infinity: the relative degree (0 for an improper G); `None` for G ≡ 0, which
    /// has no meaningful relative degree.
    pub zeros_at_infinity: Option<usize>,
}

/// Total multiplicity of a root list.
pub(crate) fn count(roots: &[Root]) -> usize {
    roots.iter().map(|r| r.multiplicity).sum()
}

/// Equal values merged (exact equality), multiplicities added, in order of first appearance.
pub(super) fn merge(values: &[(Complex64, usize)]) -> Vec<(Complex64, usize)> {
    let mut out: Vec<(Complex64, usize)> = Vec::new();
    for &(v, m) in values {
        match out.iter_mut().find(|(w, _)| *w == v) {
            Some((_, k)) => *k += m,
            None => out.push((v, m)),
        }
    }
    out
}

impl PoleZero {
    /// Matches numerator roots with denominator roots ([`Root::same_as`]) and builds the
    /// reduced lists. `zero` says G ≡ 0 (then there are no zeros and nothing cancels).
    pub(crate) fn new(poles: Vec<Root>, zeros: Vec<Root>, zero: bool) -> PoleZero {
        let mut zero_left = zeros.clone();
        let mut cancelled = Vec::new();
        let mut pole_left = Vec::new();
        for p in &poles {
            let mut m = p.multiplicity;
            if let Some(z) = zero_left
                .iter_mut()
                .find(|z| z.multiplicity > 0 && z.same_as(p.value))
            {
                let k = m.min(z.multiplicity);
                z.multiplicity -= k;
                m -= k;
                cancelled.push(Root::new(p.value, k));
            }
            if m > 0 {
                pole_left.push(Root::new(p.value, m));
            }
        }
        zero_left.retain(|z| z.multiplicity > 0);
        let zeros_at_infinity = (!zero).then(|| count(&poles).saturating_sub(count(&zeros)));
        PoleZero {
            poles,
            zeros,
            cancelled,
            reduced_poles: pole_left,
            reduced_zeros: zero_left,
            zeros_at_infinity,
        }
    }

    /// From lists decided elsewhere (the certified structure of exact input).
    pub(crate) fn from_parts(
        poles: Vec<Root>,
        zeros: Vec<Root>,
        cancelled: Vec<Root>,
        reduced_poles: Vec<Root>,
        reduced_zeros: Vec<Root>,
        zero: bool,
    ) -> PoleZero {
        let zeros_at_infinity = (!zero).then(|| count(&poles).saturating_sub(count(&zeros)));
        PoleZero {
            poles,
            zeros,
            cancelled,
            reduced_poles,
            reduced_zeros,
            zeros_at_infinity,
        }
    }

    /// Order: the number of characteristic roots (with multiplicity).
    pub fn order(&self) -> usize {
        count(&self.poles)
    }

    /// The number of zeros as given (with multiplicity).
    pub fn num_degree(&self) -> usize {
        count(&self.zeros)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::Complex64 as C;

    fn r(re: f64, m: usize) -> Root {
        Root::new(C::new(re, 0.0), m)
    }

    #[test]
    fn partial_cancellation_of_a_double_pole() {
        // (s+1) / ((s+1)² (s+2))
        let pz = PoleZero::new(vec![r(-1.0, 2), r(-2.0, 1)], vec![r(-1.0, 1)], false);
        assert_eq!(pz.cancelled, vec![r(-1.0, 1)]);
        assert_eq!(pz.reduced_poles, vec![r(-1.0, 1), r(-2.0, 1)]);
        assert!(pz.reduced_zeros.is_empty());
        assert_eq!(pz.zeros_at_infinity, Some(2));
        assert_eq!(pz.order(), 3);
    }

    #[test]
    fn zero_transfer_function_has_no_zeros_at_infinity() {
        let pz = PoleZero::new(vec![r(-1.0, 1)], vec![], true);
        assert_eq!(pz.zeros_at_infinity, None);
        assert!(pz.cancelled.is_empty());
    }
}
