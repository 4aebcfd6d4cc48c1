//! The piecewise closed form of a delayed closed loop (the method of steps, see
//! [`super::steps`]): y(t) = Σ (−1)^(k+1) h_k(t − kT), each h_k the response of L^k in closed
//! form, with L^k exact from the factors ([`loop_powers`]); how it is evaluated, bounded and
//! written. The responses that choose between it and the march live in `steps.rs`.

use std::fmt;

use serde::Serialize;

use crate::analysis::closed_form::ClosedForm;
use crate::analysis::delay::checks::{check_delay, check_loop};
use crate::analysis::delay::march::interval_index;
use crate::analysis::factored::{Factored, MAX_FACTORED_ORDER};
use crate::analysis::input::Input;
use crate::analysis::laplace::Decomposition;
use crate::error::{LtiError, Result, check_finite};
use crate::poly::Root;

/// The most pieces (delays within the horizon, ⌊t_end/T⌋) a [`DelayedClosedForm`] is expanded
/// into (the response and step metrics go beyond on the collocation march). Beyond it the
/// alternating pieces have lost their accuracy for any loop with |L| ≳ 1 at low frequency, and the exact march of L^k (order k·n) costs O(k³) per piece: for the
/// PI/FOPDT loop of `tests/delay_steps.rs`, 50 pieces keep y to 3.5e-9, 100 pieces only to
/// 4e-3 (and take seconds).
pub const MAX_DELAY_PIECES: usize = 100;

/// The piecewise closed form of a delayed closed loop's response: y(t) = Σ_{k=1}^{K}
/// (−1)^(k+1) h_k(t − kT)·1(t − kT), valid for 0 ≤ t < (K + 1)T.
///
/// `pieces[k − 1]` is h_k (the response of L^k to the input, a [`ClosedForm`] in its own time
/// variable): it is active for t ≥ kT and evaluated at t − kT, with the sign (−1)^(k+1).
///
/// ```
/// use ltikit::analysis::{Factored, Input, delay::DelayedClosedForm};
/// use ltikit::Root;
/// use num_complex::Complex64 as C;
/// // L = 1/(s + 1), T = 1: y = 0 before T, y = 1 − e^(−(t−1)) on [1, 2].
/// let l = Factored::from_zpk(&[], &[Root::new(C::new(-1.0, 0.0), 1)], 1.0).unwrap();
/// let y = DelayedClosedForm::new(&l, 1.0, &Input::Step, 1.5).unwrap();
/// assert_eq!(y.pieces.len(), 1);
/// assert_eq!(y.eval(0.7), 0.0);
/// assert!((y.eval(1.5) - (1.0 - (-0.5f64).exp())).abs() < 1e-15);
/// assert!(y.eval(2.5).is_nan()); // beyond (K + 1)T: not covered
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DelayedClosedForm {
    /// The dead time T (s).
    pub delay: f64,
    /// h_1, h_2, …, h_K: the responses of L, L², …, L^K to the input.
    pub pieces: Vec<ClosedForm>,
}

impl DelayedClosedForm {
    /// The pieces of the loop `l` (continuous time, proper) with dead time `delay` > 0 for the
    /// `input`, enough for 0 ≤ t ≤ `horizon` ([`DelayedClosedForm::pieces_for`]).
    ///
    /// Errors: a discrete-time loop, a delay that is not a finite number > 0, a horizon that
    /// is not finite or negative, an improper L, an invalid input, more than
    /// [`MAX_DELAY_PIECES`] pieces or an order of L^K beyond
    /// [`crate::analysis::MAX_FACTORED_ORDER`] ([`LtiError::LimitExceeded`]), a gain^K that
    /// overflows.
    ///
    /// ```
    /// use ltikit::analysis::{Factored, Input, delay::DelayedClosedForm};
    /// use ltikit::Root;
    /// use num_complex::Complex64 as C;
    /// let l = Factored::from_zpk(&[], &[Root::new(C::new(-1.0, 0.0), 1)], 1.0).unwrap();
    /// assert!(DelayedClosedForm::new(&l, 0.0, &Input::Step, 1.0).is_err()); // no delay
    /// assert!(DelayedClosedForm::new(&l, 1e-6, &Input::Step, 10.0).is_err()); // 10⁷ pieces
    /// ```
    pub fn new(l: &Factored, delay: f64, input: &Input, horizon: f64) -> Result<DelayedClosedForm> {
        let powers = loop_powers(l, delay, input, horizon)?;
        DelayedClosedForm::of_powers(&powers, delay, input)
    }

    /// The pieces from the powers L, L², … (see [`loop_powers`]).
    pub(crate) fn of_powers(
        powers: &[Factored],
        delay: f64,
        input: &Input,
    ) -> Result<DelayedClosedForm> {
        let pieces = powers
            .iter()
            .map(|lk| {
                Ok(Decomposition::new(lk, input, &[])?
                    .closed_form()?
                    .closed_form)
            })
            .collect::<Result<Vec<ClosedForm>>>()?;
        Ok(DelayedClosedForm { delay, pieces })
    }

    /// The number of pieces that 0 ≤ t ≤ `horizon` needs: ⌊horizon/T⌋ (piece k starts at kT),
    /// checked against [`MAX_DELAY_PIECES`].
    ///
    /// ```
    /// use ltikit::analysis::delay::DelayedClosedForm;
    /// assert_eq!(DelayedClosedForm::pieces_for(10.0, 1.0).unwrap(), 10);
    /// assert_eq!(DelayedClosedForm::pieces_for(0.999, 1.0).unwrap(), 0);
    /// assert!(DelayedClosedForm::pieces_for(1e4, 1.0).is_err());
    /// ```
    pub fn pieces_for(horizon: f64, delay: f64) -> Result<usize> {
        check_delay(delay)?;
        check_finite(|| "the horizon".into(), horizon)?;
        let ratio = (horizon / delay).floor();
        if ratio.is_nan() || ratio > MAX_DELAY_PIECES as f64 {
            return Err(too_many_pieces(horizon, delay, ratio));
        }
        // ratio is an integer in [0, MAX_DELAY_PIECES] (or −1 for a negative horizon)
        Ok(interval_index(
            horizon.max(0.0),
            delay,
            ratio.max(0.0) as usize,
        ))
    }

    /// The number of pieces K.
    pub fn len(&self) -> usize {
        self.pieces.len()
    }

    /// True when there is no piece (the horizon is shorter than one delay: y = 0 there).
    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }

    /// The end of the validity: (K + 1)T (y is covered for 0 ≤ t < this).
    pub fn valid_until(&self) -> f64 {
        (self.pieces.len() + 1) as f64 * self.delay
    }

    /// The start kT of piece k (the kinks of y), as [`DelayedClosedForm::eval`] reads them.
    pub fn kink(&self, k: usize) -> f64 {
        k as f64 * self.delay
    }

    /// The index k of the interval \[kT, (k+1)T) holding t ≥ 0 (the number of active pieces),
    /// consistent with [`DelayedClosedForm::kink`] to the last bit.
    pub fn interval_of(&self, t: f64) -> usize {
        let guess = (t / self.delay).floor();
        if guess.is_nan() || guess < 0.0 {
            return 0;
        }
        // a guess beyond the pieces stays beyond (eval answers NaN there)
        let g = if guess > (self.pieces.len() + 2) as f64 {
            self.pieces.len() + 2
        } else {
            guess as usize
        };
        interval_index(t, self.delay, g)
    }

    /// y(t) for 0 ≤ t < (K + 1)T (δ terms excluded; at a kink kT the value just after it);
    /// 0 for t < 0; NaN for NaN and beyond the validity.
    pub fn eval(&self, t: f64) -> f64 {
        self.locate(t).map_or_else(|v| v, |k| self.eval_in(k, t))
    }

    /// The interval k of t for the evaluations, or what they answer without one: NaN for NaN
    /// and beyond the validity, 0 before t = 0.
    fn locate(&self, t: f64) -> std::result::Result<usize, f64> {
        if t.is_nan() {
            return Err(f64::NAN);
        }
        if t < 0.0 {
            return Err(0.0);
        }
        let k = self.interval_of(t);
        if k > self.pieces.len() {
            return Err(f64::NAN);
        }
        Ok(k)
    }

    /// y′(t) like [`DelayedClosedForm::eval`] (at a kink the derivative just after it).
    pub fn eval_derivative(&self, t: f64) -> f64 {
        self.locate(t)
            .map_or_else(|v| v, |k| self.derivative_in(k, t))
    }

    /// The rounding of the evaluation [`DelayedClosedForm::eval`] at t: 16·eps times the sum
    /// of the active pieces' envelopes (Σ|cⱼ|tʲe^(σt) of each), which the alternating pieces
    /// cancel down to y. It does not include the rounding of the residues themselves, which
    /// grows with k: [`DelayedResponse::closed_form_error`](super::DelayedResponse::closed_form_error)
    /// measures the whole. NaN where eval is NaN.
    pub fn error_bound(&self, t: f64) -> f64 {
        let k = match self.locate(t) {
            Ok(k) => k,
            Err(v) => return v,
        };
        let sum: f64 = (1..=k)
            .map(|j| self.pieces[j - 1].envelope(t - self.kink(j)))
            .sum();
        16.0 * f64::EPSILON * sum
    }

    /// The sum of the first k pieces at t (compensated): smooth on the closed interval
    /// \[kT, (k+1)T\], the right limit of y at kT and its left limit at (k+1)T.
    pub(crate) fn eval_in(&self, k: usize, t: f64) -> f64 {
        self.signed_sum(k, |h, s| h.eval(s), t)
    }

    /// The derivative of [`DelayedClosedForm::eval_in`].
    pub(crate) fn derivative_in(&self, k: usize, t: f64) -> f64 {
        self.signed_sum(k, |h, s| h.eval_derivative(s), t)
    }

    /// Σ_{j=1}^{k} (−1)^(j+1) f(h_j, t − jT), summed with Neumaier's compensation.
    fn signed_sum(&self, k: usize, f: impl Fn(&ClosedForm, f64) -> f64, t: f64) -> f64 {
        let (mut sum, mut comp) = (0.0f64, 0.0f64);
        for (j, h) in self.pieces.iter().enumerate().take(k) {
            let v = f(h, (t - self.kink(j + 1)).max(0.0));
            let v = if j % 2 == 0 { v } else { -v };
            let s = sum + v;
            comp += if sum.abs() >= v.abs() {
                (sum - s) + v
            } else {
                (v - s) + sum
            };
            sum = s;
        }
        sum + comp
    }

    /// The text of piece k (1-based): `h_2(t) = …`.
    pub fn piece_formula(&self, k: usize) -> Option<String> {
        self.pieces
            .get(k.wrapping_sub(1))
            .map(|h| h.formula(&format!("h_{k}(t)")))
    }
}

/// How many pieces the text lists before it counts the rest.
const SHOWN_PIECES: usize = 3;

impl fmt::Display for DelayedClosedForm {
    /// `y(t) = Σ_{k=1}^{K} (-1)^(k+1) h_k(t - kT)·1(t - kT), T = …`, then the first pieces
    /// one per line and how many more there are.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let t = crate::fmt::fmt_sig(self.delay, 6);
        let until = crate::fmt::fmt_sig(self.valid_until(), 6);
        let k = self.pieces.len();
        if k == 0 {
            return write!(f, "y(t) = 0 for t < T = {t} s (no delay has elapsed)");
        }
        write!(
            f,
            "y(t) = Σ_{{k=1}}^{{{k}}} (-1)^(k+1) h_k(t - k T)·1(t - k T), T = {t} s, \
             h_k the response of L^k (valid for t < {until} s)"
        )?;
        for (j, h) in self.pieces.iter().enumerate().take(SHOWN_PIECES) {
            write!(f, "\n  {}", h.formula(&format!("h_{}(t)", j + 1)))?;
        }
        if k > SHOWN_PIECES {
            let more = k - SHOWN_PIECES;
            let word = if more == 1 { "piece" } else { "pieces" };
            write!(
                f,
                "\n  … {more} more {word} (h_{} to h_{k})",
                SHOWN_PIECES + 1
            )?;
        }
        Ok(())
    }
}

/// L, L², …, L^K (K the pieces of the horizon), each exactly from the reduced factors of L,
/// after every check of [`DelayedClosedForm::new`].
pub(crate) fn loop_powers(
    l: &Factored,
    delay: f64,
    input: &Input,
    horizon: f64,
) -> Result<Vec<Factored>> {
    check_loop(l, delay, input, horizon)?;
    let count = DelayedClosedForm::pieces_for(horizon, delay)?;
    check_order(l, input, count)?;
    let poles = l.reduced_poles();
    let zeros = l.reduced_zeros();
    let mut powers = Vec::with_capacity(count);
    for k in 1..=count {
        // count ≤ MAX_DELAY_PIECES, so k fits an i32
        let gain = l.gain().powi(k as i32);
        if !gain.is_finite() || (gain == 0.0 && l.gain() != 0.0) {
            return Err(LtiError::Overflow {
                what: format!("the gain of L^{k} ({}^{k})", l.gain()),
                reason: format!(
                    " (the horizon needs {count} pieces; shorten it or scale the loop)"
                ),
            });
        }
        powers.push(Factored::from_zpk(
            &times(zeros, k),
            &times(poles, k),
            gain,
        )?);
    }
    Ok(powers)
}

fn too_many_pieces(horizon: f64, delay: f64, ratio: f64) -> LtiError {
    LtiError::LimitExceeded {
        field: format!(
            "the horizon {} s over the delay {} s (pieces of the method of steps; shorten the \
             horizon or use a Padé approximant of the delay)",
            crate::fmt::fmt_sig(horizon, 6),
            crate::fmt::fmt_sig(delay, 6)
        ),
        value: if ratio.is_finite() {
            ratio as u128
        } else {
            u128::MAX
        },
        max: MAX_DELAY_PIECES as u64,
        unit: "pieces".into(),
        limit: "MAX_DELAY_PIECES".into(),
    }
}

/// The order of L^K with the input's poles must stay within the factored core's limit.
fn check_order(l: &Factored, input: &Input, count: usize) -> Result<()> {
    let n: usize = l.reduced_poles().iter().map(|p| p.multiplicity).sum();
    let nu: usize = input.poles().iter().map(|p| p.1).sum();
    let order = (n as u128) * (count as u128) + nu as u128;
    if order > MAX_FACTORED_ORDER as u128 {
        return Err(LtiError::LimitExceeded {
            field: format!(
                "the order of L^{count} with the input ({n} poles × {count} pieces + {nu}; \
                 shorten the horizon or use a Padé approximant of the delay)"
            ),
            value: order,
            max: MAX_FACTORED_ORDER as u64,
            unit: String::new(),
            limit: "MAX_FACTORED_ORDER".into(),
        });
    }
    Ok(())
}

/// The roots with their multiplicities times k.
fn times(roots: &[Root], k: usize) -> Vec<Root> {
    roots
        .iter()
        .map(|r| Root::new(r.value, r.multiplicity * k))
        .collect()
}
