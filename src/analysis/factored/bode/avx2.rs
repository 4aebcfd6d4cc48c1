//! The fused product of [`super::kernel`] for four frequencies per AVX2 register, selected at
//! run time when the CPU has AVX2 (x86-64 only; elsewhere, or without AVX2, the portable
//! lane loop runs). The operations and their order are exactly those of the portable
//! `Products::mul_set` (no fused multiply-add, no reassociation), so both paths give
//! bitwise-identical products, turn counts and quarter turns — tested below.
//!
//! Only factor sets without imaginary-axis pairs come here (the caller checks); those, and
//! every lane whose product is not a normal number, go through the portable path.
//!
//! Length: the per-block loop is one function of ~130 lines on purpose — its state lives in
//! locals (registers) across the factor loop, and splitting it into calls measurably costs
//! throughput (the loop is latency-bound); the three loops mirror each other line by line,
//! which is what the bitwise-equality tests rely on.

// Compiled only where build.rs found rustc ≥ 1.89 (`cfg(ltikit_simd)`), whatever the crate's
// declared minimum: the intrinsics used here are stable from there on.
#![allow(clippy::incompatible_msrv)]

use std::arch::x86_64::*;

use super::factors::FactorSet;

/// Output of the vector product for 4 frequencies (one per lane).
pub(super) struct Product4 {
    pub(super) re: [f64; 4],
    pub(super) im: [f64; 4],
    /// Power of two moved out of the product minus that moved out of `d2`.
    pub(super) exp: [i64; 4],
    pub(super) turns: [i64; 4],
    pub(super) quarters: [i64; 4],
    /// Π|F_D|², in [1, 2) after each factor.
    pub(super) d2: [f64; 4],
}

/// True when the running CPU can take the AVX2 path.
pub(super) fn available() -> bool {
    is_x86_feature_detected!("avx2")
}

struct State {
    re: __m256d,
    im: __m256d,
    exp: __m256i,
    /// all-ones where the argument is in (0, π]
    upper: __m256d,
    turns: __m256d,
    quarters: __m256d,
    d2: __m256d,
}

/// |x| (clears the sign bit).
#[inline]
#[target_feature(enable = "avx2")]
fn abs(x: __m256d) -> __m256d {
    _mm256_andnot_pd(_mm256_set1_pd(-0.0), x)
}

/// Biased exponent field of each lane (as i64).
#[inline]
#[target_feature(enable = "avx2")]
fn biased_exponent(m: __m256d) -> __m256i {
    _mm256_and_si256(
        _mm256_srli_epi64::<52>(_mm256_castpd_si256(m)),
        _mm256_set1_epi64x(0x7ff),
    )
}

/// For a positive magnitude m: (2^−e, e) with e = its binary exponent clamped to
/// [−1022, 1022], as `factors::exponent` and `pow2` do it.
#[inline]
#[target_feature(enable = "avx2")]
fn scale_of(m: __m256d) -> (__m256d, __m256i) {
    let e = _mm256_sub_epi64(biased_exponent(m), _mm256_set1_epi64x(1023));
    // clamp to [−1022, 1022] (only subnormals or zero fall below, nothing reaches above)
    let lo = _mm256_set1_epi64x(-1022);
    let hi = _mm256_set1_epi64x(1022);
    let e = _mm256_blendv_epi8(e, lo, _mm256_cmpgt_epi64(lo, e));
    let e = _mm256_blendv_epi8(e, hi, _mm256_cmpgt_epi64(e, hi));
    // 2^−e: biased exponent 1023 − e
    let s = _mm256_slli_epi64::<52>(_mm256_sub_epi64(_mm256_set1_epi64x(1023), e));
    (_mm256_castsi256_pd(s), e)
}

impl State {
    #[inline]
    #[target_feature(enable = "avx2")]
    fn new() -> State {
        State {
            re: _mm256_set1_pd(1.0),
            im: _mm256_setzero_pd(),
            exp: _mm256_setzero_si256(),
            upper: _mm256_setzero_pd(),
            turns: _mm256_setzero_pd(),
            quarters: _mm256_setzero_pd(),
            d2: _mm256_set1_pd(1.0),
        }
    }

    /// Multiplies by (fr + j·fi) with fr ≥ 0, counting crossings of the negative real axis
    /// (see `Products::mul`).
    #[inline]
    #[target_feature(enable = "avx2")]
    fn mul(&mut self, fr: __m256d, fi: __m256d) {
        let (re, im) = (self.re, self.im);
        let nr = _mm256_sub_pd(_mm256_mul_pd(re, fr), _mm256_mul_pd(im, fi));
        let ni = _mm256_add_pd(_mm256_mul_pd(re, fi), _mm256_mul_pd(im, fr));
        let zero = _mm256_setzero_pd();
        let nup = _mm256_or_pd(
            _mm256_cmp_pd::<_CMP_GT_OQ>(ni, zero),
            _mm256_and_pd(
                _mm256_cmp_pd::<_CMP_EQ_OQ>(ni, zero),
                _mm256_cmp_pd::<_CMP_LT_OQ>(nr, zero),
            ),
        );
        let re_nearer = _mm256_cmp_pd::<_CMP_GE_OQ>(abs(re), abs(im));
        let s = _mm256_blendv_pd(nr, re, re_nearer);
        let cross = _mm256_and_pd(
            _mm256_xor_pd(nup, self.upper),
            _mm256_cmp_pd::<_CMP_LT_OQ>(s, zero),
        );
        // +1 leaving the upper half plane, −1 entering it
        let dir = _mm256_blendv_pd(_mm256_set1_pd(-1.0), _mm256_set1_pd(1.0), self.upper);
        self.turns = _mm256_add_pd(self.turns, _mm256_and_pd(cross, dir));
        self.re = nr;
        self.im = ni;
        self.upper = nup;
    }

    /// d2 ← d2·(fr² + fi²), renormalised (see `Products::div_norm2`).
    #[inline]
    #[target_feature(enable = "avx2")]
    fn div_norm2(&mut self, fr: __m256d, fi: __m256d) {
        let d = _mm256_mul_pd(
            self.d2,
            _mm256_add_pd(_mm256_mul_pd(fr, fr), _mm256_mul_pd(fi, fi)),
        );
        let (s, e) = scale_of(d);
        self.d2 = _mm256_mul_pd(d, s);
        self.exp = _mm256_sub_epi64(self.exp, e);
    }

    #[inline]
    #[target_feature(enable = "avx2")]
    fn rescale(&mut self) {
        let (s, e) = scale_of(_mm256_max_pd(abs(self.re), abs(self.im)));
        self.re = _mm256_mul_pd(self.re, s);
        self.im = _mm256_mul_pd(self.im, s);
        self.exp = _mm256_add_epi64(self.exp, e);
    }

    #[inline]
    #[target_feature(enable = "avx2")]
    fn mul_set(&mut self, s: &FactorSet, w: __m256d, w2: __m256d, conj: bool) {
        let sign = if conj { -1.0 } else { 1.0 };
        let one = _mm256_set1_pd(1.0);
        let neg_zero = _mm256_set1_pd(-0.0);
        for chunk in s.real_c.chunks(4) {
            for &c in chunk {
                let fi = _mm256_mul_pd(_mm256_set1_pd(sign * c), w);
                self.mul(one, fi);
                if conj {
                    self.div_norm2(one, fi);
                }
            }
            self.rescale();
        }
        for chunk in s.quad.chunks(4) {
            for q in chunk {
                let x = _mm256_sub_pd(one, _mm256_mul_pd(_mm256_set1_pd(q.a), w2));
                let y = _mm256_mul_pd(_mm256_set1_pd(sign * q.b), w);
                let neg = _mm256_cmp_pd::<_CMP_LT_OQ>(x, _mm256_setzero_pd());
                let half = if conj { -2.0 } else { 2.0 } * q.sb as f64;
                self.quarters =
                    _mm256_add_pd(self.quarters, _mm256_and_pd(neg, _mm256_set1_pd(half)));
                // negate both parts where x < 0 (flip the sign bits)
                let flip = _mm256_and_pd(neg, neg_zero);
                self.mul(_mm256_xor_pd(x, flip), _mm256_xor_pd(y, flip));
                if conj {
                    self.div_norm2(x, y);
                }
            }
            self.rescale();
        }
    }
}

/// The four lanes of a vector.
#[inline]
#[target_feature(enable = "avx2")]
pub(super) fn lanes(v: __m256d) -> [f64; 4] {
    let lo = _mm256_castpd256_pd128(v);
    let hi = _mm256_extractf128_pd::<1>(v);
    [
        _mm_cvtsd_f64(lo),
        _mm_cvtsd_f64(_mm_unpackhi_pd(lo, lo)),
        _mm_cvtsd_f64(hi),
        _mm_cvtsd_f64(_mm_unpackhi_pd(hi, hi)),
    ]
}

/// The fused product G(jω)/(K·(jω)^k) = Π F_N · Π conj(F_D) / Π|F_D|² at four frequencies,
/// for factor sets without imaginary-axis pairs. Callable only where AVX2 is available
/// ([`available`]).
#[target_feature(enable = "avx2")]
pub(super) fn product4(num: &FactorSet, den: &FactorSet, w: &[f64; 4]) -> Product4 {
    let wv = _mm256_set_pd(w[3], w[2], w[1], w[0]);
    let w2 = _mm256_mul_pd(wv, wv);
    let mut st = State::new();
    st.mul_set(num, wv, w2, false);
    st.mul_set(den, wv, w2, true);
    st.rescale();
    let (turns, quarters) = (lanes(st.turns), lanes(st.quarters));
    Product4 {
        re: lanes(st.re),
        im: lanes(st.im),
        exp: [
            _mm256_extract_epi64::<0>(st.exp),
            _mm256_extract_epi64::<1>(st.exp),
            _mm256_extract_epi64::<2>(st.exp),
            _mm256_extract_epi64::<3>(st.exp),
        ],
        turns: turns.map(|t| t as i64),
        quarters: quarters.map(|q| q as i64),
        d2: lanes(st.d2),
    }
}

/// |G|, dB and phase (degrees) of four frequencies, and which lanes are valid (a lane whose
/// product is not a normal number, or whose magnitude needs the saturating path, must be
/// redone by the caller).
pub(super) struct Response4 {
    pub(super) magnitude: [f64; 4],
    pub(super) magnitude_db: [f64; 4],
    pub(super) phase_deg: [f64; 4],
    pub(super) valid: [bool; 4],
}

/// i64 lanes (|k| < 2^51) to f64, exactly.
#[inline]
#[target_feature(enable = "avx2")]
fn i64_to_f64(k: __m256i) -> __m256d {
    const MAGIC: f64 = 6_755_399_441_055_744.0; // 1.5·2^52
    let bits = _mm256_add_epi64(k, _mm256_castpd_si256(_mm256_set1_pd(MAGIC)));
    _mm256_sub_pd(_mm256_castsi256_pd(bits), _mm256_set1_pd(MAGIC))
}

/// `fastmath::atan2` for lanes with finite (y, x) not both zero, same operations.
#[inline]
#[target_feature(enable = "avx2")]
fn atan2(y: __m256d, x: __m256d) -> __m256d {
    use super::fastmath::{AT, ATANHI, ATANLO, PI_LO};
    let zero = _mm256_setzero_pd();
    let one = _mm256_set1_pd(1.0);
    let (ax, ay) = (abs(x), abs(y));
    let r = _mm256_div_pd(ay, ax);
    // argument reduction of atan(r), r ≥ 0: t = num/den by range
    let lt = |v: f64| _mm256_cmp_pd::<_CMP_LT_OQ>(r, _mm256_set1_pd(v));
    let (r0, r1, r2, r3) = (lt(0.4375), lt(0.6875), lt(1.1875), lt(2.4375));
    let two_r = _mm256_mul_pd(_mm256_set1_pd(2.0), r);
    // from the top range down, so the smallest matching range wins
    let mut num = _mm256_set1_pd(-1.0);
    let mut den = r;
    let mut hi = _mm256_set1_pd(ATANHI[3]);
    let mut lo = _mm256_set1_pd(ATANLO[3]);
    let pick = |m: __m256d, a: __m256d, b: __m256d| _mm256_blendv_pd(a, b, m);
    num = pick(r3, num, _mm256_sub_pd(r, _mm256_set1_pd(1.5)));
    den = pick(
        r3,
        den,
        _mm256_add_pd(one, _mm256_mul_pd(_mm256_set1_pd(1.5), r)),
    );
    hi = pick(r3, hi, _mm256_set1_pd(ATANHI[2]));
    lo = pick(r3, lo, _mm256_set1_pd(ATANLO[2]));
    num = pick(r2, num, _mm256_sub_pd(r, one));
    den = pick(r2, den, _mm256_add_pd(r, one));
    hi = pick(r2, hi, _mm256_set1_pd(ATANHI[1]));
    lo = pick(r2, lo, _mm256_set1_pd(ATANLO[1]));
    num = pick(r1, num, _mm256_sub_pd(two_r, one));
    den = pick(r1, den, _mm256_add_pd(_mm256_set1_pd(2.0), r));
    hi = pick(r1, hi, _mm256_set1_pd(ATANHI[0]));
    lo = pick(r1, lo, _mm256_set1_pd(ATANLO[0]));
    num = pick(r0, num, r);
    den = pick(r0, den, one);
    let t = _mm256_div_pd(num, den);
    let z = _mm256_mul_pd(t, t);
    let w = _mm256_mul_pd(z, z);
    let c = |k: usize| _mm256_set1_pd(AT[k]);
    let madd = |a: __m256d, b: __m256d, acc: __m256d| _mm256_add_pd(a, _mm256_mul_pd(b, acc));
    // s1 = z·(AT0 + w·(AT2 + w·(AT4 + w·(AT6 + w·(AT8 + w·AT10)))))
    let s1 = _mm256_mul_pd(
        z,
        madd(
            c(0),
            w,
            madd(c(2), w, madd(c(4), w, madd(c(6), w, madd(c(8), w, c(10))))),
        ),
    );
    // s2 = w·(AT1 + w·(AT3 + w·(AT5 + w·(AT7 + w·AT9))))
    let s2 = _mm256_mul_pd(
        w,
        madd(c(1), w, madd(c(3), w, madd(c(5), w, madd(c(7), w, c(9))))),
    );
    let ts = _mm256_mul_pd(t, _mm256_add_pd(s1, s2));
    let small = _mm256_sub_pd(t, ts);
    let reduced = _mm256_sub_pd(hi, _mm256_sub_pd(_mm256_sub_pd(ts, lo), t));
    let mut zr = _mm256_blendv_pd(reduced, small, r0);
    // r = ∞ (ax = 0, or overflow): π/2; r = 0 (ay = 0, or underflow): 0
    let inf = _mm256_cmp_pd::<_CMP_EQ_OQ>(r, _mm256_set1_pd(f64::INFINITY));
    zr = _mm256_blendv_pd(zr, _mm256_set1_pd(std::f64::consts::FRAC_PI_2), inf);
    zr = _mm256_blendv_pd(zr, zero, _mm256_cmp_pd::<_CMP_EQ_OQ>(r, zero));
    // x < 0: π − (z − π_lo), or π exactly on the negative real axis
    let xneg = _mm256_cmp_pd::<_CMP_LT_OQ>(x, zero);
    let pi = _mm256_set1_pd(std::f64::consts::PI);
    let left = _mm256_sub_pd(pi, _mm256_sub_pd(zr, _mm256_set1_pd(PI_LO)));
    let on_axis = _mm256_and_pd(
        _mm256_cmp_pd::<_CMP_EQ_OQ>(zr, zero),
        _mm256_cmp_pd::<_CMP_EQ_OQ>(ay, zero),
    );
    let left = _mm256_blendv_pd(left, pi, on_axis);
    let a = _mm256_blendv_pd(zr, left, xneg);
    // the sign of y
    _mm256_xor_pd(a, _mm256_and_pd(y, _mm256_set1_pd(-0.0)))
}

/// `fastmath::ln` for lanes holding positive normal numbers, same operations.
#[inline]
#[target_feature(enable = "avx2")]
fn ln(x: __m256d) -> __m256d {
    use super::fastmath::{LG, LN2_HI, LN2_LO};
    let bits = _mm256_castpd_si256(x);
    let k = _mm256_sub_epi64(biased_exponent(x), _mm256_set1_epi64x(1023));
    let m = _mm256_and_si256(bits, _mm256_set1_epi64x(0x000f_ffff_ffff_ffff));
    // 1 + f in [√2/2, √2): mantissas at or above √2's go one binade down
    let high = _mm256_cmpgt_epi64(m, _mm256_set1_epi64x(0x0006_a09e_667f_3bcc));
    let k = _mm256_sub_epi64(k, high); // high is −1 where set
    let expo = _mm256_blendv_epi8(
        _mm256_set1_epi64x(0x3ff0_0000_0000_0000),
        _mm256_set1_epi64x(0x3fe0_0000_0000_0000),
        high,
    );
    let f = _mm256_sub_pd(
        _mm256_castsi256_pd(_mm256_or_si256(m, expo)),
        _mm256_set1_pd(1.0),
    );
    let dk = i64_to_f64(k);
    let hfsq = _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(0.5), f), f);
    let s = _mm256_div_pd(f, _mm256_add_pd(_mm256_set1_pd(2.0), f));
    let z = _mm256_mul_pd(s, s);
    let w = _mm256_mul_pd(z, z);
    let c = |k: usize| _mm256_set1_pd(LG[k]);
    let madd = |a: __m256d, b: __m256d, acc: __m256d| _mm256_add_pd(a, _mm256_mul_pd(b, acc));
    let t1 = _mm256_mul_pd(w, madd(c(1), w, madd(c(3), w, c(5))));
    let t2 = _mm256_mul_pd(z, madd(c(0), w, madd(c(2), w, madd(c(4), w, c(6)))));
    let r = _mm256_add_pd(t2, t1);
    // dk·ln2_hi − ((hfsq − (s·(hfsq + r) + dk·ln2_lo)) − f)
    let inner = _mm256_add_pd(
        _mm256_mul_pd(s, _mm256_add_pd(hfsq, r)),
        _mm256_mul_pd(dk, _mm256_set1_pd(LN2_LO)),
    );
    _mm256_sub_pd(
        _mm256_mul_pd(dk, _mm256_set1_pd(LN2_HI)),
        _mm256_sub_pd(_mm256_sub_pd(hfsq, inner), f),
    )
}

/// Groups of four frequencies interleaved by [`response8`] (its state is kept in locals, so
/// it stays in registers).
pub(super) const G: usize = 2;

/// The whole fast path for eight frequencies of a G without integrators or differentiators
/// (k = 0) and without imaginary-axis pairs: the product of [`product4`] for two groups of
/// four frequencies whose independent dependency chains interleave (one group alone is
/// latency-bound), then magnitude, dB and phase exactly as `BodeForm::finish` and
/// `kernel::store` compute them. `k_mant·2^k_exp` = |K|; `base_quarters` the quarter turns
/// of K. Same operations in the same order as [`State`]'s methods.
///
/// Longer than our ~120-line rule on purpose: one function, so that the compiler keeps the
/// two interleaved groups in registers across the whole sweep (the reason for the kernel).
#[target_feature(enable = "avx2")]
#[allow(clippy::needless_range_loop)] // g indexes the parallel per-group locals
pub(super) fn response8(
    num: &FactorSet,
    den: &FactorSet,
    w: &[f64; 4 * G],
    k_mant: f64,
    k_exp: i32,
    base_quarters: i64,
) -> [Response4; G] {
    let wv: [__m256d; G] =
        std::array::from_fn(|g| _mm256_set_pd(w[4 * g + 3], w[4 * g + 2], w[4 * g + 1], w[4 * g]));
    let w2: [__m256d; G] = std::array::from_fn(|g| _mm256_mul_pd(wv[g], wv[g]));
    let zero = _mm256_setzero_pd();
    let one = _mm256_set1_pd(1.0);
    let neg_zero = _mm256_set1_pd(-0.0);
    let mut re = [one; G];
    let mut im = [zero; G];
    let mut exp = [_mm256_setzero_si256(); G];
    let mut upper = [zero; G];
    let mut turns = [zero; G];
    let mut quarters = [zero; G];
    let mut d2 = [one; G];
    // State::mul
    macro_rules! mul {
        ($g:expr, $fr:expr, $fi:expr) => {{
            let g = $g;
            let (fr, fi) = ($fr, $fi);
            let (r, i) = (re[g], im[g]);
            let nr = _mm256_sub_pd(_mm256_mul_pd(r, fr), _mm256_mul_pd(i, fi));
            let ni = _mm256_add_pd(_mm256_mul_pd(r, fi), _mm256_mul_pd(i, fr));
            let nup = _mm256_or_pd(
                _mm256_cmp_pd::<_CMP_GT_OQ>(ni, zero),
                _mm256_and_pd(
                    _mm256_cmp_pd::<_CMP_EQ_OQ>(ni, zero),
                    _mm256_cmp_pd::<_CMP_LT_OQ>(nr, zero),
                ),
            );
            let re_nearer = _mm256_cmp_pd::<_CMP_GE_OQ>(abs(r), abs(i));
            let sx = _mm256_blendv_pd(nr, r, re_nearer);
            let cross = _mm256_and_pd(
                _mm256_xor_pd(nup, upper[g]),
                _mm256_cmp_pd::<_CMP_LT_OQ>(sx, zero),
            );
            let dir = _mm256_blendv_pd(_mm256_set1_pd(-1.0), one, upper[g]);
            turns[g] = _mm256_add_pd(turns[g], _mm256_and_pd(cross, dir));
            re[g] = nr;
            im[g] = ni;
            upper[g] = nup;
        }};
    }
    // State::div_norm2
    macro_rules! div_norm2 {
        ($g:expr, $fr:expr, $fi:expr) => {{
            let g = $g;
            let (fr, fi) = ($fr, $fi);
            let d = _mm256_mul_pd(
                d2[g],
                _mm256_add_pd(_mm256_mul_pd(fr, fr), _mm256_mul_pd(fi, fi)),
            );
            let (sc, e) = scale_of(d);
            d2[g] = _mm256_mul_pd(d, sc);
            exp[g] = _mm256_sub_epi64(exp[g], e);
        }};
    }
    // State::rescale
    macro_rules! rescale {
        () => {{
            for g in 0..G {
                let (sc, e) = scale_of(_mm256_max_pd(abs(re[g]), abs(im[g])));
                re[g] = _mm256_mul_pd(re[g], sc);
                im[g] = _mm256_mul_pd(im[g], sc);
                exp[g] = _mm256_add_epi64(exp[g], e);
            }
        }};
    }
    for (set, conj) in [(num, false), (den, true)] {
        let sign = if conj { -1.0 } else { 1.0 };
        for chunk in set.real_c.chunks(4) {
            for &c in chunk {
                let sc = _mm256_set1_pd(sign * c);
                for g in 0..G {
                    let fi = _mm256_mul_pd(sc, wv[g]);
                    mul!(g, one, fi);
                    if conj {
                        div_norm2!(g, one, fi);
                    }
                }
            }
            rescale!();
        }
        for chunk in set.quad.chunks(4) {
            for q in chunk {
                let (a, b) = (_mm256_set1_pd(q.a), _mm256_set1_pd(sign * q.b));
                let half = _mm256_set1_pd(if conj { -2.0 } else { 2.0 } * q.sb as f64);
                for g in 0..G {
                    let x = _mm256_sub_pd(one, _mm256_mul_pd(a, w2[g]));
                    let y = _mm256_mul_pd(b, wv[g]);
                    let neg = _mm256_cmp_pd::<_CMP_LT_OQ>(x, zero);
                    quarters[g] = _mm256_add_pd(quarters[g], _mm256_and_pd(neg, half));
                    let flip = _mm256_and_pd(neg, neg_zero);
                    mul!(g, _mm256_xor_pd(x, flip), _mm256_xor_pd(y, flip));
                    if conj {
                        div_norm2!(g, x, y);
                    }
                }
            }
            rescale!();
        }
    }
    rescale!();
    std::array::from_fn(|g| {
        finish4(
            &State {
                re: re[g],
                im: im[g],
                exp: exp[g],
                upper: upper[g],
                turns: turns[g],
                quarters: quarters[g],
                d2: d2[g],
            },
            k_mant,
            k_exp,
            base_quarters,
        )
    })
}

/// Magnitude, dB and phase of four finished products.
#[inline]
#[target_feature(enable = "avx2")]
fn finish4(st: &State, k_mant: f64, k_exp: i32, base_quarters: i64) -> Response4 {
    let (re, im) = (st.re, st.im);
    let zero = _mm256_setzero_pd();
    let finite = _mm256_and_pd(
        _mm256_cmp_pd::<_CMP_LT_OQ>(abs(re), _mm256_set1_pd(f64::INFINITY)),
        _mm256_cmp_pd::<_CMP_LT_OQ>(abs(im), _mm256_set1_pd(f64::INFINITY)),
    );
    let nonzero = _mm256_or_pd(
        _mm256_cmp_pd::<_CMP_NEQ_OQ>(re, zero),
        _mm256_cmp_pd::<_CMP_NEQ_OQ>(im, zero),
    );
    // −0 imaginary parts to +0: the negative real axis counts as +π (see `BodeForm::finish`)
    let angle = atan2(_mm256_add_pd(im, zero), re);
    let mant = _mm256_div_pd(
        _mm256_mul_pd(
            _mm256_set1_pd(k_mant),
            _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(re, re), _mm256_mul_pd(im, im))),
        ),
        st.d2,
    );
    let exp2 = _mm256_add_epi64(st.exp, _mm256_set1_epi64x(k_exp as i64));
    let in_range = _mm256_andnot_si256(
        _mm256_or_si256(
            _mm256_cmpgt_epi64(exp2, _mm256_set1_epi64x(1000)),
            _mm256_cmpgt_epi64(_mm256_set1_epi64x(-1000), exp2),
        ),
        _mm256_set1_epi64x(-1),
    );
    let scale = _mm256_castsi256_pd(_mm256_slli_epi64::<52>(_mm256_add_epi64(
        exp2,
        _mm256_set1_epi64x(1023),
    )));
    let magnitude = _mm256_mul_pd(mant, scale);
    const DB_PER_NEPER: f64 = 20.0 * std::f64::consts::LOG10_E;
    let magnitude_db = _mm256_mul_pd(
        _mm256_set1_pd(DB_PER_NEPER),
        _mm256_add_pd(
            ln(mant),
            _mm256_mul_pd(_mm256_set1_pd(std::f64::consts::LN_2), i64_to_f64(exp2)),
        ),
    );
    // quarter turns: base + 4·turns + quarters (small integers, exact in f64)
    let quarters = _mm256_add_pd(
        _mm256_add_pd(
            _mm256_set1_pd(base_quarters as f64),
            _mm256_mul_pd(_mm256_set1_pd(4.0), st.turns),
        ),
        st.quarters,
    );
    let phase_deg = _mm256_add_pd(
        _mm256_mul_pd(angle, _mm256_set1_pd(180.0f64 / std::f64::consts::PI)),
        _mm256_mul_pd(_mm256_set1_pd(90.0), quarters),
    );
    let valid = lanes(_mm256_and_pd(
        _mm256_and_pd(finite, nonzero),
        _mm256_castsi256_pd(in_range),
    ));
    Response4 {
        magnitude: lanes(magnitude),
        magnitude_db: lanes(magnitude_db),
        phase_deg: lanes(phase_deg),
        valid: valid.map(|v| v.to_bits() != 0),
    }
}
