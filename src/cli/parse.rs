//! Parsing of command-line values: number lists ("1 0.8 4", "1,0.8,4", "-3,-12") and
//! `NAME=VALUE` parameters.

use anyhow::{Result, bail};

/// Parses a list of numbers separated by spaces, commas or semicolons. `what` names the option
/// in errors ("--num: 'x' is not a number"). NaN and infinities parse (they are rejected later
/// with a message that names the coefficient).
pub fn numbers(text: &str, what: &str) -> Result<Vec<f64>> {
    let mut out = Vec::new();
    for tok in text
        .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
        .filter(|t| !t.is_empty())
    {
        match tok.parse::<f64>() {
            Ok(v) => out.push(v),
            Err(_) => bail!("{what}: '{tok}' is not a number"),
        }
    }
    if out.is_empty() {
        bail!("{what}: no numbers given");
    }
    Ok(out)
}

/// Parses every `NAME=VALUE` of a repeated `--param`.
pub fn params(list: &[String]) -> Result<Vec<(String, f64)>> {
    list.iter().map(|p| param(p)).collect()
}

/// Parses `NAME=VALUE`.
pub fn param(text: &str) -> Result<(String, f64)> {
    let Some((k, v)) = text.split_once('=') else {
        bail!("--param '{text}': expected NAME=VALUE");
    };
    let k = k.trim();
    if k.is_empty() {
        bail!("--param '{text}': missing parameter name");
    }
    let v = v.trim();
    if v.is_empty() {
        bail!("--param '{text}': missing value for {k}");
    }
    let value: f64 = v
        .parse()
        .map_err(|_| anyhow::anyhow!("--param {k}: '{v}' is not a number"))?;
    Ok((k.to_string(), value))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn number_lists() {
        assert_eq!(numbers("1 0.8 4", "--den").unwrap(), vec![1.0, 0.8, 4.0]);
        assert_eq!(numbers("-3,-12", "--num").unwrap(), vec![-3.0, -12.0]);
        assert_eq!(numbers(" 1, 2 ;3 ", "--num").unwrap(), vec![1.0, 2.0, 3.0]);
        assert!(
            numbers("1 x", "--num")
                .unwrap_err()
                .to_string()
                .contains("'x'")
        );
        assert!(numbers("  ", "--num").is_err());
        assert!(numbers("nan", "--num").unwrap()[0].is_nan());
    }

    #[test]
    fn params() {
        assert_eq!(param("K=4").unwrap(), ("K".into(), 4.0));
        assert!(param("K").is_err());
        assert!(param("K=").is_err());
        assert!(param("=3").is_err());
        assert!(param("K=abc").is_err());
    }
}
