//! A nonlinear model under linear state feedback about an operating point: the law a linear
//! design (LQR, pole placement) produces, applied to the model it was designed from.
//!
//! u = ū + v − K (x − x̄), each entry optionally clipped to ±`limit` (an actuator that
//! saturates); v is the closed loop's own input (a reference or a disturbance, zero for a
//! regulator). The closed loop is again a [`NonlinearSystem`], so equilibria, exact
//! linearisation (at x̄ it is A − B K when no limit is active), simulation and phase portraits
//! all apply to it unchanged.

use nalgebra::DMatrix;

use crate::error::{LtiError, Result};
use crate::nonlinear::system::{NonlinearSystem, Scalar, SystemInfo};

/// The closed loop ẋ = f(x, sat(ū + v − K (x − x̄))), y = h(x, ·) of a model under state
/// feedback (module docs).
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::nonlinear::{DynSystem, StateFeedback, models::Pendulum};
/// let p = Pendulum::new(1.0, 1.0, 0.5, 9.81).unwrap();
/// let upright = [std::f64::consts::PI, 0.0];
/// let k = DMatrix::from_row_slice(1, 2, &[20.0, 5.0]);
/// let cl = StateFeedback::new(p, &upright, &[0.0], k, None).unwrap();
/// // linearised at the operating point it is A − B K
/// let (a, _) = cl.jacobian_f(&upright, &[0.0]);
/// let (a0, b0) = p.jacobian_f(&upright, &[0.0]);
/// let expected = a0 - b0 * DMatrix::from_row_slice(1, 2, &[20.0, 5.0]);
/// assert!((a - expected).norm() < 1e-14);
/// ```
#[derive(Debug, Clone)]
pub struct StateFeedback<S> {
    plant: S,
    x_op: Vec<f64>,
    u_op: Vec<f64>,
    gain: DMatrix<f64>,
    limit: Option<f64>,
}

impl<S: NonlinearSystem> StateFeedback<S> {
    /// The closed loop of `plant` under u = ū + v − K (x − x̄), clipped to ±`limit` when given.
    ///
    /// Errors: x̄, ū or K of the wrong size, a non-finite entry, a limit that is not positive.
    pub fn new(
        plant: S,
        x_op: &[f64],
        u_op: &[f64],
        gain: DMatrix<f64>,
        limit: Option<f64>,
    ) -> Result<Self> {
        let (n, m) = (plant.nx(), plant.nu());
        if x_op.len() != n || u_op.len() != m {
            return Err(LtiError::invalid(format!(
                "state feedback: the operating point has {} states and {} inputs, the model {n} \
                 and {m}",
                x_op.len(),
                u_op.len()
            )));
        }
        if gain.nrows() != m || gain.ncols() != n {
            return Err(LtiError::invalid(format!(
                "state feedback: K is {}×{}, the model needs {m}×{n} (inputs × states)",
                gain.nrows(),
                gain.ncols()
            )));
        }
        if !x_op
            .iter()
            .chain(u_op)
            .chain(gain.iter())
            .all(|v| v.is_finite())
        {
            return Err(LtiError::invalid(
                "state feedback: the operating point and K must be finite",
            ));
        }
        if let Some(l) = limit
            && !(l > 0.0 && l.is_finite())
        {
            return Err(LtiError::invalid(format!(
                "state feedback: the input limit must be positive and finite, got {l}"
            )));
        }
        Ok(StateFeedback {
            plant,
            x_op: x_op.to_vec(),
            u_op: u_op.to_vec(),
            gain,
            limit,
        })
    }

    /// The model under feedback.
    pub fn plant(&self) -> &S {
        &self.plant
    }

    /// The input the law applies at state x with external input v (after the limit).
    pub fn control<D: Scalar>(&self, x: &[D], v: &[D]) -> Vec<D> {
        (0..self.plant.nu())
            .map(|i| {
                let mut u = D::from(self.u_op[i]) + v[i];
                for (j, xj) in x.iter().enumerate() {
                    u -= (*xj - self.x_op[j]) * self.gain[(i, j)];
                }
                match self.limit {
                    Some(l) if u.re() > l => D::from(l),
                    Some(l) if u.re() < -l => D::from(-l),
                    _ => u,
                }
            })
            .collect()
    }
}

impl<S: NonlinearSystem> SystemInfo for StateFeedback<S> {
    fn nx(&self) -> usize {
        self.plant.nx()
    }
    fn nu(&self) -> usize {
        self.plant.nu()
    }
    fn ny(&self) -> usize {
        self.plant.ny()
    }
    fn model_name(&self) -> String {
        format!("{} under state feedback", self.plant.model_name())
    }
    fn params(&self) -> Vec<(String, f64)> {
        self.plant.params()
    }
    fn state_names(&self) -> Vec<String> {
        self.plant.state_names()
    }
    fn input_names(&self) -> Vec<String> {
        self.plant.input_names()
    }
    fn output_names(&self) -> Vec<String> {
        self.plant.output_names()
    }
}

impl<S: NonlinearSystem> NonlinearSystem for StateFeedback<S> {
    fn f<D: Scalar>(&self, x: &[D], v: &[D], dx: &mut [D]) {
        let u = self.control(x, v);
        self.plant.f(x, &u, dx);
    }
    fn h<D: Scalar>(&self, x: &[D], v: &[D], y: &mut [D]) {
        let u = self.control(x, v);
        self.plant.h(x, &u, y);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nonlinear::models::Pendulum;
    use crate::nonlinear::{DynSystem, InputSignal, simulate};
    use crate::numeric::rk45::Rk45Options;
    use std::f64::consts::PI;

    fn pendulum() -> Pendulum {
        Pendulum::new(1.0, 1.0, 0.5, 9.81).unwrap()
    }

    #[test]
    fn sizes_and_values_are_checked() {
        let k = DMatrix::from_row_slice(1, 2, &[1.0, 1.0]);
        assert!(StateFeedback::new(pendulum(), &[0.0], &[0.0], k.clone(), None).is_err());
        assert!(StateFeedback::new(pendulum(), &[0.0, 0.0], &[], k.clone(), None).is_err());
        let k3 = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, 1.0]);
        assert!(StateFeedback::new(pendulum(), &[0.0, 0.0], &[0.0], k3, None).is_err());
        assert!(StateFeedback::new(pendulum(), &[f64::NAN, 0.0], &[0.0], k.clone(), None).is_err());
        assert!(StateFeedback::new(pendulum(), &[0.0, 0.0], &[0.0], k.clone(), Some(0.0)).is_err());
        assert!(StateFeedback::new(pendulum(), &[0.0, 0.0], &[0.0], k, Some(1.0)).is_ok());
    }

    #[test]
    fn the_limit_clips_the_input() {
        let k = DMatrix::from_row_slice(1, 2, &[10.0, 0.0]);
        let cl = StateFeedback::new(pendulum(), &[PI, 0.0], &[0.0], k, Some(2.0)).unwrap();
        // x − x̄ = −1 rad: −K(x − x̄) = 10, clipped to 2
        assert_eq!(cl.control(&[PI - 1.0, 0.0], &[0.0]), vec![2.0]);
        assert_eq!(cl.control(&[PI + 1.0, 0.0], &[0.0]), vec![-2.0]);
        assert_eq!(
            cl.control(&[PI + 0.1, 0.0], &[0.0]),
            vec![-1.0000000000000009]
        );
    }

    #[test]
    fn a_stabilising_gain_holds_the_pendulum_upright() {
        // linearised at θ = π: θ̈ = 14.715 (θ − π) − 1.5 θ̇ + 3τ; K = [20, 5] gives the
        // characteristic polynomial s² + 16.5 s + 45.285, both roots in the left half plane
        let k = DMatrix::from_row_slice(1, 2, &[20.0, 5.0]);
        let cl = StateFeedback::new(pendulum(), &[PI, 0.0], &[0.0], k, None).unwrap();
        let times: Vec<f64> = (0..=100).map(|i| 0.1 * i as f64).collect();
        let sim = simulate(
            &cl,
            &[PI - 0.3, 0.0],
            &InputSignal::constant(vec![0.0]),
            &times,
            &Rk45Options::default(),
        )
        .unwrap();
        let last = sim.states.last().unwrap();
        assert!((last[0] - PI).abs() < 1e-6, "{last:?}");
        let mut dx = [0.0; 2];
        cl.eval_f(&[PI, 0.0], &[0.0], &mut dx);
        // sin(π) in floating point is 1.2e-16: the upright equilibrium to that rounding
        assert!(dx[0] == 0.0 && dx[1].abs() < 1e-14, "{dx:?}");
    }
}
