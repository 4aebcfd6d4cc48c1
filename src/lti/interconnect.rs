//! Interconnections of models in one shape on every model type: the methods
//! `series(&self, &next)`, `parallel(&self, &other)` and `feedback(&self, &h, sign)` of
//! [`TransferFunction`] (on the coefficients, nothing cancelled), [`StateSpace`] (block
//! matrices, no detour through coefficients; any numbers of inputs and outputs that fit) and
//! the factored core's `Factored` (the factors kept; its `feedback` returns a `Feedback` with
//! the closed loop, the characteristic polynomial, the closed-loop poles and the hidden modes).
//!
//! Conventions (as python-control and MATLAB): `g1.series(&g2)` is g2·g1 (the signal goes
//! through g1 first); `g.feedback(&h, sign)` closes u = r + sign·h·y around g, so
//! `sign = -1.0` is negative feedback, T = G/(1 + G·H).
//!
//! Every interconnection joins the two models' domains ([`Domain::join`](crate::lti::Domain::join)): the result is in
//! their common domain, and connecting a continuous-time and a discrete-time model, or two
//! different sampling periods, is an error naming the operation and both domains.
//!
//! ```
//! use ltikit::TransferFunction;
//! use ltikit::lti::Domain;
//! let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap();   // 1/(s+1)
//! let h = TransferFunction::from_descending(&[2.0], &[1.0, 3.0]).unwrap();   // 2/(s+3)
//! assert_eq!(g.series(&h).unwrap().den().coeffs(), &[1.0, 4.0, 3.0]);
//! assert_eq!(g.parallel(&h).unwrap().num().coeffs(), &[3.0, 5.0]);
//! let t = g.feedback(&h, -1.0).unwrap();                                   // (s+3)/((s+1)(s+3)+2)
//! assert_eq!(t.den().coeffs(), &[1.0, 4.0, 5.0]);
//! // a continuous and a discrete model do not connect
//! let gz = g.clone().with_domain(Domain::discrete(0.1).unwrap());
//! let e = g.series(&gz).unwrap_err().to_string();
//! assert!(e.contains("series") && e.contains("continuous-time") && e.contains("dt = 0.1"));
//! ```

use nalgebra::DMatrix;

use crate::error::{LtiError, Result};
use crate::lti::{StateSpace, TransferFunction};

impl TransferFunction {
    /// Series connection: `self` first, then `next` — next·self (no cancellation), in the
    /// two models' common domain.
    ///
    /// Errors: models of different domains ([`Domain::join`](crate::lti::Domain::join)).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap();
    /// assert_eq!(g.series(&g).unwrap().den().coeffs(), &[1.0, 2.0, 1.0]);
    /// ```
    pub fn series(&self, next: &TransferFunction) -> Result<TransferFunction> {
        let domain = self.domain().join(next.domain(), "series")?;
        Ok((next * self).with_domain(domain))
    }

    /// Parallel connection self + other = (N₁D₂ + N₂D₁)/(D₁D₂) (no cancellation), in the two
    /// models' common domain.
    ///
    /// Errors: models of different domains; those of [`TransferFunction::new`] (a sum that
    /// vanishes identically is the zero transfer function, which is allowed).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap();
    /// let p = g.parallel(&g).unwrap();
    /// assert_eq!((p.num().coeffs(), p.den().coeffs()), (&[2.0, 2.0][..], &[1.0, 2.0, 1.0][..]));
    /// ```
    pub fn parallel(&self, other: &TransferFunction) -> Result<TransferFunction> {
        let domain = self.domain().join(other.domain(), "parallel")?;
        let delay = crate::lti::delay::common_delay("parallel", self.delay(), other.delay())?;
        let num = &(self.num() * other.den()) + &(other.num() * self.den());
        TransferFunction::new(num, self.den() * other.den())?
            .with_domain(domain)
            .with_delay(delay)
    }

    /// Feedback u = r + sign·H·y around G = `self`: T = N_G·D_H/(D_G·D_H − sign·N_G·N_H) (no
    /// cancellation; `sign = -1.0` is negative feedback), in the two models' common domain. A
    /// constant gain k in the loop is `h = TransferFunction::constant(k)`.
    ///
    /// Errors: a sign other than ±1, models of different domains, a characteristic polynomial
    /// that vanishes identically (the loop is not well posed).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // 1/s with a gain 2 in negative feedback: 1/(s + 2)
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 0.0]).unwrap();
    /// let t = g.feedback(&TransferFunction::constant(2.0), -1.0).unwrap();
    /// assert_eq!(t.den().coeffs(), &[1.0, 2.0]);
    /// ```
    pub fn feedback(&self, h: &TransferFunction, sign: f64) -> Result<TransferFunction> {
        check_sign(sign)?;
        let domain = self.domain().join(h.domain(), "feedback")?;
        crate::lti::delay::require_rational("feedback", self.delay() + h.delay())?;
        let num = self.num() * h.den();
        let den = &(self.den() * h.den()) - &(self.num() * h.num()).scale(sign);
        if den.is_zero() {
            return Err(LtiError::invalid(
                "the feedback loop is not well posed: 1 − sign·G·H vanishes identically",
            ));
        }
        Ok(TransferFunction::new(num, den)?.with_domain(domain))
    }
}

/// Errors unless `sign` is −1 or +1.
pub(crate) fn check_sign(sign: f64) -> Result<()> {
    if [1.0, -1.0].contains(&sign) {
        Ok(())
    } else {
        Err(LtiError::InvalidParameter {
            name: "sign".into(),
            value: sign,
            reason: "the feedback sign must be -1 (negative) or +1 (positive)".into(),
        })
    }
}

impl StateSpace {
    /// Series connection: `self` first, then `next` (x = [x₁; x₂]):
    /// A = [A₁ 0; B₂C₁ A₂], B = [B₁; B₂D₁], C = [D₂C₁ C₂], D = D₂D₁, in the two models'
    /// common domain.
    ///
    /// Errors: models of different domains ([`Domain::join`](crate::lti::Domain::join)); the outputs of `self` do not
    /// match the inputs of `next`.
    ///
    /// ```
    /// use ltikit::{StateSpace, TransferFunction};
    /// let g = StateSpace::from_tf(&TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap()).unwrap();
    /// let s = g.series(&g).unwrap();
    /// assert_eq!(s.to_tf().unwrap().den().coeffs(), &[1.0, 2.0, 1.0]);
    /// ```
    pub fn series(&self, next: &StateSpace) -> Result<StateSpace> {
        self.require_no_delays("series")?;
        next.require_no_delays("series")?;
        let domain = self.domain.join(next.domain, "series")?;
        if self.n_outputs() != next.n_inputs() {
            return Err(LtiError::invalid(format!(
                "series connection: the first model has {} outputs but the second {} inputs",
                self.n_outputs(),
                next.n_inputs()
            )));
        }
        let (n1, n2) = (self.order(), next.order());
        let mut a = DMatrix::zeros(n1 + n2, n1 + n2);
        a.view_mut((0, 0), (n1, n1)).copy_from(&self.a);
        a.view_mut((n1, 0), (n2, n1))
            .copy_from(&(&next.b * &self.c));
        a.view_mut((n1, n1), (n2, n2)).copy_from(&next.a);
        let b = stack_rows(&self.b, &(&next.b * &self.d));
        let c = stack_cols(&(&next.d * &self.c), &next.c);
        Ok(StateSpace::new(a, b, c, &next.d * &self.d)?.with_domain(domain))
    }

    /// Parallel connection (same inputs, outputs added): A = diag(A₁, A₂), B = [B₁; B₂],
    /// C = [C₁ C₂], D = D₁ + D₂, in the two models' common domain.
    ///
    /// Errors: models of different domains; different numbers of inputs or outputs.
    ///
    /// ```
    /// use ltikit::{StateSpace, TransferFunction};
    /// let g = StateSpace::from_tf(&TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap()).unwrap();
    /// let p = g.parallel(&g).unwrap();
    /// assert!((p.to_tf().unwrap().eval(0.0.into()).re - 2.0).abs() < 1e-14);
    /// ```
    pub fn parallel(&self, other: &StateSpace) -> Result<StateSpace> {
        self.require_no_delays("parallel")?;
        other.require_no_delays("parallel")?;
        let domain = self.domain.join(other.domain, "parallel")?;
        if self.dims() != other.dims() {
            return Err(LtiError::invalid(format!(
                "parallel connection: {}×{} and {}×{} models (outputs × inputs) differ",
                self.n_outputs(),
                self.n_inputs(),
                other.n_outputs(),
                other.n_inputs()
            )));
        }
        let a = block_diag(&self.a, &other.a);
        let b = stack_rows(&self.b, &other.b);
        let c = stack_cols(&self.c, &other.c);
        Ok(StateSpace::new(a, b, c, &self.d + &other.d)?.with_domain(domain))
    }

    /// Feedback u₁ = r + sign·y₂ with y₂ = H·y₁ around `self` = G (x = [x_G; x_H]). With
    /// E = (I − sign·D_H·D_G)⁻¹ and u₁ = E(r + sign·D_H·C_G x_G + sign·C_H x_H):
    /// ẋ_G = A_G x_G + B_G u₁, ẋ_H = A_H x_H + B_H y₁, y₁ = C_G x_G + D_G u₁ (x\[k+1\] for ẋ in
    /// discrete time), in the two models' common domain.
    ///
    /// Errors: a sign other than ±1, models of different domains, mismatched dimensions, a singular I − sign·D_H·D_G
    /// (algebraic loop not well posed).
    ///
    /// ```
    /// use ltikit::{StateSpace, TransferFunction};
    /// let tf = |n: &[f64], d: &[f64]| TransferFunction::from_descending(n, d).unwrap();
    /// let g = StateSpace::from_tf(&tf(&[1.0], &[1.0, 1.0])).unwrap();
    /// let h = StateSpace::from_tf(&tf(&[2.0], &[1.0, 3.0])).unwrap();
    /// let t = g.feedback(&h, -1.0).unwrap().to_tf().unwrap();
    /// assert_eq!(t.den().coeffs(), &[1.0, 4.0, 5.0]);
    /// ```
    pub fn feedback(&self, h: &StateSpace, sign: f64) -> Result<StateSpace> {
        self.require_no_delays("feedback")?;
        h.require_no_delays("feedback")?;
        check_sign(sign)?;
        let domain = self.domain.join(h.domain, "feedback")?;
        let (m, p) = (self.n_inputs(), self.n_outputs());
        if h.n_inputs() != p || h.n_outputs() != m {
            return Err(LtiError::invalid(format!(
                "feedback: G is {p}×{m} (outputs × inputs), so H must be {m}×{p}, not {}×{}",
                h.n_outputs(),
                h.n_inputs()
            )));
        }
        let i_m = DMatrix::<f64>::identity(m, m);
        let e = (&i_m - (&h.d * &self.d) * sign)
            .try_inverse()
            .ok_or_else(|| {
                LtiError::invalid(
                    "feedback: I − sign·D_H·D_G is singular (the algebraic loop is not well posed)",
                )
            })?;
        let (n1, n2) = (self.order(), h.order());
        // u₁ = E·r + K₁·x_G + K₂·x_H
        let k1 = &e * &h.d * &self.c * sign;
        let k2 = &e * &h.c * sign;
        // y₁ = (C_G + D_G K₁) x_G + D_G K₂ x_H + D_G E r
        let y1 = &self.c + &self.d * &k1;
        let y2 = &self.d * &k2;
        let mut a = DMatrix::zeros(n1 + n2, n1 + n2);
        a.view_mut((0, 0), (n1, n1))
            .copy_from(&(&self.a + &self.b * &k1));
        a.view_mut((0, n1), (n1, n2)).copy_from(&(&self.b * &k2));
        a.view_mut((n1, 0), (n2, n1)).copy_from(&(&h.b * &y1));
        a.view_mut((n1, n1), (n2, n2))
            .copy_from(&(&h.a + &h.b * &y2));
        let de = &self.d * &e;
        let b = stack_rows(&(&self.b * &e), &(&h.b * &de));
        let c = stack_cols(&y1, &y2);
        Ok(StateSpace::new(a, b, c, de)?.with_domain(domain))
    }

    /// (outputs, inputs).
    fn dims(&self) -> (usize, usize) {
        (self.n_outputs(), self.n_inputs())
    }
}

fn block_diag(a: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(a.nrows() + b.nrows(), a.ncols() + b.ncols());
    m.view_mut((0, 0), a.shape()).copy_from(a);
    m.view_mut(a.shape(), b.shape()).copy_from(b);
    m
}

fn stack_rows(a: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(a.nrows() + b.nrows(), a.ncols());
    m.view_mut((0, 0), a.shape()).copy_from(a);
    m.view_mut((a.nrows(), 0), b.shape()).copy_from(b);
    m
}

fn stack_cols(a: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(a.nrows(), a.ncols() + b.ncols());
    m.view_mut((0, 0), a.shape()).copy_from(a);
    m.view_mut((0, a.ncols()), b.shape()).copy_from(b);
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::Complex64;

    fn tf(n: &[f64], d: &[f64]) -> TransferFunction {
        TransferFunction::from_descending(n, d).unwrap()
    }

    #[test]
    fn feedback_signs_and_bad_sign() {
        let g = tf(&[1.0], &[1.0, 0.0]);
        let one = tf(&[1.0], &[1.0]);
        // 1/s with +1 feedback: 1/(s − 1)
        assert_eq!(g.feedback(&one, 1.0).unwrap().den().coeffs(), &[1.0, -1.0]);
        assert!(g.feedback(&one, 0.5).is_err());
        // G = 1, H = 1, positive feedback: 1 − 1 ≡ 0
        assert!(one.feedback(&one, 1.0).is_err());
    }

    #[test]
    fn state_space_feedback_with_feedthrough_matches_tf() {
        // G = (s + 2)/(s + 1) (D = 1), H = 3/(s + 4): T = G/(1 + GH)
        let g = tf(&[1.0, 2.0], &[1.0, 1.0]);
        let h = tf(&[3.0], &[1.0, 4.0]);
        let t = g.feedback(&h, -1.0).unwrap();
        let ss = StateSpace::from_tf(&g)
            .unwrap()
            .feedback(&StateSpace::from_tf(&h).unwrap(), -1.0)
            .unwrap()
            .to_tf()
            .unwrap();
        for s in [Complex64::new(0.3, 1.7), Complex64::new(-2.5, 0.2)] {
            let (a, b) = (t.eval(s), ss.eval(s));
            assert!((a - b).norm() <= 1e-13 * a.norm(), "{a} {b}");
        }
        // D_G = 1, D_H = 1, positive feedback: I − 1 is singular
        let one = StateSpace::from_tf(&tf(&[1.0], &[1.0])).unwrap();
        assert!(one.feedback(&one, 1.0).is_err());
    }
}
