//! Sampling a continuous-time model (`c2d`) and its inverse (`d2c`), on the matrices and the
//! coefficients; the factored form's own versions (ZOH poles mapped as e^(pT) with their exact
//! multiplicities) are `Factored::c2d` and
//! `Factored::d2c` (the analysis layer), which share the root maps of this module.
//!
//! | method | state space (A, B, C, D) → (A_d, B_d, C_d, D_d) |
//! |---|---|
//! | ZOH | exp([[A, B], [0, 0]]·T) = [[A_d, B_d], [0, I]]; C, D unchanged |
//! | FOH (triangle hold) | exp([[A·T, B·T, 0], [0, 0, I], [0, 0, 0]]) = [[Φ, Γ₁, Γ₂], …]: A_d = Φ, B_d = Γ₁ − Γ₂ + Φ·Γ₂, D_d = D + C·Γ₂ (as MATLAB, python-control and scipy `foh`) |
//! | Tustin | with h = T/2, or h = tan(ωT/2)/ω when prewarped at ω: A_d = (I − hA)⁻¹(I + hA), B_d = (I − hA)⁻¹·2h·B, C_d = C(I − hA)⁻¹, D_d = D + h·C·(I − hA)⁻¹B (scipy's `bilinear`, i.e. `gbt` with α = ½) |
//! | impulse | A_d = e^(AT), B_d = T·e^(AT)·B, C_d = C, D_d = T·C·B; needs D = 0 (scipy's `impulse`: h_d\[k\] = T·h(kT) for k ≥ 0, the whole h(0) at k = 0) |
//! | matched | SISO: poles e^(pT), finite zeros e^(zT), zeros at infinity as MATLAB (see `matched_zpk`), gain matched at low frequency |
//!
//! `d2c` inverts ZOH by the real matrix logarithm of [[A_d, B_d], [0, I]]
//! ([`crate::numeric::logm()`]; a pole at 0 or on the negative real axis has no preimage), and
//! Tustin by A = (1/h)(A_d + I)⁻¹(A_d − I), B = (A_d + I)⁻¹B_d/h, C = 2C_d(A_d + I)⁻¹,
//! D = D_d − C_d(A_d + I)⁻¹B_d (a pole at −1 has no preimage).

use nalgebra::DMatrix;
use num_complex::Complex64;

use crate::error::{LtiError, Result, abbreviate};
use crate::fmt::fmt_num;
use crate::lti::{Domain, StateSpace, TransferFunction};
use crate::poly::{Poly, Root};

mod roots;

pub(crate) use roots::{
    Zpk, map_roots, matched_zpk, tustin_preimage, tustin_root, tustin_zpk, tustin_zpk_inverse,
    zoh_preimage, zoh_root,
};

/// The names `--method` / `Discretization::parse` accept.
pub const METHOD_NAMES: &str = "zoh, foh, tustin (or bilinear), matched, impulse";

/// How a continuous-time model is sampled (see the [module docs](self)).
///
/// ```
/// use ltikit::lti::Discretization;
/// assert_eq!(Discretization::parse("bilinear", None).unwrap(), Discretization::Tustin { prewarp: None });
/// assert_eq!(Discretization::parse("ZOH", None).unwrap().name(), "zoh");
/// let e = Discretization::parse("euler", None).unwrap_err().to_string();
/// assert!(e.contains("zoh, foh, tustin"), "{e}");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Discretization {
    /// Zero-order hold: the input is held constant over each sampling period (exact at the
    /// samples for a staircase input).
    Zoh,
    /// First-order (triangle) hold: the input interpolated linearly between the samples
    /// (non-causal; MATLAB's, python-control's and scipy's `foh`).
    Foh,
    /// The bilinear (Tustin) map s = (1/h)·(z − 1)/(z + 1), h = T/2; with `prewarp` = ω the
    /// factor 2/T becomes ω/tan(ωT/2), so that G(z) matches G(s) at s = jω (0 < ω < π/T).
    Tustin {
        /// The frequency in rad/s at which the responses match, if any.
        prewarp: Option<f64>,
    },
    /// Matched pole-zero (SISO): poles and zeros mapped by z = e^(sT), zeros at infinity as
    /// MATLAB's `c2d(…, 'matched')`, gain matched at low frequency.
    Matched,
    /// Impulse invariance, scipy's convention: h_d\[k\] = T·h(kT) (needs a strictly proper
    /// plant).
    Impulse,
}

impl Discretization {
    /// From a method name (`zoh`, `foh`, `tustin` or `bilinear`, `matched`, `impulse`; any
    /// case) and an optional prewarp frequency (Tustin only).
    ///
    /// Errors: an unknown name (listing the known ones), a prewarp frequency with another
    /// method.
    pub fn parse(name: &str, prewarp: Option<f64>) -> Result<Discretization> {
        let method = match name.trim().to_ascii_lowercase().as_str() {
            "zoh" => Discretization::Zoh,
            "foh" => Discretization::Foh,
            "tustin" | "bilinear" => Discretization::Tustin { prewarp },
            "matched" => Discretization::Matched,
            "impulse" => Discretization::Impulse,
            _ => {
                return Err(LtiError::invalid(format!(
                    "`method`: unknown discretisation method '{}' (known: {METHOD_NAMES})",
                    abbreviate(name)
                )));
            }
        };
        if prewarp.is_some() && !matches!(method, Discretization::Tustin { .. }) {
            return Err(LtiError::invalid(format!(
                "`prewarp` is for the tustin method, not {}",
                method.name()
            )));
        }
        Ok(method)
    }

    /// The method's name: "zoh", "foh", "tustin", "matched" or "impulse".
    pub fn name(&self) -> &'static str {
        match self {
            Discretization::Zoh => "zoh",
            Discretization::Foh => "foh",
            Discretization::Tustin { .. } => "tustin",
            Discretization::Matched => "matched",
            Discretization::Impulse => "impulse",
        }
    }

    /// h of the Tustin map s = (1/h)(z − 1)/(z + 1) at period `dt`: T/2, or tan(ωT/2)/ω when
    /// prewarped at ω. Errors unless 0 < ω < π/T. `None` for the other methods.
    pub(crate) fn tustin_h(&self, dt: f64) -> Result<Option<f64>> {
        let Discretization::Tustin { prewarp } = self else {
            return Ok(None);
        };
        let Some(w) = prewarp else {
            return Ok(Some(0.5 * dt));
        };
        let nyquist = std::f64::consts::PI / dt;
        if !w.is_finite() || *w <= 0.0 || *w >= nyquist {
            return Err(LtiError::InvalidParameter {
                name: "prewarp".into(),
                value: *w,
                reason: format!(
                    "the prewarp frequency must lie in (0, π/T) = (0, {}) rad/s for dt = {}",
                    fmt_num(nyquist),
                    fmt_num(dt)
                ),
            });
        }
        Ok(Some((0.5 * w * dt).tan() / w))
    }
}

/// The discrete domain of a `c2d` at period `dt` of a model in `domain`: errors if the model
/// is already discrete or `dt` is not finite and > 0.
pub(crate) fn c2d_domain(domain: Domain, dt: f64) -> Result<Domain> {
    domain.require_continuous("c2d")?;
    Domain::discrete(dt)
}

/// The d2c methods: ZOH and Tustin.
fn require_d2c_method(method: Discretization) -> Result<()> {
    match method {
        Discretization::Zoh | Discretization::Tustin { .. } => Ok(()),
        other => Err(LtiError::invalid(format!(
            "`method`: d2c inverts zoh and tustin, not {}",
            other.name()
        ))),
    }
}

/// The period of a model given to `d2c` (errors for a continuous one) after checking the
/// method.
pub(crate) fn d2c_period(domain: Domain, method: Discretization) -> Result<f64> {
    let dt = domain.require_discrete("d2c")?;
    require_d2c_method(method)?;
    Ok(dt)
}

/// The top-left n × c block of `m` starting at column `col`.
fn block(m: &DMatrix<f64>, n: usize, col: usize, cols: usize) -> DMatrix<f64> {
    m.view((0, col), (n, cols)).into_owned()
}

/// (I − hA)⁻¹ by an LU solve, or the error naming the eigenvalue 1/h.
fn tustin_inverse(a: &DMatrix<f64>, h: f64) -> Result<DMatrix<f64>> {
    let n = a.nrows();
    let m = DMatrix::<f64>::identity(n, n) - a * h;
    m.lu().try_inverse().ok_or_else(|| LtiError::Undefined {
        what: "the Tustin map".into(),
        reason: format!(
            "I − hA is singular: A has an eigenvalue at s = 1/h = {}, which maps to z = ∞",
            fmt_num(1.0 / h)
        ),
    })
}

impl StateSpace {
    /// The discrete-time model at period `dt` by `method` (see the [module docs](self) for
    /// the formulas); any number of inputs and outputs (`Matched`: one input and one output).
    /// The result is in [`Domain::Discrete`] with that `dt`.
    ///
    /// Errors: a model that is already discrete, `dt` not finite and > 0, a prewarp frequency
    /// outside (0, π/T), D ≠ 0 for `Impulse`, a MIMO model for `Matched`, an exponential
    /// that overflows.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::{StateSpace, lti::Discretization};
    /// // ẋ = −2x + u, y = x sampled with a zero-order hold at T = 0.1 s
    /// let one = |x: f64| DMatrix::from_element(1, 1, x);
    /// let ss = StateSpace::new(one(-2.0), one(1.0), one(1.0), one(0.0)).unwrap();
    /// let d = ss.c2d(0.1, Discretization::Zoh).unwrap();
    /// assert!((d.a[(0, 0)] - (-0.2f64).exp()).abs() < 1e-16);
    /// assert!((d.b[(0, 0)] - (1.0 - (-0.2f64).exp()) / 2.0).abs() < 1e-16);
    /// assert_eq!(d.domain.dt(), Some(0.1));
    /// assert!(d.c2d(0.1, Discretization::Zoh).is_err()); // already discrete
    /// ```
    pub fn c2d(&self, dt: f64, method: Discretization) -> Result<StateSpace> {
        self.require_no_delays("c2d")?;
        let domain = c2d_domain(self.domain, dt)?;
        let (n, m) = (self.order(), self.b.ncols());
        let (a, b, c, d) = match method {
            Discretization::Zoh => {
                // a second-order A = [[0, I], [−G, −E]]: from its modes (one 4×4 exponential
                // each, four products of half the order), not the dense exponential
                let structure = crate::numeric::linalg::StateMatrix::recognise(&self.a);
                let (phi, gamma) = match structure.second_order() {
                    Some(so) => so.zoh(&self.b, dt)?,
                    None => {
                        let mut aug = DMatrix::<f64>::zeros(n + m, n + m);
                        aug.view_mut((0, 0), (n, n)).copy_from(&(&self.a * dt));
                        aug.view_mut((0, n), (n, m)).copy_from(&(&self.b * dt));
                        let e = crate::numeric::expm(&aug)?;
                        (block(&e, n, 0, n), block(&e, n, n, m))
                    }
                };
                (phi, gamma, self.c.clone(), self.d.clone())
            }
            Discretization::Foh => {
                let mut aug = DMatrix::<f64>::zeros(n + 2 * m, n + 2 * m);
                aug.view_mut((0, 0), (n, n)).copy_from(&(&self.a * dt));
                aug.view_mut((0, n), (n, m)).copy_from(&(&self.b * dt));
                aug.view_mut((n, n + m), (m, m))
                    .copy_from(&DMatrix::<f64>::identity(m, m));
                let e = crate::numeric::expm(&aug)?;
                let phi = block(&e, n, 0, n);
                let g1 = block(&e, n, n, m);
                let g2 = block(&e, n, n + m, m);
                let bd = &g1 - &g2 + &phi * &g2;
                let dd = &self.d + &self.c * &g2;
                (phi, bd, self.c.clone(), dd)
            }
            Discretization::Tustin { .. } => {
                let h = method.tustin_h(dt)?.unwrap_or(0.5 * dt);
                let inv = tustin_inverse(&self.a, h)?;
                let id = DMatrix::<f64>::identity(n, n);
                let ad = &inv * (&id + &self.a * h);
                let bd = &inv * &self.b * (2.0 * h);
                let cd = &self.c * &inv;
                let dd = &self.d + &self.c * &bd * 0.5;
                (ad, bd, cd, dd)
            }
            Discretization::Impulse => {
                if let Some(x) = self.d.iter().find(|x| **x != 0.0) {
                    return Err(LtiError::invalid(format!(
                        "impulse invariance needs a strictly proper model (D = 0); D has the entry {}",
                        fmt_num(*x)
                    )));
                }
                let ad = crate::numeric::expm(&(&self.a * dt))?;
                let bd = &ad * &self.b * dt;
                let dd = &self.c * &self.b * dt;
                (ad, bd, self.c.clone(), dd)
            }
            Discretization::Matched => {
                let (z, p, k) = self.siso_zpk("the matched pole-zero method")?;
                let (zd, pd, kd) = matched_zpk(&z, &p, k, dt)?;
                return Ok(StateSpace::from_zpk(&zd, &pd, kd)?.with_domain(domain));
            }
        };
        let out = StateSpace::new(a, b, c, d).map_err(|e| match e {
            LtiError::NonFinite { value, .. } => LtiError::Overflow {
                what: format!(
                    "the {} discretisation at dt = {}",
                    method.name(),
                    fmt_num(dt)
                ),
                reason: format!(" (an entry became {value})"),
            },
            other => other,
        })?;
        Ok(out.with_domain(domain))
    }

    /// The continuous-time model whose `method` discretisation at the model's period is this
    /// discrete model: ZOH by the real matrix logarithm of [[A, B], [0, I]], Tustin (with its
    /// prewarp frequency) by the inverse bilinear map (see the [module docs](self)).
    ///
    /// Errors: a continuous model, a method other than ZOH and Tustin, a pole (eigenvalue of
    /// A) without a preimage — at 0 or on the negative real axis for ZOH
    /// ([`LtiError::NoPreimage`] names it), at −1 for Tustin.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::{StateSpace, lti::{Discretization, Domain}};
    /// let one = |x: f64| DMatrix::from_element(1, 1, x);
    /// let ss = StateSpace::new(one(-2.0), one(1.0), one(1.0), one(0.0)).unwrap();
    /// let back = ss.c2d(0.1, Discretization::Zoh).unwrap().d2c(Discretization::Zoh).unwrap();
    /// assert!((back.a[(0, 0)] + 2.0).abs() < 1e-13 && (back.b[(0, 0)] - 1.0).abs() < 1e-13);
    /// let neg = StateSpace::new(one(-0.5), one(1.0), one(1.0), one(0.0)).unwrap()
    ///     .with_domain(Domain::discrete(0.1).unwrap());
    /// assert!(neg.d2c(Discretization::Zoh).unwrap_err().to_string().contains("z = -0.5"));
    /// ```
    pub fn d2c(&self, method: Discretization) -> Result<StateSpace> {
        let dt = d2c_period(self.domain, method)?;
        let (n, m) = (self.order(), self.b.ncols());
        let id = DMatrix::<f64>::identity(n, n);
        let (a, b, c, d) = if let Some(h) = method.tustin_h(dt)? {
            let plus = &self.a + &id;
            let inv = plus.clone().lu().try_inverse();
            let inv = match inv {
                Some(inv) => inv,
                None => {
                    let z = crate::numeric::eigenvalues(&self.a)?
                        .into_iter()
                        .min_by(|x, y| (x + 1.0).norm().total_cmp(&(y + 1.0).norm()))
                        .unwrap_or(Complex64::new(-1.0, 0.0));
                    return Err(LtiError::NoPreimage {
                        method: "d2c (tustin)".into(),
                        re: z.re,
                        im: z.im,
                        reason: "the Tustin map sends no finite s to z = −1".into(),
                    });
                }
            };
            let a = &inv * (&self.a - &id) / h;
            let b = &inv * &self.b / h;
            let c = &self.c * &inv * 2.0;
            let d = &self.d - &self.c * &inv * &self.b;
            (a, b, c, d)
        } else {
            if n > 0
                && let Some(z) = crate::numeric::logm::negative_real_eigenvalue(&self.a)?
            {
                return Err(LtiError::NoPreimage {
                    method: "d2c (zoh)".into(),
                    re: z.re,
                    im: z.im,
                    reason: "e^(sT) is never 0 nor a negative real number".into(),
                });
            }
            let mut aug = DMatrix::<f64>::identity(n + m, n + m);
            aug.view_mut((0, 0), (n, n)).copy_from(&self.a);
            aug.view_mut((0, n), (n, m)).copy_from(&self.b);
            let l = crate::numeric::logm(&aug)? / dt;
            (
                block(&l, n, 0, n),
                block(&l, n, n, m),
                self.c.clone(),
                self.d.clone(),
            )
        };
        Ok(StateSpace::new(a, b, c, d)?.with_domain(Domain::Continuous))
    }

    /// Zeros, poles and gain of a SISO model, from its minimal realisation: the eigenvalues
    /// of A with the multiplicities of their eigen structure, the transmission zeros, the
    /// first non-zero Markov parameter (the factored form's recipe, at the numeric layer).
    fn siso_zpk(&self, what: &str) -> Result<Zpk> {
        if self.b.ncols() != 1 || self.c.nrows() != 1 {
            return Err(LtiError::invalid(format!(
                "{what} needs one input and one output; the model has {} inputs and {} outputs",
                self.b.ncols(),
                self.c.nrows()
            )));
        }
        use crate::numeric::linalg::{
            eigen_structure, minimal_realization, relative_degree, transmission_zeros,
        };
        let min = minimal_realization(&self.a, &self.b, &self.c, &self.d, None)?;
        let rd = relative_degree(&min.a, &min.b, &min.c, &min.d, None)?;
        let poles = if min.order() == 0 {
            Vec::new()
        } else {
            let st = eigen_structure(&min.a)?;
            conjugate_closed(
                &st.clusters
                    .iter()
                    .map(|c| (c.value, c.algebraic))
                    .collect::<Vec<_>>(),
            )
        };
        if rd.r.is_none() {
            return Ok((Vec::new(), poles, 0.0));
        }
        let tz = transmission_zeros(&min.a, &min.b, &min.c, &min.d, None)?;
        Ok((conjugate_closed(&tz.distinct), poles, rd.gain))
    }
}

/// Roots with multiplicities made a real set: real values (imaginary part within rounding of
/// 0) on the axis, each upper value with its exact conjugate (lower values are taken as the
/// partners of upper ones).
pub(crate) fn conjugate_closed(values: &[(Complex64, usize)]) -> Vec<Root> {
    let mut out = Vec::new();
    for &(v, m) in values {
        if v.im.abs() <= 8.0 * f64::EPSILON * v.norm() {
            out.push(Root::new(Complex64::new(v.re, 0.0), m));
        } else if v.im > 0.0 {
            out.push(Root::new(v, m));
            out.push(Root::new(v.conj(), m));
        }
    }
    let mut merged: Vec<Root> = Vec::new();
    for r in out {
        match merged.iter_mut().find(|q| q.value == r.value) {
            Some(q) => q.multiplicity += r.multiplicity,
            None => merged.push(r),
        }
    }
    crate::poly::roots::sort_roots(&mut merged);
    merged
}

impl TransferFunction {
    /// The discrete-time transfer function at period `dt` by `method`: ZOH, FOH and impulse
    /// through the controllable canonical realisation ([`StateSpace::c2d`]), Tustin by the
    /// substitution s = (1/h)(z − 1)/(z + 1) in the coefficients, matched pole-zero on the
    /// roots of the numerator and the denominator. The result is in [`Domain::Discrete`];
    /// its denominator is monic.
    ///
    /// Errors: those of [`StateSpace::c2d`], an improper G.
    ///
    /// ```
    /// use ltikit::{TransferFunction, lti::Discretization};
    /// // 1/(s + 1) by Tustin at T = 0.5: (0.2z + 0.2)/(z − 0.6)
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap();
    /// let d = g.c2d(0.5, Discretization::Tustin { prewarp: None }).unwrap();
    /// assert_eq!(d.to_string(), "(0.2 z + 0.2) / (z - 0.6)");
    /// ```
    pub fn c2d(&self, dt: f64, method: Discretization) -> Result<TransferFunction> {
        if self.delay() > 0.0 {
            // d whole periods are z^(−d), exact; a fraction left over is the modified
            // z-transform (ZOH only)
            let (d, tau) = split_delay(self.delay(), dt);
            let rational = if tau > 0.0 {
                require_zoh_for_fraction(method, self.delay(), dt)?;
                StateSpace::from_tf(&self.rational())?
                    .c2d_zoh_fractional(dt, tau)?
                    .to_tf()?
            } else {
                self.rational().c2d(dt, method)?
            };
            return rational.with_delay(d as f64 * dt);
        }
        let domain = c2d_domain(self.domain(), dt)?;
        self.require_proper("c2d", false)?;
        let out = match method {
            Discretization::Tustin { .. } => {
                let h = method.tustin_h(dt)?.unwrap_or(0.5 * dt);
                // N(s)/D(s)·(z + 1)^n h^n: s^k → h^(n−k)(z − 1)^k (z + 1)^(n−k)
                let n = self.order();
                let num = substitute(self.num(), n, h, [1.0, -1.0], [1.0, 1.0])?;
                let den = substitute(self.den(), n, h, [1.0, -1.0], [1.0, 1.0])?;
                monic(num, den)?
            }
            Discretization::Matched => {
                let zeros = if self.num().is_zero() {
                    Vec::new()
                } else {
                    self.num().roots()?
                };
                let (zd, pd, kd) = matched_zpk(&zeros, &self.den().roots()?, self.gain(), dt)?;
                let num = Poly::from_root_list(&zd)?.scale(kd);
                TransferFunction::new(num, Poly::from_root_list(&pd)?)?
            }
            Discretization::Zoh if self.order() > 0 => zoh_tf(self, dt)?,
            _ => {
                let ss = StateSpace::from_tf(self)?.c2d(dt, method)?;
                let g = ss.to_tf()?;
                monic(g.num().clone(), g.den().clone())?
            }
        };
        Ok(out.with_domain(domain))
    }

    /// The continuous-time transfer function whose `method` discretisation (ZOH or Tustin) at
    /// this model's period is this one: ZOH through the realisation ([`StateSpace::d2c`]),
    /// Tustin by the substitution z = (1 + hs)/(1 − hs).
    ///
    /// Errors: a continuous G, another method, a pole without a preimage (named).
    ///
    /// ```
    /// use ltikit::{TransferFunction, lti::{Discretization, Domain}};
    /// let gd = TransferFunction::from_descending(&[0.2, 0.2], &[1.0, -0.6]).unwrap()
    ///     .with_domain(Domain::discrete(0.5).unwrap());
    /// let g = gd.d2c(Discretization::Tustin { prewarp: None }).unwrap();
    /// assert_eq!(g.to_string(), "1 / (s + 1)");
    /// ```
    pub fn d2c(&self, method: Discretization) -> Result<TransferFunction> {
        let dt = d2c_period(self.domain(), method)?;
        self.require_proper("d2c", false)?;
        let out = if let Some(h) = method.tustin_h(dt)? {
            // z^k → (1 + hs)^k (1 − hs)^(n−k)
            let n = self.order();
            // the degree of the image drops by the multiplicity of a pole at z = −1
            let asc = self.den().ascending();
            let at_minus_one: f64 = asc
                .iter()
                .enumerate()
                .map(|(k, a)| if k % 2 == 0 { *a } else { -a })
                .sum();
            let size: f64 = asc.iter().map(|a| a.abs()).sum();
            if at_minus_one.abs() <= 8.0 * (n as f64 + 1.0) * f64::EPSILON * size {
                let p = self
                    .den()
                    .roots()?
                    .into_iter()
                    .map(|r| r.value)
                    .min_by(|x, y| (x + 1.0).norm().total_cmp(&(y + 1.0).norm()))
                    .unwrap_or(Complex64::new(-1.0, 0.0));
                return Err(LtiError::NoPreimage {
                    method: "d2c (tustin)".into(),
                    re: p.re,
                    im: p.im,
                    reason: "the Tustin map sends no finite s to z = −1".into(),
                });
            }
            let den = substitute_z(self.den(), n, h)?;
            let num = substitute_z(self.num(), n, h)?;
            monic(num, den)?
        } else {
            let ss = StateSpace::from_tf(self)?.d2c(method)?;
            let g = ss.to_tf()?;
            monic(g.num().clone(), g.den().clone())?
        };
        Ok(out.with_domain(Domain::Continuous))
    }
}

/// The ZOH equivalent of a proper G(s) of order n ≥ 1 with one eigenproblem, the roots of its
/// denominator: the poles e^(pT) (multiplicities kept, conjugates exact), the denominator
/// a(z) = Π(z − e^(pT)) expanded (monic), and the numerator from the Markov parameters of the
/// discretised controllable canonical realisation (balanced), g₀ = D, g_k = C·Φ^(k−1)·Γ (k = 1 … n):
/// G(z) = Σ g_k z^(−k), so N(z) = a(z)·Σ g_k z^(−k) truncated to its polynomial part,
/// N_i = Σ_(k ≤ i) a_(i−k)·g_k (descending coefficients, a₀ = 1).
fn zoh_tf(g: &TransferFunction, dt: f64) -> Result<TransferFunction> {
    let n = g.order();
    // the continuous poles: the eigenvalues of the balanced companion matrix (the root
    // finder's candidates; a multiple pole scatters by ~ε^(1/m), but the coefficients of
    // Π(z − e^(pT)) are symmetric functions of the poles, smooth in the coefficients of
    // G's denominator: the scatter cancels in them); the whole root finder when the
    // companion iteration fails or the coefficients span too wide a range
    let mapped = |poles: Vec<Complex64>| -> Result<Poly> {
        Poly::from_roots(&poles.iter().map(|&p| zoh_root(p, dt)).collect::<Vec<_>>())
    };
    // balanced (an exact diagonal similarity: the Markov parameters are unchanged): the
    // companion matrix's norm drops by orders of magnitude, and with it the exponential's
    // squarings and Padé degree. From order 3 the root finder's own balanced companion
    // serves both: its eigenvalues are the poles, and it is the realisation's A (the same
    // matrix: `StateSpace::from_tf` is the companion of the monic denominator).
    let (poles, ss) = match shared_companion(g)? {
        Some((poles, ss)) => (poles, ss),
        None => (
            crate::poly::roots::candidates(g.den()),
            StateSpace::from_tf(g)?.balanced(),
        ),
    };
    let den = match poles.and_then(mapped) {
        Ok(den) => den,
        Err(_) => mapped(crate::poly::roots::flatten(&g.den().roots()?))?,
    };
    let mut aug = DMatrix::<f64>::zeros(n + 1, n + 1);
    aug.view_mut((0, 0), (n, n)).copy_from(&(&ss.a * dt));
    aug.view_mut((0, n), (n, 1)).copy_from(&(&ss.b * dt));
    let e = crate::numeric::expm(&aug)?;
    let phi = e.view((0, 0), (n, n));
    let c = ss.c.row(0);
    // Φ^(k−1)·Γ by repeated products into two buffers
    let mut v = e.view((0, n), (n, 1)).into_owned();
    let mut next = v.clone();
    let mut markov = Vec::with_capacity(n + 1);
    markov.push(ss.d[(0, 0)]);
    for k in 1..=n {
        markov.push(c.iter().zip(v.iter()).map(|(x, y)| x * y).sum());
        if k < n {
            next.gemm(1.0, &phi, &v, 0.0);
            std::mem::swap(&mut v, &mut next);
        }
    }
    let a = den.coeffs();
    let num: Vec<f64> = (0..=n)
        .map(|i| (0..=i).map(|k| a[i - k] * markov[k]).sum())
        .collect();
    let out = TransferFunction::new(Poly::trimmed(num), den).map_err(|e| match e {
        LtiError::NonFinite { value, .. } => LtiError::Overflow {
            what: format!("the zoh discretisation at dt = {}", fmt_num(dt)),
            reason: format!(" (an entry became {value})"),
        },
        other => other,
    })?;
    Ok(out)
}

/// The poles (`Err` when the companion iteration did not converge) and the balanced
/// controllable realisation of `g` from one balancing of its companion matrix
/// ([`crate::poly::roots::balanced_companion`]); `None` below order 3 (the root finder's
/// closed forms) or when a coefficient or a scaled entry is not finite.
#[allow(clippy::type_complexity)]
fn shared_companion(g: &TransferFunction) -> Result<Option<(Result<Vec<Complex64>>, StateSpace)>> {
    let n = g.order();
    if n < 3 {
        return Ok(None);
    }
    let c = g.den().coeffs();
    let lead = c[0];
    let tail: Vec<f64> = c[1..].iter().map(|x| x / lead).collect();
    if tail.iter().any(|x| !x.is_finite()) {
        return Ok(None);
    }
    let (a, d, ev) = crate::poly::roots::balanced_companion(&tail);
    let mut ss = StateSpace::from_tf(g)?;
    ss.a = DMatrix::from_row_slice(n, n, &a);
    for (i, &di) in d.iter().enumerate() {
        ss.b[(i, 0)] /= di;
        ss.c[(0, i)] *= di;
    }
    if ss.b.iter().chain(ss.c.iter()).any(|x| !x.is_finite()) {
        return Ok(None);
    }
    let poles = ev.ok_or_else(|| LtiError::invalid("the companion iteration did not converge"));
    Ok(Some((poles, ss)))
}

/// Σ p_k s^k with s^k → h^(n−k)·a(z)^k·b(z)^(n−k), a and b linear (descending pairs).
fn substitute(p: &Poly, n: usize, h: f64, a: [f64; 2], b: [f64; 2]) -> Result<Poly> {
    let asc = p.ascending();
    let mut out = Poly::zero();
    for (k, &c) in asc.iter().enumerate() {
        if c == 0.0 {
            continue;
        }
        let mut term = Poly::from_descending(&[c * h.powi((n - k) as i32)])?;
        for _ in 0..k {
            term = &term * &Poly::from_descending(&a)?;
        }
        for _ in k..n {
            term = &term * &Poly::from_descending(&b)?;
        }
        out = &out + &term;
    }
    Ok(out)
}

/// Σ p_k z^k with z^k → (1 + hs)^k (1 − hs)^(n−k).
fn substitute_z(p: &Poly, n: usize, h: f64) -> Result<Poly> {
    substitute(p, n, 1.0, [h, 1.0], [-h, 1.0])
}

/// num/den with den made monic (its leading coefficient divided out of both).
fn monic(num: Poly, den: Poly) -> Result<TransferFunction> {
    let lead = den.leading();
    TransferFunction::new(num.scale(1.0 / lead), den.scale(1.0 / lead))
}

/// Errors unless `method` is ZOH: only the zero-order hold has a modified z-transform for a
/// delay that is not a whole number of periods.
pub fn require_zoh_for_fraction(method: Discretization, delay: f64, dt: f64) -> Result<()> {
    if method == Discretization::Zoh {
        return Ok(());
    }
    Err(LtiError::invalid(format!(
        "c2d: the dead time {} s is not a whole number of periods (dt = {} s); only zoh samples \
         a fractional delay (the modified z-transform) — use `method` zoh, or a period that \
         divides the delay",
        crate::fmt::fmt_num(delay),
        crate::fmt::fmt_num(dt)
    )))
}

/// A dead time `delay` sampled at the period `dt`: d whole periods and the fraction
/// τ ∈ [0, dt) left over (a fraction within 1e-9 of 0 or of a period is rounded away).
///
/// ```
/// use ltikit::lti::discretize::split_delay;
/// assert_eq!(split_delay(0.3, 0.1), (3, 0.0));
/// let (d, tau) = split_delay(0.25, 0.1);
/// assert_eq!(d, 2);
/// assert!((tau - 0.05).abs() < 1e-15);
/// ```
pub fn split_delay(delay: f64, dt: f64) -> (usize, f64) {
    let q = delay / dt;
    let d = q.floor();
    let frac = q - d;
    if frac <= 1e-9 * q.max(1.0) {
        (d as usize, 0.0)
    } else if 1.0 - frac <= 1e-9 * q.max(1.0) {
        (d as usize + 1, 0.0)
    } else {
        (d as usize, delay - d * dt)
    }
}

impl StateSpace {
    /// Zero-order-hold sampling at the period `dt` of this model with its input delayed by
    /// the fraction `tau` of a period (0 < τ < dt; the modified z-transform, as MATLAB `c2d`
    /// of a model with a fractional input delay). Over a period the held input is u\[k−1\]
    /// for τ seconds, then u\[k\]:
    ///
    /// x\[k+1\] = Φ x\[k\] + Γ₁ u\[k−1\] + Γ₀ u\[k\], y\[k\] = C x\[k\] + D u\[k−1\],
    ///
    /// Φ = e^(A·dt), Γ₀ = ∫₀^(dt−τ) e^(Aσ)dσ B, Γ₁ = e^(A(dt−τ)) ∫₀^τ e^(Aσ)dσ B; the state is
    /// augmented by u\[k−1\] (one more state per input, a pole at z = 0).
    ///
    /// Errors: a discrete model, τ outside (0, dt), a model with delays of its own, those of
    /// the matrix exponential.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::StateSpace;
    /// // ẋ = −x + u(t − 0.05), sampled at 0.1 s: a step from k = 0 gives
    /// // x(t) = 1 − e^(−(t − 0.05)) for t ≥ 0.05, so x[1] = 1 − e^(−0.05)
    /// let one = DMatrix::from_element(1, 1, 1.0);
    /// let ss = StateSpace::new(-one.clone(), one.clone(), one.clone(), one.scale(0.0)).unwrap();
    /// let d = ss.c2d_zoh_fractional(0.1, 0.05).unwrap();
    /// assert_eq!(d.order(), 2);
    /// let r = d.step_response_from(0, &[0.0, 0.1, 0.2], false).unwrap();
    /// assert!((r.y[0][1] - (1.0 - (-0.05f64).exp())).abs() < 1e-15);
    /// assert!((r.y[0][2] - (1.0 - (-0.15f64).exp())).abs() < 1e-15);
    /// ```
    pub fn c2d_zoh_fractional(&self, dt: f64, tau: f64) -> Result<StateSpace> {
        self.require_no_delays("c2d")?;
        let domain = c2d_domain(self.domain, dt)?;
        if !(tau > 0.0 && tau < dt) {
            return Err(LtiError::invalid(format!(
                "a fractional input delay must lie strictly between 0 and the period {} s \
                 (found {})",
                crate::fmt::fmt_num(dt),
                crate::fmt::fmt_num(tau)
            )));
        }
        let (n, m, p) = (self.order(), self.b.ncols(), self.c.nrows());
        // e^([[A, B], [0, 0]]·s): e^(As) and ∫₀^s e^(Aσ)dσ B
        let exp_int = |s: f64| -> Result<(DMatrix<f64>, DMatrix<f64>)> {
            let mut aug = DMatrix::<f64>::zeros(n + m, n + m);
            aug.view_mut((0, 0), (n, n)).copy_from(&(&self.a * s));
            aug.view_mut((0, n), (n, m)).copy_from(&(&self.b * s));
            let e = crate::numeric::expm(&aug)?;
            Ok((block(&e, n, 0, n), block(&e, n, n, m)))
        };
        let (e_rest, g0) = exp_int(dt - tau)?;
        let (e_tau, i_tau) = exp_int(tau)?;
        let phi = &e_rest * &e_tau;
        let g1 = &e_rest * &i_tau;
        let mut a = DMatrix::<f64>::zeros(n + m, n + m);
        a.view_mut((0, 0), (n, n)).copy_from(&phi);
        a.view_mut((0, n), (n, m)).copy_from(&g1);
        let mut b = DMatrix::<f64>::zeros(n + m, m);
        b.view_mut((0, 0), (n, m)).copy_from(&g0);
        b.view_mut((n, 0), (m, m))
            .copy_from(&DMatrix::<f64>::identity(m, m));
        let mut c = DMatrix::<f64>::zeros(p, n + m);
        c.view_mut((0, 0), (p, n)).copy_from(&self.c);
        c.view_mut((0, n), (p, m)).copy_from(&self.d);
        Ok(StateSpace::new(a, b, c, DMatrix::zeros(p, m))?.with_domain(domain))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tustin_zpk_round_trip() {
        let c = |re, im| Complex64::new(re, im);
        let zeros = [Root::new(c(-3.0, 0.0), 1)];
        let poles = [
            Root::new(c(-1.0, 2.0), 1),
            Root::new(c(-1.0, -2.0), 1),
            Root::new(c(-0.5, 0.0), 2),
        ];
        let (zd, pd, kd) = tustin_zpk(&zeros, &poles, 2.0, 0.05).unwrap();
        let (zc, pc, kc) = tustin_zpk_inverse(&zd, &pd, kd, 0.05).unwrap();
        assert!((kc - 2.0).abs() < 1e-13, "{kc}");
        assert_eq!(zc.len(), 1);
        assert!((zc[0].value - zeros[0].value).norm() < 1e-12);
        assert_eq!(pc.len(), 3);
        assert_eq!(pc.iter().map(|p| p.multiplicity).sum::<usize>(), 4);
    }
}
