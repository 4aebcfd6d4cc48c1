//! The axi-symmetric heavy top of seed §1.5.5 (eqs. 1.101–1.102, 2.63–2.67): a body with
//! I1 = I2 about a fixed pivot on its symmetry axis, the centre of mass at distance l along
//! the body axis χ = e₃.
//!
//! Γ̇ = Γ × Ω,  I Ω̇ = IΩ × Ω + m g l Γ × χ;  x = [Γ, Ω] (6 states), no input, y = Γ.
//!
//! Γ is the upward vertical seen in the body frame (so that the potential energy is
//! m g l Γ·χ = m g l Γ₃, seed eq. 2.65, and the gravity torque about the pivot is
//! (l χ) × (−m g Γ) = m g l Γ × χ). In components, with I = diag(I1, I1, I3):
//! I1 Ω̇₁ = (I1 − I3) Ω₂Ω₃ + m g l Γ₂,  I1 Ω̇₂ = (I3 − I1) Ω₃Ω₁ − m g l Γ₁,  I3 Ω̇₃ = 0.
//!
//! **Conserved** (seed eqs. 2.65–2.67, and Π₃ for the axi-symmetric top): the energy
//! E = ½ Ω·IΩ + m g l Γ₃, the Casimirs Π·Γ and |Γ|² (= 1 for a physical state), and
//! Π₃ = I3 Ω₃.
//!
//! **Sleeping top** (spinning upright): Γ = e₃, Ω = ω₃ e₃ (the parameter `w3`), an
//! equilibrium for every ω₃; the **hanging top** Γ = −e₃ likewise. Linearised at the sleeping
//! top, the transverse motion (γ = γ₁ + iγ₂, o = o₁ + io₂ ∝ e^{st}) satisfies
//! (I1 s + i(I1 − I3)ω₃)(s + iω₃) = m g l, so s = iσ with
//!
//!   I1 σ² + (2 I1 − I3) ω₃ σ + (I1 − I3) ω₃² + m g l = 0,
//!   σ = (−(2I1 − I3)ω₃ ± √(I3²ω₃² − 4 I1 m g l)) / (2 I1),
//!
//! plus two zero eigenvalues (Γ₃, Ω₃). The discriminant gives the classical threshold: for
//! I3²ω₃² > 4 I1 m g l all eigenvalues are on the imaginary axis (a "fast top", spectrally
//! stable and, by the energy–Casimir test, Lyapunov stable); below it a pair has real part
//! ±√(4 I1 m g l − I3²ω₃²)/(2 I1) (unstable). The hanging top has m g l → −m g l: always
//! on the axis.

use num_complex::Complex64;

use crate::error::{LtiError, Result};
use crate::lti::params::{Constraint, ModelParam, check_values, named, param};
use crate::nonlinear::energy_casimir::energy_casimir;
use crate::nonlinear::equilibria::{Equilibrium, EquilibriumMethod};
use crate::nonlinear::linearize::{LocalStability, analyze_equilibrium};
use crate::nonlinear::system::{NonlinearSystem, Scalar, SystemInfo};

/// Parameters of `heavy-top`: I1 (= I2), I3, m, g, l and the spin w3 of the sleeping top.
pub const HEAVY_TOP_PARAMS: &[ModelParam] = &[
    param(
        "I1",
        1.0,
        "kg·m²",
        "transverse moment of inertia I1 = I2 about the pivot",
        Constraint::Positive,
    ),
    param(
        "I3",
        0.5,
        "kg·m²",
        "moment of inertia I3 about the symmetry axis",
        Constraint::Positive,
    ),
    param("m", 1.0, "kg", "mass", Constraint::Positive),
    param(
        "g",
        9.81,
        "m/s²",
        "gravitational acceleration",
        Constraint::NonNegative,
    ),
    param(
        "l",
        0.5,
        "m",
        "distance from the pivot to the centre of mass",
        Constraint::Positive,
    ),
    param(
        "w3",
        12.0,
        "rad/s",
        "spin ω3 of the sleeping top",
        Constraint::Any,
    ),
];

/// The axi-symmetric heavy top.
///
/// ```
/// use ltikit::nonlinear::{models::HeavyTop, SystemInfo};
/// let top = HeavyTop::default();
/// // I3²ω3² = 4 I1 m g l at ω3 = √(4·1·1·9.81·0.5)/0.5
/// assert!((top.threshold_spin() - 19.62f64.sqrt() / 0.5).abs() < 1e-14);
/// assert_eq!(top.closed_form_equilibria(&[]).unwrap().len(), 2);
/// assert!(HeavyTop::from_values(&[1.0, 2.5, 1.0, 9.81, 0.5, 12.0]).is_err()); // I3 > 2 I1
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeavyTop {
    /// I1 = I2.
    pub i1: f64,
    /// I3.
    pub i3: f64,
    /// Mass m.
    pub m: f64,
    /// Gravity g.
    pub g: f64,
    /// Pivot to centre of mass l.
    pub l: f64,
    /// Spin ω₃ of the sleeping top.
    pub w3: f64,
}

impl Default for HeavyTop {
    fn default() -> Self {
        HeavyTop {
            i1: 1.0,
            i3: 0.5,
            m: 1.0,
            g: 9.81,
            l: 0.5,
            w3: 12.0,
        }
    }
}

impl HeavyTop {
    /// From values in the order of [`HEAVY_TOP_PARAMS`]; the moments must satisfy the
    /// triangle inequality I3 ≤ 2 I1.
    pub fn from_values(v: &[f64]) -> Result<Self> {
        check_values(HEAVY_TOP_PARAMS, v)?;
        super::rigid_body::check_inertias(&[v[0], v[0], v[1]])?;
        Ok(HeavyTop {
            i1: v[0],
            i3: v[1],
            m: v[2],
            g: v[3],
            l: v[4],
            w3: v[5],
        })
    }

    fn values(&self) -> [f64; 6] {
        [self.i1, self.i3, self.m, self.g, self.l, self.w3]
    }

    /// The same top with another sleeping spin ω₃.
    pub fn with_spin(&self, w3: f64) -> Result<Self> {
        let mut v = self.values();
        v[5] = w3;
        Self::from_values(&v)
    }

    /// m g l.
    pub fn mgl(&self) -> f64 {
        self.m * self.g * self.l
    }

    /// The classical threshold spin √(4 I1 m g l)/I3 above which the sleeping top is stable.
    pub fn threshold_spin(&self) -> f64 {
        (4.0 * self.i1 * self.mgl()).sqrt() / self.i3
    }

    /// The sleeping top state [Γ, Ω] = [0, 0, 1, 0, 0, ω₃].
    pub fn sleeping(&self) -> [f64; 6] {
        [0.0, 0.0, 1.0, 0.0, 0.0, self.w3]
    }

    /// The closed-form eigenvalues at the sleeping top (upright = true) or the hanging top:
    /// ±iσ₁, ±iσ₂ and 0, 0 as in the module docs, where a complex σ gives a real part.
    /// Sorted by decreasing real part, then imaginary part.
    pub fn eigenvalues_closed_form(&self, upright: bool) -> Vec<Complex64> {
        let w = self.w3;
        let mgl = if upright { self.mgl() } else { -self.mgl() };
        // I1 σ² + (2I1 − I3) w σ + (I1 − I3) w² + mgl = 0, s = iσ.
        let b = (2.0 * self.i1 - self.i3) * w;
        let disc = self.i3 * self.i3 * w * w - 4.0 * self.i1 * mgl;
        let sq = Complex64::new(disc, 0.0).sqrt();
        let mut out = Vec::with_capacity(6);
        for sign in [1.0, -1.0] {
            let sigma = (Complex64::new(-b, 0.0) + sq * sign) / (2.0 * self.i1);
            let s = Complex64::new(0.0, 1.0) * sigma;
            out.push(s);
            out.push(s.conj());
        }
        out.push(Complex64::new(0.0, 0.0));
        out.push(Complex64::new(0.0, 0.0));
        out.sort_by(|p, q| q.re.total_cmp(&p.re).then(q.im.total_cmp(&p.im)));
        out
    }
}

/// The spin above which the sleeping top is no longer unstable, found **from the
/// eigenvalues**: bisection on ω₃ ≥ 0 of the local stability of the linearisation at the
/// sleeping top (unstable ↔ an eigenvalue in the right half plane), to relative width 4 eps.
/// Compare with [`HeavyTop::threshold_spin`].
///
/// ```
/// use ltikit::nonlinear::models::{HeavyTop, heavy_top::threshold_from_eigenvalues};
/// let top = HeavyTop::default();
/// let w = threshold_from_eigenvalues(&top).unwrap();
/// assert!((w - top.threshold_spin()).abs() < 1e-9 * w);
/// ```
pub fn threshold_from_eigenvalues(top: &HeavyTop) -> Result<f64> {
    let unstable = |w: f64| -> Result<bool> {
        let t = top.with_spin(w)?;
        let x = t.sleeping().to_vec();
        let eq = Equilibrium {
            residual: 0.0,
            physical: true,
            u: Vec::new(),
            x,
            method: EquilibriumMethod::ClosedForm,
        };
        Ok(analyze_equilibrium(&t, &eq)?.stability == LocalStability::Unstable)
    };
    if top.mgl() == 0.0 || !unstable(0.0)? {
        return Err(LtiError::Undefined {
            what: "the stability threshold of the sleeping top".into(),
            reason: "the top is not unstable without spin (no gravity torque)".into(),
        });
    }
    // Bracket: double the spin (from the natural scale √(m g l I1)/I3) until stable.
    let mut lo = 0.0;
    let mut hi = (top.mgl() * top.i1).sqrt() / top.i3;
    let mut tries = 0;
    while unstable(hi)? {
        lo = hi;
        hi *= 2.0;
        tries += 1;
        if tries > 200 {
            return Err(LtiError::NoConvergence {
                what: "bracketing the sleeping-top threshold".into(),
                iterations: tries,
            });
        }
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if hi - lo <= 4.0 * f64::EPSILON * hi || mid <= lo || mid >= hi {
            break;
        }
        if unstable(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// The spin above which the energy–Casimir test proves the sleeping top Lyapunov stable
/// (bisection on its verdict between 0 and the first doubling of √(m g l I1)/I3 that is
/// stable), to relative width 1e-12. Holm, Marsden, Ratiu & Weinstein (1985, §5) show it is the
/// classical I3²ω₃² = 4 I1 m g l; the test's definiteness tolerance (1e-9 of the Hessian's
/// scale) moves it by ~1e-9 relative.
///
/// ```
/// use ltikit::nonlinear::models::{HeavyTop, heavy_top::threshold_from_energy_casimir};
/// let top = HeavyTop::default();
/// let w = threshold_from_energy_casimir(&top).unwrap();
/// assert!((w - top.threshold_spin()).abs() < 1e-6 * w);
/// ```
pub fn threshold_from_energy_casimir(top: &HeavyTop) -> Result<f64> {
    let stable = |w: f64| -> Result<bool> {
        let t = top.with_spin(w)?;
        Ok(energy_casimir(&t, &t.sleeping())?.is_some_and(|e| e.lyapunov_stable))
    };
    if top.mgl() == 0.0 || stable(0.0)? {
        return Err(LtiError::Undefined {
            what: "the energy–Casimir threshold of the sleeping top".into(),
            reason: "the top is stable without spin (no gravity torque)".into(),
        });
    }
    let mut lo = 0.0;
    let mut hi = (top.mgl() * top.i1).sqrt() / top.i3;
    let mut tries = 0;
    while !stable(hi)? {
        lo = hi;
        hi *= 2.0;
        tries += 1;
        if tries > 200 {
            return Err(LtiError::NoConvergence {
                what: "bracketing the energy–Casimir threshold".into(),
                iterations: tries,
            });
        }
    }
    while hi - lo > 1e-12 * hi {
        let mid = 0.5 * (lo + hi);
        if stable(mid)? {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

impl SystemInfo for HeavyTop {
    fn nx(&self) -> usize {
        6
    }
    fn nu(&self) -> usize {
        0
    }
    fn ny(&self) -> usize {
        3
    }
    fn model_name(&self) -> String {
        "heavy-top".into()
    }
    fn params(&self) -> Vec<(String, f64)> {
        named(HEAVY_TOP_PARAMS, &self.values())
    }
    fn state_names(&self) -> Vec<String> {
        ["Gamma1", "Gamma2", "Gamma3", "Omega1", "Omega2", "Omega3"]
            .iter()
            .map(|s| s.to_string())
            .collect()
    }
    fn output_names(&self) -> Vec<String> {
        ["Gamma1", "Gamma2", "Gamma3"]
            .iter()
            .map(|s| s.to_string())
            .collect()
    }

    /// The hanging and the sleeping top with spin ω₃.
    fn closed_form_equilibria(&self, _u: &[f64]) -> Option<Vec<Vec<f64>>> {
        let w = self.w3;
        Some(vec![
            vec![0.0, 0.0, -1.0, 0.0, 0.0, w],
            vec![0.0, 0.0, 1.0, 0.0, 0.0, w],
        ])
    }

    /// |Γ| = 1.
    fn is_physical(&self, x: &[f64]) -> bool {
        let g2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
        (g2 - 1.0).abs() <= 1e-9
    }

    /// The sleeping top tilted by 0.1 rad about the body's first axis.
    fn default_initial_state(&self) -> Vec<f64> {
        let (s, c) = 0.1f64.sin_cos();
        vec![0.0, s, c, 0.0, 0.0, self.w3]
    }

    fn default_horizon(&self) -> f64 {
        10.0
    }

    fn conserved_names(&self) -> Vec<String> {
        vec![
            "E".into(),
            "Pi.Gamma".into(),
            "|Gamma|^2".into(),
            "Pi3".into(),
        ]
    }

    /// E: m g l (the potential's amplitude); Π·Γ and Π₃: I3|ω₃|; |Γ|²: 1.
    fn conserved_scales(&self) -> Vec<f64> {
        let spin = self.i3 * self.w3.abs();
        vec![self.mgl(), spin, 1.0, spin]
    }

    fn equilibria_note(&self) -> Option<String> {
        Some(format!(
            "hanging and sleeping top spinning at w3 = {} rad/s; the threshold I3²w3² = 4 I1 m g l \
             is at w3 = {:.10} rad/s (other relative equilibria, conical rotations, are not listed)",
            self.w3,
            self.threshold_spin()
        ))
    }
}

impl NonlinearSystem for HeavyTop {
    fn f<D: Scalar>(&self, x: &[D], _u: &[D], dx: &mut [D]) {
        let (g1, g2, g3) = (x[0], x[1], x[2]);
        let (o1, o2, o3) = (x[3], x[4], x[5]);
        let mgl = self.mgl();
        // Γ̇ = Γ × Ω
        dx[0] = g2 * o3 - g3 * o2;
        dx[1] = g3 * o1 - g1 * o3;
        dx[2] = g1 * o2 - g2 * o1;
        // I Ω̇ = IΩ × Ω + m g l Γ × χ, χ = e₃
        dx[3] = (o2 * o3 * (self.i1 - self.i3) + g2 * mgl) / self.i1;
        dx[4] = (o3 * o1 * (self.i3 - self.i1) - g1 * mgl) / self.i1;
        dx[5] = D::from(0.0);
    }
    fn h<D: Scalar>(&self, x: &[D], _u: &[D], y: &mut [D]) {
        y.copy_from_slice(&x[..3]);
    }
    fn conserved<D: Scalar>(&self, x: &[D], c: &mut [D]) {
        let (i1, i3) = (self.i1, self.i3);
        let (g1, g2, g3) = (x[0], x[1], x[2]);
        let (o1, o2, o3) = (x[3], x[4], x[5]);
        c[0] = (o1 * o1 * i1 + o2 * o2 * i1 + o3 * o3 * i3) * 0.5 + g3 * self.mgl();
        c[1] = (g1 * o1 + g2 * o2) * i1 + g3 * o3 * i3;
        c[2] = g1 * g1 + g2 * g2 + g3 * g3;
        c[3] = o3 * i3;
    }
}
