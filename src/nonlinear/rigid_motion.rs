//! The closed-form motion of the free rigid body in Jacobi elliptic functions (seed
//! eqs. 2.54–2.62 and exercise 2.13, eqs. 2.82–2.87), for any ordering of the moments.
//!
//! With h = |Π|², E the energy and D_i = h − 2E I_i = Σ_{j≠i} Π_j² (I_j − I_i)/I_j (a sum
//! without cancellation for the extreme axes), the orbit circles the axis **a** of the
//! largest moment when D_b > 0 for the intermediate axis b (low energy), the axis of the
//! smallest moment when D_b < 0; c is the remaining extreme axis. Then
//!
//!   Π_a = ±A dn(ωt + u₀),  Π_b = B sn(ωt + u₀),  Π_c = C cn(ωt + u₀),
//!   A² = I_a(−D_c)/(I_c − I_a),  B² = I_b D_a/(I_b − I_a),  C² = I_c D_a/(I_c − I_a),
//!   ω² = (I_b − I_a)(−D_c)/(I_a I_b I_c),  k² = (I_c − I_b) D_a / ((I_b − I_a)(−D_c)),
//!   k′² = 1 − k² = (I_c − I_a) D_b / ((I_b − I_a) D_c),
//!
//! period T = 4K(k)/ω. For a = 3, b = 2, c = 1 (I1 > I2 > I3 and h < 2EI2) these are the
//! seed's eqs. 2.58–2.59 with its ω and k; for I1 > I3 > I2 its eqs. 2.82–2.84 and k₂ —
//! but the seed's ω₂ = √((h − 2EI2)(2EI1 − h)/(I1 I2)) there is a typo: substituting into
//! Π̇₃ = (I1 − I2)/(I1 I2) Π₁Π₂ requires ω₂ = √((I3 − I2)(2EI1 − h)/(I1 I2 I3)), the formula
//! above (and what the simulation confirms to 1e-10). k′² is evaluated in the product form,
//! so K(k) = π/(2 AGM(1, k′)) keeps full precision near the separatrix.
//!
//! The phase u₀ = F(φ₀, k) with φ₀ = atan2(Π_b(0)/B, Π_c(0)/C) (the amplitude), the sign of
//! Π_a from Π_a(0), and the direction of time from the sign of Π̇_b(0) (or Π̇_c(0)). An
//! axi-symmetric body has k = 0 (sn, cn, dn → sin, cos, 1: seed eqs. 2.60–2.62); on the
//! separatrix (D_b = 0) k = 1 and sn, cn, dn → tanh, sech, sech (no period); an equilibrium
//! stays put.

use serde::Serialize;

use crate::error::{LtiError, Result, check_finite};
use crate::nonlinear::elliptic::{carlson_rf, jacobi_kkp, k_from_complement};
use crate::nonlinear::models::RigidBody;

/// The closed-form solution of the free rigid body from one initial state.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FreeRigidMotion {
    /// Energy E (seed eq. 2.51).
    pub energy: f64,
    /// h = |Π|² (seed eq. 2.53).
    pub momentum2: f64,
    /// The axis the orbit circles (0, 1, 2; the dn component); `None` at an equilibrium.
    pub circled_axis: Option<usize>,
    /// Elliptic modulus k (0 for an axi-symmetric body, 1 on the separatrix).
    pub modulus: f64,
    /// ω (rad/s).
    pub omega: f64,
    /// Period 4K(k)/ω of Π(t); `None` at an equilibrium or on the separatrix.
    pub period: Option<f64>,
    #[serde(skip)]
    form: Form,
}

#[derive(Debug, Clone, PartialEq)]
enum Form {
    Constant([f64; 3]),
    Elliptic {
        axes: [usize; 3],
        amp: [f64; 3],
        sign_a: f64,
        sign_c: f64,
        dir: f64,
        u0: f64,
        k: f64,
        kp: f64,
    },
}

impl Default for Form {
    fn default() -> Self {
        Form::Constant([0.0; 3])
    }
}

fn sign(x: f64) -> f64 {
    if x < 0.0 { -1.0 } else { 1.0 }
}

/// F(φ, k) with the complementary modulus carried separately (precision near k = 1).
fn elliptic_f_kkp(phi: f64, kp: f64) -> Result<f64> {
    let j = (phi / std::f64::consts::PI).round();
    let psi = phi - j * std::f64::consts::PI;
    let (s, c) = psi.sin_cos();
    // 1 − k² sin²ψ = cos²ψ + k′² sin²ψ (no cancellation).
    let base = s * carlson_rf(c * c, c * c + kp * kp * s * s, 1.0)?;
    Ok(base + 2.0 * j * k_from_complement(kp))
}

impl FreeRigidMotion {
    /// The motion of `body` from Π(0) = `pi0`.
    ///
    /// ```
    /// use ltikit::nonlinear::{models::RigidBody, rigid_motion::FreeRigidMotion};
    /// let body = RigidBody::new(3.0, 2.0, 1.0).unwrap();
    /// // Seed fig. 2.12 (a): Π(0) = [0.6, −1, 2] gives k = 0.2951 and T = 5.4.
    /// let m = FreeRigidMotion::new(&body, &[0.6, -1.0, 2.0]).unwrap();
    /// assert!((m.modulus - 0.2951).abs() < 5e-5);
    /// assert!((m.period.unwrap() - 5.4).abs() < 0.01);
    /// let p = m.at(0.0);
    /// assert!((p[0] - 0.6).abs() < 1e-15 && (p[1] + 1.0).abs() < 1e-15 && (p[2] - 2.0).abs() < 1e-15);
    /// ```
    pub fn new(body: &RigidBody, pi0: &[f64; 3]) -> Result<Self> {
        for (i, &v) in pi0.iter().enumerate() {
            check_finite(|| format!("Π{}(0)", i + 1), v)?;
        }
        let inertia = body.inertia;
        let energy = body.energy(pi0);
        let momentum2 = pi0.iter().map(|p| p * p).sum::<f64>();
        let constant = |pi: [f64; 3]| FreeRigidMotion {
            energy,
            momentum2,
            circled_axis: None,
            modulus: 0.0,
            omega: 0.0,
            period: None,
            form: Form::Constant(pi),
        };
        // Equilibrium: Π ∥ I⁻¹Π.
        let om = [0, 1, 2].map(|i| pi0[i] / inertia[i]);
        let cross = [
            pi0[1] * om[2] - pi0[2] * om[1],
            pi0[2] * om[0] - pi0[0] * om[2],
            pi0[0] * om[1] - pi0[1] * om[0],
        ];
        let norm = |v: &[f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm(&cross) <= 8.0 * f64::EPSILON * norm(pi0) * norm(&om) {
            return Ok(constant(*pi0));
        }
        let d = [0, 1, 2].map(|i| {
            (0..3)
                .filter(|&j| j != i)
                .map(|j| pi0[j] * pi0[j] * (inertia[j] - inertia[i]) / inertia[j])
                .sum::<f64>()
        });
        let mut idx = [0usize, 1, 2];
        idx.sort_by(|&p, &q| inertia[p].total_cmp(&inertia[q]));
        let (lo, b, hi) = (idx[0], idx[1], idx[2]);
        let same = |x: f64, y: f64| (x - y).abs() <= 1e-14 * x.max(y);
        let a = if same(inertia[b], inertia[hi]) {
            lo
        } else if same(inertia[b], inertia[lo]) || d[b] > 0.0 {
            hi
        } else {
            lo
        };
        let c = if a == hi { lo } else { hi };
        let (ia, ib, ic) = (inertia[a], inertia[b], inertia[c]);
        let amp_a = (ia * -d[c] / (ic - ia)).max(0.0).sqrt();
        let amp_b = (ib * d[a] / (ib - ia)).max(0.0).sqrt();
        let amp_c = (ic * d[a] / (ic - ia)).max(0.0).sqrt();
        let omega = ((ib - ia) * -d[c] / (ia * ib * ic)).max(0.0).sqrt();
        let k2 = ((ic - ib) * d[a] / ((ib - ia) * -d[c])).clamp(0.0, 1.0);
        let kp2 = ((ic - ia) * d[b] / ((ib - ia) * d[c])).clamp(0.0, 1.0);
        if !(omega > 0.0 && amp_b > 0.0 && amp_c > 0.0 && omega.is_finite()) {
            return Err(LtiError::Undefined {
                what: "the elliptic solution of the rigid body".into(),
                reason: format!("degenerate amplitudes for Π(0) = {pi0:?}"),
            });
        }
        let (k, kp) = (k2.sqrt(), kp2.sqrt());
        let dpi = [
            pi0[1] * pi0[2] * (inertia[1] - inertia[2]) / (inertia[1] * inertia[2]),
            pi0[2] * pi0[0] * (inertia[2] - inertia[0]) / (inertia[2] * inertia[0]),
            pi0[0] * pi0[1] * (inertia[0] - inertia[1]) / (inertia[0] * inertia[1]),
        ];
        let sn0 = (pi0[b] / amp_b).clamp(-1.0, 1.0);
        let cn0 = (pi0[c] / amp_c).clamp(-1.0, 1.0);
        let (u0, sign_c, dir, period) = if kp == 0.0 {
            // Separatrix: sn = tanh, cn = dn = sech.
            (sn0.atanh(), sign(pi0[c]), sign(dpi[b]), None)
        } else {
            let u0 = elliptic_f_kkp(sn0.atan2(cn0), kp)?;
            let dir = if cn0.abs() >= 0.5 {
                sign(dpi[b] * cn0)
            } else {
                sign(-dpi[c] * sn0)
            };
            (u0, 1.0, dir, Some(4.0 * k_from_complement(kp) / omega))
        };
        Ok(FreeRigidMotion {
            energy,
            momentum2,
            circled_axis: Some(a),
            modulus: k,
            omega,
            period,
            form: Form::Elliptic {
                axes: [a, b, c],
                amp: [amp_a, amp_b, amp_c],
                sign_a: sign(pi0[a]),
                sign_c,
                dir,
                u0,
                k,
                kp,
            },
        })
    }

    /// Π(t).
    pub fn at(&self, t: f64) -> [f64; 3] {
        match &self.form {
            Form::Constant(p) => *p,
            Form::Elliptic {
                axes,
                amp,
                sign_a,
                sign_c,
                dir,
                u0,
                k,
                kp,
            } => {
                let j = jacobi_kkp(dir * self.omega * t + u0, *k, *kp);
                let mut p = [0.0; 3];
                p[axes[0]] = sign_a * amp[0] * j.dn;
                p[axes[1]] = amp[1] * j.sn;
                p[axes[2]] = sign_c * amp[2] * j.cn;
                p
            }
        }
    }
}
