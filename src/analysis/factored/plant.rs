//! A plant's factored form: a transfer function is factored by its roots, a SISO state-space
//! model (or one channel of a MIMO one) by its eigenvalues and transmission zeros.

use super::Factored;
use crate::error::{LtiError, Result};
use crate::lti::{Model, Plant, StateSpace};

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
            Model::Tf(g) => g.factored(),
            Model::Ss(ss) => {
                if ss.n_inputs() != 1 || ss.n_outputs() != 1 {
                    return Err(LtiError::invalid(format!(
                        "this analysis takes one input and one output; the plant has {} inputs and {} outputs: choose a channel (--channel INPUT,OUTPUT)",
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
            Model::Tf(g) => {
                if input != 0 || output != 0 {
                    return Err(LtiError::invalid(format!(
                        "channel input {} → output {} does not exist: a transfer function has one input and one output",
                        input + 1,
                        output + 1
                    )));
                }
                g.factored()
            }
            Model::Ss(ss) => Factored::from_state_space(&ss.channel(input, output)?),
        }
    }
}

impl Factored {
    /// The factored form of a SISO state-space model.
    ///
    /// Errors: a model that is not SISO.
    pub fn from_state_space(ss: &StateSpace) -> Result<Factored> {
        // Interim: through the transfer function (orders ≤ MAX_ORDER) until the state-space
        // kernels (eigenvalues, transmission zeros, minimal realisation) land.
        ss.to_tf()?.factored()
    }
}
