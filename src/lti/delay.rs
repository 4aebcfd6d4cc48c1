//! Dead time: the factor e^(−sT) of a delayed plant, kept exact beside the rational part.
//!
//! A delay is a property of a model, like its [`Domain`](crate::lti::Domain): a
//! [`TransferFunction`] and the factored core carry `delay` (seconds), a
//! [`StateSpace`](crate::StateSpace) carries one delay per input and per output (a channel's
//! delay is the sum of its input's and its output's). The rational part is never replaced
//! silently: analyses that can keep the delay exact do (the phase −ωT, the shifted closed
//! form, the delayed closed loop); the Padé approximant ([`pade`]) is used only when asked.
//!
//! In discrete time a delay of d whole sampling periods is z^(−d) — rational, exact — and
//! is absorbed into the model (d poles at z = 0); [`delay_samples`] converts.

use crate::error::{LtiError, Result};
use crate::fmt::fmt_num;
use crate::limits::{MAX_DELAY, MAX_PADE_ORDER};
use crate::lti::TransferFunction;
use crate::poly::Poly;

/// Checks a dead time: finite, ≥ 0 and at most [`MAX_DELAY`] seconds; returns it.
///
/// ```
/// use ltikit::lti::delay::check_delay;
/// assert_eq!(check_delay(0.5).unwrap(), 0.5);
/// assert!(check_delay(-1.0).is_err() && check_delay(f64::NAN).is_err());
/// assert!(check_delay(1e300).unwrap_err().to_string().contains("MAX_DELAY"));
/// ```
pub fn check_delay(t: f64) -> Result<f64> {
    if !t.is_finite() || t < 0.0 {
        return Err(LtiError::InvalidInput(format!(
            "`delay`: a dead time must be a finite number ≥ 0 s (found {})",
            fmt_num(t)
        )));
    }
    if t > MAX_DELAY as f64 {
        return Err(LtiError::InvalidInput(format!(
            "`delay`: {} s exceeds the limit of {} s (MAX_DELAY): beyond it the phase −ωT \
             keeps no digits of its angle",
            fmt_num(t),
            crate::limits::grouped(MAX_DELAY)
        )));
    }
    Ok(t)
}

/// The number of sampling periods `dt` in the delay `t` (a discrete model delays by whole
/// samples: z^(−d)). Errors unless `t` is a whole multiple of `dt` (to 1e-9 relative).
///
/// ```
/// use ltikit::lti::delay::delay_samples;
/// assert_eq!(delay_samples(0.3, 0.1).unwrap(), 3);
/// assert!(delay_samples(0.25, 0.1).is_err());
/// ```
pub fn delay_samples(t: f64, dt: f64) -> Result<usize> {
    let t = check_delay(t)?;
    let d = (t / dt).round();
    if (t / dt - d).abs() > 1e-9 * d.max(1.0) {
        return Err(LtiError::InvalidInput(format!(
            "`delay`: {} s is not a whole number of sampling periods (dt = {} s); a discrete \
             model delays by whole samples z^(−d)",
            fmt_num(t),
            fmt_num(dt)
        )));
    }
    if d > 1e5 {
        return Err(LtiError::InvalidInput(format!(
            "`delay`: {} s is {} sampling periods; at most 100 000 are absorbed as poles at z = 0",
            fmt_num(t),
            fmt_num(d)
        )));
    }
    Ok(d as usize)
}

/// The coefficients of the [n/n] Padé approximant of e^(−sT): numerator and denominator in
/// descending powers of s, P(s)/Q(s) with Q(s) = Σ cₖ (sT)^k, P(s) = Q(−s),
/// cₖ = (2n − k)!·n! / ((2n)!·k!·(n − k)!) (so c₀ = 1).
///
/// Errors: a bad delay ([`check_delay`]), `n` = 0 or above [`MAX_PADE_ORDER`].
///
/// ```
/// use ltikit::lti::delay::pade;
/// // [1/1]: (1 − sT/2)/(1 + sT/2); T = 2: (−s + 1)/(s + 1)
/// let g = pade(2.0, 1).unwrap();
/// assert_eq!(g.num().coeffs(), &[-1.0, 1.0]);
/// assert_eq!(g.den().coeffs(), &[1.0, 1.0]);
/// // |P/Q| = 1 on the axis, and the phase is −ωT to O((ωT)^(2n+1))
/// let g = pade(0.5, 3).unwrap();
/// let v = g.eval(num_complex::Complex64::new(0.0, 1.0));
/// assert!((v.norm() - 1.0).abs() < 1e-15);
/// assert!((v.arg() + 0.5).abs() < 1e-7); // error ≈ (ωT)⁷·(3!)²/(6!·7!) = 7.8e-8
/// ```
pub fn pade(t: f64, n: usize) -> Result<TransferFunction> {
    let t = check_delay(t)?;
    if n == 0 || n > MAX_PADE_ORDER {
        return Err(LtiError::InvalidInput(format!(
            "`pade`: the order of a Padé approximant must be 1 to {MAX_PADE_ORDER} (found {n})"
        )));
    }
    if t == 0.0 {
        return TransferFunction::from_descending(&[1.0], &[1.0]);
    }
    let (p, q) = pade_coefficients(t, n);
    if q.iter().any(|x| !x.is_finite() || *x == 0.0) {
        return Err(LtiError::InvalidInput(format!(
            "`pade`: the [{n}/{n}] approximant of a {} s delay has coefficients beyond the \
             range of a double",
            fmt_num(t)
        )));
    }
    TransferFunction::new(Poly::from_descending(&p)?, Poly::from_descending(&q)?)
}

/// Numerator and denominator of the [n/n] Padé approximant of e^(−sT) in descending powers
/// of s, any order (no checks: the root search of `analysis::delay` uses high orders at
/// T = 1 for its starting points): Q(s) = Σ cₖ (sT)^k, P(s) = Q(−s),
/// cₖ = (2n − k)!·n! / ((2n)!·k!·(n − k)!), by the ratio cₖ/cₖ₋₁ = (n − k + 1)/(k(2n − k + 1)).
pub(crate) fn pade_coefficients(t: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut q = vec![1.0];
    let mut c = 1.0_f64;
    let mut tk = 1.0_f64;
    for k in 1..=n {
        c *= (n - k + 1) as f64 / (k as f64 * (2 * n - k + 1) as f64);
        tk *= t;
        q.push(c * tk);
    }
    let p: Vec<f64> = q
        .iter()
        .enumerate()
        .map(|(k, &x)| if k % 2 == 1 { -x } else { x })
        .rev()
        .collect();
    q.reverse();
    (p, q)
}

/// The delay of a parallel connection: both branches must have the same dead time (then
/// G₁e^(−sT) + G₂e^(−sT) = (G₁ + G₂)e^(−sT)); different ones have no rational part with one
/// delay.
#[allow(clippy::float_cmp)] // the same delay is the same number
pub fn common_delay(operation: &str, a: f64, b: f64) -> Result<f64> {
    if a == b {
        Ok(a)
    } else {
        Err(LtiError::InvalidInput(format!(
            "{operation}: the branches have different dead times ({} s and {} s); their sum is              not a rational function times one delay (replace the delays by a Padé              approximant, `pade`)",
            fmt_num(a),
            fmt_num(b)
        )))
    }
}

/// Errors when `delay` ≠ 0: `operation` needs a rational model (a feedback loop around a
/// dead time has no rational transfer function; the delayed loop is analysed as such, or the
/// delay replaced by its Padé approximant).
pub fn require_rational(operation: &str, delay: f64) -> Result<()> {
    if delay == 0.0 {
        return Ok(());
    }
    Err(LtiError::InvalidInput(format!(
        "{operation} needs a rational model; this one has a dead time e^(-{} s) (analyse the          delayed loop with a controller, or replace the delay by a Padé approximant, `pade`)",
        fmt_num(delay)
    )))
}

/// The delay factor as text in the model's variable: `e^(-0.5 s)` (empty for no delay).
///
/// ```
/// assert_eq!(ltikit::lti::delay::factor_text(0.5), "e^(-0.5 s)");
/// assert_eq!(ltikit::lti::delay::factor_text(0.0), "");
/// ```
pub fn factor_text(t: f64) -> String {
    if t == 0.0 {
        String::new()
    } else {
        format!("e^(-{} s)", fmt_num(t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::Complex64;

    #[test]
    fn pade_coefficients_match_the_closed_form() {
        // [3/3]: Q = 1 + sT/2 + (sT)²/10 + (sT)³/120 (standard table)
        let g = pade(1.0, 3).unwrap();
        let q = g.den().coeffs();
        let lead = q[0];
        let want = [1.0 / 120.0, 0.1, 0.5, 1.0];
        for (a, b) in q.iter().zip(want) {
            assert!((a / lead * (1.0 / 120.0) - b).abs() < 1e-15, "{q:?}");
        }
    }

    #[test]
    fn pade_phase_error_shrinks_with_order() {
        let w = 1.0;
        let mut last = f64::INFINITY;
        for n in 1..=10 {
            let g = pade(1.0, n).unwrap();
            let v = g.eval(Complex64::new(0.0, w));
            let err = (v.arg() + w).abs();
            assert!(err < last || err < 1e-15, "n = {n}: {err}");
            assert!((v.norm() - 1.0).abs() < 1e-13);
            last = err;
        }
        assert!(last < 1e-15);
    }

    #[test]
    fn high_order_coefficients_match_the_exponential() {
        // [8/8] at T = 1 against e^(−x) on the real axis
        let (num, den) = pade_coefficients(1.0, 8);
        let ev = |c: &[f64], x: f64| c.iter().fold(0.0, |a, &v| a * x + v);
        for x in [0.1, 0.5, 1.0, 1.5] {
            let r = ev(&num, x) / ev(&den, x);
            assert!((r - (-x).exp()).abs() < 1e-14, "x = {x}: {r}");
        }
    }

    #[test]
    fn bad_input() {
        assert!(pade(1.0, 0).is_err());
        assert!(pade(1.0, MAX_PADE_ORDER + 1).is_err());
        assert!(pade(f64::INFINITY, 3).is_err());
        assert!(check_delay(-0.0).is_ok());
        assert!(delay_samples(1e5, 1e-5).is_err());
    }
}
