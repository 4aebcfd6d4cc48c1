//! Time responses of state-space models (SISO or MIMO) by exact discretisation.
//!
//! Between two output times the input is a polynomial of degree ≤ 1 (a step is constant, a
//! first-order hold is linear), so the state update over a step h is exact:
//! e^(Mh) with M = [[A, B, 0], [0, 0, I], [0, 0, 0]] (Van Loan) gives
//! x(t + h) = Φx(t) + Γ₀u(t) + Γ₁u̇ with Φ = e^(Ah) and Γ₀, Γ₁ its other blocks. One
//! exponential serves every step of a uniform grid (recognised to a few ulps). The impulse
//! response starts from x(0⁺) = B·eᵢ (the D·δ(t) term is not included in the values); the
//! initial-state response from x(0) with u = 0.

use std::rc::Rc;

use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use crate::analysis::time::check_times;
use crate::error::{LtiError, Result};
use crate::lti::StateSpace;
use crate::numeric::expm;
use crate::numeric::linalg::StateMatrix;
use crate::numeric::linalg::modal::ModalForm;

use super::block_march::{BlockMap, BlockState, block_len};

/// Samples of the outputs (and optionally the states) of a state-space model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SsTimeResponse {
    /// Times (s), in the caller's order.
    pub t: Vec<f64>,
    /// `y[j][k]`: output j at `t[k]`.
    pub y: Vec<Vec<f64>>,
    /// `x[i][k]`: state i at `t[k]` (when asked for).
    pub x: Option<Vec<Vec<f64>>>,
}

/// How the input moves between its samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Hold {
    /// Piecewise constant: u(t) = u_k on \[t_k, t_(k+1)) (zero-order hold).
    Zero,
    /// Piecewise linear between the samples (first-order hold).
    First,
}

/// An input signal: times (increasing, ≥ 0) and one row of m values per time.
#[derive(Debug, Clone, PartialEq)]
pub struct InputSignal {
    /// Sample times (s), strictly increasing, the first ≥ 0.
    pub t: Vec<f64>,
    /// `u[k]`: the m input values at `t[k]`.
    pub u: Vec<Vec<f64>>,
}

impl InputSignal {
    /// Checks times (finite, ≥ 0, strictly increasing), lengths and values against `m` inputs.
    pub fn validate(&self, m: usize) -> Result<()> {
        check_times(&self.t)?;
        if self.t.len() != self.u.len() {
            return Err(LtiError::invalid(format!(
                "the input signal has {} times but {} rows of values",
                self.t.len(),
                self.u.len()
            )));
        }
        if self.t.is_empty() {
            return Err(LtiError::invalid("the input signal has no samples"));
        }
        for (k, w) in self.t.windows(2).enumerate() {
            if w[1] <= w[0] {
                return Err(LtiError::InvalidTime {
                    value: w[1],
                    reason: format!(
                        "input sample times must increase (row {} after t = {})",
                        k + 2,
                        w[0]
                    ),
                });
            }
        }
        for (k, row) in self.u.iter().enumerate() {
            if row.len() != m {
                return Err(LtiError::invalid(format!(
                    "input row {} has {} values, the model has {m} inputs",
                    k + 1,
                    row.len()
                )));
            }
            if let Some(v) = row.iter().find(|v| !v.is_finite()) {
                return Err(LtiError::NonFinite {
                    what: format!("input value in row {}", k + 1),
                    value: *v,
                });
            }
        }
        Ok(())
    }
}

/// The exact one-step maps for a step h: Φ, Γ₀ (constant input), Γ₁ (input slope).
struct StepMaps {
    phi: DMatrix<f64>,
    g0: DMatrix<f64>,
    g1: DMatrix<f64>,
}

impl StepMaps {
    /// The maps of a gap of m = h/T samples of a discrete-time model: Φ = A^m and
    /// Γ₀ = Σ_{i<m} A^i B (the input held over the gap), by binary powers of the augmented
    /// matrix [[A, B], [0, I]]; no slope term.
    fn discrete(a: &DMatrix<f64>, b: &DMatrix<f64>, h: f64, dt: f64) -> StepMaps {
        let (n, m) = (a.nrows(), b.ncols());
        let mut big = DMatrix::zeros(n + m, n + m);
        big.view_mut((0, 0), (n, n)).copy_from(a);
        big.view_mut((0, n), (n, m)).copy_from(b);
        for i in 0..m {
            big[(n + i, n + i)] = 1.0;
        }
        let result = crate::numeric::linalg::matrix_power(&big, (h / dt).round().max(0.0) as u64);
        StepMaps {
            phi: result.view((0, 0), (n, n)).into_owned(),
            g0: result.view((0, n), (n, m)).into_owned(),
            g1: DMatrix::zeros(n, m),
        }
    }

    fn new(a: &DMatrix<f64>, b: &DMatrix<f64>, h: f64) -> Result<StepMaps> {
        let (n, m) = (a.nrows(), b.ncols());
        let mut big = DMatrix::zeros(n + 2 * m, n + 2 * m);
        big.view_mut((0, 0), (n, n)).copy_from(&(a * h));
        big.view_mut((0, n), (n, m)).copy_from(&(b * h));
        for i in 0..m {
            big[(n + i, n + m + i)] = h;
        }
        let e = expm(&big)?;
        Ok(StepMaps {
            phi: e.view((0, 0), (n, n)).into_owned(),
            g0: e.view((0, n), (n, m)).into_owned(),
            // z = [x; u; u̇] with ż = Mz: the third block column maps the slope u̇
            g1: e.view((0, n + m), (n, m)).into_owned(),
        })
    }
}

/// The map of one step length: the one-step maps, and for a long run of equal steps under a
/// constant input the block maps ([`super::block_march`]).
enum StepMap {
    Plain(StepMaps),
    Blocked(Rc<BlockMap>),
}

/// Marches x from t = 0 through the sorted times, with the input `u(t)` given by `input`
/// (value and slope on the interval that starts at t), recording y (and x). `constant`: the
/// input's value when it is constant (step, impulse and free responses): long runs of equal
/// steps then go by blocks when that pays ([`block_len`]) and the states are not recorded.
struct March<'a> {
    ss: &'a StateSpace,
    keep_states: bool,
    constant: Option<DVector<f64>>,
}

impl March<'_> {
    fn run(
        &self,
        x0: DVector<f64>,
        t: &[f64],
        input: impl Fn(f64, f64) -> (DVector<f64>, DVector<f64>),
    ) -> Result<SsTimeResponse> {
        let ss = self.ss;
        let (n, p) = (ss.order(), ss.n_outputs());
        let mut y = vec![vec![0.0; t.len()]; p];
        let mut xs = self.keep_states.then(|| vec![vec![0.0; t.len()]; n]);
        let mut state = BlockState::new(x0);
        // in discrete time the state moves at the samples: a time reads the sample at or
        // before it
        let dt = ss.domain.dt();
        let snapped: Vec<f64> = match dt {
            Some(dt) => t
                .iter()
                .map(|&x| crate::analysis::closed_form::sample_floor(x, dt) * dt)
                .collect(),
            None => t.to_vec(),
        };
        let blocks = |run: usize| {
            let u = self.constant.as_ref()?;
            if self.keep_states {
                return None;
            }
            block_len(n, p, run).map(|len| (u, len))
        };
        crate::numeric::march::march(
            &snapped,
            &mut state,
            |h, _, run| {
                let maps = match dt {
                    Some(dt) => StepMaps::discrete(&ss.a, &ss.b, h, dt),
                    None => StepMaps::new(&ss.a, &ss.b, h)?,
                };
                Ok(match blocks(run) {
                    Some((u, len)) => {
                        let g = &maps.g0 * u;
                        let du = &ss.d * u;
                        StepMap::Blocked(Rc::new(BlockMap::new(&maps.phi, &g, &ss.c, &du, len)?))
                    }
                    None => StepMap::Plain(maps),
                })
            },
            |mp, st, from, to| {
                match mp {
                    StepMap::Plain(mp) => {
                        let (u, du) = input(from, to);
                        let x = st.settle();
                        *x = &mp.phi * &*x + &mp.g0 * &u + &mp.g1 * &du;
                    }
                    StepMap::Blocked(bm) => st.advance(bm),
                }
                Ok(())
            },
            |i, ti, st| {
                let computed;
                let yi = match st.outputs() {
                    Some(v) => v,
                    None => {
                        let (u_now, _) = input(ti, ti);
                        computed = &ss.c * st.anchor() + &ss.d * &u_now;
                        computed.as_slice()
                    }
                };
                for j in 0..p {
                    if !yi[j].is_finite() {
                        return Err(LtiError::Diverged {
                            t: ti,
                            norm: st.anchor().norm(),
                        });
                    }
                    y[j][i] = yi[j];
                }
                if let Some(xs) = xs.as_mut() {
                    let x = st.anchor();
                    for (k, row) in xs.iter_mut().enumerate() {
                        row[i] = x[k];
                    }
                }
                Ok(())
            },
        )?;
        Ok(SsTimeResponse {
            t: t.to_vec(),
            y,
            x: xs,
        })
    }
}

impl StateSpace {
    /// The modal form for the step, impulse and initial responses: models of order ≥
    /// [`MODAL_MIN_ORDER`](super::modal_time::MODAL_MIN_ORDER) with the second-order structure
    /// (their modal form comes from the modes, without a Schur form) and without the states
    /// asked for, when the form is safe ([`ModalForm::new`]); `None` sends them to the dense
    /// march. A model without that structure goes to the dense march too: one exponential and,
    /// on long runs of equal steps, blocks of samples ([`super::block_march`]) cost less than the
    /// Schur form with its vectors that a general modal form needs (256 random states, 10 000
    /// samples: ~15 ms against ~120 ms; docs/PERFORMANCE.md).
    fn modal_for(&self, states: bool) -> Option<ModalForm> {
        if states || self.order() < super::modal_time::MODAL_MIN_ORDER || self.domain.is_discrete()
        {
            return None;
        }
        let sm = StateMatrix::recognise(&self.a);
        sm.second_order()?;
        sm.modal_form(&self.b, &self.c, &self.d).ok().flatten()
    }

    fn check_input(&self, input: usize) -> Result<()> {
        if input >= self.n_inputs() {
            return Err(LtiError::invalid(format!(
                "input {} does not exist: the model has inputs 1…{}",
                input + 1,
                self.n_inputs()
            )));
        }
        Ok(())
    }

    /// A response to input `input` of a model with dead times: `rational` (the same response
    /// of the model without them) at the times shifted by each output's channel delay, 0
    /// before it; the states shifted by the input's delay.
    fn delayed_from(
        &self,
        input: usize,
        t: &[f64],
        states: bool,
        rational: impl Fn(&StateSpace, &[f64]) -> Result<SsTimeResponse>,
    ) -> Result<SsTimeResponse> {
        let mut plain = self.clone();
        plain.input_delays.clear();
        plain.output_delays.clear();
        let shifted = |d: f64| -> Result<Vec<Vec<f64>>> {
            let (ts, before) = crate::analysis::time::shift_times(t, d);
            let mut r = rational(&plain, &ts)?;
            for row in r.y.iter_mut().chain(r.x.iter_mut().flatten()) {
                for (v, &b) in row.iter_mut().zip(&before) {
                    if b {
                        *v = 0.0;
                    }
                }
            }
            Ok(r.y.into_iter().chain(r.x.into_iter().flatten()).collect())
        };
        let p = self.n_outputs();
        let mut y = vec![Vec::new(); p];
        let mut done: Vec<(f64, Vec<Vec<f64>>)> = Vec::new();
        for (i, yi) in y.iter_mut().enumerate() {
            let d = self.channel_delay(input, i);
            let k = match done.iter().position(|(e, _)| e.to_bits() == d.to_bits()) {
                Some(k) => k,
                None => {
                    done.push((d, shifted(d)?));
                    done.len() - 1
                }
            };
            *yi = done[k].1[i].clone();
        }
        let x = if states {
            let d = self.input_delays.get(input).copied().unwrap_or(0.0);
            Some(shifted(d)?.split_off(p))
        } else {
            None
        };
        Ok(SsTimeResponse {
            t: t.to_vec(),
            y,
            x,
        })
    }

    /// Response of every output to a unit step on input `input` (0-based) from x(0) = 0, at
    /// the times `t` (any order, finite, ≥ 0); the states too when `states`.
    ///
    /// ```
    /// use ltikit::StateSpace;
    /// use nalgebra::DMatrix;
    /// // ẋ = −x + u, y = x: y = 1 − e^(−t)
    /// let ss = StateSpace::new(
    ///     DMatrix::from_element(1, 1, -1.0), DMatrix::from_element(1, 1, 1.0),
    ///     DMatrix::from_element(1, 1, 1.0), DMatrix::zeros(1, 1),
    /// ).unwrap();
    /// let r = ss.step_response_from(0, &[0.0, 1.0, 2.0], false).unwrap();
    /// assert!((r.y[0][1] - (1.0 - (-1f64).exp())).abs() < 1e-15);
    /// ```
    pub fn step_response_from(
        &self,
        input: usize,
        t: &[f64],
        states: bool,
    ) -> Result<SsTimeResponse> {
        self.check_input(input)?;
        check_times(t)?;
        if self.has_delays() {
            return self.delayed_from(input, t, states, |ss, t| {
                ss.step_response_from(input, t, states)
            });
        }
        if let Some(mf) = self.modal_for(states) {
            let z0 = vec![num_complex::Complex64::new(0.0, 0.0); self.order()];
            let y = super::modal_time::march(&mf, z0, Some(input), t)?;
            return Ok(SsTimeResponse {
                t: t.to_vec(),
                y,
                x: None,
            });
        }
        let m = self.n_inputs();
        let mut u = DVector::zeros(m);
        u[input] = 1.0;
        let zero = DVector::zeros(m);
        March {
            ss: self,
            keep_states: states,
            constant: Some(u.clone()),
        }
        .run(DVector::zeros(self.order()), t, |_, _| {
            (u.clone(), zero.clone())
        })
    }

    /// Response of every output to a unit impulse on input `input` (x(0⁺) = B·eᵢ; the D·δ(t)
    /// term is not in the values).
    pub fn impulse_response_from(
        &self,
        input: usize,
        t: &[f64],
        states: bool,
    ) -> Result<SsTimeResponse> {
        self.check_input(input)?;
        check_times(t)?;
        if self.has_delays() {
            return self.delayed_from(input, t, states, |ss, t| {
                ss.impulse_response_from(input, t, states)
            });
        }
        let x0 = self.b.column(input).into_owned();
        if let Some(dt) = self.domain.dt() {
            // δ[k]: y[0] = D eᵢ (with x[0] = 0), then y[k] = C A^(k−1) B eᵢ — the free
            // response from B one sample late
            let late: Vec<f64> = t.iter().map(|&x| (x - dt).max(0.0)).collect();
            let mut r = self.free(x0, &late, states)?;
            for (i, &ti) in t.iter().enumerate() {
                if ti < dt * (1.0 - 4.0 * f64::EPSILON) {
                    for (j, row) in r.y.iter_mut().enumerate() {
                        row[i] = self.d[(j, input)];
                    }
                    if let Some(xs) = r.x.as_mut() {
                        for row in xs.iter_mut() {
                            row[i] = 0.0;
                        }
                    }
                }
            }
            r.t = t.to_vec();
            return Ok(r);
        }
        self.free(x0, t, states)
    }

    /// Free response from the initial state `x0` (u = 0).
    ///
    /// Errors: `x0` of the wrong length or not finite, bad times.
    pub fn initial_response(&self, x0: &[f64], t: &[f64], states: bool) -> Result<SsTimeResponse> {
        check_times(t)?;
        if !self.output_delays.is_empty() {
            return Err(LtiError::invalid(
                "a free response with output dead times: the outputs over [0, τ) would show \
                 the unknown past of the state",
            ));
        }
        if x0.len() != self.order() {
            return Err(LtiError::invalid(format!(
                "the initial state has {} values, the model has {} states",
                x0.len(),
                self.order()
            )));
        }
        if let Some(v) = x0.iter().find(|v| !v.is_finite()) {
            return Err(LtiError::NonFinite {
                what: "an initial state value".into(),
                value: *v,
            });
        }
        self.free(DVector::from_column_slice(x0), t, states)
    }

    fn free(&self, x0: DVector<f64>, t: &[f64], states: bool) -> Result<SsTimeResponse> {
        if let Some(mf) = self.modal_for(states) {
            let z0 = mf.modal_coordinates(x0.as_slice());
            let y = super::modal_time::march(&mf, z0, None, t)?;
            return Ok(SsTimeResponse {
                t: t.to_vec(),
                y,
                x: None,
            });
        }
        let zero = DVector::zeros(self.n_inputs());
        March {
            ss: self,
            keep_states: states,
            constant: Some(zero.clone()),
        }
        .run(x0, t, |_, _| (zero.clone(), zero.clone()))
    }

    /// Response to a sampled input signal (MATLAB `lsim`), held between its samples by `hold`,
    /// from `x0` (zero when `None`), at the signal's own times.
    ///
    /// ```
    /// use ltikit::StateSpace;
    /// use ltikit::analysis::ss::{Hold, InputSignal};
    /// use nalgebra::DMatrix;
    /// // ẋ = u, y = x with u = t (first-order hold is exact for a ramp): y = t²/2
    /// let ss = StateSpace::new(
    ///     DMatrix::zeros(1, 1), DMatrix::from_element(1, 1, 1.0),
    ///     DMatrix::from_element(1, 1, 1.0), DMatrix::zeros(1, 1),
    /// ).unwrap();
    /// let t: Vec<f64> = (0..=10).map(|k| 0.3 * k as f64).collect();
    /// let sig = InputSignal { u: t.iter().map(|&x| vec![x]).collect(), t: t.clone() };
    /// let r = ss.lsim(&sig, Hold::First, None, false).unwrap();
    /// assert!((r.y[0][10] - 4.5).abs() < 1e-13);
    /// ```
    pub fn lsim(
        &self,
        signal: &InputSignal,
        hold: Hold,
        x0: Option<&[f64]>,
        states: bool,
    ) -> Result<SsTimeResponse> {
        self.require_no_delays("a simulated response (lsim)")?;
        let m = self.n_inputs();
        signal.validate(m)?;
        let x0 = match x0 {
            Some(v) => {
                if v.len() != self.order() {
                    return Err(LtiError::invalid(format!(
                        "the initial state has {} values, the model has {} states",
                        v.len(),
                        self.order()
                    )));
                }
                DVector::from_column_slice(v)
            }
            None => DVector::zeros(self.order()),
        };
        let ts = &signal.t;
        let rows: Vec<DVector<f64>> = signal
            .u
            .iter()
            .map(|r| DVector::from_column_slice(r))
            .collect();
        let zero = DVector::zeros(m);
        // the interval [ts[k], ts[k+1]) that contains `from`
        let at = |from: f64| -> usize { ts.partition_point(|&x| x <= from).saturating_sub(1) };
        let input = |from: f64, to: f64| {
            if from < ts[0] {
                return (zero.clone(), zero.clone());
            }
            let k = at(from);
            let u = rows[k].clone();
            let du = match hold {
                Hold::First if k + 1 < ts.len() && to > from => {
                    (&rows[k + 1] - &rows[k]) / (ts[k + 1] - ts[k])
                }
                _ => zero.clone(),
            };
            (u, du)
        };
        // march from 0 to the first sample with u = 0, then through the samples
        let march = March {
            ss: self,
            keep_states: states,
            constant: None,
        };
        march.run(x0, ts, input)
    }
}
