//! Exact linearisation at the equilibria, local stability (seed §2.3, eqs. 2.13–2.14), and the
//! input→output transfer function of each linearisation analysed with the LTI core.
//!
//! **Local stability** from the eigenvalues λ of A = ∂f/∂x (Lyapunov's indirect method):
//! - every Re λ < 0 → *asymptotically stable*;
//! - some Re λ > 0 → *unstable* (this holds whether or not other eigenvalues lie on the axis);
//! - otherwise (no right-half-plane eigenvalue, some on the imaginary axis: the equilibrium is
//!   non-hyperbolic) → *undetermined*: "the local stability of x̄ can not be determined by the
//!   linearized system" (seed §2.3).
//!
//! Where the model declares conserved quantities, each equilibrium (at zero input) also gets
//! the energy–Casimir test ([`crate::nonlinear::energy_casimir()`]), which decides Lyapunov
//! stability of centres; multi-input or multi-output models get every channel's transfer
//! function ([`ChannelTf`]).
//!
//! An eigenvalue is *on* the axis when |Re λ| ≤ 1e-9·|λ| (`AXIS_REL_TOL`, as for poles) or
//! |λ| ≤ 10·n·eps·‖A‖_F (a zero eigenvalue computed as ±1e-17: numerically zero).

use num_complex::Complex64;
use serde::{Serialize, Serializer};

use crate::analysis::{HalfPlane, Mode, half_plane};
use crate::error::Result;
use crate::lti::{StateSpace, TransferFunction};
use crate::nonlinear::energy_casimir::{EnergyCasimir, energy_casimir};
use crate::nonlinear::equilibria::{Equilibrium, EquilibriumMethod, EquilibriumSearch, equilibria};
use crate::nonlinear::system::{DynSystem, SystemInfo, jacobians};
use crate::numeric::eigenvalues;
use crate::numeric::tol::{EPS, ZERO_REL_TOL};
use crate::poly::Root;

/// Local stability of an equilibrium from its linearisation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LocalStability {
    /// All eigenvalues in the open left half plane.
    AsymptoticallyStable,
    /// An eigenvalue in the open right half plane.
    Unstable,
    /// Non-hyperbolic without right-half-plane eigenvalues: the linearisation cannot decide.
    Undetermined,
}

impl LocalStability {
    /// Words: "asymptotically stable", "unstable", "undetermined".
    pub fn words(&self) -> &'static str {
        match self {
            LocalStability::AsymptoticallyStable => "asymptotically stable",
            LocalStability::Unstable => "unstable",
            LocalStability::Undetermined => "undetermined",
        }
    }
}

/// The input→output transfer function of a linearisation, with the core's analysis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LinearizedTf {
    /// Numerator, descending powers of s.
    pub num: Vec<f64>,
    /// Denominator, descending powers of s (det(sI − A)).
    pub den: Vec<f64>,
    /// Poles (roots of `den`) with multiplicities.
    pub poles: Vec<Root>,
    /// Finite zeros with multiplicities.
    pub zeros: Vec<Root>,
    /// ωₙ, ζ, time constant per pole.
    pub modes: Vec<Mode>,
    /// dc gain of the reduced G (`null` when infinite).
    pub dc_gain: Option<f64>,
    /// The transfer function itself.
    #[serde(skip)]
    pub g: TransferFunction,
}

/// The transfer function of one input→output channel of a multi-input or multi-output
/// linearisation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelTf {
    /// Input index j (0-based).
    pub input: usize,
    /// Output index i (0-based).
    pub output: usize,
    /// Input name.
    pub input_name: String,
    /// Output name.
    pub output_name: String,
    /// Numerator, descending powers of s.
    pub num: Vec<f64>,
    /// Denominator det(sI − A), descending powers of s.
    pub den: Vec<f64>,
    /// The transfer function itself.
    #[serde(skip)]
    pub g: TransferFunction,
    /// For display: `g` with coefficient rounding noise removed (terms below
    /// [`ZERO_REL_TOL`] of the denominator's size at the largest pole magnitude) and common
    /// factors cancelled — 2s³/(s⁵ + 1600s³) + 1e-13 s² noise becomes 2/(s² + 1600).
    #[serde(skip)]
    pub reduced: TransferFunction,
}

/// `g` without coefficient rounding noise, in lowest terms (see [`ChannelTf::reduced`]).
fn cleaned(g: &TransferFunction) -> Result<TransferFunction> {
    let r = g
        .poles()?
        .iter()
        .map(|p| p.value.norm())
        .fold(0.0, f64::max);
    let r = if r > 0.0 { r } else { 1.0 };
    let size = |c: &[f64]| {
        let n = c.len();
        c.iter()
            .enumerate()
            .map(|(i, v)| v.abs() * r.powi((n - 1 - i) as i32))
            .sum::<f64>()
    };
    let den = g.den().coeffs();
    let floor = ZERO_REL_TOL * size(den);
    let clean = |c: &[f64]| -> Vec<f64> {
        let n = c.len();
        c.iter()
            .enumerate()
            .map(|(i, v)| {
                if v.abs() * r.powi((n - 1 - i) as i32) <= floor {
                    0.0
                } else {
                    *v
                }
            })
            .collect()
    };
    let num = clean(g.num().coeffs());
    if num.iter().all(|v| *v == 0.0) {
        return TransferFunction::from_descending(&[0.0], &clean(den));
    }
    TransferFunction::from_descending(&num, &clean(den))?
        .factored()?
        .reduced_tf()
}

/// One equilibrium with its linearisation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LinearizedEquilibrium {
    /// The state x̄.
    pub x: Vec<f64>,
    /// The input ū.
    pub u: Vec<f64>,
    /// ∂f/∂x (rows).
    #[serde(rename = "A")]
    pub a: Vec<Vec<f64>>,
    /// ∂f/∂u (rows).
    #[serde(rename = "B")]
    pub b: Vec<Vec<f64>>,
    /// ∂h/∂x (rows).
    #[serde(rename = "C")]
    pub c: Vec<Vec<f64>>,
    /// ∂h/∂u (rows).
    #[serde(rename = "D")]
    pub d: Vec<Vec<f64>>,
    /// Eigenvalues of A (`[re, im]` in JSON), sorted by decreasing real part.
    pub eigenvalues: Vec<Complex64>,
    /// No eigenvalue on the imaginary axis.
    pub hyperbolic: bool,
    /// Local stability.
    pub stability: LocalStability,
    /// Why, in words.
    pub stability_reason: String,
    /// Physically meaningful state.
    pub physical: bool,
    /// ‖f(x̄, ū)‖∞.
    pub residual: f64,
    /// How the equilibrium was found.
    pub method: EquilibriumMethod,
    /// Input→output transfer function (single-input single-output models only).
    pub tf: Option<LinearizedTf>,
    /// Multi-input or multi-output models: the transfer function of every input j → output i
    /// channel (the SISO sub-system with column j of B and row i of C), `StateSpace::to_tf`
    /// per channel. Empty for SISO models (see `tf`) and models without inputs.
    pub channels: Vec<ChannelTf>,
    /// The energy–Casimir test (models with conserved quantities, at ū = 0): decides
    /// Lyapunov stability where the eigenvalues cannot.
    pub energy_casimir: Option<EnergyCasimir>,
    /// The linearisation as a state-space model.
    #[serde(skip)]
    pub ss: StateSpace,
}

/// A model's equilibria and their linearisations (the `linearize` JSON document).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Linearization {
    /// Model name.
    pub model: String,
    /// Parameter values (a JSON object in declaration order).
    #[serde(serialize_with = "params_as_map")]
    pub params: Vec<(String, f64)>,
    /// Every equilibrium found, linearised.
    pub equilibria: Vec<LinearizedEquilibrium>,
}

fn params_as_map<S: Serializer>(p: &[(String, f64)], s: S) -> std::result::Result<S::Ok, S::Error> {
    s.collect_map(p.iter().map(|(k, v)| (k, v)))
}

fn rows(m: &nalgebra::DMatrix<f64>) -> Vec<Vec<f64>> {
    (0..m.nrows())
        .map(|i| m.row(i).iter().copied().collect())
        .collect()
}

/// The linearisation (A, B, C, D) at (x, u) as a [`StateSpace`] — exact Jacobians by AD.
///
/// ```
/// use ltikit::nonlinear::{linearize_at, models::Pendulum};
/// let ss = linearize_at(&Pendulum::default(), &[0.0, 0.0], &[0.0]).unwrap();
/// assert!((ss.a[(1, 0)] + 14.715).abs() < 1e-12); // −3g/(2L)
/// assert!((ss.a[(1, 1)] + 1.5).abs() < 1e-15);    // −3C/(ML²)
/// ```
pub fn linearize_at(sys: &dyn DynSystem, x: &[f64], u: &[f64]) -> Result<StateSpace> {
    let j = jacobians(sys, x, u)?;
    StateSpace::new(j.a, j.b, j.c, j.d)
}

/// Hyperbolicity and local stability from eigenvalues; `scale` is a norm of A (for the
/// absolute zero test).
///
/// ```
/// use num_complex::Complex64;
/// use ltikit::nonlinear::{local_stability, LocalStability};
/// let c = |re, im| Complex64::new(re, im);
/// assert_eq!(local_stability(&[c(-1.0, 2.0), c(-1.0, -2.0)], 1.0).1,
///            LocalStability::AsymptoticallyStable);
/// assert_eq!(local_stability(&[c(0.0, 1.0), c(0.0, -1.0)], 1.0).1, LocalStability::Undetermined);
/// assert_eq!(local_stability(&[c(1e-18, 0.0), c(2.0, 0.0)], 1.0).1, LocalStability::Unstable);
/// ```
pub fn local_stability(eigs: &[Complex64], scale: f64) -> (bool, LocalStability, String) {
    let abs_zero = 10.0 * (eigs.len().max(1) as f64) * EPS * scale;
    let where_is = |l: &Complex64| {
        if l.norm() <= abs_zero {
            HalfPlane::Axis
        } else {
            half_plane(*l)
        }
    };
    let fmt = |l: &Complex64| crate::fmt::fmt_root(*l, 4);
    let rhp: Vec<&Complex64> = eigs
        .iter()
        .filter(|l| where_is(l) == HalfPlane::Right && l.im >= 0.0)
        .collect();
    let axis: Vec<&Complex64> = eigs
        .iter()
        .filter(|l| where_is(l) == HalfPlane::Axis && l.im >= 0.0)
        .collect();
    let hyperbolic = axis.is_empty();
    if let Some(worst) = rhp.iter().max_by(|a, b| a.re.total_cmp(&b.re)) {
        let reason = format!(
            "eigenvalue {} in the right half plane{}",
            fmt(worst),
            if hyperbolic {
                String::new()
            } else {
                " (instability holds although the equilibrium is not hyperbolic)".into()
            }
        );
        return (hyperbolic, LocalStability::Unstable, reason);
    }
    if !hyperbolic {
        let list: Vec<String> = axis
            .iter()
            .map(|l| fmt(&Complex64::new(0.0, l.im)))
            .collect();
        return (
            false,
            LocalStability::Undetermined,
            format!(
                "non-hyperbolic (eigenvalue {} on the imaginary axis): the local stability cannot \
                 be determined by the linearised system",
                list.join(", ")
            ),
        );
    }
    (
        true,
        LocalStability::AsymptoticallyStable,
        if eigs.is_empty() {
            "no states".into()
        } else {
            "every eigenvalue in the open left half plane".into()
        },
    )
}

/// The local stability of `sys` at the point (x, u) from the eigenvalues of the exact Jacobian
/// (no transfer function is formed): (stability, eigenvalues sorted by decreasing real part).
pub fn stability_at(
    sys: &dyn DynSystem,
    x: &[f64],
    u: &[f64],
) -> Result<(LocalStability, Vec<Complex64>)> {
    let ss = linearize_at(sys, x, u)?;
    let eigs = sorted_eigenvalues(&ss)?;
    let (_, stability, _) = local_stability(&eigs, eigen_scale(&ss.a, &eigs));
    Ok((stability, eigs))
}

/// The scale against which an eigenvalue counts as zero ([`local_stability`]): ‖A‖_F (the
/// backward error of a Schur iteration is eps·‖A‖), except for 2×2 matrices, whose eigenvalues
/// come from the trace and an accurately rounded determinant: there the smaller one is known to
/// eps·(|ad| + |bc|)/|λ_big| (for C = 1e200 in the spring–mass–damper, λ = −4e-200 is an
/// eigenvalue, not a zero).
fn eigen_scale(a: &nalgebra::DMatrix<f64>, eigs: &[Complex64]) -> f64 {
    let big = eigs.iter().map(|z| z.norm()).fold(0.0, f64::max);
    if a.nrows() == 2 && big > 0.0 {
        ((a[(0, 0)] * a[(1, 1)]).abs() + (a[(0, 1)] * a[(1, 0)]).abs()) / big
    } else {
        a.norm()
    }
}

fn sorted_eigenvalues(ss: &StateSpace) -> Result<Vec<Complex64>> {
    let mut eigs = eigenvalues(&ss.a)?;
    eigs.sort_by(|p, q| q.re.total_cmp(&p.re).then(q.im.total_cmp(&p.im)));
    Ok(eigs)
}

/// Linearises at one equilibrium: A, B, C, D, eigenvalues, stability and the transfer function.
pub fn analyze_equilibrium(sys: &dyn DynSystem, eq: &Equilibrium) -> Result<LinearizedEquilibrium> {
    let ss = linearize_at(sys, &eq.x, &eq.u)?;
    let eigs = sorted_eigenvalues(&ss)?;
    let scale = eigen_scale(&ss.a, &eigs);
    let (hyperbolic, stability, stability_reason) = local_stability(&eigs, scale);
    let siso = ss.b.ncols() == 1 && ss.c.nrows() == 1;
    let tf = if siso { Some(tf_analysis(&ss)?) } else { None };
    let channels = if siso {
        Vec::new()
    } else {
        channel_tfs(sys, &ss)?
    };
    let energy_casimir = if eq.u.iter().all(|v| *v == 0.0) {
        energy_casimir(sys, &eq.x)?
    } else {
        None
    };
    Ok(LinearizedEquilibrium {
        x: eq.x.clone(),
        u: eq.u.clone(),
        a: rows(&ss.a),
        b: rows(&ss.b),
        c: rows(&ss.c),
        d: rows(&ss.d),
        eigenvalues: eigs,
        hyperbolic,
        stability,
        stability_reason,
        physical: eq.physical,
        residual: eq.residual,
        method: eq.method,
        tf,
        channels,
        energy_casimir,
        ss,
    })
}

/// Every input→output channel's transfer function (a stand-in until MIMO analysis lands in
/// the state-space layer: one SISO `to_tf` per channel).
fn channel_tfs(sys: &dyn DynSystem, ss: &StateSpace) -> Result<Vec<ChannelTf>> {
    let (inputs, outputs) = (sys.input_names(), sys.output_names());
    let name = |names: &[String], k: usize, prefix: &str| {
        names
            .get(k)
            .cloned()
            .unwrap_or_else(|| format!("{prefix}{}", k + 1))
    };
    let mut out = Vec::new();
    for j in 0..ss.b.ncols() {
        for i in 0..ss.c.nrows() {
            let sub = StateSpace::new(
                ss.a.clone(),
                ss.b.columns(j, 1).into_owned(),
                ss.c.rows(i, 1).into_owned(),
                ss.d.view((i, j), (1, 1)).into_owned(),
            )?;
            let g = sub.to_tf()?;
            let reduced = cleaned(&g)?;
            out.push(ChannelTf {
                input: j,
                output: i,
                input_name: name(&inputs, j, "u"),
                output_name: name(&outputs, i, "y"),
                num: g.num().coeffs().to_vec(),
                den: g.den().coeffs().to_vec(),
                g,
                reduced,
            });
        }
    }
    Ok(out)
}

fn tf_analysis(ss: &StateSpace) -> Result<LinearizedTf> {
    let g = ss.to_tf()?;
    let f = g.factored()?;
    Ok(LinearizedTf {
        num: g.num().coeffs().to_vec(),
        den: g.den().coeffs().to_vec(),
        modes: f.modes(),
        dc_gain: f.dc_gain(),
        poles: f.poles().to_vec(),
        zeros: f.zeros().to_vec(),
        g,
    })
}

/// Every equilibrium of `sys` for the constant input `u` (default: the model's operating
/// input), each linearised and classified.
///
/// ```
/// use ltikit::nonlinear::{linearize, EquilibriumSearch, LocalStability, models::Pendulum};
/// let lin = linearize(&Pendulum::default(), None, &EquilibriumSearch::default()).unwrap();
/// assert_eq!(lin.equilibria.len(), 2);
/// assert_eq!(lin.equilibria[0].stability, LocalStability::AsymptoticallyStable); // θ = 0
/// assert_eq!(lin.equilibria[1].stability, LocalStability::Unstable);             // θ = π
/// // torque → angle: 3/(ML²) / (s² + 3C/(ML²) s + 3g/(2L))
/// let tf = lin.equilibria[0].tf.as_ref().unwrap();
/// assert!((tf.den[2] - 14.715).abs() < 1e-12 && (tf.num[0] - 3.0).abs() < 1e-12);
/// ```
pub fn linearize(
    sys: &dyn DynSystem,
    u: Option<&[f64]>,
    search: &EquilibriumSearch,
) -> Result<Linearization> {
    let u = u.map_or_else(|| sys.operating_input(), |u| u.to_vec());
    let eqs = equilibria(sys, &u, search)?;
    let equilibria = eqs
        .iter()
        .map(|e| analyze_equilibrium(sys, e))
        .collect::<Result<Vec<_>>>()?;
    Ok(Linearization {
        model: SystemInfo::model_name(sys),
        params: sys.params(),
        equilibria,
    })
}
