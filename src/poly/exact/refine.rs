//! Roots of a square-free integer polynomial to full double precision, with inclusion disks.
//!
//! 1. The variable is scaled by an exact power of two so that the roots cluster around |u| ≈ 1,
//!    and the exact coefficients are rounded to double-double (~106 bits).
//! 2. Starting points: the companion-matrix eigenvalues of the rounded polynomial
//!    ([`crate::poly::roots::candidates`]).
//! 3. Aberth–Ehrlich iteration in complex double-double. It refines all roots simultaneously
//!    and keeps them apart (each root is repelled by the others), so two simple roots 10⁻¹²
//!    apart converge to two distinct values instead of both falling into one. For |u| > 1 the
//!    reversed polynomial is evaluated (no overflow for high degree).
//! 4. Inclusion disks (Braess–Hadeler): with Wₖ = p(zₖ)/(a_d Π_{j≠k}(zₖ − zⱼ)), every root of p
//!    lies in the union of the disks |z − zₖ| ≤ d·|Wₖ|, and a connected union of m disks holds
//!    exactly m roots. |p(zₖ)| is bounded above by the computed value plus a rigorous bound on
//!    the rounding error of the double-double evaluation (coefficient rounding included), the
//!    product below by its computed value less its rounding error. Disjoint disks therefore
//!    prove: one root in each; a disk centred on the real axis holds a real root (its conjugate
//!    is in the same disk); a disk off the real axis holds a non-real root; a disk off the
//!    imaginary axis fixes the half plane of its root.
//! 5. Approximations whose disk touches the real axis are put on it (and polished by real
//!    Newton steps); the others are paired with their conjugates, the lower member replaced by
//!    the exact conjugate of the upper one. The disks are recomputed for these final values.
//!
//! When the disks do not come out disjoint (roots closer than double-double can separate, or
//! a factor too ill-conditioned, like Wilkinson's), [`super::mp`] refines at 192…960 bits with
//! exact evaluation; beyond that the result is `None`: beyond the exact budget.

use num_complex::Complex64;

use super::cdd::{Cdd, mul_f64};
use super::disk::DiskRoot;
use super::number::ratio_to_f64;
use super::zpoly::ZPoly;
use crate::numeric::dd::Dd;
use crate::poly::Poly;

/// Most Aberth sweeps.
const MAX_SWEEPS: usize = 80;

/// Relative correction below which a root is left alone in the first, quick pass.
const QUICK_STOP: f64 = 1e-14;

/// Relative correction below which a root is left alone in the full pass.
const FULL_STOP: f64 = 1e-28;

/// Largest relative inclusion radius the quick pass accepts (2⁻⁷⁰ ≈ 8.5e-22: the doubles
/// reported are then the roundings of points within 10⁻²¹ relative of the roots).
const QUICK_RADIUS: f64 = 8.470329472543003e-22;

/// u = 2⁻¹⁰⁴: the unit of the double-double error bounds (with slack for the sloppy
/// double-double additions, whose error is a few u relative to the summands).
const U_DD: f64 = 4.930380657631324e-32;

/// The polynomial of the iteration: ascending double-double coefficients.
struct DdPoly {
    c: Vec<Dd>,
    /// Reversed coefficients (for |z| > 1).
    rev: Vec<Dd>,
    /// |cᵢ| as doubles, upward rounded a little, for the error bounds.
    abs: Vec<f64>,
}

/// Value, derivative, and a bound on the rounding error of the value.
struct Eval {
    p: Cdd,
    dp: Cdd,
    err: f64,
}

impl DdPoly {
    fn new(c: Vec<Dd>) -> DdPoly {
        let mut rev = c.clone();
        rev.reverse();
        let abs = c
            .iter()
            .map(|x| (x.hi.abs() + x.lo.abs()) * (1.0 + 1e-15))
            .collect();
        DdPoly { c, rev, abs }
    }

    fn deg(&self) -> usize {
        self.c.len() - 1
    }

    /// Horner for p and p′ on ascending coefficients `c` at z, with the error bound
    /// γ·Σ|cᵢ||z|ⁱ (γ covers coefficient rounding and the ~2d operations).
    fn horner(c: &[Dd], abs: &[f64], z: Cdd, reversed: bool) -> Eval {
        let n = c.len();
        let mut p = Cdd::ZERO;
        let mut dp = Cdd::ZERO;
        let az = z.abs() * (1.0 + 1e-15);
        let mut bound = 0.0;
        for k in (0..n).rev() {
            dp = dp * z + p;
            p = p * z
                + Cdd {
                    re: c[k],
                    im: Dd::ZERO,
                };
            let a = if reversed { abs[n - 1 - k] } else { abs[k] };
            bound = bound * az + a;
        }
        let gamma = 8.0 * (n as f64 + 2.0) * U_DD;
        Eval {
            p,
            dp,
            err: gamma * bound * (1.0 + 1e-12) + 1e-300,
        }
    }

    /// Newton correction p(z)/p′(z) and the error-bounded |p(z)| as (ln-free) pieces:
    /// returns (correction, |p̂| + err, scale) with |p(z)| ≤ (|p̂| + err)·|z|^scale_power.
    fn newton(&self, z: Cdd) -> Option<(Cdd, f64, bool)> {
        let d = self.deg();
        if z.abs() <= 1.0 {
            let e = DdPoly::horner(&self.c, &self.abs, z, false);
            if e.dp.re.hi == 0.0 && e.dp.im.hi == 0.0 {
                return None;
            }
            Some((e.p / e.dp, e.p.abs() * (1.0 + 1e-15) + e.err, false))
        } else {
            // p(z) = z^d q(w), w = 1/z: p/p′ = z·q / (d·q − w·q′).
            let w = z.inv();
            let e = DdPoly::horner(&self.rev, &self.abs, w, true);
            let den = Cdd {
                re: mul_f64(e.p.re, d as f64),
                im: mul_f64(e.p.im, d as f64),
            } - w * e.dp;
            if den.re.hi == 0.0 && den.im.hi == 0.0 {
                return None;
            }
            Some((z * e.p / den, e.p.abs() * (1.0 + 1e-15) + e.err, true))
        }
    }
}

/// Roots of a square-free polynomial b (degree ≥ 1, b(0) ≠ 0) with disjoint inclusion disks,
/// or `None` when they cannot be separated in double-double or leave the range of doubles.
pub(crate) fn simple_roots(b: &ZPoly) -> Option<Vec<DiskRoot>> {
    let d = b.deg();
    if d == 0 {
        return Some(Vec::new());
    }
    if d == 1 {
        // −a₀/a₁ exactly, rounded once.
        let (a0, a1) = (b.coeff(0), b.coeff(1));
        let neg = (a0 < dashu_int::IBig::ZERO) != (a1 < dashu_int::IBig::ZERO);
        let num = dashu_int::IBig::from(dashu_int::ops::UnsignedAbs::unsigned_abs(a0));
        let v = ratio_to_f64(
            &if neg { num } else { -num },
            &dashu_int::ops::UnsignedAbs::unsigned_abs(a1),
        );
        if !v.is_finite() || v == 0.0 {
            return None;
        }
        return Some(vec![DiskRoot {
            z: Cdd::from_c64(Complex64::new(v, 0.0)),
            r: 0.0,
        }]);
    }
    // 1. Scale s = 2^k u so that the geometric mean of |roots| is ≈ 1.
    let bits = |x: &dashu_int::IBig| {
        dashu_int::ops::BitTest::bit_len(&dashu_int::ops::UnsignedAbs::unsigned_abs(x.clone()))
            as i64
    };
    let k = (bits(&b.coeff(0)) - bits(&b.lc())).div_euclid(d as i64);
    let scaled = scale_variable(b, k);
    let (c, _) = scaled.to_dd_scaled();
    let poly = DdPoly::new(c);
    // 2. Starting points.
    let mut z = starting_points(&poly)?;
    // 3. Aberth iteration: first until every correction is below 10⁻¹⁴ relative (from the
    //    companion eigenvalues of a well-conditioned factor that is one double-double step,
    //    after which the error is ~10⁻³⁰ by quadratic convergence) and certify with disks
    //    small enough for the doubles; only when that fails iterate to 10⁻²⁸.
    let mut steps = aberth(&poly, &mut z, QUICK_STOP);
    let quick = certify(&poly, z.clone(), &steps).filter(|r| {
        r.iter()
            .all(|x| x.r <= QUICK_RADIUS * x.z.abs() && x.r.is_finite())
    });
    // 4–5. Symmetrise, certify; at higher precision when double-double cannot separate.
    let roots = match quick {
        Some(r) => r,
        None => {
            steps = aberth(&poly, &mut z, FULL_STOP);
            match certify(&poly, z.clone(), &steps) {
                Some(r) => r,
                None => super::mp::refine(&scaled, &z)?,
            }
        }
    };
    // Back to s.
    let out: Vec<DiskRoot> = roots
        .into_iter()
        .map(|r| DiskRoot {
            z: r.z.scale_pow2(k),
            r: super::zpoly::pow2_mul(r.r, k),
        })
        .collect();
    let ok = out.iter().all(|r| {
        let v = r.value();
        v.re.is_finite() && v.im.is_finite() && v.norm() > 1e-300 && r.r.is_finite()
    });
    ok.then_some(out)
}

/// b(2^k u) times a power of two that keeps the coefficients integral.
fn scale_variable(b: &ZPoly, k: i64) -> ZPoly {
    let d = b.deg();
    let c = b
        .coeffs()
        .iter()
        .enumerate()
        .map(|(i, x)| {
            let sh = if k >= 0 {
                k as usize * i
            } else {
                (-k) as usize * (d - i)
            };
            x << sh
        })
        .collect();
    ZPoly::new(c)
}

/// Companion eigenvalues of the rounded polynomial; made pairwise distinct.
fn starting_points(p: &DdPoly) -> Option<Vec<Cdd>> {
    let d = p.deg();
    let desc: Vec<f64> = p.c.iter().rev().map(|x| x.hi).collect();
    let cand = Poly::from_descending(&desc)
        .ok()
        .and_then(|q| crate::poly::roots::candidates(&q).ok())
        .filter(|c| c.len() == d && c.iter().all(|z| z.re.is_finite() && z.im.is_finite()));
    let mut pts: Vec<Complex64> = match cand {
        Some(c) => c,
        None => (0..d)
            .map(|j| {
                let t = 2.0 * std::f64::consts::PI * (j as f64 + 0.25) / d as f64;
                Complex64::from_polar(1.0, t)
            })
            .collect(),
    };
    // Aberth needs distinct points: nudge exact duplicates apart.
    for i in 0..d {
        for j in 0..i {
            if (pts[i] - pts[j]).norm() <= 1e-14 * pts[i].norm().max(1e-300) {
                let t = 0.7 + i as f64;
                let bump = Complex64::from_polar(1e-8 * pts[i].norm().max(1e-300), t);
                pts[i] += bump;
            }
        }
    }
    Some(pts.into_iter().map(Cdd::from_c64).collect())
}

/// Gauss–Seidel Aberth–Ehrlich sweeps until every correction is below `stop` relative (the
/// doubles reported need 10⁻¹⁷; the disks certify whatever is reached) or
/// stops decreasing. Returns the size of each root's last correction.
fn aberth(p: &DdPoly, z: &mut [Cdd], stop: f64) -> Vec<f64> {
    let d = z.len();
    let mut done = vec![false; d];
    let mut last = vec![f64::INFINITY; d];
    for _ in 0..MAX_SWEEPS {
        let mut all = true;
        for k in 0..d {
            if done[k] {
                continue;
            }
            let Some((n, _, _)) = p.newton(z[k]) else {
                done[k] = true;
                continue;
            };
            // S = Σ 1/(z_k − z_j): differences in double-double, the sum in doubles.
            let mut s = Complex64::new(0.0, 0.0);
            for j in 0..d {
                if j != k {
                    let diff = (z[k] - z[j]).to_c64();
                    s += diff.inv();
                }
            }
            let nc = n.to_c64();
            let denom = Complex64::new(1.0, 0.0) - nc * s;
            let w = if denom.norm() > 1e-300 && denom.re.is_finite() {
                let inv = denom.inv();
                n * Cdd::from_c64(inv)
            } else {
                n
            };
            z[k] = z[k] - w;
            let size = w.abs() / z[k].abs().max(1e-300);
            if size <= stop || (size >= last[k] * 0.5 && size <= 1e-24) {
                done[k] = true;
            } else {
                all = false;
            }
            last[k] = size;
        }
        if all {
            break;
        }
    }
    last.iter()
        .zip(z.iter())
        .map(|(l, zk)| l * zk.abs())
        .collect()
}

/// Puts near-real approximations on the real axis (those within a few last corrections of
/// it: only a guess, the disks below decide), pairs the others with exact conjugates,
/// computes the inclusion radii and checks that the disks are disjoint.
fn certify(p: &DdPoly, z: Vec<Cdd>, steps: &[f64]) -> Option<Vec<DiskRoot>> {
    let d = z.len();
    let mut real = Vec::new();
    let mut upper = Vec::new();
    let mut lower = Vec::new();
    for (zk, &step) in z.into_iter().zip(steps) {
        let im = zk.im.to_f64();
        if im.abs() <= (4.0 * d as f64 * step).max(1e-28 * zk.abs()) {
            real.push(Cdd::from_dd(zk.re));
        } else if im > 0.0 {
            upper.push(zk);
        } else {
            lower.push(zk);
        }
    }
    if upper.len() != lower.len() {
        return None;
    }
    for x in real.iter_mut() {
        *x = real_newton(p, *x);
    }
    let mut fin = real;
    for u in &upper {
        fin.push(*u);
        fin.push(u.conj());
    }
    debug_assert_eq!(fin.len(), d);
    let r = radii(p, &fin)?;
    let roots: Vec<DiskRoot> = fin
        .into_iter()
        .zip(r)
        .map(|(z, r)| DiskRoot { z, r })
        .collect();
    // Disjoint disks; non-real centres must be off the real axis by more than the radius.
    for (i, a) in roots.iter().enumerate() {
        let im = a.z.im.to_f64();
        if im != 0.0 && im.abs() <= a.r * (1.0 + 1e-12) {
            return None;
        }
        for b in &roots[..i] {
            let dist = (a.z - b.z).abs() * (1.0 - 1e-12);
            if dist <= (a.r + b.r) * (1.0 + 1e-12) {
                return None;
            }
        }
    }
    Some(roots)
}

/// One real double-double Newton step after the projection onto the real axis.
fn real_newton(p: &DdPoly, x: Cdd) -> Cdd {
    match p.newton(x) {
        Some((n, _, _)) if n.re.hi.is_finite() => Cdd::from_dd(x.re - n.re),
        _ => x,
    }
}

/// Braess–Hadeler radii d·|Wₖ| (rigorous upper bounds), `None` when not finite.
fn radii(p: &DdPoly, z: &[Cdd]) -> Option<Vec<f64>> {
    let d = z.len();
    let lead = p.c.last()?.hi.abs() * (1.0 - 1e-15);
    let mut out = Vec::with_capacity(d);
    for k in 0..d {
        let (_, pabs, reversed) = p.newton(z[k]).unwrap_or((Cdd::ZERO, f64::INFINITY, false));
        // |W| = |p(z)| / (|a_d| Π|z − z_j|); for |z| > 1, |p(z)| = |z|^d |q(1/z)| and each
        // factor |z|/|z − z_j| is accumulated instead.
        let az = z[k].abs();
        let mut m = pabs / lead;
        let mut e2: i64 = 0;
        for (j, zj) in z.iter().enumerate() {
            if j == k {
                continue;
            }
            let diff = (z[k] - *zj).abs() * (1.0 - 4e-16);
            if diff == 0.0 {
                return None;
            }
            m *= if reversed { az / diff } else { 1.0 / diff };
            if !(1e-200..=1e200).contains(&m) {
                if m == 0.0 || !m.is_finite() {
                    return None;
                }
                let ex = m.log2().floor() as i64;
                m = super::zpoly::pow2_mul(m, -ex);
                e2 += ex;
            }
        }
        if reversed {
            m *= az;
        }
        let r = super::zpoly::pow2_mul(m * d as f64 * (1.0 + 1e-12), e2);
        if !r.is_finite() {
            return None;
        }
        out.push(r);
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use dashu_int::IBig;

    fn zd(c: &[i64]) -> ZPoly {
        ZPoly::new(c.iter().rev().map(|&x| IBig::from(x)).collect())
    }

    #[test]
    fn close_simple_roots_stay_apart() {
        // (s + 1)(s + 1 + 10⁻¹²)·10¹² = 10¹² s² + (2·10¹² + 1) s + 10¹² + 1.
        let e12 = IBig::from(10u8).pow(12);
        let b = ZPoly::new(vec![
            &e12 + IBig::ONE,
            IBig::from(2) * &e12 + IBig::ONE,
            e12,
        ]);
        let r = simple_roots(&b).unwrap();
        let mut v: Vec<f64> = r.iter().map(|x| x.value().re).collect();
        v.sort_by(f64::total_cmp);
        assert_eq!(r.iter().filter(|x| x.value().im == 0.0).count(), 2);
        assert!((v[0] - (-1.0 - 1e-12)).abs() <= 2.3e-16, "{v:?}");
        assert!((v[1] + 1.0).abs() <= 1.2e-16, "{v:?}");
    }

    #[test]
    fn conjugate_pairs_are_exact() {
        // s³ + 2s² + 3s + 4
        let r = simple_roots(&zd(&[1, 2, 3, 4])).unwrap();
        let vals: Vec<Complex64> = r.iter().map(DiskRoot::value).collect();
        let reals = vals.iter().filter(|z| z.im == 0.0).count();
        assert_eq!(reals, 1);
        let up = vals.iter().find(|z| z.im > 0.0).unwrap();
        assert!(vals.contains(&up.conj()));
        // Residuals: every value is a root to rounding.
        for z in vals {
            let p = ((z + 2.0) * z + 3.0) * z + 4.0;
            assert!(p.norm() < 1e-14, "{z}: {p}");
        }
    }
}
