//! Numbers as the user typed them: lists of coefficients ("1 0.8 4", "1,0.8,4", "-3;-12") and
//! `NAME=VALUE` parameters. One parser for the command line, plant files and batch lines.

use crate::error::{LtiError, Result};
use crate::poly::exact::Rational;

/// A coefficient as typed: its text (kept for exact arithmetic) and its value.
#[derive(Debug, Clone, PartialEq)]
pub struct Coefficient {
    /// The token as typed, e.g. `0.2` or `1.5e-3`.
    pub text: String,
    /// Its value as the nearest f64.
    pub value: f64,
}

/// Parses one number token (`1`, `-0.8`, `1.5e-3`, `nan`, `inf`; NaN and infinities parse and
/// are rejected later with a message that names the coefficient).
///
/// ```
/// use ltikit::lti::plant::parse_number;
/// assert_eq!(parse_number("-1.5e-3", "`den`").unwrap(), -1.5e-3);
/// let e = parse_number("x1", "`den`").unwrap_err().to_string();
/// assert_eq!(e, "`den`: 'x1' is not a number");
/// ```
pub fn parse_number(token: &str, what: &str) -> Result<f64> {
    token
        .trim()
        .parse::<f64>()
        .map_err(|_| LtiError::bad_number(what, token.trim(), "is not a number"))
}

/// The value of one coefficient token: a decimal, an exponent form or a fraction (`1/3`),
/// checked by the exact reader ([`Rational`]) so that every token that reaches the exact path
/// is valid; `nan`/`inf` pass here and are rejected later with a message naming the
/// coefficient.
fn coefficient_value(tok: &str, what: &str) -> Result<f64> {
    let plain = tok.trim().parse::<f64>();
    let word = !tok.trim().chars().any(|c| c.is_ascii_digit());
    if let Ok(v) = plain {
        if word && !v.is_finite() {
            return Ok(v); // nan, inf, -inf as words
        }
    }
    if plain.is_err() && !tok.contains('/') {
        return parse_number(tok, what); // "is not a number"
    }
    let exact = Rational::parse_named(tok, what)?;
    Ok(match plain {
        Ok(v) => v,
        Err(_) => exact.to_f64(),
    })
}

/// Splits a list on spaces, commas and semicolons and parses every token: decimals,
/// exponents (`1.5e-3`) and fractions (`1/3`), each kept as typed for the exact path.
///
/// Errors: an empty list, a token that is not a number (named, abbreviated), a malformed
/// fraction (`1/0`, `1/`, `/2`), more than [`crate::poly::exact::MAX_DIGITS`] digits, an
/// exponent beyond [`crate::poly::exact::MAX_EXPONENT`].
///
/// ```
/// use ltikit::lti::plant::parse_list;
/// let c = parse_list(" 1, 0.8 ;4 ", "`den`").unwrap();
/// assert_eq!(c.iter().map(|c| c.value).collect::<Vec<_>>(), vec![1.0, 0.8, 4.0]);
/// assert_eq!(c[1].text, "0.8");
/// assert!(parse_list("  ", "`den`").is_err());
/// assert_eq!(parse_list("1/4", "`num`").unwrap()[0].value, 0.25);
/// let e = parse_list("1 1/0", "`den`").unwrap_err().to_string();
/// assert!(e.contains("'1/0'"), "{e}");
/// ```
pub fn parse_list(text: &str, what: &str) -> Result<Vec<Coefficient>> {
    let mut out = Vec::new();
    for tok in text
        .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
        .filter(|t| !t.is_empty())
    {
        out.push(Coefficient {
            text: tok.to_string(),
            value: coefficient_value(tok, what)?,
        });
    }
    if out.is_empty() {
        return Err(LtiError::invalid(format!("{what}: no numbers given")));
    }
    Ok(out)
}

/// Parses a matrix: rows separated by `;` (or new lines), entries by spaces or commas, e.g.
/// `"0 1; -4 -0.8"`.
///
/// Errors: no entries, rows of different lengths (naming the row), a token that is not a
/// number.
///
/// ```
/// use ltikit::lti::plant::parse_matrix;
/// let a = parse_matrix("0 1; -4 -0.8", "`a`").unwrap();
/// assert_eq!((a.nrows(), a.ncols(), a[(1, 1)]), (2, 2, -0.8));
/// let e = parse_matrix("1 2; 3", "`a`").unwrap_err().to_string();
/// assert!(e.contains("row 2 has 1 entries"), "{e}");
/// ```
pub fn parse_matrix(text: &str, what: &str) -> Result<nalgebra::DMatrix<f64>> {
    let mut rows: Vec<Vec<f64>> = Vec::new();
    for row in text.split([';', '\n']) {
        let vals: Vec<f64> = row
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|t| !t.is_empty())
            .map(|t| parse_number(t, what))
            .collect::<Result<_>>()?;
        if !vals.is_empty() {
            rows.push(vals);
        }
    }
    matrix_of_rows(rows, what)
}

/// A matrix from its rows (all of one length).
pub fn matrix_of_rows(rows: Vec<Vec<f64>>, what: &str) -> Result<nalgebra::DMatrix<f64>> {
    let Some(n) = rows.first().map(Vec::len) else {
        return Err(LtiError::invalid(format!("{what}: no entries given")));
    };
    if let Some((i, r)) = rows.iter().enumerate().find(|(_, r)| r.len() != n) {
        return Err(LtiError::invalid(format!(
            "{what}: row {} has {} entries, row 1 has {n} (rows must be of equal length)",
            i + 1,
            r.len()
        )));
    }
    let flat: Vec<f64> = rows.iter().flatten().copied().collect();
    Ok(nalgebra::DMatrix::from_row_slice(rows.len(), n, &flat))
}

/// The values of [`parse_list`], at most [`crate::limits::MAX_POINTS`] of them (counted
/// before anything is allocated).
///
/// ```
/// use ltikit::lti::plant::parse_values;
/// assert_eq!(parse_values("0 0.5 1", "`t`").unwrap(), vec![0.0, 0.5, 1.0]);
/// let many = "0 ".repeat(ltikit::limits::MAX_POINTS + 1);
/// assert!(parse_values(&many, "`t`").is_err());
/// ```
pub fn parse_values(text: &str, what: &str) -> Result<Vec<f64>> {
    let n = text
        .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .count();
    crate::limits::POINTS.check_usize(what, n)?;
    Ok(parse_list(text, what)?
        .into_iter()
        .map(|c| c.value)
        .collect())
}

/// Parses `NAME=VALUE` (a model parameter).
///
/// ```
/// use ltikit::lti::plant::parse_param;
/// assert_eq!(parse_param("K=4").unwrap(), ("K".to_string(), 4.0));
/// assert!(parse_param("K").is_err() && parse_param("=3").is_err() && parse_param("K=x").is_err());
/// ```
pub fn parse_param(text: &str) -> Result<(String, f64)> {
    let Some((k, v)) = text.split_once('=') else {
        return Err(LtiError::bad_number("`param`", text, "is not NAME=VALUE"));
    };
    let k = k.trim();
    if k.is_empty() {
        return Err(LtiError::bad_number(
            "`param`",
            text,
            "has no parameter name",
        ));
    }
    let v = v.trim();
    if v.is_empty() {
        return Err(LtiError::bad_number(
            "`param`",
            text,
            format!("has no value for {}", crate::error::abbreviate(k)),
        ));
    }
    Ok((
        k.to_string(),
        parse_number(v, &format!("`param` {}", crate::error::abbreviate(k)))?,
    ))
}

/// Parses every `NAME=VALUE` of a list.
pub fn parse_params(list: &[String]) -> Result<Vec<(String, f64)>> {
    list.iter().map(|p| parse_param(p)).collect()
}

/// The coefficients of `values` as text (`Display` of f64: the shortest text that reads back
/// as the same value).
pub fn coefficients_of(values: &[f64]) -> Vec<Coefficient> {
    values
        .iter()
        .map(|&value| Coefficient {
            text: value.to_string(),
            value,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_and_errors() {
        let v = parse_values("-3,-12", "`num`").unwrap();
        assert_eq!(v, vec![-3.0, -12.0]);
        assert!(parse_values("nan", "`num`").unwrap()[0].is_nan());
        let e = parse_values("1 x", "`num`").unwrap_err().to_string();
        assert!(e.contains("'x'"), "{e}");
        let long = format!("1 {}", "y".repeat(100_000));
        let e = parse_values(&long, "`num`").unwrap_err().to_string();
        assert!(e.len() < 200, "{e}");
    }
}
