//! The factored (Bode) form of a transfer function, shared by the frequency response, the
//! margins and the grids.

use std::f64::consts::{LN_2, TAU};

use super::factors::*;
use super::fastmath;
use super::horner::{AxisHorner, FACTORED_CHECK_TOL, wrap_pi};
use crate::analysis::factored::low_frequency::LowFrequency;
use crate::lti::TransferFunction;
use num_complex::Complex64;

use crate::poly::{HalfPlane, Root};

/// The factored (Bode) form of a reduced transfer function, precomputed for evaluation at
/// many frequencies. Shared by the frequency response, margins and grids.
#[derive(Debug, Clone)]
pub(crate) struct BodeForm {
    /// G ≡ 0.
    pub(super) zero: bool,
    /// |K| = k_mant·2^k_exp.
    pub(super) k_mant: f64,
    pub(super) k_exp: i32,
    /// ln|K|.
    pub(super) ln_k: f64,
    /// Quarter turns of the low-frequency asymptote: −2 for K < 0, plus k.
    pub(super) base_quarters: i64,
    /// Order k of (jω)^k (zeros at 0 minus poles at 0).
    pub(super) int_order: i32,
    pub(super) num: FactorSet,
    pub(super) den: FactorSet,
    /// Above this ω the logarithmic path is used.
    pub(super) fast_limit: f64,
    /// Set when the factored form does not reproduce the coefficients (roots too
    /// ill-conditioned, e.g. an expanded (s+1)^20): magnitude and principal phase then come
    /// from double-double Horner, the factored form only picks the branch.
    pub(super) exact: Option<Box<AxisHorner>>,
}

impl BodeForm {
    /// The evaluation form of a factored plant (G ≡ 0 when `zero`): K and k of the
    /// low-frequency asymptote `lf` (from the source: exact from coefficients), the reduced
    /// zeros and poles as real factors; for a plant given by coefficients, `coefficients` are
    /// (as given, reduced, cancelled roots) and the factors are checked against them
    /// ([`BodeForm::checked`]). `side` decides the half plane of each root (the factored
    /// form's decision: exact for coefficients typed as text).
    pub fn new(
        zero: bool,
        lf: LowFrequency,
        reduced_zeros: &[Root],
        reduced_poles: &[Root],
        coefficients: Option<(&TransferFunction, &TransferFunction, &[Root])>,
        side: &dyn Fn(Complex64) -> HalfPlane,
    ) -> BodeForm {
        if zero {
            return Self::zero_form();
        }
        let num = FactorSet::from_roots(reduced_zeros, side);
        let den = FactorSet::from_roots(reduced_poles, side);
        let rate = num.max_rate().max(den.max_rate());
        let fast_limit = if rate > 0.0 {
            FAST_FACTOR_LIMIT / rate
        } else {
            f64::INFINITY
        };
        let ka = lf.k.abs();
        let (k_mant, k_exp) = if ka.is_normal() {
            let e = exponent(ka);
            (ka * pow2(-e), e)
        } else {
            // the ratio under- or overflowed: rebuild it from logarithms
            let e = (lf.ln_abs / LN_2).floor();
            ((lf.ln_abs - e * LN_2).exp(), e as i32)
        };
        let form = BodeForm {
            zero: false,
            k_mant,
            k_exp,
            ln_k: lf.ln_abs,
            base_quarters: (if lf.sign < 0.0 { -2 } else { 0 }) + lf.int_order as i64,
            int_order: lf.int_order,
            num,
            den,
            fast_limit,
            exact: None,
        };
        match coefficients {
            Some((given, reduced, cancelled)) => form.checked(given, reduced, cancelled),
            None => form,
        }
    }

    /// Compares the factored form with double-double Horner on the coefficients *as given*
    /// at probe frequencies (the corner frequencies and a log grid); on disagreement beyond
    /// [`FACTORED_CHECK_TOL`] switches to Horner magnitudes and principal phases. (The reduced
    /// coefficients come from a division by the computed common factor and carry its error:
    /// they are only the reference within a relative 1e-6 of a cancelled root on the axis,
    /// where N and D both vanish.)
    pub(super) fn checked(
        mut self,
        given: &TransferFunction,
        reduced: &TransferFunction,
        cancelled: &[Root],
    ) -> BodeForm {
        let horner = AxisHorner::new(given, reduced, cancelled);
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

    /// Horner magnitude and principal phase on the branch of the factored phase `f`.
    #[cold]
    pub(super) fn refine(f: Eval, h: &AxisHorner, w: f64) -> Eval {
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
            let angle = fastmath::atan2(qi, qr);
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
    /// order; the fast path runs [`LANES`] frequencies side by side. (The frequency response
    /// itself uses the fused loop of `kernel`; this one checks the branch tracking in tests.)
    #[cfg(test)]
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lti::TransferFunction;
    use num_complex::Complex64;

    fn tf(n: &[f64], d: &[f64]) -> TransferFunction {
        TransferFunction::from_descending(n, d).unwrap()
    }

    fn form(g: &TransferFunction) -> BodeForm {
        g.factored().unwrap().bode().clone()
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
            let f = form(g);
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
        let f = form(&g);
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
            let f = form(&g);
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

    /// Expanded (s + 1)^k: binomial coefficients, exact for k ≤ 20.
    fn binomial_den(k: usize) -> Vec<f64> {
        let mut den = vec![1.0];
        for _ in 0..k {
            let mut next = vec![0.0; den.len() + 1];
            for (i, &c) in den.iter().enumerate() {
                next[i] += c;
                next[i + 1] += c;
            }
            den = next;
        }
        den
    }

    #[test]
    fn twenty_fold_pole_is_accurate() {
        // (s + 1)^20 expanded: the roots come back as one exact 20-fold pole, so the factored
        // form is used; |G| = (1 + ω²)^−10, φ = −20·atan ω.
        let g = tf(&[1.0], &binomial_den(20));
        let f = form(&g);
        for &w in &[0.01, 0.5, 1.0, 2.0, 100.0] {
            let e = f.eval(w);
            let m = (1.0 + w * w).powi(-10);
            assert!(
                (e.magnitude() - m).abs() < 1e-12 * m,
                "{w}: {} vs {m}",
                e.magnitude()
            );
            assert!((e.phase_rad() + 20.0 * w.atan()).abs() < 1e-12);
        }
    }

    #[test]
    fn ill_conditioned_roots_fall_back_to_horner() {
        // Wilkinson's polynomial Π(s + k), k = 1..20: the coefficients are not representable,
        // the roots are violently ill conditioned and do not reproduce the coefficients, so
        // magnitude and phase come from double-double Horner. Reference: f64 Horner on the same
        // coefficients, accurate here because on the imaginary axis |D(jω)| is within a factor
        // √2^20 of Σ|aᵢ|ωⁱ (every root is on the negative real axis).
        let mut den = vec![1.0];
        for k in 1..=20 {
            let mut next = vec![0.0; den.len() + 1];
            for (i, &c) in den.iter().enumerate() {
                next[i] += c;
                next[i + 1] += c * k as f64;
            }
            den = next;
        }
        let g = tf(&[1.0], &den);
        let f = form(&g);
        assert!(f.uses_horner());
        for &w in &[0.01, 1.0, 10.0, 100.0] {
            let e = f.eval(w);
            let d = g.den().eval_complex(num_complex::Complex64::new(0.0, w));
            let m = 1.0 / d.norm();
            assert!(
                (e.magnitude() - m).abs() < 1e-9 * m,
                "{w}: {} vs {m}",
                e.magnitude()
            );
        }
        // a healthy plant does not
        let g = tf(&[1.0, 2.0], &[1.0, 3.0, 7.0, 9.0, 4.0, 0.5]);
        assert!(!form(&g).uses_horner());
    }
}
