//! The maps of roots under sampling, shared by the matrices' c2d/d2c (the lti layer) and the
//! factored form's (the analysis layer): ZOH z = e^(pT) and its preimage, the matched
//! pole-zero rule, the Tustin map and its inverse — each exact for conjugates (a root below the
//! axis maps to the conjugate of its upper twin's image).

use num_complex::Complex64;

use crate::error::{LtiError, Result};
use crate::fmt::fmt_num;
use crate::poly::Root;

/// e^(pT), with the exact conjugate for a root below the axis and a real result for a real
/// root.
pub(crate) fn zoh_root(p: Complex64, dt: f64) -> Complex64 {
    if p.im < 0.0 {
        return zoh_root(p.conj(), dt).conj();
    }
    if p.im == 0.0 {
        return Complex64::new((p.re * dt).exp(), 0.0);
    }
    let r = (p.re * dt).exp();
    let (s, c) = (p.im * dt).sin_cos();
    Complex64::new(r * c, r * s)
}

/// e^(pT) − 1 without cancellation (for p·T near 0).
fn expm1_complex(x: Complex64) -> Complex64 {
    if x.im == 0.0 {
        return Complex64::new(x.re.exp_m1(), 0.0);
    }
    let half = (0.5 * x.im).sin();
    // e^a cos b − 1 = expm1(a)·cos b − 2 sin²(b/2)
    Complex64::new(
        x.re.exp_m1() * x.im.cos() - 2.0 * half * half,
        x.re.exp() * x.im.sin(),
    )
}

/// The principal logarithm ln(z)/T of a discrete pole, or the error that it has none under
/// ZOH (z = 0 or on the negative real axis).
pub(crate) fn zoh_preimage(z: Complex64, dt: f64) -> Result<Complex64> {
    if (z.im == 0.0 && z.re <= 0.0) || z.norm() == 0.0 {
        return Err(LtiError::NoPreimage {
            method: "d2c (zoh)".into(),
            re: z.re,
            im: z.im,
            reason: "e^(sT) is never 0 nor a negative real number".into(),
        });
    }
    if z.im < 0.0 {
        return Ok(zoh_preimage(z.conj(), dt)?.conj());
    }
    if z.im == 0.0 {
        return Ok(Complex64::new(z.re.ln() / dt, 0.0));
    }
    Ok(z.ln() / dt)
}

/// `roots` mapped by `f` (multiplicities kept), sorted.
pub(crate) fn map_roots(
    roots: &[Root],
    mut f: impl FnMut(Complex64) -> Result<Complex64>,
) -> Result<Vec<Root>> {
    let mut out = roots
        .iter()
        .map(|r| Ok(Root::new(f(r.value)?, r.multiplicity)))
        .collect::<Result<Vec<_>>>()?;
    crate::poly::roots::sort_roots(&mut out);
    Ok(out)
}

fn count(roots: &[Root]) -> usize {
    roots.iter().map(|r| r.multiplicity).sum()
}

/// Zeros, poles and gain of a discrete G(z) = k·Π(z − ζ)/Π(z − π).
pub(crate) type Zpk = (Vec<Root>, Vec<Root>, f64);

/// The matched pole-zero map of G(s) = k·Π(s − zᵢ)/Π(s − pⱼ) at period `dt`, as MATLAB's
/// `c2d(sys, T, 'matched')`:
/// - poles e^(pT) and finite zeros e^(zT), multiplicities kept;
/// - the zeros at infinity (relative degree r) go to z = −1 except one, so that a strictly
///   proper G(s) gives a strictly proper G(z) (one sample of delay): r − 1 zeros at −1. This is
///   the "modified" matched pole-zero method of Franklin, Powell & Workman (Digital Control of
///   Dynamic Systems, §6.3.3), which MATLAB implements: `c2d(tf(11, [1 1 0]), 0.1, 'matched')`
///   is 0.052339 (z + 1)/((z − 1)(z − 0.9048)) (MATLAB Answers 2175248, "One zero is missing
///   in the result of c2d function uses 'matched'");
/// - the gain matched at low frequency: lim s→0 s^k·G(s) = lim z→1 ((z − 1)/T)^k·G(z), k the
///   number of poles minus zeros at s = 0 (which map to z = 1): the dc gain for k = 0, the
///   integrators' asymptote otherwise (it reproduces MATLAB's 0.052339 above).
///
/// Errors: more zeros than poles, a root other than 0 that maps onto z = 1 (aliasing: no
/// low frequency to match at), a gain beyond f64.
pub(crate) fn matched_zpk(zeros: &[Root], poles: &[Root], gain: f64, dt: f64) -> Result<Zpk> {
    let (nz, np) = (count(zeros), count(poles));
    if nz > np {
        return Err(LtiError::Improper {
            operation: "the matched pole-zero map".into(),
            required: "proper".into(),
            num_degree: nz,
            den_degree: np,
            limit: np,
        });
    }
    let at_minus_one = if np > nz { np - nz - 1 } else { 0 };
    let mut zd = map_roots(zeros, |z| Ok(zoh_root(z, dt)))?;
    if at_minus_one > 0 {
        zd.push(Root::new(Complex64::new(-1.0, 0.0), at_minus_one));
        crate::poly::roots::sort_roots(&mut zd);
    }
    let pd = map_roots(poles, |p| Ok(zoh_root(p, dt)))?;
    // k_d = K_s·T^κ·Π'(1 − πⱼ) / (Π'(1 − ζᵢ)·2^m), K_s = k·Π'(−zᵢ)/Π'(−pⱼ) (' : roots ≠ 0,
    // κ = poles minus zeros at 0)
    let mut ratio = Complex64::new(gain, 0.0);
    let factor = |r: &Root, numerator: bool, ratio: &mut Complex64| -> Result<()> {
        if r.value == Complex64::new(0.0, 0.0) {
            // s = 0 ↔ z = 1: counted by the power of T below
            return Ok(());
        }
        let x = r.value * dt;
        let one_minus = -expm1_complex(x);
        if one_minus.norm() <= 64.0 * f64::EPSILON * x.norm() {
            return Err(LtiError::Undefined {
                what: "the matched pole-zero gain".into(),
                reason: format!(
                    "the root s = {} maps onto z = 1 at dt = {} (aliasing): there is no low frequency to match the gain at",
                    crate::error::complex_number(r.value.re, r.value.im),
                    fmt_num(dt)
                ),
            });
        }
        // (−r)/(1 − e^(rT)) per zero, its inverse per pole; (−r)·T/(1 − e^(rT)) → 1 as r → 0
        let f = -x / one_minus;
        let m = r.multiplicity as i32;
        *ratio *= if numerator { f.powi(m) } else { f.powi(-m) };
        Ok(())
    };
    for z in zeros {
        factor(z, true, &mut ratio)?;
    }
    for p in poles {
        factor(p, false, &mut ratio)?;
    }
    // with f(r) = −rT/(1 − e^(rT)): k_d = k·2^(−m)·T^(np − nz)·Π'f(zᵢ)/Π'f(pⱼ)
    let t_power = np as i32 - nz as i32;
    let kd = ratio.re * dt.powi(t_power) / 2f64.powi(at_minus_one as i32);
    if !kd.is_finite() {
        return Err(LtiError::NonFinite {
            what: "the matched pole-zero gain".into(),
            value: kd,
        });
    }
    Ok((zd, pd, kd))
}

/// The Tustin map of G(s) = k·Π(s − zᵢ)/Π(s − pⱼ) with s = (1/h)(z − 1)/(z + 1): roots
/// (1 + hr)/(1 − hr), the zeros at infinity to z = −1, gain k·h^(np − nz)·Π(1 − hzᵢ)/Π(1 − hpⱼ).
///
/// Errors: more zeros than poles, a root at s = 1/h (it maps to z = ∞).
pub(crate) fn tustin_zpk(zeros: &[Root], poles: &[Root], gain: f64, h: f64) -> Result<Zpk> {
    let (nz, np) = (count(zeros), count(poles));
    if nz > np {
        return Err(LtiError::Improper {
            operation: "the Tustin map".into(),
            required: "proper".into(),
            num_degree: nz,
            den_degree: np,
            limit: np,
        });
    }
    let one = Complex64::new(1.0, 0.0);
    let mut ratio = Complex64::new(gain, 0.0);
    let mut image = |r: &Root, numerator: bool| -> Result<Root> {
        let hr = r.value * h;
        let den = one - hr;
        if den.norm() <= 4.0 * f64::EPSILON * hr.norm().max(1.0) {
            return Err(LtiError::Undefined {
                what: "the Tustin map".into(),
                reason: format!(
                    "the root s = {} maps to z = ∞ (s = 1/h = {})",
                    crate::error::complex_number(r.value.re, r.value.im),
                    fmt_num(1.0 / h)
                ),
            });
        }
        let m = r.multiplicity as i32;
        ratio *= if numerator { den.powi(m) } else { den.powi(-m) };
        let z = conj_map(r.value, |v| Ok((one + v * h) / (one - v * h)))?;
        Ok(Root::new(z, r.multiplicity))
    };
    let mut zd = zeros
        .iter()
        .map(|r| image(r, true))
        .collect::<Result<Vec<_>>>()?;
    let mut pd = poles
        .iter()
        .map(|r| image(r, false))
        .collect::<Result<Vec<_>>>()?;
    if np > nz {
        zd.push(Root::new(Complex64::new(-1.0, 0.0), np - nz));
    }
    crate::poly::roots::sort_roots(&mut zd);
    crate::poly::roots::sort_roots(&mut pd);
    let kd = ratio.re * h.powi((np - nz) as i32);
    finite_gain(kd, "the Tustin map's gain")?;
    Ok((zd, pd, kd))
}

/// The inverse Tustin map of G(z) = k·Π(z − ζᵢ)/Π(z − πⱼ) with z = (1 + hs)/(1 − hs): roots
/// (ζ − 1)/(h(ζ + 1)); zeros at z = −1 go to infinity; np − nz zeros at s = 1/h; gain
/// k·(−1)^(np − nz)·(2/h)^c·Π'(1 + ζᵢ)/Π(1 + πⱼ) (c zeros at −1, Π' over the others).
///
/// Errors: a pole at z = −1 (it has no preimage), more zeros than poles.
pub(crate) fn tustin_zpk_inverse(zeros: &[Root], poles: &[Root], gain: f64, h: f64) -> Result<Zpk> {
    let (nz, np) = (count(zeros), count(poles));
    if nz > np {
        return Err(LtiError::Improper {
            operation: "the inverse Tustin map".into(),
            required: "proper".into(),
            num_degree: nz,
            den_degree: np,
            limit: np,
        });
    }
    let one = Complex64::new(1.0, 0.0);
    let at_minus_one = |v: Complex64| (v + one).norm() <= 4.0 * f64::EPSILON * v.norm().max(1.0);
    let mut ratio = Complex64::new(gain * if (np - nz) % 2 == 1 { -1.0 } else { 1.0 }, 0.0);
    let mut zc = Vec::new();
    for r in zeros {
        let m = r.multiplicity as i32;
        if at_minus_one(r.value) {
            ratio *= (2.0 / h).powi(m);
            continue;
        }
        ratio *= (r.value + one).powi(m);
        let s = conj_map(r.value, |v| Ok((v - one) / ((v + one) * h)))?;
        zc.push(Root::new(s, r.multiplicity));
    }
    let mut pc = Vec::new();
    for r in poles {
        if at_minus_one(r.value) {
            return Err(LtiError::NoPreimage {
                method: "d2c (tustin)".into(),
                re: r.value.re,
                im: r.value.im,
                reason: "the Tustin map sends no finite s to z = −1".into(),
            });
        }
        ratio /= (r.value + one).powi(r.multiplicity as i32);
        let s = conj_map(r.value, |v| Ok((v - one) / ((v + one) * h)))?;
        pc.push(Root::new(s, r.multiplicity));
    }
    if np > nz {
        zc.push(Root::new(Complex64::new(1.0 / h, 0.0), np - nz));
    }
    crate::poly::roots::sort_roots(&mut zc);
    crate::poly::roots::sort_roots(&mut pc);
    let kc = ratio.re;
    finite_gain(kc, "the inverse Tustin map's gain")?;
    Ok((zc, pc, kc))
}

/// The Tustin image (1 + hs)/(1 − hs) of a root (exact conjugates, real for a real root).
pub(crate) fn tustin_root(s: Complex64, h: f64) -> Result<Complex64> {
    let one = Complex64::new(1.0, 0.0);
    conj_map(s, |v| Ok((one + v * h) / (one - v * h)))
}

/// The inverse Tustin image (z − 1)/(h(z + 1)) of a root.
pub(crate) fn tustin_preimage(z: Complex64, h: f64) -> Result<Complex64> {
    let one = Complex64::new(1.0, 0.0);
    if (z + one).norm() <= 4.0 * f64::EPSILON * z.norm().max(1.0) {
        return Err(LtiError::NoPreimage {
            method: "d2c (tustin)".into(),
            re: z.re,
            im: z.im,
            reason: "the Tustin map sends no finite s to z = −1".into(),
        });
    }
    conj_map(z, |v| Ok((v - one) / ((v + one) * h)))
}

/// `f(v)` with conjugate symmetry made exact: the conjugate of f(v̄) below the axis, a real
/// result for a real v.
fn conj_map(v: Complex64, mut f: impl FnMut(Complex64) -> Result<Complex64>) -> Result<Complex64> {
    if v.im < 0.0 {
        return Ok(f(v.conj())?.conj());
    }
    let w = f(v)?;
    Ok(if v.im == 0.0 {
        Complex64::new(w.re, 0.0)
    } else {
        w
    })
}

fn finite_gain(k: f64, what: &str) -> Result<()> {
    if k.is_finite() {
        Ok(())
    } else {
        Err(LtiError::NonFinite {
            what: what.into(),
            value: k,
        })
    }
}
