//! Sampling the factored form (`c2d`) and its inverse (`d2c`): the poles are mapped from the
//! factored poles with their exact multiplicities — never re-rooted from coefficients, where a
//! pole of multiplicity m scatters by ε^(1/m) — and the zeros and the gain come from the
//! discretised realisation (ZOH), or the zeros are mapped too (matched, Tustin).

use super::form::Factored;
use crate::error::Result;
use crate::lti::discretize::{
    Zpk, c2d_domain, conjugate_closed, d2c_period, map_roots, matched_zpk, tustin_preimage,
    tustin_root, tustin_zpk, tustin_zpk_inverse, zoh_preimage, zoh_root,
};
use crate::lti::{Discretization, Domain, StateSpace};
use crate::numeric::linalg::{relative_degree, transmission_zeros};
use crate::poly::Root;

impl Factored {
    /// The discrete-time factored form at period `dt` by `method`
    /// ([`Discretization`]):
    /// - **ZOH**: the poles are e^(pT) of the factored poles, each with its multiplicity (a
    ///   triple pole stays one triple pole); the zeros are the transmission zeros of the
    ///   ZOH-discretised realisation of the reduced plant (a cascade of real sections,
    ///   [`StateSpace::from_zpk`]) and the gain its first non-zero Markov parameter;
    /// - **matched**: poles e^(pT), finite zeros e^(zT), r − 1 of the r zeros at infinity at
    ///   z = −1, the gain matched at low frequency (MATLAB's rule, see
    ///   [`crate::lti::discretize`]);
    /// - **Tustin**: every root mapped by (1 + hs)/(1 − hs), the zeros at infinity to −1;
    /// - **FOH, impulse**: through the realisation ([`StateSpace::c2d`], then
    ///   [`Factored::from_state_space`]).
    ///
    /// Cancelled roots c (common to the numerator and the denominator) are mapped and stay
    /// cancelled (ZOH, matched, Tustin). The result is in [`Domain::Discrete`].
    ///
    /// Errors: a discrete plant, `dt` not finite and > 0, an improper plant, those of the
    /// method.
    ///
    /// ```
    /// use ltikit::{Root, analysis::Factored, lti::Discretization};
    /// use num_complex::Complex64 as C;
    /// // 1/(s + 1)³ sampled at T = 0.1: one pole e^(−0.1) of multiplicity 3
    /// let f = Factored::from_zpk(&[], &[Root::new(C::new(-1.0, 0.0), 3)], 1.0).unwrap();
    /// let d = f.c2d(0.1, Discretization::Zoh).unwrap();
    /// assert_eq!(d.poles().len(), 1);
    /// assert_eq!(d.poles()[0].multiplicity, 3);
    /// assert_eq!(d.poles()[0].value.re, (-0.1f64).exp());
    /// assert!((d.eval(C::new(1.0, 0.0)).re - 1.0).abs() < 1e-13); // G(z = 1) = G(s = 0)
    /// ```
    pub fn c2d(&self, dt: f64, method: Discretization) -> Result<Factored> {
        if self.delay() > 0.0 {
            return self.c2d_delayed(dt, method);
        }
        let domain = c2d_domain(self.domain(), dt)?;
        self.require_proper("c2d", false)?;
        let h = method.tustin_h(dt)?;
        let zoh = |p| Ok(zoh_root(p, dt));
        let cancelled = &self.pole_zero().cancelled;
        let (zeros, poles, gain) = match method {
            Discretization::Zoh => {
                let poles = map_roots(self.poles(), zoh)?;
                if self.is_zero() {
                    (Vec::new(), poles, 0.0)
                } else {
                    let ss = self.reduced_realisation()?;
                    let (zeros, gain) = zeros_and_gain(&ss.c2d(dt, method)?, None)?;
                    (with(zeros, map_roots(cancelled, zoh)?), poles, gain)
                }
            }
            Discretization::Matched | Discretization::Tustin { .. } if !self.is_zero() => {
                let (z, p, k) = match h {
                    Some(h) => {
                        tustin_zpk(self.reduced_zeros(), self.reduced_poles(), self.gain(), h)?
                    }
                    None => {
                        matched_zpk(self.reduced_zeros(), self.reduced_poles(), self.gain(), dt)?
                    }
                };
                let c = match h {
                    Some(h) => map_roots(cancelled, |v| tustin_root(v, h))?,
                    None => map_roots(cancelled, zoh)?,
                };
                (with(z, c.clone()), with(p, c), k)
            }
            Discretization::Matched => (Vec::new(), map_roots(self.poles(), zoh)?, 0.0),
            Discretization::Tustin { .. } => {
                let h = h.unwrap_or(0.5 * dt);
                (
                    Vec::new(),
                    map_roots(self.poles(), |v| tustin_root(v, h))?,
                    0.0,
                )
            }
            Discretization::Foh | Discretization::Impulse => {
                let ss = self.reduced_realisation()?.c2d(dt, method)?;
                return Factored::from_state_space(&ss);
            }
        };
        Ok(Factored::from_zpk(&zeros, &poles, gain)?.with_domain(domain))
    }

    /// c2d of a delayed plant: d whole periods are z^(−d), exact (d poles at z = 0); a
    /// fraction τ left over is the modified z-transform (ZOH only): the poles e^(pT) of the
    /// factored poles and one more at z = 0 (the held input of the previous period), the
    /// zeros and the gain from the realisation sampled with the fractional input delay
    /// ([`StateSpace::c2d_zoh_fractional`]).
    fn c2d_delayed(&self, dt: f64, method: Discretization) -> Result<Factored> {
        let (d, tau) = crate::lti::discretize::split_delay(self.delay(), dt);
        let whole = d as f64 * dt;
        if tau == 0.0 {
            return self.rational().c2d(dt, method)?.with_delay(whole);
        }
        crate::lti::discretize::require_zoh_for_fraction(method, self.delay(), dt)?;
        let domain = c2d_domain(self.domain(), dt)?;
        self.require_proper("c2d", false)?;
        let zoh = |p| Ok(zoh_root(p, dt));
        let mut poles = map_roots(self.poles(), zoh)?;
        poles.push(Root::new(num_complex::Complex64::new(0.0, 0.0), 1));
        let (zeros, gain) = if self.is_zero() {
            (Vec::new(), 0.0)
        } else {
            let ss = self
                .rational()
                .reduced_realisation()?
                .c2d_zoh_fractional(dt, tau)?;
            let (zeros, gain) = zeros_and_gain(&ss, None)?;
            (
                with(zeros, map_roots(&self.pole_zero().cancelled, zoh)?),
                gain,
            )
        };
        Factored::from_zpk(&zeros, &poles, gain)?
            .with_domain(domain)
            .with_delay(whole)
    }

    /// The continuous-time factored form whose `method` discretisation (ZOH or Tustin) at this
    /// plant's period is this one:
    /// - **ZOH**: poles ln(π)/T (principal logarithm) of the factored poles with their
    ///   multiplicities; zeros and gain from the realisation converted by the matrix logarithm
    ///   ([`StateSpace::d2c`]);
    /// - **Tustin**: every root mapped by (z − 1)/(h(z + 1)); zeros at z = −1 go to infinity.
    ///
    /// Errors: a continuous plant, another method, a pole without a preimage
    /// ([`crate::LtiError::NoPreimage`] names it: at 0 or on the negative real axis for ZOH,
    /// at −1 for Tustin).
    ///
    /// ```
    /// use ltikit::{Root, analysis::Factored, lti::{Discretization, Domain}};
    /// use num_complex::Complex64 as C;
    /// let f = Factored::from_zpk(&[], &[Root::new(C::new(-1.0, 0.0), 2)], 1.0).unwrap();
    /// let d = f.c2d(0.2, Discretization::Zoh).unwrap();
    /// let back = d.d2c(Discretization::Zoh).unwrap();
    /// assert_eq!(back.poles()[0].multiplicity, 2);
    /// assert!((back.poles()[0].value.re + 1.0).abs() < 1e-15);
    /// assert!((back.gain() - 1.0).abs() < 1e-12);
    /// let half = Factored::from_zpk(&[], &[Root::new(C::new(-0.5, 0.0), 1)], 1.0).unwrap()
    ///     .with_domain(Domain::discrete(0.1).unwrap());
    /// assert!(half.d2c(Discretization::Zoh).unwrap_err().to_string().contains("z = -0.5"));
    /// ```
    pub fn d2c(&self, method: Discretization) -> Result<Factored> {
        let dt = d2c_period(self.domain(), method)?;
        self.require_proper("d2c", false)?;
        let cancelled = &self.pole_zero().cancelled;
        let (zeros, poles, gain): Zpk = match method.tustin_h(dt)? {
            Some(h) => {
                let poles = map_roots(self.poles(), |z| tustin_preimage(z, h))?;
                if self.is_zero() {
                    (Vec::new(), poles, 0.0)
                } else {
                    let (z, p, k) = tustin_zpk_inverse(
                        self.reduced_zeros(),
                        self.reduced_poles(),
                        self.gain(),
                        h,
                    )?;
                    let c = map_roots(cancelled, |v| tustin_preimage(v, h))?;
                    (with(z, c.clone()), with(p, c), k)
                }
            }
            None => {
                let poles = map_roots(self.poles(), |z| zoh_preimage(z, dt))?;
                if self.is_zero() {
                    (Vec::new(), poles, 0.0)
                } else {
                    let ss = self.reduced_realisation()?.with_domain(self.domain());
                    let (zeros, gain) = zeros_and_gain(&ss.d2c(method)?, Some(LOG_RANK_TOL))?;
                    let c = map_roots(cancelled, |z| zoh_preimage(z, dt))?;
                    (with(zeros, c), poles, gain)
                }
            }
        };
        Ok(Factored::from_zpk(&zeros, &poles, gain)?.with_domain(Domain::Continuous))
    }

    /// A realisation of the reduced plant: the cascade of real sections of its reduced zeros
    /// and poles (continuous, whatever the plant's domain).
    fn reduced_realisation(&self) -> Result<StateSpace> {
        StateSpace::from_zpk(self.reduced_zeros(), self.reduced_poles(), self.gain())
    }
}

/// The relative rank tolerance of the zeros of a realisation converted by the matrix
/// logarithm: its structurally zero Markov parameters come out at ~1e-14 of the system's
/// norm (the rounding of the discrete data, amplified by 1/T), which the default tolerance
/// ((n + 1)²·ε) would take for a gain — and then report zeros near infinity.
const LOG_RANK_TOL: f64 = 1e-10;

/// The transmission zeros (multiplicities by clusters, exact conjugates) and the first
/// non-zero Markov parameter of a SISO model (rank tolerance `tol`, relative; `None`: the
/// default); no zeros and gain 0 for G ≡ 0.
fn zeros_and_gain(ss: &StateSpace, tol: Option<f64>) -> Result<(Vec<Root>, f64)> {
    let rd = relative_degree(&ss.a, &ss.b, &ss.c, &ss.d, tol)?;
    if rd.r.is_none() {
        return Ok((Vec::new(), 0.0));
    }
    let tz = transmission_zeros(&ss.a, &ss.b, &ss.c, &ss.d, tol)?;
    Ok((conjugate_closed(&tz.distinct), rd.gain))
}

/// `a` followed by `b`.
fn with(mut a: Vec<Root>, b: Vec<Root>) -> Vec<Root> {
    a.extend(b);
    a
}
