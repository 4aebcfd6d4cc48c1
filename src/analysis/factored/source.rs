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

use super::low_frequency::LowFrequency;
use super::pole_zero::PoleZero;
use super::series::eval_factors;
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

/// Relative distance to a cancelled root within which the reduced coefficients are used.
const NEAR_CANCELLED: f64 = 1e-6;

impl Source {
    pub(crate) fn coefficients(&self) -> Option<&Coeffs> {
        match self {
            Source::Coefficients(c) => Some(c),
            Source::Factors | Source::StateSpace(_) => None,
        }
    }

    /// The realisation of a state-space source.
    pub(crate) fn state_space(&self) -> Option<&SsSource> {
        match self {
            Source::StateSpace(ss) => Some(ss),
            Source::Coefficients(_) | Source::Factors => None,
        }
    }

    pub(crate) fn coefficients_of(tf: TransferFunction, reduced: TransferFunction) -> Source {
        Source::Coefficients(Box::new(Coeffs { tf, reduced }))
    }

    /// G(s) of the plant with gain `gain` and pole–zero part `pz` that came from this source.
    pub(crate) fn eval(&self, gain: f64, pz: &PoleZero, s: Complex64) -> Complex64 {
        match self {
            Source::Coefficients(c) => {
                let near = pz
                    .cancelled
                    .iter()
                    .any(|r| (s - r.value).norm() <= NEAR_CANCELLED * r.value.norm().max(1e-300));
                let g = if near { &c.reduced } else { &c.tf };
                g.eval(s)
            }
            Source::Factors => eval_factors(gain, &pz.reduced_zeros, &pz.reduced_poles, s),
            Source::StateSpace(ss) => ss.eval(s),
        }
    }

    /// The low-frequency asymptote of the reduced G (of the plant with gain `gain` and
    /// pole–zero part `pz` that came from this source).
    pub(crate) fn low_frequency(&self, gain: f64, pz: &PoleZero) -> LowFrequency {
        let factors = || LowFrequency::from_factors(gain, &pz.reduced_zeros, &pz.reduced_poles);
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
                let at_origin = pz.reduced_poles.iter().chain(&pz.reduced_zeros);
                if at_origin.clone().any(|r| r.is_origin()) {
                    factors()
                } else {
                    ss.low_frequency().unwrap_or_else(factors)
                }
            }
            Source::Factors => factors(),
        }
    }
}
