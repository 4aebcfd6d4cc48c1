//! Test inputs u(t) with their Laplace transforms, and ODE initial conditions.
//!
//! Inputs are zero for t < 0 (they all carry the unit step 1(t)). Initial conditions are those
//! of the ODE (DESIGN §1.3, seed eqs. 3.8 and 3.22): y(0), y′(0), …, y^(n−1)(0), with the input
//! zero for t < 0. With D(s) = Σ aₖ sᵏ the Laplace transform of the output is
//!
//! Y(s) = G(s)·U(s) + P_ic(s)/D(s),  P_ic(s) = Σ_{k=1..n} aₖ Σ_{j=0..k−1} s^(k−1−j) y^(j)(0).

use std::fmt;
use std::str::FromStr;

use num_complex::Complex64;
use serde::{Serialize, Serializer};

use crate::error::{LtiError, Result, check_finite};
use crate::poly::Poly;

/// A standard test input u(t), zero for t < 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Input {
    /// δ(t); U(s) = 1.
    Impulse,
    /// 1(t); U(s) = 1/s.
    Step,
    /// t·1(t); U(s) = 1/s².
    Ramp,
    /// e^(a t)·1(t) (`exp:-3` is e^(−3t)); U(s) = 1/(s − a).
    Exp(f64),
    /// sin(ωt)·1(t), ω > 0; U(s) = ω/(s² + ω²).
    Sin(f64),
    /// cos(ωt)·1(t), ω > 0; U(s) = s/(s² + ω²).
    Cos(f64),
    /// No input (initial-condition response only); U(s) = 0.
    None,
}

impl Input {
    /// U(s) as (numerator, denominator).
    ///
    /// ```
    /// use ltikit::analysis::Input;
    /// let (n, d) = Input::Sin(2.0).laplace();
    /// assert_eq!(n.coeffs(), &[2.0]);
    /// assert_eq!(d.coeffs(), &[1.0, 0.0, 4.0]);
    /// ```
    pub fn laplace(&self) -> (Poly, Poly) {
        let one = Poly::constant(1.0);
        match *self {
            Input::Impulse => (one.clone(), one),
            Input::Step => (one, Poly::s()),
            Input::Ramp => (one, Poly::trimmed(vec![1.0, 0.0, 0.0])),
            Input::Exp(a) => (one, Poly::trimmed(vec![1.0, -a])),
            Input::Sin(w) => (Poly::constant(w), Poly::trimmed(vec![1.0, 0.0, w * w])),
            Input::Cos(w) => (Poly::s(), Poly::trimmed(vec![1.0, 0.0, w * w])),
            Input::None => (Poly::zero(), one),
        }
    }

    /// The poles of U(s), exact (0, a, ±jω), each with its multiplicity; the pair ±jω is
    /// listed upper member first.
    pub fn poles(&self) -> Vec<(Complex64, usize)> {
        let c = Complex64::new;
        match *self {
            Input::Impulse | Input::None => vec![],
            Input::Step => vec![(c(0.0, 0.0), 1)],
            Input::Ramp => vec![(c(0.0, 0.0), 2)],
            Input::Exp(a) => vec![(c(a, 0.0), 1)],
            Input::Sin(w) | Input::Cos(w) => vec![(c(0.0, w), 1), (c(0.0, -w), 1)],
        }
    }

    /// u(t) for t ≥ 0 (0 for the impulse, whose mass sits at t = 0, and for t < 0).
    ///
    /// ```
    /// use ltikit::analysis::Input;
    /// assert_eq!(Input::Ramp.eval(2.5), 2.5);
    /// assert_eq!(Input::Exp(-1.0).eval(0.0), 1.0);
    /// ```
    pub fn eval(&self, t: f64) -> f64 {
        if t < 0.0 {
            return 0.0;
        }
        match *self {
            Input::Impulse | Input::None => 0.0,
            Input::Step => 1.0,
            Input::Ramp => t,
            Input::Exp(a) => (a * t).exp(),
            Input::Sin(w) => (w * t).sin(),
            Input::Cos(w) => (w * t).cos(),
        }
    }

    /// Checks the parameter: a finite, ω finite and > 0.
    pub fn validate(&self) -> Result<()> {
        match *self {
            Input::Exp(a) => {
                check_finite(|| "the exponent a of the input exp:a".into(), a)?;
            }
            Input::Sin(w) | Input::Cos(w) => {
                check_finite(|| "the input frequency ω".into(), w)?;
                if w <= 0.0 {
                    return Err(LtiError::InvalidParameter {
                        name: "ω".into(),
                        value: w,
                        reason: "the input frequency must be > 0".into(),
                    });
                }
            }
            _ => {}
        }
        Ok(())
    }
}

impl Input {
    /// A human name for titles and legends: `Step`, `Impulse`, `Ramp`, `e^(-3 t)`,
    /// `sin(2 t)`, `cos(2 t)`, `No input`.
    ///
    /// ```
    /// use ltikit::analysis::Input;
    /// assert_eq!(Input::Sin(2.0).title(), "sin(2 t)");
    /// assert_eq!(Input::Step.title(), "Step");
    /// ```
    pub fn title(&self) -> String {
        match *self {
            Input::Impulse => "Impulse".into(),
            Input::Step => "Step".into(),
            Input::Ramp => "Ramp".into(),
            Input::Exp(a) => format!("e^({a} t)"),
            Input::Sin(w) => format!("sin({w} t)"),
            Input::Cos(w) => format!("cos({w} t)"),
            Input::None => "No input".into(),
        }
    }
}

impl fmt::Display for Input {
    /// The form [`Input::from_str`] parses (`step`, `exp:-3`, `sin:2`, …), exact: it parses
    /// back to the same input.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Input::Impulse => f.write_str("impulse"),
            Input::Step => f.write_str("step"),
            Input::Ramp => f.write_str("ramp"),
            Input::Exp(a) => write!(f, "exp:{a}"),
            Input::Sin(w) => write!(f, "sin:{w}"),
            Input::Cos(w) => write!(f, "cos:{w}"),
            Input::None => f.write_str("none"),
        }
    }
}

impl Serialize for Input {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl FromStr for Input {
    type Err = LtiError;

    /// Parses `impulse | step | ramp | exp:A | sin:W | cos:W | none` (case-insensitive).
    ///
    /// ```
    /// use ltikit::analysis::Input;
    /// assert_eq!("exp:-3".parse::<Input>().unwrap(), Input::Exp(-3.0));
    /// assert_eq!("sin:2".parse::<Input>().unwrap(), Input::Sin(2.0));
    /// assert!("sin:-1".parse::<Input>().is_err());
    /// assert!("square".parse::<Input>().is_err());
    /// ```
    fn from_str(text: &str) -> Result<Input> {
        let t = text.trim().to_ascii_lowercase();
        // echoed text is abbreviated (an input of 100 000 characters is not repeated)
        let shown = crate::error::abbreviate(text);
        let text = shown.as_str();
        let (name, arg) = match t.split_once(':') {
            Some((n, a)) => (n.trim(), Some(a.trim())),
            None => (t.as_str(), None),
        };
        let parse_arg = |what: &str| -> Result<f64> {
            let a = arg.ok_or_else(|| {
                LtiError::invalid(format!(
                    "input '{text}' needs a value: {}:{what} (e.g. {}:2)",
                    crate::error::abbreviate(name),
                    crate::error::abbreviate(name)
                ))
            })?;
            a.parse::<f64>().map_err(|_| {
                LtiError::invalid(format!(
                    "input '{text}': '{}' is not a number",
                    crate::error::abbreviate(a)
                ))
            })
        };
        let no_arg = |i: Input| -> Result<Input> {
            match arg {
                None => Ok(i),
                Some(_) => Err(LtiError::invalid(format!(
                    "input '{text}': {} takes no value",
                    crate::error::abbreviate(name)
                ))),
            }
        };
        let input = match name {
            "impulse" => no_arg(Input::Impulse)?,
            "step" => no_arg(Input::Step)?,
            "ramp" => no_arg(Input::Ramp)?,
            "none" => no_arg(Input::None)?,
            "exp" => Input::Exp(parse_arg("A")?),
            "sin" => Input::Sin(parse_arg("W")?),
            "cos" => Input::Cos(parse_arg("W")?),
            _ => {
                return Err(LtiError::invalid(format!(
                    "unknown input '{text}' (expected impulse, step, ramp, exp:A, sin:W, cos:W or none)"
                )));
            }
        };
        input.validate()?;
        Ok(input)
    }
}

/// P_ic(s) = Σ_{k=1..n} aₖ Σ_{j=0..k−1} s^(k−1−j) y^(j)(0) for the characteristic polynomial
/// `den` (degree n) and initial conditions `ics` = [y(0), y′(0), …] (fewer than n: the rest
/// are 0). Then Y(s) = G(s)U(s) + P_ic(s)/D(s).
///
/// Errors: more than n values, or a NaN/∞ value.
///
/// ```
/// use ltikit::{Poly, analysis::input::ic_polynomial};
/// // s² + 2ζωₙ s + ωₙ² with ζ = 0.5, ωₙ = 1: P_ic = (s + 1) y(0) + y′(0) (seed eq. 3.22)
/// let d = Poly::from_descending(&[1.0, 1.0, 1.0]).unwrap();
/// let p = ic_polynomial(&d, &[2.0, 3.0]).unwrap();
/// assert_eq!(p.coeffs(), &[2.0, 5.0]);
/// ```
pub fn ic_polynomial(den: &Poly, ics: &[f64]) -> Result<Poly> {
    let n = den.degree();
    if ics.len() > n {
        return Err(LtiError::invalid(format!(
            "{} initial conditions given for an order-{n} system (at most {n}: y(0){})",
            ics.len(),
            match n {
                0 => " is not needed: the system has no state".to_string(),
                1 => String::new(),
                2 => ", y'(0)".to_string(),
                _ => format!(", …, y^({})(0)", n - 1),
            }
        )));
    }
    for (j, &y) in ics.iter().enumerate() {
        check_finite(|| format!("initial condition {j} (y^({j})(0))"), y)?;
    }
    // Coefficient of s^i in P_ic: Σ_{k=i+1..n} a_k y^(k−1−i)(0).
    let asc: Vec<f64> = (0..n)
        .map(|i| {
            (i + 1..=n)
                .map(|k| {
                    let j = k - 1 - i;
                    den.coeff(k) * ics.get(j).copied().unwrap_or(0.0)
                })
                .sum()
        })
        .collect();
    if asc.is_empty() {
        return Ok(Poly::zero());
    }
    Ok(Poly::trimmed(asc.into_iter().rev().collect()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_every_form_and_round_trips() {
        for (s, i) in [
            ("impulse", Input::Impulse),
            ("Step", Input::Step),
            (" ramp ", Input::Ramp),
            ("exp:-3", Input::Exp(-3.0)),
            ("exp:0.5", Input::Exp(0.5)),
            ("sin:2", Input::Sin(2.0)),
            ("cos:0.25", Input::Cos(0.25)),
            ("none", Input::None),
        ] {
            let p: Input = s.parse().unwrap();
            assert_eq!(p, i);
            assert_eq!(p.to_string().parse::<Input>().unwrap(), i);
        }
    }

    #[test]
    fn rejects_bad_inputs_with_reasons() {
        for bad in [
            "sin:0", "sin:-2", "cos:nan", "sin:inf", "exp:x", "exp", "sin", "step:2", "pulse", "",
        ] {
            let e = bad.parse::<Input>().unwrap_err();
            assert!(!e.to_string().is_empty(), "{bad}");
        }
        assert!(
            "exp:nan"
                .parse::<Input>()
                .unwrap_err()
                .to_string()
                .contains("NaN")
        );
    }

    #[test]
    fn laplace_transforms() {
        let (n, d) = Input::Cos(3.0).laplace();
        assert_eq!(
            (n.coeffs(), d.coeffs()),
            (&[1.0, 0.0][..], &[1.0, 0.0, 9.0][..])
        );
        let (n, d) = Input::Exp(-2.0).laplace();
        assert_eq!((n.coeffs(), d.coeffs()), (&[1.0][..], &[1.0, 2.0][..]));
        let (n, _) = Input::None.laplace();
        assert!(n.is_zero());
    }

    #[test]
    fn ic_polynomial_third_order() {
        // a3 = 2, a2 = 3, a1 = 5, a0 = 7; ics y0 = 1, y1 = 10, y2 = 100
        // P = a3 (s² y0 + s y1 + y2) + a2 (s y0 + y1) + a1 y0
        //   = 2 s² + (20 + 3) s + (200 + 30 + 5)
        let d = Poly::from_descending(&[2.0, 3.0, 5.0, 7.0]).unwrap();
        let p = ic_polynomial(&d, &[1.0, 10.0, 100.0]).unwrap();
        assert_eq!(p.coeffs(), &[2.0, 23.0, 235.0]);
        let p = ic_polynomial(&d, &[1.0]).unwrap();
        assert_eq!(p.coeffs(), &[2.0, 3.0, 5.0]);
        assert!(ic_polynomial(&d, &[]).unwrap().is_zero());
        assert!(ic_polynomial(&d, &[1.0, 2.0, 3.0, 4.0]).is_err());
        assert!(ic_polynomial(&d, &[f64::NAN]).is_err());
    }
}
