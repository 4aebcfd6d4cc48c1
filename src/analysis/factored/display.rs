//! `G(s) = …` for a factored plant: the coefficients when it was given by them, otherwise the
//! factors, k·(s + a)^m (s² + b s + c)… / (…).

use std::fmt;

use super::form::Factored;
use crate::fmt::fmt_num;
use crate::poly::{Poly, Root, format_poly};

/// The real factor of a root as text: `s`, `(s + 2)`, `(s^2 + 2 s + 5)`, with `^m`.
fn factor_text(r: &Root, var: &str) -> String {
    let body = if r.is_origin() {
        var.to_string()
    } else if r.is_real() {
        format!(
            "({})",
            Poly::from_descending(&[1.0, -r.value.re])
                .map_or_else(|_| "?".into(), |p| format_poly(&p, var))
        )
    } else {
        let c = [1.0, -2.0 * r.value.re, r.value.norm_sqr()];
        format!(
            "({})",
            Poly::from_descending(&c).map_or_else(|_| "?".into(), |p| format_poly(&p, var))
        )
    };
    if r.multiplicity > 1 {
        format!("{body}^{}", r.multiplicity)
    } else {
        body
    }
}

fn product(roots: &[Root], var: &str) -> Vec<String> {
    roots
        .iter()
        .filter(|r| r.value.im >= 0.0)
        .map(|r| factor_text(r, var))
        .collect()
}

impl fmt::Display for Factored {
    /// The plant as given: `4 / (s^2 + 0.8 s + 4)` for coefficients, `3 (s + 1)^2 / (s + 2)^20`
    /// for factors.
    ///
    /// ```
    /// use ltikit::analysis::Factored;
    /// use ltikit::Root;
    /// use num_complex::Complex64 as C;
    /// let f = Factored::from_zpk(
    ///     &[Root::new(C::new(-1.0, 0.0), 2)],
    ///     &[Root::new(C::new(-1.0, 2.0), 1), Root::new(C::new(-1.0, -2.0), 1), Root::new(C::new(0.0, 0.0), 1)],
    ///     3.0,
    /// ).unwrap();
    /// assert_eq!(f.to_string(), "3 (s + 1)^2 / (s (s^2 + 2 s + 5))");
    /// ```
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.fmt_rational(f)?;
        if self.delay() > 0.0 {
            write!(f, " · {}", crate::lti::delay::factor_text(self.delay()))?;
        }
        Ok(())
    }
}

impl Factored {
    /// The rational part as text (see the `Display` impl).
    fn fmt_rational(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(tf) = self.transfer_function() {
            return write!(f, "{}", tf.rational());
        }
        if self.is_zero() {
            return f.write_str("0");
        }
        let var = self.domain().variable();
        let num = product(self.zeros(), var);
        let den = product(self.poles(), var);
        let k = self.gain();
        let mut top = if num.is_empty() {
            fmt_num(k)
        } else if k.to_bits() == 1f64.to_bits() {
            String::new() // exactly 1 is not printed
        } else if k.to_bits() == (-1f64).to_bits() {
            "-".into()
        } else {
            format!("{} ", fmt_num(k))
        };
        top.push_str(&num.join(" "));
        if den.is_empty() {
            return f.write_str(&top);
        }
        let bottom = if den.len() == 1 {
            den[0].clone()
        } else {
            format!("({})", den.join(" "))
        };
        write!(f, "{top} / {bottom}")
    }
}
