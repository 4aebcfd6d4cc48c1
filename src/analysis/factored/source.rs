//! Where a factored plant came from, and what the source does better than the roots.
//!
//! - **Coefficients** (ODE input): G is evaluated from the coefficients *as given* (they are
//!   exact; computed roots of a cluster are not), except within a relative 1e-6 of a
//!   cancelled root, where N and D both vanish and the reduced coefficients are used. The
//!   low-frequency gain is the ratio of the lowest non-zero coefficients of the plant as given
//!   (a cancelled factor contributes the same value to both). The reduced coefficients serve
//!   the canonical realisation of responses and the polynomial margin equations.
//! - **Factors** (zeros, poles, gain): everything from the factors, with products kept in
//!   scaled form so that high orders neither overflow nor underflow.
//! - **State space** (a SISO model or channel, [`super::ss_source`]): G from the Hessenberg
//!   form of the minimal realisation, the dc gain by a solve D − C·A⁻¹·B; everything else from
//!   the factors (poles = eigenvalues, zeros = transmission zeros).

use num_complex::Complex64;

use super::Factored;
use super::series::{ScaledProduct, eval_factors};
use super::ss_source::SsSource;
use crate::lti::TransferFunction;

/// The coefficients of a plant given by them, and of its reduced form.
#[derive(Debug, Clone)]
pub(crate) struct Coeffs {
    /// The plant as given.
    pub tf: TransferFunction,
    /// In lowest terms: the given polynomials divided by the cancelled common factor.
    pub reduced: TransferFunction,
}

/// The source of a factored plant.
#[derive(Debug, Clone)]
pub(crate) enum Source {
    /// ODE coefficients.
    Coefficients(Box<Coeffs>),
    /// Zeros, poles and gain only.
    Factors,
    /// A SISO state-space model: its minimal realisation.
    StateSpace(Box<SsSource>),
}

/// The low-frequency asymptote K·s^k of the reduced G: K = sign·e^(ln_abs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LowFrequency {
    /// Sign of K (±1).
    pub sign: f64,
    /// ln|K|.
    pub ln_abs: f64,
    /// k: zeros at s = 0 minus poles at s = 0.
    pub int_order: i32,
    /// K itself when it is a normal f64 (NaN otherwise).
    pub k: f64,
}

impl LowFrequency {
    /// The asymptote of a G finite at s = 0 with value `k`.
    pub(crate) fn of_value(k: f64) -> LowFrequency {
        LowFrequency {
            sign: if k < 0.0 { -1.0 } else { 1.0 },
            ln_abs: k.abs().ln(),
            int_order: 0,
            k,
        }
    }

    /// K as an f64 (from the logarithm when the direct ratio under- or overflowed).
    pub fn value(&self) -> f64 {
        if self.k.is_finite() && self.k != 0.0 {
            self.k
        } else {
            self.sign * self.ln_abs.exp()
        }
    }
}

/// Relative distance to a cancelled root within which the reduced coefficients are used.
const NEAR_CANCELLED: f64 = 1e-6;

impl Source {
    pub(crate) fn coefficients(&self) -> Option<&Coeffs> {
        match self {
            Source::Coefficients(c) => Some(c),
            Source::Factors | Source::StateSpace(_) => None,
        }
    }

    pub(crate) fn coefficients_of(tf: TransferFunction, reduced: TransferFunction) -> Source {
        Source::Coefficients(Box::new(Coeffs { tf, reduced }))
    }

    /// G(s).
    pub(crate) fn eval(&self, f: &Factored, s: Complex64) -> Complex64 {
        match self {
            Source::Coefficients(c) => {
                let near =
                    f.pz.cancelled.iter().any(|r| {
                        (s - r.value).norm() <= NEAR_CANCELLED * r.value.norm().max(1e-300)
                    });
                let g = if near { &c.reduced } else { &c.tf };
                g.eval(s)
            }
            Source::Factors => eval_factors(f.gain, &f.pz.reduced_zeros, &f.pz.reduced_poles, s),
            Source::StateSpace(ss) => ss.eval(s),
        }
    }

    /// The low-frequency asymptote of the reduced G.
    pub(crate) fn low_frequency(&self, f: &Factored) -> LowFrequency {
        match self {
            Source::Coefficients(c) => {
                let (n, d) = (c.tf.num(), c.tf.den());
                let zn = n.zero_root_multiplicity();
                let zd = d.zero_root_multiplicity();
                let (a, b) = (n.coeff(zn), d.coeff(zd));
                LowFrequency {
                    sign: if (a < 0.0) != (b < 0.0) { -1.0 } else { 1.0 },
                    ln_abs: a.abs().ln() - b.abs().ln(),
                    int_order: zn as i32 - zd as i32,
                    k: a / b,
                }
            }
            Source::StateSpace(ss) => {
                let at_origin = f.pz.reduced_poles.iter().chain(&f.pz.reduced_zeros);
                if at_origin.clone().any(|r| r.is_origin()) {
                    factors_low_frequency(f)
                } else {
                    ss.low_frequency()
                        .unwrap_or_else(|| factors_low_frequency(f))
                }
            }
            Source::Factors => factors_low_frequency(f),
        }
    }
}

/// The low-frequency asymptote from the reduced factors.
fn factors_low_frequency(f: &Factored) -> LowFrequency {
    let mut acc = ScaledProduct::new(Complex64::new(f.gain, 0.0));
    let mut int_order = 0i32;
    let mut ln_abs = f.gain.abs().ln();
    for z in &f.pz.reduced_zeros {
        if z.is_origin() {
            int_order += z.multiplicity as i32;
        } else {
            acc.mul_pow(-z.value, z.multiplicity);
            ln_abs += z.multiplicity as f64 * z.value.norm().ln();
        }
    }
    for p in &f.pz.reduced_poles {
        if p.is_origin() {
            int_order -= p.multiplicity as i32;
        } else {
            acc.div_pow(-p.value, p.multiplicity);
            ln_abs -= p.multiplicity as f64 * p.value.norm().ln();
        }
    }
    let k = acc.value().re;
    let sign = if f.gain < 0.0 { -1.0 } else { 1.0 }
        * real_root_sign(&f.pz.reduced_zeros)
        * real_root_sign(&f.pz.reduced_poles);
    LowFrequency {
        sign,
        ln_abs,
        int_order,
        k,
    }
}

/// Sign of Π(−r)^m over the non-zero roots (conjugate pairs contribute |r|² > 0).
fn real_root_sign(roots: &[crate::poly::Root]) -> f64 {
    let negative = roots
        .iter()
        .filter(|r| r.is_real() && r.value.re > 0.0 && r.multiplicity % 2 == 1)
        .count();
    if negative % 2 == 1 { -1.0 } else { 1.0 }
}
