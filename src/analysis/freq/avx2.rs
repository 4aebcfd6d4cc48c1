//! The fused product of [`super::kernel`] for four frequencies per AVX2 register, selected at
//! run time when the CPU has AVX2 (x86-64 only; elsewhere, or without AVX2, the portable
//! lane loop runs). The operations and their order are exactly those of the portable
//! `Products::mul_set` (no fused multiply-add, no reassociation), so both paths give
//! bitwise-identical products, turn counts and quarter turns — tested below.
//!
//! Only factor sets without imaginary-axis pairs come here (the caller checks); those, and
//! every lane whose product is not a normal number, go through the portable path.

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
fn lanes(v: __m256d) -> [f64; 4] {
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
    let mut st = State {
        re: _mm256_set1_pd(1.0),
        im: _mm256_setzero_pd(),
        exp: _mm256_setzero_si256(),
        upper: _mm256_setzero_pd(),
        turns: _mm256_setzero_pd(),
        quarters: _mm256_setzero_pd(),
        d2: _mm256_set1_pd(1.0),
    };
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
