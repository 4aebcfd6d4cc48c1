//! [`super::avx2::response8`] with eight frequencies per AVX-512 register (two groups
//! interleaved: sixteen per call), selected at run time where the CPU has AVX-512F. Same
//! operations in the same order as the portable lane loop and the AVX2 path (no fused
//! multiply-add, no reassociation; masks where AVX2 blends), so all three give bitwise the
//! same values — tested in `kernel`.
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

/// Frequencies per call.
pub(super) const WIDTH: usize = 8 * G;

/// Groups of eight frequencies interleaved per call.
const G: usize = 2;

/// True when the running CPU can take the AVX-512 path.
pub(super) fn available() -> bool {
    is_x86_feature_detected!("avx512f")
}

/// |G|, dB and phase (degrees) of eight frequencies and which lanes are valid (see
/// `avx2::Response4`).
pub(super) struct Response8 {
    pub(super) magnitude: [f64; 8],
    pub(super) magnitude_db: [f64; 8],
    pub(super) phase_deg: [f64; 8],
    pub(super) valid: [bool; 8],
}

#[inline]
#[target_feature(enable = "avx512f")]
fn cast(x: __m512d) -> __m512i {
    _mm512_castpd_si512(x)
}

#[inline]
#[target_feature(enable = "avx512f")]
fn uncast(x: __m512i) -> __m512d {
    _mm512_castsi512_pd(x)
}

/// −x by flipping the sign bit where `m` is set (as the scalar `-x`, −0 included).
#[inline]
#[target_feature(enable = "avx512f")]
fn neg_where(m: __mmask8, x: __m512d) -> __m512d {
    uncast(_mm512_mask_xor_epi64(
        cast(x),
        m,
        cast(x),
        _mm512_set1_epi64(i64::MIN),
    ))
}

/// Biased exponent field of each lane.
#[inline]
#[target_feature(enable = "avx512f")]
fn biased_exponent(m: __m512d) -> __m512i {
    _mm512_and_si512(_mm512_srli_epi64::<52>(cast(m)), _mm512_set1_epi64(0x7ff))
}

/// (2^−e, e) with e the binary exponent clamped to [−1022, 1022] (`factors::exponent`).
#[inline]
#[target_feature(enable = "avx512f")]
fn scale_of(m: __m512d) -> (__m512d, __m512i) {
    let e = _mm512_sub_epi64(biased_exponent(m), _mm512_set1_epi64(1023));
    let e = _mm512_min_epi64(
        _mm512_max_epi64(e, _mm512_set1_epi64(-1022)),
        _mm512_set1_epi64(1022),
    );
    let s = _mm512_slli_epi64::<52>(_mm512_sub_epi64(_mm512_set1_epi64(1023), e));
    (uncast(s), e)
}

/// i64 lanes (|k| < 2^51) to f64, exactly (as `avx2::i64_to_f64`).
#[inline]
#[target_feature(enable = "avx512f")]
fn i64_to_f64(k: __m512i) -> __m512d {
    const MAGIC: f64 = 6_755_399_441_055_744.0; // 1.5·2^52
    let bits = _mm512_add_epi64(k, cast(_mm512_set1_pd(MAGIC)));
    _mm512_sub_pd(uncast(bits), _mm512_set1_pd(MAGIC))
}

/// `fastmath::atan2` for lanes with finite (y, x) not both zero, same operations.
#[inline]
#[target_feature(enable = "avx512f")]
fn atan2(y: __m512d, x: __m512d) -> __m512d {
    use super::fastmath::{AT, ATANHI, ATANLO, PI_LO};
    let zero = _mm512_setzero_pd();
    let one = _mm512_set1_pd(1.0);
    let (ax, ay) = (_mm512_abs_pd(x), _mm512_abs_pd(y));
    let r = _mm512_div_pd(ay, ax);
    let lt = |v: f64| _mm512_cmp_pd_mask::<_CMP_LT_OQ>(r, _mm512_set1_pd(v));
    let (r0, r1, r2, r3) = (lt(0.4375), lt(0.6875), lt(1.1875), lt(2.4375));
    let two_r = _mm512_mul_pd(_mm512_set1_pd(2.0), r);
    let mut num = _mm512_set1_pd(-1.0);
    let mut den = r;
    let mut hi = _mm512_set1_pd(ATANHI[3]);
    let mut lo = _mm512_set1_pd(ATANLO[3]);
    num = _mm512_mask_blend_pd(r3, num, _mm512_sub_pd(r, _mm512_set1_pd(1.5)));
    den = _mm512_mask_blend_pd(
        r3,
        den,
        _mm512_add_pd(one, _mm512_mul_pd(_mm512_set1_pd(1.5), r)),
    );
    hi = _mm512_mask_blend_pd(r3, hi, _mm512_set1_pd(ATANHI[2]));
    lo = _mm512_mask_blend_pd(r3, lo, _mm512_set1_pd(ATANLO[2]));
    num = _mm512_mask_blend_pd(r2, num, _mm512_sub_pd(r, one));
    den = _mm512_mask_blend_pd(r2, den, _mm512_add_pd(r, one));
    hi = _mm512_mask_blend_pd(r2, hi, _mm512_set1_pd(ATANHI[1]));
    lo = _mm512_mask_blend_pd(r2, lo, _mm512_set1_pd(ATANLO[1]));
    num = _mm512_mask_blend_pd(r1, num, _mm512_sub_pd(two_r, one));
    den = _mm512_mask_blend_pd(r1, den, _mm512_add_pd(_mm512_set1_pd(2.0), r));
    hi = _mm512_mask_blend_pd(r1, hi, _mm512_set1_pd(ATANHI[0]));
    lo = _mm512_mask_blend_pd(r1, lo, _mm512_set1_pd(ATANLO[0]));
    num = _mm512_mask_blend_pd(r0, num, r);
    den = _mm512_mask_blend_pd(r0, den, one);
    let t = _mm512_div_pd(num, den);
    let z = _mm512_mul_pd(t, t);
    let w = _mm512_mul_pd(z, z);
    let c = |k: usize| _mm512_set1_pd(AT[k]);
    let madd = |a: __m512d, b: __m512d, acc: __m512d| _mm512_add_pd(a, _mm512_mul_pd(b, acc));
    let s1 = _mm512_mul_pd(
        z,
        madd(
            c(0),
            w,
            madd(c(2), w, madd(c(4), w, madd(c(6), w, madd(c(8), w, c(10))))),
        ),
    );
    let s2 = _mm512_mul_pd(
        w,
        madd(c(1), w, madd(c(3), w, madd(c(5), w, madd(c(7), w, c(9))))),
    );
    let ts = _mm512_mul_pd(t, _mm512_add_pd(s1, s2));
    let small = _mm512_sub_pd(t, ts);
    let reduced = _mm512_sub_pd(hi, _mm512_sub_pd(_mm512_sub_pd(ts, lo), t));
    let mut zr = _mm512_mask_blend_pd(r0, reduced, small);
    let inf = _mm512_cmp_pd_mask::<_CMP_EQ_OQ>(r, _mm512_set1_pd(f64::INFINITY));
    zr = _mm512_mask_blend_pd(inf, zr, _mm512_set1_pd(std::f64::consts::FRAC_PI_2));
    zr = _mm512_mask_blend_pd(_mm512_cmp_pd_mask::<_CMP_EQ_OQ>(r, zero), zr, zero);
    let xneg = _mm512_cmp_pd_mask::<_CMP_LT_OQ>(x, zero);
    let pi = _mm512_set1_pd(std::f64::consts::PI);
    let left = _mm512_sub_pd(pi, _mm512_sub_pd(zr, _mm512_set1_pd(PI_LO)));
    let on_axis =
        _mm512_cmp_pd_mask::<_CMP_EQ_OQ>(zr, zero) & _mm512_cmp_pd_mask::<_CMP_EQ_OQ>(ay, zero);
    let left = _mm512_mask_blend_pd(on_axis, left, pi);
    let a = _mm512_mask_blend_pd(xneg, zr, left);
    // the sign of y
    uncast(_mm512_xor_si512(
        cast(a),
        _mm512_and_si512(cast(y), _mm512_set1_epi64(i64::MIN)),
    ))
}

/// `fastmath::ln` for lanes holding positive normal numbers, same operations.
#[inline]
#[target_feature(enable = "avx512f")]
fn ln(x: __m512d) -> __m512d {
    use super::fastmath::{LG, LN2_HI, LN2_LO};
    let k = _mm512_sub_epi64(biased_exponent(x), _mm512_set1_epi64(1023));
    let m = _mm512_and_si512(cast(x), _mm512_set1_epi64(0x000f_ffff_ffff_ffff));
    let high = _mm512_cmpgt_epi64_mask(m, _mm512_set1_epi64(0x0006_a09e_667f_3bcc));
    let k = _mm512_mask_add_epi64(k, high, k, _mm512_set1_epi64(1));
    let expo = _mm512_mask_blend_epi64(
        high,
        _mm512_set1_epi64(0x3ff0_0000_0000_0000),
        _mm512_set1_epi64(0x3fe0_0000_0000_0000),
    );
    let f = _mm512_sub_pd(uncast(_mm512_or_si512(m, expo)), _mm512_set1_pd(1.0));
    let dk = i64_to_f64(k);
    let hfsq = _mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(0.5), f), f);
    let s = _mm512_div_pd(f, _mm512_add_pd(_mm512_set1_pd(2.0), f));
    let z = _mm512_mul_pd(s, s);
    let w = _mm512_mul_pd(z, z);
    let c = |k: usize| _mm512_set1_pd(LG[k]);
    let madd = |a: __m512d, b: __m512d, acc: __m512d| _mm512_add_pd(a, _mm512_mul_pd(b, acc));
    let t1 = _mm512_mul_pd(w, madd(c(1), w, madd(c(3), w, c(5))));
    let t2 = _mm512_mul_pd(z, madd(c(0), w, madd(c(2), w, madd(c(4), w, c(6)))));
    let r = _mm512_add_pd(t2, t1);
    let inner = _mm512_add_pd(
        _mm512_mul_pd(s, _mm512_add_pd(hfsq, r)),
        _mm512_mul_pd(dk, _mm512_set1_pd(LN2_LO)),
    );
    _mm512_sub_pd(
        _mm512_mul_pd(dk, _mm512_set1_pd(LN2_HI)),
        _mm512_sub_pd(_mm512_sub_pd(hfsq, inner), f),
    )
}

/// The eight lanes of a vector.
#[inline]
#[target_feature(enable = "avx512f")]
fn lanes(v: __m512d) -> [f64; 8] {
    let lo = super::avx2::lanes(_mm512_extractf64x4_pd::<0>(v));
    let hi = super::avx2::lanes(_mm512_extractf64x4_pd::<1>(v));
    [lo[0], lo[1], lo[2], lo[3], hi[0], hi[1], hi[2], hi[3]]
}

/// The fast path for [`WIDTH`] frequencies of a G with k = 0 and without imaginary-axis
/// pairs (as `avx2::response8`, which documents the arguments and why it is one long
/// function).
#[target_feature(enable = "avx512f")]
#[allow(clippy::needless_range_loop)] // g indexes the parallel per-group locals
pub(super) fn response16(
    num: &FactorSet,
    den: &FactorSet,
    w: &[f64; WIDTH],
    k_mant: f64,
    k_exp: i32,
    base_quarters: i64,
) -> [Response8; G] {
    let wv: [__m512d; G] = std::array::from_fn(|g| {
        let b = 8 * g;
        _mm512_set_pd(
            w[b + 7],
            w[b + 6],
            w[b + 5],
            w[b + 4],
            w[b + 3],
            w[b + 2],
            w[b + 1],
            w[b],
        )
    });
    let w2: [__m512d; G] = std::array::from_fn(|g| _mm512_mul_pd(wv[g], wv[g]));
    let zero = _mm512_setzero_pd();
    let one = _mm512_set1_pd(1.0);
    let mut re = [one; G];
    let mut im = [zero; G];
    let mut exp = [_mm512_setzero_si512(); G];
    let mut upper: [__mmask8; G] = [0; G];
    let mut turns = [zero; G];
    let mut quarters = [zero; G];
    let mut d2 = [one; G];
    macro_rules! mul {
        ($g:expr, $fr:expr, $fi:expr) => {{
            let g = $g;
            let (fr, fi) = ($fr, $fi);
            let (r, i) = (re[g], im[g]);
            let nr = _mm512_sub_pd(_mm512_mul_pd(r, fr), _mm512_mul_pd(i, fi));
            let ni = _mm512_add_pd(_mm512_mul_pd(r, fi), _mm512_mul_pd(i, fr));
            let nup = _mm512_cmp_pd_mask::<_CMP_GT_OQ>(ni, zero)
                | (_mm512_cmp_pd_mask::<_CMP_EQ_OQ>(ni, zero)
                    & _mm512_cmp_pd_mask::<_CMP_LT_OQ>(nr, zero));
            let re_nearer = _mm512_cmp_pd_mask::<_CMP_GE_OQ>(_mm512_abs_pd(r), _mm512_abs_pd(i));
            let sx = _mm512_mask_blend_pd(re_nearer, nr, r);
            let cross = (nup ^ upper[g]) & _mm512_cmp_pd_mask::<_CMP_LT_OQ>(sx, zero);
            // +1 leaving the upper half plane, −1 entering it
            turns[g] = _mm512_mask_add_pd(turns[g], cross & upper[g], turns[g], one);
            turns[g] = _mm512_mask_sub_pd(turns[g], cross & !upper[g], turns[g], one);
            re[g] = nr;
            im[g] = ni;
            upper[g] = nup;
        }};
    }
    macro_rules! div_norm2 {
        ($g:expr, $fr:expr, $fi:expr) => {{
            let g = $g;
            let (fr, fi) = ($fr, $fi);
            let d = _mm512_mul_pd(
                d2[g],
                _mm512_add_pd(_mm512_mul_pd(fr, fr), _mm512_mul_pd(fi, fi)),
            );
            let (sc, e) = scale_of(d);
            d2[g] = _mm512_mul_pd(d, sc);
            exp[g] = _mm512_sub_epi64(exp[g], e);
        }};
    }
    macro_rules! rescale {
        () => {{
            for g in 0..G {
                let m = _mm512_max_pd(_mm512_abs_pd(re[g]), _mm512_abs_pd(im[g]));
                let (sc, e) = scale_of(m);
                re[g] = _mm512_mul_pd(re[g], sc);
                im[g] = _mm512_mul_pd(im[g], sc);
                exp[g] = _mm512_add_epi64(exp[g], e);
            }
        }};
    }
    for (set, conj) in [(num, false), (den, true)] {
        let sign = if conj { -1.0 } else { 1.0 };
        for chunk in set.real_c.chunks(4) {
            for &c in chunk {
                let sc = _mm512_set1_pd(sign * c);
                for g in 0..G {
                    let fi = _mm512_mul_pd(sc, wv[g]);
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
                let (a, b) = (_mm512_set1_pd(q.a), _mm512_set1_pd(sign * q.b));
                let half = _mm512_set1_pd(if conj { -2.0 } else { 2.0 } * q.sb as f64);
                for g in 0..G {
                    let x = _mm512_sub_pd(one, _mm512_mul_pd(a, w2[g]));
                    let y = _mm512_mul_pd(b, wv[g]);
                    let neg = _mm512_cmp_pd_mask::<_CMP_LT_OQ>(x, zero);
                    quarters[g] = _mm512_mask_add_pd(quarters[g], neg, quarters[g], half);
                    mul!(g, neg_where(neg, x), neg_where(neg, y));
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
        finish8(
            re[g],
            im[g],
            exp[g],
            turns[g],
            quarters[g],
            d2[g],
            k_mant,
            k_exp,
            base_quarters,
        )
    })
}

/// Magnitude, dB and phase of eight finished products (as `avx2::finish4`).
#[inline]
#[target_feature(enable = "avx512f")]
#[allow(clippy::too_many_arguments)]
fn finish8(
    re: __m512d,
    im: __m512d,
    exp: __m512i,
    turns: __m512d,
    quarters: __m512d,
    d2: __m512d,
    k_mant: f64,
    k_exp: i32,
    base_quarters: i64,
) -> Response8 {
    let zero = _mm512_setzero_pd();
    let inf = _mm512_set1_pd(f64::INFINITY);
    let finite = _mm512_cmp_pd_mask::<_CMP_LT_OQ>(_mm512_abs_pd(re), inf)
        & _mm512_cmp_pd_mask::<_CMP_LT_OQ>(_mm512_abs_pd(im), inf);
    let nonzero =
        _mm512_cmp_pd_mask::<_CMP_NEQ_OQ>(re, zero) | _mm512_cmp_pd_mask::<_CMP_NEQ_OQ>(im, zero);
    // −0 imaginary parts to +0: the negative real axis counts as +π (see `BodeForm::finish`)
    let angle = atan2(_mm512_add_pd(im, zero), re);
    let mant = _mm512_div_pd(
        _mm512_mul_pd(
            _mm512_set1_pd(k_mant),
            _mm512_sqrt_pd(_mm512_add_pd(_mm512_mul_pd(re, re), _mm512_mul_pd(im, im))),
        ),
        d2,
    );
    let exp2 = _mm512_add_epi64(exp, _mm512_set1_epi64(k_exp as i64));
    let in_range = _mm512_cmple_epi64_mask(exp2, _mm512_set1_epi64(1000))
        & _mm512_cmpge_epi64_mask(exp2, _mm512_set1_epi64(-1000));
    let scale = uncast(_mm512_slli_epi64::<52>(_mm512_add_epi64(
        exp2,
        _mm512_set1_epi64(1023),
    )));
    let magnitude = _mm512_mul_pd(mant, scale);
    const DB_PER_NEPER: f64 = 20.0 * std::f64::consts::LOG10_E;
    let magnitude_db = _mm512_mul_pd(
        _mm512_set1_pd(DB_PER_NEPER),
        _mm512_add_pd(
            ln(mant),
            _mm512_mul_pd(_mm512_set1_pd(std::f64::consts::LN_2), i64_to_f64(exp2)),
        ),
    );
    let q = _mm512_add_pd(
        _mm512_add_pd(
            _mm512_set1_pd(base_quarters as f64),
            _mm512_mul_pd(_mm512_set1_pd(4.0), turns),
        ),
        quarters,
    );
    let phase_deg = _mm512_add_pd(
        _mm512_mul_pd(angle, _mm512_set1_pd(180.0f64 / std::f64::consts::PI)),
        _mm512_mul_pd(_mm512_set1_pd(90.0), q),
    );
    let valid = finite & nonzero & in_range;
    Response8 {
        magnitude: lanes(magnitude),
        magnitude_db: lanes(magnitude_db),
        phase_deg: lanes(phase_deg),
        valid: std::array::from_fn(|l| (valid >> l) & 1 == 1),
    }
}
