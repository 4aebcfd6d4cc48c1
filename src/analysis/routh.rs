//! The Routh–Hurwitz table of a polynomial: the number of roots in the open right half plane
//! from the sign changes of its first column, with the two special cases.
//!
//! - **A zero first element** (the rest of its row not all zero): replaced by a small ε > 0
//!   (ε = [`ZERO_REL_TOL`] times the largest magnitude in the table so far), and the signs
//!   are read for ε → 0⁺.
//! - **A row of zeros**: the polynomial has roots symmetric about the origin, those of the
//!   *auxiliary polynomial* formed from the row above (powers n − k, n − k − 2, …); the zero row
//!   is replaced by the coefficients of its derivative. The auxiliary polynomial of degree q
//!   has r right-half-plane roots (the sign changes from its row on), as many left-half-plane
//!   ones, and q − 2r on the imaginary axis.
//!
//! The table is computed in f64; the verdict is checked in `tests/routh.rs` against the roots.

use serde::Serialize;

use crate::error::{LtiError, Result};
use crate::numeric::tol::ZERO_REL_TOL;
use crate::poly::Poly;

/// A special case met while building the table.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum RouthEvent {
    /// The first element of the row of s^power was 0 and was replaced by ε.
    ZeroFirstElement {
        /// The power of s labelling the row.
        power: usize,
        /// The ε used.
        epsilon: f64,
    },
    /// The row of s^power was all zeros: the auxiliary polynomial (descending coefficients,
    /// from the row above) divides the polynomial; the row became its derivative.
    ZeroRow {
        /// The power of s labelling the zero row.
        power: usize,
        /// The auxiliary polynomial, descending powers.
        auxiliary: Vec<f64>,
        /// Its roots on the imaginary axis.
        axis_roots: usize,
    },
}

/// The Routh table and what it says.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RouthTable {
    /// Rows from s^n down to s^0 (padded with zeros to one width).
    pub rows: Vec<Vec<f64>>,
    /// The power of s labelling each row.
    pub powers: Vec<usize>,
    /// Special cases, in the order met.
    pub events: Vec<RouthEvent>,
    /// Roots in the open right half plane (sign changes of the first column).
    pub rhp: usize,
    /// Roots on the imaginary axis (from auxiliary polynomials).
    pub axis: usize,
    /// Roots in the open left half plane.
    pub lhp: usize,
}

/// The Routh–Hurwitz table of `p` (degree ≥ 1).
///
/// ```
/// use ltikit::Poly;
/// use ltikit::analysis::routh;
/// // s³ + s² + 2s + 8 = (s + 2)(s² − s + 4): two right-half-plane roots.
/// let t = routh(&Poly::from_descending(&[1.0, 1.0, 2.0, 8.0]).unwrap()).unwrap();
/// assert_eq!((t.rhp, t.axis, t.lhp), (2, 0, 1));
/// ```
pub fn routh(p: &Poly) -> Result<RouthTable> {
    let c = p.coeffs();
    let n = p.degree();
    if n == 0 || c.iter().all(|x| *x == 0.0) {
        return Err(LtiError::invalid(
            "the Routh table needs a polynomial of degree ≥ 1",
        ));
    }
    // Roots at s = 0 (trailing zero coefficients) are on the axis; the table is built for the
    // rest.
    let zeros_at_origin = c.iter().rev().take_while(|x| **x == 0.0).count();
    let c = &c[..c.len() - zeros_at_origin];
    let m = c.len() - 1;
    let width = m / 2 + 1;
    let sign = if c[0] < 0.0 { -1.0 } else { 1.0 };
    let row_of = |start: usize| -> Vec<f64> {
        (0..width)
            .map(|j| c.get(start + 2 * j).map_or(0.0, |x| sign * x))
            .collect()
    };
    let mut rows = vec![row_of(0)];
    if m >= 1 {
        rows.push(row_of(1));
    }
    let mut events = Vec::new();
    let mut axis = zeros_at_origin;
    let mut scale = c.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    for i in 1..=m {
        // Make row i usable: a zero row, or a zero first element.
        let big = rows[i].iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let tol = ZERO_REL_TOL * scale;
        if big <= tol {
            let power = m - i;
            let above = m - i + 1;
            let aux: Vec<f64> = (0..=above)
                .map(|k| {
                    if k % 2 == 0 {
                        rows[i - 1].get(k / 2).copied().unwrap_or(0.0)
                    } else {
                        0.0
                    }
                })
                .collect();
            rows[i] = (0..width)
                .map(|j| {
                    let k = 2 * j;
                    aux.get(k).map_or(0.0, |a| a * (above - k) as f64)
                })
                .collect();
            events.push(RouthEvent::ZeroRow {
                power,
                auxiliary: aux,
                axis_roots: 0, // filled in below
            });
        } else if rows[i][0].abs() <= tol {
            let epsilon = tol.max(f64::MIN_POSITIVE);
            rows[i][0] = epsilon;
            events.push(RouthEvent::ZeroFirstElement {
                power: m - i,
                epsilon,
            });
        }
        scale = scale.max(rows[i].iter().fold(0.0f64, |a, x| a.max(x.abs())));
        if i == m {
            break;
        }
        let (r0, r1) = (&rows[i - 1], &rows[i]);
        let next: Vec<f64> = (0..width)
            .map(|j| {
                let a = r0.get(j + 1).copied().unwrap_or(0.0);
                let b = r1.get(j + 1).copied().unwrap_or(0.0);
                (r1[0] * a - r0[0] * b) / r1[0]
            })
            .collect();
        if next.iter().any(|x| !x.is_finite()) {
            return Err(LtiError::invalid(
                "the Routh table overflows for these coefficients",
            ));
        }
        rows.push(next);
    }
    let first: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let changes = |from: usize| {
        first[from..]
            .windows(2)
            .filter(|w| (w[0] < 0.0) != (w[1] < 0.0))
            .count()
    };
    let rhp = changes(0);
    // Each auxiliary polynomial of degree q: r RHP roots (sign changes from its row on), r LHP
    // and q − 2r on the axis. Below the first zero row the table is that of the first
    // auxiliary polynomial, so a later zero row (repeated axis roots, e.g. (s² + 1)²) belongs
    // to a divisor of it: its roots are among the first's and are not counted again.
    let mut counted = false;
    for e in &mut events {
        if let RouthEvent::ZeroRow {
            power,
            auxiliary,
            axis_roots,
            ..
        } = e
        {
            let q = auxiliary.len() - 1;
            let row = m - (*power + 1);
            let r = changes(row);
            *axis_roots = q.saturating_sub(2 * r);
            if !counted {
                axis += *axis_roots;
                counted = true;
            }
        }
    }
    let powers = (0..rows.len()).map(|i| m - i).collect();
    Ok(RouthTable {
        rows,
        powers,
        events,
        rhp,
        axis,
        lhp: n.saturating_sub(rhp + axis),
    })
}

/// The gains K for which D + K·N (unity negative feedback around K·N/D) has every root in the
/// open left half plane, as open intervals (lo, hi) (±∞ allowed), increasing.
///
/// The ends are the gains at which a closed-loop root crosses the imaginary axis — K =
/// −D(jω)/N(jω) at the real ω ≥ 0 where Im(D(jω)·conj N(jω)) = 0, a polynomial in ω — and the
/// gain at which the degree drops; each interval between consecutive ends is decided by the
/// Routh table at an interior gain.
///
/// ```
/// use ltikit::Poly;
/// use ltikit::analysis::routh::stable_gains;
/// // 1/(s(s + 1)(s + 2)): stable for 0 < K < 6 (the locus crosses the axis at ±j√2, K = 6).
/// let n = Poly::from_descending(&[1.0]).unwrap();
/// let d = Poly::from_descending(&[1.0, 3.0, 2.0, 0.0]).unwrap();
/// let k = stable_gains(&n, &d).unwrap();
/// assert_eq!(k.len(), 1);
/// assert!(k[0].0.abs() < 1e-12 && (k[0].1 - 6.0).abs() < 1e-12);
/// ```
pub fn stable_gains(num: &Poly, den: &Poly) -> Result<Vec<(f64, f64)>> {
    if num.coeffs().iter().all(|x| *x == 0.0) {
        return Err(LtiError::invalid(
            "the loop has a zero numerator: no gain acts",
        ));
    }
    if num.degree() > den.degree() {
        return Err(LtiError::invalid(
            "the loop is improper (numerator degree above the denominator's)",
        ));
    }
    let mut ends: Vec<f64> = axis_crossings(num, den)?.into_iter().map(|c| c.1).collect();
    if num.degree() == den.degree() {
        ends.push(-den.coeffs()[0] / num.coeffs()[0]);
    }
    ends.retain(|k| k.is_finite());
    ends.sort_by(f64::total_cmp);
    ends.dedup_by(|a, b| (*a - *b).abs() <= ZERO_REL_TOL * a.abs().max(b.abs()).max(1.0));
    let mut bounds = vec![f64::NEG_INFINITY];
    bounds.extend(&ends);
    bounds.push(f64::INFINITY);
    let stable_at = |k: f64| -> Result<bool> {
        let q = &den.clone() + &num.scale(k);
        if q.degree() < den.degree() {
            return Ok(false);
        }
        let t = routh(&q)?;
        Ok(t.rhp == 0 && t.axis == 0)
    };
    let mut out: Vec<(f64, f64)> = Vec::new();
    for w in bounds.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        let mid = match (lo.is_finite(), hi.is_finite()) {
            (true, true) => 0.5 * (lo + hi),
            (false, true) => hi - hi.abs().max(1.0),
            (true, false) => lo + lo.abs().max(1.0),
            (false, false) => 0.0,
        };
        if stable_at(mid)? {
            match out.last_mut() {
                // the same bound, copied: adjacent stable intervals merge
                Some(last) if last.1.to_bits() == lo.to_bits() => last.1 = hi,
                _ => out.push((lo, hi)),
            }
        }
    }
    Ok(out)
}

/// Where D + K·N has a root on the imaginary axis: the pairs (ω, K) with ω ≥ 0 real and K
/// real (of either sign) such that D(jω) + K·N(jω) = 0, increasing in ω. Found as the real
/// roots of Im(D(jω)·conj N(jω)) — a polynomial in ω — with K = −D(jω)/N(jω) there (ω = 0
/// included, when N(0) ≠ 0).
///
/// ```
/// use ltikit::Poly;
/// use ltikit::analysis::routh::axis_crossings;
/// // 1/(s(s + 1)(s + 2)): s = ±j√2 at K = 6, and s = 0 at K = 0.
/// let n = Poly::from_descending(&[1.0]).unwrap();
/// let d = Poly::from_descending(&[1.0, 3.0, 2.0, 0.0]).unwrap();
/// let c = axis_crossings(&n, &d).unwrap();
/// assert_eq!(c.len(), 2);
/// assert!(c[0].0 == 0.0 && c[0].1.abs() < 1e-15);
/// assert!((c[1].0 - 2f64.sqrt()).abs() < 1e-14 && (c[1].1 - 6.0).abs() < 1e-13);
/// ```
pub fn axis_crossings(num: &Poly, den: &Poly) -> Result<Vec<(f64, f64)>> {
    if num.is_zero() {
        return Ok(Vec::new());
    }
    // D(jω) = Dr(ω) + j·Di(ω) and likewise N; P(ω) = Di·Nr − Dr·Ni.
    let parts = |p: &Poly| -> Result<(Poly, Poly)> {
        let c = p.coeffs();
        let n = c.len() - 1;
        let mut re = vec![0.0; n + 1];
        let mut im = vec![0.0; n + 1];
        for (i, &a) in c.iter().enumerate() {
            let k = n - i;
            match k % 4 {
                0 => re[i] = a,
                1 => im[i] = a,
                2 => re[i] = -a,
                _ => im[i] = -a,
            }
        }
        Ok((Poly::from_descending(&re)?, Poly::from_descending(&im)?))
    };
    let (dr, di) = parts(den)?;
    let (nr, ni) = parts(num)?;
    let p = &(&di * &nr) + &(&dr * &ni).scale(-1.0);
    if p.is_zero() || p.degree() == 0 {
        // N and D in phase at every ω (e.g. N = 1, D = s² + 1: roots on the axis for a whole
        // range of K): no isolated crossing. (P is odd in ω, so a nonzero constant P cannot
        // occur.)
        return Ok(Vec::new());
    }
    // P is odd: ω = 0 is always among its roots.
    let mut omegas: Vec<f64> = Vec::new();
    for r in p.roots()? {
        let w = r.value;
        if w.re >= 0.0 && w.im.abs() <= ZERO_REL_TOL.sqrt() * w.norm().max(1.0) {
            omegas.push(w.re);
        }
    }
    omegas.sort_by(f64::total_cmp);
    omegas.dedup();
    let mut out = Vec::new();
    for w in omegas {
        let s = num_complex::Complex64::new(0.0, w);
        let nv = num.eval_complex(s);
        if nv.norm() > 0.0 {
            let k = -(den.eval_complex(s) / nv).re;
            if k.is_finite() {
                out.push((w, k));
            }
        }
    }
    Ok(out)
}
