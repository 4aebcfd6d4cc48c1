//! Discrete time: what the z-domain changes in each analysis, asked by the analyses of
//! [`Factored`](crate::analysis::Factored) through its [`Domain`](crate::lti::Domain).
//!
//! | analysis | continuous (s) | discrete (z, period T) |
//! |---|---|---|
//! | stable region | open left half plane | open unit disc |
//! | marginal | simple poles on the imaginary axis | simple poles on the unit circle |
//! | dc gain | G(0) | G(1) (∞ with a pole at z = 1: a discrete integrator) |
//! | modes | ωₙ = \|p\|, ζ = −Re p/\|p\| | the same of the equivalent s = ln(z)/T (MATLAB `damp`) |
//! | frequency | s = jω, ω ≥ 0 | z = e^(jωT), 0 ≤ ω ≤ π/T (the Nyquist frequency) |
//! | responses | closed form in t | the sequence y\[k\] at t = kT, exact by the one marcher |
//! | closed form | inverse Laplace transform of Y(s) | inverse z-transform of Y(z)/z: Σ c·kʲ·pᵏ |
//! | Nyquist contour | s = jω, −∞ < ω < ∞, closed at ∞; P = poles with Re p > 0 | z = e^(jωT), −π/T ≤ ω ≤ π/T; P = poles with \|p\| > 1 |
//! | initial conditions | y(0), y′(0), … of the ODE | y\[−1\], y\[−2\], … of the difference equation |
//!
//! The files: `freq.rs` (G(e^(jωT)) with its continuous phase), `margins.rs` (crossings on
//! (0, π/T]), `time.rs` (step, impulse and input responses as sequences, step metrics in
//! samples), `inverse_z.rs` (partial fractions of Y(z)/z and the closed-form y\[k\]),
//! `nyquist.rs` (the Nyquist contour along the unit circle, arcs outside it around the poles
//! on it, P counted outside the circle).

mod freq;
mod inverse_z;
mod margins;
mod nyquist;
mod time;

pub(crate) use freq::freq_response;
pub(crate) use inverse_z::closed_parts;
pub(crate) use margins::{margins, peak};
pub(crate) use nyquist::nyquist_contour;
pub use time::MAX_STEP_INFO_SAMPLES;
pub(crate) use time::{step_info, time_response};

use num_complex::Complex64;

use crate::analysis::{HalfPlane, Mode};
use crate::numeric::tol::AXIS_REL_TOL;
use crate::poly::Root;

/// Where a z-plane root lies, in the words of the s-plane: `Left` strictly inside the unit
/// circle, `Axis` on it (to the relative tolerance [`AXIS_REL_TOL`]), `Right` outside.
///
/// ```
/// use ltikit::analysis::{HalfPlane, discrete::circle_side};
/// use num_complex::Complex64 as C;
/// assert_eq!(circle_side(C::new(0.5, 0.5)), HalfPlane::Left);
/// assert_eq!(circle_side(C::new(-1.0, 0.0)), HalfPlane::Axis);
/// assert_eq!(circle_side(C::new(0.6, 0.8 + 1e-15)), HalfPlane::Axis); // |z| = 1 to rounding
/// assert_eq!(circle_side(C::new(1.001, 0.0)), HalfPlane::Right);
/// ```
pub fn circle_side(z: Complex64) -> HalfPlane {
    let r = z.norm();
    if (r - 1.0).abs() <= AXIS_REL_TOL * r.max(1.0) {
        HalfPlane::Axis
    } else if r < 1.0 {
        HalfPlane::Left
    } else {
        HalfPlane::Right
    }
}

/// The equivalent continuous-time pole s = ln(z)/T of a z-plane pole (principal logarithm;
/// z = 0, a deadbeat mode, has none: `None`).
pub fn equivalent_s(z: Complex64, dt: f64) -> Option<Complex64> {
    (z.norm() > 0.0).then(|| {
        let s = Complex64::new(z.norm().ln(), z.im.atan2(z.re)) / dt;
        Complex64::new(s.re, if z.im == 0.0 && z.re > 0.0 { 0.0 } else { s.im })
    })
}

/// The modes of z-plane poles with the natural frequency, damping and time constant of the
/// equivalent s = ln(z)/T (MATLAB `damp`): a pole on the unit circle has ζ = 0; a pole at
/// z = 0 (a deadbeat mode, gone after its multiplicity of samples) has ωₙ = ∞, ζ = 1 and
/// τ = 0. `side` decides the unit circle (exactly where the factored form knows).
pub(crate) fn modes(poles: &[Root], dt: f64, side: impl Fn(Complex64) -> HalfPlane) -> Vec<Mode> {
    poles
        .iter()
        .map(|r| {
            let Some(s) = equivalent_s(r.value, dt) else {
                return Mode {
                    pole: r.value,
                    multiplicity: r.multiplicity,
                    wn: f64::INFINITY,
                    zeta: Some(1.0),
                    time_constant: Some(0.0),
                };
            };
            let wn = s.norm();
            let on = side(r.value) == HalfPlane::Axis;
            let zeta = if wn == 0.0 {
                None
            } else if on {
                Some(0.0)
            } else {
                Some(-s.re / wn)
            };
            Mode {
                pole: r.value,
                multiplicity: r.multiplicity,
                wn,
                zeta,
                time_constant: (s.re < 0.0 && !on).then(|| -1.0 / s.re),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modes_are_those_of_the_equivalent_s() {
        // z = e^(sT) with s = −1 ± 2j, T = 0.1
        let dt = 0.1;
        let s = Complex64::new(-1.0, 2.0);
        let z = (s * dt).exp();
        let m = modes(
            &[Root::new(z, 1), Root::new(Complex64::new(0.0, 0.0), 2)],
            dt,
            circle_side,
        );
        assert!((m[0].wn - 5f64.sqrt()).abs() < 1e-14, "{}", m[0].wn);
        assert!((m[0].zeta.unwrap() - 1.0 / 5f64.sqrt()).abs() < 1e-14);
        assert!((m[0].time_constant.unwrap() - 1.0).abs() < 1e-13);
        assert_eq!(m[1].time_constant, Some(0.0));
        // z = −0.5: s = (ln 0.5 + jπ)/T
        let m = modes(&[Root::new(Complex64::new(-0.5, 0.0), 1)], 1.0, circle_side);
        let s = Complex64::new(0.5f64.ln(), std::f64::consts::PI);
        assert!((m[0].wn - s.norm()).abs() < 1e-15);
    }
}
