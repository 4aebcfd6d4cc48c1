//! The Jury table of a polynomial in z — the discrete-time Routh table — and the gains that
//! keep a sampled loop stable.
//!
//! **The table** (Jury's test in the form of Åström & Wittenmark, *Computer-Controlled
//! Systems*, 3rd ed., §3.2, Theorem 3.2, after Raible): with A(z) = a₀zⁿ + … + aₙ (a₀ > 0),
//! each stage k = n, n − 1, …, 1 writes the coefficients a₀ᵏ … aₖᵏ and their reverse, forms
//! αₖ = aₖᵏ/a₀ᵏ and the next stage aᵢᵏ⁻¹ = aᵢᵏ − αₖ·aₖ₋ᵢᵏ. Every root lies strictly inside
//! the unit circle iff a₀ᵏ > 0 for k = 0 … n − 1; when no a₀ᵏ is 0, the number of negative a₀ᵏ
//! is the number of roots outside. A zero a₀ᵏ (|αₖ₊₁| = 1: roots on the circle, or roots in
//! pairs z, 1/z̄) is the *singular case*: the table stops and the counts come from the bilinear
//! map w = (z − 1)/(z + 1) and the Routh table of the image.
//!
//! **Exactly**: [`JuryTable::exact`] holds the counts decided in rational arithmetic
//! ([`ExactPoly::unit_circle_counts`]: the bilinear map and the exact half-plane counts, no
//! singular case), for the coefficients as typed ([`jury_exact`]) or for the binary values of
//! the f64 coefficients ([`jury`]).
//!
//! **Stable gains** ([`discrete_stable_gains`]): the K for which every root of D(z) + K·N(z)
//! is strictly inside the unit circle. A root crosses the circle at z = 1 (K = −D(1)/N(1)),
//! at z = −1 (K = −D(−1)/N(−1)) or as a pair e^(±jθ), and escapes through infinity at
//! K = −d₀/n₀ when deg N = deg D; the pairs are the imaginary-axis crossings of the bilinear
//! images (w = j·tan(θ/2), [`circle_crossings`]). Each interval between consecutive
//! boundaries is decided exactly at a rational gain inside it.

use num_complex::Complex64;
use serde::Serialize;

use super::routh::{axis_crossings, routh};
use crate::error::{LtiError, Result};
use crate::numeric::tol::ZERO_REL_TOL;
use crate::poly::Poly;
use crate::poly::exact::{CircleCounts, ExactPoly, Rational};

/// The Jury table and what it says.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JuryTable {
    /// Two rows per stage k = n … 1 (the coefficients a₀ᵏ … aₖᵏ, then reversed), then the
    /// last row a₀⁰; the polynomial is normalised to a₀ > 0. Shorter when the table is singular.
    pub rows: Vec<Vec<f64>>,
    /// αₖ = aₖᵏ/a₀ᵏ for k = n, n − 1, … (one per stage computed).
    pub alphas: Vec<f64>,
    /// The first elements a₀ᵏ for k = n, n − 1, …, 0 (as far as computed).
    pub first: Vec<f64>,
    /// The stage k at which a₀ᵏ vanished (to the relative tolerance 1e-12 of the table), when
    /// the table is singular: its counts then come from the bilinear map.
    pub singular_at: Option<usize>,
    /// Roots strictly inside the unit circle (from the table; the bilinear map when singular).
    pub inside: usize,
    /// Roots on the unit circle.
    pub on: usize,
    /// Roots strictly outside the unit circle.
    pub outside: usize,
    /// The counts in exact rational arithmetic (`None` beyond the exact path's budget).
    pub exact: Option<CircleCounts>,
}

impl JuryTable {
    /// The counts that decide: the exact ones when they exist, else the table's.
    ///
    /// ```
    /// use ltikit::Poly;
    /// use ltikit::analysis::jury;
    /// let t = jury(&Poly::from_descending(&[1.0, 0.0, 1.0]).unwrap()).unwrap();
    /// assert_eq!(t.counts().on, 2);
    /// ```
    pub fn counts(&self) -> CircleCounts {
        self.exact.unwrap_or(CircleCounts {
            inside: self.inside,
            on: self.on,
            outside: self.outside,
        })
    }

    /// True when every root is strictly inside the unit circle (by [`JuryTable::counts`]).
    pub fn stable(&self) -> bool {
        let c = self.counts();
        c.on == 0 && c.outside == 0
    }
}

/// The Jury table of `p` (degree ≥ 1), with the exact counts of its f64 coefficients (their
/// binary values).
///
/// Errors: a constant or zero polynomial; a table that overflows.
///
/// ```
/// use ltikit::Poly;
/// use ltikit::analysis::jury;
/// // z³ − 1.3z² − 0.08z + 0.24 = (z − 0.5)(z + 0.4)(z − 1.2) ... one root outside.
/// let p = Poly::from_descending(&[1.0, -1.3, -0.08, 0.24]).unwrap();
/// let t = jury(&p).unwrap();
/// assert_eq!((t.inside, t.on, t.outside), (2, 0, 1));
/// assert_eq!(t.exact.unwrap().outside, 1);
/// // z² + 1: roots ±j on the circle — a singular table, decided by the bilinear map.
/// let t = jury(&Poly::from_descending(&[1.0, 0.0, 1.0]).unwrap()).unwrap();
/// assert_eq!(t.singular_at, Some(1));
/// assert_eq!((t.inside, t.on, t.outside), (0, 2, 0));
/// ```
pub fn jury(p: &Poly) -> Result<JuryTable> {
    let exact = within_budget(ExactPoly::from_f64_descending(p.coeffs()).and_then(|e| {
        if e.degree() == 0 {
            Err(degree_error())
        } else {
            e.unit_circle_counts()
        }
    }))?;
    table(p, exact)
}

/// The Jury table of an exact polynomial (the coefficients as typed: `0.1` is 1/10), with its
/// exact counts; the table itself is computed on the rounded coefficients.
///
/// ```
/// use ltikit::analysis::jury_exact;
/// use ltikit::poly::exact::ExactPoly;
/// // z − 1.0000000000001 typed as text: outside, though the table's f64 says so only barely.
/// let p = ExactPoly::parse_descending(&["1", "-1.0000000000001"]).unwrap();
/// let t = jury_exact(&p).unwrap();
/// assert_eq!(t.exact.unwrap().outside, 1);
/// ```
pub fn jury_exact(p: &ExactPoly) -> Result<JuryTable> {
    if p.is_zero() || p.degree() == 0 {
        return Err(degree_error());
    }
    let exact = within_budget(p.unit_circle_counts())?;
    table(&p.to_poly()?, exact)
}

fn degree_error() -> LtiError {
    LtiError::invalid("the Jury table needs a polynomial of degree ≥ 1")
}

/// `None` for the exact path's budget error, the value otherwise; other errors pass.
fn within_budget<T>(r: Result<T>) -> Result<Option<T>> {
    match r {
        Ok(v) => Ok(Some(v)),
        Err(LtiError::BeyondExactBudget { .. }) => Ok(None),
        Err(e) => Err(e),
    }
}

fn table(p: &Poly, exact: Option<CircleCounts>) -> Result<JuryTable> {
    let n = p.degree();
    if n == 0 || p.is_zero() {
        return Err(degree_error());
    }
    let sign = if p.leading() < 0.0 { -1.0 } else { 1.0 };
    let mut a: Vec<f64> = p.coeffs().iter().map(|x| sign * x).collect();
    let scale = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut rows = Vec::new();
    let mut alphas = Vec::new();
    let mut first = vec![a[0]];
    let mut singular_at = None;
    for k in (1..=n).rev() {
        let rev: Vec<f64> = a.iter().rev().copied().collect();
        rows.push(a.clone());
        rows.push(rev.clone());
        let alpha = a[k] / a[0];
        alphas.push(alpha);
        let next: Vec<f64> = (0..k).map(|i| a[i] - alpha * rev[i]).collect();
        if next.iter().any(|x| !x.is_finite()) {
            return Err(LtiError::invalid(
                "the Jury table overflows for these coefficients",
            ));
        }
        first.push(next[0]);
        a = next;
        if a[0].abs() <= ZERO_REL_TOL * scale {
            singular_at = Some(k - 1);
            break;
        }
    }
    if singular_at.is_none() {
        rows.push(a.clone());
    }
    let (inside, on, outside) = if singular_at.is_some() {
        // the Routh table of the bilinear image: left half plane = inside
        let q = bilinear_f64(p, n)?;
        let drop = n - q.degree();
        if q.degree() == 0 {
            (0, drop, 0)
        } else {
            let t = routh(&q)?;
            (t.lhp, t.axis + drop, t.rhp)
        }
    } else {
        let out = first[1..].iter().filter(|x| **x < 0.0).count();
        (n - out, 0, out)
    };
    Ok(JuryTable {
        rows,
        alphas,
        first,
        singular_at,
        inside,
        on,
        outside,
        exact,
    })
}

/// (1 − w)ⁿ·p((1 + w)/(1 − w)) in f64 for p of degree ≤ n (homogenised at degree n).
fn bilinear_f64(p: &Poly, n: usize) -> Result<Poly> {
    let c = p.coeffs(); // descending
    let m = c.len() - 1;
    let u = Poly::from_descending(&[1.0, 1.0])?;
    let v = Poly::from_descending(&[-1.0, 1.0])?;
    // Σ c_{m−k}·u^k·v^(n−k), k = 0 … m (c descending: c[i] multiplies z^(m−i))
    let mut acc = Poly::from_descending(&[0.0])?;
    let mut uk = Poly::from_descending(&[1.0])?;
    for k in 0..=m {
        let mut term = uk.scale(c[m - k]);
        for _ in 0..(n - k) {
            term = &term * &v;
        }
        acc = &acc + &term;
        uk = &uk * &u;
    }
    Ok(acc)
}

/// (1 − w)ⁿ·p((1 + w)/(1 − w)) exactly, for p of degree ≤ n.
fn bilinear_exact(p: &ExactPoly, n: usize) -> Result<ExactPoly> {
    if p.is_zero() {
        return Ok(p.clone());
    }
    let one_minus_w =
        ExactPoly::from_rationals(&[Rational::from_integer(-1), Rational::from_integer(1)])?;
    let mut q = p.bilinear();
    for _ in p.degree()..n {
        q = &q * &one_minus_w;
    }
    Ok(q)
}

/// Where D(z) + K·N(z) has a root on the unit circle: the pairs (θ, K), 0 ≤ θ ≤ π, with a
/// root at e^(±jθ) for the real gain K, increasing in θ. θ = 0 is z = 1 (K = −D(1)/N(1)),
/// θ = π is z = −1; the pairs in between are the imaginary-axis crossings of the bilinear
/// images (ω = tan(θ/2)).
///
/// ```
/// use ltikit::Poly;
/// use ltikit::analysis::jury::circle_crossings;
/// // K/((z − 1)(z − 0.5)): z = 1 at K = 0, e^(±jθ) with cos θ = 0.75 at K = 0.5, z = −1 at K = −3.
/// let n = Poly::from_descending(&[1.0]).unwrap();
/// let d = Poly::from_descending(&[1.0, -1.5, 0.5]).unwrap();
/// let c = circle_crossings(&n, &d).unwrap();
/// assert_eq!(c.len(), 3);
/// assert!(c[0].0 == 0.0 && c[0].1.abs() < 1e-15);
/// assert!((c[1].0 - 0.75f64.acos()).abs() < 1e-14 && (c[1].1 - 0.5).abs() < 1e-14);
/// assert!((c[2].0 - std::f64::consts::PI).abs() < 1e-15 && (c[2].1 + 3.0).abs() < 1e-14);
/// ```
pub fn circle_crossings(num: &Poly, den: &Poly) -> Result<Vec<(f64, f64)>> {
    let (n, d) = (exact_of(num)?, exact_of(den)?);
    circle_crossings_exact(&n, &d, num, den)
}

fn exact_of(p: &Poly) -> Result<ExactPoly> {
    ExactPoly::from_f64_descending(p.coeffs())
}

/// [`circle_crossings`] with the bilinear images formed exactly from `n`, `d` (their
/// roundings `num`, `den`), in f64 beyond the exact budget.
fn circle_crossings_exact(
    n: &ExactPoly,
    d: &ExactPoly,
    num: &Poly,
    den: &Poly,
) -> Result<Vec<(f64, f64)>> {
    if num.is_zero() {
        return Ok(Vec::new());
    }
    let deg = num.degree().max(den.degree());
    let exact = (|| -> Result<(Poly, Poly)> {
        let bn = bilinear_exact(n, deg)?;
        let bd = bilinear_exact(d, deg)?;
        bn.check_budget()?;
        bd.check_budget()?;
        Ok((bn.to_poly()?, bd.to_poly()?))
    })();
    let (wn, wd) = match exact {
        Ok(v) => v,
        Err(LtiError::BeyondExactBudget { .. }) => {
            (bilinear_f64(num, deg)?, bilinear_f64(den, deg)?)
        }
        Err(e) => return Err(e),
    };
    let mut out: Vec<(f64, f64)> = axis_crossings(&wn, &wd)?
        .into_iter()
        .map(|(w, k)| (2.0 * w.atan(), k))
        .collect();
    // z = −1 is w = ∞: not among the axis crossings of the images
    let m1 = Complex64::new(-1.0, 0.0);
    let nv = num.eval_complex(m1);
    if nv.norm() > 0.0 {
        let k = -(den.eval_complex(m1) / nv).re;
        if k.is_finite() {
            out.push((std::f64::consts::PI, k));
        }
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(out)
}

/// The gains K for which every root of D(z) + K·N(z) (unity negative feedback around K·N/D in
/// discrete time) lies strictly inside the unit circle, as open intervals (lo, hi) (±∞
/// allowed), increasing. The ends are where a root crosses the circle or escapes through
/// infinity ([`circle_crossings`]; accurate to rounding); each interval is decided exactly
/// at a rational gain inside it ([`ExactPoly::unit_circle_counts`]; the f64 Jury table beyond
/// the exact budget).
///
/// ```
/// use ltikit::Poly;
/// use ltikit::analysis::discrete_stable_gains;
/// // K(z + 0.5)/(z(z − 1)): z² + (K − 1)z + 0.5K; Jury: |0.5K| < 1, 1.5K > 0, 2 − 0.5K > 0,
/// // so 0 < K < 2 (the roots cross the circle at e^(±j2π/3) for K = 2).
/// let n = Poly::from_descending(&[1.0, 0.5]).unwrap();
/// let d = Poly::from_descending(&[1.0, -1.0, 0.0]).unwrap();
/// let k = discrete_stable_gains(&n, &d).unwrap();
/// assert_eq!(k.len(), 1);
/// assert!(k[0].0.abs() < 1e-14 && (k[0].1 - 2.0).abs() < 1e-14);
/// ```
pub fn discrete_stable_gains(num: &Poly, den: &Poly) -> Result<Vec<(f64, f64)>> {
    discrete_stable_gains_exact(&exact_of(num)?, &exact_of(den)?)
}

/// As [`discrete_stable_gains`] for exact coefficients (as typed): the intervals are decided in
/// rational arithmetic on these coefficients.
///
/// ```
/// use ltikit::analysis::jury::discrete_stable_gains_exact;
/// use ltikit::poly::exact::ExactPoly;
/// // K/((z − 1)(z − 0.5)): z² − 1.5z + 0.5 + K; Jury: |0.5 + K| < 1, K > 0, 3 + K > 0:
/// // 0 < K < 0.5.
/// let n = ExactPoly::parse_descending(&["1"]).unwrap();
/// let d = ExactPoly::parse_descending(&["1", "-1.5", "0.5"]).unwrap();
/// let k = discrete_stable_gains_exact(&n, &d).unwrap();
/// assert_eq!(k.len(), 1);
/// assert!(k[0].0.abs() < 1e-15 && (k[0].1 - 0.5).abs() < 1e-15);
/// ```
pub fn discrete_stable_gains_exact(num: &ExactPoly, den: &ExactPoly) -> Result<Vec<(f64, f64)>> {
    if num.is_zero() {
        return Err(LtiError::invalid(
            "the loop has a zero numerator: no gain acts",
        ));
    }
    if num.degree() > den.degree() {
        return Err(LtiError::invalid(
            "the loop is improper (numerator degree above the denominator's)",
        ));
    }
    let (nf, df) = (num.to_poly()?, den.to_poly()?);
    let mut ends: Vec<f64> = circle_crossings_exact(num, den, &nf, &df)?
        .into_iter()
        .map(|c| c.1)
        .collect();
    if num.degree() == den.degree() {
        ends.push(-df.leading() / nf.leading());
    }
    ends.retain(|k| k.is_finite());
    ends.sort_by(f64::total_cmp);
    ends.dedup();
    let mut bounds = vec![f64::NEG_INFINITY];
    bounds.extend(&ends);
    bounds.push(f64::INFINITY);
    let stable_at = |k: f64| -> Result<bool> {
        let kq = ExactPoly::from_rationals(&[Rational::from_f64(k)?])?;
        let q = den + &(&kq * num);
        if q.degree() < den.degree() || q.is_zero() {
            return Ok(false);
        }
        if q.degree() == 0 {
            return Ok(true);
        }
        match q.unit_circle_counts() {
            Ok(c) => Ok(c.on == 0 && c.outside == 0),
            Err(LtiError::BeyondExactBudget { .. }) => {
                let t = table(&(&df + &nf.scale(k)), None)?;
                Ok(t.stable())
            }
            Err(e) => Err(e),
        }
    };
    let mut out: Vec<(f64, f64)> = Vec::new();
    for w in bounds.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        let mid = match (lo.is_finite(), hi.is_finite()) {
            (true, true) => 0.5 * lo + 0.5 * hi,
            (false, true) => hi - hi.abs().max(1.0),
            (true, false) => lo + lo.abs().max(1.0),
            (false, false) => 0.0,
        };
        if !(mid > lo && mid < hi) {
            continue; // no double between two ends: nothing to decide
        }
        if stable_at(mid)? {
            match out.last_mut() {
                Some(last) if last.1.to_bits() == lo.to_bits() => last.1 = hi,
                _ => out.push((lo, hi)),
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(c: &[f64]) -> Poly {
        Poly::from_descending(c).unwrap()
    }

    /// Roots outside the circle by the root finder, for polynomials whose roots are far from it.
    fn outside_by_roots(q: &Poly) -> usize {
        q.roots()
            .unwrap()
            .iter()
            .filter(|r| r.value.norm() > 1.0)
            .map(|r| r.multiplicity)
            .sum()
    }

    #[test]
    fn the_table_counts_like_the_roots() {
        // products of (z − r) for r on a grid away from the circle
        let rs = [-2.5, -0.7, -0.2, 0.3, 0.8, 1.6, 3.0];
        let mut seen = 0;
        for mask in 1u32..(1 << rs.len()) {
            let mut q = p(&[1.0]);
            for (i, r) in rs.iter().enumerate() {
                if mask & (1 << i) != 0 {
                    q = &q * &p(&[1.0, -r]);
                }
            }
            let t = jury(&q).unwrap();
            let out = outside_by_roots(&q);
            assert_eq!(t.counts().outside, out, "{:?}", q.coeffs());
            if t.singular_at.is_none() {
                assert_eq!(t.outside, out, "{:?}", q.coeffs());
                seen += 1;
            }
        }
        assert!(seen > 100, "{seen}");
    }

    #[test]
    fn stable_gains_of_a_double_integrator_are_empty() {
        // K/(z − 1)²: z² − 2z + 1 + K; Jury: |1 + K| < 1 and P(1) = K > 0 contradict.
        let k = discrete_stable_gains(&p(&[1.0]), &p(&[1.0, -2.0, 1.0])).unwrap();
        assert!(k.is_empty(), "{k:?}");
    }

    #[test]
    fn bilinear_in_f64_and_exactly_agree() {
        let q = p(&[1.0, -0.5, 0.25, 2.0]);
        let a = bilinear_f64(&q, 4).unwrap();
        let b = bilinear_exact(&exact_of(&q).unwrap(), 4)
            .unwrap()
            .to_poly()
            .unwrap();
        assert_eq!(a.coeffs(), b.coeffs());
    }
}
