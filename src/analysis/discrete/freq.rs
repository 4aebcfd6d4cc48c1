//! G(e^(jωT)): magnitude and a continuous phase from the factors, on 0 ≤ ω ≤ π/T.
//!
//! The phase is not unwrapped from samples. Each factor (z − r) contributes an angle that is
//! continuous in θ = ωT on [0, π] by itself:
//! - |r| < 1: ∠(e^(jθ) − r) = θ + ∠(1 − r·e^(−jθ)), the second term principal (its argument
//!   has a positive real part);
//! - |r| > 1: ∠(−r) + ∠(1 − e^(jθ)/r), with ∠(−r) = π for a real r > 1 (so an unstable real
//!   pole starts at −180°, as in s) and ± of a pair cancelling;
//! - |r| = 1, r = e^(jα): (θ + α)/2 ± π/2 on either side of θ = α (a jump of π where G has a
//!   pole or zero on the circle, as an imaginary-axis pair in s); exactly at θ = α the
//!   midpoint, except a real root (z = ±1), which takes its one-sided limit from inside
//!   (0, π): 1/(z − 1) starts at −90° like 1/s.
//!
//! φ = [k < 0 ? −180° : 0] + Σ zeros − Σ poles, over the reduced factors with their
//! multiplicities; |G| is summed in logarithms (no overflow at high order).

use std::f64::consts::{FRAC_PI_2, PI};

use num_complex::Complex64;

use super::circle_side;
use crate::analysis::{Factored, FrequencyResponse, HalfPlane};
use crate::error::{LtiError, Result};
use crate::poly::Root;

/// Every frequency finite, ≥ 0 and at most the Nyquist frequency π/T (to rounding).
pub(crate) fn check_band(w: &[f64], dt: f64) -> Result<()> {
    let nyquist = PI / dt;
    for &x in w {
        if !x.is_finite() || x < 0.0 {
            return Err(LtiError::InvalidInput(format!(
                "frequencies must be finite and ≥ 0 (found {})",
                crate::fmt::fmt_num(x)
            )));
        }
        if x > nyquist * (1.0 + 1e-12) {
            return Err(LtiError::InvalidInput(format!(
                "ω = {} rad/s is beyond the Nyquist frequency π/T = {} rad/s of this \
                 discrete-time plant (dt = {})",
                crate::fmt::fmt_num(x),
                crate::fmt::fmt_sig(nyquist, 6),
                crate::fmt::fmt_num(dt)
            )));
        }
    }
    Ok(())
}

/// ln|e^(jθ) − r| and its continuous angle (see the module docs).
fn factor(theta: f64, r: Complex64) -> (f64, f64) {
    let e = Complex64::from_polar(1.0, -theta);
    match circle_side(r) {
        HalfPlane::Left => {
            let q = Complex64::new(1.0, 0.0) - r * e;
            (q.norm().ln(), theta + q.im.atan2(q.re))
        }
        HalfPlane::Right => {
            let q = Complex64::new(1.0, 0.0) - Complex64::from_polar(1.0, theta) / r;
            let base = if r.im == 0.0 && r.re > 0.0 {
                PI
            } else {
                (-r.im).atan2(-r.re)
            };
            (r.norm().ln() + q.norm().ln(), base + q.im.atan2(q.re))
        }
        HalfPlane::Axis => {
            let alpha = r.im.atan2(r.re);
            let half = (theta - alpha) / 2.0;
            let sin = half.sin();
            let side = if sin != 0.0 && half.abs() > 1e-300 {
                sin.signum()
            } else if r.im == 0.0 {
                // z = 1 seen from θ > 0, z = −1 from θ < π
                if r.re > 0.0 { 1.0 } else { -1.0 }
            } else {
                0.0
            };
            (
                (2.0 * sin.abs()).ln(),
                (theta + alpha) / 2.0 + FRAC_PI_2 * side,
            )
        }
    }
}

/// ln|G(e^(jθ))| and the continuous phase (radians) of the reduced factors.
pub(crate) fn eval(f: &Factored, theta: f64) -> (f64, f64) {
    if f.is_zero() {
        return (f64::NEG_INFINITY, 0.0);
    }
    let k = f.gain();
    let mut ln = k.abs().ln();
    let mut phase = if k < 0.0 { -PI } else { 0.0 };
    let mut add = |roots: &[Root], sign: f64| {
        for r in roots {
            let (l, p) = factor(theta, r.value);
            let m = r.multiplicity as f64;
            ln += sign * m * l;
            phase += sign * m * p;
        }
    };
    add(f.reduced_zeros(), 1.0);
    add(f.reduced_poles(), -1.0);
    (ln, phase)
}

/// The frequency response of a discrete-time plant (see the module docs).
pub(crate) fn freq_response(f: &Factored, dt: f64, w: &[f64]) -> Result<FrequencyResponse> {
    check_band(w, dt)?;
    let mut out = FrequencyResponse {
        w: w.to_vec(),
        magnitude: Vec::with_capacity(w.len()),
        magnitude_db: Vec::with_capacity(w.len()),
        phase_deg: Vec::with_capacity(w.len()),
    };
    for &x in w {
        let (ln, ph) = eval(f, (x * dt).min(PI));
        out.magnitude.push(ln.exp());
        out.magnitude_db.push(ln * 20.0 / std::f64::consts::LN_10);
        out.phase_deg.push(ph.to_degrees());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::TransferFunction;
    use crate::lti::Domain;

    fn zf(num: &[f64], den: &[f64], dt: f64) -> Factored {
        TransferFunction::from_descending(num, den)
            .unwrap()
            .with_domain(Domain::discrete(dt).unwrap())
            .factored()
            .unwrap()
    }

    #[test]
    fn values_match_horner_and_the_phase_is_continuous() {
        let dt = 0.1;
        let cases: [(&[f64], &[f64]); 5] = [
            (&[0.5], &[1.0, -0.5]),
            (&[1.0, -2.0], &[1.0, -1.2, 0.61]), // RHP-like zero outside the circle
            (&[1.0], &[1.0, -1.0]),             // integrator
            (&[-1.0, 0.3], &[1.0, 0.0, 0.0, -0.2]),
            (&[1.0], &[1.0, -2.5, 1.0]), // unstable real pole 2
        ];
        for (num, den) in cases {
            let f = zf(num, den, dt);
            let g = TransferFunction::from_descending(num, den).unwrap();
            let n = 2001;
            let w: Vec<f64> = (1..n).map(|i| PI / dt * i as f64 / n as f64).collect();
            let r = freq_response(&f, dt, &w).unwrap();
            for (i, &x) in w.iter().enumerate() {
                let h = g.eval(Complex64::from_polar(1.0, x * dt));
                assert!(
                    (r.magnitude[i] / h.norm() - 1.0).abs() < 1e-12,
                    "{num:?}/{den:?} at {x}"
                );
                let d = (r.phase_deg[i].to_radians() - h.arg()).rem_euclid(2.0 * PI);
                assert!(d.min(2.0 * PI - d) < 1e-12, "{num:?}/{den:?} phase at {x}");
                if i > 0 {
                    assert!((r.phase_deg[i] - r.phase_deg[i - 1]).abs() < 5.0);
                }
            }
        }
    }

    #[test]
    fn the_integrator_starts_at_minus_90_and_a_delay_is_linear() {
        let f = zf(&[1.0], &[1.0, -1.0], 1.0);
        let r = freq_response(&f, 1.0, &[0.0, 1e-9]).unwrap();
        assert!((r.phase_deg[0] + 90.0).abs() < 1e-9 && (r.phase_deg[1] + 90.0).abs() < 1e-6);
        // z^-3 = 1/z³: φ = −3ωT exactly, |G| = 1
        let f = zf(&[1.0], &[1.0, 0.0, 0.0, 0.0], 0.5);
        let r = freq_response(&f, 0.5, &[1.0, 2.0, 2.0 * PI]).unwrap();
        for (w, (p, m)) in [1.0, 2.0, 2.0 * PI]
            .iter()
            .zip(r.phase_deg.iter().zip(&r.magnitude))
        {
            assert!((p.to_radians() + 3.0 * w * 0.5).abs() < 1e-14 && (m - 1.0).abs() < 1e-15);
        }
        let e = freq_response(&f, 0.5, &[7.0]).unwrap_err().to_string();
        assert!(e.contains("Nyquist frequency"), "{e}");
    }
}
