//! Transfer functions G(s) = N(s)/D(s) built from ODE coefficients.
//!
//! The ODE `a_n y^(n) + … + a_0 y = b_m u^(m) + … + b_0 u` becomes
//! `TransferFunction::from_descending(&[b_m, …, b_0], &[a_n, …, a_0])`. The denominator as given
//! is the characteristic polynomial: its roots are the poles (common factors with the numerator
//! are *not* removed here; the analysis layer's `pole_zero()` gives the reduced form).

use num_complex::Complex64;
use std::fmt;

use crate::error::{LtiError, Result};
use crate::lti::Domain;
use crate::poly::{MAX_ORDER, Poly, Root, format_poly};

/// A SISO transfer function with real coefficients.
#[derive(Debug, Clone, PartialEq)]
pub struct TransferFunction {
    num: Poly,
    den: Poly,
    domain: Domain,
    /// Dead time T ≥ 0 (s) of the factor e^(−sT); 0 for none (continuous time only).
    delay: f64,
}

impl TransferFunction {
    /// From numerator and denominator coefficients in **descending** powers of s.
    ///
    /// Leading zeros are trimmed; the leading coefficient need not be 1; the numerator degree
    /// may exceed the denominator's (an improper G, e.g. a differentiator `s`), although some
    /// analyses then refuse with [`LtiError::Improper`].
    ///
    /// Errors: empty or all-zero denominator, NaN/∞ coefficients, order above [`MAX_ORDER`].
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // 4 y'' + 0.8·4 y' + 16 y = 16 u, i.e. 4 / (s² + 0.8 s + 4)
    /// let g = TransferFunction::from_descending(&[16.0], &[4.0, 3.2, 16.0]).unwrap();
    /// assert_eq!(g.order(), 2);
    /// assert_eq!(g.to_string(), "16 / (4 s^2 + 3.2 s + 16)");
    /// ```
    pub fn from_descending(num: &[f64], den: &[f64]) -> Result<Self> {
        let num = Poly::from_descending_named(num, "numerator")?;
        let den = Poly::from_descending_named(den, "denominator")?;
        Self::new(num, den)
    }

    /// From numerator and denominator polynomials.
    pub fn new(num: Poly, den: Poly) -> Result<Self> {
        if den.is_zero() {
            return Err(LtiError::ZeroPolynomial {
                what: "denominator".into(),
            });
        }
        if den.degree() > MAX_ORDER {
            return Err(LtiError::OrderTooHigh {
                order: den.degree(),
                max: MAX_ORDER,
            });
        }
        if num.degree() > MAX_ORDER {
            return Err(LtiError::InvalidInput(format!(
                "numerator degree {} exceeds the supported maximum {MAX_ORDER}",
                num.degree()
            )));
        }
        Ok(TransferFunction {
            num,
            den,
            domain: Domain::Continuous,
            delay: 0.0,
        })
    }

    /// From zeros, poles and the gain k: G(s) = k·Π(s − zᵢ)/Π(s − pᵢ). Complex zeros and poles
    /// must come in conjugate pairs.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use num_complex::Complex64 as C;
    /// let g = TransferFunction::from_zpk(&[C::new(-2.0, 0.0)], &[C::new(-1.0, 1.0), C::new(-1.0, -1.0)], 3.0).unwrap();
    /// assert_eq!(g.num().coeffs(), &[3.0, 6.0]);
    /// assert_eq!(g.den().coeffs(), &[1.0, 2.0, 2.0]);
    /// ```
    pub fn from_zpk(zeros: &[Complex64], poles: &[Complex64], gain: f64) -> Result<Self> {
        crate::error::check_finite(|| "the gain".into(), gain)?;
        let num = Poly::from_roots(zeros)?.scale(gain);
        let den = Poly::from_roots(poles)?;
        Self::new(num, den)
    }

    /// The Laplace variable s as a transfer function (s/1), for building G from expressions.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let s = TransferFunction::s();
    /// let g = (&s + &TransferFunction::constant(1.0)).inv().unwrap(); // 1/(s+1)
    /// assert_eq!(g.den().coeffs(), &[1.0, 1.0]);
    /// ```
    pub fn s() -> Self {
        TransferFunction {
            num: Poly::s(),
            den: Poly::constant(1.0),
            domain: Domain::Continuous,
            delay: 0.0,
        }
    }

    /// The constant transfer function k.
    pub fn constant(k: f64) -> Self {
        TransferFunction {
            num: Poly::constant(k),
            den: Poly::constant(1.0),
            domain: Domain::Continuous,
            delay: 0.0,
        }
    }

    /// The same transfer function in `domain`: with [`Domain::Discrete`] the coefficients are
    /// read in descending powers of z (G(z), the difference equation
    /// a_n y\[k+n\] + … + a_0 y\[k\] = b_m u\[k+m\] + … + b_0 u\[k\]).
    ///
    /// ```
    /// use ltikit::{TransferFunction, lti::Domain};
    /// let g = TransferFunction::from_descending(&[0.5], &[1.0, -0.5]).unwrap()
    ///     .with_domain(Domain::discrete(0.1).unwrap());
    /// assert_eq!(g.domain().dt(), Some(0.1));
    /// assert_eq!(g.to_string(), "0.5 / (z - 0.5)");
    /// ```
    pub fn with_domain(mut self, domain: Domain) -> Self {
        self.domain = domain;
        self
    }

    /// Continuous or discrete time (with the sampling period).
    pub fn domain(&self) -> Domain {
        self.domain
    }

    /// The same rational part with the dead time `delay` (s): G(s)·e^(−s·delay). In discrete
    /// time the delay must be a whole number d of sampling periods and becomes z^(−d) — the
    /// denominator times z^d, exact (then [`TransferFunction::delay`] stays 0).
    ///
    /// Errors: a delay that is negative, not finite or above
    /// [`MAX_DELAY`](crate::limits::MAX_DELAY); in discrete time, not a whole number of
    /// periods.
    ///
    /// ```
    /// use ltikit::{TransferFunction, lti::Domain};
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap().with_delay(0.5).unwrap();
    /// assert_eq!(g.delay(), 0.5);
    /// assert_eq!(g.to_string(), "1 / (s + 1) · e^(-0.5 s)");
    /// let z = TransferFunction::from_descending(&[0.5], &[1.0, -0.5]).unwrap()
    ///     .with_domain(Domain::discrete(0.1).unwrap()).with_delay(0.2).unwrap();
    /// assert_eq!(z.to_string(), "0.5 / (z^3 - 0.5 z^2)");
    /// ```
    pub fn with_delay(mut self, delay: f64) -> Result<Self> {
        let delay = crate::lti::delay::check_delay(delay)?;
        match self.domain.dt() {
            None => {
                self.delay = delay;
                Ok(self)
            }
            Some(dt) => {
                let d = crate::lti::delay::delay_samples(delay, dt)?;
                let mut shifted = self.den.ascending().to_vec();
                shifted.splice(0..0, std::iter::repeat_n(0.0, d));
                let den = Poly::from_ascending(&shifted)?;
                Ok(Self::new(self.num, den)?.with_domain(self.domain))
            }
        }
    }

    /// The dead time T (s) of the factor e^(−sT); 0 without one.
    pub fn delay(&self) -> f64 {
        self.delay
    }

    /// The rational part alone (the delay dropped).
    pub fn rational(&self) -> Self {
        let mut g = self.clone();
        g.delay = 0.0;
        g
    }

    /// Numerator polynomial.
    pub fn num(&self) -> &Poly {
        &self.num
    }

    /// Denominator (characteristic) polynomial.
    pub fn den(&self) -> &Poly {
        &self.den
    }

    /// System order: the degree of the denominator.
    pub fn order(&self) -> usize {
        self.den.degree()
    }

    /// deg D − deg N (negative for an improper G). The zero transfer function has relative
    /// degree 0 by convention.
    pub fn relative_degree(&self) -> i64 {
        if self.num.is_zero() {
            return 0;
        }
        self.den.degree() as i64 - self.num.degree() as i64
    }

    /// True when deg N ≤ deg D.
    pub fn is_proper(&self) -> bool {
        self.num.is_zero() || self.num.degree() <= self.den.degree()
    }

    /// True when deg N < deg D (or N = 0).
    pub fn is_strictly_proper(&self) -> bool {
        self.num.is_zero() || self.num.degree() < self.den.degree()
    }

    /// Errors with [`LtiError::Improper`] unless proper (or strictly proper when `strict`).
    pub fn require_proper(&self, operation: &str, strict: bool) -> Result<()> {
        let ok = if strict {
            self.is_strictly_proper()
        } else {
            self.is_proper()
        };
        if ok {
            return Ok(());
        }
        let n = self.den.degree();
        Err(LtiError::Improper {
            operation: operation.into(),
            required: if strict { "strictly proper" } else { "proper" }.into(),
            num_degree: self.num.degree(),
            den_degree: n,
            limit: if strict { n.saturating_sub(1) } else { n },
        })
    }

    /// G(s) at a complex point (Horner on both polynomials).
    pub fn eval(&self, s: Complex64) -> Complex64 {
        self.num.eval_complex(s) / self.den.eval_complex(s)
    }

    /// Poles: roots of the denominator as given, with multiplicities.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 2.0, 1.0]).unwrap();
    /// let p = g.poles().unwrap();
    /// assert_eq!(p.len(), 1);
    /// assert_eq!(p[0].multiplicity, 2); // critically damped: an exact double pole at −1
    /// ```
    pub fn poles(&self) -> Result<Vec<Root>> {
        self.den.roots()
    }

    /// Finite zeros: roots of the numerator (none for the zero transfer function).
    pub fn zeros(&self) -> Result<Vec<Root>> {
        if self.num.is_zero() {
            return Ok(Vec::new());
        }
        self.num.roots()
    }

    /// 1/G. Errors if G is the zero transfer function.
    pub fn inv(&self) -> Result<Self> {
        if self.num.is_zero() {
            return Err(LtiError::ZeroPolynomial {
                what: "numerator (cannot invert the zero transfer function)".into(),
            });
        }
        if self.delay != 0.0 {
            return Err(LtiError::invalid(format!(
                "1/G of a delayed plant would be a predictor e^(+{} s): not causal",
                crate::fmt::fmt_num(self.delay)
            )));
        }
        Ok(Self::new(self.den.clone(), self.num.clone())?.with_domain(self.domain))
    }

    /// Non-zero leading coefficients ratio b_m / a_n (the high-frequency gain coefficient).
    pub fn gain(&self) -> f64 {
        self.num.leading() / self.den.leading()
    }
}

impl std::ops::Mul for &TransferFunction {
    type Output = TransferFunction;
    /// The product G₁·G₂ (no cancellation is performed), in G₁'s domain; the series
    /// connection that checks the domains is [`TransferFunction::series`].
    fn mul(self, o: &TransferFunction) -> TransferFunction {
        TransferFunction {
            num: &self.num * &o.num,
            den: &self.den * &o.den,
            domain: self.domain,
            delay: self.delay + o.delay,
        }
    }
}

impl std::ops::Add for &TransferFunction {
    type Output = TransferFunction;
    /// The sum G₁ + G₂ over the common denominator D₁D₂, in G₁'s domain; the parallel
    /// connection that checks the domains is [`TransferFunction::parallel`].
    fn add(self, o: &TransferFunction) -> TransferFunction {
        if self.den == o.den {
            return TransferFunction {
                num: &self.num + &o.num,
                den: self.den.clone(),
                domain: self.domain,
                delay: self.delay,
            };
        }
        TransferFunction {
            num: &(&self.num * &o.den) + &(&o.num * &self.den),
            den: &self.den * &o.den,
            domain: self.domain,
            delay: self.delay,
        }
    }
}

impl std::ops::Neg for &TransferFunction {
    type Output = TransferFunction;
    fn neg(self) -> TransferFunction {
        TransferFunction {
            num: -&self.num,
            den: self.den.clone(),
            domain: self.domain,
            delay: self.delay,
        }
    }
}

impl fmt::Display for TransferFunction {
    /// `N / (D)` with polynomials in descending powers, e.g. `4 / (s^2 + 0.8 s + 4)`.
    #[allow(clippy::float_cmp)] // exact 1 means "no denominator to show"
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let var = self.domain.variable();
        let n = format_poly(&self.num, var);
        let d = format_poly(&self.den, var);
        let wrap = |s: &str, p: &Poly| {
            if p.degree() == 0 || (p.coeffs().iter().filter(|c| **c != 0.0).count() == 1) {
                s.to_string()
            } else {
                format!("({s})")
            }
        };
        let delay = if self.delay == 0.0 {
            String::new()
        } else {
            format!(" · {}", crate::lti::delay::factor_text(self.delay))
        };
        if self.den.degree() == 0 && self.den.leading() == 1.0 {
            return write!(f, "{n}{delay}");
        }
        write!(
            f,
            "{} / {}{delay}",
            wrap(&n, &self.num),
            wrap(&d, &self.den)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_input() {
        assert!(TransferFunction::from_descending(&[1.0], &[]).is_err());
        assert!(TransferFunction::from_descending(&[1.0], &[0.0]).is_err());
        assert!(TransferFunction::from_descending(&[f64::NAN], &[1.0]).is_err());
        assert!(TransferFunction::from_descending(&[1.0], &[1.0, f64::INFINITY]).is_err());
        let mut big = vec![0.0; 302];
        big[0] = 1.0;
        assert!(TransferFunction::from_descending(&[1.0], &big).is_err());
    }

    #[test]
    fn properness_and_degrees() {
        let g = TransferFunction::from_descending(&[1.0, 0.0, 0.0], &[1.0, 1.0]).unwrap();
        assert!(!g.is_proper());
        assert_eq!(g.relative_degree(), -1);
        assert!(g.require_proper("step response", false).is_err());
        let g = TransferFunction::from_descending(&[0.0, 2.0], &[0.0, 1.0, 1.0]).unwrap();
        assert!(g.is_strictly_proper());
        assert_eq!(g.num().coeffs(), &[2.0]);
    }

    #[test]
    fn algebra() {
        let s = TransferFunction::s();
        let one = TransferFunction::constant(1.0);
        let g = (&s + &one).inv().unwrap();
        let h = &g * &g;
        assert_eq!(h.den().coeffs(), &[1.0, 2.0, 1.0]);
        let cl = g.feedback(&one, -1.0).unwrap();
        assert_eq!(cl.den().coeffs(), &[1.0, 2.0]);
        assert_eq!(format!("{}", -&g), "-1 / (s + 1)");
    }
}
