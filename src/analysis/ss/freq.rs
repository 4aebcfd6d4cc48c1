//! Frequency response of a state-space model, all channels at once: one Hessenberg reduction
//! of A ([`HessenbergResponse`]), then one O(n²) solve per frequency for all p×m channels
//! (ControlSystems.jl's method); from [`MODAL_POINTS_PER_STATE`]·n frequencies on, the modal
//! form ([`ModalForm`], O(n) per frequency and channel) when it is safe. The phase of each channel is made continuous along the
//! frequencies given (steps of more than 180° between neighbours are unwrapped by whole
//! turns).

use num_complex::Complex64;
use serde::Serialize;

use crate::error::{LtiError, Result, check_finite};
use crate::lti::StateSpace;
use crate::numeric::linalg::HessenbergResponse;
use crate::numeric::linalg::modal::ModalForm;

/// `freq_response_mimo` uses the modal form from this many frequencies per state on.
pub const MODAL_POINTS_PER_STATE: usize = 16;

/// G(jω) of every channel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MimoFreqResponse {
    /// Frequencies (rad/s), as given.
    pub w: Vec<f64>,
    /// `magnitude[j][i][k]`: |G_ji(jω_k)|, input i → output j.
    pub magnitude: Vec<Vec<Vec<f64>>>,
    /// `phase_deg[j][i][k]`: the continuous phase of G_ji (degrees).
    pub phase_deg: Vec<Vec<Vec<f64>>>,
}

impl StateSpace {
    /// G(jω) of all p×m channels at the frequencies `w` (finite, ≥ 0), continuous phase per
    /// channel (see the [module docs](self)).
    ///
    /// Errors: a negative or non-finite frequency.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::StateSpace;
    /// // 1/(s + 1) and 2/(s + 1) from one input.
    /// let ss = StateSpace::new(
    ///     DMatrix::from_element(1, 1, -1.0),
    ///     DMatrix::from_element(1, 1, 1.0),
    ///     DMatrix::from_row_slice(2, 1, &[1.0, 2.0]),
    ///     DMatrix::zeros(2, 1),
    /// ).unwrap();
    /// let r = ss.freq_response_mimo(&[0.0, 1.0]).unwrap();
    /// assert!((r.magnitude[1][0][0] - 2.0).abs() < 1e-15);
    /// assert!((r.phase_deg[0][0][1] + 45.0).abs() < 1e-13);
    /// ```
    pub fn freq_response_mimo(&self, w: &[f64]) -> Result<MimoFreqResponse> {
        for (k, &x) in w.iter().enumerate() {
            check_finite(|| format!("frequency {k}"), x)?;
            if x < 0.0 {
                return Err(LtiError::invalid(format!(
                    "frequency {k} is {x}: frequencies must be ≥ 0"
                )));
            }
        }
        let (m, p) = (self.b.ncols(), self.c.nrows());
        let mut magnitude = vec![vec![Vec::with_capacity(w.len()); m]; p];
        let mut phase_deg = vec![vec![Vec::with_capacity(w.len()); m]; p];
        let mut push = |j: usize, i: usize, z: Complex64| {
            magnitude[j][i].push(z.norm());
            let raw = z.arg().to_degrees();
            let ph: &mut Vec<f64> = &mut phase_deg[j][i];
            let v = match ph.last() {
                Some(&prev) => raw + 360.0 * ((prev - raw) / 360.0).round(),
                None => raw,
            };
            ph.push(v);
        };
        // Many frequencies: the modal form (O(n) per point after an O(n³) decomposition that
        // pays off beyond ~16n points), when it is safe; the Hessenberg solve otherwise.
        let modal = if w.len() >= MODAL_POINTS_PER_STATE * self.order() {
            ModalForm::new(&self.a, &self.b, &self.c, &self.d)?
        } else {
            None
        };
        if let Some(mf) = modal {
            for j in 0..p {
                for i in 0..m {
                    let ch = mf.channel(i, j);
                    for &x in w {
                        push(j, i, ch.eval(Complex64::new(0.0, x)));
                    }
                }
            }
        } else {
            let h = HessenbergResponse::new(&self.a, &self.b, &self.c, &self.d)?;
            let s: Vec<Complex64> = w.iter().map(|&x| Complex64::new(0.0, x)).collect();
            for g in h.eval_many(&s) {
                for j in 0..p {
                    for i in 0..m {
                        push(j, i, g[(j, i)]);
                    }
                }
            }
        }
        Ok(MimoFreqResponse {
            w: w.to_vec(),
            magnitude,
            phase_deg,
        })
    }
}
