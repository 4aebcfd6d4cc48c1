//! What a plant is, once read: a transfer function (SISO, from coefficients) or a state-space
//! model (SISO or MIMO), with the names of its signals.

use nalgebra::DMatrix;

use crate::error::{LtiError, Result};
use crate::lti::{StateSpace, TransferFunction};

pub use crate::limits::{MAX_SIGNALS, MAX_STATES};

/// A plant's model.
#[derive(Debug, Clone, PartialEq)]
pub enum Model {
    /// A SISO transfer function from ODE coefficients.
    Tf(TransferFunction),
    /// A state-space model ẋ = Ax + Bu, y = Cx + Du.
    Ss(StateSpace),
}

impl Model {
    /// (inputs, outputs).
    pub fn dims(&self) -> (usize, usize) {
        match self {
            Model::Tf(_) => (1, 1),
            Model::Ss(ss) => (ss.b.ncols(), ss.c.nrows()),
        }
    }

    /// One input and one output.
    pub fn is_siso(&self) -> bool {
        self.dims() == (1, 1)
    }

    /// Number of states (the order).
    pub fn order(&self) -> usize {
        match self {
            Model::Tf(g) => g.order(),
            Model::Ss(ss) => ss.order(),
        }
    }
}

impl std::fmt::Display for Model {
    /// A transfer function as `N / (D)`; a state-space model by its size.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Model::Tf(g) => write!(f, "{g}"),
            Model::Ss(ss) => write!(
                f,
                "state-space model with {} states, {} inputs, {} outputs",
                ss.order(),
                ss.n_inputs(),
                ss.n_outputs()
            ),
        }
    }
}

/// Names of a plant's inputs, outputs and states (generated `u1`, `y1`, `x1`, … when not
/// given).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Signals {
    /// One per input.
    pub inputs: Vec<String>,
    /// One per output.
    pub outputs: Vec<String>,
    /// One per state (empty for a transfer function).
    pub states: Vec<String>,
}

impl Signals {
    /// Names for `model`: the given ones (which must have the right count) or generated.
    ///
    /// ```
    /// use ltikit::lti::model::{Model, Signals};
    /// use ltikit::TransferFunction;
    /// let g = Model::Tf(TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap());
    /// let s = Signals::for_model(&g, vec![], vec!["level".into()], vec![]).unwrap();
    /// assert_eq!((s.inputs[0].as_str(), s.outputs[0].as_str()), ("u", "level"));
    /// ```
    pub fn for_model(
        model: &Model,
        inputs: Vec<String>,
        outputs: Vec<String>,
        states: Vec<String>,
    ) -> Result<Signals> {
        let (m, p) = model.dims();
        let n = match model {
            Model::Tf(_) => 0,
            Model::Ss(ss) => ss.order(),
        };
        let names = |given: Vec<String>, count: usize, stem: &str, what: &str| {
            if given.is_empty() {
                return Ok(if count == 1 && stem != "x" {
                    vec![stem.to_string()]
                } else {
                    (1..=count).map(|k| format!("{stem}{k}")).collect()
                });
            }
            if given.len() != count {
                return Err(LtiError::invalid(format!(
                    "{} {what} names given for a model with {count} {what}s",
                    given.len()
                )));
            }
            Ok(given)
        };
        Ok(Signals {
            inputs: names(inputs, m, "u", "input")?,
            outputs: names(outputs, p, "y", "output")?,
            states: names(states, n, "x", "state")?,
        })
    }
}

impl StateSpace {
    /// Number of inputs m.
    pub fn n_inputs(&self) -> usize {
        self.b.ncols()
    }

    /// Number of outputs p.
    pub fn n_outputs(&self) -> usize {
        self.c.nrows()
    }

    /// The SISO channel from input `input` to output `output` (0-based): (A, B\[:, i\],
    /// C\[j, :\], D\[j, i\]), in the model's domain.
    ///
    /// Errors: an index that does not exist (naming the ranges).
    ///
    /// ```
    /// use ltikit::StateSpace;
    /// use nalgebra::DMatrix;
    /// let ss = StateSpace::new(
    ///     DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -2.0]),
    ///     DMatrix::identity(2, 2),
    ///     DMatrix::identity(2, 2),
    ///     DMatrix::zeros(2, 2),
    /// ).unwrap();
    /// let ch = ss.channel(1, 1).unwrap();
    /// assert_eq!((ch.b[(1, 0)], ch.c[(0, 1)]), (1.0, 1.0));
    /// assert!(ss.channel(2, 0).is_err());
    /// ```
    pub fn channel(&self, input: usize, output: usize) -> Result<StateSpace> {
        let (m, p) = (self.n_inputs(), self.n_outputs());
        if input >= m || output >= p {
            return Err(LtiError::invalid(format!(
                "channel input {} → output {} does not exist: the model has inputs 1…{m} and outputs 1…{p}",
                input + 1,
                output + 1
            )));
        }
        StateSpace::new(
            self.a.clone(),
            self.b.columns(input, 1).into_owned(),
            self.c.rows(output, 1).into_owned(),
            DMatrix::from_element(1, 1, self.d[(output, input)]),
        )?
        .with_domain(self.domain)
        .with_delays(
            self.input_delays
                .get(input)
                .map(|&t| vec![t])
                .unwrap_or_default(),
            self.output_delays
                .get(output)
                .map(|&t| vec![t])
                .unwrap_or_default(),
        )
    }

    /// Refuses models beyond [`MAX_STATES`] states or [`MAX_SIGNALS`] inputs or outputs.
    pub fn check_size(&self) -> Result<()> {
        if self.order() > MAX_STATES {
            return Err(LtiError::OrderTooHigh {
                order: self.order(),
                max: MAX_STATES,
            });
        }
        let (m, p) = (self.n_inputs(), self.n_outputs());
        if m > MAX_SIGNALS || p > MAX_SIGNALS {
            return Err(LtiError::invalid(format!(
                "{m} inputs and {p} outputs: at most {MAX_SIGNALS} of each are supported"
            )));
        }
        Ok(())
    }
}
