//! Certified structure of a ratio of exact polynomials: a coprime basis of square-free
//! factors with exact multiplicities in numerator and denominator, exact cancellations, exact
//! half-plane counts, and the roots of every factor to full double precision.

use num_complex::Complex64;

use super::budget::beyond;
use super::cdd::dd_sqrt;
use super::number::Rational;
use super::qpoly::ExactPoly;
use super::refine::simple_roots;
use super::sqfree::{BasisElement, insert, square_free};
use super::sturm::{HalfPlaneCounts, square_free_counts};
use super::zpoly::ZPoly;
use crate::error::{LtiError, Result};
use crate::poly::Root;

/// Where a root lies, decided exactly.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Open left half plane (Re s < 0).
    Left,
    /// On the imaginary axis (Re s = 0, including s = 0).
    Axis,
    /// Open right half plane (Re s > 0).
    Right,
}

/// A simple root of a square-free factor: its value to full double precision (real roots
/// have an imaginary part of exactly 0, axis roots a real part of exactly 0, conjugates are
/// exact conjugates) and its exactly decided half plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CertifiedRoot {
    /// The root.
    pub value: Complex64,
    /// Its half plane (for a root within ~10⁻³⁰ relative of the axis the sign of
    /// `value.re` may be rounding; `side` is exact).
    pub side: Side,
}

/// One square-free factor of the coprime basis of numerator·denominator.
#[derive(Debug, Clone)]
pub struct Factor {
    /// The factor: square-free, primitive integer coefficients, positive leading coefficient.
    pub poly: ExactPoly,
    /// Its multiplicity in the numerator (0 if it does not divide it).
    pub in_numerator: usize,
    /// Its multiplicity in the denominator.
    pub in_denominator: usize,
    /// Its roots, each simple, sorted like [`crate::poly::roots::roots`].
    pub roots: Vec<CertifiedRoot>,
    /// Half-plane counts of its roots (each once), from the exact polynomial.
    pub counts: HalfPlaneCounts,
}

/// The certified structure of N/D (see [`certify`]).
#[derive(Debug, Clone)]
pub struct Structure {
    factors: Vec<Factor>,
    numerator: ExactPoly,
    denominator: ExactPoly,
    gcd: ExactPoly,
    reduced_numerator: ExactPoly,
    reduced_denominator: ExactPoly,
}

/// Certified structure of num/den from exact coefficients: every multiplicity, cancellation
/// and half-plane count is decided without tolerance; root values are the nearest doubles
/// (to ~1 ulp) of the exact roots.
///
/// Errors: a zero denominator ([`LtiError::ZeroPolynomial`]), or
/// [`LtiError::BeyondExactBudget`] when the input exceeds the exact budget (then use the
/// numerical path). A zero numerator cancels nothing.
///
/// ```
/// use ltikit::poly::exact::{ExactPoly, certify};
/// // (s + 0.1)(s + 0.3) / ((s + 0.1)(s + 0.7)): the factor s + 0.1 cancels exactly.
/// let n = ExactPoly::parse_descending(&["1", "0.4", "0.03"]).unwrap();
/// let d = ExactPoly::parse_descending(&["1", "0.8", "0.07"]).unwrap();
/// let s = certify(&n, &d).unwrap();
/// let c = s.cancelled();
/// assert_eq!(c.len(), 1);
/// assert_eq!((c[0].value.re, c[0].multiplicity), (-0.1, 1));
/// assert_eq!(s.reduced_denominator().to_string(), "s + 7/10");
/// assert_eq!(s.reduced_denominator_counts().lhp, 1);
/// ```
pub fn certify(num: &ExactPoly, den: &ExactPoly) -> Result<Structure> {
    if den.is_zero() {
        return Err(LtiError::ZeroPolynomial {
            what: "denominator".into(),
        });
    }
    num.check_budget()?;
    den.check_budget()?;
    let mut basis: Vec<BasisElement> = Vec::new();
    let (kn, kd) = (num.zero_root_multiplicity(), den.zero_root_multiplicity());
    let parts = [(num, kn, true), (den, kd, false)];
    for (p, k, is_num) in parts {
        if p.is_zero() {
            continue;
        }
        let rest = p.prim().shift_down(k);
        if rest.deg() == 0 {
            continue;
        }
        let sf = square_free(&rest).ok_or_else(gcd_budget)?;
        for (f, i) in sf {
            let (a, b) = if is_num { (i, 0) } else { (0, i) };
            insert(&mut basis, &f, a, b).ok_or_else(gcd_budget)?;
        }
    }
    if kn + kd > 0 {
        basis.push(BasisElement {
            poly: ZPoly::x(),
            num: kn,
            den: kd,
        });
    }
    let mut factors = Vec::with_capacity(basis.len());
    let mut g = ZPoly::one();
    for e in basis {
        let (roots, counts) = factor_roots(&e.poly)?;
        let m = if num.is_zero() { 0 } else { e.num.min(e.den) };
        g = g.mul(&e.poly.pow(m));
        factors.push(Factor {
            poly: ExactPoly::from_integer_poly(e.poly, &Rational::from_integer(1)),
            in_numerator: e.num,
            in_denominator: e.den,
            roots,
            counts,
        });
    }
    let reduce = |p: &ExactPoly| -> Result<ExactPoly> {
        if p.is_zero() {
            return Ok(p.clone());
        }
        // p = c·P, P = G·Q in ℤ[s]; p divided by the monic gcd G/lc(G) is c·lc(G)·Q, which
        // keeps the leading coefficient of p.
        let q = p
            .prim()
            .div_exact(&g)
            .ok_or_else(|| beyond("internal: the gcd does not divide"))?;
        let c = p.content();
        let scale = Rational::from_parts(c.numer() * g.lc(), c.denom().clone().into());
        Ok(ExactPoly::from_integer_poly(q, &scale))
    };
    Ok(Structure {
        reduced_numerator: reduce(num)?,
        reduced_denominator: reduce(den)?,
        gcd: ExactPoly::from_integer_poly(g, &Rational::from_integer(1)),
        factors,
        numerator: num.clone(),
        denominator: den.clone(),
    })
}

fn gcd_budget() -> LtiError {
    beyond("a gcd's coefficients exceed the modular prime table (~3900 bits)")
}

/// Roots and half-plane counts of one square-free basis factor.
pub(super) fn factor_roots(b: &ZPoly) -> Result<(Vec<CertifiedRoot>, HalfPlaneCounts)> {
    if *b == ZPoly::x() {
        let root = CertifiedRoot {
            value: Complex64::new(0.0, 0.0),
            side: Side::Axis,
        };
        let counts = HalfPlaneCounts {
            axis: 1,
            ..HalfPlaneCounts::default()
        };
        return Ok((vec![root], counts));
    }
    let internal = || beyond("internal: an exact division failed");
    let close = || beyond("roots closer than the double-double refinement separates");
    let (counts, g) = square_free_counts(b).ok_or_else(internal)?;
    let mut roots = Vec::with_capacity(b.deg());
    let c = if g.deg() > 0 {
        let axis = symmetric_roots(&g, &mut roots).ok_or_else(close)?;
        if axis != counts.axis {
            return Err(beyond("internal: axis roots disagree with the exact count"));
        }
        b.div_exact(&g.of_square()).ok_or_else(internal)?
    } else {
        b.clone()
    };
    if c.deg() > 0 {
        // Counts of c alone: g(s²) contributes deg g − axis/2 to each open half plane.
        let sym = g.deg() - counts.axis / 2;
        let (want_l, want_r) = (counts.lhp - sym, counts.rhp - sym);
        let disks = simple_roots(&c).ok_or_else(close)?;
        let (l, r) = disks.iter().fold((0, 0), |(l, r), d| match d.side() {
            -1 => (l + 1, r),
            1 => (l, r + 1),
            _ => (l, r),
        });
        let amb = disks.len() - l - r;
        let fill = if l > want_l || r > want_r {
            return Err(beyond("internal: root disks disagree with the exact count"));
        } else if amb == 0 || l == want_l {
            Side::Right
        } else if r == want_r {
            Side::Left
        } else {
            return Err(beyond(
                "roots within the double-double rounding of the imaginary axis on both sides",
            ));
        };
        for d in disks {
            let side = match d.side() {
                -1 => Side::Left,
                1 => Side::Right,
                _ => fill,
            };
            roots.push(CertifiedRoot {
                value: d.value(),
                side,
            });
        }
    }
    sort(&mut roots);
    Ok((roots, counts))
}

/// Roots of g(s²) from the roots x of g: ±√x. Returns the number of axis roots.
fn symmetric_roots(g: &ZPoly, out: &mut Vec<CertifiedRoot>) -> Option<usize> {
    let xs = simple_roots(g)?;
    let mut axis = 0;
    for x in xs {
        let re = x.z.re.to_f64();
        if x.z.im.to_f64() == 0.0 {
            if re.abs() <= x.r {
                return None; // cannot happen: g(0) ≠ 0 and the disk is exact for linear g
            }
            let y = dd_sqrt(if re < 0.0 { -x.z.re } else { x.z.re }).to_f64();
            if re < 0.0 {
                axis += 2;
                for v in [y, -y] {
                    out.push(CertifiedRoot {
                        value: Complex64::new(0.0, v),
                        side: Side::Axis,
                    });
                }
            } else {
                out.push(CertifiedRoot {
                    value: Complex64::new(y, 0.0),
                    side: Side::Right,
                });
                out.push(CertifiedRoot {
                    value: Complex64::new(-y, 0.0),
                    side: Side::Left,
                });
            }
        } else if x.z.im.to_f64() > 0.0 {
            // x and x̄ give √x, −√x, √x̄ = conj √x, −conj √x; Re √x > 0 for non-real x.
            let w = x.z.sqrt().to_c64();
            for v in [w, -w, w.conj(), -w.conj()] {
                let side = if v.re > 0.0 { Side::Right } else { Side::Left };
                out.push(CertifiedRoot { value: v, side });
            }
        }
    }
    Some(axis)
}

/// Decreasing real part, then decreasing imaginary part (as `poly::roots::sort_roots`).
fn sort(r: &mut [CertifiedRoot]) {
    r.sort_by(|a, b| {
        b.value
            .re
            .total_cmp(&a.value.re)
            .then(b.value.im.total_cmp(&a.value.im))
    });
}

impl Structure {
    /// The coprime basis: square-free factors with their multiplicities and roots.
    pub fn factors(&self) -> &[Factor] {
        &self.factors
    }

    /// The numerator as given.
    pub fn numerator(&self) -> &ExactPoly {
        &self.numerator
    }

    /// The denominator as given.
    pub fn denominator(&self) -> &ExactPoly {
        &self.denominator
    }

    /// The exact gcd of numerator and denominator (primitive, positive leading coefficient;
    /// 1 when nothing cancels).
    pub fn gcd(&self) -> &ExactPoly {
        &self.gcd
    }

    /// Numerator divided by the monic gcd (its leading coefficient is kept).
    pub fn reduced_numerator(&self) -> &ExactPoly {
        &self.reduced_numerator
    }

    /// Denominator divided by the monic gcd (its leading coefficient is kept).
    pub fn reduced_denominator(&self) -> &ExactPoly {
        &self.reduced_denominator
    }

    /// Roots of the numerator with their exact multiplicities.
    pub fn zeros(&self) -> Vec<Root> {
        self.collect(|f| f.in_numerator)
    }

    /// Roots of the denominator with their exact multiplicities.
    pub fn poles(&self) -> Vec<Root> {
        self.collect(|f| f.in_denominator)
    }

    /// Common roots of numerator and denominator, with the multiplicity that cancels.
    pub fn cancelled(&self) -> Vec<Root> {
        let z = self.numerator.is_zero();
        self.collect(|f| {
            if z {
                0
            } else {
                f.in_numerator.min(f.in_denominator)
            }
        })
    }

    /// Zeros of the reduced ratio.
    pub fn reduced_zeros(&self) -> Vec<Root> {
        self.collect(|f| f.in_numerator.saturating_sub(f.in_denominator))
    }

    /// Poles of the reduced ratio.
    pub fn reduced_poles(&self) -> Vec<Root> {
        let z = self.numerator.is_zero();
        self.collect(|f| {
            if z {
                f.in_denominator
            } else {
                f.in_denominator.saturating_sub(f.in_numerator)
            }
        })
    }

    /// Half-plane counts of the numerator's roots (with multiplicity).
    pub fn numerator_counts(&self) -> HalfPlaneCounts {
        self.count(|f| f.in_numerator)
    }

    /// Half-plane counts of the denominator's roots: internal stability.
    pub fn denominator_counts(&self) -> HalfPlaneCounts {
        self.count(|f| f.in_denominator)
    }

    /// Half-plane counts of the reduced denominator's roots: BIBO stability.
    pub fn reduced_denominator_counts(&self) -> HalfPlaneCounts {
        let z = self.numerator.is_zero();
        self.count(|f| {
            if z {
                f.in_denominator
            } else {
                f.in_denominator.saturating_sub(f.in_numerator)
            }
        })
    }

    /// Square-free factorisation of the numerator: (fᵢ, i), fᵢ the product of the basis
    /// factors of multiplicity i, i increasing.
    pub fn numerator_square_free(&self) -> Vec<(ExactPoly, usize)> {
        self.square_free_by(|f| f.in_numerator)
    }

    /// Square-free factorisation of the denominator.
    pub fn denominator_square_free(&self) -> Vec<(ExactPoly, usize)> {
        self.square_free_by(|f| f.in_denominator)
    }

    fn collect(&self, mult: impl Fn(&Factor) -> usize) -> Vec<Root> {
        let mut out: Vec<Root> = self
            .factors
            .iter()
            .filter(|f| mult(f) > 0)
            .flat_map(|f| {
                f.roots.iter().map(|r| Root {
                    value: r.value,
                    multiplicity: mult(f),
                })
            })
            .collect();
        crate::poly::roots::sort_roots(&mut out);
        out
    }

    fn count(&self, mult: impl Fn(&Factor) -> usize) -> HalfPlaneCounts {
        self.factors
            .iter()
            .fold(HalfPlaneCounts::default(), |acc, f| {
                acc.plus(&f.counts.times(mult(f)))
            })
    }

    fn square_free_by(&self, mult: impl Fn(&Factor) -> usize) -> Vec<(ExactPoly, usize)> {
        let top = self.factors.iter().map(&mult).max().unwrap_or(0);
        (1..=top)
            .filter_map(|i| {
                let fs: Vec<&Factor> = self.factors.iter().filter(|f| mult(f) == i).collect();
                (!fs.is_empty()).then(|| {
                    let p = fs.iter().fold(ExactPoly::one(), |acc, f| &acc * &f.poly);
                    (p, i)
                })
            })
            .collect()
    }
}

impl ExactPoly {
    /// The constant 1.
    pub(crate) fn one() -> ExactPoly {
        ExactPoly::from_integer_poly(ZPoly::one(), &Rational::from_integer(1))
    }

    /// Roots with exact multiplicities, certified (see [`certify`]).
    ///
    /// ```
    /// use ltikit::poly::exact::ExactPoly;
    /// // (s + 3)²(s + 3.03)² = s⁴ + 12.06 s³ + 54.5409 s² + 109.6254 s + 82.6281
    /// let p = ExactPoly::parse_descending(&["1", "12.06", "54.5409", "109.6254", "82.6281"])
    ///     .unwrap();
    /// let r = p.roots().unwrap();
    /// assert_eq!(r.len(), 2);
    /// assert_eq!((r[0].value.re, r[0].multiplicity), (-3.0, 2));
    /// assert_eq!((r[1].value.re, r[1].multiplicity), (-3.03, 2));
    /// ```
    pub fn roots(&self) -> Result<Vec<Root>> {
        if self.is_zero() {
            return Err(LtiError::ZeroPolynomial {
                what: "polynomial".into(),
            });
        }
        Ok(certify(self, &ExactPoly::one())?.zeros())
    }
}
