//! The factored form of a SISO plant: computed once, read by every analysis.
//!
//! A plant enters ltikit as ODE coefficients (a [`TransferFunction`]) or as zeros, poles and a
//! gain; a state-space channel will enter through its eigenvalues, transmission zeros and
//! first Markov parameter. Whatever the source, it is factored **once** into a [`Factored`]:
//!
//! - poles and zeros with exact multiplicities, the common roots that cancel, and the reduced
//!   (lowest-terms) poles and zeros ([`PoleZero`]);
//! - the gain k of G(s) = k·Π(s − zᵢ)/Π(s − pᵢ) (as given and reduced alike);
//! - the source itself, kept for what it does better than the roots: the coefficients of a
//!   transfer function evaluate G accurately where the roots are ill-conditioned (clusters),
//!   give the dc gain exactly and realise the response in controllable canonical form;
//! - lazily, the evaluation form of the frequency kernels (built at the first frequency
//!   response, margin or grid, then shared).
//!
//! Stability, modes, partial fractions, closed forms and exact responses, step metrics,
//! frequency response, margins, Nyquist, asymptotes and the automatic grids are methods of
//! [`Factored`]; the [`TransferFunction`] methods of the same names are one-line delegates that
//! factor first. A caller that runs several analyses of one plant factors it once:
//!
//! ```
//! use ltikit::TransferFunction;
//! let g = TransferFunction::from_descending(&[2.0], &[1.0, 3.0, 2.0, 0.0]).unwrap();
//! let f = g.factored().unwrap();          // the only root finding
//! let a = f.analyze().unwrap();           // poles, stability, modes, step metrics
//! let m = f.margins().unwrap();           // margins on the same factors
//! assert!(a.stability.internal_reason.contains("marginally"));
//! assert!((m.gain_margin.unwrap() - 3.0).abs() < 1e-12);
//! ```
//!
//! Nothing downstream needs polynomial coefficients that a factored source cannot provide:
//! where the coefficients help (accuracy, the canonical realisation, the polynomials of the
//! margin equations) the analyses ask the source, and a source without coefficients answers
//! from the factors.

mod display;
mod exact;
mod interconnect;
mod plant;
mod pole_zero;
pub(crate) mod series;
mod source;
mod ss_modal;
mod ss_source;

use std::cell::Cell;
use std::sync::OnceLock;

use num_complex::Complex64;

pub use exact::StructurePath;
pub use interconnect::Feedback;
pub(crate) use interconnect::{close, series_parts};
pub use pole_zero::PoleZero;
pub(crate) use pole_zero::count;
pub(crate) use series::ScaledProduct;
pub(crate) use source::{LowFrequency, Source};

use crate::analysis::freq::BodeForm;
use crate::error::{LtiError, Result, check_finite};
use crate::lti::TransferFunction;
use crate::poly::{HalfPlane, Poly, Root};

/// Highest order (number of poles with multiplicity) of a factored plant. Polynomial
/// coefficients stop at [`crate::MAX_ORDER`]; a factored plant (a state-space channel) may be
/// larger.
pub const MAX_FACTORED_ORDER: usize = crate::limits::MAX_FACTORED_ORDER;

thread_local! {
    static FACTORIZATIONS: Cell<usize> = const { Cell::new(0) };
}

/// How many plants have been factored on the calling thread so far (a diagnostic: the
/// analyses of one plant should factor it once; tests count with it).
///
/// ```
/// use ltikit::TransferFunction;
/// use ltikit::analysis::factorizations_on_this_thread;
/// let g = TransferFunction::from_descending(&[1.0], &[1.0, 2.0, 1.0]).unwrap();
/// let before = factorizations_on_this_thread();
/// let f = g.factored().unwrap();
/// let _ = (f.analyze().unwrap(), f.margins().unwrap(), f.freq_response(&[1.0]).unwrap());
/// assert_eq!(factorizations_on_this_thread() - before, 1);
/// ```
pub fn factorizations_on_this_thread() -> usize {
    FACTORIZATIONS.with(|c| c.get())
}

fn count_factorization() {
    FACTORIZATIONS.with(|c| c.set(c.get() + 1));
}

/// A SISO plant in factored form (see the [module docs](self)).
#[derive(Debug)]
pub struct Factored {
    pz: PoleZero,
    gain: f64,
    source: Source,
    bode: OnceLock<BodeForm>,
    /// Which path decided the structure (exact or numerical).
    decision: exact::Decision,
}

impl Clone for Factored {
    fn clone(&self) -> Self {
        let bode = OnceLock::new();
        if let Some(b) = self.bode.get() {
            let _ = bode.set(b.clone());
        }
        Factored {
            pz: self.pz.clone(),
            gain: self.gain,
            source: self.source.clone(),
            bode,
            decision: self.decision.clone(),
        }
    }
}

impl TransferFunction {
    /// The factored form of G: roots of the numerator and denominator with exact
    /// multiplicities, the cancelled common roots and the reduced form. Every analysis method
    /// of [`TransferFunction`] calls this first; call it once yourself to run several
    /// analyses on one factorisation.
    ///
    /// Errors: the root finder's ([`crate::Poly::roots`]).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // s / (s (s + 1)): the pole at 0 cancels, the reduced G is 1/(s + 1).
    /// let g = TransferFunction::from_descending(&[1.0, 0.0], &[1.0, 1.0, 0.0]).unwrap();
    /// let f = g.factored().unwrap();
    /// assert_eq!(f.pole_zero().cancelled.len(), 1);
    /// assert_eq!(f.reduced_tf().unwrap().den().coeffs(), &[1.0, 1.0]);
    /// assert_eq!(f.pole_zero().zeros_at_infinity, Some(1));
    /// ```
    pub fn factored(&self) -> Result<Factored> {
        Factored::from_tf(self)
    }

    /// Poles, zeros, cancelled common roots and the reduced root lists
    /// ([`Factored::pole_zero`] of [`TransferFunction::factored`]).
    ///
    /// A numerator root and a denominator root cancel when they are the same root
    /// ([`crate::poly::same_root`]: 1e-8 relative; exactly for roots at s = 0).
    pub fn pole_zero(&self) -> Result<PoleZero> {
        Ok(self.factored()?.pz)
    }

    /// dc gain lim s→0 of the reduced G: `None` when infinite (a pole at s = 0 remains).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let g = TransferFunction::from_descending(&[1.0, 0.0], &[1.0, 1.0, 0.0]).unwrap();
    /// assert_eq!(g.dc_gain().unwrap(), Some(1.0)); // s/(s(s+1)) → 1
    /// let i = TransferFunction::from_descending(&[1.0], &[1.0, 0.0]).unwrap();
    /// assert_eq!(i.dc_gain().unwrap(), None);       // 1/s
    /// ```
    pub fn dc_gain(&self) -> Result<Option<f64>> {
        Ok(self.factored()?.dc_gain())
    }
}

impl Factored {
    /// Factors a transfer function given by its coefficients.
    pub fn from_tf(tf: &TransferFunction) -> Result<Factored> {
        let zero = tf.num().is_zero();
        let poles = tf.den().roots()?;
        let zeros = if zero { Vec::new() } else { tf.num().roots()? };
        let pz = PoleZero::new(poles, zeros, zero);
        let reduced = if pz.cancelled.is_empty() {
            tf.clone()
        } else {
            let common = Poly::from_root_list(&pz.cancelled)?;
            let (num, _) = tf.num().div_rem(&common)?;
            let (den, _) = tf.den().div_rem(&common)?;
            TransferFunction::new(num, den)?
        };
        count_factorization();
        Ok(Factored {
            gain: if zero { 0.0 } else { tf.gain() },
            pz,
            source: Source::coefficients_of(tf.clone(), reduced),
            bode: OnceLock::new(),
            decision: exact::Decision::default(),
        })
    }

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
        count_factorization();
        Ok(Factored {
            gain,
            pz,
            source: Source::Factors,
            bode: OnceLock::new(),
            decision: exact::Decision::default(),
        })
    }

    /// A factored plant from its parts (the structure decided numerically unless the caller
    /// says otherwise).
    pub(crate) fn with_source(pz: PoleZero, gain: f64, source: Source) -> Factored {
        Factored {
            pz,
            gain,
            source,
            bode: OnceLock::new(),
            decision: exact::Decision::default(),
        }
    }

    /// Poles, zeros, cancellations and reduced root lists.
    pub fn pole_zero(&self) -> &PoleZero {
        &self.pz
    }

    /// Characteristic roots (the denominator as given), with multiplicities.
    pub fn poles(&self) -> &[Root] {
        &self.pz.poles
    }

    /// Finite zeros as given.
    pub fn zeros(&self) -> &[Root] {
        &self.pz.zeros
    }

    /// Poles of G in lowest terms.
    pub fn reduced_poles(&self) -> &[Root] {
        &self.pz.reduced_poles
    }

    /// Zeros of G in lowest terms.
    pub fn reduced_zeros(&self) -> &[Root] {
        &self.pz.reduced_zeros
    }

    /// The gain k of G(s) = k·Π(s − zᵢ)/Π(s − pⱼ) (the ratio of the leading coefficients;
    /// 0 for G ≡ 0).
    pub fn gain(&self) -> f64 {
        self.gain
    }

    /// True for G ≡ 0.
    pub fn is_zero(&self) -> bool {
        self.pz.zeros_at_infinity.is_none()
    }

    /// System order: the number of characteristic roots.
    pub fn order(&self) -> usize {
        self.pz.order()
    }

    /// deg D − deg N (negative for an improper G); `None` for G ≡ 0.
    pub fn relative_degree(&self) -> Option<i64> {
        (!self.is_zero()).then(|| self.order() as i64 - self.pz.num_degree() as i64)
    }

    /// True when deg N ≤ deg D (G ≡ 0 is proper).
    pub fn is_proper(&self) -> bool {
        self.relative_degree().is_none_or(|r| r >= 0)
    }

    /// Errors with [`LtiError::Improper`] unless proper (strictly proper when `strict`).
    pub fn require_proper(&self, operation: &str, strict: bool) -> Result<()> {
        let Some(r) = self.relative_degree() else {
            return Ok(());
        };
        if r > 0 || (r == 0 && !strict) {
            return Ok(());
        }
        let n = self.order();
        Err(LtiError::Improper {
            operation: operation.into(),
            required: if strict { "strictly proper" } else { "proper" }.into(),
            num_degree: self.pz.num_degree(),
            den_degree: n,
            limit: if strict { n.saturating_sub(1) } else { n },
        })
    }

    /// The plant's coefficients, when it was given by them.
    pub fn transfer_function(&self) -> Option<&TransferFunction> {
        self.source.coefficients().map(|c| &c.tf)
    }

    /// G in lowest terms as coefficients: the given numerator and denominator divided by the
    /// cancelled common factor, or, for a plant without coefficients, expanded from the
    /// reduced factors (errors beyond [`crate::MAX_ORDER`]).
    pub fn reduced_tf(&self) -> Result<TransferFunction> {
        if let Some(c) = self.source.coefficients() {
            return Ok(c.reduced.clone());
        }
        let num = Poly::from_root_list(&self.pz.reduced_zeros)?.scale(self.gain);
        let den = Poly::from_root_list(&self.pz.reduced_poles)?;
        TransferFunction::new(num, den)
    }

    /// The characteristic polynomial (monic for a factored source).
    pub(crate) fn characteristic_poly(&self) -> Result<Poly> {
        match self.source.coefficients() {
            Some(c) => Ok(c.tf.den().clone()),
            None => Poly::from_root_list(&self.pz.poles),
        }
    }

    /// dc gain lim s→0 of the reduced G; `None` when infinite (a pole at s = 0 remains).
    /// From coefficients it is the ratio of the lowest non-zero coefficients of the plant as
    /// given (exact to rounding, and unaffected by a cancelled factor).
    pub fn dc_gain(&self) -> Option<f64> {
        if self.is_zero() {
            return Some(0.0);
        }
        let lf = self.low_frequency();
        match lf.int_order {
            k if k > 0 => Some(0.0),
            k if k < 0 => None,
            _ => Some(lf.value()),
        }
    }

    /// G(s) at a complex point: from the coefficients as given when the plant came with them
    /// (the reduced coefficients within 1e-6 relative of a cancelled root), else from the
    /// factors, multiplied in scaled form.
    pub fn eval(&self, s: Complex64) -> Complex64 {
        self.source.eval(self, s)
    }

    /// The evaluation form of the frequency kernels, built on first use.
    pub(crate) fn bode(&self) -> &BodeForm {
        self.bode.get_or_init(|| BodeForm::new(self))
    }

    /// The source (coefficients or factors).
    pub(crate) fn source(&self) -> &Source {
        &self.source
    }

    /// K and k of the low-frequency asymptote K·s^k of the reduced G.
    pub(crate) fn low_frequency(&self) -> LowFrequency {
        self.source.low_frequency(self)
    }

    /// True when some reduced pole lies outside the open left half plane.
    pub(crate) fn has_unstable_pole(&self) -> bool {
        self.pz
            .reduced_poles
            .iter()
            .any(|p| self.side_of(p.value) != HalfPlane::Left)
    }
}

/// Validates, merges equal roots and sorts a root list (decreasing real part, then
/// decreasing imaginary part, as [`crate::Poly::roots`]); conjugates are made exact.
fn canonical_roots(roots: &[Root], what: &str) -> Result<Vec<Root>> {
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

    #[test]
    fn zero_transfer_function() {
        let g = TransferFunction::from_descending(&[0.0], &[1.0, 1.0]).unwrap();
        let f = g.factored().unwrap();
        assert!(f.is_zero());
        assert_eq!(f.relative_degree(), None);
        assert_eq!(f.dc_gain(), Some(0.0));
        assert!(f.require_proper("x", true).is_ok());
    }
}
