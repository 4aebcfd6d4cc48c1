//! The electrostatic MEMS mirror of seed exercises 1.4 and 2.11: a plate of mass m on a spring
//! k (rest gap l0) with damping b, a parallel-plate capacitor C(l) = εA/l charged through a
//! resistor R from the voltage v.
//!
//! m l̈ = −k (l − l0) − b l̇ − q²/(2εA),  R q̇ = v − q l/(εA);  x = [l, l̇, q], u = \[v\], y = l.
//!
//! **Equilibria** (q̇ = 0: q = εA v/l; l̈ = 0): l²(l0 − l) = εA v²/(2k), a cubic solved with
//! [`Poly::roots`]. Below the pull-in voltage v_pi = √(8 k l0³/(27 εA)) it has three real roots:
//! one negative (non-physical) and two in (0, l0) — the larger stable, the smaller unstable;
//! they merge at l = 2 l0/3 when |v| = v_pi (a saddle-node), and above it only the negative
//! root is left. For v = 0 the double root l = 0 carries the charged, touching states
//! q = ±√(2εA k l0), which are reported too (non-physical: `physical` is 0 < l ≤ l0).
//!
//! The equations hold while the plates are apart: a simulation stops at contact, l = 0
//! ([`SystemInfo::in_domain`]); beyond it the model would blow up (q grows like e^{|l|t/(RεA)}).

use crate::error::Result;
use crate::lti::params::{Constraint, ModelParam, check_values, named, param};
use crate::nonlinear::system::{NonlinearSystem, Scalar, SystemInfo};
use crate::poly::Poly;

/// Parameters of `mems`: eps, A, m, k, l0, b, R, v (exercise 2.11 values, R = 1, v = 1.5).
pub const MEMS_PARAMS: &[ModelParam] = &[
    param("eps", 1.0, "F/m", "permittivity", Constraint::Positive),
    param("A", 1.0, "m²", "plate area", Constraint::Positive),
    param("m", 1.0, "kg", "plate mass", Constraint::Positive),
    param("k", 1.0, "N/m", "spring stiffness", Constraint::Positive),
    param("l0", 3.0, "m", "rest gap", Constraint::Positive),
    param("b", 0.02, "N·s/m", "damping", Constraint::NonNegative),
    param("R", 1.0, "Ω", "series resistance", Constraint::Positive),
    param("v", 1.5, "V", "operating voltage", Constraint::Any),
];

/// The MEMS mirror model.
///
/// ```
/// use ltikit::nonlinear::{models::Mems, SystemInfo};
/// let m = Mems::default();
/// assert!((m.pull_in_voltage() - 8f64.sqrt()).abs() < 1e-15); // √(8·1·27/27)
/// let eq = m.closed_form_equilibria(&[1.5]).unwrap();
/// assert_eq!(eq.len(), 3);
/// assert_eq!(eq.iter().filter(|x| m.is_physical(x)).count(), 2);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mems {
    /// Permittivity ε.
    pub eps: f64,
    /// Plate area A.
    pub area: f64,
    /// Mass m.
    pub m: f64,
    /// Stiffness k.
    pub k: f64,
    /// Rest gap l0.
    pub l0: f64,
    /// Damping b.
    pub b: f64,
    /// Resistance R.
    pub r: f64,
    /// Operating voltage v.
    pub v: f64,
}

impl Default for Mems {
    fn default() -> Self {
        Mems {
            eps: 1.0,
            area: 1.0,
            m: 1.0,
            k: 1.0,
            l0: 3.0,
            b: 0.02,
            r: 1.0,
            v: 1.5,
        }
    }
}

impl Mems {
    /// From values in the order of [`MEMS_PARAMS`].
    pub fn from_values(v: &[f64]) -> Result<Self> {
        check_values(MEMS_PARAMS, v)?;
        Ok(Mems {
            eps: v[0],
            area: v[1],
            m: v[2],
            k: v[3],
            l0: v[4],
            b: v[5],
            r: v[6],
            v: v[7],
        })
    }

    /// The same device at another operating voltage.
    pub fn with_voltage(&self, v: f64) -> Result<Self> {
        let mut vals = self.values();
        vals[7] = v;
        Self::from_values(&vals)
    }

    fn values(&self) -> Vec<f64> {
        vec![
            self.eps, self.area, self.m, self.k, self.l0, self.b, self.r, self.v,
        ]
    }

    /// εA.
    pub fn ea(&self) -> f64 {
        self.eps * self.area
    }

    /// The pull-in voltage √(8 k l0³/(27 εA)).
    pub fn pull_in_voltage(&self) -> f64 {
        (8.0 * self.k * self.l0.powi(3) / (27.0 * self.ea())).sqrt()
    }

    /// The gap at pull-in, 2 l0/3.
    pub fn pull_in_gap(&self) -> f64 {
        2.0 * self.l0 / 3.0
    }

    /// The equilibrium cubic l³ − l0 l² + εA v²/(2k) (descending).
    pub fn equilibrium_cubic(&self, v: f64) -> Result<Poly> {
        Poly::from_descending(&[1.0, -self.l0, 0.0, self.ea() * v * v / (2.0 * self.k)])
    }

    /// Real roots l of the equilibrium cubic (distinct, decreasing), from [`Poly::roots`].
    pub fn equilibrium_gaps(&self, v: f64) -> Result<Vec<f64>> {
        let roots = self.equilibrium_cubic(v)?.roots()?;
        Ok(roots
            .iter()
            .filter(|r| r.is_real())
            .map(|r| r.value.re)
            .collect())
    }
}

impl SystemInfo for Mems {
    fn nx(&self) -> usize {
        3
    }
    fn nu(&self) -> usize {
        1
    }
    fn ny(&self) -> usize {
        1
    }
    fn model_name(&self) -> String {
        "mems".into()
    }
    fn params(&self) -> Vec<(String, f64)> {
        named(MEMS_PARAMS, &self.values())
    }
    fn state_names(&self) -> Vec<String> {
        vec!["l".into(), "l_dot".into(), "q".into()]
    }
    fn input_names(&self) -> Vec<String> {
        vec!["v".into()]
    }
    fn output_names(&self) -> Vec<String> {
        vec!["l".into()]
    }
    fn operating_input(&self) -> Vec<f64> {
        vec![self.v]
    }

    // Exact zero roots are deflated exactly by `Poly::roots`, so `l == 0.0` is meant.
    #[allow(clippy::float_cmp)]
    fn closed_form_equilibria(&self, u: &[f64]) -> Option<Vec<Vec<f64>>> {
        let v = u.first().copied().unwrap_or(self.v);
        let gaps = self.equilibrium_gaps(v).ok()?;
        let ea = self.ea();
        let mut out = Vec::new();
        for l in gaps {
            if l == 0.0 {
                // Only for v = 0 (exact zero roots are deflated exactly): touching plates
                // held by the charge whose attraction balances the spring.
                let q = (2.0 * ea * self.k * self.l0).sqrt();
                out.push(vec![0.0, 0.0, q]);
                out.push(vec![0.0, 0.0, -q]);
            } else {
                out.push(vec![l, 0.0, ea * v / l]);
            }
        }
        Some(out)
    }

    fn is_physical(&self, x: &[f64]) -> bool {
        x[0] > 0.0 && x[0] <= self.l0
    }

    /// The model holds while the plates are apart, l > 0 (a simulation stops at contact).
    fn in_domain(&self, x: &[f64]) -> bool {
        x[0] > 0.0
    }

    fn domain_note(&self) -> Option<String> {
        Some("the plates touch: l ≤ 0".into())
    }

    /// At rest at the rest gap, uncharged: l = l0, l̇ = 0, q = 0 (exercise 2.11).
    fn default_initial_state(&self) -> Vec<f64> {
        vec![self.l0, 0.0, 0.0]
    }

    fn default_horizon(&self) -> f64 {
        60.0
    }
}

impl NonlinearSystem for Mems {
    fn f<D: Scalar>(&self, x: &[D], u: &[D], dx: &mut [D]) {
        let ea = self.ea();
        dx[0] = x[1];
        dx[1] = (-((x[0] - self.l0) * self.k) - x[1] * self.b - x[2] * x[2] / (2.0 * ea)) / self.m;
        dx[2] = (u[0] - x[2] * x[0] / ea) / self.r;
    }
    fn h<D: Scalar>(&self, x: &[D], _u: &[D], y: &mut [D]) {
        y[0] = x[0];
    }
}
