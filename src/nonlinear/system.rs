//! The model traits: [`NonlinearSystem`] (generic over the scalar type, so Jacobians come from
//! forward-mode automatic differentiation) and its object-safe view [`DynSystem`].
//!
//! A model ẋ = f(x, u), y = h(x, u) implements two traits:
//! - [`SystemInfo`]: dimensions and names (plus, optionally, closed-form equilibria and a
//!   physical-validity test) — plain methods, object safe;
//! - [`NonlinearSystem`]: `f` and `h`, written once for any [`Scalar`] `D`. Evaluated with
//!   `D = f64` they simulate; evaluated with dual numbers `D = Dual64` they return the exact
//!   directional derivatives, one Jacobian column per evaluation (no finite differences, no
//!   step size, no truncation error).
//!
//! Every `NonlinearSystem` is automatically a [`DynSystem`] (blanket impl), which is what the
//! algorithms ([`crate::nonlinear::equilibria()`], [`crate::nonlinear::linearize()`],
//! [`crate::nonlinear::simulate()`]) and the model registry (`Box<dyn DynSystem>`) use.

use nalgebra::{DMatrix, DVector};
use num_dual::{Dual64, DualNum, HyperDual64};

use crate::error::{LtiError, Result, check_finite};

/// The scalar types a model is evaluated with: `f64`, and num-dual's dual numbers for exact
/// derivatives. Arithmetic with `f64` constants works on the right (`x * 2.0`, `x - 1.0`);
/// `D::from(2.0)` makes a constant; `sin`, `cos`, `exp`, `sqrt`, `powi`, … are methods.
pub trait Scalar: DualNum<Primitive = f64> + Copy {}

impl<T: DualNum<Primitive = f64> + Copy> Scalar for T {}

/// Dimensions, names and model knowledge that do not depend on the scalar type.
pub trait SystemInfo {
    /// Number of states n.
    fn nx(&self) -> usize;
    /// Number of inputs m (0 for an autonomous system).
    fn nu(&self) -> usize;
    /// Number of outputs p.
    fn ny(&self) -> usize;

    /// Model name (the registry name for built-in models).
    fn model_name(&self) -> String {
        "custom".into()
    }

    /// Parameter values in declaration order.
    fn params(&self) -> Vec<(String, f64)> {
        Vec::new()
    }

    /// State names (default x1, x2, …).
    fn state_names(&self) -> Vec<String> {
        (1..=self.nx()).map(|i| format!("x{i}")).collect()
    }

    /// Input names (default u1, u2, …).
    fn input_names(&self) -> Vec<String> {
        (1..=self.nu()).map(|i| format!("u{i}")).collect()
    }

    /// Output names (default y1, y2, …).
    fn output_names(&self) -> Vec<String> {
        (1..=self.ny()).map(|i| format!("y{i}")).collect()
    }

    /// The input at which equilibria are sought by default (zeros unless the model has an
    /// operating point, e.g. the MEMS voltage `v`).
    fn operating_input(&self) -> Vec<f64> {
        vec![0.0; self.nu()]
    }

    /// Every equilibrium for the constant input `u`, when the model knows them in closed form
    /// (`None`: search numerically). `u` has length [`SystemInfo::nu`].
    fn closed_form_equilibria(&self, _u: &[f64]) -> Option<Vec<Vec<f64>>> {
        None
    }

    /// Whether an equilibrium state is physically meaningful (e.g. a gap in (0, l0]); default
    /// true.
    fn is_physical(&self, _x: &[f64]) -> bool {
        true
    }

    /// Whether the model's equations hold at x (default true). A simulation started inside the
    /// domain stops where the trajectory leaves it (the MEMS plates touch at l = 0).
    fn in_domain(&self, _x: &[f64]) -> bool {
        true
    }

    /// What the domain's boundary is, in words ("the plates touch, l ≤ 0"), for the error
    /// when a simulation starts outside it where the equations are singular. Default `None`.
    fn domain_note(&self) -> Option<String> {
        None
    }

    /// The initial state `ltikit simulate` uses when none is given (default: zeros). The seed's
    /// where it gives one (Lorenz from [1, 0, 0], the rigid body from [0.6, −1, 2]).
    fn default_initial_state(&self) -> Vec<f64> {
        vec![0.0; self.nx()]
    }

    /// The simulation horizon (s) used when none is given (default 10 s).
    fn default_horizon(&self) -> f64 {
        10.0
    }

    /// Names of the quantities conserved along every solution with zero input (computed by
    /// [`NonlinearSystem::conserved`]); empty when there are none (the default) or when the
    /// parameters break them (damping). The **first** plays the energy in the
    /// energy–Casimir test ([`crate::nonlinear::energy_casimir()`]); the others (Casimirs,
    /// momenta) are the constraints it is extremised on.
    fn conserved_names(&self) -> Vec<String> {
        Vec::new()
    }

    /// A natural magnitude of each conserved quantity (e.g. the depth of a potential well),
    /// used as the reference of the relative drift when |Q(0)| is smaller (an energy whose
    /// zero is arbitrary can start at 0). Default: none (the reference is |Q(0)|).
    fn conserved_scales(&self) -> Vec<f64> {
        Vec::new()
    }

    /// A sentence about the equilibria that the list cannot say (a continuum of them, a
    /// family of which only representatives are listed); `None` by default.
    fn equilibria_note(&self) -> Option<String> {
        None
    }
}

/// A nonlinear model ẋ = f(x, u), y = h(x, u), generic over the scalar type.
///
/// Implement [`SystemInfo`] for the dimensions and this trait for `f` and `h`; the Jacobians,
/// equilibria, linearisation and simulation come for free.
///
/// ```
/// use ltikit::nonlinear::{NonlinearSystem, Scalar, SystemInfo, DynSystem};
/// /// A Duffing-type oscillator ẍ = −x − x³ + u, output x.
/// struct Duffing;
/// impl SystemInfo for Duffing {
///     fn nx(&self) -> usize { 2 }
///     fn nu(&self) -> usize { 1 }
///     fn ny(&self) -> usize { 1 }
/// }
/// impl NonlinearSystem for Duffing {
///     fn f<D: Scalar>(&self, x: &[D], u: &[D], dx: &mut [D]) {
///         dx[0] = x[1];
///         dx[1] = -x[0] - x[0].powi(3) + u[0];
///     }
///     fn h<D: Scalar>(&self, x: &[D], _u: &[D], y: &mut [D]) {
///         y[0] = x[0];
///     }
/// }
/// let (a, b) = Duffing.jacobian_f(&[2.0, 0.0], &[0.0]);
/// assert_eq!(a[(1, 0)], -1.0 - 3.0 * 4.0); // ∂(−x − x³)/∂x at x = 2, exact
/// assert_eq!(b[(1, 0)], 1.0);
/// ```
pub trait NonlinearSystem: SystemInfo {
    /// Writes ẋ = f(x, u) into `dx` (length [`SystemInfo::nx`]); `x` and `u` have lengths nx and nu.
    fn f<D: Scalar>(&self, x: &[D], u: &[D], dx: &mut [D]);
    /// Writes y = h(x, u) into `y` (length [`SystemInfo::ny`]).
    fn h<D: Scalar>(&self, x: &[D], u: &[D], y: &mut [D]);

    /// Writes the conserved quantities named by [`SystemInfo::conserved_names`] at x into `c`
    /// (same length). Generic like `f`, so their gradients and Hessians are exact (AD).
    /// Default: none.
    fn conserved<D: Scalar>(&self, _x: &[D], _c: &mut [D]) {}
}

/// The object-safe view of a model: `f64` evaluation and exact Jacobians.
///
/// Implemented for every [`NonlinearSystem`]; use `&dyn DynSystem` / `Box<dyn DynSystem>` to hand
/// models around by name. The slices must have the model's dimensions (the checked entry points
/// are [`derivative`], [`jacobians`] and the algorithms of this module).
pub trait DynSystem: SystemInfo {
    /// ẋ = f(x, u) in `dx`.
    fn eval_f(&self, x: &[f64], u: &[f64], dx: &mut [f64]);
    /// y = h(x, u) in `y`.
    fn eval_h(&self, x: &[f64], u: &[f64], y: &mut [f64]);
    /// (∂f/∂x, ∂f/∂u) at (x, u): the A (n × n) and B (n × m) of the linearisation.
    fn jacobian_f(&self, x: &[f64], u: &[f64]) -> (DMatrix<f64>, DMatrix<f64>);
    /// (∂h/∂x, ∂h/∂u) at (x, u): the C (p × n) and D (p × m) of the linearisation.
    fn jacobian_h(&self, x: &[f64], u: &[f64]) -> (DMatrix<f64>, DMatrix<f64>);
    /// The conserved quantities at x (length: [`SystemInfo::conserved_names`]).
    fn eval_conserved(&self, x: &[f64], c: &mut [f64]);
    /// Value, gradient and Hessian of every conserved quantity at x, exact (hyper-dual
    /// numbers: one evaluation per entry of the upper triangle).
    fn conserved_derivatives(&self, x: &[f64]) -> Vec<Derivatives2>;
}

/// Value, gradient and Hessian of a scalar function at a point.
#[derive(Debug, Clone, PartialEq)]
pub struct Derivatives2 {
    /// The value.
    pub value: f64,
    /// ∇q (length n).
    pub gradient: DVector<f64>,
    /// ∇²q (n × n, symmetric).
    pub hessian: DMatrix<f64>,
}

/// Second derivatives of the conserved quantities by hyper-dual numbers: seeding ε₁ on x_i and
/// ε₂ on x_j gives ∂²q/∂x_i∂x_j in the ε₁ε₂ part, exactly.
fn hyperdual_derivatives<S: NonlinearSystem + ?Sized>(sys: &S, x: &[f64]) -> Vec<Derivatives2> {
    let k = sys.conserved_names().len();
    let n = x.len();
    let zero = HyperDual64::new(0.0, 0.0, 0.0, 0.0);
    let mut xd: Vec<HyperDual64> = x
        .iter()
        .map(|&v| HyperDual64::new(v, 0.0, 0.0, 0.0))
        .collect();
    let mut out = vec![zero; k];
    let mut res: Vec<Derivatives2> = (0..k)
        .map(|_| Derivatives2 {
            value: 0.0,
            gradient: DVector::zeros(n),
            hessian: DMatrix::zeros(n, n),
        })
        .collect();
    if n == 0 {
        sys.conserved(&xd, &mut out);
        for (r, o) in res.iter_mut().zip(&out) {
            r.value = o.re;
        }
        return res;
    }
    for i in 0..n {
        for j in i..n {
            xd[i].eps1 = 1.0;
            xd[j].eps2 = 1.0;
            out.fill(zero);
            sys.conserved(&xd, &mut out);
            for (r, o) in res.iter_mut().zip(&out) {
                r.value = o.re;
                r.hessian[(i, j)] = o.eps1eps2;
                r.hessian[(j, i)] = o.eps1eps2;
                if i == j {
                    r.gradient[i] = o.eps1;
                }
            }
            xd[i].eps1 = 0.0;
            xd[j].eps2 = 0.0;
        }
    }
    res
}

/// Which map to differentiate.
#[derive(Clone, Copy)]
enum Map {
    F,
    H,
}

/// Jacobians of f or h by forward-mode AD: one evaluation with dual numbers per column, seeding
/// the derivative direction e_j of (x, u).
fn ad_jacobian<S: NonlinearSystem + ?Sized>(
    sys: &S,
    map: Map,
    x: &[f64],
    u: &[f64],
) -> (DMatrix<f64>, DMatrix<f64>) {
    let rows = match map {
        Map::F => sys.nx(),
        Map::H => sys.ny(),
    };
    let (n, m) = (x.len(), u.len());
    let mut xd: Vec<Dual64> = x.iter().map(|&v| Dual64::new(v, 0.0)).collect();
    let mut ud: Vec<Dual64> = u.iter().map(|&v| Dual64::new(v, 0.0)).collect();
    let mut out = vec![Dual64::new(0.0, 0.0); rows];
    let mut jx = DMatrix::zeros(rows, n);
    let mut ju = DMatrix::zeros(rows, m);
    let run = |xd: &[Dual64], ud: &[Dual64], out: &mut [Dual64]| {
        out.fill(Dual64::new(0.0, 0.0));
        match map {
            Map::F => sys.f(xd, ud, out),
            Map::H => sys.h(xd, ud, out),
        }
    };
    for j in 0..n {
        xd[j].eps = 1.0;
        run(&xd, &ud, &mut out);
        for (i, o) in out.iter().enumerate() {
            jx[(i, j)] = o.eps;
        }
        xd[j].eps = 0.0;
    }
    for j in 0..m {
        ud[j].eps = 1.0;
        run(&xd, &ud, &mut out);
        for (i, o) in out.iter().enumerate() {
            ju[(i, j)] = o.eps;
        }
        ud[j].eps = 0.0;
    }
    (jx, ju)
}

impl<T: NonlinearSystem + ?Sized> DynSystem for T {
    fn eval_f(&self, x: &[f64], u: &[f64], dx: &mut [f64]) {
        self.f(x, u, dx)
    }

    fn eval_h(&self, x: &[f64], u: &[f64], y: &mut [f64]) {
        self.h(x, u, y)
    }

    fn jacobian_f(&self, x: &[f64], u: &[f64]) -> (DMatrix<f64>, DMatrix<f64>) {
        ad_jacobian(self, Map::F, x, u)
    }

    fn jacobian_h(&self, x: &[f64], u: &[f64]) -> (DMatrix<f64>, DMatrix<f64>) {
        ad_jacobian(self, Map::H, x, u)
    }

    fn eval_conserved(&self, x: &[f64], c: &mut [f64]) {
        self.conserved(x, c)
    }

    fn conserved_derivatives(&self, x: &[f64]) -> Vec<Derivatives2> {
        hyperdual_derivatives(self, x)
    }
}

/// A model that can be shared between threads and handed out by name.
pub type BoxedSystem = Box<dyn DynSystem + Send + Sync>;

/// Checks that `x` and `u` have the model's dimensions and finite entries.
pub fn check_point(sys: &dyn DynSystem, x: &[f64], u: &[f64]) -> Result<()> {
    check_len("state", x.len(), sys.nx())?;
    check_len("input", u.len(), sys.nu())?;
    let names = sys.state_names();
    for (i, &v) in x.iter().enumerate() {
        check_finite(|| format!("state {}", name_or_index(&names, i)), v)?;
    }
    let names = sys.input_names();
    for (i, &v) in u.iter().enumerate() {
        check_finite(|| format!("input {}", name_or_index(&names, i)), v)?;
    }
    Ok(())
}

fn name_or_index(names: &[String], i: usize) -> String {
    names
        .get(i)
        .cloned()
        .unwrap_or_else(|| format!("{}", i + 1))
}

/// Error unless a vector has the expected length.
pub(crate) fn check_len(what: &str, got: usize, expected: usize) -> Result<()> {
    if got == expected {
        Ok(())
    } else {
        Err(LtiError::invalid(format!(
            "the {what} vector has {got} entries, the model needs {expected}"
        )))
    }
}

/// ẋ = f(x, u) with dimension and finiteness checks.
///
/// ```
/// use ltikit::nonlinear::{derivative, models::Pendulum};
/// let p = Pendulum::default();
/// let dx = derivative(&p, &[0.0, 1.0], &[0.0]).unwrap();
/// assert!((dx[1] + 1.5).abs() < 1e-15); // −3C/(ML²)·θ̇ with C = 0.5
/// assert!(derivative(&p, &[0.0], &[0.0]).is_err());
/// ```
pub fn derivative(sys: &dyn DynSystem, x: &[f64], u: &[f64]) -> Result<Vec<f64>> {
    check_point(sys, x, u)?;
    let mut dx = vec![0.0; sys.nx()];
    sys.eval_f(x, u, &mut dx);
    Ok(dx)
}

/// The conserved quantities of a model at x ([`SystemInfo::conserved_names`] order), with
/// dimension and finiteness checks.
///
/// ```
/// use ltikit::nonlinear::{conserved_quantities, models::RigidBody};
/// let body = RigidBody::new(3.0, 2.0, 1.0).unwrap();
/// let c = conserved_quantities(&body, &[0.6, -1.0, 2.0]).unwrap();
/// // E = ½(0.36/3 + 1/2 + 4/1) (seed eq. 2.51), |Π|² = 5.36 (eq. 2.53)
/// assert!((c[0] - 2.31).abs() < 1e-15 && (c[1] - 5.36).abs() < 1e-14);
/// ```
pub fn conserved_quantities(sys: &dyn DynSystem, x: &[f64]) -> Result<Vec<f64>> {
    check_point(sys, x, &vec![0.0; sys.nu()])?;
    let mut c = vec![0.0; sys.conserved_names().len()];
    sys.eval_conserved(x, &mut c);
    Ok(c)
}

/// The four Jacobians at a point.
#[derive(Debug, Clone, PartialEq)]
pub struct Jacobians {
    /// ∂f/∂x (n × n).
    pub a: DMatrix<f64>,
    /// ∂f/∂u (n × m).
    pub b: DMatrix<f64>,
    /// ∂h/∂x (p × n).
    pub c: DMatrix<f64>,
    /// ∂h/∂u (p × m).
    pub d: DMatrix<f64>,
}

/// A, B, C, D at (x, u) by automatic differentiation, with dimension and finiteness checks.
///
/// ```
/// use ltikit::nonlinear::{jacobians, models::Pendulum};
/// let p = Pendulum::default();
/// let j = jacobians(&p, &[std::f64::consts::PI, 0.0], &[0.0]).unwrap();
/// assert!((j.a[(1, 0)] - 1.5 * 9.81).abs() < 1e-12); // −(3g/2L)·cos π (seed eq. 2.18)
/// ```
pub fn jacobians(sys: &dyn DynSystem, x: &[f64], u: &[f64]) -> Result<Jacobians> {
    check_point(sys, x, u)?;
    let (a, b) = sys.jacobian_f(x, u);
    let (c, d) = sys.jacobian_h(x, u);
    for (m, name) in [(&a, "A"), (&b, "B"), (&c, "C"), (&d, "D")] {
        if let Some(v) = m.iter().find(|v| !v.is_finite()) {
            return Err(LtiError::NonFinite {
                what: format!("an entry of the Jacobian {name} at x = {x:?}"),
                value: *v,
            });
        }
    }
    Ok(Jacobians { a, b, c, d })
}
