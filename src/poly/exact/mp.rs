//! Multi-precision refinement for factors whose roots double-double cannot separate
//! (Wilkinson-like products, roots closer than ~10⁻²⁸ relative).
//!
//! A point is a Gaussian integer X = Xr + jXi standing for X·2^(−P). The polynomial is
//! evaluated **exactly** there (integer Horner on 2^(Pd)·p(X/2^P)), and only the Newton
//! quotient p/p′ and the Aberth sum are formed in doubles — they need ~16 correct digits, not
//! P bits, for the iteration to converge to P bits. The inclusion radii use the exact |p(zₖ)|.
//! Precision doubles from 192 bits up to [`MAX_PREC`] until the disks are disjoint.

use dashu_int::IBig;
use dashu_int::ops::{BitTest, UnsignedAbs};
use num_complex::Complex64;

use super::cdd::Cdd;
use super::disk::DiskRoot;
use super::zpoly::{ZPoly, pow2_mul};
use crate::numeric::dd::Dd;

/// Highest working precision (bits after the binary point).
pub(crate) const MAX_PREC: usize = 960;

/// Most sweeps per precision.
const SWEEPS: usize = 60;

#[derive(Clone, Debug, PartialEq)]
struct G {
    re: IBig,
    im: IBig,
}

impl G {
    fn mul(&self, o: &G) -> G {
        G {
            re: &self.re * &o.re - &self.im * &o.im,
            im: &self.re * &o.im + &self.im * &o.re,
        }
    }
}

/// x ≈ m·2^e with m a double (53 significant bits of x).
fn to_f64_exp(x: &IBig) -> (f64, i64) {
    let len = x.unsigned_abs().bit_len() as i64;
    let sh = (len - 62).max(0);
    let t = if sh > 0 { x >> sh as usize } else { x.clone() };
    (i64::try_from(&t).unwrap_or(0) as f64, sh)
}

/// A Gaussian integer times 2^(−shift) as a complex double (0 for values below the doubles).
fn g_to_c64(x: &G, shift: i64) -> Complex64 {
    let (a, ea) = to_f64_exp(&x.re);
    let (b, eb) = to_f64_exp(&x.im);
    Complex64::new(pow2_mul(a, ea - shift), pow2_mul(b, eb - shift))
}

/// round(x·2^p) for a finite double.
fn f64_to_fixed(x: f64, p: usize) -> IBig {
    if x == 0.0 || !x.is_finite() {
        return IBig::ZERO;
    }
    let bits = x.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i64;
    let frac = bits & ((1u64 << 52) - 1);
    let (mant, e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), exp - 1075)
    };
    let m = IBig::from(mant);
    let sh = e + p as i64;
    let v = if sh >= 0 {
        m << sh as usize
    } else {
        // round to nearest
        let s = (-sh) as usize;
        (m + (IBig::ONE << (s - 1))) >> s
    };
    if x < 0.0 { -v } else { v }
}

fn dd_to_fixed(x: Dd, p: usize) -> IBig {
    f64_to_fixed(x.hi, p) + f64_to_fixed(x.lo, p)
}

/// (2^(Pd)·p(z), 2^(P(d−1))·p′(z)) exactly at z = X/2^P.
fn horner(c: &[IBig], x: &G, p: usize) -> (G, G) {
    let d = c.len() - 1;
    let mut acc = G {
        re: c[d].clone(),
        im: IBig::ZERO,
    };
    let mut dacc = G {
        re: IBig::ZERO,
        im: IBig::ZERO,
    };
    for i in (0..d).rev() {
        dacc = dacc.mul(x);
        dacc.re += &acc.re;
        dacc.im += &acc.im;
        acc = acc.mul(x);
        acc.re += &c[i] << (p * (d - i));
    }
    (acc, dacc)
}

/// |B|·2^(−shift) in log₂ (−∞ for 0).
fn log2_abs(b: &G, shift: i64) -> f64 {
    let (a, ea) = to_f64_exp(&b.re);
    let (c, ec) = to_f64_exp(&b.im);
    let e = ea.max(ec);
    let v = Complex64::new(pow2_mul(a, ea - e), pow2_mul(c, ec - e)).norm();
    v.log2() + (e - shift) as f64
}

/// Refines the approximations `z` of the roots of the square-free `b` (scaled so its roots
/// are near |u| ≈ 1) at increasing precision until the inclusion disks are disjoint.
pub(crate) fn refine(b: &ZPoly, z: &[Cdd]) -> Option<Vec<DiskRoot>> {
    let c = b.coeffs();
    let mut prec = 192;
    let mut pts: Vec<G> = z
        .iter()
        .map(|w| G {
            re: dd_to_fixed(w.re, prec),
            im: dd_to_fixed(w.im, prec),
        })
        .collect();
    loop {
        aberth(c, &mut pts, prec);
        if let Some(r) = symmetrise_and_certify(c, &mut pts, prec) {
            return Some(r);
        }
        if prec * 2 > MAX_PREC {
            return None;
        }
        for x in pts.iter_mut() {
            x.re <<= prec;
            x.im <<= prec;
        }
        prec *= 2;
    }
}

fn aberth(c: &[IBig], pts: &mut [G], p: usize) {
    let n = pts.len();
    let mut done = vec![false; n];
    for _ in 0..SWEEPS {
        let mut all = true;
        for k in 0..n {
            if done[k] {
                continue;
            }
            let w = correction(c, pts, k, p);
            let zk = g_to_c64(&pts[k], p as i64);
            if !(w.re.is_finite() && w.im.is_finite()) {
                done[k] = true;
                continue;
            }
            pts[k].re -= f64_to_fixed(w.re, p);
            pts[k].im -= f64_to_fixed(w.im, p);
            let size = w.norm() / zk.norm().max(1e-300);
            if size.log2() < -(p as f64) + 16.0 {
                done[k] = true;
            } else {
                all = false;
            }
        }
        if all {
            break;
        }
    }
}

/// The Aberth correction N/(1 − N·Σ 1/(zₖ − zⱼ)) with N = p/p′ (doubles, exact inputs).
fn correction(c: &[IBig], pts: &[G], k: usize, p: usize) -> Complex64 {
    let (b, db) = horner(c, &pts[k], p);
    // N = B/B′ · 2^(−P)
    let (br, er) = to_f64_exp(&b.re);
    let (bi, ei) = to_f64_exp(&b.im);
    let (dr, fr) = to_f64_exp(&db.re);
    let (di, fi) = to_f64_exp(&db.im);
    let eb = er.max(ei);
    let ed = fr.max(fi);
    let num = Complex64::new(pow2_mul(br, er - eb), pow2_mul(bi, ei - eb));
    let den = Complex64::new(pow2_mul(dr, fr - ed), pow2_mul(di, fi - ed));
    if den.norm() == 0.0 {
        return Complex64::new(f64::NAN, 0.0);
    }
    let q = num / den;
    let nn = Complex64::new(
        pow2_mul(q.re, eb - ed - p as i64),
        pow2_mul(q.im, eb - ed - p as i64),
    );
    let mut s = Complex64::new(0.0, 0.0);
    for (j, x) in pts.iter().enumerate() {
        if j != k {
            let diff = G {
                re: &pts[k].re - &x.re,
                im: &pts[k].im - &x.im,
            };
            let dz = g_to_c64(&diff, p as i64);
            if dz.norm() > 0.0 {
                s += dz.inv();
            }
        }
    }
    let den = Complex64::new(1.0, 0.0) - nn * s;
    if den.norm() > 1e-300 { nn / den } else { nn }
}

/// Radii d·|p(zₖ)|/(|a_d|·Π|zₖ − zⱼ|) from the exact |p(zₖ)|, as log₂.
fn log2_radii(c: &[IBig], pts: &[G], p: usize) -> Vec<f64> {
    let d = c.len() - 1;
    let lead = log2_abs(
        &G {
            re: c[d].clone(),
            im: IBig::ZERO,
        },
        0,
    );
    (0..pts.len())
        .map(|k| {
            let (b, _) = horner(c, &pts[k], p);
            let mut l = log2_abs(&b, (p * d) as i64) - lead + (d as f64).log2();
            for (j, x) in pts.iter().enumerate() {
                if j != k {
                    let diff = G {
                        re: &pts[k].re - &x.re,
                        im: &pts[k].im - &x.im,
                    };
                    l -= log2_abs(&diff, p as i64);
                }
            }
            l + 1e-9 // slack for the rounding of the logarithms
        })
        .collect()
}

fn symmetrise_and_certify(c: &[IBig], pts: &mut [G], p: usize) -> Option<Vec<DiskRoot>> {
    let lr = log2_radii(c, pts, p);
    let mut upper = Vec::new();
    let mut fin: Vec<G> = Vec::new();
    let mut lower = 0;
    for (x, l) in pts.iter().zip(&lr) {
        let im = log2_abs(
            &G {
                re: x.im.clone(),
                im: IBig::ZERO,
            },
            p as i64,
        );
        if im <= l + 1.0 {
            let mut r = G {
                re: x.re.clone(),
                im: IBig::ZERO,
            };
            for _ in 0..3 {
                let w = correction(c, std::slice::from_ref(&r), 0, p);
                if !w.re.is_finite() {
                    break;
                }
                r.re -= f64_to_fixed(w.re, p);
            }
            fin.push(r);
        } else if x.im > IBig::ZERO {
            upper.push(x.clone());
        } else {
            lower += 1;
        }
    }
    if upper.len() != lower {
        return None;
    }
    for u in upper {
        fin.push(G {
            re: u.re.clone(),
            im: -u.im.clone(),
        });
        fin.push(u);
    }
    let lr = log2_radii(c, &fin, p);
    let roots: Vec<DiskRoot> = fin
        .iter()
        .zip(&lr)
        .map(|(x, &l)| {
            let hi = g_to_c64(x, p as i64);
            let rest = G {
                re: &x.re - f64_to_fixed(hi.re, p),
                im: &x.im - f64_to_fixed(hi.im, p),
            };
            let lo = g_to_c64(&rest, p as i64);
            let z = Cdd {
                re: Dd {
                    hi: hi.re,
                    lo: lo.re,
                },
                im: Dd {
                    hi: hi.im,
                    lo: lo.im,
                },
            };
            let r = l.exp2().max(1e-300 * hi.norm());
            DiskRoot { z, r }
        })
        .collect();
    for (i, a) in roots.iter().enumerate() {
        let im = a.z.im.to_f64();
        if im != 0.0 && im.abs() <= a.r * (1.0 + 1e-12) {
            return None;
        }
        for (j, b) in roots[..i].iter().enumerate() {
            let diff = G {
                re: &fin[i].re - &fin[j].re,
                im: &fin[i].im - &fin[j].im,
            };
            let dist = g_to_c64(&diff, p as i64).norm() * (1.0 - 1e-12);
            if dist.is_nan() || dist <= (a.r + b.r) * (1.0 + 1e-12) {
                return None;
            }
        }
    }
    pts.clone_from_slice(&fin);
    Some(roots)
}
