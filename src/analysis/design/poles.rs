//! The requested closed-loop poles: read from text (`-1, -2+1j, -2-1j`), checked (finite,
//! closed under conjugation), paired, and matched to the achieved eigenvalues.

use num_complex::Complex64;

use crate::error::{LtiError, Result, abbreviate};

/// Reads a list of complex numbers separated by commas, semicolons or spaces: `-1`,
/// `-2+1j`, `-2-1.5i`, `3j`, `1e-3-2e1j` (the imaginary unit written `j` or `i`).
///
/// Errors: an empty list, a token that is not a number (named, abbreviated).
///
/// ```
/// use ltikit::analysis::design::parse_poles;
/// let p = parse_poles("-1, -2+1j, -2-1j").unwrap();
/// assert_eq!(p.len(), 3);
/// assert_eq!((p[1].re, p[1].im), (-2.0, 1.0));
/// assert_eq!((p[2].re, p[2].im), (-2.0, -1.0));
/// assert!(parse_poles("-1, x").is_err());
/// ```
pub fn parse_poles(text: &str) -> Result<Vec<Complex64>> {
    let tokens: Vec<&str> = text
        .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .collect();
    if tokens.is_empty() {
        return Err(LtiError::invalid("`poles`: the list is empty"));
    }
    tokens.iter().map(|t| parse_complex(t)).collect()
}

/// One complex number: `a`, `bj`, `a+bj`, `a-bj` (`i` for `j` too).
fn parse_complex(tok: &str) -> Result<Complex64> {
    let bad = || LtiError::bad_number("`poles`", tok, "is not a number (write a, bj or a+bj)");
    let real = |s: &str| s.parse::<f64>().map_err(|_| bad());
    let Some(body) = tok.strip_suffix(['j', 'i', 'J', 'I']) else {
        return Ok(Complex64::new(real(tok)?, 0.0));
    };
    // the sign that starts the imaginary part: the last + or − not at the start and not
    // after an exponent mark
    let bytes = body.as_bytes();
    let split = (1..bytes.len())
        .rev()
        .find(|&k| (bytes[k] == b'+' || bytes[k] == b'-') && !matches!(bytes[k - 1], b'e' | b'E'));
    let (re, im) = match split {
        Some(k) => (real(&body[..k])?, &body[k..]),
        None => (0.0, body),
    };
    let im = match im {
        "" | "+" => 1.0,
        "-" => -1.0,
        s => real(s)?,
    };
    Ok(Complex64::new(re, im))
}

/// One complex number (not a pair) with `sig` significant digits: "-2", "3j", "-2 + 1j".
///
/// ```
/// use num_complex::Complex64 as C;
/// use ltikit::analysis::design::poles::complex_label;
/// assert_eq!(complex_label(C::new(-2.0, -1.0), 6), "-2 - 1j");
/// assert_eq!(complex_label(C::new(0.0, 3.0), 6), "3j");
/// ```
pub fn complex_label(z: Complex64, sig: usize) -> String {
    let f = |x: f64| crate::fmt::fmt_sig(x, sig);
    match (z.re == 0.0, z.im == 0.0) {
        (_, true) => f(z.re),
        (true, false) => format!("{}j", f(z.im)),
        (false, false) => format!(
            "{} {} {}j",
            f(z.re),
            if z.im < 0.0 { "-" } else { "+" },
            f(z.im.abs())
        ),
    }
}

/// Checks the requested poles: `n` of them, finite, closed under conjugation (a partner
/// within 1e-12 relative is made the exact conjugate). Returns the poles in the given order
/// with exact partners and, for each, the index of its conjugate partner (itself when real).
pub(crate) fn check_poles(poles: &[Complex64], n: usize) -> Result<(Vec<Complex64>, Vec<usize>)> {
    if poles.len() != n {
        return Err(LtiError::invalid(format!(
            "`poles`: {} poles requested for a plant with {n} state{}",
            poles.len(),
            if n == 1 { "" } else { "s" }
        )));
    }
    for p in poles {
        for v in [p.re, p.im] {
            if !v.is_finite() {
                return Err(LtiError::NonFinite {
                    what: "a requested pole (`poles`)".into(),
                    value: v,
                });
            }
        }
    }
    let mut out = poles.to_vec();
    let mut partner: Vec<usize> = (0..n).collect();
    let mut used = vec![false; n];
    for i in 0..n {
        if out[i].im <= 0.0 || used[i] {
            continue;
        }
        let tol = 1e-12 * out[i].norm();
        let found = (0..n).find(|&k| {
            !used[k] && k != i && out[k].im < 0.0 && (out[k].conj() - out[i]).norm() <= tol
        });
        let Some(k) = found else {
            return Err(LtiError::invalid(format!(
                "`poles`: the requested poles are not closed under conjugation: {} has no \
                 partner {} (a real gain needs conjugate pairs)",
                abbreviate(&complex_label(out[i], 6)),
                abbreviate(&complex_label(out[i].conj(), 6))
            )));
        };
        out[k] = out[i].conj();
        used[i] = true;
        used[k] = true;
        partner[i] = k;
        partner[k] = i;
    }
    if let Some(i) = (0..n).find(|&i| out[i].im < 0.0 && !used[i]) {
        return Err(LtiError::invalid(format!(
            "`poles`: the requested poles are not closed under conjugation: {} has no \
             partner {} (a real gain needs conjugate pairs)",
            complex_label(out[i], 6),
            complex_label(out[i].conj(), 6)
        )));
    }
    Ok((out, partner))
}

/// The achieved eigenvalues reordered to face the requested poles (each requested pole
/// takes the nearest achieved one not yet taken, the requested poles in the given order),
/// with the distances.
pub(crate) fn match_poles(
    requested: &[Complex64],
    achieved: &[Complex64],
) -> (Vec<Complex64>, Vec<f64>) {
    let mut free: Vec<Complex64> = achieved.to_vec();
    let mut out = Vec::with_capacity(requested.len());
    let mut dist = Vec::with_capacity(requested.len());
    for r in requested {
        let best = free
            .iter()
            .enumerate()
            .min_by(|a, b| (a.1 - r).norm().total_cmp(&(b.1 - r).norm()))
            .map(|(k, _)| k);
        if let Some(k) = best {
            let z = free.swap_remove(k);
            dist.push((z - r).norm());
            out.push(z);
        }
    }
    (out, dist)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn complex_tokens() {
        let p = parse_poles("1e-3-2e1j 3j -j +2.5 -1e+2+1e-2i").unwrap();
        assert_eq!(p[0], Complex64::new(1e-3, -20.0));
        assert_eq!(p[1], Complex64::new(0.0, 3.0));
        assert_eq!(p[2], Complex64::new(0.0, -1.0));
        assert_eq!(p[3], Complex64::new(2.5, 0.0));
        assert_eq!(p[4], Complex64::new(-100.0, 1e-2));
        assert!(parse_poles("1+").is_err());
        assert!(parse_poles("j1").is_err());
        assert!(parse_poles(" , ").is_err());
    }

    #[test]
    fn conjugation_is_checked() {
        let c = |a, b| Complex64::new(a, b);
        let (p, partner) = check_poles(&[c(-1.0, 2.0), c(-3.0, 0.0), c(-1.0, -2.0)], 3).unwrap();
        assert_eq!(partner, vec![2, 1, 0]);
        assert_eq!(p[2], p[0].conj());
        let e = check_poles(&[c(-1.0, 2.0), c(-1.0, -2.5)], 2)
            .unwrap_err()
            .to_string();
        assert!(e.contains("conjugation"), "{e}");
        assert!(check_poles(&[c(-1.0, 0.0)], 2).is_err());
        assert!(check_poles(&[c(f64::NAN, 0.0)], 1).is_err());
    }
}
