//! Linear models ẋ = A x + B u, y = C x + D u as nonlinear systems — in particular the seed's
//! linear textbook plants ([`crate::lti::plant_specs`]). Their linearisation at any point is
//! (A, B, C, D) itself, bit for bit: forward-mode AD of a linear map is exact.
//!
//! All-pole plants b₀/(aₙsⁿ + … + a₀) are realised in phase variables x = [y, y′, …, y⁽ⁿ⁻¹⁾]
//! (states named `y`, `y'`, `y''`, …), so a simulation shows the physical output and its
//! derivatives; other plants use the controllable canonical form of [`StateSpace::from_tf`].

use nalgebra::{DMatrix, DVector};

use crate::analysis::auto_time_span;
use crate::error::Result;
use crate::lti::{StateSpace, TransferFunction, build_plant};
use crate::nonlinear::system::{NonlinearSystem, Scalar, SystemInfo};

/// A linear state-space model wrapped as a [`NonlinearSystem`].
///
/// ```
/// use ltikit::nonlinear::{models::LinearModel, jacobians};
/// let m = LinearModel::from_plant("spring-mass-damper", &[]).unwrap();
/// let j = jacobians(&m, &[0.3, -1.0], &[2.0]).unwrap();
/// assert_eq!(j.a, m.ss().a); // exactly
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct LinearModel {
    name: String,
    ss: StateSpace,
    params: Vec<(String, f64)>,
    states: Vec<String>,
    horizon: f64,
}

impl LinearModel {
    /// Wraps a state-space model (states named x1, x2, …).
    pub fn new(name: impl Into<String>, ss: StateSpace) -> Self {
        let states = (1..=ss.order()).map(|i| format!("x{i}")).collect();
        LinearModel {
            name: name.into(),
            ss,
            params: Vec::new(),
            states,
            horizon: 10.0,
        }
    }

    /// A realisation of a proper SISO transfer function: phase variables for an all-pole
    /// G, the controllable canonical form otherwise.
    pub fn from_tf(name: impl Into<String>, g: &TransferFunction) -> Result<Self> {
        g.require_proper("a state-space realisation", false)?;
        if g.num().degree() == 0 && g.order() >= 1 {
            let n = g.order();
            let den = g.den().coeffs();
            let lead = den[0];
            let mut a = DMatrix::zeros(n, n);
            for i in 0..n - 1 {
                a[(i, i + 1)] = 1.0;
            }
            for j in 0..n {
                // y⁽ⁿ⁾ = −(a₀ y + a₁ y′ + … + aₙ₋₁ y⁽ⁿ⁻¹⁾)/aₙ + (b₀/aₙ) u
                a[(n - 1, j)] = -den[n - j] / lead;
            }
            let mut b = DMatrix::zeros(n, 1);
            b[(n - 1, 0)] = g.num().coeff(0) / lead;
            let mut c = DMatrix::zeros(1, n);
            c[(0, 0)] = 1.0;
            let ss = StateSpace::new(a, b, c, DMatrix::zeros(1, 1))?;
            let states = (0..n).map(|k| format!("y{}", "'".repeat(k))).collect();
            Ok(LinearModel {
                name: name.into(),
                ss,
                params: Vec::new(),
                states,
                horizon: horizon(g),
            })
        } else {
            let mut m = Self::new(name, StateSpace::from_tf(g)?);
            m.horizon = horizon(g);
            Ok(m)
        }
    }

    /// The textbook plant `name` with parameter overrides (see [`build_plant`]).
    pub fn from_plant(name: &str, overrides: &[(String, f64)]) -> Result<Self> {
        let (g, used) = build_plant(name, overrides)?;
        let mut m = Self::from_tf(name, &g)?;
        m.params = used;
        Ok(m)
    }

    /// The wrapped state-space model.
    pub fn ss(&self) -> &StateSpace {
        &self.ss
    }
}

/// The automatic time span of the plant's responses (1.5× the 2 % settling of the slowest
/// mode, five periods of undamped modes, …), 10 s when it has none.
fn horizon(g: &TransferFunction) -> f64 {
    g.factored()
        .and_then(|f| auto_time_span(&f))
        .map(|s| s.t_end)
        .ok()
        .filter(|t| t.is_finite() && *t > 0.0)
        .unwrap_or(10.0)
}

impl SystemInfo for LinearModel {
    fn nx(&self) -> usize {
        self.ss.order()
    }
    fn nu(&self) -> usize {
        self.ss.b.ncols()
    }
    fn ny(&self) -> usize {
        self.ss.c.nrows()
    }
    fn model_name(&self) -> String {
        self.name.clone()
    }
    fn params(&self) -> Vec<(String, f64)> {
        self.params.clone()
    }
    fn state_names(&self) -> Vec<String> {
        self.states.clone()
    }

    /// The first state 1, the others 0: y(0) = 1 at rest for the phase-variable plants (the
    /// seed's exercise 2.7 start).
    fn default_initial_state(&self) -> Vec<f64> {
        let mut x = vec![0.0; self.nx()];
        if let Some(v) = x.first_mut() {
            *v = 1.0;
        }
        x
    }

    fn default_horizon(&self) -> f64 {
        self.horizon
    }

    /// Solutions of A x = −B u: the unique one when A is invertible; the minimum-norm one when
    /// A is singular and B u lies in its range (then the equilibria form an affine subspace);
    /// none otherwise.
    fn closed_form_equilibria(&self, u: &[f64]) -> Option<Vec<Vec<f64>>> {
        let n = self.nx();
        let rhs = -(&self.ss.b * DVector::from_column_slice(u));
        if n == 0 {
            return Some(vec![Vec::new()]);
        }
        if let Some(x) = self.ss.a.clone().lu().solve(&rhs) {
            if x.iter().all(|v| v.is_finite()) {
                return Some(vec![x.as_slice().to_vec()]);
            }
        }
        let x = crate::numeric::lstsq::min_norm_solve(&self.ss.a, &rhs, 1e-12)?;
        let res = (&self.ss.a * &x - &rhs).amax();
        if res <= 1e-10 * (1.0 + rhs.amax()) {
            Some(vec![x.as_slice().to_vec()])
        } else {
            Some(Vec::new())
        }
    }
}

fn affine<D: Scalar>(m: &DMatrix<f64>, v: &[D], acc: &mut [D]) {
    for (i, a) in acc.iter_mut().enumerate() {
        for (j, &vj) in v.iter().enumerate() {
            let c = m[(i, j)];
            if c != 0.0 {
                *a += vj * c;
            }
        }
    }
}

impl NonlinearSystem for LinearModel {
    fn f<D: Scalar>(&self, x: &[D], u: &[D], dx: &mut [D]) {
        dx.fill(D::from(0.0));
        affine(&self.ss.a, x, dx);
        affine(&self.ss.b, u, dx);
    }
    fn h<D: Scalar>(&self, x: &[D], u: &[D], y: &mut [D]) {
        y.fill(D::from(0.0));
        affine(&self.ss.c, x, y);
        affine(&self.ss.d, u, y);
    }
}
