//! Frequency response of a state-space model, all channels, through the one frequency engine:
//! each channel ([`StateSpace::channel`]) enters the factored core
//! ([`Factored::from_state_space`]: minimal realisation, eigenvalues, transmission zeros) and
//! is evaluated by its Bode form ([`Factored::freq_response`], O(n) per frequency in the fused
//! kernel). A channel's magnitude and phase are therefore exactly those of the SISO frequency
//! response of that channel, with its one phase rule (see [`crate::analysis::freq`]): continuous
//! in ω and independent of the grid — the low-frequency asymptote K·(jω)^k fixes the start
//! (1/s³ starts at −270°, a negative gain at −180°), each factor's angle is tracked on its own
//! branch, a right-half-plane zero adds lag, a pole pair on the imaginary axis drops the phase
//! by 180° as ω passes it.

use serde::Serialize;

use crate::analysis::factored::Factored;
use crate::analysis::freq::check_frequencies;
use crate::error::Result;
use crate::lti::StateSpace;

/// G(jω) of every channel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MimoFreqResponse {
    /// Frequencies (rad/s), as given.
    pub w: Vec<f64>,
    /// `magnitude[j][i][k]`: |G_ji(jω_k)|, input i → output j.
    pub magnitude: Vec<Vec<Vec<f64>>>,
    /// `phase_deg[j][i][k]`: the continuous phase of G_ji (degrees), as the SISO
    /// [`Factored::freq_response`] of that channel gives it.
    pub phase_deg: Vec<Vec<Vec<f64>>>,
}

impl StateSpace {
    /// G(jω) of all p×m channels at the frequencies `w` (rad/s, finite, ≥ 0, any order), each
    /// channel by its factored form (see the [module docs](self)): the same values as
    /// `Factored::from_state_space(&ss.channel(i, j)?)?.freq_response(w)`.
    ///
    /// Errors: a negative or non-finite frequency; a channel the factored core refuses.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::StateSpace;
    /// // 1/(s + 1) and −2/(s + 1) from one input: the negative gain starts at −180°.
    /// let ss = StateSpace::new(
    ///     DMatrix::from_element(1, 1, -1.0),
    ///     DMatrix::from_element(1, 1, 1.0),
    ///     DMatrix::from_row_slice(2, 1, &[1.0, -2.0]),
    ///     DMatrix::zeros(2, 1),
    /// ).unwrap();
    /// let r = ss.freq_response_mimo(&[0.0, 1.0]).unwrap();
    /// assert!((r.magnitude[1][0][0] - 2.0).abs() < 1e-15);
    /// assert!((r.phase_deg[0][0][1] + 45.0).abs() < 1e-13);
    /// assert!((r.phase_deg[1][0][0] + 180.0).abs() < 1e-13);
    /// ```
    pub fn freq_response_mimo(&self, w: &[f64]) -> Result<MimoFreqResponse> {
        check_frequencies(w)?;
        let (m, p) = (self.n_inputs(), self.n_outputs());
        let mut magnitude = Vec::with_capacity(p);
        let mut phase_deg = Vec::with_capacity(p);
        for j in 0..p {
            let (mut mag_j, mut phase_j) = (Vec::with_capacity(m), Vec::with_capacity(m));
            for i in 0..m {
                let r = Factored::from_state_space(&self.channel(i, j)?)?.freq_response(w)?;
                mag_j.push(r.magnitude);
                phase_j.push(r.phase_deg);
            }
            magnitude.push(mag_j);
            phase_deg.push(phase_j);
        }
        Ok(MimoFreqResponse {
            w: w.to_vec(),
            magnitude,
            phase_deg,
        })
    }
}
