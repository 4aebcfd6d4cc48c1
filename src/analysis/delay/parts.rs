//! The delayed loop's parts: D(s) = Π(s − pⱼ) over the reduced poles and N(s) = k·Π(s − zᵢ)
//! over the reduced zeros of L = N/D, checked once, and what the analyses evaluate on them —
//! log L and its slope, the magnitude gap ln|D(jω)| − ln|N(jω)|, the phase of −L(jω) and the
//! polynomial W(ω²) = |D(jω)|² − |N(jω)|² — all from the factors.

use num_complex::Complex64;

use crate::analysis::factored::Factored;
use crate::error::{LtiError, Result};
use crate::fmt::fmt_num;
use crate::limits::MAX_ORDER;
use crate::poly::{Poly, Root};

/// L(s) = N(s)/D(s) = k·Π(s − zᵢ)/Π(s − pⱼ), the roots listed with repetition.
#[derive(Debug, Clone)]
pub(super) struct DelayedLoop {
    /// Reduced poles of L, each repeated by its multiplicity.
    pub(super) poles: Vec<Complex64>,
    /// Reduced zeros of L, each repeated by its multiplicity.
    pub(super) zeros: Vec<Complex64>,
    /// The gain k (N = k·Π(s − zᵢ), D monic).
    pub(super) gain: f64,
    /// The modes cancelled in L (outside the characteristic equation).
    pub(super) hidden: Vec<Root>,
}

fn flatten(roots: &[Root]) -> Vec<Complex64> {
    roots
        .iter()
        .flat_map(|r| std::iter::repeat_n(r.value, r.multiplicity))
        .collect()
}

impl DelayedLoop {
    /// The reduced parts of `f`, refused when the question has no answer here: a
    /// discrete-time loop, L ≡ 0, an improper L, an order beyond [`MAX_ORDER`] (the analyses
    /// form polynomials), a bi-proper L with |L(∞)| ≥ 1 (a neutral equation whose roots
    /// reach the axis for every delay).
    pub(super) fn new(f: &Factored, what: &str) -> Result<DelayedLoop> {
        f.domain().require_continuous(what)?;
        if f.is_zero() || f.gain() == 0.0 {
            return Err(LtiError::invalid(format!(
                "{what}: the loop L is zero, so the dead time never enters the closed loop (its characteristic equation is the open-loop denominator alone)"
            )));
        }
        f.require_proper(what, false)?;
        let poles = flatten(f.reduced_poles());
        let zeros = flatten(f.reduced_zeros());
        if poles.len() > MAX_ORDER {
            return Err(LtiError::OrderTooHigh {
                order: poles.len(),
                max: MAX_ORDER,
            });
        }
        let l = DelayedLoop {
            poles,
            zeros,
            gain: f.gain(),
            hidden: f.pole_zero().cancelled.clone(),
        };
        if let Some(c) = l.at_infinity()
            && c.abs() >= 1.0
        {
            let kind = if c.abs() <= 1.0 {
                "a chain of characteristic roots approaches the imaginary axis for every delay T > 0 (never exponentially stable)"
            } else {
                "infinitely many characteristic roots lie in the right half plane for every delay T > 0 (unstable for every delay)"
            };
            return Err(LtiError::invalid(format!(
                "{what}: the loop is bi-proper with |L(∞)| = {} ≥ 1; the delayed closed loop D(s) + N(s)·e^(−sT) is of neutral type and {kind}",
                fmt_num(c.abs())
            )));
        }
        Ok(l)
    }

    /// lim L(s) at s → ∞ when L is bi-proper (the neutral-type coefficient), `None` when L is
    /// strictly proper.
    pub(super) fn at_infinity(&self) -> Option<f64> {
        (self.zeros.len() == self.poles.len()).then_some(self.gain)
    }

    /// ln L(s) on some branch (a zero of L gives −∞).
    pub(super) fn log_loop(&self, s: Complex64) -> Complex64 {
        let k = Complex64::new(self.gain, 0.0).ln();
        let up: Complex64 = self.zeros.iter().map(|&z| (s - z).ln()).sum();
        let down: Complex64 = self.poles.iter().map(|&p| (s - p).ln()).sum();
        k + up - down
    }

    /// L′(s)/L(s) = Σ 1/(s − zᵢ) − Σ 1/(s − pⱼ).
    pub(super) fn log_slope(&self, s: Complex64) -> Complex64 {
        let up: Complex64 = self.zeros.iter().map(|&z| (s - z).inv()).sum();
        let down: Complex64 = self.poles.iter().map(|&p| (s - p).inv()).sum();
        up - down
    }

    /// The magnitude gap g(ω) = ln|D(jω)| − ln|N(jω)| (zero at a crossing frequency) and its
    /// derivative g′(ω), from the factors.
    pub(super) fn magnitude_gap(&self, w: f64) -> (f64, f64) {
        let s = Complex64::new(0.0, w);
        let j = Complex64::new(0.0, 1.0);
        let mut g = -self.gain.abs().ln();
        let mut dg = 0.0;
        for &p in &self.poles {
            g += (s - p).norm().ln();
            dg += (j / (s - p)).re;
        }
        for &z in &self.zeros {
            g -= (s - z).norm().ln();
            dg -= (j / (s - z)).re;
        }
        (g, dg)
    }

    /// θ = arg(−L(jω)) in [0, 2π): the delays at which e^(−jωT) = −D(jω)/N(jω) are
    /// (θ + 2πk)/ω. The arguments are summed factor by factor.
    pub(super) fn phase(&self, w: f64) -> f64 {
        let s = Complex64::new(0.0, w);
        let mut a = std::f64::consts::PI
            + if self.gain < 0.0 {
                std::f64::consts::PI
            } else {
                0.0
            };
        for &z in &self.zeros {
            a += (s - z).arg();
        }
        for &p in &self.poles {
            a -= (s - p).arg();
        }
        a.rem_euclid(std::f64::consts::TAU)
    }

    /// L(0) from the factors (±∞ with a pole at 0).
    pub(super) fn at_zero(&self) -> f64 {
        let v = crate::analysis::factored::series::eval_factors(
            self.gain,
            &self
                .zeros
                .iter()
                .map(|&z| Root::new(z, 1))
                .collect::<Vec<_>>(),
            &self
                .poles
                .iter()
                .map(|&p| Root::new(p, 1))
                .collect::<Vec<_>>(),
            Complex64::new(0.0, 0.0),
        );
        v.re
    }

    /// A power of two near the largest root magnitude (1 without finite non-zero roots):
    /// the frequency scale of the crossing polynomial.
    pub(super) fn frequency_scale(&self) -> f64 {
        let m = self
            .poles
            .iter()
            .chain(&self.zeros)
            .map(|r| r.norm())
            .fold(0.0_f64, f64::max);
        if m > 0.0 && m.is_finite() {
            2f64.powi(m.log2().round().clamp(-500.0, 500.0) as i32)
        } else {
            1.0
        }
    }

    /// W(ρ·y)/ρⁿ with x = ω² = ρ·y: Π(y + pⱼ²/ρ) − k²ρ^(m−n)·Π(y + zᵢ²/ρ), where
    /// (jω − p)(−jω − p) = ω² + p², so W(ω²) = |D(jω)|² − |N(jω)|². Conjugate pairs give
    /// real quadratics. Errors when the scaled gain overflows.
    pub(super) fn crossing_poly(&self, rho: f64) -> Result<Poly> {
        let side = |roots: &[Complex64]| -> Poly {
            let mut p = Poly::constant(1.0);
            for &r in roots {
                if r.im > 0.0 {
                    continue;
                }
                let q = r * r / rho;
                let f = if r.im == 0.0 {
                    Poly::trimmed(vec![1.0, q.re])
                } else {
                    // (y + q)(y + q̄)
                    Poly::trimmed(vec![1.0, 2.0 * q.re, q.norm_sqr()])
                };
                p = &p * &f;
            }
            p
        };
        let d = side(&self.poles);
        let n = side(&self.zeros);
        // k²·ρ^(m−n): exact (ρ is a power of two) unless an intermediate leaves the range
        let shift = self.zeros.len() as i32 - self.poles.len() as i32;
        let mut k2 = self.gain * self.gain;
        for _ in 0..shift.unsigned_abs() {
            k2 = if shift > 0 { k2 * rho } else { k2 / rho };
        }
        if !k2.is_finite() || k2 == 0.0 {
            k2 = (2.0 * self.gain.abs().ln() + f64::from(shift) * rho.ln()).exp();
        }
        if !k2.is_finite() || d.coeffs().iter().chain(n.coeffs()).any(|c| !c.is_finite()) {
            return Err(LtiError::Overflow {
                what: "the crossing polynomial |D(jω)|² − |N(jω)|²".into(),
                reason: format!(
                    ", gain {} with roots up to {} rad/s",
                    fmt_num(self.gain),
                    fmt_num(rho)
                ),
            });
        }
        Ok(&d - &n.scale(k2))
    }

    /// The characteristic polynomial at T = 0, D + N, from the factors (monic D).
    pub(super) fn undelayed_poly(&self) -> Result<Poly> {
        let d = Poly::from_roots(&self.poles)?;
        let n = Poly::from_roots(&self.zeros)?.scale(self.gain);
        Ok(&d + &n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::TransferFunction;

    fn parts(n: &[f64], d: &[f64]) -> DelayedLoop {
        let f = TransferFunction::from_descending(n, d)
            .unwrap()
            .factored()
            .unwrap();
        DelayedLoop::new(&f, "test").unwrap()
    }

    #[test]
    fn crossing_polynomial_of_a_second_order_loop() {
        // L = 3/(s² + s + 2): |D(jω)|² = (2 − ω²)² + ω² = x² − 3x + 4, |N|² = 9 → x² − 3x − 5
        let l = parts(&[3.0], &[1.0, 1.0, 2.0]);
        let w = l.crossing_poly(1.0).unwrap();
        let c = w.coeffs();
        assert!(
            (c[0] - 1.0).abs() < 1e-15 && (c[1] + 3.0).abs() < 1e-14,
            "{c:?}"
        );
        assert!((c[2] + 5.0).abs() < 1e-14, "{c:?}");
        // scaled: x = 4y → (16y² − 12y − 5)/16
        let w4 = l.crossing_poly(4.0).unwrap();
        assert!(
            (w4.coeffs()[1] + 0.75).abs() < 1e-15 && (w4.coeffs()[2] + 5.0 / 16.0).abs() < 1e-15
        );
    }

    #[test]
    #[allow(clippy::float_cmp)] // L(0) = 2 exactly
    fn gap_and_phase_of_a_first_order_loop() {
        // L = 2/(s + 1): g(√3) = ln 2 − ln 2 = 0, θ = arg(−L(j√3)) = 2π/3
        let l = parts(&[2.0], &[1.0, 1.0]);
        let w = 3f64.sqrt();
        let (g, dg) = l.magnitude_gap(w);
        assert!(g.abs() < 1e-15);
        // g′ = ω/(1 + ω²) = √3/4
        assert!((dg - w / 4.0).abs() < 1e-15);
        assert!((l.phase(w) - 2.0 * std::f64::consts::PI / 3.0).abs() < 1e-15);
        assert_eq!(l.at_zero(), 2.0);
        // a negative gain turns the phase by π: −2/(s + 1) at ω = 1: arg(2/(1 + j)) = −π/4
        let l = parts(&[-2.0], &[1.0, 1.0]);
        assert!((l.phase(1.0) - 7.0 * std::f64::consts::PI / 4.0).abs() < 1e-15);
    }
}
