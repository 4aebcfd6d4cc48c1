//! Number formatting for reports and messages: compact numbers, a given number of
//! significant digits, roots and conjugate pairs. The ground floor: every layer may print a
//! number in a reason or a label, so this module depends on nothing of the crate.

use num_complex::Complex64;

/// Formats a number compactly: integers without a decimal point, others with up to 6
/// significant digits, no trailing zeros.
pub fn fmt_num(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if x.fract() == 0.0 && x.abs() < 1e15 {
        return format!("{}", x as i64);
    }
    let ax = x.abs();
    if !(1e-4..1e6).contains(&ax) {
        let s = format!("{:.5e}", x);
        // trim mantissa zeros: 1.50000e-5 -> 1.5e-5
        if let Some((m, e)) = s.split_once('e') {
            let m = if m.contains('.') {
                m.trim_end_matches('0').trim_end_matches('.')
            } else {
                m
            };
            return format!("{m}e{e}");
        }
        return s;
    }
    let digits = 6i32 - 1 - ax.log10().floor() as i32;
    let s = format!("{:.*}", digits.max(0) as usize, x);
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Formats a number with at most `sig` significant digits (trailing zeros trimmed), for
/// human-readable reasons and reports: `fmt_sig(1.3229, 3)` is "1.32".
pub fn fmt_sig(x: f64, sig: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return if x == 0.0 { "0".into() } else { format!("{x}") };
    }
    let ax = x.abs();
    if !(1e-4..1e7).contains(&ax) {
        let s = format!("{:.*e}", sig.saturating_sub(1), x);
        if let Some((m, e)) = s.split_once('e') {
            let m = if m.contains('.') {
                m.trim_end_matches('0').trim_end_matches('.')
            } else {
                m
            };
            return format!("{m}e{e}");
        }
        return s;
    }
    let digits = sig as i32 - 1 - ax.log10().floor() as i32;
    let s = format!("{:.*}", digits.max(0) as usize, x);
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// [`fmt_sig`] of a value that may be missing: "not computed" for `None` (a metric whose
/// note says why).
///
/// ```
/// use ltikit::fmt::fmt_opt;
/// assert_eq!(fmt_opt(Some(1.23456), 3), "1.23");
/// assert_eq!(fmt_opt(None, 3), "not computed");
/// ```
pub fn fmt_opt(x: Option<f64>, sig: usize) -> String {
    x.map_or_else(|| "not computed".to_string(), |x| fmt_sig(x, sig))
}

/// Formats a root for messages: `-2`, `0.25 ± 1.32j` (a conjugate pair), `±1j`, `0`, with
/// `sig` significant digits. A root with positive or negative imaginary part is shown as its
/// pair.
pub fn fmt_root(z: Complex64, sig: usize) -> String {
    if z.im == 0.0 {
        return fmt_sig(z.re, sig);
    }
    let im = fmt_sig(z.im.abs(), sig);
    if z.re == 0.0 {
        format!("±{im}j")
    } else {
        format!("{} ± {im}j", fmt_sig(z.re, sig))
    }
}

/// `v` with its digits in groups of three from the right, separated by spaces, for numbers
/// of five digits or more ("10 000 000", "4096"): how the limits are printed.
///
/// ```
/// assert_eq!(ltikit::fmt::grouped(10_000_000), "10 000 000");
/// assert_eq!(ltikit::fmt::grouped(4096), "4096");
/// ```
pub fn grouped(v: u64) -> String {
    let s = v.to_string();
    if v < 10_000 {
        return s;
    }
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i) % 3 == 0 {
            out.push(' ');
        }
        out.push(c);
    }
    out
}

/// "10 000 000 sample points": a limit with its unit, as error messages print it.
///
/// ```
/// assert_eq!(ltikit::fmt::amount(16_384, "px a side"), "16 384 px a side");
/// assert_eq!(ltikit::fmt::amount(200, ""), "200");
/// ```
pub fn amount(max: u64, unit: &str) -> String {
    if unit.is_empty() {
        grouped(max)
    } else {
        format!("{} {unit}", grouped(max))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formatting() {
        assert_eq!(fmt_num(1.0 / 3.0), "0.333333");
        assert_eq!(fmt_num(2.5e-7), "2.5e-7");
        assert_eq!(fmt_num(-12.0), "-12");
        assert_eq!(fmt_sig(1.32287, 3), "1.32");
        assert_eq!(fmt_root(Complex64::new(0.25, -1.3229), 3), "0.25 ± 1.32j");
        assert_eq!(fmt_root(Complex64::new(0.0, 2.0), 3), "±2j");
    }
}
