//! Gain and phase margins, bandwidth and resonance, found by root-finding on the analytic
//! G(jω) — never by interpolating a sampled grid.
//!
//! # Method
//! With N(jω) = e_N(u) + jω·o_N(u) and D(jω) likewise (u = ω², e and o the even and odd parts
//! of the polynomial with alternating signs), every question becomes a real polynomial in u:
//!
//! | quantity | polynomial in u | kept roots |
//! |---|---|---|
//! | gain crossings |G| = 1 | e_N² + u·o_N² − (e_D² + u·o_D²) | u > 0 |
//! | phase crossings φ ≡ −180° | o_N·e_D − e_N·o_D (= Im(N·conj D)/ω) | u > 0 with Re G < 0 |
//! | bandwidth |G| = c·|G(0)| | e_N² + u·o_N² − c²·(e_D² + u·o_D²) | the smallest u > 0 |
//! | resonance d|G|²/du = 0 | A_N′·A_D − A_N·A_D′ (A = e² + u·o²) | local maxima |
//!
//! The frequency is scaled by a power of two near the geometric mean of the corner
//! frequencies first (exact, and it balances the coefficients). The positive real roots of
//! [`Poly::roots`] are then polished by Brent's method on the analytic function itself
//! (ln|G|, the continuous phase, or d ln|G|/dω, evaluated in factored form), so the results
//! are exact to rounding, not to the accuracy of the polynomial's roots.
//!
//! # Conventions (MATLAB `margin` / `bandwidth`)
//! - Gain margin at a phase crossing ω_pc: 1/|G(jω_pc)| (and −20·log₁₀|G| dB). Phase margin at
//!   a gain crossing ω_gc: 180° + φ(ω_gc), wrapped into (−180°, 180°].
//! - Headline values (as MATLAB `margin`): among several crossings, the gain margin closest to
//!   0 dB and the phase margin closest to 0°; `None` when there is no crossing (infinite
//!   margin). A finite negative dc gain is a phase crossing at ω = 0 (G(0) = −|G(0)|: the
//!   loop gain 1/|G(0)| puts a closed-loop pole at s = 0), reported with the others; the
//!   asymptote of an integrator at ω → 0 is not a crossing, nor are phase "crossings" at an
//!   imaginary-axis pole, where |G| = ∞ and the phase jumps, nor the non-isolated ones of a G
//!   that is real on the whole axis.
//! - Bandwidth: the first ω where |G| falls to exactly 10^(−3/20) of the dc gain; `None` for a
//!   dc gain of 0 or ∞ or when |G| never falls that far.
//! - Resonant peak: M_r = max|G(jω)|/|G(0)| over ω > 0 with ω_r where it is attained, when
//!   the maximum is at a finite ω > 0 and exceeds both |G(0)| and the limit at ω → ∞;
//!   `None` otherwise or for a dc gain of 0 or ∞. An undamped pole pair ±jβ gives M_r = +∞ at
//!   ω_r = β (the lowest such β).

use std::f64::consts::{FRAC_PI_2, PI, TAU};

pub(crate) mod crossing;
mod delayed;
mod realised;

pub use crossing::{GainCrossing, Margins, PhaseCrossing};
pub(crate) use crossing::{dedup_by_w, wrap_deg};

use super::factored::Factored;
use super::factored::{BodeForm, mul_pow2};
use crate::error::Result;
use crate::lti::TransferFunction;
use crate::numeric::scalar::{Bracket, all_crossings, brent};
use crate::poly::{MAX_ORDER, Poly};

impl TransferFunction {
    /// Gain and phase margins (every crossing and the MATLAB-style headline values),
    /// bandwidth and resonant peak of the reduced G, by polynomial root-finding polished on
    /// the analytic G(jω). See the [module docs](crate::analysis::margins) for definitions.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // 2 / (s (s+1) (s+2)): GM = 3 at ω = √2, PM = 32.6131° at ω = 0.749368.
    /// let g = TransferFunction::from_descending(&[2.0], &[1.0, 3.0, 2.0, 0.0]).unwrap();
    /// let m = g.margins().unwrap();
    /// assert!((m.gain_margin.unwrap() - 3.0).abs() < 1e-12);
    /// assert!((m.phase_crossover.unwrap() - 2f64.sqrt()).abs() < 1e-12);
    /// assert!((m.phase_margin_deg.unwrap() - 32.6131).abs() < 1e-4);
    /// assert!(m.bandwidth.is_none()); // infinite dc gain
    /// ```
    pub fn margins(&self) -> Result<Margins> {
        self.factored()?.margins()
    }
}

impl Factored {
    /// Margins, bandwidth and resonance on this factorisation ([`TransferFunction::margins`]).
    /// A negative finite dc gain is a phase crossing at ω = 0 (its gain margin is the lower
    /// end of the stabilising gains).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // −2/(s + 1): φ(0) = −180°, closed loop s + 1 − 2K stable for K < 1/2: GM = 0.5 at ω = 0.
    /// let f = TransferFunction::from_descending(&[-2.0], &[1.0, 1.0]).unwrap().factored().unwrap();
    /// let m = f.margins().unwrap();
    /// assert_eq!(m.phase_crossings[0].w, 0.0);
    /// assert!((m.gain_margin.unwrap() - 0.5).abs() < 1e-15);
    /// ```
    pub fn margins(&self) -> Result<Margins> {
        if let Some(dt) = self.domain().dt() {
            return crate::analysis::discrete::margins(self, dt);
        }
        let form = self.bode();
        let mut out = Margins::default();
        if self.is_zero() {
            return Ok(out);
        }
        let cand = Candidates::new(self, form)?;
        let singular: Vec<f64> = form
            .axis_poles()
            .iter()
            .chain(form.axis_zeros())
            .copied()
            .collect();
        // a state-space source: every crossing is refined on the realisation's own G(jω)
        let real = self
            .source()
            .state_space()
            .map(|ss| realised::Realised::new(ss, form));
        let ln_mag = |w: f64| match &real {
            Some(r) => r.ln_mag(w),
            None => form.eval(w).ln_mag(),
        };
        let phase_deg = |w: f64| match &real {
            Some(r) => r.phase_rad(w).to_degrees(),
            None => form.eval(w).phase_deg(),
        };
        // the gain margin at a phase crossing, as a ratio and in dB
        let gain_margin = |w: f64| match &real {
            Some(r) => {
                let lm = r.ln_mag(w);
                ((-lm).exp(), -20.0 * std::f64::consts::LOG10_E * lm)
            }
            None => {
                let e = form.eval(w);
                ((-e.ln_mag()).exp(), -e.db())
            }
        };

        // gain crossings
        for w in cand.gain_crossings(form)? {
            if let Some(w) = polish(|x| form.eval(x).ln_mag(), w, &singular, 1e-10) {
                let w = real.as_ref().map_or(w, |r| r.level(w, 0.0, &singular));
                out.gain_crossings.push(GainCrossing {
                    w,
                    phase_margin_deg: wrap_deg(
                        180.0 + phase_deg(w) - (w * self.delay()).to_degrees(),
                    ),
                });
            }
        }
        dedup_by_w(&mut out.gain_crossings, |c| c.w);

        // phase crossings: ω = 0 when G(0) is finite and negative (and G has a pole that the
        // loop gain 1/|G(0)| moves to s = 0), then ω > 0
        let lf = self.low_frequency();
        if lf.int_order == 0 && lf.sign < 0.0 && !self.reduced_poles().is_empty() {
            let e = form.eval(0.0);
            out.phase_crossings.push(PhaseCrossing {
                w: 0.0,
                gain_margin: (-e.ln_mag()).exp(),
                gain_margin_db: -e.db(),
            });
        }
        let delay = self.delay();
        if delay > 0.0 {
            let w_plot = 10f64.powf(form.decade_range().1);
            let (crossings, listed_to) = delayed::phase_crossings(form, delay, w_plot, &singular);
            out.phase_crossings.extend(crossings);
            out.crossings_listed_to = Some(listed_to);
        }
        for w in if delay > 0.0 {
            Vec::new()
        } else {
            cand.phase_crossings(form)?
        } {
            if singular.iter().any(|&b| (w - b).abs() <= 1e-8 * b) {
                continue;
            }
            let e = form.eval(w);
            if !(e.mant > 0.0 && e.mant.is_finite()) {
                continue;
            }
            let phi = e.phase_rad();
            let target = PI * (2.0 * ((phi - PI) / TAU).round() + 1.0);
            if (phi - target).abs() >= FRAC_PI_2 {
                continue; // G real positive here
            }
            if let Some(w) = polish(|x| form.eval(x).phase_rad() - target, w, &singular, 1e-10) {
                let w = real.as_ref().map_or(w, |r| r.phase(w, target, &singular));
                let (gain_margin, gain_margin_db) = gain_margin(w);
                out.phase_crossings.push(PhaseCrossing {
                    w,
                    gain_margin,
                    gain_margin_db,
                });
            }
        }
        dedup_by_w(&mut out.phase_crossings, |c| c.w);
        out.headline();

        // |G(0)| = |K| from the source (0 or ∞ with a zero or pole at 0)
        let dc = form.eval(0.0).magnitude();
        if !(dc > 0.0 && dc.is_finite()) {
            return Ok(out);
        }

        // bandwidth: |G| = 10^(−3/20)·|G(0)|
        let level = dc.ln() - 0.15 * std::f64::consts::LN_10;
        for w in cand.level_crossings(form, dc * dc * 10f64.powf(-0.3), level)? {
            if let Some(w) = polish(|x| form.eval(x).ln_mag() - level, w, &singular, 1e-10) {
                let w = real.as_ref().map_or(w, |r| r.level(w, level, &singular));
                out.bandwidth = Some(w);
                break;
            }
        }

        // resonance
        if let Some(beta) = form
            .axis_poles()
            .iter()
            .copied()
            .min_by(|a, b| a.total_cmp(b))
        {
            out.resonant_peak = Some(f64::INFINITY);
            out.resonant_frequency = Some(beta);
            return Ok(out);
        }
        let mut best: Option<(f64, f64)> = None;
        for w in resonance_candidates(&cand, form, &singular)? {
            let w = real.as_ref().map_or(w, |r| r.peak(w, &singular));
            let lm = ln_mag(w);
            if best.is_none_or(|(_, l)| lm > l) {
                best = Some((w, lm));
            }
        }
        let ln_inf = match self.relative_degree() {
            Some(0) => self.gain().abs().ln(),
            Some(r) if r > 0 => f64::NEG_INFINITY,
            _ => f64::INFINITY,
        };
        if let Some((w, lm)) = best {
            let floor = dc.ln().max(ln_inf);
            if lm > floor + 1e-12 {
                out.resonant_peak = Some((lm - dc.ln()).exp());
                out.resonant_frequency = Some(w);
            }
        }
        Ok(out)
    }
}

/// Where crossing candidates come from: the polynomials in ω² of the reduced coefficients
/// (plants given by coefficients), or sign changes on a dense grid adapted to the factors
/// (plants without coefficients). Either way the candidates are polished on G(jω).
enum Candidates {
    Polys(AxisPolys),
    Grid(Vec<f64>),
}

/// Grid points per decade for plants without coefficients.
const GRID_PER_DECADE: usize = 200;

impl Candidates {
    fn new(f: &Factored, form: &BodeForm) -> Result<Candidates> {
        match f.source().coefficients() {
            Some(c) => Ok(Candidates::Polys(AxisPolys::new(&c.reduced, form)?)),
            None => Ok(Candidates::Grid(form.sampling_grid(GRID_PER_DECADE))),
        }
    }

    fn gain_crossings(&self, form: &BodeForm) -> Result<Vec<f64>> {
        self.level_crossings(form, 1.0, 0.0)
    }

    /// ω where |G| = e^level (`c2` = e^(2·level) for the polynomial form).
    fn level_crossings(&self, form: &BodeForm, c2: f64, level: f64) -> Result<Vec<f64>> {
        match self {
            Candidates::Polys(ax) => {
                let p = &ax.mag2(&ax.n) - &ax.mag2(&ax.d).scale(c2);
                ax.positive_roots(&p)
            }
            Candidates::Grid(xs) => {
                let f = |x: f64| form.eval(x).ln_mag() - level;
                let fs: Vec<f64> = xs.iter().map(|&x| f(x)).collect();
                Ok(all_crossings(f, xs, &fs, 0.0))
            }
        }
    }

    /// ω where φ ≡ 180° (mod 360°), or G is real (polynomial form: roots of Im(N·conj D)).
    fn phase_crossings(&self, form: &BodeForm) -> Result<Vec<f64>> {
        match self {
            Candidates::Polys(ax) => {
                let h = &(&ax.n.odd * &ax.d.even) - &(&ax.n.even * &ax.d.odd);
                ax.positive_roots(&h)
            }
            Candidates::Grid(xs) => {
                // the branch index k of φ ∈ (−180° + 360°k, 180° + 360°k] changes at a crossing
                let branch = |x: f64| ((form.eval(x).phase_rad() - PI) / TAU).ceil();
                let mut out = Vec::new();
                for w in xs.windows(2) {
                    let (ka, kb) = (branch(w[0]), branch(w[1]));
                    if !ka.is_finite() || !kb.is_finite() || (ka - kb).abs() < 0.5 {
                        continue;
                    }
                    let target = PI * (2.0 * ka.max(kb) - 1.0);
                    let f = |x: f64| form.eval(x).phase_rad() - target;
                    let (fa, fb) = (f(w[0]), f(w[1]));
                    if fa.signum() != fb.signum() {
                        let br = Bracket {
                            a: w[0],
                            b: w[1],
                            fa,
                            fb,
                        };
                        if let Ok(x) = brent(f, br, 0.0) {
                            out.push(x);
                        }
                    }
                }
                Ok(out)
            }
        }
    }
}

/// Even and odd parts of a polynomial on the imaginary axis, in u = (ω/ω₀)²:
/// P(jω) = even(u) + j·(ω/ω₀)·odd(u).
struct Parts {
    even: Poly,
    odd: Poly,
}

/// The numerator's and denominator's parts after the exact frequency scaling s = ω₀·s′ and a
/// common power-of-two normalisation (which leaves G unchanged).
struct AxisPolys {
    /// ω₀ (a power of two).
    w0: f64,
    n: Parts,
    d: Parts,
}

impl AxisPolys {
    fn new(reduced: &TransferFunction, form: &BodeForm) -> Result<AxisPolys> {
        let corners = form.corner_frequencies();
        let w0 = match (
            corners.iter().copied().reduce(f64::min),
            corners.iter().copied().reduce(f64::max),
        ) {
            (Some(lo), Some(hi)) => (lo.sqrt() * hi.sqrt())
                .log2()
                .round()
                .clamp(-1000.0, 1000.0),
            _ => 0.0,
        };
        let e_w = w0 as i32;
        // exponents of the scaled coefficients p_i·2^(i·e_w), to choose a common normalisation
        let mut max_e = i32::MIN;
        for p in [reduced.num(), reduced.den()] {
            for (i, &c) in p.ascending().iter().enumerate() {
                if c != 0.0 {
                    let e = exponent_of(c).saturating_add((i as i32).saturating_mul(e_w));
                    max_e = max_e.max(e);
                }
            }
        }
        let shift = -max_e;
        let parts = |p: &Poly| -> Result<Parts> {
            let a = p.ascending();
            let scaled: Vec<f64> = a
                .iter()
                .enumerate()
                .map(|(i, &c)| mul_pow2(c, (i as i32).saturating_mul(e_w).saturating_add(shift)))
                .collect();
            let mut even = Vec::new();
            let mut odd = Vec::new();
            for (i, &c) in scaled.iter().enumerate() {
                let sign = if (i / 2) % 2 == 0 { 1.0 } else { -1.0 };
                if i % 2 == 0 {
                    even.push(sign * c);
                } else {
                    odd.push(sign * c);
                }
            }
            if odd.is_empty() {
                odd.push(0.0);
            }
            Ok(Parts {
                even: Poly::from_ascending(&even)?,
                odd: Poly::from_ascending(&odd)?,
            })
        };
        Ok(AxisPolys {
            w0: mul_pow2(1.0, e_w),
            n: parts(reduced.num())?,
            d: parts(reduced.den())?,
        })
    }

    /// |P(jω)|² = even² + u·odd².
    fn mag2(&self, p: &Parts) -> Poly {
        &(&p.even * &p.even) + &(&Poly::s() * &(&p.odd * &p.odd))
    }

    /// ω = ω₀·√u for the positive real roots u of `p` (roots with an imaginary part below
    /// 1e-6 relative count as real: the polishing step decides), sorted.
    fn positive_roots(&self, p: &Poly) -> Result<Vec<f64>> {
        if p.is_zero() || p.degree() == 0 {
            return Ok(Vec::new());
        }
        let mut out: Vec<f64> = p
            .roots()?
            .iter()
            .filter(|r| r.value.re > 0.0 && r.value.im.abs() <= 1e-6 * r.value.re)
            .filter(|r| r.value.im >= 0.0)
            .map(|r| self.w0 * r.value.re.sqrt())
            .filter(|w| w.is_finite() && *w > 0.0)
            .collect();
        out.sort_by(f64::total_cmp);
        Ok(out)
    }
}

/// Binary exponent of a finite non-zero number.
fn exponent_of(x: f64) -> i32 {
    if x == 0.0 || !x.is_finite() {
        return 0;
    }
    x.abs().log2().floor() as i32
}

/// Polishes a candidate root `w` of the analytic function `f` by Brent's method on a sign
/// change found in growing neighbourhoods (never across one of the `walls`, where f jumps).
/// A candidate without a sign change nearby is kept only when |f(w)| ≤ `tangent_tol` (a
/// tangency, e.g. a double root).
fn polish(f: impl Fn(f64) -> f64, w: f64, walls: &[f64], tangent_tol: f64) -> Option<f64> {
    let f0 = f(w);
    if f0 == 0.0 {
        return Some(w);
    }
    if !f0.is_finite() {
        return None;
    }
    let lo_wall = walls.iter().copied().filter(|&b| b < w).fold(0.0, f64::max);
    let hi_wall = walls
        .iter()
        .copied()
        .filter(|&b| b > w)
        .fold(f64::INFINITY, f64::min);
    for rel in [1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-3, 1e-2] {
        let a = w * (1.0 - rel);
        let b = w * (1.0 + rel);
        if a <= lo_wall || b >= hi_wall {
            break;
        }
        let fa = f(a);
        if fa.is_finite() && (fa == 0.0 || fa.signum() != f0.signum()) {
            let br = Bracket {
                a,
                b: w,
                fa,
                fb: f0,
            };
            return brent(&f, br, 0.0).ok();
        }
        let fb = f(b);
        if fb.is_finite() && (fb == 0.0 || fb.signum() != f0.signum()) {
            let br = Bracket {
                a: w,
                b,
                fa: f0,
                fb,
            };
            return brent(&f, br, 0.0).ok();
        }
    }
    (f0.abs() <= tangent_tol).then_some(w)
}

/// Every local maximum of |G(jω)| at ω > 0 (excluding imaginary-axis poles, where |G| = ∞),
/// sorted.
pub(crate) fn local_maxima(f: &Factored) -> Result<Vec<f64>> {
    if f.is_zero() {
        return Ok(Vec::new());
    }
    let form = f.bode();
    let cand = Candidates::new(f, form)?;
    let walls: Vec<f64> = form
        .axis_poles()
        .iter()
        .chain(form.axis_zeros())
        .copied()
        .collect();
    let mut out = resonance_candidates(&cand, form, &walls)?;
    dedup_by_w(&mut out, |&w| w);
    Ok(out)
}

/// Local maxima of |G(jω)| at ω > 0: roots of d|G|²/du, polished on d ln|G|/dω. When that
/// polynomial's degree exceeds [`MAX_ORDER`], sign changes of d ln|G|/dω on a dense
/// logarithmic grid (refined at lightly damped modes) are used instead.
fn resonance_candidates(cand: &Candidates, form: &BodeForm, walls: &[f64]) -> Result<Vec<f64>> {
    let d = |x: f64| form.d_ln_mag(x);
    let mut out = Vec::new();
    let r = match cand {
        Candidates::Polys(ax) => {
            let an = ax.mag2(&ax.n);
            let ad = ax.mag2(&ax.d);
            Some((ax, &(&an.derivative() * &ad) - &(&an * &ad.derivative())))
        }
        Candidates::Grid(_) => None,
    };
    if let Some((ax, r)) = r.filter(|(_, r)| r.degree() <= MAX_ORDER) {
        for w in ax.positive_roots(&r)? {
            if let Some(w) = polish(d, w, walls, 0.0) {
                out.push(w);
            }
        }
    } else {
        let xs = form.sampling_grid(40);
        let fs: Vec<f64> = xs.iter().map(|&x| d(x)).collect();
        out = all_crossings(d, &xs, &fs, 0.0);
    }
    // keep maxima: d ln|G|/dω goes from + to −. Probed at growing offsets: next to a shallow
    // peak of an ill-conditioned plant the slope 1e-7·ω away is below the accuracy of the
    // factored-form derivative (root errors of ~1e-9), while 1e-3·ω away it is not.
    out.retain(|&w| {
        [1e-7, 1e-5, 1e-3].iter().any(|&k| {
            let h = k * w;
            d(w - h) > 0.0 && d(w + h) < 0.0
        })
    });
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_into_half_open_interval() {
        assert!((wrap_deg(-90.0) + 90.0).abs() < 1e-12);
        assert!((wrap_deg(180.0) - 180.0).abs() < 1e-12);
        assert!((wrap_deg(-180.0) - 180.0).abs() < 1e-12);
        assert!((wrap_deg(-270.0) - 90.0).abs() < 1e-12);
        assert!((wrap_deg(400.0) - 40.0).abs() < 1e-12);
    }

    #[test]
    fn polish_refuses_to_cross_a_wall() {
        // f jumps across 1: no root may be reported there
        let f = |x: f64| if x < 1.0 { 1.0 } else { -1.0 };
        assert!(polish(f, 1.0 - 1e-9, &[1.0], 1e-10).is_none());
        let g = |x: f64| x - 2.0;
        assert!((polish(g, 2.0 + 1e-9, &[1.0], 1e-10).unwrap() - 2.0).abs() < 1e-15);
    }
}
