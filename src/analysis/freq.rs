//! Frequency response G(jω): magnitude, dB and continuous phase.
//!
//! # Conventions
//! - ω in rad/s, finite and ≥ 0; magnitudes as ratios and in dB (20·log₁₀); phase in degrees.
//! - The phase is **continuous in ω** and independent of the grid: it is not unwrapped from
//!   samples but built from the factored (Bode) form of the reduced transfer function
//!
//!   G(jω) = K·(jω)^k·Π(1 − jω/zᵢ) / Π(1 − jω/pᵢ),
//!
//!   where the k zero roots (exactly: the trailing zero coefficients) are pulled into (jω)^k
//!   and K is the low-frequency asymptote gain (ratio of the lowest non-zero coefficients).
//!   φ(ω) = [K < 0 ? −180° : 0] + 90°·k + Σ∠(1 − jω/zᵢ) − Σ∠(1 − jω/pᵢ). Each factor's angle
//!   stays on one side of its branch cut, so the sum is continuous. Consequences (DESIGN
//!   §1.3): 1/s³ starts at −270°, a negative gain at −180°, a right-half-plane zero adds lag.
//! - Roots on the imaginary axis (within the relative tolerance
//!   [`AXIS_REL_TOL`](crate::numeric::tol::AXIS_REL_TOL) they are taken as exactly on it) follow
//!   the limit of vanishing damping: a pole pair ±jβ drops the phase by 180° as ω passes β, a
//!   zero pair raises it by 180°; at ω = β exactly the magnitude is +∞ (pole) or 0 (zero) and
//!   the phase is the midpoint.
//! - G ≡ 0 has magnitude 0 (−∞ dB) and, by convention, phase 0.
//! - Infinite magnitudes (a pole hit exactly, or ω = 0 with an integrator) are kept as f64
//!   infinities; −∞ / +∞ dB likewise.
//!
//! # Method and cost
//! The factors are grouped into real first-order factors (1 + jcω) and real quadratic factors
//! (1 − aω²) + jbω (a conjugate pair); each has a positive real part after pulling out an
//! exact half turn, so its angle lies in (−π/2, π/2]. The complex product of all factors is
//! accumulated with exact power-of-two rescaling (no overflow at high order or high ω), and
//! the branch of its argument is tracked by counting crossings of the negative real axis —
//! a few comparisons per factor instead of an `atan2` per factor. One `atan2` per ω then
//! gives the phase exactly to rounding. Frequencies so extreme that a single factor could
//! overflow (ω beyond ~1e60 × the corner frequency) use a per-factor logarithmic path.

use num_complex::Complex64;
use serde::Serialize;
use std::f64::consts::{FRAC_PI_2, LN_2, PI, TAU};

use crate::analysis::pz::PoleZero;
use crate::analysis::stability::{HalfPlane, half_plane};
use crate::error::{LtiError, Result, check_finite};
use crate::lti::TransferFunction;
use crate::poly::Root;

/// G(jω) sampled at the frequencies `w` (rad/s). All vectors have the same length.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrequencyResponse {
    /// Frequencies (rad/s), as requested.
    pub w: Vec<f64>,
    /// |G(jω)|.
    pub magnitude: Vec<f64>,
    /// 20·log₁₀|G(jω)| (dB); −∞ at an exact zero on the axis.
    pub magnitude_db: Vec<f64>,
    /// Phase in degrees, continuous in ω (DESIGN §1.3).
    pub phase_deg: Vec<f64>,
}

impl TransferFunction {
    /// Frequency response G(jω) at the frequencies `w` (rad/s, finite, ≥ 0, any order).
    ///
    /// Uses the reduced (lowest-terms) G in factored form; see the [module
    /// docs](crate::analysis::freq) for the phase convention. Magnitudes agree with Horner's
    /// rule on the coefficients to rounding (tested to 1e-10 relative).
    ///
    /// Errors: a NaN/infinite or negative frequency; root-finding failures of the polynomials.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // 1/s³ starts at −270°, not +90°.
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 0.0, 0.0, 0.0]).unwrap();
    /// let r = g.freq_response(&[0.01, 1.0]).unwrap();
    /// assert!((r.phase_deg[0] + 270.0).abs() < 1e-12);
    /// assert!((r.magnitude_db[1]).abs() < 1e-12);
    /// // 1/(s² + 1) drops by 180° through ω = 1; the phase is −90° and |G| = ∞ exactly there.
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 0.0, 1.0]).unwrap();
    /// let r = g.freq_response(&[0.5, 1.0, 2.0]).unwrap();
    /// assert!(r.phase_deg[0].abs() < 1e-12);
    /// assert!((r.phase_deg[1] + 90.0).abs() < 1e-12 && r.magnitude[1].is_infinite());
    /// assert!((r.phase_deg[2] + 180.0).abs() < 1e-12);
    /// ```
    pub fn freq_response(&self, w: &[f64]) -> Result<FrequencyResponse> {
        check_frequencies(w)?;
        let form = BodeForm::new(self)?;
        let n = w.len();
        let mut magnitude = Vec::with_capacity(n);
        let mut magnitude_db = Vec::with_capacity(n);
        let mut phase_deg = Vec::with_capacity(n);
        form.eval_many(w, |e| {
            magnitude.push(e.magnitude());
            magnitude_db.push(e.db());
            phase_deg.push(e.phase_deg());
        });
        Ok(FrequencyResponse {
            w: w.to_vec(),
            magnitude,
            magnitude_db,
            phase_deg,
        })
    }
}

/// Checks that every frequency is finite and ≥ 0.
pub(crate) fn check_frequencies(w: &[f64]) -> Result<()> {
    for (i, &x) in w.iter().enumerate() {
        check_finite(|| format!("frequency w[{i}]"), x)?;
        if x < 0.0 {
            return Err(LtiError::InvalidParameter {
                name: format!("w[{i}]"),
                value: x,
                reason: "frequencies must be ≥ 0 rad/s".into(),
            });
        }
    }
    Ok(())
}

/// A real quadratic factor (1 − aω²) + jbω of a conjugate pair p, p̄ (p = σ + jβ):
/// a = 1/|p|², b = −2σ/|p|²; `r` = |p| and `sn` = σ/r for the overflow-free path.
#[derive(Debug, Clone, Copy)]
struct Quad {
    a: f64,
    b: f64,
    /// +1 when b ≥ 0 (left half plane), −1 otherwise: the direction of the half turn.
    sb: i32,
    r: f64,
    sn: f64,
}

/// The normalised factors of one polynomial (numerator or denominator).
#[derive(Debug, Clone, Default)]
struct FactorSet {
    /// c = −1/p for each real root p (with repetition): factor 1 + jcω.
    real_c: Vec<f64>,
    /// The real roots themselves (for the logarithmic path).
    real_p: Vec<f64>,
    /// Conjugate pairs off the axis (with repetition).
    quad: Vec<Quad>,
    /// β > 0 of imaginary-axis pairs ±jβ (with repetition).
    axis: Vec<f64>,
    /// 1/β for each axis pair.
    axis_inv: Vec<f64>,
}

impl FactorSet {
    fn from_roots(roots: &[Root]) -> FactorSet {
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
            if half_plane(p) == HalfPlane::Axis {
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
    fn max_rate(&self) -> f64 {
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
const FAST_FACTOR_LIMIT: f64 = 1.606_938_044_258_990_3e60; // 2^200

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
        20.0 * self.mant.log10() + (20.0 * std::f64::consts::LOG10_2) * self.exp2 as f64
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
fn pow2(e: i32) -> f64 {
    f64::from_bits(((e + 1023) as u64) << 52)
}

/// Binary exponent of a normal positive number (clamped so that 2^−e is representable).
#[inline(always)]
fn exponent(m: f64) -> i32 {
    ((((m.to_bits() >> 52) & 0x7ff) as i32) - 1023).clamp(-1022, 1022)
}

/// Rescales (re, im) to max(|re|, |im|) ∈ [1, 2), moving the power of two into `e`.
#[inline(always)]
fn rescale(re: &mut f64, im: &mut f64, e: &mut i32) {
    let ex = exponent(re.abs().max(im.abs()));
    let s = pow2(-ex);
    *re *= s;
    *im *= s;
    *e += ex;
}

/// Number of frequencies evaluated side by side on the fast path: independent dependency
/// chains let the CPU overlap the complex multiplications.
const LANES: usize = 4;

/// Running products of factors with positive real part at `L` frequencies at once, tracking
/// the full turns of each argument, plus the exact half and quarter turns pulled out.
#[derive(Clone, Copy)]
struct Lanes<const L: usize> {
    re: [f64; L],
    im: [f64; L],
    exp: [i32; L],
    /// The argument is in (0, π] ("upper": Im > 0, or on the negative real axis).
    upper: [bool; L],
    /// Full turns (2π) gained by crossing the negative real axis.
    turns: [i32; L],
    /// Half turns pulled out of quadratic factors with negative real part.
    halves: [i32; L],
    /// Quarter turns of imaginary-axis pairs (2 past β, 1 at β).
    axis_quarters: [i32; L],
    /// ω hit an axis root exactly.
    hit: [bool; L],
}

impl<const L: usize> Lanes<L> {
    #[inline(always)]
    fn one() -> Self {
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
    fn mul(&mut self, l: usize, fr: f64, fi: f64) {
        let (re, im) = (self.re[l], self.im[l]);
        let nr = re * fr - im * fi;
        let ni = re * fi + im * fr;
        let nup = ni > 0.0 || (ni == 0.0 && nr < 0.0);
        // When the argument passes the real axis it does so through π iff the point nearer
        // to the axis (in angle) has Re < 0: one of the two is within π/4 of the crossing.
        let s = if re.abs() >= im.abs() { re } else { nr };
        let cross = (nup != self.upper[l]) & (s < 0.0);
        let dir = if self.upper[l] { 1 } else { -1 };
        self.turns[l] += if cross { dir } else { 0 };
        self.re[l] = nr;
        self.im[l] = ni;
        self.upper[l] = nup;
    }

    #[inline(always)]
    fn rescale(&mut self) {
        for l in 0..L {
            rescale(&mut self.re[l], &mut self.im[l], &mut self.exp[l]);
        }
    }

    /// The product of every factor of `s` at the frequencies `w` (`w2` = ω²).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lanes index several parallel arrays
    fn of_set(s: &FactorSet, w: &[f64; L], w2: &[f64; L]) -> Self {
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
fn quadrant_centre(re: f64, im: f64) -> f64 {
    let a = if re >= 0.0 {
        std::f64::consts::FRAC_PI_4
    } else {
        3.0 * std::f64::consts::FRAC_PI_4
    };
    if im >= 0.0 { a } else { -a }
}

/// ln|F| and ∠F of every factor of a set, summed, by the overflow-free logarithmic path.
fn set_log(s: &FactorSet, w: f64) -> (f64, f64, bool) {
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

/// The factored (Bode) form of a reduced transfer function, precomputed for evaluation at
/// many frequencies. Shared by the frequency response, margins and grids.
#[derive(Debug, Clone)]
pub(crate) struct BodeForm {
    /// G ≡ 0.
    zero: bool,
    /// |K| = k_mant·2^k_exp.
    k_mant: f64,
    k_exp: i32,
    /// ln|K|.
    ln_k: f64,
    /// Quarter turns of the low-frequency asymptote: −2 for K < 0, plus k.
    base_quarters: i64,
    /// Order k of (jω)^k (zeros at 0 minus poles at 0).
    int_order: i32,
    num: FactorSet,
    den: FactorSet,
    /// Above this ω the logarithmic path is used.
    fast_limit: f64,
    /// Set when the factored form does not reproduce the coefficients (roots too
    /// ill-conditioned, e.g. an expanded (s+1)^20): magnitude and principal phase then come
    /// from double-double Horner, the factored form only picks the branch.
    exact: Option<Box<AxisHorner>>,
}

/// Reduced numerator and denominator for double-double Horner evaluation on the axis:
/// coefficients normalised by a power of two to max |c| ∈ [1, 2), zero roots stripped.
#[derive(Debug, Clone)]
struct AxisHorner {
    num: Vec<f64>,
    den: Vec<f64>,
    /// zeros at s = 0 minus poles at s = 0
    int_order: i32,
    /// ln(max|num| / max|den|)
    ln_scale: f64,
}

impl AxisHorner {
    fn new(reduced: &TransferFunction) -> AxisHorner {
        let prep = |p: &crate::poly::Poly| -> (Vec<f64>, usize, f64) {
            let z = p.zero_root_multiplicity();
            let c = &p.coeffs()[..p.coeffs().len() - z];
            // normalise by a power of two: exact, so Horner sees the coefficients as given
            let e = exponent(c.iter().fold(0.0f64, |a, &x| a.max(x.abs())));
            (
                c.iter().map(|&x| mul_pow2(x, -e)).collect(),
                z,
                e as f64 * LN_2,
            )
        };
        let (num, zn, ln_n) = prep(reduced.num());
        let (den, zd, ln_d) = prep(reduced.den());
        AxisHorner {
            num,
            den,
            int_order: zn as i32 - zd as i32,
            ln_scale: ln_n - ln_d,
        }
    }

    /// (ln|G(jω)|, principal-or-not argument of G(jω)) for ω > 0.
    fn eval(&self, w: f64) -> (f64, f64) {
        let (ln_n, arg_n) = dd_axis(&self.num, w);
        let (ln_d, arg_d) = dd_axis(&self.den, w);
        let k = self.int_order as f64;
        (
            self.ln_scale + ln_n - ln_d + k * w.ln(),
            arg_n - arg_d + k * FRAC_PI_2,
        )
    }
}

/// ln|P(jω)| and an argument of P(jω) (ω > 0) by Horner's rule in double-double; for ω > 1
/// on the reversed polynomial in 1/(jω), so nothing overflows. `c` descending, c[n] ≠ 0.
fn dd_axis(c: &[f64], w: f64) -> (f64, f64) {
    use crate::numeric::dd::Dd;
    let n = c.len() - 1;
    let (mut re, mut im) = (Dd::ZERO, Dd::ZERO);
    if w <= 1.0 {
        let wd = Dd::from(w);
        for &a in c {
            // (re + j·im)(jω) + a = (a − ω·im) + j·ω·re
            let nre = Dd::from(a).sub(wd.mul(im));
            im = wd.mul(re);
            re = nre;
        }
        let (r, i) = (re.to_f64(), im.to_f64());
        (r.hypot(i).ln(), i.atan2(r))
    } else {
        // P(jω) = (jω)^n·R(1/(jω)), R the reversed polynomial, 1/(jω) = −j·v, v = 1/ω
        let hi = 1.0 / w;
        let v = Dd {
            hi,
            lo: (-hi).mul_add(w, 1.0) / w,
        };
        for &a in c.iter().rev() {
            // (re + j·im)(−j·v) + a = (a + v·im) − j·v·re
            let nre = Dd::from(a).add(v.mul(im));
            im = Dd::ZERO.sub(v.mul(re));
            re = nre;
        }
        let (r, i) = (re.to_f64(), im.to_f64());
        (
            n as f64 * w.ln() + r.hypot(i).ln(),
            i.atan2(r) + n as f64 * FRAC_PI_2,
        )
    }
}

/// Relative tolerance of the factored form against double-double Horner at the probe
/// frequencies before it is trusted on its own.
const FACTORED_CHECK_TOL: f64 = 1e-11;

/// Wraps radians into (−π, π].
fn wrap_pi(x: f64) -> f64 {
    let y = x - TAU * (x / TAU).round();
    if y <= -PI { y + TAU } else { y }
}

impl BodeForm {
    /// Builds the factored form of the reduced G.
    pub fn new(tf: &TransferFunction) -> Result<BodeForm> {
        if tf.num().is_zero() {
            return Ok(Self::zero_form());
        }
        Ok(Self::with_pole_zero(tf, &tf.pole_zero()?))
    }

    /// As [`BodeForm::new`], reusing an already computed [`PoleZero`] of `tf`.
    pub fn with_pole_zero(tf: &TransferFunction, pz: &PoleZero) -> BodeForm {
        if tf.num().is_zero() {
            return Self::zero_form();
        }
        // K and k from the coefficients as given: cancelled common factors contribute the
        // same lowest non-zero coefficient to both, so the ratio is that of the reduced G.
        let zn = tf.num().zero_root_multiplicity();
        let zd = tf.den().zero_root_multiplicity();
        let k = tf.num().coeff(zn) / tf.den().coeff(zd);
        let int_order = zn as i32 - zd as i32;
        let num = FactorSet::from_roots(&pz.reduced_zeros);
        let den = FactorSet::from_roots(&pz.reduced_poles);
        let rate = num.max_rate().max(den.max_rate());
        let fast_limit = if rate > 0.0 {
            FAST_FACTOR_LIMIT / rate
        } else {
            f64::INFINITY
        };
        let ka = k.abs();
        let ln_k = tf.num().coeff(zn).abs().ln() - tf.den().coeff(zd).abs().ln();
        let (k_mant, k_exp) = if ka.is_normal() {
            let e = exponent(ka);
            (ka * pow2(-e), e)
        } else {
            // the ratio under- or overflowed: rebuild it from logarithms
            let e = (ln_k / LN_2).floor();
            ((ln_k - e * LN_2).exp(), e as i32)
        };
        BodeForm {
            zero: false,
            k_mant,
            k_exp,
            ln_k,
            base_quarters: (if k < 0.0 { -2 } else { 0 }) + int_order as i64,
            int_order,
            num,
            den,
            fast_limit,
            exact: None,
        }
        .checked(&pz.reduced)
    }

    /// Compares the factored form with double-double Horner on the reduced coefficients at
    /// probe frequencies (the corner frequencies and a log grid); on disagreement beyond
    /// [`FACTORED_CHECK_TOL`] switches to Horner magnitudes and principal phases.
    fn checked(mut self, reduced: &TransferFunction) -> BodeForm {
        let horner = AxisHorner::new(reduced);
        let mut probes = self.corner_frequencies();
        probes.sort_by(f64::total_cmp);
        probes.dedup_by(|b, a| (*b - *a).abs() <= 1e-3 * *a);
        if probes.len() > 48 {
            let step = probes.len() as f64 / 48.0;
            probes = (0..48)
                .map(|i| probes[(i as f64 * step) as usize])
                .collect();
        }
        let (a, b) = self.decade_range();
        probes.extend((0..16).map(|i| 10f64.powf(a + (b - a) * i as f64 / 15.0)));
        let axis: Vec<f64> = self
            .num
            .axis
            .iter()
            .chain(&self.den.axis)
            .copied()
            .collect();
        for &w in &probes {
            if !(w > 0.0 && w.is_finite()) || axis.iter().any(|&b| (w - b).abs() <= 1e-6 * b) {
                continue;
            }
            let f = self.eval(w);
            if !(f.mant > 0.0 && f.mant.is_finite()) {
                continue;
            }
            let (ln_h, arg_h) = horner.eval(w);
            let dl = (f.ln_mag() - ln_h).abs();
            let dp = wrap_pi(f.phase_rad() - arg_h).abs();
            if !(dl <= FACTORED_CHECK_TOL && dp <= FACTORED_CHECK_TOL) {
                self.exact = Some(Box::new(horner));
                break;
            }
        }
        self
    }

    /// True when evaluation falls back to double-double Horner (see [`BodeForm::checked`]).
    #[allow(dead_code)]
    pub fn uses_horner(&self) -> bool {
        self.exact.is_some()
    }

    fn zero_form() -> BodeForm {
        BodeForm {
            zero: true,
            k_mant: 0.0,
            k_exp: 0,
            ln_k: f64::NEG_INFINITY,
            base_quarters: 0,
            int_order: 0,
            num: FactorSet::default(),
            den: FactorSet::default(),
            fast_limit: 0.0,
            exact: None,
        }
    }

    /// β of the imaginary-axis pole pairs (with repetition).
    pub fn axis_poles(&self) -> &[f64] {
        &self.den.axis
    }

    /// β of the imaginary-axis zero pairs (with repetition).
    pub fn axis_zeros(&self) -> &[f64] {
        &self.num.axis
    }

    /// G(jω) for one ω ≥ 0 (finite; not checked here).
    #[inline]
    pub fn eval(&self, w: f64) -> Eval {
        if self.zero {
            return Eval {
                mant: 0.0,
                exp2: 0,
                angle: 0.0,
                quarters: 0,
            };
        }
        if w == 0.0 {
            let mant = match self.int_order {
                0 => self.k_mant,
                k if k > 0 => 0.0,
                _ => f64::INFINITY,
            };
            return Eval {
                mant,
                exp2: if self.int_order == 0 { self.k_exp } else { 0 },
                angle: 0.0,
                quarters: self.base_quarters,
            };
        }
        let f = if w >= f64::MIN_POSITIVE && w <= self.fast_limit {
            self.eval_fast(w)
        } else {
            self.eval_log(w)
        };
        match &self.exact {
            None => f,
            Some(h) => Self::refine(f, h, w),
        }
    }

    /// Horner magnitude and principal phase on the branch of the factored phase `f`.
    #[cold]
    fn refine(f: Eval, h: &AxisHorner, w: f64) -> Eval {
        if !(f.mant > 0.0 && f.mant.is_finite()) {
            return f; // an exact zero or pole on the axis
        }
        let (ln, arg) = h.eval(w);
        let e = (ln / LN_2).floor().clamp(-2.0e9, 2.0e9);
        Eval {
            mant: (ln - e * LN_2).exp(),
            exp2: e as i32,
            angle: f.angle + wrap_pi(arg - f.phase_rad()),
            quarters: f.quarters,
        }
    }

    #[inline(always)]
    fn eval_fast(&self, w: f64) -> Eval {
        self.eval_fast_lanes::<1>(&[w])[0]
    }

    /// The fast path at `L` frequencies side by side (each must be normal and
    /// ≤ `fast_limit`); lanes whose product is not a normal number are redone by the
    /// logarithmic path.
    #[inline(always)]
    fn eval_fast_lanes<const L: usize>(&self, w: &[f64; L]) -> [Eval; L] {
        let w2: [f64; L] = std::array::from_fn(|l| w[l] * w[l]);
        let n = Lanes::<L>::of_set(&self.num, w, &w2);
        let d = Lanes::<L>::of_set(&self.den, w, &w2);
        std::array::from_fn(|l| {
            let (nr, ni, dr, di) = (n.re[l], n.im[l], d.re[l], d.im[l]);
            if !(nr.is_finite() && ni.is_finite() && dr.is_finite() && di.is_finite())
                || (nr == 0.0 && ni == 0.0)
                || (dr == 0.0 && di == 0.0)
            {
                return self.eval_log(w[l]);
            }
            // Q = P_N · conj(P_D): its principal argument differs from ∠P_N − ∠P_D
            // (principal values) by a multiple of 2π that the quadrant estimates pin down:
            // the estimate is within π/2 of the truth, so (est − angle)/2π is within 1/4
            // of an integer in {−1, 0, 1}.
            let qr = nr * dr + ni * di;
            let qi = ni * dr - nr * di;
            let angle = qi.atan2(qr);
            let t = (quadrant_centre(nr, ni) - quadrant_centre(dr, di) - angle) * (1.0 / TAU);
            let fix: i64 = if t > 0.5 {
                1
            } else if t < -0.5 {
                -1
            } else {
                0
            };
            let quarters = self.base_quarters
                + 4 * (fix + (n.turns[l] - d.turns[l]) as i64)
                + 2 * (n.halves[l] - d.halves[l]) as i64
                + (n.axis_quarters[l] - d.axis_quarters[l]) as i64;
            // magnitude: |K|·ω^k·|P_N|/|P_D|
            let ratio = ((nr * nr + ni * ni) / (dr * dr + di * di)).sqrt();
            let mut mant = self.k_mant * ratio;
            let mut exp2 = self.k_exp + n.exp[l] - d.exp[l];
            if self.int_order != 0 {
                let we = exponent(w[l]);
                mant *= (w[l] * pow2(-we)).powi(self.int_order);
                exp2 += self.int_order.saturating_mul(we);
            }
            if n.hit[l] {
                mant = 0.0;
                exp2 = 0;
            } else if d.hit[l] {
                mant = f64::INFINITY;
                exp2 = 0;
            }
            Eval {
                mant,
                exp2,
                angle,
                quarters,
            }
        })
    }

    /// Evaluates at every ω of `w` (each finite, ≥ 0), calling `out` with the value, in
    /// order; the fast path runs [`LANES`] frequencies side by side.
    pub fn eval_many(&self, w: &[f64], mut out: impl FnMut(Eval)) {
        let mut chunks = w.chunks_exact(LANES);
        for c in &mut chunks {
            let block: [f64; LANES] = std::array::from_fn(|k| c[k]);
            let fast = self.exact.is_none()
                && !self.zero
                && block
                    .iter()
                    .all(|&x| x >= f64::MIN_POSITIVE && x <= self.fast_limit);
            if fast {
                for e in self.eval_fast_lanes(&block) {
                    out(e);
                }
            } else {
                for &x in &block {
                    out(self.eval(x));
                }
            }
        }
        for &x in chunks.remainder() {
            out(self.eval(x));
        }
    }

    /// The overflow-free path: ln|F| and ∠F per factor.
    fn eval_log(&self, w: f64) -> Eval {
        let (ln_n, ang_n, hit_n) = set_log(&self.num, w);
        let (ln_d, ang_d, hit_d) = set_log(&self.den, w);
        let ln = if hit_n {
            f64::NEG_INFINITY
        } else if hit_d {
            f64::INFINITY
        } else {
            self.ln_k + self.int_order as f64 * w.ln() + ln_n - ln_d
        };
        let (mant, exp2) = if ln.is_finite() {
            let e = (ln / LN_2).floor();
            let e = e.clamp(-2.0e9, 2.0e9);
            ((ln - e * LN_2).exp(), e as i32)
        } else if ln > 0.0 {
            (f64::INFINITY, 0)
        } else {
            (0.0, 0)
        };
        Eval {
            mant,
            exp2,
            angle: ang_n - ang_d,
            quarters: self.base_quarters,
        }
    }

    /// d ln|G(jω)| / dω at ω > 0 (used to locate resonant peaks).
    pub fn d_ln_mag(&self, w: f64) -> f64 {
        if self.zero {
            return 0.0;
        }
        if self.exact.is_some() {
            let h = 1e-6 * w;
            return (self.eval(w + h).ln_mag() - self.eval(w - h).ln_mag()) / (2.0 * h);
        }
        let mut d = self.int_order as f64 / w;
        for (set, sign) in [(&self.num, 1.0), (&self.den, -1.0)] {
            let mut s = 0.0;
            for &p in &set.real_p {
                // ½ ln(1 + t²), t = ω/|p|: derivative t²/(ω(1 + t²))
                let t = w / p.abs();
                s += if t > 1.0 {
                    1.0 / (w * (1.0 + 1.0 / (t * t)))
                } else {
                    t * t / (w * (1.0 + t * t))
                };
            }
            for q in &set.quad {
                let u = w / q.r;
                let sn2 = q.sn * q.sn;
                // ½ ln[(1 − u²)² + 4 sn² u²], derivative w.r.t. u, then ÷ r
                let du = if u <= 1.0 {
                    let f2 = (1.0 - u * u).powi(2) + 4.0 * sn2 * u * u;
                    (-2.0 * u * (1.0 - u * u) + 4.0 * sn2 * u) / f2
                } else {
                    let v = 1.0 / u;
                    let f2 = (v * v - 1.0).powi(2) + 4.0 * sn2 * v * v;
                    (2.0 * v - 2.0 * v * v * v + 4.0 * sn2 * v * v * v) / f2
                };
                s += du / q.r;
            }
            for &beta in &set.axis {
                // ln|1 − u²|, u = ω/β
                let u = w / beta;
                s += -2.0 * u / (1.0 - u * u) / beta;
            }
            d += sign * s;
        }
        d
    }

    /// Corner frequencies |p| of every non-zero reduced pole and zero (with repetition).
    pub fn corner_frequencies(&self) -> Vec<f64> {
        let mut out = Vec::new();
        for s in [&self.num, &self.den] {
            out.extend(s.real_p.iter().map(|p| p.abs()));
            out.extend(s.quad.iter().map(|q| q.r));
            out.extend(s.axis.iter().copied());
        }
        out
    }

    /// Lightly damped pairs (ζ < `zeta_max`, including undamped ones with ζ = 0) of the
    /// numerator and denominator, as (ωn, ζ).
    pub fn light_pairs(&self, zeta_max: f64) -> Vec<(f64, f64)> {
        let mut out = Vec::new();
        for s in [&self.num, &self.den] {
            out.extend(s.axis.iter().map(|&b| (b, 0.0)));
            out.extend(
                s.quad
                    .iter()
                    .map(|q| (q.r, q.sn.abs()))
                    .filter(|&(_, z)| z < zeta_max),
            );
        }
        out
    }

    /// The plotting range: two decades below the smallest corner frequency and above the
    /// largest, rounded out to whole decades; 0.01…100 rad/s without corners. Returned as
    /// (log₁₀ ω_min, log₁₀ ω_max).
    pub fn decade_range(&self) -> (f64, f64) {
        let c = self.corner_frequencies();
        let lo = c.iter().copied().reduce(f64::min);
        let hi = c.iter().copied().reduce(f64::max);
        match (lo, hi) {
            (Some(lo), Some(hi)) => (
                (lo.log10() - 2.0).floor().max(-300.0),
                (hi.log10() + 2.0).ceil().min(300.0),
            ),
            _ => (-2.0, 2.0),
        }
    }

    /// A dense sampling grid for bracketing: `per_decade` log-spaced points per decade over
    /// [`BodeForm::decade_range`] plus points around every lightly damped pair within a
    /// few bandwidths ζ·ωn of ωn. Sorted, unique, finite, positive.
    pub fn sampling_grid(&self, per_decade: usize) -> Vec<f64> {
        let (a, b) = self.decade_range();
        let n = ((b - a) * per_decade as f64).ceil().max(1.0) as usize;
        let mut xs: Vec<f64> = (0..=n)
            .map(|i| 10f64.powf(a + (b - a) * i as f64 / n as f64))
            .collect();
        for (wn, z) in self.light_pairs(0.5) {
            let z = z.max(1e-6);
            for k in -40..=40 {
                let x = wn * (1.0 + 0.25 * z * k as f64);
                if x > 0.0 {
                    xs.push(x);
                }
            }
        }
        xs.retain(|x| x.is_finite() && *x > 0.0);
        xs.sort_by(f64::total_cmp);
        xs.dedup();
        xs
    }

    /// G(jω) as a complex number (for tests and diagnostics).
    #[allow(dead_code)]
    pub fn complex(&self, w: f64) -> Complex64 {
        let e = self.eval(w);
        Complex64::from_polar(e.magnitude(), e.phase_rad())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tf(n: &[f64], d: &[f64]) -> TransferFunction {
        TransferFunction::from_descending(n, d).unwrap()
    }

    /// Both evaluation paths agree (fast path against the per-factor logarithmic path).
    #[test]
    fn fast_and_log_paths_agree() {
        let cases = [
            tf(&[1.0, -2.0, 5.0], &[1.0, 3.0, 7.0, 9.0, 4.0, 0.5]),
            tf(&[-3.0, 0.0], &[1.0, 0.2, 0.0, 4.0, 1.0, 0.0, 0.0]),
            tf(&[1.0, 0.0, 4.0], &[1.0, 1.0, 1.0, 1.0]),
            tf(&[2.0], &[1.0, -1.0, 10.0]),
        ];
        for g in &cases {
            let f = BodeForm::new(g).unwrap();
            for i in 0..400 {
                let w = 10f64.powf(-4.0 + 8.0 * i as f64 / 399.0);
                let a = f.eval_fast(w);
                let b = f.eval_log(w);
                assert!(
                    (a.ln_mag() - b.ln_mag()).abs() < 1e-12 * (1.0 + b.ln_mag().abs()),
                    "{g} at {w}: {} vs {}",
                    a.ln_mag(),
                    b.ln_mag()
                );
                assert!(
                    (a.phase_rad() - b.phase_rad()).abs() < 1e-12,
                    "{g} at {w}: {} vs {}",
                    a.phase_deg(),
                    b.phase_deg()
                );
            }
        }
    }

    #[test]
    #[allow(clippy::float_cmp)] // an underflow to exactly 0 is what is checked
    fn extreme_frequencies_do_not_overflow() {
        // order 40 with corners at 1: |G| ~ ω^-40 at ω = 1e100 is 1e-4000.
        let mut den = vec![1.0];
        for _ in 0..20 {
            let mut next = vec![0.0; den.len() + 2];
            for (i, &c) in den.iter().enumerate() {
                next[i] += c;
                next[i + 1] += 0.2 * c;
                next[i + 2] += c;
            }
            den = next;
        }
        let g = tf(&[1.0], &den);
        let r = g.freq_response(&[1e100, 1e-100, 1e300]).unwrap();
        assert!((r.magnitude_db[0] + 40.0 * 20.0 * 100.0).abs() < 1e-6);
        assert_eq!(r.magnitude[0], 0.0);
        assert!(r.magnitude_db[1].abs() < 1e-9);
        assert!((r.phase_deg[0] + 20.0 * 180.0).abs() < 1e-9);
        assert!((r.magnitude_db[2] + 40.0 * 20.0 * 300.0).abs() < 1e-6);
    }

    #[test]
    fn derivative_matches_finite_difference() {
        let g = tf(&[1.0, -2.0, 5.0], &[1.0, 3.0, 7.0, 9.0, 4.0, 0.5]);
        let f = BodeForm::new(&g).unwrap();
        for &w in &[0.01, 0.3, 1.0, 2.5, 40.0, 1e4] {
            let h = 1e-6 * w;
            let fd = (f.eval(w + h).ln_mag() - f.eval(w - h).ln_mag()) / (2.0 * h);
            let d = f.d_ln_mag(w);
            assert!((fd - d).abs() < 1e-6 * (1.0 + d.abs()), "{w}: {fd} vs {d}");
        }
    }

    use proptest::prelude::*;

    /// Random roots: real and complex pairs in both half planes (including light damping),
    /// magnitudes 10^[−2, 2], some repeated.
    fn roots(max: usize) -> impl Strategy<Value = Vec<Complex64>> {
        prop::collection::vec(
            (any::<bool>(), -2.0f64..2.0, -1.0f64..1.0, 0usize..4),
            0..=max,
        )
        .prop_map(|spec| {
            let mut out = Vec::new();
            for (pair, lm, c, rep) in spec {
                let m = 10f64.powf(lm);
                for _ in 0..if rep == 0 { 2 } else { 1 } {
                    if pair {
                        // c = cos of the angle from the negative real axis, signed
                        let re = -c * m;
                        let im = m * (1.0 - c * c).sqrt();
                        out.push(Complex64::new(re, im));
                        out.push(Complex64::new(re, -im));
                    } else {
                        out.push(Complex64::new(if c < 0.0 { m } else { -m }, 0.0));
                    }
                }
            }
            out
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 96, .. ProptestConfig::default() })]

        /// The branch tracking of the fast path (four lanes, crossing counts, half turns, one
        /// atan2) gives exactly the sum of the per-factor angles of the logarithmic path.
        #[test]
        fn fast_path_tracks_the_branch(z in roots(6), p in roots(12), int in -3i32..3) {
            let mut g = TransferFunction::from_zpk(&z, &p, -1.5).unwrap();
            let s = TransferFunction::s();
            for _ in 0..int.abs() {
                g = if int > 0 { &g * &s } else { &g * &s.inv().unwrap() };
            }
            let f = BodeForm::new(&g).unwrap();
            let mut w: Vec<f64> = (0..301).map(|i| 10f64.powf(-4.0 + 8.0 * i as f64 / 300.0)).collect();
            for c in f.corner_frequencies() {
                w.extend([c, c * (1.0 + 1e-9), c * (1.0 - 1e-9), c * 1.01, c * 0.99]);
            }
            let mut fast = Vec::new();
            let mut f2 = f.clone();
            f2.exact = None; // compare the factored paths themselves
            f2.eval_many(&w, |e| fast.push(e));
            for (i, &x) in w.iter().enumerate() {
                let l = f2.eval_log(x);
                let a = fast[i];
                if !(a.mant > 0.0 && a.mant.is_finite()) { continue; }
                prop_assert!((a.phase_rad() - l.phase_rad()).abs() < 1e-9,
                    "ω={} fast {} log {}", x, a.phase_deg(), l.phase_deg());
                prop_assert!((a.ln_mag() - l.ln_mag()).abs() < 1e-11 * (1.0 + l.ln_mag().abs()));
            }
        }
    }

    #[test]
    fn ill_conditioned_roots_fall_back_to_horner() {
        // (s + 1)^20 expanded: the companion eigenvalues scatter the 20-fold root by ~0.3
        let mut den = vec![1.0];
        for _ in 0..20 {
            let mut next = vec![0.0; den.len() + 1];
            for (i, &c) in den.iter().enumerate() {
                next[i] += c;
                next[i + 1] += c;
            }
            den = next;
        }
        let g = tf(&[1.0], &den);
        let f = BodeForm::new(&g).unwrap();
        assert!(f.uses_horner());
        for &w in &[0.01, 0.5, 1.0, 2.0, 100.0] {
            let e = f.eval(w);
            // |G| = (1 + ω²)^−10, φ = −20·atan ω (binomial coefficients ≤ 184756 are exact)
            let m = (1.0 + w * w).powi(-10);
            assert!(
                (e.magnitude() - m).abs() < 1e-12 * m,
                "{w}: {} vs {m}",
                e.magnitude()
            );
            assert!((e.phase_rad() + 20.0 * w.atan()).abs() < 1e-12);
        }
        // a healthy plant does not
        let g = tf(&[1.0, 2.0], &[1.0, 3.0, 7.0, 9.0, 4.0, 0.5]);
        assert!(!BodeForm::new(&g).unwrap().uses_horner());
    }

    #[test]
    fn bad_frequencies_are_rejected() {
        let g = tf(&[1.0], &[1.0, 1.0]);
        assert!(matches!(
            g.freq_response(&[1.0, f64::NAN]),
            Err(LtiError::NonFinite { .. })
        ));
        assert!(matches!(
            g.freq_response(&[-1.0]),
            Err(LtiError::InvalidParameter { .. })
        ));
        assert!(g.freq_response(&[f64::INFINITY]).is_err());
        assert!(g.freq_response(&[]).unwrap().w.is_empty());
    }
}
