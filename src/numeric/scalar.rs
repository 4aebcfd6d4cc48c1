//! Scalar root finding: Brent's method on a sign-changing bracket.
//!
//! Step metrics, margins and bandwidth all reduce to "where does this smooth function cross
//! this level"; they find a bracket on a grid and then call [`brent`], so the answer is exact
//! to the tolerance, not to the grid spacing.

use crate::error::{LtiError, Result};

/// A bracket `[a, b]` with function values of opposite sign (or one of them zero).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bracket {
    /// Left end.
    pub a: f64,
    /// Right end.
    pub b: f64,
    /// f(a).
    pub fa: f64,
    /// f(b).
    pub fb: f64,
}

/// Brent's method (inverse quadratic interpolation with bisection safeguard).
///
/// Returns x in the bracket with |x − x*| ≤ `xtol` (plus 4·eps·|x|). The bracket must change sign.
#[allow(clippy::float_cmp)] // `a == c`: the same bracket end, as in Brent's algorithm
pub fn brent(f: impl Fn(f64) -> f64, bracket: Bracket, xtol: f64) -> Result<f64> {
    let Bracket {
        mut a,
        mut b,
        mut fa,
        mut fb,
    } = bracket;
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    if !(fa.is_finite() && fb.is_finite()) || fa.signum() == fb.signum() {
        return Err(LtiError::invalid(format!(
            "root bracket [{a}, {b}] does not change sign (f = {fa}, {fb})"
        )));
    }
    let mut c = a;
    let mut fc = fa;
    let mut d = b - a;
    let mut e = d;
    const MAX_ITER: usize = 200;
    for _ in 0..MAX_ITER {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol = 2.0 * f64::EPSILON * b.abs() + 0.5 * xtol;
        let m = 0.5 * (c - b);
        if m.abs() <= tol || fb == 0.0 {
            return Ok(b);
        }
        if e.abs() >= tol && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                let qa = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * m * qa * (qa - r) - (b - a) * (r - 1.0));
                q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol { d } else { tol.copysign(m) };
        fb = f(b);
        if !fb.is_finite() {
            return Err(LtiError::invalid(format!("function is {fb} at x = {b}")));
        }
    }
    Err(LtiError::NoConvergence {
        what: "Brent root finder".into(),
        iterations: MAX_ITER,
    })
}

/// Finds every sign change of `f` on the sorted grid `xs` (values `fs`) and refines each with
/// [`brent`]. Grid points where f is exactly zero are returned as they are.
pub fn all_crossings(f: impl Fn(f64) -> f64, xs: &[f64], fs: &[f64], xtol: f64) -> Vec<f64> {
    let mut out = Vec::new();
    for i in 0..xs.len().saturating_sub(1) {
        let (fa, fb) = (fs[i], fs[i + 1]);
        if fa == 0.0 {
            if out.last() != Some(&xs[i]) {
                out.push(xs[i]);
            }
            continue;
        }
        if fb != 0.0 && fa.signum() != fb.signum() && fa.is_finite() && fb.is_finite() {
            let br = Bracket {
                a: xs[i],
                b: xs[i + 1],
                fa,
                fb,
            };
            if let Ok(x) = brent(&f, br, xtol) {
                out.push(x);
            }
        }
    }
    if let (Some(&x), Some(&fx)) = (xs.last(), fs.last())
        && fx == 0.0
        && out.last() != Some(&x)
    {
        out.push(x);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `brent` on a worked example (an internal kernel: a unit test, not a doctest).
    #[test]
    #[allow(clippy::float_cmp)] // exact values are meant
    fn brent_example() {
        use crate::numeric::scalar::{Bracket, brent};
        let f = |x: f64| x * x - 2.0;
        let r = brent(
            f,
            Bracket {
                a: 0.0,
                b: 2.0,
                fa: -2.0,
                fb: 2.0,
            },
            1e-15,
        )
        .unwrap();
        assert!((r - 2f64.sqrt()).abs() < 1e-14);
    }

    #[test]
    fn brent_finds_cos_root() {
        let r = brent(
            f64::cos,
            Bracket {
                a: 1.0,
                b: 2.0,
                fa: 1f64.cos(),
                fb: 2f64.cos(),
            },
            1e-15,
        )
        .unwrap();
        assert!((r - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    }

    #[test]
    fn brent_rejects_non_bracket() {
        let e = brent(
            |x| x * x + 1.0,
            Bracket {
                a: -1.0,
                b: 1.0,
                fa: 2.0,
                fb: 2.0,
            },
            1e-12,
        );
        assert!(e.is_err());
    }

    #[test]
    fn all_crossings_of_sine() {
        let xs: Vec<f64> = (0..=100).map(|i| 0.1 + i as f64 * 0.1).collect();
        let fs: Vec<f64> = xs.iter().map(|x| x.sin()).collect();
        let r = all_crossings(f64::sin, &xs, &fs, 1e-14);
        assert_eq!(r.len(), 3);
        for (k, x) in r.iter().enumerate() {
            assert!((x - (k + 1) as f64 * std::f64::consts::PI).abs() < 1e-12);
        }
    }
}
