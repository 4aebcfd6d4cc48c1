//! The closed loop of a rational loop L(s) with dead time T, in negative unity feedback, by the
//! method of steps: exact, piece by piece.
//!
//! # Method
//! Y = L e^(−sT)/(1 + L e^(−sT))·R expands into Σ_{k≥1} (−1)^(k+1) L^k e^(−ksT) R, so on any
//! finite horizon only finitely many terms act:
//!
//! y(t) = Σ_{k=1}^{⌊t/T⌋} (−1)^(k+1) h_k(t − kT),
//!
//! where h_k is the response of L^k to the input r, in closed form. L^k is exact on the
//! factored form — the same reduced poles and zeros with their multiplicities times k, the
//! gain to the k-th power, no coefficients and no re-rooting ([`Factored::from_zpk`]) — and
//! h_k is its inverse Laplace transform with the input (partial fractions with repeated
//! poles: sums of t^j e^(pt) terms). On each interval \[kT, (k+1)T\] y is a finite sum of
//! such terms, so it is smooth there; at t = kT piece k starts, with a kink (a jump for a
//! bi-proper L and a step input).
//!
//! An **impulse** input gives h_k = the impulse response of L^k; for a bi-proper L (direct
//! term D ≠ 0) h_k carries D^k δ(t), i.e. y carries (−1)^(k+1) D^k δ(t − kT): those δ terms are
//! kept in the pieces (and shown in the text) and excluded from the values, like every δ term
//! of a [`ClosedForm`](crate::analysis::ClosedForm).
//!
//! # Accuracy
//! The pieces alternate in sign and grow: for L = K/(s + a) and a step, h_k(t) tends to
//! (K/a)^k; for an integrating loop h_k grows like (κt)^k/k!. Their sum is bounded (the loop
//! may well be stable) but each value carries the rounding of its largest piece. Two
//! evaluations are kept side by side, as in [`crate::analysis::response`]:
//! - the **closed form** ([`DelayedClosedForm::eval`]) carries the rounding of the residues
//!   of the k-fold poles, which grows with k;
//! - the **exact march** of each h_k (the matrix exponential of a realisation of L^k·U,
//!   [`Factored::time_response`]), summed with compensation, carries only the cancellation,
//!   16·eps·Σ_k|h_k(t − kT)|.
//!
//! [`DelayedResponse::y`] comes from the closed form when it agrees with the march to 1e-10
//! (relative) at the kinks and mid-intervals, from the march at every time otherwise;
//! [`DelayedResponse::closed_form_error`] says how far the two are apart.
//!
//! Measured (`tests/delay_steps.rs`, against the DDE solved exactly by sympy): first-order loop
//! K = 2, a = 1, T = 1/2 over 3 delays: closed form 2.2e-15 (march 2.6e-14); PI around
//! 1/(s + 1) with T = 1 over 10 delays: closed form 4.9e-15 (march 2.1e-14, bound 6e-14).
//! Over longer horizons the closed form degrades first: 40 pieces of the first-order loop
//! (|L(0)| = 2): closed form off by 7e-5, march bound 2.4e-10; 60 pieces of the PI loop:
//! closed form useless (off by 6e2), march within 4.8e-9 of y∞ (bound 6e-8); the march itself
//! fails by 100 pieces (bound 4e-3), hence [`MAX_DELAY_PIECES`] for [`DelayedClosedForm`].
//!
//! # Long horizons
//! [`Factored::delayed_feedback_response`] uses the pieces up to [`CLOSED_FORM_PIECES`] delays
//! while their estimated error (closed form against march, and the cancellation bound) stays
//! within 1e-10 of max(1, |y|); beyond, or when they lose accuracy, it takes the values from
//! the Chebyshev collocation march of the delay equation ([`crate::analysis::delay::march`]),
//! which has no alternating sum and reaches [`crate::analysis::delay::MAX_MARCH_INTERVALS`]
//! delays. The result says which ([`DelayedResponse::method`]) and how accurate
//! ([`DelayedResponse::estimated_error`]); with the march the closed form keeps the first
//! [`CROSS_CHECK_PIECES`] pieces as the text and cross-check.
//!
//! # Limits
//! The closed form: at most [`MAX_DELAY_PIECES`] pieces (⌊t_end/T⌋), and the order of L^k (k
//! times the order of L) at most [`crate::analysis::MAX_FACTORED_ORDER`]; beyond either, an
//! error with the numbers. The response: those of the march.

use serde::Serialize;

use crate::analysis::delay::checks::check_loop;
use crate::analysis::delay::march::{DelayMarch, interval_index};
use crate::analysis::delay::pieces::loop_powers;
pub use crate::analysis::delay::pieces::{DelayedClosedForm, MAX_DELAY_PIECES};
use crate::analysis::factored::{Factored, MAX_FACTORED_ORDER};
use crate::analysis::input::Input;
use crate::analysis::time::check_times;
use crate::error::Result;

/// The closed-loop response of a delayed loop at given times, with its piecewise closed form.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DelayedResponse {
    /// y(t) as pieces, up to the largest time.
    pub closed_form: DelayedClosedForm,
    /// The times, in the caller's order.
    pub t: Vec<f64>,
    /// y(t) (δ terms excluded; at a kink the value just after it): the closed form when it
    /// agrees with the exact march to 1e-10 (relative to max(1, |y|)) at the kinks and the
    /// middle of every interval; otherwise each h_k(t − kT) by the exact matrix-exponential
    /// march of L^k·U ([`Factored::time_response`]) at every time, the pieces summed with
    /// compensation.
    pub y: Vec<f64>,
    /// The control error e = r − y, which is also the signal entering L e^(−sT) (the loop's
    /// input; for an impulse r its δ at t = 0 is excluded).
    pub error: Vec<f64>,
    /// The rounding bound of each y from the cancellation of the alternating pieces:
    /// 16·eps·Σ_k |h_k(t − kT)| (with the pieces' envelopes in place of |h_k| when the values
    /// come from the closed form).
    pub cancellation_bound: Vec<f64>,
    /// max of `cancellation_bound` (0 for no times): the accuracy of `y`.
    pub max_cancellation_bound: f64,
    /// max |closed form − exact march| over the probe times (and over every time when the
    /// values are marched): the built-in cross-check of the closed form (its residues for
    /// k-fold poles carry rounding that the march does not). With the collocation march
    /// ([`DelayMethod::CollocationMarch`]): max |closed form − collocation| over the kinks and
    /// mid-intervals of the closed form's first pieces (at most [`CROSS_CHECK_PIECES`]).
    pub closed_form_error: f64,
    /// Where `y` comes from.
    pub method: DelayMethod,
    /// The estimated error of `y`: max(`closed_form_error`, `max_cancellation_bound`) for
    /// the pieces; for the collocation march its own estimate ([`DelayMarch::estimated_error`]:
    /// the unresolved Chebyshev tail plus rounding) and the cross-check on the first pieces.
    pub estimated_error: f64,
}

/// How the values of a delayed closed loop were computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DelayMethod {
    /// The piecewise closed form (or the exact march of its pieces), within
    /// [`CLOSED_FORM_PIECES`] delays while it stays accurate.
    Pieces,
    /// The Chebyshev collocation march of the delay equation
    /// ([`crate::analysis::delay::march`]), beyond.
    CollocationMarch,
}

/// The alternating pieces give the values up to this many delays within the horizon (when
/// their closed form and exact march agree to 1e-10); the collocation march beyond, up to
/// [`crate::analysis::delay::MAX_MARCH_INTERVALS`].
pub const CLOSED_FORM_PIECES: usize = 30;

/// With the collocation march, the closed form keeps this many first pieces, as the text and
/// the cross-check.
pub const CROSS_CHECK_PIECES: usize = 10;

impl Factored {
    /// The closed-loop response y of this loop L (continuous time, proper) with dead time
    /// `delay` > 0 in negative unity feedback, Y = L e^(−sT)/(1 + L e^(−sT))·R, to the `input`
    /// (step, impulse, ramp, exponential, sine, cosine), at the times `t` (any order, finite,
    /// ≥ 0), by the method of steps (see [`crate::analysis::delay::steps`]). Up to
    /// [`CLOSED_FORM_PIECES`] delays the closed form covers 0 ≤ t ≤ max(t) and the values
    /// march each piece exactly, reporting how far the closed form agrees; beyond (or when
    /// the pieces lose accuracy) the values come from the collocation march
    /// ([`crate::analysis::delay::march`]), the closed form keeping its first pieces.
    ///
    /// Zero delay is refused: the rational closed loop is [`Factored::feedback`].
    ///
    /// Errors: a discrete-time or improper loop, an invalid delay or input, negative or
    /// non-finite times, more than [`crate::analysis::delay::MAX_MARCH_INTERVALS`] delays or
    /// [`crate::analysis::delay::MAX_MARCH_NODES`] collocation nodes, values that overflow.
    ///
    /// ```
    /// use ltikit::analysis::{Factored, Input};
    /// use ltikit::Root;
    /// use num_complex::Complex64 as C;
    /// // L = 1/(s + 1), T = 1: on [1, 2], y = 1 − e^(−(t − 1)); on [2, 3] the second piece
    /// // h_2(τ) = 1 − (1 + τ) e^(−τ) (the step response of 1/(s + 1)²) is subtracted.
    /// let l = Factored::from_zpk(&[], &[Root::new(C::new(-1.0, 0.0), 1)], 1.0).unwrap();
    /// let r = l.delayed_feedback_response(1.0, &Input::Step, &[0.5, 1.5, 2.5]).unwrap();
    /// assert_eq!(r.y[0], 0.0);
    /// let h1 = |x: f64| 1.0 - (-x).exp();
    /// let h2 = |x: f64| 1.0 - (1.0 + x) * (-x).exp();
    /// assert!((r.y[2] - (h1(1.5) - h2(0.5))).abs() < 1e-15);
    /// assert!((r.error[1] - (1.0 - h1(0.5))).abs() < 1e-15);
    /// assert!(r.closed_form_error < 1e-14 && r.max_cancellation_bound < 1e-13);
    /// ```
    pub fn delayed_feedback_response(
        &self,
        delay: f64,
        input: &Input,
        t: &[f64],
    ) -> Result<DelayedResponse> {
        check_times(t)?;
        let horizon = t.iter().copied().fold(0.0, f64::max);
        check_loop(self, delay, input, horizon)?;
        if (horizon / delay).floor() <= CLOSED_FORM_PIECES as f64 {
            let r = self.pieces_response(delay, input, t, horizon)?;
            let scale = r.y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
            if r.estimated_error <= CLOSED_FORM_AGREEMENT * scale {
                return Ok(r);
            }
        }
        self.march_response(delay, input, t, horizon)
    }

    /// The values by the collocation march, with the first pieces' closed form as text and
    /// cross-check.
    fn march_response(
        &self,
        delay: f64,
        input: &Input,
        t: &[f64],
        horizon: f64,
    ) -> Result<DelayedResponse> {
        let m = DelayMarch::new(self, delay, input, horizon)?;
        // the closed form's first pieces (fewer for a high order; none when even that fails)
        let n: usize = self.reduced_poles().iter().map(|p| p.multiplicity).sum();
        let nu: usize = input.poles().iter().map(|p| p.1).sum();
        let fit = MAX_FACTORED_ORDER.saturating_sub(nu) / n.max(1);
        let k = CROSS_CHECK_PIECES
            .min(fit)
            .min(interval_index(horizon, delay, 0).min(CROSS_CHECK_PIECES + 1));
        let cf_horizon = (k as f64 * delay).min(horizon);
        let closed_form = loop_powers(self, delay, input, cf_horizon)
            .and_then(|p| DelayedClosedForm::of_powers(&p, delay, input))
            .or_else(|_| DelayedClosedForm::of_powers(&[], delay, input))?;
        let probes = probe_times(
            &closed_form,
            cf_horizon.min(closed_form.kink(closed_form.len())),
        );
        let closed_form_error = probes
            .iter()
            .map(|&x| (closed_form.eval(x) - m.eval(x)).abs())
            .filter(|e| e.is_finite())
            .fold(0.0, f64::max);
        let y: Vec<f64> = t.iter().map(|&x| m.eval(x)).collect();
        let bound: Vec<f64> = t.iter().map(|&x| m.error_at(x)).collect();
        let error = t.iter().zip(&y).map(|(&x, v)| input.eval(x) - v).collect();
        let max_cancellation_bound = bound.iter().copied().fold(0.0, f64::max);
        Ok(DelayedResponse {
            closed_form,
            t: t.to_vec(),
            y,
            error,
            cancellation_bound: bound,
            max_cancellation_bound,
            closed_form_error,
            method: DelayMethod::CollocationMarch,
            estimated_error: m.estimated_error.max(closed_form_error),
        })
    }

    /// The values by the alternating pieces (closed form, or their exact march).
    fn pieces_response(
        &self,
        delay: f64,
        input: &Input,
        t: &[f64],
        horizon: f64,
    ) -> Result<DelayedResponse> {
        let powers = loop_powers(self, delay, input, horizon)?;
        let closed_form = DelayedClosedForm::of_powers(&powers, delay, input)?;
        // The closed form where it agrees with the exact march at the kinks and the middle of
        // every interval; the march at every time otherwise.
        let probes = probe_times(&closed_form, horizon);
        let at_probes = march_pieces(&powers, &closed_form, input, &probes)?;
        let probe_error = probes
            .iter()
            .zip(&at_probes.y)
            .map(|(&x, v)| (closed_form.eval(x) - v).abs())
            .fold(0.0, f64::max);
        let scale = at_probes.y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let (marched, closed_form_error) = if probe_error <= CLOSED_FORM_AGREEMENT * scale {
            let y = t.iter().map(|&x| closed_form.eval(x)).collect();
            let bound = t.iter().map(|&x| closed_form.error_bound(x)).collect();
            (Marched { y, bound }, probe_error)
        } else {
            let m = march_pieces(&powers, &closed_form, input, t)?;
            let e = t
                .iter()
                .zip(&m.y)
                .map(|(&x, v)| (closed_form.eval(x) - v).abs())
                .fold(probe_error, f64::max);
            (m, e)
        };
        let error = t
            .iter()
            .zip(&marched.y)
            .map(|(&x, v)| input.eval(x) - v)
            .collect();
        let max_cancellation_bound = marched.bound.iter().copied().fold(0.0, f64::max);
        Ok(DelayedResponse {
            closed_form,
            t: t.to_vec(),
            y: marched.y,
            error,
            cancellation_bound: marched.bound,
            max_cancellation_bound,
            closed_form_error,
            method: DelayMethod::Pieces,
            estimated_error: closed_form_error.max(max_cancellation_bound),
        })
    }
}

/// The closed form gives the values when it agrees with the march to this, relative to
/// max(1, |y|), at the probe times ([`probe_times`]).
const CLOSED_FORM_AGREEMENT: f64 = 1e-10;

/// The kinks kT, the middle of each interval and the horizon: where the closed form is checked
/// against the march.
pub(crate) fn probe_times(y: &DelayedClosedForm, horizon: f64) -> Vec<f64> {
    let last = y.interval_of(horizon).min(y.len());
    let mut t = Vec::with_capacity(2 * last + 1);
    for k in 1..=last {
        let a = y.kink(k);
        let b = if k == last { horizon } else { y.kink(k + 1) };
        t.push(a);
        t.push(0.5 * (a + b));
    }
    t.push(horizon);
    t
}

/// Values of y and their cancellation bounds.
pub(crate) struct Marched {
    pub y: Vec<f64>,
    pub bound: Vec<f64>,
}

/// y at the times `t` (within the pieces' validity): each h_k(t − kT) marched exactly
/// ([`Factored::time_response`] of L^k with the input) at the times where piece k is active,
/// summed with Neumaier's compensation; the bound is 16·eps·Σ|h_k|.
pub(crate) fn march_pieces(
    powers: &[Factored],
    form: &DelayedClosedForm,
    input: &Input,
    t: &[f64],
) -> Result<Marched> {
    let n = t.len();
    let (mut sum, mut comp, mut mag) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let active: Vec<usize> = t.iter().map(|&x| form.interval_of(x)).collect();
    for (j, lk) in powers.iter().enumerate() {
        let k = j + 1;
        let idx: Vec<usize> = (0..n).filter(|&i| active[i] >= k).collect();
        if idx.is_empty() {
            continue;
        }
        let start = form.kink(k);
        let taus: Vec<f64> = idx.iter().map(|&i| (t[i] - start).max(0.0)).collect();
        let h = lk.time_response(input, &[], &taus)?.y;
        for (&i, v) in idx.iter().zip(h) {
            let v = if k % 2 == 1 { v } else { -v };
            let s = sum[i] + v;
            comp[i] += if f64::abs(sum[i]) >= v.abs() {
                (sum[i] - s) + v
            } else {
                (v - s) + sum[i]
            };
            sum[i] = s;
            mag[i] += v.abs();
        }
    }
    Ok(Marched {
        y: sum.iter().zip(&comp).map(|(a, b)| a + b).collect(),
        bound: mag.iter().map(|m| 16.0 * f64::EPSILON * m).collect(),
    })
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact zeros before the delay are meant
mod tests {
    use super::*;
    use crate::error::LtiError;
    use crate::poly::Root;
    use num_complex::Complex64;

    fn first_order(k: f64, a: f64) -> Factored {
        Factored::from_zpk(&[], &[Root::new(Complex64::new(-a, 0.0), 1)], k).unwrap()
    }

    #[test]
    fn interval_index_matches_kinks() {
        let y = DelayedClosedForm::new(&first_order(1.0, 1.0), 0.1, &Input::Step, 5.0).unwrap();
        assert_eq!(y.len(), 50);
        for k in 0..=50 {
            let t = y.kink(k);
            assert_eq!(y.interval_of(t), k, "k = {k}");
            let before = f64::from_bits(t.to_bits().saturating_sub(1));
            if k > 0 {
                assert_eq!(y.interval_of(before), k - 1);
            }
        }
        assert!((y.valid_until() - 5.1).abs() < 1e-12);
    }

    #[test]
    fn bad_inputs_are_errors() {
        let l = first_order(1.0, 1.0);
        for d in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(
                l.delayed_feedback_response(d, &Input::Step, &[1.0])
                    .is_err()
            );
        }
        assert!(
            l.delayed_feedback_response(1.0, &Input::Step, &[f64::NAN])
                .is_err()
        );
        assert!(
            l.delayed_feedback_response(1.0, &Input::Step, &[-1.0])
                .is_err()
        );
        // 10⁴ delays: the collocation march
        let r = l
            .delayed_feedback_response(1e-3, &Input::Step, &[10.0])
            .unwrap();
        assert_eq!(r.method, DelayMethod::CollocationMarch);
        // y∞ = 1/2, approached as e^(s₁t), s₁ ≈ −2 (s + 1 + e^(−0.001 s) = 0): 0.5·e^(−20) ≈ 1e-9
        assert!((0.5 - r.y[0] - 1.0e-9).abs() < 1e-10, "{}", r.y[0]);
        let e = l
            .delayed_feedback_response(1e-6, &Input::Step, &[10.0])
            .unwrap_err()
            .to_string();
        assert!(e.contains("MAX_MARCH_INTERVALS"), "{e}");
        let improper = Factored::from_zpk(
            &[Root::new(Complex64::new(-1.0, 0.0), 2)],
            &[Root::new(Complex64::new(-2.0, 0.0), 1)],
            1.0,
        )
        .unwrap();
        assert!(matches!(
            improper.delayed_feedback_response(1.0, &Input::Step, &[1.0]),
            Err(LtiError::Improper { .. })
        ));
        // the order limit of the closed form: 50 poles × 100 pieces
        let fifty =
            Factored::from_zpk(&[], &[Root::new(Complex64::new(-1.0, 0.0), 50)], 1.0).unwrap();
        let e = DelayedClosedForm::new(&fifty, 0.01, &Input::Step, 1.0)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(e.contains("MAX_FACTORED_ORDER"), "{e}");
    }

    #[test]
    fn text_lists_first_pieces() {
        let y = DelayedClosedForm::new(&first_order(1.0, 1.0), 1.0, &Input::Step, 5.5).unwrap();
        let s = y.to_string();
        assert!(
            s.starts_with("y(t) = Σ_{k=1}^{5} (-1)^(k+1) h_k(t - k T)"),
            "{s}"
        );
        assert!(s.contains("h_1(t) = 1 - e^(-t)"), "{s}");
        assert!(s.contains("… 2 more pieces (h_4 to h_5)"), "{s}");
        let empty = DelayedClosedForm::new(&first_order(1.0, 1.0), 1.0, &Input::Step, 0.5).unwrap();
        assert_eq!(
            empty.to_string(),
            "y(t) = 0 for t < T = 1 s (no delay has elapsed)"
        );
    }

    #[test]
    fn biproper_impulse_keeps_delta_terms() {
        // L = (s + 2)/(s + 1) = 1 + 1/(s + 1): h_k has δ(t) of weight 1.
        let l = Factored::from_zpk(
            &[Root::new(Complex64::new(-2.0, 0.0), 1)],
            &[Root::new(Complex64::new(-1.0, 0.0), 1)],
            1.0,
        )
        .unwrap();
        let y = DelayedClosedForm::new(&l, 1.0, &Input::Impulse, 2.5).unwrap();
        assert!(
            y.pieces[0].expression().starts_with("δ(t)"),
            "{}",
            y.pieces[0]
        );
        // on [1, 2): y = h_1(t − 1) = e^(−(t−1)) (δ excluded)
        assert!((y.eval(1.5) - (-0.5f64).exp()).abs() < 1e-15);
    }
}
