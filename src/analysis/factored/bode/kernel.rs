//! The frequency-response hot loop: |G|, dB and the continuous phase at many frequencies.
//!
//! Same factored form and branch tracking as [`BodeForm::eval`], fused into one running
//! product per frequency: G(jω)/(K·(jω)^k) = Π F_N(jω) · Π conj(F_D(jω)) / Π|F_D(jω)|² (a
//! denominator factor's angle is subtracted; conj(F) has the same positive real part, so
//! the branch tracking of a product of right-half-plane factors applies), so the whole
//! phase is one principal `atan2` of the product plus the full turns counted while
//! multiplying, plus the exact half and quarter turns pulled out of the factors — no
//! separate numerator and denominator products to reconcile, no per-factor `atan2`. The
//! libm calls are replaced by inlined fdlibm `atan2`/`ln` ([`super::fastmath`]).
//!
//! Three loops compute it, chosen per call: the portable lane loop here, and on x86-64 (when
//! build.rs enables `cfg(ltikit_simd)`) `avx2::response8` and `avx512::response16`, picked at
//! run time from the CPU's features for a G without imaginary-axis pairs. They perform the
//! same floating-point operations in the same order, so they return bitwise the same values
//! (tested); the rest of a grid that does not fill a vector block goes through the portable
//! lanes, padded.
//!
//! Frequencies the fast path does not cover (ω = 0, beyond the overflow-free limit, an
//! exact hit of an imaginary-axis root, a product that is not a normal number, the
//! double-double Horner fallback) go through [`BodeForm::eval`].
//!
//! Length: the per-block loop is one function of ~130 lines on purpose — its state lives in
//! locals (registers) across the factor loop, and splitting it into calls measurably costs
//! throughput (the loop is latency-bound); the three loops mirror each other line by line,
//! which is what the bitwise-equality tests rely on.

use std::f64::consts::LN_2;

use super::factors::{Eval, FactorSet, exponent, mul_pow2, pow2};
use super::fastmath;
use super::form::BodeForm;

/// Which evaluation loop `response_fill` runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Path {
    /// The lane loop below (any CPU).
    Portable,
    /// `avx2::response8` (x86-64 with AVX2, no imaginary-axis pairs).
    #[cfg_attr(not(all(target_arch = "x86_64", ltikit_simd)), allow(dead_code))]
    Avx2,
    /// `avx512::response16` (x86-64 with AVX-512F, no imaginary-axis pairs).
    #[cfg_attr(not(all(target_arch = "x86_64", ltikit_simd)), allow(dead_code))]
    Avx512,
}

/// Frequencies evaluated side by side by the portable loop (independent dependency chains;
/// also the block the SIMD paths must reproduce lane by lane).
const L: usize = 8;

/// The running products of `L` frequencies with their branch bookkeeping.
struct Products {
    re: [f64; L],
    im: [f64; L],
    exp: [i32; L],
    /// The argument is in (0, π] (Im > 0, or on the negative real axis).
    upper: [bool; L],
    /// Full turns gained by crossing the negative real axis.
    turns: [i32; L],
    /// Quarter turns pulled out of the factors (half turns of quadratics with negative real
    /// part, imaginary-axis pairs passed).
    quarters: [i32; L],
    /// Π|F_D|² of the denominator factors multiplied in as conj(F_D), kept in [1, 2) by
    /// moving its power of two into `exp` with the opposite sign: |G| ∝ |product| / d2.
    d2: [f64; L],
    /// ω hit an imaginary-axis root exactly.
    hit: [bool; L],
}

impl Products {
    fn one() -> Products {
        Products {
            re: [1.0; L],
            im: [0.0; L],
            exp: [0; L],
            upper: [false; L],
            turns: [0; L],
            quarters: [0; L],
            d2: [1.0; L],
            hit: [false; L],
        }
    }

    /// Multiplies lane `l` by (fr + j·fi), fr ≥ 0 (the factor's angle is in [−π/2, π/2]),
    /// counting turns (`factors::mul_tracked`).
    #[inline(always)]
    fn mul(&mut self, l: usize, fr: f64, fi: f64) {
        super::factors::mul_tracked(
            &mut self.re[l],
            &mut self.im[l],
            &mut self.upper[l],
            &mut self.turns[l],
            fr,
            fi,
        );
    }

    /// d2 ← d2·|F|² for lane `l` (|F| ≤ 2^200 on the fast path: one factor cannot overflow).
    #[inline(always)]
    fn div_norm2(&mut self, l: usize, fr: f64, fi: f64) {
        let d = self.d2[l] * (fr * fr + fi * fi);
        let ex = exponent(d);
        self.d2[l] = d * pow2(-ex);
        self.exp[l] -= ex;
    }

    #[inline(always)]
    fn rescale(&mut self) {
        for l in 0..L {
            let ex = exponent(self.re[l].abs().max(self.im[l].abs()));
            let s = pow2(-ex);
            self.re[l] *= s;
            self.im[l] *= s;
            self.exp[l] += ex;
        }
    }

    /// Multiplies by every factor of `s` (by its conjugate when `conj`, for the
    /// denominator), rescaling after every four.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lanes index several parallel arrays
    fn mul_set(&mut self, s: &FactorSet, w: &[f64; L], w2: &[f64; L], conj: bool) {
        let sign = if conj { -1.0 } else { 1.0 };
        for chunk in s.real_c.chunks(4) {
            for &c in chunk {
                let sc = sign * c;
                for l in 0..L {
                    let fi = sc * w[l];
                    self.mul(l, 1.0, fi);
                    if conj {
                        self.div_norm2(l, 1.0, fi);
                    }
                }
            }
            self.rescale();
        }
        for chunk in s.quad.chunks(4) {
            for q in chunk {
                let sb = sign * q.b;
                let half = if conj { -2 * q.sb } else { 2 * q.sb };
                for l in 0..L {
                    let x = 1.0 - q.a * w2[l];
                    let y = sb * w[l];
                    // x < 0: F = −(−x − j·b·ω), a half turn towards the side of the pair
                    let neg = x < 0.0;
                    self.quarters[l] += if neg { half } else { 0 };
                    let (fr, fi) = if neg { (-x, -y) } else { (x, y) };
                    self.mul(l, fr, fi);
                    if conj {
                        self.div_norm2(l, x, y);
                    }
                }
            }
            self.rescale();
        }
        for (&beta, &ib) in s.axis.iter().zip(&s.axis_inv) {
            for l in 0..L {
                let x = ((beta - w[l]) * ib) * ((beta + w[l]) * ib);
                if x == 0.0 {
                    self.hit[l] = true;
                    continue;
                }
                if x < 0.0 {
                    self.quarters[l] += if conj { -2 } else { 2 };
                }
                let ax = if conj { 1.0 / x.abs() } else { x.abs() };
                self.re[l] *= ax;
                self.im[l] *= ax;
            }
            self.rescale();
        }
    }
}

/// Writes |G|, dB and the phase (degrees) of `e` at index `i`.
#[inline(always)]
fn store(
    e: Eval,
    i: usize,
    magnitude: &mut [f64],
    magnitude_db: &mut [f64],
    phase_deg: &mut [f64],
) {
    const DB_PER_NEPER: f64 = 20.0 * std::f64::consts::LOG10_E;
    magnitude[i] = if e.mant > 0.0 && e.mant.is_finite() && (-1000..=1000).contains(&e.exp2) {
        e.mant * pow2(e.exp2)
    } else {
        mul_pow2(e.mant, e.exp2)
    };
    magnitude_db[i] = DB_PER_NEPER * (fastmath::ln(e.mant) + LN_2 * e.exp2 as f64);
    phase_deg[i] = e.phase_deg();
}

impl BodeForm {
    /// The end of the fused fast path for one frequency: principal phase, magnitude and the
    /// integrator power from the product (re, im)·2^exp / d2 with its counted turns and
    /// quarter turns; `None` when the product is not a normal number.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn finish(
        &self,
        w: f64,
        re: f64,
        im: f64,
        exp: i64,
        d2: f64,
        turns: i64,
        quarters: i64,
    ) -> Option<Eval> {
        if !(re.is_finite() && im.is_finite()) || (re == 0.0 && im == 0.0) {
            return None;
        }
        // The turn count takes the negative real axis as the upper side (argument +π): an
        // imaginary part of −0 must not make atan2 say −π (+ 0.0 turns −0 into +0).
        let angle = fastmath::atan2(im + 0.0, re);
        let mut mant = self.k_mant * (re * re + im * im).sqrt() / d2;
        let mut exp2 = self.k_exp + exp as i32;
        if self.int_order != 0 {
            let we = exponent(w);
            mant *= (w * pow2(-we)).powi(self.int_order);
            exp2 += self.int_order.saturating_mul(we);
        }
        Some(Eval {
            mant,
            exp2,
            angle,
            quarters: self.base_quarters + 4 * turns + quarters,
        })
    }

    /// G(jω) at `L` frequencies on the portable fused path (each normal and ≤ the fast
    /// limit); `None` in a lane the general path must decide (see the module docs).
    #[inline(always)]
    fn eval_fused(&self, w: &[f64; L]) -> [Option<Eval>; L] {
        let w2: [f64; L] = std::array::from_fn(|l| w[l] * w[l]);
        let mut p = Products::one();
        p.mul_set(&self.num, w, &w2, false);
        p.mul_set(&self.den, w, &w2, true);
        p.rescale();
        std::array::from_fn(|l| {
            if p.hit[l] {
                return None;
            }
            self.finish(
                w[l],
                p.re[l],
                p.im[l],
                p.exp[l] as i64,
                p.d2[l],
                p.turns[l] as i64,
                p.quarters[l] as i64,
            )
        })
    }

    /// As [`BodeForm::eval_fused`] for 4 frequencies with the AVX2 product (bitwise the same
    /// values). The factor sets must have no imaginary-axis pairs and the CPU must have AVX2
    /// (`Path::Avx2` or `Path::Avx512`).
    #[cfg(all(target_arch = "x86_64", ltikit_simd))]
    #[inline(always)]
    fn eval_fused_avx2(&self, w: &[f64; 4]) -> [Option<Eval>; 4] {
        // SAFETY: only on `Path::Avx2`/`Path::Avx512`, chosen after `avx2::available()` or
        // `avx512::available()` (AVX-512F implies AVX2) in `simd_path`.
        let p = unsafe { super::avx2::product4(&self.num, &self.den, w) };
        std::array::from_fn(|l| {
            self.finish(
                w[l],
                p.re[l],
                p.im[l],
                p.exp[l],
                p.d2[l],
                p.turns[l],
                p.quarters[l],
            )
        })
    }

    /// The vector path the CPU allows for this G (imaginary-axis pairs always take the
    /// portable loop).
    fn simd_path(&self) -> Path {
        #[cfg(all(target_arch = "x86_64", ltikit_simd))]
        if self.num.axis.is_empty() && self.den.axis.is_empty() {
            if super::avx512::available() {
                return Path::Avx512;
            }
            if super::avx2::available() {
                return Path::Avx2;
            }
        }
        Path::Portable
    }

    /// |G|, 20·log₁₀|G| and the continuous phase (degrees) at every ω of `w` (each finite,
    /// ≥ 0), written to the three slices (each as long as `w`).
    pub(crate) fn response_fill(
        &self,
        w: &[f64],
        magnitude: &mut [f64],
        magnitude_db: &mut [f64],
        phase_deg: &mut [f64],
    ) {
        self.response_fill_with(w, self.simd_path(), magnitude, magnitude_db, phase_deg);
    }

    /// [`BodeForm::response_fill`] on the given path (a vector path only where
    /// [`BodeForm::simd_path`] allows it: AVX-512 implies AVX2).
    fn response_fill_with(
        &self,
        w: &[f64],
        path: Path,
        magnitude: &mut [f64],
        magnitude_db: &mut [f64],
        phase_deg: &mut [f64],
    ) {
        let fused = self.exact.is_none() && !self.zero;
        let in_range = |x: f64| x >= f64::MIN_POSITIVE && x <= self.fast_limit;
        let width = match path {
            #[cfg(all(target_arch = "x86_64", ltikit_simd))]
            Path::Avx512 => super::avx512::WIDTH,
            #[cfg(all(target_arch = "x86_64", ltikit_simd))]
            Path::Avx2 => 4 * super::avx2::G,
            _ => L,
        };
        let mut chunks = w.chunks_exact(width);
        let mut i = 0;
        for c in &mut chunks {
            if !(fused && c.iter().all(|&x| in_range(x))) {
                i = self.fill_scalar(c, i, magnitude, magnitude_db, phase_deg);
                continue;
            }
            #[cfg(all(target_arch = "x86_64", ltikit_simd))]
            if path == Path::Avx512 {
                if self.int_order == 0 {
                    let block: [f64; super::avx512::WIDTH] = std::array::from_fn(|k| c[k]);
                    // SAFETY: `Path::Avx512` only after `avx512::available()` (`simd_path`).
                    let r = unsafe {
                        super::avx512::response16(
                            &self.num,
                            &self.den,
                            &block,
                            self.k_mant,
                            self.k_exp,
                            self.base_quarters,
                        )
                    };
                    if r.iter().all(|h| h.valid.iter().all(|&v| v)) {
                        for (h, r) in r.iter().enumerate() {
                            let j = i + 8 * h;
                            magnitude[j..j + 8].copy_from_slice(&r.magnitude);
                            magnitude_db[j..j + 8].copy_from_slice(&r.magnitude_db);
                            phase_deg[j..j + 8].copy_from_slice(&r.phase_deg);
                        }
                        i += super::avx512::WIDTH;
                        continue;
                    }
                }
                // AVX-512 implies AVX2: the four-wide product with the scalar tail
                i = self.fill_quads(c, i, magnitude, magnitude_db, phase_deg);
                continue;
            }
            #[cfg(all(target_arch = "x86_64", ltikit_simd))]
            if path == Path::Avx2 {
                if self.int_order == 0 {
                    let block: [f64; 4 * super::avx2::G] = std::array::from_fn(|k| c[k]);
                    // SAFETY: `Path::Avx2` only after `avx2::available()` (`simd_path`).
                    let r = unsafe {
                        super::avx2::response8(
                            &self.num,
                            &self.den,
                            &block,
                            self.k_mant,
                            self.k_exp,
                            self.base_quarters,
                        )
                    };
                    if r.iter().all(|h| h.valid.iter().all(|&v| v)) {
                        for (h, r) in r.iter().enumerate() {
                            let j = i + 4 * h;
                            magnitude[j..j + 4].copy_from_slice(&r.magnitude);
                            magnitude_db[j..j + 4].copy_from_slice(&r.magnitude_db);
                            phase_deg[j..j + 4].copy_from_slice(&r.phase_deg);
                        }
                        i += 4 * super::avx2::G;
                        continue;
                    }
                }
                i = self.fill_quads(c, i, magnitude, magnitude_db, phase_deg);
                continue;
            }
            let block: [f64; L] = std::array::from_fn(|k| c[k]);
            for (e, &x) in self.eval_fused(&block).into_iter().zip(&block) {
                store(
                    e.unwrap_or_else(|| self.eval(x)),
                    i,
                    magnitude,
                    magnitude_db,
                    phase_deg,
                );
                i += 1;
            }
        }
        // The rest (fewer than `width`): the portable lanes, padded with its last frequency,
        // so every frequency gets the fused path's values whatever the block width.
        for c in chunks.remainder().chunks(L) {
            if !(fused && c.iter().all(|&x| in_range(x))) {
                i = self.fill_scalar(c, i, magnitude, magnitude_db, phase_deg);
                continue;
            }
            let block: [f64; L] = std::array::from_fn(|k| c[k.min(c.len() - 1)]);
            for (e, &x) in self.eval_fused(&block).into_iter().zip(c) {
                store(
                    e.unwrap_or_else(|| self.eval(x)),
                    i,
                    magnitude,
                    magnitude_db,
                    phase_deg,
                );
                i += 1;
            }
        }
    }

    /// Frequencies one by one on the scalar path; returns the next output index.
    fn fill_scalar(
        &self,
        w: &[f64],
        mut i: usize,
        magnitude: &mut [f64],
        magnitude_db: &mut [f64],
        phase_deg: &mut [f64],
    ) -> usize {
        for &x in w {
            store(self.eval(x), i, magnitude, magnitude_db, phase_deg);
            i += 1;
        }
        i
    }

    /// Frequencies four at a time on the AVX2 product (a lane it cannot take goes to the
    /// scalar path); `w.len()` a multiple of 4; returns the next output index.
    #[cfg(all(target_arch = "x86_64", ltikit_simd))]
    fn fill_quads(
        &self,
        w: &[f64],
        mut i: usize,
        magnitude: &mut [f64],
        magnitude_db: &mut [f64],
        phase_deg: &mut [f64],
    ) -> usize {
        for quad in w.chunks_exact(4) {
            let block: [f64; 4] = std::array::from_fn(|k| quad[k]);
            for (e, &x) in self.eval_fused_avx2(&block).into_iter().zip(&block) {
                store(
                    e.unwrap_or_else(|| self.eval(x)),
                    i,
                    magnitude,
                    magnitude_db,
                    phase_deg,
                );
                i += 1;
            }
        }
        i
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn form(g: &crate::lti::TransferFunction) -> BodeForm {
        g.factored().unwrap().bode().clone()
    }
    use crate::lti::TransferFunction;
    use num_complex::Complex64;
    use proptest::prelude::*;

    /// Random roots: real and complex pairs in both half planes, on the imaginary axis, some
    /// repeated, magnitudes 10^[−2, 2].
    fn roots(max: usize) -> impl Strategy<Value = Vec<Complex64>> {
        prop::collection::vec((0u8..5, -2.0f64..2.0, -1.0f64..1.0, 0usize..4), 0..=max).prop_map(
            |spec| {
                let mut out = Vec::new();
                for (kind, lm, c, rep) in spec {
                    let m = 10f64.powf(lm);
                    for _ in 0..if rep == 0 { 2 } else { 1 } {
                        match kind {
                            0 | 1 => {
                                let re = -c * m;
                                let im = m * (1.0 - c * c).sqrt();
                                out.push(Complex64::new(re, im));
                                out.push(Complex64::new(re, -im));
                            }
                            2 => {
                                out.push(Complex64::new(0.0, m));
                                out.push(Complex64::new(0.0, -m));
                            }
                            _ => out.push(Complex64::new(if c < 0.0 { m } else { -m }, 0.0)),
                        }
                    }
                }
                out
            },
        )
    }

    /// A double pole pair on the unit circle, hit exactly at ω = 1: both factors are purely
    /// imaginary there and the product lands on the negative real axis with a −0 imaginary
    /// part (found by `fused_matches_eval`): the phase is −180° (K < 0) − 2·90° = −360°.
    #[test]
    fn product_on_the_negative_real_axis_keeps_its_branch() {
        let p = Complex64::new(-0.8148459734085408, 0.5796775307184915);
        let poles = [p, p.conj(), p, p.conj()];
        let g = TransferFunction::from_zpk(&[], &poles, -4.67837878872059).unwrap();
        let f = form(&g);
        let w = [
            0.5, 1.0, 2.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0,
        ];
        let (mut m, mut db, mut ph) = ([0.0; 16], [0.0; 16], [0.0; 16]);
        f.response_fill(&w, &mut m, &mut db, &mut ph);
        for (i, &x) in w.iter().enumerate() {
            assert!(
                (ph[i] - f.eval(x).phase_deg()).abs() < 1e-9,
                "ω = {x}: {}",
                ph[i]
            );
        }
        assert!((ph[1] + 360.0).abs() < 1e-9, "{}", ph[1]);
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 96, .. ProptestConfig::default() })]

        /// The AVX2 and AVX-512 paths give bitwise the values of the portable lane loop.
        #[cfg(all(target_arch = "x86_64", ltikit_simd))]
        #[test]
        fn vector_paths_are_bitwise_portable(z in roots(6), p in roots(12), int in -2i32..2) {
            let z: Vec<Complex64> = z.into_iter().filter(|r| r.re != 0.0).collect();
            let p: Vec<Complex64> = p.into_iter().filter(|r| r.re != 0.0).collect();
            let mut g = TransferFunction::from_zpk(&z, &p, 2.5).unwrap();
            let s = TransferFunction::s();
            for _ in 0..int.abs() {
                g = if int > 0 { &g * &s } else { &g * &s.inv().unwrap() };
            }
            let f = form(&g);
            let best = f.simd_path();
            prop_assume!(best != Path::Portable);
            let w: Vec<f64> = (0..203).map(|i| 10f64.powf(-4.0 + 8.0 * i as f64 / 202.0)).collect();
            let n = w.len();
            let run = |path: Path| {
                let (mut m, mut db, mut ph) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
                f.response_fill_with(&w, path, &mut m, &mut db, &mut ph);
                (m, db, ph)
            };
            let portable = run(Path::Portable);
            let mut paths = vec![Path::Avx2];
            if best == Path::Avx512 {
                paths.push(Path::Avx512);
            }
            for path in paths {
                let a = run(path);
                for (i, x) in w.iter().enumerate() {
                    prop_assert_eq!(a.0[i].to_bits(), portable.0[i].to_bits(), "{:?} |G| at {}", path, x);
                    prop_assert_eq!(a.1[i].to_bits(), portable.1[i].to_bits(), "{:?} dB at {}", path, x);
                    prop_assert_eq!(a.2[i].to_bits(), portable.2[i].to_bits(), "{:?} φ at {}", path, x);
                }
            }
        }

        /// The fused loop gives the values of the per-frequency evaluation (the tested
        /// branch tracking of `BodeForm::eval`) to rounding, phase branch included.
        #[test]
        fn fused_matches_eval(z in roots(6), p in roots(12), int in -3i32..3, k in -5.0f64..5.0) {
            prop_assume!(k.abs() > 1e-3);
            let mut g = TransferFunction::from_zpk(&z, &p, k).unwrap();
            let s = TransferFunction::s();
            for _ in 0..int.abs() {
                g = if int > 0 { &g * &s } else { &g * &s.inv().unwrap() };
            }
            let f = form(&g);
            let mut w: Vec<f64> = (0..301).map(|i| 10f64.powf(-4.0 + 8.0 * i as f64 / 300.0)).collect();
            for c in f.corner_frequencies() {
                w.extend([c, c * (1.0 + 1e-9), c * (1.0 - 1e-9), c * 1.01, c * 0.99]);
            }
            w.push(0.0);
            let (mut m, mut db, mut ph) = (vec![0.0; w.len()], vec![0.0; w.len()], vec![0.0; w.len()]);
            f.response_fill(&w, &mut m, &mut db, &mut ph);
            for (i, &x) in w.iter().enumerate() {
                let e = f.eval(x);
                let (mr, dbr, phr) = (e.magnitude(), e.db(), e.phase_deg());
                if mr.is_finite() && mr > 0.0 {
                    prop_assert!((m[i] - mr).abs() <= 1e-12 * mr, "ω={} |G| {} vs {}", x, m[i], mr);
                    prop_assert!((db[i] - dbr).abs() <= 1e-11 * (1.0 + dbr.abs()), "ω={} dB {} vs {}", x, db[i], dbr);
                } else {
                    // 0 or ∞ exactly (a root on the axis hit): the same special value
                    prop_assert!(m[i].to_bits() == mr.to_bits(), "ω={} |G| {} vs {}", x, m[i], mr);
                }
                prop_assert!((ph[i] - phr).abs() <= 1e-9, "ω={} φ {} vs {}", x, ph[i], phr);
            }
        }
    }
}
