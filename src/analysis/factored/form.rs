//! The factored form itself: [`Factored`], the one constructor every source goes through
//! ([`assemble`]), what it answers directly, and the evaluation form it caches.

use std::cell::Cell;
use std::sync::OnceLock;

use num_complex::Complex64;

use super::bode::BodeForm;
use super::decision::Decision;
use super::low_frequency::LowFrequency;
use super::pole_zero::PoleZero;
use super::source::Source;
use crate::error::{LtiError, Result};
use crate::lti::{Domain, TransferFunction};
use crate::poly::{HalfPlane, Poly, Root};

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

/// A SISO plant in factored form (see the [module docs](super)).
#[derive(Debug, Clone)]
pub struct Factored {
    pz: PoleZero,
    gain: f64,
    source: Source,
    /// The evaluation form of the frequency kernels, built at first use (a clone keeps it).
    bode: OnceLock<BodeForm>,
    /// Which path decided the structure (exact or numerical).
    decision: Decision,
    /// Continuous (s) or discrete (z, with the sampling period).
    domain: Domain,
    /// Dead time T ≥ 0 (s) of the factor e^(−sT) beside the rational part (continuous time;
    /// a discrete delay is absorbed as poles at z = 0).
    delay: f64,
}

/// The one constructor of a [`Factored`]: every source (coefficients, exact coefficients,
/// zeros–poles–gain, state space, interconnections) builds its parts and hands them here.
/// The evaluation form starts empty, and the factorisation is counted
/// ([`factorizations_on_this_thread`]).
pub(super) fn assemble(pz: PoleZero, gain: f64, source: Source, decision: Decision) -> Factored {
    count_factorization();
    Factored {
        pz,
        gain,
        source,
        bode: OnceLock::new(),
        decision,
        domain: Domain::Continuous,
        delay: 0.0,
    }
}

impl Factored {
    /// Continuous or discrete time (with the sampling period): every analysis asks it.
    pub fn domain(&self) -> Domain {
        self.domain
    }

    /// The same factors read in `domain` (roots in the z-plane for [`Domain::Discrete`]).
    ///
    /// ```
    /// use ltikit::{Root, analysis::Factored, lti::Domain};
    /// use num_complex::Complex64 as C;
    /// let f = Factored::from_zpk(&[], &[Root::new(C::new(0.5, 0.0), 1)], 0.5).unwrap()
    ///     .with_domain(Domain::discrete(0.1).unwrap());
    /// assert_eq!(f.domain().dt(), Some(0.1));
    /// ```
    pub fn with_domain(mut self, domain: Domain) -> Factored {
        self.domain = domain;
        self.bode = OnceLock::new();
        self
    }

    /// The dead time T (s) of the factor e^(−sT) beside the rational part (0 without one).
    /// Every analysis reads it: the frequency response loses ωT of phase, a response is the
    /// rational one shifted by T, a closed loop around it is a delayed loop.
    pub fn delay(&self) -> f64 {
        self.delay
    }

    /// The same rational part with the dead time `delay` (s). In discrete time the delay must
    /// be a whole number d of sampling periods and is absorbed exactly as z^(−d) (d more
    /// poles at z = 0; [`Factored::delay`] stays 0).
    ///
    /// Errors: a negative, non-finite or too long delay
    /// ([`check_delay`](crate::lti::delay::check_delay)); in discrete time, not a whole
    /// number of periods.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let f = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap()
    ///     .factored().unwrap().with_delay(0.5).unwrap();
    /// assert_eq!(f.delay(), 0.5);
    /// assert_eq!(f.poles().len(), 1); // the rational part is unchanged
    /// ```
    pub fn with_delay(mut self, delay: f64) -> Result<Factored> {
        let delay = crate::lti::delay::check_delay(delay)?;
        match self.domain.dt() {
            None => {
                self.delay = delay;
                Ok(self)
            }
            Some(dt) => {
                let d = crate::lti::delay::delay_samples(delay, dt)?;
                if d == 0 {
                    return Ok(self);
                }
                let shift =
                    Factored::from_zpk(&[], &[Root::new(Complex64::new(0.0, 0.0), d)], 1.0)?
                        .with_domain(self.domain);
                self.series(&shift)
            }
        }
    }

    /// The rational part alone (the delay dropped; the cached evaluation form kept).
    pub fn rational(&self) -> Factored {
        let mut f = self.clone();
        f.delay = 0.0;
        f
    }

    /// The dead time replaced by its [n/n] Padé approximant
    /// ([`pade`](crate::lti::delay::pade)): a rational plant (the same one without a delay).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let f = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap()
    ///     .with_delay(0.5).unwrap().factored().unwrap();
    /// let p = f.pade(3).unwrap();
    /// assert_eq!((p.delay(), p.order()), (0.0, 4));
    /// ```
    pub fn pade(&self, n: usize) -> Result<Factored> {
        let approx = crate::lti::delay::pade(self.delay.max(0.0), n)?;
        if self.delay == 0.0 {
            return Ok(self.clone());
        }
        self.rational().series(&approx.factored()?)
    }

    /// G(s)·e^(−sT) at a complex point: [`Factored::eval`] times the delay factor.
    pub fn eval_delayed(&self, s: Complex64) -> Complex64 {
        let g = self.eval(s);
        if self.delay == 0.0 {
            g
        } else {
            g * (-s * self.delay).exp()
        }
    }

    /// Poles, zeros, cancellations and reduced root lists.
    pub fn pole_zero(&self) -> &PoleZero {
        &self.pz
    }

    /// The pole–zero part, taken out of the factored form.
    pub(super) fn into_pole_zero(self) -> PoleZero {
        self.pz
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
        Ok(TransferFunction::new(num, den)?.with_domain(self.domain))
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
        if self.domain().is_discrete() {
            return self.dc_gain_z();
        }
        let lf = self.low_frequency();
        match lf.int_order {
            k if k > 0 => Some(0.0),
            k if k < 0 => None,
            _ => Some(lf.value()),
        }
    }

    /// G(1) of a discrete-time plant (`None` with a reduced pole at z = 1, 0 with a reduced
    /// zero there).
    fn dc_gain_z(&self) -> Option<f64> {
        let one = Complex64::new(1.0, 0.0);
        if self.pz.reduced_poles.iter().any(|p| p.same_as(one)) {
            return None;
        }
        if self.pz.reduced_zeros.iter().any(|z| z.same_as(one)) {
            return Some(0.0);
        }
        Some(self.eval(one).re)
    }

    /// G(s) at a complex point: from the coefficients as given when the plant came with them
    /// (the reduced coefficients within 1e-6 relative of a cancelled root), else from the
    /// factors, multiplied in scaled form.
    pub fn eval(&self, s: Complex64) -> Complex64 {
        self.source.eval(self.gain, &self.pz, s)
    }

    /// The evaluation form of the frequency kernels, built on first use and then shared by
    /// every frequency response, margin and grid of this plant.
    pub(crate) fn bode(&self) -> &BodeForm {
        self.bode.get_or_init(|| {
            let coefficients = self
                .source
                .coefficients()
                .map(|c| (&c.tf, &c.reduced, self.pz.cancelled.as_slice()));
            BodeForm::new(
                self.is_zero(),
                self.low_frequency(),
                &self.pz.reduced_zeros,
                &self.pz.reduced_poles,
                coefficients,
                &|p| self.side_of(p),
            )
        })
    }

    /// The source (coefficients or factors).
    pub(crate) fn source(&self) -> &Source {
        &self.source
    }

    /// K and k of the low-frequency asymptote K·s^k of the reduced G.
    pub(crate) fn low_frequency(&self) -> LowFrequency {
        self.source.low_frequency(self.gain, &self.pz)
    }

    /// How the structure was decided.
    pub(super) fn decision(&self) -> &Decision {
        &self.decision
    }

    /// True when some reduced pole lies outside the open left half plane.
    pub(crate) fn has_unstable_pole(&self) -> bool {
        self.pz
            .reduced_poles
            .iter()
            .any(|p| self.side_of(p.value) != HalfPlane::Left)
    }
}
