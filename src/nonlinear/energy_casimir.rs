//! Nonlinear (Lyapunov) stability from conserved quantities: the energy–Casimir test, which
//! decides the equilibria that the linearisation leaves undetermined (centres).
//!
//! **The test.** Let H (the first of a model's [conserved quantities](
//! crate::nonlinear::SystemInfo::conserved_names), the energy) and C₁ … C_m (the others:
//! Casimirs, momenta) be conserved, x̄ an equilibrium. If multipliers λ exist with
//! ∇(H + Σλⱼ Cⱼ)(x̄) = 0 and the Hessian of H + Σλⱼ Cⱼ is definite on the tangent space
//! T = {δ : ∇Cⱼ(x̄)·δ = 0 for all j}, then for μ large enough
//! V = ±(H + Σλⱼ Cⱼ) + μ Σ (Cⱼ − Cⱼ(x̄))² is conserved and has a strict local minimum at x̄:
//! a Lyapunov function, so x̄ is **Lyapunov stable** (not asymptotically: V is conserved).
//! Equivalently x̄ is a strict extremum of H on the joint level set of the Cⱼ (Arnold's method;
//! Holm, Marsden, Ratiu & Weinstein, "Nonlinear stability of fluid and plasma equilibria",
//! Phys. Rep. 123, 1985, §2 — the rigid body and the heavy top are their first examples).
//! With no Cⱼ it is the Lagrange–Dirichlet theorem (a strict minimum of the energy).
//!
//! **Verdicts.** Definite → [`Extremum::Minimum`] or [`Extremum::Maximum`], Lyapunov stable.
//! Indefinite → [`Extremum::Saddle`]: no Lyapunov function of this form; stability is *not*
//! shown (instability, where it holds, comes from the eigenvalues: a real pair). Singular →
//! [`Extremum::Degenerate`] (e.g. a continuum of equilibria): the test cannot decide.
//!
//! **Dependent gradients.** When the ∇Cⱼ are linearly dependent at x̄ (the sleeping top: there
//! ∇(Π·Γ) = I3ω₃∇Π₃ + ½∇|Γ|²), λ is not unique: λ = λ_p + N t with N spanning the null space
//! of [∇C₁ … ∇C_m]. The restricted Hessian M(t) is affine in t and its smallest eigenvalue is
//! concave in t, so "is there a definite combination?" is a concave maximisation — solved
//! exactly (bracketing plus golden section) for one free multiplier, by coordinate ascent for
//! more. For the heavy top this recovers the classical I3²ω₃² > 4 I1 m g l.
//!
//! Tolerances: rank of the gradients at 1e-10 of the largest singular value; stationarity
//! ‖∇H + Σλⱼ∇Cⱼ‖ ≤ 1e-8 of the size of its terms plus 1e-12·‖∇²(H + Σλⱼ Cⱼ)‖(1 + ‖x̄‖) (the
//! gradient that rounding x̄ to floating point leaves); definiteness when every eigenvalue of the
//! restricted Hessian exceeds 1e-9 of its scale (‖∇²H‖ + Σ|λⱼ|‖∇²Cⱼ‖).

use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use crate::error::Result;
use crate::nonlinear::system::{Derivatives2, DynSystem, check_point};

/// What the energy is on the level set of the other conserved quantities at x̄.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Extremum {
    /// Strict local minimum: Lyapunov stable.
    Minimum,
    /// Strict local maximum: Lyapunov stable.
    Maximum,
    /// The conserved quantities pin x̄ (the level set is locally the point): Lyapunov stable.
    Pinned,
    /// A saddle (indefinite restricted Hessian): the test shows nothing.
    Saddle,
    /// Singular restricted Hessian: the test cannot decide.
    Degenerate,
    /// No multipliers make x̄ a critical point (x̄ is not a constrained critical point of H).
    NotCritical,
}

impl Extremum {
    /// Whether the verdict proves Lyapunov stability.
    pub fn lyapunov_stable(&self) -> bool {
        matches!(
            self,
            Extremum::Minimum | Extremum::Maximum | Extremum::Pinned
        )
    }
}

/// The result of the energy–Casimir test at one equilibrium.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EnergyCasimir {
    /// Minimum, maximum, saddle, …
    pub extremum: Extremum,
    /// True when the test proves Lyapunov stability.
    pub lyapunov_stable: bool,
    /// The multipliers λⱼ of the second, third, … conserved quantity.
    pub multipliers: Vec<f64>,
    /// Eigenvalues (ascending) of the Hessian of H + Σλⱼ Cⱼ on the tangent space.
    pub hessian_eigenvalues: Vec<f64>,
    /// Dimension of the tangent space of the level set.
    pub tangent_dim: usize,
    /// Number of free multipliers (dependent gradients) that were optimised over.
    pub free_multipliers: usize,
    /// The verdict in words.
    pub reason: String,
}

/// The energy–Casimir test at x (module docs). `Ok(None)` when the model declares no
/// conserved quantity. The quantities are conserved for zero input, so call it at equilibria
/// with u = 0.
///
/// ```
/// use ltikit::nonlinear::{energy_casimir, Extremum, models::RigidBody};
/// let body = RigidBody::new(3.0, 2.0, 1.0).unwrap();
/// let on = |k: usize| { let mut x = [0.0; 3]; x[k] = 1.0; x };
/// let v = |k| energy_casimir(&body, &on(k)).unwrap().unwrap().extremum;
/// assert_eq!(v(0), Extremum::Minimum);  // largest moment: E minimal on the sphere
/// assert_eq!(v(1), Extremum::Saddle);   // intermediate
/// assert_eq!(v(2), Extremum::Maximum);  // smallest
/// ```
pub fn energy_casimir(sys: &dyn DynSystem, x: &[f64]) -> Result<Option<EnergyCasimir>> {
    check_point(sys, x, &vec![0.0; sys.nu()])?;
    let d = sys.conserved_derivatives(x);
    let Some((h, cs)) = d.split_first() else {
        return Ok(None);
    };
    let xnorm = x.iter().map(|v| v * v).sum::<f64>().sqrt();
    Ok(Some(test(h, cs, &sys.conserved_names(), xnorm)))
}

/// Orthonormal basis of the orthogonal complement of the columns of `g` (n × m), and of
/// the null space of `g` (in ℝᵐ), with the numerical rank at 1e-10·σ_max.
fn complements(g: &DMatrix<f64>) -> (DMatrix<f64>, DMatrix<f64>, usize) {
    let (n, m) = g.shape();
    if m == 0 {
        return (DMatrix::identity(n, n), DMatrix::zeros(0, 0), 0);
    }
    let svd = g.clone().svd(true, true);
    let smax = svd.singular_values.max();
    let keep: Vec<usize> = (0..svd.singular_values.len())
        .filter(|&i| smax > 0.0 && svd.singular_values[i] > 1e-10 * smax)
        .collect();
    let rank = keep.len();
    let (Some(u), Some(vt)) = (svd.u, svd.v_t) else {
        return (DMatrix::identity(n, n), DMatrix::identity(m, m), 0);
    };
    let basis_of_complement = |vectors: Vec<DVector<f64>>, dim: usize| {
        let mut p = DMatrix::identity(dim, dim);
        for v in &vectors {
            p -= v * v.transpose();
        }
        let eig = p.symmetric_eigen();
        let cols: Vec<DVector<f64>> = (0..dim)
            .filter(|&i| eig.eigenvalues[i] > 0.5)
            .map(|i| eig.eigenvectors.column(i).into_owned())
            .collect();
        if cols.is_empty() {
            DMatrix::zeros(dim, 0)
        } else {
            DMatrix::from_columns(&cols)
        }
    };
    let z = basis_of_complement(keep.iter().map(|&i| u.column(i).into_owned()).collect(), n);
    let nn = basis_of_complement(
        keep.iter()
            .map(|&i| vt.row(i).transpose().into_owned())
            .collect(),
        m,
    );
    (z, nn, rank)
}

fn sorted_eigenvalues(m: &DMatrix<f64>) -> Vec<f64> {
    if m.nrows() == 0 {
        return Vec::new();
    }
    let sym = 0.5 * (m + m.transpose());
    let mut e: Vec<f64> = sym.symmetric_eigenvalues().iter().copied().collect();
    e.sort_by(f64::total_cmp);
    e
}

fn min_eig(m: &DMatrix<f64>) -> f64 {
    sorted_eigenvalues(m)
        .first()
        .copied()
        .unwrap_or(f64::INFINITY)
}

/// Maximises a concave function of one variable: bracket by doubling, then golden section.
fn maximise_concave(f: &dyn Fn(f64) -> f64, start: f64, scale: f64) -> (f64, f64) {
    let f0 = f(start);
    let (fr, fl) = (f(start + scale), f(start - scale));
    let (mut a, mut b) = (start - scale, start + scale);
    if fr > f0 || fl > f0 {
        let dir = if fr > f0 { 1.0 } else { -1.0 };
        let (mut prev, mut cur, mut fcur) = (start, start + dir * scale, fr.max(fl));
        let mut step = scale;
        for _ in 0..80 {
            step *= 2.0;
            let next = cur + dir * step;
            let fnext = f(next);
            if fnext <= fcur {
                (a, b) = if dir > 0.0 {
                    (prev, next)
                } else {
                    (next, prev)
                };
                break;
            }
            prev = cur;
            cur = next;
            fcur = fnext;
            (a, b) = if dir > 0.0 { (prev, cur) } else { (cur, prev) };
        }
    }
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - r * (b - a), a + r * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..200 {
        if (b - a).abs() <= 1e-14 * (a.abs().max(b.abs()) + scale) {
            break;
        }
        if fc > fd {
            b = d;
            d = c;
            fd = fc;
            c = b - r * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + r * (b - a);
            fd = f(d);
        }
    }
    if fc > fd { (c, fc) } else { (d, fd) }
}

/// Maximises the concave t ↦ `sign`·λ_min(sign·M(t)), M(t) = M₀ + Σ tᵢ Mᵢ.
fn best_multipliers(
    m0: &DMatrix<f64>,
    mi: &[DMatrix<f64>],
    sign: f64,
    scale: f64,
) -> (Vec<f64>, f64) {
    let eval = |t: &[f64]| {
        let mut m = m0.clone();
        for (ti, mm) in t.iter().zip(mi) {
            m += mm * *ti;
        }
        min_eig(&(m * sign))
    };
    let mut t = vec![0.0; mi.len()];
    let mut best = eval(&t);
    let rounds = if mi.len() == 1 { 1 } else { 30 };
    for _ in 0..rounds {
        let before = best;
        for i in 0..mi.len() {
            let f = |s: f64| {
                let mut tt = t.clone();
                tt[i] = s;
                eval(&tt)
            };
            let (s, v) = maximise_concave(&f, t[i], scale);
            if v > best {
                t[i] = s;
                best = v;
            }
        }
        if best - before <= 1e-14 * scale {
            break;
        }
    }
    (t, best)
}

/// Zᵀ(∇²H + Σ λⱼ∇²Cⱼ)Z (with `with_energy`), or Zᵀ(Σ λⱼ∇²Cⱼ)Z.
fn restricted(
    h: &Derivatives2,
    cs: &[Derivatives2],
    lambda: &[f64],
    z: &DMatrix<f64>,
    with_energy: bool,
) -> DMatrix<f64> {
    let n = h.gradient.len();
    let mut l = if with_energy {
        h.hessian.clone()
    } else {
        DMatrix::zeros(n, n)
    };
    for (c, lj) in cs.iter().zip(lambda) {
        l += &c.hessian * *lj;
    }
    z.transpose() * l * z
}

fn test(h: &Derivatives2, cs: &[Derivatives2], names: &[String], xnorm: f64) -> EnergyCasimir {
    let n = h.gradient.len();
    let m = cs.len();
    let g = if m == 0 {
        DMatrix::zeros(n, 0)
    } else {
        DMatrix::from_columns(&cs.iter().map(|c| c.gradient.clone()).collect::<Vec<_>>())
    };
    let (z, null, _) = complements(&g);
    // Particular multipliers: least squares G λ = −∇H (minimum norm).
    let lambda_p = if m == 0 {
        DVector::zeros(0)
    } else {
        g.clone()
            .svd(true, true)
            .solve(&(-&h.gradient), 1e-10 * g.norm().max(f64::MIN_POSITIVE))
            .unwrap_or_else(|_| DVector::zeros(m))
    };
    let resid = (&h.gradient + &g * &lambda_p).norm();
    // Relative to the terms, plus the gradient change that rounding x̄ itself causes
    // (sin π = 1.2e-16: the upright pendulum's energy gradient is not exactly zero).
    let curvature = h.hessian.norm()
        + cs.iter()
            .zip(lambda_p.iter())
            .map(|(c, l)| c.hessian.norm() * l.abs())
            .sum::<f64>();
    let size = h.gradient.norm() + g.norm() * lambda_p.norm() + 1e-4 * curvature * (1.0 + xnorm);
    let mut out = EnergyCasimir {
        extremum: Extremum::NotCritical,
        lyapunov_stable: false,
        multipliers: lambda_p.iter().copied().collect(),
        hessian_eigenvalues: Vec::new(),
        tangent_dim: z.ncols(),
        free_multipliers: null.ncols(),
        reason: String::new(),
    };
    if resid > 1e-8 * size {
        out.reason = format!(
            "x̄ is not a critical point of the energy on the level set (residual {resid:.3e})"
        );
        return out;
    }
    if z.ncols() == 0 {
        out.extremum = Extremum::Pinned;
        out.lyapunov_stable = true;
        out.reason = "the conserved quantities pin the state (their level set is locally a \
                      point): Lyapunov stable"
            .into();
        return out;
    }
    let hess = |lambda: &DVector<f64>| restricted(h, cs, lambda.as_slice(), &z, true);
    let m0 = hess(&lambda_p);
    let mi: Vec<DMatrix<f64>> = (0..null.ncols())
        .map(|k| {
            let dir: Vec<f64> = null.column(k).iter().copied().collect();
            restricted(h, cs, &dir, &z, false)
        })
        .collect();
    let scale = h.hessian.norm()
        + cs.iter()
            .zip(lambda_p.iter())
            .map(|(c, l)| c.hessian.norm() * (1.0 + l.abs()))
            .sum::<f64>();
    let tol = 1e-9 * scale.max(f64::MIN_POSITIVE);
    let (tmin, vmin) = best_multipliers(&m0, &mi, 1.0, 1.0 + lambda_p.norm());
    let (tmax, vmax) = best_multipliers(&m0, &mi, -1.0, 1.0 + lambda_p.norm());
    let lambda_at = |t: &[f64]| {
        let mut l = lambda_p.clone();
        for (k, tk) in t.iter().enumerate() {
            l += null.column(k) * *tk;
        }
        l
    };
    let (t, extremum) = if vmin > tol {
        (tmin, Extremum::Minimum)
    } else if vmax > tol {
        (tmax, Extremum::Maximum)
    } else if vmin < -tol && vmax < -tol {
        (tmin, Extremum::Saddle)
    } else {
        (tmin, Extremum::Degenerate)
    };
    let lambda = lambda_at(&t);
    out.hessian_eigenvalues = sorted_eigenvalues(&hess(&lambda));
    out.multipliers = lambda.iter().copied().collect();
    out.extremum = extremum;
    out.lyapunov_stable = extremum.lyapunov_stable();
    out.reason = reason(extremum, names, null.ncols());
    out
}

/// The verdict in words, naming the conserved quantities.
fn reason(extremum: Extremum, names: &[String], free: usize) -> String {
    let energy = names.first().map_or("the energy", |n| n.as_str());
    let level = if names.len() <= 1 {
        energy.to_string()
    } else {
        let others: Vec<&str> = names.iter().skip(1).map(|n| n.as_str()).collect();
        format!("{energy} on the level set of {}", others.join(", "))
    };
    let free = if free > 0 {
        format!(
            " (optimised over {free} free multiplier{})",
            if free == 1 { "" } else { "s" }
        )
    } else {
        String::new()
    };
    match extremum {
        Extremum::Minimum | Extremum::Maximum => format!(
            "energy–Casimir: strict {} of {level}{free} ⇒ Lyapunov stable",
            if extremum == Extremum::Minimum {
                "minimum"
            } else {
                "maximum"
            }
        ),
        Extremum::Saddle => {
            format!("energy–Casimir: a saddle of {level}{free}: no Lyapunov function of this form")
        }
        _ => format!(
            "energy–Casimir: the Hessian of {level} is singular{free} (e.g. a continuum of \
             equilibria): the test cannot decide"
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn concave_maximiser_finds_the_top() {
        let f = |t: f64| -(t - 7.5).powi(2) + 3.0;
        let (t, v) = maximise_concave(&f, 0.0, 1.0);
        assert!((t - 7.5).abs() < 1e-6 && (v - 3.0).abs() < 1e-12);
        let f = |t: f64| -(t + 1e4).abs();
        let (t, _) = maximise_concave(&f, 0.0, 1.0);
        assert!((t + 1e4).abs() < 1e-6);
    }

    #[test]
    fn complements_of_dependent_columns() {
        let g = DMatrix::from_row_slice(3, 2, &[1.0, 2.0, 0.0, 0.0, 0.0, 0.0]);
        let (z, null, rank) = complements(&g);
        assert_eq!((z.ncols(), null.ncols(), rank), (2, 1, 1));
        assert!((g * null.column(0)).norm() < 1e-15);
    }
}
