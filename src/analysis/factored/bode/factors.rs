//! The normalised first- and second-order factors of a polynomial on the imaginary axis, and
//! their evaluation: the fast lane-parallel product with branch tracking, and the
//! overflow-free per-factor logarithmic path.

use std::f64::consts::{FRAC_PI_2, LN_2, PI};

use num_complex::Complex64;

use crate::poly::{HalfPlane, Root};

/// A real quadratic factor (1 − aω²) + jbω of a conjugate pair p, p̄ (p = σ + jβ):
/// a = 1/|p|², b = −2σ/|p|²; `r` = |p| and `sn` = σ/r for the overflow-free path.
#[derive(Debug, Clone, Copy)]
pub(super) struct Quad {
    pub(super) a: f64,
    pub(super) b: f64,
    /// +1 when b ≥ 0 (left half plane), −1 otherwise: the direction of the half turn.
    pub(super) sb: i32,
    pub(super) r: f64,
    pub(super) sn: f64,
}

/// The normalised factors of one polynomial (numerator or denominator).
#[derive(Debug, Clone, Default)]
pub(super) struct FactorSet {
    /// c = −1/p for each real root p (with repetition): factor 1 + jcω.
    pub(super) real_c: Vec<f64>,
    /// The real roots themselves (for the logarithmic path).
    pub(super) real_p: Vec<f64>,
    /// Conjugate pairs off the axis (with repetition).
    pub(super) quad: Vec<Quad>,
    /// β > 0 of imaginary-axis pairs ±jβ (with repetition).
    pub(super) axis: Vec<f64>,
    /// 1/β for each axis pair.
    pub(super) axis_inv: Vec<f64>,
}

impl FactorSet {
    /// The factors of `roots`, with the half plane of each pair decided by `side` (the
    /// factored form's decision: exact for coefficients typed as text, so a pair 1e-20 left of
    /// the axis is a lightly damped quadratic with a finite peak, not an axis pole).
    pub(super) fn from_roots(roots: &[Root], side: &dyn Fn(Complex64) -> HalfPlane) -> FactorSet {
        let mut s = FactorSet::default();
        for r in roots {
            let p = r.value;
            if p.re == 0.0 && p.im == 0.0 {
                continue; // pulled into (jω)^k
            }
            if p.im == 0.0 {
                for _ in 0..r.multiplicity {
                    s.real_c.push(-1.0 / p.re);
                    s.real_p.push(p.re);
                }
                continue;
            }
            if p.im < 0.0 {
                continue; // the upper member stands for the pair
            }
            if side(p) == HalfPlane::Axis {
                for _ in 0..r.multiplicity {
                    s.axis.push(p.im);
                    s.axis_inv.push(1.0 / p.im);
                }
                continue;
            }
            let r2 = p.re * p.re + p.im * p.im;
            let rr = p.re.hypot(p.im);
            let b = -2.0 * p.re / r2;
            for _ in 0..r.multiplicity {
                s.quad.push(Quad {
                    a: 1.0 / r2,
                    b,
                    sb: if p.re <= 0.0 { 1 } else { -1 },
                    r: rr,
                    sn: p.re / rr,
                });
            }
        }
        s
    }

    /// Largest ω·(scale of a factor) coefficient: the fast path is used while
    /// `ω · max_rate ≤ FAST_FACTOR_LIMIT`.
    pub(super) fn max_rate(&self) -> f64 {
        let mut m: f64 = 0.0;
        for &c in &self.real_c {
            m = m.max(c.abs());
        }
        for q in &self.quad {
            m = m.max(q.a.sqrt()).max(q.b.abs());
        }
        for &ib in &self.axis_inv {
            m = m.max(ib);
        }
        if m.is_finite() { m } else { f64::INFINITY }
    }
}

/// Every factor stays below 2^200 in magnitude on the fast path, so four of them multiply
/// without overflow between rescalings.
pub(super) const FAST_FACTOR_LIMIT: f64 = 1.606_938_044_258_990_3e60; // 2^200

/// The result of evaluating G(jω): |G| = `mant`·2^`exp2`, ∠G = `angle` + `quarters`·π/2.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Eval {
    /// Mantissa of the magnitude (0 or +∞ at an exact zero/pole, else positive finite).
    pub mant: f64,
    /// Binary exponent of the magnitude.
    pub exp2: i32,
    /// Principal part of the phase (radians).
    pub angle: f64,
    /// Whole quarter turns added to `angle`.
    pub quarters: i64,
}

impl Eval {
    /// |G| (saturates to 0 or +∞ beyond the f64 range).
    pub fn magnitude(&self) -> f64 {
        mul_pow2(self.mant, self.exp2)
    }
    /// 20·log₁₀|G|.
    pub fn db(&self) -> f64 {
        // 20·log₁₀|G| = (20/ln 10)·(ln mant + exp2·ln 2)
        const DB_PER_NEPER: f64 = 20.0 * std::f64::consts::LOG10_E;
        DB_PER_NEPER * (super::fastmath::ln(self.mant) + LN_2 * self.exp2 as f64)
    }
    /// ln|G|.
    pub fn ln_mag(&self) -> f64 {
        self.mant.ln() + LN_2 * self.exp2 as f64
    }
    /// Phase in radians.
    pub fn phase_rad(&self) -> f64 {
        self.angle + FRAC_PI_2 * self.quarters as f64
    }
    /// Phase in degrees (the quarter turns are added exactly as multiples of 90°).
    pub fn phase_deg(&self) -> f64 {
        self.angle.to_degrees() + 90.0 * self.quarters as f64
    }
}

/// x·2^e without intermediate overflow (saturating); exact unless the result leaves the
/// f64 range.
pub(crate) fn mul_pow2(x: f64, e: i32) -> f64 {
    let mut x = x;
    let mut e = e;
    while e > 1000 {
        x *= pow2(1000);
        e -= 1000;
        if x.is_infinite() {
            return x;
        }
    }
    while e < -1000 {
        x *= pow2(-1000);
        e += 1000;
        if x == 0.0 {
            return x;
        }
    }
    x * pow2(e)
}

/// 2^e for e in [−1022, 1023].
#[inline(always)]
pub(super) fn pow2(e: i32) -> f64 {
    f64::from_bits(((e + 1023) as u64) << 52)
}

/// Binary exponent of a normal positive number (clamped so that 2^−e is representable).
#[inline(always)]
pub(super) fn exponent(m: f64) -> i32 {
    ((((m.to_bits() >> 52) & 0x7ff) as i32) - 1023).clamp(-1022, 1022)
}

/// Rescales (re, im) to max(|re|, |im|) ∈ [1, 2), moving the power of two into `e`.
#[inline(always)]
pub(super) fn rescale(re: &mut f64, im: &mut f64, e: &mut i32) {
    let ex = exponent(re.abs().max(im.abs()));
    let s = pow2(-ex);
    *re *= s;
    *im *= s;
    *e += ex;
}

/// Number of frequencies evaluated side by side on the fast path: independent dependency
/// chains let the CPU overlap the complex multiplications.
#[cfg(test)]
pub(super) const LANES: usize = 4;

/// (re + j·im) ← (re + j·im)·(fr + j·fi) for a factor with fr ≥ 0 (angle in [−π/2, π/2]),
/// counting full turns: `upper` says the argument is in (0, π] (Im > 0, or on the negative
/// real axis) and `turns` gains ±1 when the product crosses the negative real axis. It passes
/// the real axis through π iff the point nearer to the axis (in angle) has Re < 0: one of the
/// two is within π/4 of the crossing. Shared by the per-frequency lanes and the fused kernel.
#[inline(always)]
pub(super) fn mul_tracked(
    re: &mut f64,
    im: &mut f64,
    upper: &mut bool,
    turns: &mut i32,
    fr: f64,
    fi: f64,
) {
    let (r, i) = (*re, *im);
    let nr = r * fr - i * fi;
    let ni = r * fi + i * fr;
    let nup = ni > 0.0 || (ni == 0.0 && nr < 0.0);
    let s = if r.abs() >= i.abs() { r } else { nr };
    let cross = (nup != *upper) & (s < 0.0);
    let dir = if *upper { 1 } else { -1 };
    *turns += if cross { dir } else { 0 };
    *re = nr;
    *im = ni;
    *upper = nup;
}

/// Running products of factors with positive real part at `L` frequencies at once, tracking
/// the full turns of each argument, plus the exact half and quarter turns pulled out.
#[derive(Clone, Copy)]
pub(super) struct Lanes<const L: usize> {
    pub(super) re: [f64; L],
    pub(super) im: [f64; L],
    pub(super) exp: [i32; L],
    /// The argument is in (0, π] ("upper": Im > 0, or on the negative real axis).
    pub(super) upper: [bool; L],
    /// Full turns (2π) gained by crossing the negative real axis.
    pub(super) turns: [i32; L],
    /// Half turns pulled out of quadratic factors with negative real part.
    pub(super) halves: [i32; L],
    /// Quarter turns of imaginary-axis pairs (2 past β, 1 at β).
    pub(super) axis_quarters: [i32; L],
    /// ω hit an axis root exactly.
    pub(super) hit: [bool; L],
}

impl<const L: usize> Lanes<L> {
    #[inline(always)]
    pub(super) fn one() -> Self {
        Lanes {
            re: [1.0; L],
            im: [0.0; L],
            exp: [0; L],
            upper: [false; L],
            turns: [0; L],
            halves: [0; L],
            axis_quarters: [0; L],
            hit: [false; L],
        }
    }

    /// Multiplies lane `l` by (fr + j·fi), fr ≥ 0 (the factor's angle is in [−π/2, π/2]).
    #[inline(always)]
    pub(super) fn mul(&mut self, l: usize, fr: f64, fi: f64) {
        mul_tracked(
            &mut self.re[l],
            &mut self.im[l],
            &mut self.upper[l],
            &mut self.turns[l],
            fr,
            fi,
        );
    }

    #[inline(always)]
    pub(super) fn rescale(&mut self) {
        for l in 0..L {
            rescale(&mut self.re[l], &mut self.im[l], &mut self.exp[l]);
        }
    }

    /// The product of every factor of `s` at the frequencies `w` (`w2` = ω²).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lanes index several parallel arrays
    pub(super) fn of_set(s: &FactorSet, w: &[f64; L], w2: &[f64; L]) -> Self {
        let mut a = Self::one();
        for chunk in s.real_c.chunks(4) {
            for &c in chunk {
                for l in 0..L {
                    a.mul(l, 1.0, c * w[l]);
                }
            }
            a.rescale();
        }
        for chunk in s.quad.chunks(4) {
            for q in chunk {
                for l in 0..L {
                    let x = 1.0 - q.a * w2[l];
                    let y = q.b * w[l];
                    let neg = x < 0.0;
                    a.halves[l] += if neg { q.sb } else { 0 };
                    let (fr, fi) = if neg { (-x, -y) } else { (x, y) };
                    a.mul(l, fr, fi);
                }
            }
            a.rescale();
        }
        for (&beta, &ib) in s.axis.iter().zip(&s.axis_inv) {
            for l in 0..L {
                let x = ((beta - w[l]) * ib) * ((beta + w[l]) * ib);
                if x == 0.0 {
                    a.hit[l] = true;
                    a.axis_quarters[l] += 1;
                } else {
                    if x < 0.0 {
                        a.axis_quarters[l] += 2;
                    }
                    let ax = x.abs();
                    a.re[l] *= ax;
                    a.im[l] *= ax;
                }
            }
            a.rescale();
        }
        a.rescale();
        a
    }
}

/// Centre of the quadrant of (re, im), as an estimate of its principal argument (error
/// ≤ π/4).
#[inline(always)]
pub(super) fn quadrant_centre(re: f64, im: f64) -> f64 {
    let a = if re >= 0.0 {
        std::f64::consts::FRAC_PI_4
    } else {
        3.0 * std::f64::consts::FRAC_PI_4
    };
    if im >= 0.0 { a } else { -a }
}

/// ln|F| and ∠F of every factor of a set, summed, by the overflow-free logarithmic path.
pub(super) fn set_log(s: &FactorSet, w: f64) -> (f64, f64, bool) {
    let mut ln = 0.0;
    let mut ang = 0.0;
    let mut hit = false;
    for &p in &s.real_p {
        let t = -w / p;
        ang += t.atan();
        ln += if t.abs() < 1e150 {
            0.5 * (t * t).ln_1p()
        } else {
            w.ln() - p.abs().ln()
        };
    }
    for q in &s.quad {
        let u = w / q.r;
        if u <= 1.0 {
            let x = 1.0 - u * u;
            let y = -2.0 * q.sn * u;
            ang += y.atan2(x);
            ln += 0.5 * (x * x + y * y).ln();
        } else {
            let v = 1.0 / u;
            let x = v * v - 1.0;
            let y = -2.0 * q.sn * v;
            // (1 − u²) − 2j·sn·u = u²·[(v² − 1) − 2j·sn·v]; the angle of the bracket has the
            // same sign convention (Im keeps its sign, Re < 0 past the corner).
            ang += y.atan2(x);
            ln += 2.0 * u.ln() + 0.5 * (x * x + y * y).ln();
        }
    }
    for &beta in &s.axis {
        #[allow(clippy::float_cmp)] // exactly at the axis root: |G| is 0 or ∞ there
        let at_root = w == beta;
        if at_root {
            hit = true;
            ang += FRAC_PI_2;
            ln = f64::NEG_INFINITY;
        } else {
            if w > beta {
                ang += PI;
            }
            if ln.is_finite() {
                ln += (beta - w).abs().ln() + (beta + w).ln() - 2.0 * beta.ln();
            }
        }
    }
    (ln, ang, hit)
}
