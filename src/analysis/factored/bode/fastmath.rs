//! `atan2` and `ln` for the frequency-response hot loop: the fdlibm algorithms (Sun
//! Microsystems' freely distributable libm, the reference of most C libraries), written so
//! they inline into the per-frequency loop instead of calling into the C library. fdlibm's
//! `atan` and `log` are accurate to < 1 ulp; `atan2` here divides first, so it is within
//! ~1.5 ulp (glibc: < 1 ulp) — far below the rounding of the factored product itself (a few
//! ulps per factor), and measured against glibc in the tests below.
//!
//! Only what the frequency response needs: finite arguments (the callers route infinities,
//! zeros and non-normal magnitudes to the general path).

use std::f64::consts::{FRAC_PI_2, PI};

/// atan(0.5), atan(1), atan(1.5), atan(∞) (high parts).
pub(super) const ATANHI: [f64; 4] = [
    4.636_476_090_008_061e-1,
    std::f64::consts::FRAC_PI_4,
    9.827_937_232_473_29e-1,
    FRAC_PI_2,
];
pub(super) const ATANLO: [f64; 4] = [
    2.269_877_745_296_168_7e-17,
    3.061_616_997_868_383e-17,
    1.390_331_103_123_099_8e-17,
    6.123_233_995_736_766e-17,
];
pub(super) const AT: [f64; 11] = [
    3.333_333_333_333_293e-1,
    -1.999_999_999_987_648_3e-1,
    1.428_571_427_250_346_6e-1,
    -1.111_111_040_546_235_6e-1,
    9.090_887_133_436_507e-2,
    -7.691_876_205_044_83e-2,
    6.661_073_137_387_531e-2,
    -5.833_570_133_790_573_5e-2,
    4.976_877_994_615_932_4e-2,
    -3.653_157_274_421_691_6e-2,
    1.628_582_011_536_578_2e-2,
];
/// The low part of π (π − `PI` rounded), as in fdlibm.
pub(super) const PI_LO: f64 = 1.224_646_799_147_353_2e-16;

/// atan(x) for x ≥ 0 (finite or +∞), fdlibm `s_atan.c`.
#[inline(always)]
fn atan_pos(x: f64) -> f64 {
    // argument reduction into |x| < 7/16
    let (id, x) = if x < 0.4375 {
        (usize::MAX, x)
    } else if x < 0.6875 {
        (0, (2.0 * x - 1.0) / (2.0 + x))
    } else if x < 1.1875 {
        (1, (x - 1.0) / (x + 1.0))
    } else if x < 2.4375 {
        (2, (x - 1.5) / (1.0 + 1.5 * x))
    } else {
        (3, -1.0 / x)
    };
    let z = x * x;
    let w = z * z;
    let s1 = z * (AT[0] + w * (AT[2] + w * (AT[4] + w * (AT[6] + w * (AT[8] + w * AT[10])))));
    let s2 = w * (AT[1] + w * (AT[3] + w * (AT[5] + w * (AT[7] + w * AT[9]))));
    if id == usize::MAX {
        x - x * (s1 + s2)
    } else {
        ATANHI[id] - ((x * (s1 + s2) - ATANLO[id]) - x)
    }
}

/// The principal argument of x + jy in (−π, π] for finite x, y, not both zero (fdlibm
/// `e_atan2.c` for those arguments).
#[inline(always)]
pub(super) fn atan2(y: f64, x: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    let z = if ay == 0.0 {
        0.0
    } else if ax == 0.0 {
        FRAC_PI_2
    } else {
        let r = ay / ax;
        if r.is_infinite() {
            FRAC_PI_2
        } else if r == 0.0 {
            0.0 // ay/ax underflowed
        } else {
            atan_pos(r)
        }
    };
    let a = if x < 0.0 {
        if z == 0.0 && ay == 0.0 {
            PI
        } else {
            PI - (z - PI_LO)
        }
    } else {
        z
    };
    if y.is_sign_negative() { -a } else { a }
}

pub(super) const LN2_HI: f64 = 6.931_471_803_691_238e-1;
pub(super) const LN2_LO: f64 = 1.908_214_929_270_587_7e-10;
pub(super) const LG: [f64; 7] = [
    6.666_666_666_666_735e-1,
    3.999_999_999_940_942e-1,
    2.857_142_874_366_239e-1,
    2.222_219_843_214_978_4e-1,
    1.818_357_216_161_805e-1,
    1.531_383_769_920_937_3e-1,
    1.479_819_860_511_658_6e-1,
];

/// ln x for a positive normal x, fdlibm `e_log.c`; anything else goes to `f64::ln`.
#[inline(always)]
pub(super) fn ln(x: f64) -> f64 {
    if !(f64::MIN_POSITIVE..f64::INFINITY).contains(&x) {
        return x.ln();
    }
    let bits = x.to_bits();
    let mut k = ((bits >> 52) as i64) - 1023;
    let mut m = bits & 0x000f_ffff_ffff_ffff;
    // 1 + f in [√2/2, √2)
    if m >= 0x0006_a09e_667f_3bcd {
        k += 1;
        m |= 0x3fe0_0000_0000_0000; // mantissa × 2^−1
    } else {
        m |= 0x3ff0_0000_0000_0000;
    }
    let f = f64::from_bits(m) - 1.0;
    let dk = k as f64;
    let hfsq = 0.5 * f * f;
    let s = f / (2.0 + f);
    let z = s * s;
    let w = z * z;
    let t1 = w * (LG[1] + w * (LG[3] + w * LG[5]));
    let t2 = z * (LG[0] + w * (LG[2] + w * (LG[4] + w * LG[6])));
    let r = t2 + t1;
    dk * LN2_HI - ((hfsq - (s * (hfsq + r) + dk * LN2_LO)) - f)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ulps(a: f64, b: f64) -> f64 {
        (a - b).abs() / (f64::EPSILON * b.abs().max(f64::MIN_POSITIVE))
    }

    /// Deterministic pseudo-random doubles over many binades.
    fn samples() -> impl Iterator<Item = f64> {
        let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
        (0..200_000).map(move |_| {
            let s = crate::numeric::test_rng::next(&mut state);
            let mant = (s >> 12) as f64 / (1u64 << 52) as f64; // [0, 1)
            let e = ((s & 0xfff) % 120) as i32 - 60;
            (1.0 + mant) * 2f64.powi(e)
        })
    }

    #[test]
    fn atan2_within_two_ulps_of_libm() {
        let mut worst: f64 = 0.0;
        let xs: Vec<f64> = samples().collect();
        for (i, &a) in xs.iter().enumerate() {
            let b = xs[(i * 7919 + 13) % xs.len()];
            for (y, x) in [(a, b), (-a, b), (a, -b), (-a, -b), (a, a), (b, -b)] {
                worst = worst.max(ulps(atan2(y, x), y.atan2(x)));
            }
        }
        assert!(worst <= 2.0, "worst {worst} ulps");
        // axes and signed zeros
        for (y, x) in [
            (0.0, 1.0),
            (-0.0, 1.0),
            (0.0, -1.0),
            (1.0, 0.0),
            (-1.0, 0.0),
            (1e-300, 1e300),
            (1e300, 1e-300),
            (-1e-300, -1e300),
        ] {
            assert!(ulps(atan2(y, x), y.atan2(x)) <= 1.0, "{y} {x}");
        }
    }

    #[test]
    fn ln_within_one_ulp_of_libm() {
        let mut worst: f64 = 0.0;
        for x in samples() {
            worst = worst.max(ulps(ln(x), x.ln()));
        }
        assert!(worst <= 1.0, "worst {worst} ulps");
        for x in [
            1.0,
            2.0,
            0.5,
            f64::MIN_POSITIVE,
            f64::MAX,
            1.0 + f64::EPSILON,
        ] {
            let (a, b) = (ln(x), x.ln());
            assert!((a - b).abs() <= f64::EPSILON * b.abs(), "{x}: {a} vs {b}");
        }
        assert!(ln(0.0).is_infinite() && ln(f64::INFINITY).is_infinite());
    }
}
