//! Double-double Horner evaluation on the imaginary axis: the reference the factored form is
//! checked against, and its fallback when the roots do not reproduce the coefficients.

use std::f64::consts::{FRAC_PI_2, LN_2, PI, TAU};

use super::factors::{exponent, mul_pow2};
use crate::lti::TransferFunction;
use crate::poly::{HalfPlane, Root};

/// Numerator and denominator coefficients for double-double Horner evaluation on the axis:
/// normalised by a power of two to max |c| ∈ [1, 2), zero roots stripped.
#[derive(Debug, Clone)]
pub(super) struct HornerPair {
    num: Vec<f64>,
    den: Vec<f64>,
    /// zeros at s = 0 minus poles at s = 0
    int_order: i32,
    /// ln(max|num| / max|den|)
    ln_scale: f64,
}

impl HornerPair {
    fn new(g: &TransferFunction) -> HornerPair {
        let prep = |p: &crate::poly::Poly| -> (Vec<f64>, usize, f64) {
            let z = p.zero_root_multiplicity();
            let c = &p.coeffs()[..p.coeffs().len() - z];
            // normalise by a power of two: exact, so Horner sees the coefficients as given
            let e = exponent(c.iter().fold(0.0f64, |a, &x| a.max(x.abs())));
            (
                c.iter().map(|&x| mul_pow2(x, -e)).collect(),
                z,
                e as f64 * LN_2,
            )
        };
        let (num, zn, ln_n) = prep(g.num());
        let (den, zd, ln_d) = prep(g.den());
        HornerPair {
            num,
            den,
            int_order: zn as i32 - zd as i32,
            ln_scale: ln_n - ln_d,
        }
    }

    fn eval(&self, w: f64) -> (f64, f64) {
        let (ln_n, arg_n) = dd_axis(&self.num, w);
        let (ln_d, arg_d) = dd_axis(&self.den, w);
        let k = self.int_order as f64;
        (
            self.ln_scale + ln_n - ln_d + k * w.ln(),
            arg_n - arg_d + k * FRAC_PI_2,
        )
    }
}

/// The reference evaluation of G(jω): double-double Horner on the coefficients as given,
/// and on the reduced coefficients near a cancelled root on the axis (where the given N and D
/// both vanish).
#[derive(Debug, Clone)]
pub(super) struct AxisHorner {
    given: HornerPair,
    reduced: Option<HornerPair>,
    /// β ≥ 0 of the cancelled roots on the imaginary axis.
    cancelled_axis: Vec<f64>,
}

/// Relative distance to a cancelled axis root within which the reduced coefficients are used.
const NEAR_CANCELLED: f64 = 1e-6;

impl AxisHorner {
    pub(super) fn new(
        given: &TransferFunction,
        reduced: &TransferFunction,
        cancelled: &[Root],
    ) -> AxisHorner {
        let cancelled_axis: Vec<f64> = cancelled
            .iter()
            .filter(|r| r.half_plane() == HalfPlane::Axis && r.value.im >= 0.0)
            .map(|r| r.value.im)
            .collect();
        AxisHorner {
            given: HornerPair::new(given),
            reduced: (!cancelled_axis.is_empty()).then(|| HornerPair::new(reduced)),
            cancelled_axis,
        }
    }

    /// (ln|G(jω)|, principal-or-not argument of G(jω)) for ω > 0.
    pub(super) fn eval(&self, w: f64) -> (f64, f64) {
        match &self.reduced {
            Some(r)
                if self
                    .cancelled_axis
                    .iter()
                    .any(|&b| (w - b).abs() <= NEAR_CANCELLED * b.max(w)) =>
            {
                r.eval(w)
            }
            _ => self.given.eval(w),
        }
    }
}

/// ln|P(jω)| and an argument of P(jω) (ω > 0) by Horner's rule in double-double; for ω > 1
/// on the reversed polynomial in 1/(jω), so nothing overflows. `c` descending, c\[n\] ≠ 0.
pub(super) fn dd_axis(c: &[f64], w: f64) -> (f64, f64) {
    use crate::numeric::dd::Dd;
    let n = c.len() - 1;
    let (mut re, mut im) = (Dd::ZERO, Dd::ZERO);
    if w <= 1.0 {
        let wd = Dd::from(w);
        for &a in c {
            // (re + j·im)(jω) + a = (a − ω·im) + j·ω·re
            let nre = Dd::from(a) - wd * im;
            im = wd * re;
            re = nre;
        }
        let (r, i) = (re.to_f64(), im.to_f64());
        (r.hypot(i).ln(), i.atan2(r))
    } else {
        // P(jω) = (jω)^n·R(1/(jω)), R the reversed polynomial, 1/(jω) = −j·v, v = 1/ω
        let hi = 1.0 / w;
        let v = Dd {
            hi,
            lo: (-hi).mul_add(w, 1.0) / w,
        };
        for &a in c.iter().rev() {
            // (re + j·im)(−j·v) + a = (a + v·im) − j·v·re
            let nre = Dd::from(a) + v * im;
            im = -(v * re);
            re = nre;
        }
        let (r, i) = (re.to_f64(), im.to_f64());
        (
            n as f64 * w.ln() + r.hypot(i).ln(),
            i.atan2(r) + n as f64 * FRAC_PI_2,
        )
    }
}

/// Relative tolerance of the factored form against double-double Horner at the probe
/// frequencies before it is trusted on its own.
pub(super) const FACTORED_CHECK_TOL: f64 = 1e-11;

/// Wraps radians into (−π, π].
pub(super) fn wrap_pi(x: f64) -> f64 {
    let y = x - TAU * (x / TAU).round();
    if y <= -PI { y + TAU } else { y }
}
