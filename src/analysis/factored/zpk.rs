//! A plant given by its zeros, poles and gain: kept in factored form, no coefficients formed.

use super::decision::Decision;
use super::form::{Factored, assemble};
use super::pole_zero::{MAX_FACTORED_ORDER, PoleZero, count};
use super::source::Source;
use crate::error::{LtiError, Result, check_finite};
use crate::poly::Root;

impl Factored {
    /// A plant given by its zeros, poles (with multiplicities) and gain k:
    /// G(s) = k·Π(s − zᵢ)^mᵢ / Π(s − pⱼ)^mⱼ, kept in factored form (no coefficients are
    /// formed, so high orders and high multiplicities stay exact). Complex roots must come
    /// with their conjugates (same multiplicity); equal roots are merged.
    ///
    /// Errors: NaN/∞ values, a complex root without its conjugate, a multiplicity of 0, more
    /// than [`MAX_FACTORED_ORDER`] poles or zeros.
    ///
    /// ```
    /// use ltikit::analysis::Factored;
    /// use ltikit::Root;
    /// use num_complex::Complex64 as C;
    /// // (s + 1)^20 exactly: a 20-fold pole that coefficients could not carry.
    /// let f = Factored::from_zpk(&[], &[Root::new(C::new(-1.0, 0.0), 20)], 1.0).unwrap();
    /// assert_eq!(f.poles()[0].multiplicity, 20);
    /// assert_eq!(f.dc_gain(), Some(1.0));
    /// assert!(f.stability().bibo_stable);
    /// ```
    pub fn from_zpk(zeros: &[Root], poles: &[Root], gain: f64) -> Result<Factored> {
        check_finite(|| "the gain".into(), gain)?;
        let zeros = if gain == 0.0 {
            Vec::new()
        } else {
            canonical_roots(zeros, "zero")?
        };
        let poles = canonical_roots(poles, "pole")?;
        let pz = PoleZero::new(poles, zeros, gain == 0.0);
        Ok(assemble(pz, gain, Source::Factors, Decision::default()))
    }
}

/// Validates, merges equal roots and sorts a root list (decreasing real part, then
/// decreasing imaginary part, as [`crate::Poly::roots`]); conjugates are made exact.
pub(super) fn canonical_roots(roots: &[Root], what: &str) -> Result<Vec<Root>> {
    let mut out: Vec<Root> = Vec::new();
    for (i, r) in roots.iter().enumerate() {
        check_finite(|| format!("real part of {what} {i}"), r.value.re)?;
        check_finite(|| format!("imaginary part of {what} {i}"), r.value.im)?;
        if r.multiplicity == 0 {
            return Err(LtiError::invalid(format!(
                "{what} {i} has multiplicity 0 (must be ≥ 1)"
            )));
        }
        match out.iter_mut().find(|q| q.value == r.value) {
            Some(q) => q.multiplicity += r.multiplicity,
            None => out.push(*r),
        }
    }
    let total = count(&out);
    if total > MAX_FACTORED_ORDER {
        return Err(LtiError::OrderTooHigh {
            order: total,
            max: MAX_FACTORED_ORDER,
        });
    }
    // every upper root has a lower partner of the same multiplicity
    for r in out.iter().filter(|r| r.value.im > 0.0) {
        let partner = out.iter().find(|q| q.value == r.value.conj());
        if partner.is_none_or(|q| q.multiplicity != r.multiplicity) {
            return Err(LtiError::invalid(format!(
                "{what} {} + {}j has no complex conjugate partner of the same multiplicity: a real plant needs conjugate pairs",
                r.value.re, r.value.im
            )));
        }
    }
    if let Some(r) = out
        .iter()
        .find(|r| r.value.im < 0.0 && !out.iter().any(|q| q.value == r.value.conj()))
    {
        return Err(LtiError::invalid(format!(
            "{what} {} {}j has no complex conjugate partner: a real plant needs conjugate pairs",
            r.value.re, r.value.im
        )));
    }
    crate::poly::roots::sort_roots(&mut out);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::Complex64 as C;

    #[test]
    fn zpk_validation() {
        let pair = [
            Root::new(C::new(-1.0, 2.0), 1),
            Root::new(C::new(-1.0, -2.0), 1),
        ];
        assert!(Factored::from_zpk(&[], &pair, 1.0).is_ok());
        assert!(Factored::from_zpk(&[], &pair[..1], 1.0).is_err());
        assert!(Factored::from_zpk(&[], &[Root::new(C::new(f64::NAN, 0.0), 1)], 1.0).is_err());
        assert!(Factored::from_zpk(&[], &[Root::new(C::new(-1.0, 0.0), 0)], 1.0).is_err());
        assert!(Factored::from_zpk(&[], &pair, f64::INFINITY).is_err());
        let big = [Root::new(C::new(-1.0, 0.0), MAX_FACTORED_ORDER + 1)];
        assert!(matches!(
            Factored::from_zpk(&[], &big, 1.0),
            Err(LtiError::OrderTooHigh { .. })
        ));
    }

    #[test]
    fn zpk_merges_and_sorts() {
        let f = Factored::from_zpk(
            &[],
            &[
                Root::new(C::new(-2.0, 0.0), 1),
                Root::new(C::new(-1.0, 0.0), 2),
                Root::new(C::new(-2.0, 0.0), 1),
            ],
            3.0,
        )
        .unwrap();
        assert_eq!(
            f.poles(),
            &[
                Root::new(C::new(-1.0, 0.0), 2),
                Root::new(C::new(-2.0, 0.0), 2)
            ]
        );
        assert_eq!(f.order(), 4);
        assert_eq!(f.relative_degree(), Some(4));
        assert!((f.dc_gain().unwrap() - 0.75).abs() < 1e-15);
    }
}
