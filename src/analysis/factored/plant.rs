//! A plant's factored form: a transfer function is factored by its roots, a SISO state-space
//! model (or one channel of a MIMO one) by its eigenvalues and transmission zeros.

use super::decision::Decision;
use super::form::{Factored, assemble};
use super::source::Source;
use super::ss_source::factor_state_space;
use crate::error::{LtiError, Result};
use crate::lti::plant::Coefficient;
use crate::lti::{Model, Plant, StateSpace, TransferFunction};
use crate::poly::exact::ExactPoly;

impl Plant {
    /// The factored form of a SISO plant (a transfer function, or a state-space model with
    /// one input and one output).
    ///
    /// Errors: a MIMO plant (choose a channel with [`Plant::factored_channel`]), and those
    /// of the factorisation.
    ///
    /// ```
    /// use ltikit::lti::Plant;
    /// let p = Plant::from_matrices_text("0 1; -4 -0.8", "0; 4", "1 0", None).unwrap();
    /// let f = p.factored().unwrap();
    /// assert!((f.dc_gain().unwrap() - 1.0).abs() < 1e-14);
    /// ```
    pub fn factored(&self) -> Result<Factored> {
        match &self.model {
            Model::Tf(g) => match &self.typed {
                Some((num, den)) => Factored::from_typed(g, num, den)?.with_delay(g.delay()),
                None => g.factored(),
            },
            Model::Ss(ss) => {
                if ss.n_inputs() != 1 || ss.n_outputs() != 1 {
                    return Err(LtiError::invalid(format!(
                        "this analysis takes one input and one output; the plant has {} inputs and {} outputs: choose a channel (`channel` INPUT,OUTPUT)",
                        ss.n_inputs(),
                        ss.n_outputs()
                    )));
                }
                Factored::from_state_space(ss)
            }
        }
    }

    /// The factored form of the channel from input `input` to output `output` (0-based).
    pub fn factored_channel(&self, input: usize, output: usize) -> Result<Factored> {
        match &self.model {
            Model::Tf(_) => {
                if input != 0 || output != 0 {
                    return Err(LtiError::invalid(format!(
                        "channel input {} → output {} does not exist: a transfer function has one input and one output",
                        input + 1,
                        output + 1
                    )));
                }
                self.factored()
            }
            Model::Ss(ss) => Factored::from_state_space(&ss.channel(input, output)?),
        }
    }
}

impl Factored {
    /// A transfer function whose coefficients arrived as text: factored on the exact path
    /// from the text (see [`Factored::from_exact`]), numerically when the text is not exact
    /// or the exact path is beyond its budget.
    fn from_typed(
        g: &TransferFunction,
        num: &[Coefficient],
        den: &[Coefficient],
    ) -> Result<Factored> {
        let exact = |c: &[Coefficient], what: &str| {
            let texts: Vec<&str> = c.iter().map(|c| c.text.as_str()).collect();
            ExactPoly::parse_descending_named(&texts, what)
        };
        match exact(num, "numerator").and_then(|n| Ok((n, exact(den, "denominator")?))) {
            Ok((n, d)) => Factored::from_exact_tf(g, &n, &d),
            Err(e) => Factored::numerical_fallback(g, &e),
        }
    }

    /// The factored form of a SISO state-space model, without coefficients: poles are the
    /// eigenvalues of A with their multiplicities, the removed modes of a minimal realisation
    /// (uncontrollable or unobservable) are the cancelled roots, zeros are the transmission
    /// zeros and the gain is the first non-zero Markov parameter. G(s) and the dc gain come
    /// from the minimal realisation (its Hessenberg form and an LU solve).
    ///
    /// Errors: a model that is not SISO, more than
    /// [`MAX_FACTORED_ORDER`](super::pole_zero::MAX_FACTORED_ORDER) states.
    ///
    /// ```
    /// use nalgebra::{DMatrix, DVector};
    /// use ltikit::StateSpace;
    /// use ltikit::analysis::Factored;
    /// // 1/((s + 1)(s + 2)) in diagonal form, with a third, uncontrollable mode at −5.
    /// let a = DMatrix::from_diagonal(&DVector::from_vec(vec![-1.0, -2.0, -5.0]));
    /// let b = DMatrix::from_column_slice(3, 1, &[1.0, -1.0, 0.0]);
    /// let c = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, 1.0]);
    /// let ss = StateSpace::new(a, b, c, DMatrix::zeros(1, 1)).unwrap();
    /// let f = Factored::from_state_space(&ss).unwrap();
    /// assert_eq!(f.poles().len(), 3);
    /// assert_eq!(f.reduced_poles().len(), 2);
    /// assert!((f.pole_zero().cancelled[0].value.re + 5.0).abs() < 1e-14);
    /// assert!((f.dc_gain().unwrap() - 0.5).abs() < 1e-15);
    /// ```
    pub fn from_state_space(ss: &StateSpace) -> Result<Factored> {
        let (pz, gain, source) = factor_state_space(ss)?;
        assemble(
            pz,
            gain,
            Source::StateSpace(Box::new(source)),
            Decision::default(),
        )
        .with_domain(ss.domain)
        .with_delay(ss.channel_delay(0, 0))
    }
}
