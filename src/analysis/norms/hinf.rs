//! Certified H∞ and L∞ norms: the peak gain sup_ω σ_max(G(jω)) as an interval
//! \[lower, upper\] with upper/lower − 1 ≤ [`CERTIFIED_GAP`].
//!
//! # Method
//! Boyd–Balakrishnan (1990) / Bruinsma–Steinbuch (1990). The lower bound starts as the
//! largest gain at ω = 0, ω → ∞ (σ_max(D)) and the poles' frequencies |Im p| and |p|. At
//! γ = lower·(1 + 2·tol) the Hamiltonian H(γ) (`hamiltonian.rs`) has an imaginary
//! eigenvalue jω exactly when γ is a singular value of G(jω): with none, γ is an upper bound
//! and the interval is certified; otherwise the gains at the crossing frequencies and at the
//! midpoints of consecutive crossings raise the lower bound, and the test repeats (quadratic
//! convergence). A frequency whose eigenvalue is imaginary only within the tolerance, but
//! where the gain stays below the lower bound, is refuted by that evaluation (the Hamiltonian
//! test alone cannot tell a nearly imaginary eigenvalue from an imaginary one). The lower
//! bound is then polished by a golden-section search for the local maximum of σ_max(G(jω))
//! on the crossing interval that raised it; if that ever exceeds the upper bound, the
//! iteration resumes from it.
//!
//! Lower bounds are always actual evaluations of G (on the Hessenberg form of A, as every
//! frequency response); the upper bound is a γ at which the Hamiltonian has no (confirmed)
//! imaginary eigenvalue.
//!
//! A discrete-time model is mapped by the bilinear transform z = (1 + s)/(1 − s), which keeps
//! the norm (the unit circle goes to the imaginary axis, ν = tan(θ/2)); its gains are
//! evaluated on the unit circle of the model itself, ω = θ/T ∈ \[0, π/T\].
//!
//! An unstable model has an infinite H∞ norm (MATLAB's `hinfnorm` returns Inf, with the
//! same meaning): the result says so with the unstable eigenvalue; its L∞ norm
//! ([`linf_norm`]) is finite unless A has an eigenvalue on the imaginary axis (unit circle).

use nalgebra::DMatrix;
use num_complex::Complex64;
use serde::Serialize;

use super::gain::{GainEvaluator, sigma_max_real};
use super::hamiltonian::Hamiltonian;
use crate::error::{LtiError, Result};
use crate::fmt::fmt_num;
use crate::lti::StateSpace;
use crate::numeric::linalg::schur_eigenvalues;

/// The certified relative width of the interval: upper/lower − 1 ≤ 1e-10.
pub const CERTIFIED_GAP: f64 = 1e-10;

/// Step of the iteration: γ = lower·(1 + 2·ITER_TOL), well inside [`CERTIFIED_GAP`].
const ITER_TOL: f64 = 1e-11;

/// Most Hamiltonian tests (the iteration converges quadratically: a handful in practice).
const MAX_ITERATIONS: usize = 60;

/// Which peak gain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum NormKind {
    /// H∞: the peak gain of a stable model (∞ when unstable).
    Hinf,
    /// L∞: the peak gain on the imaginary axis (unit circle) of any model without poles there.
    Linf,
}

impl NormKind {
    /// "H∞" or "L∞".
    pub fn symbol(&self) -> &'static str {
        match self {
            NormKind::Hinf => "H∞",
            NormKind::Linf => "L∞",
        }
    }
}

/// A certified peak gain (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PeakGain {
    /// H∞ or L∞.
    pub kind: NormKind,
    /// The largest σ_max(G(jω)) evaluated (∞ when the norm is infinite).
    pub lower: f64,
    /// A γ the Hamiltonian test certifies: no singular value of G reaches it (∞ when the norm
    /// is infinite).
    pub upper: f64,
    /// Where `lower` was attained, rad/s (∞ — JSON null — for the limit ω → ∞ of a
    /// continuous model; at an infinite norm, the pole's frequency).
    pub w: f64,
    /// Hamiltonian eigenvalue problems solved.
    pub iterations: usize,
    /// Why the norm is infinite (None when finite).
    pub infinite: Option<String>,
}

impl PeakGain {
    /// The norm's best value: the lower bound (an evaluation of G at `w`).
    pub fn value(&self) -> f64 {
        self.lower
    }

    /// upper/lower − 1 (0 for a zero or infinite norm).
    pub fn relative_gap(&self) -> f64 {
        if self.lower > 0.0 && self.lower.is_finite() {
            self.upper / self.lower - 1.0
        } else {
            0.0
        }
    }
}

/// The certified H∞ norm of a state-space model (continuous or discrete time): an interval
/// \[lower, upper\] with upper/lower − 1 ≤ [`CERTIFIED_GAP`] and the peak frequency; an
/// infinite norm, with the unstable eigenvalue named, when A is not stable.
///
/// Dead times on the inputs and outputs do not change the norm (they multiply G(jω) by
/// diagonal unitary matrices) and are ignored.
///
/// Errors: more states than [`crate::limits::MAX_NORM_STATES`], the eigenvalue solver's.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::StateSpace;
/// use ltikit::analysis::norms::hinf_norm;
/// // 1/(s² + 2ζs + 1), ζ = 0.1: ‖G‖∞ = 1/(2ζ√(1 − ζ²))
/// let z = 0.1;
/// let ss = StateSpace::new(
///     DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, -2.0 * z]),
///     DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
///     DMatrix::from_row_slice(1, 2, &[1.0, 0.0]),
///     DMatrix::zeros(1, 1),
/// ).unwrap();
/// let n = hinf_norm(&ss).unwrap();
/// let exact = 1.0 / (2.0 * z * (1.0 - z * z).sqrt());
/// assert!(n.lower <= exact * (1.0 + 1e-13) && exact <= n.upper);
/// assert!(n.upper / n.lower - 1.0 <= 1e-10);
/// assert!((n.w - (1.0 - 2.0 * z * z).sqrt()).abs() < 1e-6);
/// ```
pub fn hinf_norm(ss: &StateSpace) -> Result<PeakGain> {
    peak_gain(ss, NormKind::Hinf)
}

/// The certified L∞ norm sup_ω σ_max(G(jω)) (on the unit circle in discrete time) of a model
/// without eigenvalues of A on the imaginary axis (unit circle); equal to the H∞ norm of a
/// stable model.
///
/// Errors: as [`hinf_norm`].
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::StateSpace;
/// use ltikit::analysis::norms::linf_norm;
/// // 1/(s − 1): unstable, |G(jω)| = 1/√(ω² + 1) peaks at ω = 0
/// let one = |x: f64| DMatrix::from_element(1, 1, x);
/// let ss = StateSpace::new(one(1.0), one(1.0), one(1.0), one(0.0)).unwrap();
/// let n = linf_norm(&ss).unwrap();
/// assert!(n.lower <= 1.0 && 1.0 <= n.upper && n.w == 0.0);
/// assert!(ltikit::analysis::norms::hinf_norm(&ss).unwrap().infinite.is_some());
/// ```
pub fn linf_norm(ss: &StateSpace) -> Result<PeakGain> {
    peak_gain(ss, NormKind::Linf)
}

fn peak_gain(ss: &StateSpace, kind: NormKind) -> Result<PeakGain> {
    crate::limits::NORM_STATES.check_usize("states", ss.order())?;
    // input and output dead times multiply G(jω) by diagonal unitary matrices: the singular
    // values, and so the norm, do not see them
    let dt = ss.domain.dt();
    let poles = if ss.order() == 0 {
        Vec::new()
    } else {
        schur_eigenvalues(&ss.a)?
    };
    if let Some(reason) = infinite_reason(&poles, dt, kind, &ss.a) {
        return Ok(PeakGain {
            kind,
            lower: f64::INFINITY,
            upper: f64::INFINITY,
            w: reason.1,
            iterations: 0,
            infinite: Some(reason.0),
        });
    }
    let eval = GainEvaluator::new(ss)?;
    if ss.order() == 0 {
        let s = sigma_max_real(&ss.d);
        return Ok(PeakGain {
            kind,
            lower: s,
            upper: s,
            w: 0.0,
            iterations: 0,
            infinite: None,
        });
    }
    // the continuous-time equivalent and its frequency ν ↔ the model's ω
    let (ham, to_w): (Hamiltonian, Box<dyn Fn(f64) -> f64>) = match dt {
        None => (
            Hamiltonian {
                a: ss.a.clone(),
                b: ss.b.clone(),
                c: ss.c.clone(),
                d: ss.d.clone(),
            },
            Box::new(|nu: f64| nu),
        ),
        Some(t) => (
            bilinear(ss)?,
            Box::new(move |nu: f64| {
                if nu.is_infinite() {
                    std::f64::consts::PI / t
                } else {
                    2.0 * nu.atan() / t
                }
            }),
        ),
    };
    let sigma = |nu: f64| eval.sigma_max(to_w(nu));
    let ct_poles = match dt {
        None => poles,
        Some(_) => schur_eigenvalues(&ham.a)?,
    };
    let (lower, upper, nu, iterations) = certify(&ham, &sigma, &ct_poles)?;
    Ok(PeakGain {
        kind,
        lower,
        upper,
        w: to_w(nu),
        iterations,
        infinite: None,
    })
}

/// Why the norm is infinite (and the frequency of the pole that makes it so), if it is.
fn infinite_reason(
    poles: &[Complex64],
    dt: Option<f64>,
    kind: NormKind,
    a: &DMatrix<f64>,
) -> Option<(String, f64)> {
    let tol = 1e3 * f64::EPSILON * a.norm().max(1.0);
    let on_axis = |p: &Complex64| match dt {
        None => p.re.abs() <= tol,
        Some(_) => (p.norm() - 1.0).abs() <= tol,
    };
    let w_of = |p: &Complex64| match dt {
        None => p.im.abs(),
        Some(t) => p.im.atan2(p.re).abs() / t,
    };
    let shown = |p: &Complex64| crate::fmt::fmt_root(*p, 6);
    let var = if dt.is_some() { "z" } else { "s" };
    if let Some(p) = poles.iter().find(|p| on_axis(p)) {
        let place = if dt.is_some() {
            "on the unit circle"
        } else {
            "on the imaginary axis"
        };
        return Some((
            format!(
                "A has the eigenvalue {var} = {} {place} (the gain is unbounded at ω = {} rad/s)",
                shown(p),
                fmt_num(w_of(p))
            ),
            w_of(p),
        ));
    }
    if kind == NormKind::Linf {
        return None;
    }
    let unstable = |p: &&Complex64| match dt {
        None => p.re > 0.0,
        Some(_) => p.norm() > 1.0,
    };
    poles.iter().find(unstable).map(|p| {
        (
            format!(
                "the model is unstable (eigenvalue {var} = {} of A); its L∞ norm (the peak gain \
                 on the {}) is finite",
                shown(p),
                if dt.is_some() {
                    "unit circle"
                } else {
                    "imaginary axis"
                }
            ),
            w_of(p),
        )
    })
}

/// The continuous-time system with the same gains, G_c(s) = G_d((1 + s)/(1 − s)):
/// A_c = (I + A)⁻¹(A − I), B_c = √2 (I + A)⁻¹B, C_c = √2 C(I + A)⁻¹, D_c = D − C(I + A)⁻¹B.
fn bilinear(ss: &StateSpace) -> Result<Hamiltonian> {
    let n = ss.order();
    let i = DMatrix::<f64>::identity(n, n);
    let lu = (&i + &ss.a).lu();
    let singular = || LtiError::Undefined {
        what: "the bilinear map of the discrete model".into(),
        reason: "A has an eigenvalue at z = −1".into(),
    };
    let inv = lu.try_inverse().ok_or_else(singular)?;
    let r2 = std::f64::consts::SQRT_2;
    let a = &inv * (&ss.a - &i);
    let b = &inv * &ss.b * r2;
    let c = &ss.c * &inv * r2;
    let d = &ss.d - &ss.c * &inv * &ss.b;
    if !a
        .iter()
        .chain(b.iter())
        .chain(c.iter())
        .all(|x| x.is_finite())
    {
        return Err(singular());
    }
    Ok(Hamiltonian { a, b, c, d })
}

/// A frequency where the gain was evaluated and the bracket around it that the local
/// polish searches.
#[derive(Debug, Clone, Copy)]
struct Probe {
    value: f64,
    nu: f64,
    bracket: (f64, f64),
}

/// The iteration of the module docs on the continuous-time system `ham`, with `sigma(ν)` its
/// gain: (lower, upper, ν at lower, Hamiltonian tests).
fn certify(
    ham: &Hamiltonian,
    sigma: &dyn Fn(f64) -> f64,
    poles: &[Complex64],
) -> Result<(f64, f64, f64, usize)> {
    let probe = |nu: f64, bracket: (f64, f64)| Probe {
        value: sigma(nu),
        nu,
        bracket,
    };
    let mut best = probe(f64::INFINITY, (f64::INFINITY, f64::INFINITY));
    let consider = |p: Probe, best: &mut Probe| {
        // the larger gain; at a tie (a flat peak) the lower frequency
        let order = p
            .value
            .total_cmp(&best.value)
            .then(best.nu.total_cmp(&p.nu));
        if order == std::cmp::Ordering::Greater {
            *best = p;
        }
    };
    consider(probe(0.0, (0.0, 0.0)), &mut best);
    for p in poles {
        for nu in [p.im.abs(), p.norm()] {
            if nu > 0.0 && nu.is_finite() {
                consider(probe(nu, (nu / 2.0, nu * 2.0)), &mut best);
            }
        }
    }
    if best.value == 0.0 {
        return Ok((0.0, 0.0, 0.0, 0));
    }
    if !best.value.is_finite() {
        return Err(LtiError::Overflow {
            what: "the gain".into(),
            reason: format!(" at ω = {}", fmt_num(best.nu)),
        });
    }
    let mut iterations = 0;
    // the frequency (its bits) whose peak was last polished
    let mut polished_at: Option<u64> = None;
    loop {
        let gamma = best.value * (1.0 + 2.0 * ITER_TOL);
        iterations += 1;
        if iterations > MAX_ITERATIONS {
            return Err(LtiError::NoConvergence {
                what: "the H∞ iteration (Hamiltonian test)".into(),
                iterations: MAX_ITERATIONS,
            });
        }
        let w = ham.imaginary_frequencies(gamma)?;
        let mut next = best;
        for (k, &nu) in w.iter().enumerate() {
            let left = if k > 0 { w[k - 1] } else { nu / 2.0 };
            let right = w.get(k + 1).copied().unwrap_or(nu * 2.0 + 1.0);
            consider(probe(nu, (left, right)), &mut next);
            if let Some(&r) = w.get(k + 1) {
                consider(probe(0.5 * (nu + r), (nu, r)), &mut next);
            }
        }
        if next.value > best.value {
            best = next;
            continue;
        }
        // no imaginary eigenvalue, or none that the gain confirms: γ is an upper bound;
        // polish the lower bound locally (once per peak), resume if it passes γ
        if polished_at != Some(best.nu.to_bits()) {
            let p = polish(sigma, best);
            if p.value > best.value {
                best = p;
            }
            polished_at = Some(best.nu.to_bits());
            if best.value > gamma {
                continue;
            }
        }
        return Ok((best.value, gamma.max(best.value), best.nu, iterations));
    }
}

/// Golden-section search for the local maximum of σ(ν) in the probe's bracket.
fn polish(sigma: &dyn Fn(f64) -> f64, p: Probe) -> Probe {
    let (mut lo, mut hi) = p.bracket;
    if !(lo.is_finite() && hi.is_finite()) || hi <= lo {
        return p;
    }
    let mut best = p;
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let mut x1 = hi - g * (hi - lo);
    let mut x2 = lo + g * (hi - lo);
    let (mut f1, mut f2) = (sigma(x1), sigma(x2));
    for _ in 0..200 {
        if hi - lo <= 4.0 * f64::EPSILON * hi.abs() {
            break;
        }
        if f1 >= f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = sigma(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = sigma(x2);
        }
        for (x, f) in [(x1, f1), (x2, f2)] {
            if f > best.value {
                best = Probe {
                    value: f,
                    nu: x,
                    bracket: p.bracket,
                };
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn second_order(z: f64) -> StateSpace {
        StateSpace::new(
            DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, -2.0 * z]),
            DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
            DMatrix::from_row_slice(1, 2, &[1.0, 0.0]),
            DMatrix::zeros(1, 1),
        )
        .unwrap()
    }

    #[test]
    fn damping_family_against_closed_form() {
        // ‖1/(s² + 2ζs + 1)‖∞ = 1/(2ζ√(1 − ζ²)) at ω = √(1 − 2ζ²) for ζ < 1/√2
        for z in [0.5, 0.1, 1e-3, 1e-5] {
            let n = hinf_norm(&second_order(z)).unwrap();
            let exact = 1.0 / (2.0 * z * (1.0 - z * z).sqrt());
            assert!(
                (n.lower / exact - 1.0).abs() <= 1e-12,
                "ζ = {z}: {} vs {exact}",
                n.lower
            );
            assert!(n.upper >= exact * (1.0 - 1e-15), "ζ = {z}: {n:?}");
            assert!(n.relative_gap() <= CERTIFIED_GAP, "ζ = {z}: {n:?}");
        }
        // ζ ≥ 1/√2: the peak is |G(0)| = 1
        for z in [0.75, 1.0, 3.0] {
            let n = hinf_norm(&second_order(z)).unwrap();
            assert_eq!((n.lower, n.w), (1.0, 0.0), "ζ = {z}");
            assert!(n.relative_gap() <= CERTIFIED_GAP);
        }
    }

    #[test]
    fn unstable_and_axis_poles() {
        let n = hinf_norm(&second_order(-0.1)).unwrap();
        assert!(n.lower.is_infinite() && n.infinite.unwrap().contains("unstable"));
        let l = linf_norm(&second_order(-0.1)).unwrap();
        // |1/(1 − ω² − 0.2jω)| has the same magnitude as for ζ = +0.1
        let exact = 1.0 / (0.2 * 0.99f64.sqrt());
        assert!((l.lower / exact - 1.0).abs() < 1e-12, "{l:?}");
        let l = linf_norm(&second_order(0.0)).unwrap();
        assert!(l.lower.is_infinite() && l.infinite.unwrap().contains("imaginary axis"));
    }
}
