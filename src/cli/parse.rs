//! Command-line values: number lists ("1 0.8 4", "1,0.8,4", "-3,-12") and `NAME=VALUE`
//! parameters, read by the one parser of [`crate::lti::plant`].

use anyhow::Result;

/// Parses a list of numbers separated by spaces, commas or semicolons. `what` names the option
/// in errors ("--t: 'x' is not a number"). NaN and infinities parse (they are rejected later
/// with a message that names the value).
pub fn numbers(text: &str, what: &str) -> Result<Vec<f64>> {
    Ok(crate::lti::plant::parse_values(text, what)?)
}

/// Parses every `NAME=VALUE` of a repeated `--param`.
pub fn params(list: &[String]) -> Result<Vec<(String, f64)>> {
    Ok(crate::lti::plant::parse_params(list)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn number_lists_and_params() {
        assert_eq!(numbers("1 0.8 4", "--t").unwrap(), vec![1.0, 0.8, 4.0]);
        assert!(
            numbers("1 x", "--t")
                .unwrap_err()
                .to_string()
                .contains("'x'")
        );
        assert_eq!(params(&["K=4".into()]).unwrap(), vec![("K".into(), 4.0)]);
        assert!(params(&["K".into()]).is_err());
    }
}
