//! Crossings refined on a state-space realisation's own G(jω) (issue 24 item 2).
//!
//! A plant that came from a state-space model is factored into poles, transmission zeros and
//! a gain; the margins find their crossings on those factors (the Bode kernel) first. The
//! factors carry the error of the eigenvalue and zero computations (an 18-state dense
//! realisation lost up to 5e-9 relative in its crossover frequency), so every crossing is
//! then polished once more on G(jω) = C(jωI − H)⁻¹B + D of the minimal realisation (one
//! Hessenberg solve per point, `SsSource::eval_with_derivative`): |G| − level and the
//! phase by Brent's method, a resonance on the slope d ln|G|/dω = Re(j·G′/G) computed from
//! the same factorisation. The continuous phase keeps the factors' branch (the nearest one to
//! the Bode kernel's value), and the margins' values (phase margin, gain margin, peak) are read
//! from the realisation too. A crossing the realisation cannot confirm nearby keeps the
//! factored value, and so does a crossing where the realisation's sum cancels (far beyond the
//! spectrum, |G| decades below its peak: there the factors evaluate G better).

use std::f64::consts::TAU;

use num_complex::Complex64;

use super::polish;
use crate::analysis::factored::{BodeForm, SsSource};

/// Largest ratio of the size of the terms summed for G(jω) to |G(jω)| at which a crossing is
/// refined on the realisation (four digits lost to cancellation leave ~1e-12).
const MAX_CANCELLATION: f64 = 1e4;

/// G(jω) of a state-space source, with the factored form for the phase branch.
pub(super) struct Realised<'a> {
    ss: &'a SsSource,
    form: &'a BodeForm,
}

impl<'a> Realised<'a> {
    pub(super) fn new(ss: &'a SsSource, form: &'a BodeForm) -> Realised<'a> {
        Realised { ss, form }
    }

    /// G(jω) and G′(jω) of the realisation where they are accurate: no more than
    /// [`MAX_CANCELLATION`] between the terms summed and the result (beyond the spectrum, where
    /// |G| falls by many decades, the sum of the solve's terms cancels and the factors are
    /// the better evaluation).
    fn g(&self, w: f64) -> Option<(Complex64, Complex64)> {
        self.ss
            .eval_with_derivative(Complex64::new(0.0, w))
            .filter(|(g, dg, terms)| {
                g.is_finite()
                    && dg.is_finite()
                    && g.norm() > 0.0
                    && *terms <= MAX_CANCELLATION * g.norm()
            })
            .map(|(g, dg, _)| (g, dg))
    }

    /// ln|G(jω)|: of the realisation where it is accurate, of the factors elsewhere.
    pub(super) fn ln_mag(&self, w: f64) -> f64 {
        self.g(w)
            .map_or_else(|| self.form.eval(w).ln_mag(), |(g, _)| g.norm().ln())
    }

    /// ln|G(jω)| of the realisation (NaN where it is not accurate: no refinement there).
    fn realised_ln_mag(&self, w: f64) -> f64 {
        self.g(w).map_or(f64::NAN, |(g, _)| g.norm().ln())
    }

    /// The continuous phase (radians): arg G(jω) of the realisation on the branch of the
    /// factored form's phase.
    pub(super) fn phase_rad(&self, w: f64) -> f64 {
        let approx = self.form.eval(w).phase_rad();
        match self.g(w) {
            Some((g, _)) => {
                let a = g.arg();
                a + TAU * ((approx - a) / TAU).round()
            }
            None => approx,
        }
    }

    /// d ln|G(jω)|/dω = Re(j·G′(jω)/G(jω)).
    fn d_ln_mag(&self, w: f64) -> f64 {
        self.g(w)
            .map_or(f64::NAN, |(g, dg)| (Complex64::new(0.0, 1.0) * dg / g).re)
    }

    /// A crossing |G| = e^level refined on the realisation (`w` when it finds no sign change
    /// nearby).
    pub(super) fn level(&self, w: f64, level: f64, walls: &[f64]) -> f64 {
        polish(|x| self.realised_ln_mag(x) - level, w, walls, 0.0).unwrap_or(w)
    }

    /// A crossing φ = `target` (an odd multiple of π) refined on the realisation.
    pub(super) fn phase(&self, w: f64, target: f64, walls: &[f64]) -> f64 {
        // arg G − target in [−π, π]: continuous through the crossing, where it is near 0
        let f = |x: f64| match self.g(x) {
            Some((g, _)) => {
                let d = g.arg() - target;
                d - TAU * (d / TAU).round()
            }
            None => f64::NAN,
        };
        polish(f, w, walls, 0.0).unwrap_or(w)
    }

    /// A local maximum of |G| refined on the realisation's slope.
    pub(super) fn peak(&self, w: f64, walls: &[f64]) -> f64 {
        polish(|x| self.d_ln_mag(x), w, walls, 0.0).unwrap_or(w)
    }
}
