//! Step 1b: splitting and scaling by the tropical roots, for coefficients of extreme range.
//!
//! The companion-matrix eigenvalues and every test after them evaluate the polynomial near its
//! roots; with coefficients like s³ − 1e308 s² + 1e100 (roots 1e308 and ±1e-104) the terms
//! overflow and the balancing and QR iteration break down. The magnitudes of the roots are
//! known in advance, to within a factor of about n, from the *tropical roots*: the slopes of the
//! upper convex hull of the points (i, log₂|aᵢ|) (i the power; Ostrowski, Newton polygon).
//! - Where two consecutive tropical roots are more than 2^[`SPLIT_BITS`] apart, the roots fall
//!   into two groups of very different size, and each group is, to below rounding level, the
//!   set of roots of the polynomial made of the coefficients between the two hull vertices
//!   that bound it (the omitted terms are smaller than the kept ones by that factor at every
//!   root of the group). The polynomial is split there.
//! - Each piece is rescaled, s = 2^c·σ with an exact power of two that centres its tropical
//!   roots on 1, and its coefficients are divided by the power of two of the largest one.
//!   The roots in σ are found by the usual steps and multiplied back by 2^c (exact).
//!
//! A polynomial whose roots already lie in a comfortable range (the usual case) is left
//! untouched: the steps run on it as given, bit for bit as before. A piece whose roots span
//! more than f64 arithmetic can resolve in one frame (no gap to split at) is refused with an
//! error naming the range.

use num_complex::Complex64;

use crate::error::{LtiError, Result};
use crate::numeric::balance::{exponent, ldexp};
use crate::poly::Poly;

/// Gap (in bits) between consecutive tropical roots at which the polynomial is split: the
/// terms left out of a piece are below 2⁻⁸⁰ of the kept ones at its roots, far below rounding.
pub const SPLIT_BITS: f64 = 80.0;

/// A polynomial whose tropical roots lie within 2^±`NATIVE_BITS` and whose coefficients lie
/// within 2^±`NATIVE_COEFF_BITS` is solved in its own frame, as given. (The acceptance tests
/// divide complex values of the size of its terms, whose squares must not underflow.)
const NATIVE_BITS: f64 = 128.0;
const NATIVE_COEFF_BITS: i32 = 400;

/// After centring, a piece's tropical roots must lie within 2^±`FRAME_BITS`: the QR iteration
/// multiplies two entries of that size.
const FRAME_BITS: f64 = 400.0;

/// A piece of the polynomial to solve on its own: its roots are those of `poly` times 2^`shift`.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Piece {
    pub(super) poly: Poly,
    pub(super) shift: i32,
}

/// A vertex of the upper hull: power and log₂|a|.
#[derive(Debug, Clone, Copy)]
struct Vertex {
    power: usize,
    log2: f64,
}

/// How to solve a polynomial without zero roots.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Plan {
    /// In its own frame, as given.
    Native,
    /// Piece by piece, each centred and normalised.
    Pieces(Vec<Piece>),
}

/// The plan for `q` (no zero roots): split at gaps of 2^[`SPLIT_BITS`] between tropical roots;
/// one piece in the native window is solved as given.
pub(super) fn plan(q: &Poly) -> Result<Plan> {
    let (hull, rho) = tropical(q);
    if rho.is_empty() {
        return Ok(Plan::Native);
    }
    let mut bounds = vec![0usize]; // indices into `hull` where pieces start/end
    for k in 1..rho.len() {
        if rho[k] - rho[k - 1] >= SPLIT_BITS {
            bounds.push(k);
        }
    }
    bounds.push(hull.len() - 1);
    let coeff_range = crate::numeric::balance::exponent_range(q.coeffs().iter().copied());
    let native = bounds.len() == 2
        && rho[0] >= -NATIVE_BITS
        && rho[rho.len() - 1] <= NATIVE_BITS
        && coeff_range.is_some_and(|(lo, hi)| lo >= -NATIVE_COEFF_BITS && hi <= NATIVE_COEFF_BITS);
    if native {
        return Ok(Plan::Native);
    }
    let c = q.coeffs();
    let n = q.degree();
    let mut out = Vec::with_capacity(bounds.len() - 1);
    for w in bounds.windows(2) {
        let (first, last) = (w[0], w[1]); // hull vertices bounding the piece
        out.push(piece(c, n, &hull[first..=last], rho[first], rho[last - 1])?);
    }
    Ok(Plan::Pieces(out))
}

/// The upper hull of (i, log₂|aᵢ|) and the log₂ of the tropical roots (increasing).
fn tropical(q: &Poly) -> (Vec<Vertex>, Vec<f64>) {
    let n = q.degree();
    let c = q.coeffs();
    // Ascending powers: a_i = c[n − i].
    let hull = upper_hull((0..=n).filter_map(|i| {
        let a = c[n - i];
        (a != 0.0).then(|| Vertex {
            power: i,
            log2: a.abs().log2(),
        })
    }));
    let rho = hull
        .windows(2)
        .map(|w| -(w[1].log2 - w[0].log2) / (w[1].power - w[0].power) as f64)
        .collect();
    (hull, rho)
}

/// The piece between two hull vertices, centred and normalised.
fn piece(c: &[f64], n: usize, hull: &[Vertex], lo: f64, hi: f64) -> Result<Piece> {
    let (p0, p1) = (hull[0].power, hull[hull.len() - 1].power);
    let mid = (0.5 * (lo + hi)).round();
    // a centre beyond ±2^20 bits (or not finite) is far outside f64 anyway
    if mid.is_nan() || mid.abs() > 1_048_576.0 {
        return Err(range_error(lo, hi, n));
    }
    let shift = mid as i32;
    let (clo, chi) = (lo - f64::from(shift), hi - f64::from(shift));
    if clo < -FRAME_BITS || chi > FRAME_BITS {
        return Err(range_error(lo, hi, n));
    }
    // Exponent of the largest scaled coefficient, so that it becomes ~1.
    let e_max = (p0..=p1)
        .filter_map(|i| exponent(c[n - i]).map(|e| e + shift * (i - p0) as i32))
        .max()
        .unwrap_or(0);
    // Descending coefficients of the piece: powers p1 down to p0.
    let coeffs: Vec<f64> = (p0..=p1)
        .rev()
        .map(|i| ldexp(c[n - i], shift * (i - p0) as i32 - e_max))
        .collect();
    // The end coefficients are hull vertices; if either fell out of the normal range the
    // piece spans more than one f64 frame.
    let ends = [coeffs[0], coeffs[coeffs.len() - 1]];
    if ends
        .iter()
        .any(|a| a.abs() < f64::MIN_POSITIVE || !a.is_finite())
    {
        return Err(range_error(lo, hi, n));
    }
    Ok(Piece {
        poly: Poly::trimmed(coeffs),
        shift,
    })
}

/// The error for roots spread beyond what one f64 frame resolves.
fn range_error(lo: f64, hi: f64, n: usize) -> LtiError {
    LtiError::invalid(format!(
        "the roots of the polynomial (order {n}) range over 2^{lo:.0} … 2^{hi:.0} in magnitude \
         with no gap to split at: beyond what f64 arithmetic can resolve"
    ))
}

/// Upper convex hull of points given in increasing `power` (monotone chain).
fn upper_hull(points: impl Iterator<Item = Vertex>) -> Vec<Vertex> {
    let mut hull: Vec<Vertex> = Vec::new();
    for p in points {
        while hull.len() >= 2 {
            let (a, b) = (hull[hull.len() - 2], hull[hull.len() - 1]);
            // b is on or below the chord a–p: not a vertex of the upper hull.
            let cross = (b.power - a.power) as f64 * (p.log2 - a.log2)
                - (b.log2 - a.log2) * (p.power - a.power) as f64;
            if cross >= 0.0 {
                hull.pop();
            } else {
                break;
            }
        }
        hull.push(p);
    }
    hull
}

/// Multiplies a root found in a piece's frame back by 2^shift (exact unless it overflows).
pub(super) fn unscale(z: Complex64, shift: i32) -> Complex64 {
    if shift == 0 {
        return z;
    }
    Complex64::new(ldexp(z.re, shift), ldexp(z.im, shift))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(c: &[f64]) -> Poly {
        Poly::from_descending(c).unwrap()
    }

    #[test]
    fn ordinary_polynomials_are_left_alone() {
        for c in [
            &[1.0, 3.0, 2.0][..],
            &[1e-17, 1.0, 3.0, 2.0],
            &[1.0, 2e3, 1e6],
        ] {
            assert_eq!(plan(&p(c)).unwrap(), Plan::Native);
        }
    }

    #[test]
    fn a_wide_gap_splits() {
        // s³ − 1e308 s² + 1e100: one root near 1e308, two near ±1e-104.
        let Plan::Pieces(ps) = plan(&p(&[1.0, -1e308, 0.0, 1e100])).unwrap() else {
            panic!("not split")
        };
        assert_eq!(ps.len(), 2);
        assert_eq!(ps[0].poly.degree(), 2);
        assert_eq!(ps[1].poly.degree(), 1);
        assert!(ps[0].shift < -300 && ps[1].shift > 1000, "{ps:?}");
    }

    #[test]
    fn tiny_coefficients_are_normalised() {
        let Plan::Pieces(ps) = plan(&p(&[1e-300, 3e-300, 2e-300])).unwrap() else {
            panic!("not scaled")
        };
        assert_eq!(ps.len(), 1);
        assert!(
            ps[0]
                .poly
                .coeffs()
                .iter()
                .all(|c| (0.1..=4.0).contains(&c.abs()))
        );
    }
}
