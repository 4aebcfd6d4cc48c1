//! The free rigid body of seed §2.3.5.1 in body angular momentum (eqs. 2.44, 2.48–2.50):
//! Π̇ = Π × I⁻¹Π with I = diag(I1, I2, I3),
//!
//! Π̇₁ = (I2 − I3)/(I2 I3) Π₂Π₃,  Π̇₂ = (I3 − I1)/(I3 I1) Π₃Π₁,  Π̇₃ = (I1 − I2)/(I1 I2) Π₁Π₂;
//! x = Π, no input, y = Π.
//!
//! **Conserved** (seed eqs. 2.51, 2.53): the kinetic energy E = ½(Π₁²/I1 + Π₂²/I2 + Π₃²/I3)
//! and h = |Π|² (the Casimir). Solutions run on the intersections of the energy ellipsoids
//! with the momentum sphere (the polhodes, seed fig. 2.11); their closed form in Jacobi
//! elliptic functions is [`crate::nonlinear::rigid_motion`].
//!
//! **Relative equilibria** on the sphere |Π| = p (the parameter `Pi`): Π parallel to I⁻¹Π,
//! i.e. ±p e_k on the principal axes (steady rotation about axis k). Linearised at p e_k with
//! (i, j) the other two axes, A has the eigenvalues 0 and ±√λ² with
//!
//!   λ² = −(Ik − Ii)(Ik − Ij)/(Ii Ij) · (p/Ik)²
//!
//! (for k = 1 the only non-zero entries of A are A₂₃ = (I3 − I1)p/(I3 I1) and
//! A₃₂ = (I1 − I2)p/(I1 I2), and λ² = A₂₃A₃₂; the other axes cyclically)
//!
//! so the intermediate axis is a saddle (a real pair) and the largest and smallest are centres
//! (an imaginary pair: not hyperbolic, the linearisation cannot decide). The energy–Casimir
//! test decides them: E restricted to the sphere has a strict minimum on the largest axis
//! and a strict maximum on the smallest, so both are Lyapunov stable; on the intermediate axis
//! it is a saddle. For an axi-symmetric body (two equal moments) every point of the circle in
//! the plane of the equal axes is a relative equilibrium (not isolated: a perturbation makes
//! Π precess along the circle, so they are not Lyapunov stable; seed p. 79); for a symmetric
//! body every Π is one.
//!
//! **Bad input**: a moment ≤ 0 is refused (parameter check); so are moments that violate the
//! triangle inequality Ii + Ij ≥ Ik, which every real body satisfies (Ii + Ij − Ik =
//! 2∫x_k² dm ≥ 0; equality for a planar lamina) — refusing rather than warning because the
//! library cannot print and the CLI must not silently simulate an impossible body.

use num_complex::Complex64;

use crate::error::{LtiError, Result};
use crate::lti::params::{Constraint, ModelParam, check_values, named, param};
use crate::nonlinear::system::{NonlinearSystem, Scalar, SystemInfo};

/// Parameters of `rigid-body`: I1, I2, I3 (seed fig. 2.12: diag(3, 2, 1)) and `Pi`, the
/// magnitude |Π| of the sphere on which the relative equilibria are reported.
pub const RIGID_BODY_PARAMS: &[ModelParam] = &[
    param(
        "I1",
        3.0,
        "kg·m²",
        "principal moment of inertia I1",
        Constraint::Positive,
    ),
    param(
        "I2",
        2.0,
        "kg·m²",
        "principal moment of inertia I2",
        Constraint::Positive,
    ),
    param(
        "I3",
        1.0,
        "kg·m²",
        "principal moment of inertia I3",
        Constraint::Positive,
    ),
    param(
        "Pi",
        1.0,
        "kg·m²/s",
        "angular momentum |Π| of the sphere on which relative equilibria are sought",
        Constraint::Positive,
    ),
];

/// Checks positive principal moments and the triangle inequalities Ii + Ij ≥ Ik (with a
/// relative slack of 1e-12 so that a lamina, Ii + Ij = Ik, passes after rounding).
///
/// ```
/// use ltikit::nonlinear::models::rigid_body::check_inertias;
/// assert!(check_inertias(&[3.0, 2.0, 1.0]).is_ok());
/// assert!(check_inertias(&[1.0, 1.0, 2.0]).is_ok()); // a thin disc about its axis
/// let e = check_inertias(&[1.0, 1.0, 3.0]).unwrap_err().to_string();
/// assert!(e.contains("triangle inequality"), "{e}");
/// ```
pub fn check_inertias(i: &[f64]) -> Result<()> {
    let names = ["I1", "I2", "I3"];
    for (k, (&v, name)) in i.iter().zip(names).enumerate() {
        if !(v.is_finite() && v > 0.0) {
            return Err(LtiError::InvalidParameter {
                name: name.into(),
                value: v,
                reason: format!("principal moment of inertia {} must be > 0", k + 1),
            });
        }
    }
    if i.len() != 3 {
        return Err(LtiError::invalid(format!(
            "three principal moments are needed, got {}",
            i.len()
        )));
    }
    for k in 0..3 {
        let (a, b) = ((k + 1) % 3, (k + 2) % 3);
        if i[a] + i[b] < i[k] * (1.0 - 1e-12) {
            return Err(LtiError::InvalidParameter {
                name: names[k].into(),
                value: i[k],
                reason: format!(
                    "the principal moments I1 = {}, I2 = {}, I3 = {} violate the triangle \
                     inequality {} + {} ≥ {} that every real body satisfies",
                    i[0], i[1], i[2], names[a], names[b], names[k]
                ),
            });
        }
    }
    Ok(())
}

/// The free rigid body (seed eq. 2.44).
///
/// ```
/// use ltikit::nonlinear::{models::RigidBody, SystemInfo};
/// let b = RigidBody::new(3.0, 2.0, 1.0).unwrap();
/// assert_eq!(b.closed_form_equilibria(&[]).unwrap().len(), 6); // ±|Π| on each axis
/// assert!(RigidBody::new(1.0, 1.0, 3.0).is_err());            // I1 + I2 < I3
/// assert!(RigidBody::new(0.0, 1.0, 1.0).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBody {
    /// Principal moments of inertia [I1, I2, I3].
    pub inertia: [f64; 3],
    /// |Π| of the sphere of relative equilibria.
    pub momentum: f64,
}

impl Default for RigidBody {
    fn default() -> Self {
        RigidBody {
            inertia: [3.0, 2.0, 1.0],
            momentum: 1.0,
        }
    }
}

/// How a principal axis ranks among the three moments.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisKind {
    /// The largest moment (strict): a centre, E minimal on the sphere.
    Largest,
    /// Strictly between the others: a saddle.
    Intermediate,
    /// The smallest moment (strict): a centre, E maximal on the sphere.
    Smallest,
    /// Equal to exactly one other moment: part of a circle of relative equilibria.
    Circle,
    /// All three moments equal: every Π is an equilibrium.
    Symmetric,
}

impl RigidBody {
    /// Validated constructor (moments > 0, triangle inequality), |Π| = 1 for the equilibria.
    pub fn new(i1: f64, i2: f64, i3: f64) -> Result<Self> {
        Self::from_values(&[i1, i2, i3, 1.0])
    }

    /// From values in the order of [`RIGID_BODY_PARAMS`].
    pub fn from_values(v: &[f64]) -> Result<Self> {
        check_values(RIGID_BODY_PARAMS, v)?;
        check_inertias(&v[..3])?;
        Ok(RigidBody {
            inertia: [v[0], v[1], v[2]],
            momentum: v[3],
        })
    }

    /// The same body with relative equilibria on the sphere |Π| = `p` (> 0: a sphere of zero
    /// radius has no relative equilibria to speak of).
    pub fn with_momentum(&self, p: f64) -> Result<Self> {
        Self::from_values(&[self.inertia[0], self.inertia[1], self.inertia[2], p])
    }

    /// Kinetic energy E = ½ Σ Πᵢ²/Iᵢ (seed eq. 2.51).
    pub fn energy(&self, pi: &[f64; 3]) -> f64 {
        0.5 * (0..3).map(|i| pi[i] * pi[i] / self.inertia[i]).sum::<f64>()
    }

    /// How axis `k` (0, 1, 2) ranks (exact comparisons of the given moments).
    pub fn axis_kind(&self, k: usize) -> AxisKind {
        let i = self.inertia;
        let (a, b) = (i[(k + 1) % 3], i[(k + 2) % 3]);
        let ik = i[k];
        let eq = |x: f64, y: f64| (x - y).abs() <= 1e-14 * x.max(y);
        if eq(ik, a) && eq(ik, b) {
            AxisKind::Symmetric
        } else if eq(ik, a) || eq(ik, b) {
            AxisKind::Circle
        } else if ik > a && ik > b {
            AxisKind::Largest
        } else if ik < a && ik < b {
            AxisKind::Smallest
        } else {
            AxisKind::Intermediate
        }
    }

    /// The closed-form eigenvalues of the linearisation at the relative equilibrium Π = p e_k
    /// (either sign of p gives the same): 0 and ±√λ², λ² = −(Ik − Ii)(Ik − Ij)/(Ii Ij)·(p/Ik)²
    /// (module docs), ordered [+, 0, −] by real part then imaginary part.
    ///
    /// ```
    /// use ltikit::nonlinear::models::RigidBody;
    /// let b = RigidBody::new(3.0, 2.0, 1.0).unwrap();
    /// let e = b.axis_eigenvalues(1, 1.0); // intermediate: ±√((2−3)(1−2)... real pair
    /// assert!((e[0].re - (1.0f64 / 3.0).sqrt() / 2.0 * 1.0).abs() < 1e-15);
    /// let e = b.axis_eigenvalues(0, 1.0); // largest: a centre
    /// assert!(e[0].re == 0.0 && e[0].im > 0.0);
    /// ```
    pub fn axis_eigenvalues(&self, k: usize, p: f64) -> [Complex64; 3] {
        let i = self.inertia;
        let k = k % 3;
        let (ia, ib) = (i[(k + 1) % 3], i[(k + 2) % 3]);
        let ik = i[k];
        let lambda2 = -(ik - ia) * (ik - ib) / (ia * ib) * (p / ik).powi(2);
        let z = Complex64::new(0.0, 0.0);
        if lambda2 >= 0.0 {
            let r = lambda2.sqrt();
            [Complex64::new(r, 0.0), z, Complex64::new(-r, 0.0)]
        } else {
            let w = (-lambda2).sqrt();
            [Complex64::new(0.0, w), z, Complex64::new(0.0, -w)]
        }
    }

    /// The eigenvalues, ascending, of the Hessian of the energy–Casimir function
    /// E − |Π|²/(2 Ik) at the relative equilibrium ±p eₖ restricted to the tangent plane of
    /// the momentum sphere: 1/Ii − 1/Ik over the other two axes i, independent of p (the
    /// multiplier −1/Ik makes the gradient vanish there; the Hessian of E is diag(1/Iᵢ)). Both
    /// positive on the largest axis (a strict minimum), both negative on the smallest (a
    /// maximum), of opposite signs on the intermediate one (a saddle).
    ///
    /// ```
    /// use ltikit::nonlinear::models::RigidBody;
    /// let b = RigidBody::new(3.0, 2.0, 1.0).unwrap();
    /// let h = b.energy_casimir_hessian(0); // largest moment: 1/2 − 1/3, 1 − 1/3
    /// assert!((h[0] - 1.0 / 6.0).abs() < 1e-15 && (h[1] - 2.0 / 3.0).abs() < 1e-15);
    /// assert!(b.energy_casimir_hessian(1)[0] < 0.0 && b.energy_casimir_hessian(1)[1] > 0.0);
    /// ```
    pub fn energy_casimir_hessian(&self, k: usize) -> [f64; 2] {
        let i = self.inertia;
        let k = k % 3;
        let a = 1.0 / i[(k + 1) % 3] - 1.0 / i[k];
        let b = 1.0 / i[(k + 2) % 3] - 1.0 / i[k];
        [a.min(b), a.max(b)]
    }

    /// Where the separatrices cross the plane of the largest and the smallest axis: on them
    /// E = p²/(2 I_b) (b the intermediate axis), so with Π_b = 0
    /// Π_a²(1/I_a − 1/I_b) + Π_c²(1/I_c − 1/I_b) = 0, i.e. Π_c/Π_a = ±√((I_a − I_b) I_c /
    /// ((I_b − I_c) I_a)) for a the largest and c the smallest axis. Returns (a, c, that
    /// slope); `None` when two moments are equal (no isolated intermediate axis).
    ///
    /// ```
    /// use ltikit::nonlinear::models::RigidBody;
    /// let (a, c, slope) = RigidBody::new(3.0, 2.0, 1.0).unwrap().separatrix_slope().unwrap();
    /// assert_eq!((a, c), (0, 2));
    /// // √((3 − 2)·1/((2 − 1)·3)) = 1/√3: they cross 30° from the Π₁ axis
    /// assert!((slope - (1.0f64 / 3.0).sqrt()).abs() < 1e-15);
    /// ```
    pub fn separatrix_slope(&self) -> Option<(usize, usize, f64)> {
        let i = self.inertia;
        let a = (0..3).find(|&k| self.axis_kind(k) == AxisKind::Largest)?;
        let c = (0..3).find(|&k| self.axis_kind(k) == AxisKind::Smallest)?;
        let b = 3 - a - c;
        Some((a, c, ((i[a] - i[b]) * i[c] / ((i[b] - i[c]) * i[a])).sqrt()))
    }
}

impl SystemInfo for RigidBody {
    fn nx(&self) -> usize {
        3
    }
    fn nu(&self) -> usize {
        0
    }
    fn ny(&self) -> usize {
        3
    }
    fn model_name(&self) -> String {
        "rigid-body".into()
    }
    fn params(&self) -> Vec<(String, f64)> {
        let i = self.inertia;
        named(RIGID_BODY_PARAMS, &[i[0], i[1], i[2], self.momentum])
    }
    fn state_names(&self) -> Vec<String> {
        vec!["Pi1".into(), "Pi2".into(), "Pi3".into()]
    }
    fn output_names(&self) -> Vec<String> {
        self.state_names()
    }

    /// ±p e_k on each principal axis (k = 1, 2, 3), p = `Pi`.
    fn closed_form_equilibria(&self, _u: &[f64]) -> Option<Vec<Vec<f64>>> {
        let p = self.momentum;
        let mut out = Vec::with_capacity(6);
        for k in 0..3 {
            for s in [1.0, -1.0] {
                let mut x = vec![0.0; 3];
                x[k] = s * p;
                out.push(x);
            }
        }
        Some(out)
    }

    fn default_initial_state(&self) -> Vec<f64> {
        vec![0.6, -1.0, 2.0] // seed fig. 2.12 (a)
    }

    fn default_horizon(&self) -> f64 {
        30.0
    }

    fn conserved_names(&self) -> Vec<String> {
        vec!["E".into(), "|Pi|^2".into()]
    }

    fn equilibria_note(&self) -> Option<String> {
        let kinds: Vec<AxisKind> = (0..3).map(|k| self.axis_kind(k)).collect();
        if kinds.contains(&AxisKind::Symmetric) {
            return Some(
                "symmetric body (I1 = I2 = I3): every Π is an equilibrium; the six axis points \
                 are listed"
                    .into(),
            );
        }
        let circle: Vec<usize> = (0..3).filter(|&k| kinds[k] == AxisKind::Circle).collect();
        if circle.len() == 2 {
            return Some(format!(
                "axi-symmetric body (I{} = I{}): every point of the circle Π{} = 0 on the sphere \
                 is a relative equilibrium (the axis points listed represent it); they are not \
                 isolated and not Lyapunov stable: a perturbation of Π{} makes Π precess along \
                 the circle",
                circle[0] + 1,
                circle[1] + 1,
                3 - circle[0] - circle[1] + 1,
                3 - circle[0] - circle[1] + 1
            ));
        }
        Some(format!(
            "relative equilibria on the sphere |Π| = {} (steady rotation about a principal axis)",
            self.momentum
        ))
    }
}

impl NonlinearSystem for RigidBody {
    fn f<D: Scalar>(&self, x: &[D], _u: &[D], dx: &mut [D]) {
        let [i1, i2, i3] = self.inertia;
        dx[0] = x[1] * x[2] * ((i2 - i3) / (i2 * i3));
        dx[1] = x[2] * x[0] * ((i3 - i1) / (i3 * i1));
        dx[2] = x[0] * x[1] * ((i1 - i2) / (i1 * i2));
    }
    fn h<D: Scalar>(&self, x: &[D], _u: &[D], y: &mut [D]) {
        y.copy_from_slice(&x[..3]);
    }
    fn conserved<D: Scalar>(&self, x: &[D], c: &mut [D]) {
        let [i1, i2, i3] = self.inertia;
        c[0] = (x[0] * x[0] / i1 + x[1] * x[1] / i2 + x[2] * x[2] / i3) * 0.5;
        c[1] = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    }
}
