//! Exact rational numbers read from text.
//!
//! A coefficient typed as `0.2` means 1/5, `2.00000002` means 200000002/10⁸, `1.5e-3` means
//! 3/2000 and `-7/2` means −7/2: [`Rational::parse`] keeps that exact value. Accepted forms:
//! an optional sign, digits with an optional decimal point (`3`, `3.`, `.5`, `3.25`), an
//! optional exponent (`e` or `E`, optional sign, digits), and optionally `/` followed by a second
//! such number (`1/3`, `-7/2`, `1.5/3e2`). Rejected, with [`LtiError::BadNumber`] naming the
//! token and the reason: empty text, anything else (`0x10`, `1_000`, `1,5`, spaces inside),
//! NaN/infinity, a zero denominator, more than [`MAX_DIGITS`] digits in one number, and an
//! exponent beyond ±[`MAX_EXPONENT`].

use std::fmt;
use std::str::FromStr;

use dashu_int::ops::{BitTest, DivRem, Gcd, UnsignedAbs};
use dashu_int::{IBig, UBig};

use crate::error::{LtiError, Result};

pub use crate::limits::{MAX_DIGITS, MAX_EXPONENT};

/// An exact rational number n/d in lowest terms (d > 0).
///
/// ```
/// use ltikit::poly::exact::Rational;
/// let x = Rational::parse("2.00000002").unwrap();
/// assert_eq!(x.to_string(), "100000001/50000000");
/// assert_eq!(Rational::parse("-7/2").unwrap(), Rational::new(-7, 2).unwrap());
/// assert_eq!(Rational::parse("1.5e-3").unwrap().to_f64(), 0.0015);
/// assert!(Rational::parse("1/0").is_err());
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Rational {
    num: IBig,
    den: UBig,
}

impl Rational {
    /// Reads the exact value of a decimal number or fraction (see the module docs for the
    /// accepted forms). Surrounding whitespace is ignored.
    pub fn parse(text: &str) -> Result<Rational> {
        Rational::parse_named(text, "number")
    }

    /// As [`Rational::parse`], naming the value in the error (e.g. "coefficient 2 of `den`").
    ///
    /// ```
    /// use ltikit::poly::exact::Rational;
    /// let e = Rational::parse_named("1/0", "coefficient 1").unwrap_err();
    /// assert_eq!(e.to_string(), "coefficient 1: '1/0' is not a valid exact number (division by zero)");
    /// ```
    pub fn parse_named(text: &str, what: &str) -> Result<Rational> {
        let t = text.trim();
        parse_token(t).map_err(|reason| {
            LtiError::bad_number(what, t, format!("is not a valid exact number ({reason})"))
        })
    }

    /// The fraction num/den. Errors when `den` is 0.
    ///
    /// ```
    /// use ltikit::poly::exact::Rational;
    /// assert_eq!(Rational::new(6, -4).unwrap().to_string(), "-3/2");
    /// ```
    pub fn new(num: i64, den: i64) -> Result<Rational> {
        if den == 0 {
            return Err(LtiError::bad_number(
                "fraction",
                &format!("{num}/{den}"),
                "is not a valid exact number (division by zero)",
            ));
        }
        Ok(Rational::from_parts(IBig::from(num), IBig::from(den)))
    }

    /// The integer `n`.
    pub fn from_integer(n: i64) -> Rational {
        Rational {
            num: IBig::from(n),
            den: UBig::ONE,
        }
    }

    /// The exact value of a finite `f64` (every double is a dyadic rational): `0.1` gives
    /// 3602879701896397/36028797018963968, not 1/10. Errors on NaN and infinities.
    ///
    /// ```
    /// use ltikit::poly::exact::Rational;
    /// assert_eq!(Rational::from_f64(0.75).unwrap(), Rational::new(3, 4).unwrap());
    /// assert_ne!(Rational::from_f64(0.1).unwrap(), Rational::parse("0.1").unwrap());
    /// ```
    pub fn from_f64(x: f64) -> Result<Rational> {
        if !x.is_finite() {
            return Err(LtiError::NonFinite {
                what: "value".into(),
                value: x,
            });
        }
        if x == 0.0 {
            return Ok(Rational::from_integer(0));
        }
        let bits = x.to_bits();
        let exp = ((bits >> 52) & 0x7ff) as i64;
        let frac = bits & ((1u64 << 52) - 1);
        let (mant, e) = if exp == 0 {
            (frac, -1074)
        } else {
            (frac | (1u64 << 52), exp - 1075)
        };
        let mut num = IBig::from(mant);
        if x < 0.0 {
            num = -num;
        }
        let (num, den) = if e >= 0 {
            (num << e as usize, IBig::ONE)
        } else {
            (num, IBig::ONE << (-e) as usize)
        };
        Ok(Rational::from_parts(num, den))
    }

    /// n/d from big integers, reduced to lowest terms with d > 0. `den` must be non-zero.
    pub(crate) fn from_parts(num: IBig, den: IBig) -> Rational {
        debug_assert!(!den.is_zero());
        let neg = (num < IBig::ZERO) != (den < IBig::ZERO);
        let (n, d) = (num.unsigned_abs(), den.unsigned_abs());
        let g = (&n).gcd(&d);
        let (n, d) = if g.is_one() { (n, d) } else { (n / &g, d / &g) };
        let n = IBig::from(n);
        Rational {
            num: if neg { -n } else { n },
            den: d,
        }
    }

    /// Numerator (carries the sign).
    pub(crate) fn numer(&self) -> &IBig {
        &self.num
    }

    /// Denominator (> 0).
    pub(crate) fn denom(&self) -> &UBig {
        &self.den
    }

    /// True for 0.
    pub fn is_zero(&self) -> bool {
        self.num.is_zero()
    }

    /// −1, 0 or 1.
    pub fn signum(&self) -> i32 {
        if self.num.is_zero() {
            0
        } else if self.num < IBig::ZERO {
            -1
        } else {
            1
        }
    }

    /// The nearest `f64` (round to nearest, ties to even), ±∞ beyond the largest double and
    /// a subnormal or ±0 below the smallest normal one.
    ///
    /// ```
    /// use ltikit::poly::exact::Rational;
    /// assert_eq!(Rational::new(1, 3).unwrap().to_f64(), 1.0 / 3.0);
    /// assert_eq!(Rational::parse("1e-320").unwrap().to_f64(), 1e-320);
    /// ```
    pub fn to_f64(&self) -> f64 {
        ratio_to_f64(&self.num, &self.den)
    }
}

impl FromStr for Rational {
    type Err = LtiError;
    fn from_str(s: &str) -> Result<Rational> {
        Rational::parse(s)
    }
}

impl fmt::Display for Rational {
    /// `n` for integers, `n/d` otherwise.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.den.is_one() {
            write!(f, "{}", self.num)
        } else {
            write!(f, "{}/{}", self.num, self.den)
        }
    }
}

/// A decimal number m·10^e read from text.
struct Decimal {
    mantissa: IBig,
    exp10: i64,
}

fn parse_token(t: &str) -> std::result::Result<Rational, String> {
    if t.is_empty() {
        return Err("empty".into());
    }
    let lower = t.trim_start_matches(['+', '-']).to_ascii_lowercase();
    if matches!(lower.as_str(), "nan" | "inf" | "infinity") {
        return Err("NaN and infinity are not finite numbers".into());
    }
    let mut parts = t.split('/');
    let first = parts.next().unwrap_or("");
    let second = parts.next();
    if parts.next().is_some() {
        return Err("more than one '/'".into());
    }
    match second {
        None => {
            let d = parse_decimal(first)?;
            Ok(from_decimals(&d, None))
        }
        Some(den) => {
            if first.is_empty() {
                return Err("the fraction has no numerator".into());
            }
            if den.is_empty() {
                return Err("the fraction has no denominator".into());
            }
            let n = parse_decimal(first).map_err(|r| format!("numerator: {r}"))?;
            let d = parse_decimal(den).map_err(|r| format!("denominator: {r}"))?;
            if d.mantissa.is_zero() {
                return Err("division by zero".into());
            }
            Ok(from_decimals(&n, Some(&d)))
        }
    }
}

/// `[+-] digits [. digits] [(e|E) [+-] digits]` with at least one mantissa digit.
fn parse_decimal(s: &str) -> std::result::Result<Decimal, String> {
    let b = s.as_bytes();
    let mut i = 0;
    let neg = match b.first() {
        Some(b'-') => {
            i = 1;
            true
        }
        Some(b'+') => {
            i = 1;
            false
        }
        _ => false,
    };
    let mut digits = String::new();
    let mut frac_digits: i64 = 0;
    let mut seen_point = false;
    while i < b.len() {
        match b[i] {
            c @ b'0'..=b'9' => {
                digits.push(c as char);
                if seen_point {
                    frac_digits += 1;
                }
                if digits.len() > MAX_DIGITS {
                    return Err(format!("more than {MAX_DIGITS} digits"));
                }
            }
            b'.' if !seen_point => seen_point = true,
            b'e' | b'E' => break,
            _ => return Err(unexpected(s, i)),
        }
        i += 1;
    }
    if digits.is_empty() {
        return Err("no digits".into());
    }
    let mut exp: i64 = 0;
    if i < b.len() {
        // b[i] is 'e' or 'E'
        i += 1;
        let eneg = match b.get(i) {
            Some(b'-') => {
                i += 1;
                true
            }
            Some(b'+') => {
                i += 1;
                false
            }
            _ => false,
        };
        if i >= b.len() {
            return Err("the exponent has no digits".into());
        }
        while i < b.len() {
            match b[i] {
                c @ b'0'..=b'9' => {
                    exp = exp * 10 + i64::from(c - b'0');
                    if exp > MAX_EXPONENT {
                        return Err(format!(
                            "exponent beyond ±{MAX_EXPONENT} (the bound of exact input)"
                        ));
                    }
                }
                _ => return Err(unexpected(s, i)),
            }
            i += 1;
        }
        if eneg {
            exp = -exp;
        }
    }
    let m: IBig = digits
        .parse::<UBig>()
        .map_err(|_| "not a number".to_string())?
        .into();
    Ok(Decimal {
        mantissa: if neg { -m } else { m },
        exp10: exp - frac_digits,
    })
}

fn unexpected(s: &str, byte: usize) -> String {
    let c = s[byte..].chars().next().unwrap_or('?');
    format!("unexpected character '{c}'")
}

/// n (or n/d) as a reduced rational.
fn from_decimals(n: &Decimal, d: Option<&Decimal>) -> Rational {
    let (dm, de) = match d {
        Some(d) => (d.mantissa.clone(), d.exp10),
        None => (IBig::ONE, 0),
    };
    // n.m·10^n.e / (dm·10^de) = n.m·10^(n.e − de) / dm
    let e = n.exp10 - de;
    let ten = |k: i64| IBig::from(UBig::from(10u8).pow(k.unsigned_abs() as usize));
    let (num, den) = if e >= 0 {
        (&n.mantissa * ten(e), dm)
    } else {
        (n.mantissa.clone(), dm * ten(e))
    };
    Rational::from_parts(num, den)
}

/// num/den (den > 0) rounded to the nearest double, ties to even.
pub(crate) fn ratio_to_f64(num: &IBig, den: &UBig) -> f64 {
    if num.is_zero() {
        return 0.0;
    }
    let neg = *num < IBig::ZERO;
    let a = num.unsigned_abs();
    // Scale so that the integer quotient has 65 or 66 bits.
    let shift = 65 + den.bit_len() as i64 - a.bit_len() as i64;
    let (q, r) = if shift >= 0 {
        (a << shift as usize).div_rem(den)
    } else {
        a.div_rem(&(den << (-shift) as usize))
    };
    let sticky = !r.is_zero();
    // q·2^(−shift) is the value (plus a sticky fraction); q < 2^67.
    let q = u128::try_from(&q).unwrap_or(u128::MAX);
    let len = 128 - i64::from(q.leading_zeros());
    let top = len - 1 - shift; // exponent of the leading bit
    let v = if top > 1023 {
        f64::INFINITY
    } else {
        // Bits kept: 53 for normal numbers, fewer for subnormals.
        let keep = if top >= -1022 { 53 } else { 53 - (-1022 - top) };
        if keep <= 0 {
            // Below half the smallest subnormal, or in (half, 1) of it.
            let half_min = keep == 0 && (q > (1u128 << (len - 1)) || sticky);
            if half_min { f64::from_bits(1) } else { 0.0 }
        } else {
            let drop = (len - keep) as u32;
            let mut m = q >> drop;
            let rest = q & ((1u128 << drop) - 1);
            let half = 1u128 << (drop - 1);
            if rest > half || (rest == half && (sticky || m & 1 == 1)) {
                m += 1;
            }
            ldexp(m as f64, i64::from(drop) - shift)
        }
    };
    if neg { -v } else { v }
}

/// x·2^e for an x and e whose product is representable (no double rounding on the way).
fn ldexp(mut x: f64, mut e: i64) -> f64 {
    let big = f64::from_bits(((1023 + 1000) as u64) << 52); // 2^1000
    let small = f64::from_bits(((1023 - 1000) as u64) << 52); // 2^-1000
    while e > 1000 {
        x *= big;
        e -= 1000;
    }
    while e < -1000 {
        x *= small;
        e += 1000;
    }
    x * f64::from_bits(((1023 + e) as u64) << 52)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // correctly rounded conversions are compared exactly
    use super::*;

    fn q(s: &str) -> Rational {
        Rational::parse(s).unwrap()
    }

    #[test]
    fn decimals_exponents_fractions() {
        assert_eq!(q("0.2"), Rational::new(1, 5).unwrap());
        assert_eq!(q("-2E+4"), Rational::from_integer(-20000));
        assert_eq!(q("1.5e-3"), Rational::new(3, 2000).unwrap());
        assert_eq!(q("+.5"), Rational::new(1, 2).unwrap());
        assert_eq!(q("3."), Rational::from_integer(3));
        assert_eq!(q("-7/2"), Rational::new(-7, 2).unwrap());
        assert_eq!(q("1.5/3e2"), Rational::new(1, 200).unwrap());
        assert_eq!(q("2/-4"), Rational::new(-1, 2).unwrap());
        assert_eq!(q(" 0.000 "), Rational::from_integer(0));
        assert_eq!(q("-0"), Rational::from_integer(0));
    }

    #[test]
    fn malformed_tokens_name_the_reason() {
        let cases = [
            ("1/0", "division by zero"),
            ("1/0.000e5", "division by zero"),
            ("1/", "no denominator"),
            ("/2", "no numerator"),
            ("", "empty"),
            ("abc", "unexpected character 'a'"),
            ("1.2.3", "unexpected character '.'"),
            ("1e", "exponent has no digits"),
            ("1e+", "exponent has no digits"),
            ("e5", "no digits"),
            ("-", "no digits"),
            ("1/2/3", "more than one '/'"),
            ("NaN", "NaN and infinity"),
            ("-inf", "NaN and infinity"),
            ("Infinity", "NaN and infinity"),
            ("1e999999", "exponent beyond ±1000"),
            ("1e-1001", "exponent beyond ±1000"),
            ("0x10", "unexpected character 'x'"),
            ("1 000", "unexpected character ' '"),
            ("1,5", "unexpected character ','"),
        ];
        for (tok, why) in cases {
            match Rational::parse(tok) {
                Err(LtiError::BadNumber { token, reason, .. }) => {
                    assert!(reason.contains(why), "{tok}: {reason}");
                    assert_eq!(token, tok.trim());
                }
                other => panic!("{tok}: {other:?}"),
            }
        }
        // 1000 digits are fine, 1001 are not; the message abbreviates the token.
        assert!(Rational::parse(&"7".repeat(1000)).is_ok());
        let long = "7".repeat(1001);
        match Rational::parse(&long) {
            Err(LtiError::BadNumber { token, reason, .. }) => {
                assert!(reason.contains("more than 1000 digits"));
                assert!(token.chars().count() < 100, "{token}");
                assert!(token.contains("1001 characters"));
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(q("1e1000").to_f64(), f64::INFINITY);
        assert_eq!(q("1e-1000").to_f64(), 0.0);
    }

    #[test]
    fn conversion_to_f64_is_correctly_rounded() {
        // Against Rust's own correctly rounded decimal parser.
        for s in [
            "0.1",
            "2.00000002",
            "1.00000002",
            "-3.03",
            "123456789012345678901234567890",
            "1.7976931348623157e308",
            "1.7976931348623159e308",
            "2.2250738585072014e-308",
            "4.9406564584124654e-324",
            "2.4703282292062328e-324",
            "2.4703282292062327e-324",
            "1e-320",
            "0.30000000000000004",
            "9007199254740993",
            "9007199254740995",
        ] {
            assert_eq!(q(s).to_f64(), s.parse::<f64>().unwrap(), "{s}");
        }
        assert_eq!(Rational::new(1, 3).unwrap().to_f64(), 1.0 / 3.0);
        assert_eq!(Rational::new(-2, 3).unwrap().to_f64(), -2.0 / 3.0);
    }

    #[test]
    fn f64_round_trip_is_exact() {
        for x in [0.1, -1e-310, 5e-324, 1.7976931348623157e308, 3.0, -0.0] {
            assert_eq!(Rational::from_f64(x).unwrap().to_f64(), x);
        }
        assert!(Rational::from_f64(f64::NAN).is_err());
    }
}
