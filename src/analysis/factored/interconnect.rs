//! Interconnections of factored plants, in the one shape of every model type
//! ([`crate::lti::interconnect`]: `series(&self, &next)`, `parallel(&self, &other)`,
//! `feedback(&self, &h, sign)`, the two domains joined): series keeps the factors, parallel and
//! feedback find the roots of the one new polynomial (the sum's numerator, the closed-loop
//! characteristic polynomial) and report what cancels. `feedback` returns more than the closed
//! loop — a [`Feedback`] with the closed loop in `closed`, the characteristic polynomial, its
//! roots and the hidden modes.

use super::coefficients::coefficient_source;
use super::decision::Decision;
use super::form::{Factored, assemble};
use super::pole_zero::{PoleZero, count};
use super::zpk::canonical_roots;
use crate::error::{LtiError, Result};
use crate::lti::TransferFunction;
use crate::poly::{Poly, Root};

/// A closed loop u = r + sign·H·y around G (see [`Factored::feedback`]).
#[derive(Debug, Clone)]
pub struct Feedback {
    /// The closed loop T = G/(1 − sign·G·H), as given: its poles are every root of the
    /// characteristic polynomial (hidden modes included, they cancel in T or not).
    pub closed: Factored,
    /// The characteristic polynomial D_G·D_H − sign·N_G·N_H before any cancellation (monic
    /// for a strictly proper loop).
    pub characteristic: Poly,
    /// Its roots with multiplicities: the closed-loop poles, hidden modes included.
    pub poles: Vec<Root>,
    /// The modes hidden by a pole–zero cancellation in the loop G·H (within G, within H or
    /// between them): roots of the characteristic polynomial whatever the gains.
    pub hidden: Vec<Root>,
}

impl Factored {
    /// Series connection self·next with the factors kept: the zeros and poles of both (equal
    /// roots merged, multiplicities added), the gains multiplied. Nothing is re-rooted, so
    /// (s + 1)⁻¹⁰ · (s + 1)⁻¹⁰ is exactly a 20-fold pole; a zero of one that is a pole of the
    /// other cancels in the reduced form and stays a characteristic root (a hidden mode).
    ///
    /// Errors: models of different domains ([`Domain::join`](crate::lti::Domain::join)); those
    /// of [`Factored::from_zpk`] (more than
    /// [`MAX_FACTORED_ORDER`](super::pole_zero::MAX_FACTORED_ORDER) roots).
    ///
    /// ```
    /// use ltikit::analysis::Factored;
    /// use ltikit::Root;
    /// use num_complex::Complex64 as C;
    /// let g = Factored::from_zpk(&[], &[Root::new(C::new(-1.0, 0.0), 10)], 1.0).unwrap();
    /// let gg = g.series(&g).unwrap();
    /// assert_eq!(gg.poles(), &[Root::new(C::new(-1.0, 0.0), 20)]);
    /// ```
    pub fn series(&self, next: &Factored) -> Result<Factored> {
        let domain = self.domain().join(next.domain(), "series")?;
        let (z, p, k) = series_parts(self, next);
        Factored::from_zpk(&z, &p, k)?
            .with_domain(domain)
            .with_delay(self.delay() + next.delay())
    }

    /// Parallel connection self + other = (N₁D₂ + N₂D₁)/(D₁D₂): the poles of both kept, the
    /// zeros found as the roots of the new numerator (the one root finding).
    ///
    /// Errors: models of different domains, a numerator beyond [`crate::MAX_ORDER`], the root
    /// finder's.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let f = |n: &[f64], d: &[f64]| TransferFunction::from_descending(n, d).unwrap().factored().unwrap();
    /// // 1/(s+1) + 1/(s+2) = (2s + 3)/((s+1)(s+2))
    /// let p = f(&[1.0], &[1.0, 1.0]).parallel(&f(&[1.0], &[1.0, 2.0])).unwrap();
    /// assert!((p.zeros()[0].value.re + 1.5).abs() < 1e-15);
    /// assert_eq!(p.order(), 2);
    /// ```
    pub fn parallel(&self, other: &Factored) -> Result<Factored> {
        let domain = self.domain().join(other.domain(), "parallel")?;
        let delay = crate::lti::delay::common_delay("parallel", self.delay(), other.delay())?;
        let num = &(&self.num_poly()? * &Poly::from_root_list(other.poles())?)
            + &(&other.num_poly()? * &Poly::from_root_list(self.poles())?);
        let mut poles = self.poles().to_vec();
        poles.extend_from_slice(other.poles());
        if num.is_zero() {
            return Ok(Factored::from_zpk(&[], &poles, 0.0)?.with_domain(domain));
        }
        let zeros = num.roots()?;
        Factored::from_zpk(&zeros, &poles, num.leading())?
            .with_domain(domain)
            .with_delay(delay)
    }

    /// Feedback u = r + sign·H·y around this G (`sign = -1.0`: negative feedback):
    /// T = N_G·D_H/(D_G·D_H − sign·N_G·N_H). The characteristic polynomial is formed once,
    /// from every factor as given; the modes hidden by cancellations in G·H are divided out
    /// exactly and added back as they are, so a cancelled root is the same value in the poles
    /// and in the hidden list. T keeps the coefficients (for the margin polynomials) and its
    /// roots.
    ///
    /// Returns the closed loop T (`closed`, in the two models' common domain) with the
    /// characteristic polynomial, its roots and the hidden modes ([`Feedback`]).
    ///
    /// Errors: a sign other than ±1, models of different domains, an improper loop G·H, a
    /// loop that is not well posed (1 − sign·G·H ≡ 0 at s → ∞), the root finder's.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let f = |n: &[f64], d: &[f64]| TransferFunction::from_descending(n, d).unwrap().factored().unwrap();
    /// // C = (s − 1)/(s + 2) cancels the unstable pole of G = 1/(s − 1): hidden mode s = 1
    /// let l = f(&[1.0, -1.0], &[1.0, 2.0]).series(&f(&[1.0], &[1.0, -1.0])).unwrap();
    /// let one = f(&[1.0], &[1.0]);
    /// let fb = l.feedback(&one, -1.0).unwrap();
    /// assert_eq!(fb.hidden[0].value.re, 1.0);
    /// assert!(fb.poles.iter().any(|p| p.value.re == 1.0));
    /// assert!(fb.closed.stability().bibo_stable && !fb.closed.stability().internally_stable);
    /// ```
    pub fn feedback(&self, h: &Factored, sign: f64) -> Result<Feedback> {
        crate::lti::interconnect::check_sign(sign)?;
        let domain = self.domain().join(h.domain(), "feedback")?;
        crate::lti::delay::require_rational("feedback", self.delay() + h.delay())?;
        let (lz, lp, lk) = series_parts(self, h);
        let (characteristic, poles, hidden) = close(&lz, &lp, lk, sign)?;
        let mut zeros = self.zeros().to_vec();
        zeros.extend_from_slice(h.poles());
        let num = &self.num_poly()? * &Poly::from_root_list(h.poles())?;
        let tf = TransferFunction::new(num, characteristic.clone())?.with_domain(domain);
        let closed = Factored::from_parts(tf, poles.clone(), zeros)?;
        Ok(Feedback {
            closed,
            characteristic,
            poles,
            hidden,
        })
    }

    /// k·Π(s − zᵢ) over the zeros as given (0 for G ≡ 0).
    pub(crate) fn num_poly(&self) -> Result<Poly> {
        if self.is_zero() {
            return Poly::from_descending(&[0.0]);
        }
        Ok(Poly::from_root_list(self.zeros())?.scale(self.gain()))
    }

    /// A factored form whose roots are already known: coefficients `tf` (kept as the source)
    /// with its denominator roots `poles` and numerator roots `zeros` (no root finding), in
    /// `tf`'s domain.
    pub(crate) fn from_parts(
        tf: TransferFunction,
        poles: Vec<Root>,
        zeros: Vec<Root>,
    ) -> Result<Factored> {
        let zero = tf.num().is_zero();
        let domain = tf.domain();
        let poles = canonical_roots(&poles, "pole")?;
        let zeros = if zero {
            Vec::new()
        } else {
            canonical_roots(&zeros, "zero")?
        };
        let pz = PoleZero::new(poles, zeros, zero);
        let gain = if zero { 0.0 } else { tf.gain() };
        let source = coefficient_source(tf, &pz)?;
        Ok(assemble(pz, gain, source, Decision::default()).with_domain(domain))
    }
}

/// Zeros, poles and gain of a·b, every factor as given.
pub(crate) fn series_parts(a: &Factored, b: &Factored) -> (Vec<Root>, Vec<Root>, f64) {
    if a.is_zero() || b.is_zero() {
        let mut p = a.poles().to_vec();
        p.extend_from_slice(b.poles());
        return (Vec::new(), p, 0.0);
    }
    let mut z = a.zeros().to_vec();
    z.extend_from_slice(b.zeros());
    let mut p = a.poles().to_vec();
    p.extend_from_slice(b.poles());
    (z, p, a.gain() * b.gain())
}

/// Closes the loop L = k·Π(s − zᵢ)/Π(s − pⱼ) (every factor as given) with `sign`: the
/// characteristic polynomial Π(s − pⱼ) − sign·k·Π(s − zᵢ), its roots (the hidden modes — the
/// roots that cancel in L — divided out exactly and added back as they are) and the hidden
/// modes.
pub(crate) fn close(
    zeros: &[Root],
    poles: &[Root],
    k: f64,
    sign: f64,
) -> Result<(Poly, Vec<Root>, Vec<Root>)> {
    let zeros = canonical_roots(zeros, "zero")?;
    let poles = canonical_roots(poles, "pole")?;
    let pz = PoleZero::new(poles.clone(), zeros.clone(), k == 0.0);
    let (n, m) = (count(&poles), count(&zeros));
    if k != 0.0 && m > n {
        return Err(LtiError::Improper {
            operation: "closing the loop".into(),
            required: "proper".into(),
            num_degree: m,
            den_degree: n,
            limit: n,
        });
    }
    let d = Poly::from_root_list(&poles)?;
    let nk = Poly::from_root_list(&zeros)?.scale(k);
    let characteristic = if k == 0.0 { d } else { &d - &nk.scale(sign) };
    if characteristic.is_zero() || characteristic.degree() < n {
        return Err(LtiError::invalid(format!(
            "the loop is not well posed: 1 {} L(s) vanishes at s → ∞ (L(∞) = {})",
            if sign < 0.0 { "+" } else { "−" },
            k
        )));
    }
    let hidden = pz.cancelled;
    let rest = if hidden.is_empty() {
        characteristic.clone()
    } else {
        characteristic.div_rem(&Poly::from_root_list(&hidden)?)?.0
    };
    let mut roots = if rest.degree() == 0 {
        Vec::new()
    } else {
        // the closed loop's poles within their error bound of the axis are on it (a loop
        // closed at its crossing gain has ±jω, not 7.9e-17 ± jω)
        crate::poly::roots::snap_to_axis(&rest, rest.roots()?)
    };
    roots.extend_from_slice(&hidden);
    Ok((characteristic, canonical_roots(&roots, "pole")?, hidden))
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::Complex64 as C;

    fn f(n: &[f64], d: &[f64]) -> Factored {
        TransferFunction::from_descending(n, d)
            .unwrap()
            .factored()
            .unwrap()
    }

    #[test]
    fn feedback_of_a_biproper_loop_and_ill_posed_loops() {
        // L = (s + 2)/(s + 1) with unity negative feedback: (s + 2)/(2s + 3)
        let fb = f(&[1.0, 2.0], &[1.0, 1.0])
            .feedback(&f(&[1.0], &[1.0]), -1.0)
            .unwrap();
        assert_eq!(fb.characteristic.coeffs(), &[2.0, 3.0]);
        assert_eq!(fb.poles[0].value, C::new(-1.5, 0.0));
        // L = −1 (constant): 1 + L ≡ 0
        let e = f(&[-1.0], &[1.0])
            .feedback(&f(&[1.0], &[1.0]), -1.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("not well posed"), "{e}");
        // improper loop
        let e = f(&[1.0, 0.0, 1.0], &[1.0, 1.0])
            .feedback(&f(&[1.0], &[1.0]), -1.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("proper"), "{e}");
        assert!(
            f(&[1.0], &[1.0, 1.0])
                .feedback(&f(&[1.0], &[1.0]), 2.0)
                .is_err()
        );
    }

    #[test]
    fn zero_plants_in_series_and_parallel() {
        let z = f(&[0.0], &[1.0, 1.0]);
        let g = f(&[1.0], &[1.0, 2.0]);
        assert!(z.series(&g).unwrap().is_zero());
        let p = z.parallel(&g).unwrap();
        assert_eq!(p.order(), 2);
        let neg = f(&[-1.0], &[1.0, 2.0]);
        assert!(g.parallel(&neg).unwrap().is_zero());
    }
}
