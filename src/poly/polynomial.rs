//! The real polynomial [`Poly`] (descending coefficients), its arithmetic and its text (see
//! the [module docs](super)).

use num_complex::Complex64;
use std::fmt;

use super::root::Root;
use crate::error::{LtiError, Result, check_finite};
use crate::fmt::fmt_num;

// the highest polynomial degree (system order) ltikit accepts, in the table of limits
pub use crate::limits::MAX_ORDER;

/// A real polynomial, coefficients stored in descending powers, leading coefficient non-zero
/// (except for the zero polynomial `[0.0]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Poly {
    pub(in crate::poly) c: Vec<f64>,
}

impl Poly {
    /// From coefficients in descending powers; leading zeros are removed.
    ///
    /// Errors on an empty slice or a NaN/infinite coefficient.
    ///
    /// ```
    /// use ltikit::Poly;
    /// let p = Poly::from_descending(&[0.0, 1.0, 3.0, 2.0]).unwrap();
    /// assert_eq!(p.degree(), 2);
    /// assert_eq!(p.coeffs(), &[1.0, 3.0, 2.0]);
    /// assert_eq!(p.eval(1.0), 6.0);
    /// ```
    pub fn from_descending(c: &[f64]) -> Result<Poly> {
        Self::from_descending_named(c, "polynomial")
    }

    /// As [`Poly::from_descending`], naming the polynomial (e.g. "denominator") in errors.
    pub fn from_descending_named(c: &[f64], what: &str) -> Result<Poly> {
        if c.is_empty() {
            return Err(LtiError::EmptyPolynomial { what: what.into() });
        }
        for (i, &x) in c.iter().enumerate() {
            check_finite(|| format!("coefficient {i} of the {what}"), x)?;
        }
        Ok(Poly::trimmed(c.to_vec()))
    }

    /// From coefficients in **ascending** powers (c₀ + c₁ s + …). The name says the order.
    pub fn from_ascending(c: &[f64]) -> Result<Poly> {
        let mut d = c.to_vec();
        d.reverse();
        Self::from_descending(&d)
    }

    /// Internal constructor: trims leading zeros, assumes finite values.
    pub(crate) fn trimmed(mut c: Vec<f64>) -> Poly {
        let first = c.iter().position(|&x| x != 0.0);
        match first {
            None => Poly { c: vec![0.0] },
            Some(k) => {
                c.drain(..k);
                Poly { c }
            }
        }
    }

    /// The constant polynomial `k`.
    pub fn constant(k: f64) -> Poly {
        Poly::trimmed(vec![k])
    }

    /// The zero polynomial.
    pub fn zero() -> Poly {
        Poly { c: vec![0.0] }
    }

    /// The polynomial `s`.
    pub fn s() -> Poly {
        Poly { c: vec![1.0, 0.0] }
    }

    /// Monic polynomial with the given roots (conjugate-symmetric set required; each complex
    /// root must appear with its conjugate). Products are formed with real linear and quadratic
    /// factors so the result is exactly real.
    ///
    /// ```
    /// use ltikit::Poly;
    /// use num_complex::Complex64 as C;
    /// let p = Poly::from_roots(&[C::new(-1.0, 2.0), C::new(-1.0, -2.0), C::new(-3.0, 0.0)]).unwrap();
    /// assert_eq!(p.coeffs(), &[1.0, 5.0, 11.0, 15.0]); // (s²+2s+5)(s+3)
    /// ```
    pub fn from_roots(roots: &[Complex64]) -> Result<Poly> {
        let mut upper: Vec<Complex64> = Vec::new();
        let mut lower: Vec<Complex64> = Vec::new();
        let mut p = Poly::constant(1.0);
        for (i, &r) in roots.iter().enumerate() {
            check_finite(|| format!("real part of root {i}"), r.re)?;
            check_finite(|| format!("imaginary part of root {i}"), r.im)?;
            if r.im == 0.0 {
                p = &p
                    * &Poly {
                        c: vec![1.0, -r.re],
                    };
            } else if r.im > 0.0 {
                upper.push(r);
            } else {
                lower.push(r);
            }
        }
        // Pair each upper root with a conjugate from the lower list.
        let tol = |z: Complex64| 1e-12 * z.norm().max(1e-300);
        for u in upper {
            let k = lower
                .iter()
                .position(|l| (l.conj() - u).norm() <= tol(u))
                .ok_or_else(|| {
                    LtiError::invalid(format!(
                        "root {} + {}j has no complex conjugate partner: a real polynomial needs conjugate pairs",
                        u.re, u.im
                    ))
                })?;
            lower.swap_remove(k);
            p = &p * &Poly::quadratic_factor(u);
        }
        if let Some(l) = lower.first() {
            return Err(LtiError::invalid(format!(
                "root {} {}j has no complex conjugate partner: a real polynomial needs conjugate pairs",
                l.re, l.im
            )));
        }
        Ok(p)
    }

    /// Monic polynomial Π (s − rₖ)^mₖ from roots with multiplicities.
    pub fn from_root_list(roots: &[Root]) -> Result<Poly> {
        let mut flat = Vec::new();
        for r in roots {
            for _ in 0..r.multiplicity {
                flat.push(r.value);
            }
        }
        Poly::from_roots(&flat)
    }

    /// s² − 2 Re(z) s + |z|², the real factor of the pair z, z̄.
    pub(crate) fn quadratic_factor(z: Complex64) -> Poly {
        Poly {
            c: vec![1.0, -2.0 * z.re, z.re * z.re + z.im * z.im],
        }
    }

    /// Coefficients in descending powers (leading coefficient first).
    pub fn coeffs(&self) -> &[f64] {
        &self.c
    }

    /// Coefficients in ascending powers (constant term first).
    pub fn ascending(&self) -> Vec<f64> {
        self.c.iter().rev().copied().collect()
    }

    /// Degree (0 for constants, including the zero polynomial).
    pub fn degree(&self) -> usize {
        self.c.len() - 1
    }

    /// True for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.c.len() == 1 && self.c[0] == 0.0
    }

    /// Leading coefficient.
    pub fn leading(&self) -> f64 {
        self.c[0]
    }

    /// Coefficient of s^k (0 beyond the degree).
    pub fn coeff(&self, k: usize) -> f64 {
        let n = self.degree();
        if k > n { 0.0 } else { self.c[n - k] }
    }

    /// Value at a real point (Horner).
    pub fn eval(&self, x: f64) -> f64 {
        self.c.iter().fold(0.0, |acc, &a| acc * x + a)
    }

    /// Value at a complex point (Horner).
    pub fn eval_complex(&self, z: Complex64) -> Complex64 {
        let mut acc = Complex64::new(0.0, 0.0);
        for &a in &self.c {
            acc = acc * z + a;
        }
        acc
    }

    /// Σ |aₖ| rᵏ: the scale of rounding errors when evaluating at |s| = r.
    pub fn eval_abs(&self, r: f64) -> f64 {
        self.c.iter().fold(0.0, |acc, &a| acc * r + a.abs())
    }

    /// First derivative.
    pub fn derivative(&self) -> Poly {
        let n = self.degree();
        if n == 0 {
            return Poly::zero();
        }
        Poly::trimmed(
            self.c[..n]
                .iter()
                .enumerate()
                .map(|(i, &a)| a * (n - i) as f64)
                .collect(),
        )
    }

    /// k-th derivative.
    pub fn nth_derivative(&self, k: usize) -> Poly {
        let mut p = self.clone();
        for _ in 0..k {
            p = p.derivative();
        }
        p
    }

    /// Multiplies by a scalar.
    pub fn scale(&self, k: f64) -> Poly {
        Poly::trimmed(self.c.iter().map(|a| a * k).collect())
    }

    /// This polynomial divided by its leading coefficient.
    pub fn monic(&self) -> Poly {
        if self.is_zero() {
            return self.clone();
        }
        let l = self.leading();
        Poly {
            c: self.c.iter().map(|a| a / l).collect(),
        }
    }

    /// Polynomial long division: `self = q·d + r` with deg r < deg d.
    ///
    /// Errors when `d` is the zero polynomial.
    ///
    /// ```
    /// use ltikit::Poly;
    /// let n = Poly::from_descending(&[1.0, 0.0, 0.0, 2.0]).unwrap(); // s³ + 2
    /// let d = Poly::from_descending(&[1.0, 1.0]).unwrap();           // s + 1
    /// let (q, r) = n.div_rem(&d).unwrap();
    /// assert_eq!(q.coeffs(), &[1.0, -1.0, 1.0]);
    /// assert_eq!(r.coeffs(), &[1.0]);
    /// ```
    pub fn div_rem(&self, d: &Poly) -> Result<(Poly, Poly)> {
        if d.is_zero() {
            return Err(LtiError::ZeroPolynomial {
                what: "divisor".into(),
            });
        }
        let (n, m) = (self.degree(), d.degree());
        if n < m || self.is_zero() {
            return Ok((Poly::zero(), self.clone()));
        }
        let mut r = self.c.clone();
        let mut q = vec![0.0; n - m + 1];
        let lead = d.leading();
        for i in 0..=n - m {
            let f = r[i] / lead;
            q[i] = f;
            for j in 0..=m {
                r[i + j] -= f * d.c[j];
            }
            r[i] = 0.0;
        }
        let rem = Poly::trimmed(r[n - m + 1..].to_vec());
        Ok((Poly::trimmed(q), rem))
    }

    /// Taylor coefficients of p at the point `a`: p(a + h) = Σ tⱼ hʲ, returned for
    /// j = 0..count (ascending in h). Computed by repeated synthetic division (Horner), which
    /// is the numerically stable way to shift a polynomial.
    pub fn taylor_at(&self, a: Complex64, count: usize) -> Vec<Complex64> {
        let mut work: Vec<Complex64> = self.c.iter().map(|&x| Complex64::new(x, 0.0)).collect();
        let mut out = Vec::with_capacity(count);
        let mut len = work.len();
        for _ in 0..count {
            if len == 0 {
                out.push(Complex64::new(0.0, 0.0));
                continue;
            }
            // Synthetic division of work[..len] by (h - a): quotient in place, remainder last.
            for i in 1..len {
                let prev = work[i - 1];
                work[i] += prev * a;
            }
            out.push(work[len - 1]);
            len -= 1;
        }
        out
    }

    /// Exact count of trailing zero coefficients (the multiplicity of the root s = 0).
    pub fn zero_root_multiplicity(&self) -> usize {
        if self.is_zero() {
            return 0;
        }
        self.c.iter().rev().take_while(|&&x| x == 0.0).count()
    }

    /// Roots with exact multiplicities. See [`roots`](super::roots::roots).
    ///
    /// ```
    /// use ltikit::Poly;
    /// // (s + 1)³ (s² + 4s + 13): a triple root and a simple complex pair.
    /// let p = Poly::from_descending(&[1.0, 7.0, 28.0, 52.0, 43.0, 13.0]).unwrap();
    /// let r = p.roots().unwrap();
    /// assert_eq!(r.len(), 3);
    /// assert_eq!(r[0].multiplicity, 3);
    /// assert!((r[0].value.re + 1.0).abs() < 1e-14);
    /// ```
    pub fn roots(&self) -> Result<Vec<Root>> {
        super::roots::roots(self)
    }
}

impl std::ops::Add for &Poly {
    type Output = Poly;
    fn add(self, o: &Poly) -> Poly {
        let n = self.c.len().max(o.c.len());
        let mut c = vec![0.0; n];
        for (i, a) in self.c.iter().enumerate() {
            c[n - self.c.len() + i] += a;
        }
        for (i, a) in o.c.iter().enumerate() {
            c[n - o.c.len() + i] += a;
        }
        Poly::trimmed(c)
    }
}

impl std::ops::Sub for &Poly {
    type Output = Poly;
    fn sub(self, o: &Poly) -> Poly {
        self + &o.scale(-1.0)
    }
}

impl std::ops::Neg for &Poly {
    type Output = Poly;
    fn neg(self) -> Poly {
        self.scale(-1.0)
    }
}

impl std::ops::Mul for &Poly {
    type Output = Poly;
    fn mul(self, o: &Poly) -> Poly {
        let mut c = vec![0.0; self.c.len() + o.c.len() - 1];
        for (i, a) in self.c.iter().enumerate() {
            for (j, b) in o.c.iter().enumerate() {
                c[i + j] += a * b;
            }
        }
        Poly::trimmed(c)
    }
}

impl fmt::Display for Poly {
    /// Human form in descending powers: `s^2 + 0.8 s + 4`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&format_poly(self, "s"))
    }
}

/// Formats a polynomial in descending powers of `var`.
#[allow(clippy::float_cmp)] // a coefficient of exactly 1 is not printed
pub fn format_poly(p: &Poly, var: &str) -> String {
    if p.is_zero() {
        return "0".into();
    }
    let n = p.degree();
    let mut out = String::new();
    for (i, &a) in p.coeffs().iter().enumerate() {
        if a == 0.0 {
            continue;
        }
        let k = n - i;
        let sign = if a < 0.0 { "-" } else { "+" };
        let mag = a.abs();
        let body = match k {
            0 => fmt_num(mag),
            _ => {
                let pw = if k == 1 {
                    var.to_string()
                } else {
                    format!("{var}^{k}")
                };
                if mag == 1.0 {
                    pw
                } else {
                    format!("{} {pw}", fmt_num(mag))
                }
            }
        };
        if out.is_empty() {
            if sign == "-" {
                out.push('-');
            }
            out.push_str(&body);
        } else {
            out.push_str(&format!(" {sign} {body}"));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // these tests expect exact values
    use super::*;

    #[test]
    fn trims_and_rejects() {
        assert!(Poly::from_descending(&[]).is_err());
        assert!(Poly::from_descending(&[1.0, f64::NAN]).is_err());
        assert!(Poly::from_descending(&[f64::INFINITY]).is_err());
        let z = Poly::from_descending(&[0.0, 0.0]).unwrap();
        assert!(z.is_zero());
        assert_eq!(z.degree(), 0);
    }

    #[test]
    fn arithmetic() {
        let a = Poly::from_descending(&[1.0, 1.0]).unwrap();
        let b = Poly::from_descending(&[1.0, -1.0]).unwrap();
        assert_eq!((&a * &b).coeffs(), &[1.0, 0.0, -1.0]);
        assert_eq!((&a + &b).coeffs(), &[2.0, 0.0]);
        assert!((&a - &a).is_zero());
        assert_eq!(a.derivative().coeffs(), &[1.0]);
        let p = Poly::from_descending(&[2.0, 0.0, 3.0, 1.0]).unwrap();
        assert_eq!(p.nth_derivative(2).coeffs(), &[12.0, 0.0]);
    }

    #[test]
    fn taylor_shift_matches_expansion() {
        // p(s) = s^3 + 2s + 5 at a = 1: p(1+h) = 8 + 5h + 3h^2 + h^3
        let p = Poly::from_descending(&[1.0, 0.0, 2.0, 5.0]).unwrap();
        let t = p.taylor_at(Complex64::new(1.0, 0.0), 5);
        let want = [8.0, 5.0, 3.0, 1.0, 0.0];
        for (a, b) in t.iter().zip(want) {
            assert_eq!(a.re, b);
            assert_eq!(a.im, 0.0);
        }
    }

    #[test]
    fn from_roots_requires_conjugates() {
        assert!(Poly::from_roots(&[Complex64::new(0.0, 1.0)]).is_err());
        let p = Poly::from_roots(&[Complex64::new(0.0, 1.0), Complex64::new(0.0, -1.0)]).unwrap();
        assert_eq!(p.coeffs(), &[1.0, 0.0, 1.0]);
    }

    #[test]
    fn formatting() {
        let p = Poly::from_descending(&[1.0, -0.8, 4.0]).unwrap();
        assert_eq!(p.to_string(), "s^2 - 0.8 s + 4");
        let p = Poly::from_descending(&[-3.0, -12.0]).unwrap();
        assert_eq!(p.to_string(), "-3 s - 12");
    }
}
