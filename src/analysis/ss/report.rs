//! State-space analysis of a whole model (SISO or MIMO), computed once: eigenvalues with their
//! multiplicity structure, controllability and observability, the minimal realisation, zeros,
//! the dc-gain matrix, internal and per-channel BIBO stability, and the modes with their
//! shapes. No coefficients are formed; everything comes from the kernels of
//! [`crate::numeric::linalg`].
//!
//! Eigenvalues follow the rule of the factored core (`Factored::from_state_space`): one
//! within its cluster radius r = ν·(64·n·ε)^(1/m) of 0 ([`crate::numeric::linalg::structure`],
//! m its algebraic multiplicity, ν the scale of A's Schur form) is made exactly 0, and one whose
//! real part is within r of 0 is put exactly on the imaginary axis — A is within ε‖A‖ of a
//! matrix with that eigenvalue there, and the undamped lattice's ±jωₖ would otherwise carry
//! real parts of ±1e-16 (a damping ratio of 1e-17, a time constant of 1e16 s). Eigenvalues,
//! modes, internal stability and the per-channel BIBO stability all read the snapped values.

use nalgebra::DMatrix;
use num_complex::Complex64;
use serde::Serialize;

use crate::analysis::discrete::{circle_side, equivalent_s};
use crate::error::Result;
use crate::fmt::fmt_root;
use crate::lti::StateSpace;
use crate::numeric::linalg::structure::radius;
use crate::numeric::linalg::{EigenCluster, StateMatrix, eigen_structure};
use crate::numeric::linalg::{
    controllability_staircase, invariant_zeros, minimal_realization, observability_staircase,
    transmission_zeros, zeros::pencil_residual,
};
use crate::poly::{HalfPlane, half_plane};

/// Largest order for which `ltikit analyze` adds the whole-model analysis to its report (the
/// method itself takes any order). The analysis is O(n³) with large constants — eigenvectors,
/// two staircases, the minimal realisation, the invariant zeros of a square system and a
/// minimal realisation with its eigenvalues per channel: measured (release build) 0.17 s for
/// the 256-state lattice, up to 2.3 s for random dense 256-state 2×2 plants (the invariant
/// zeros dominate), 1.1 s for the 512-state lattice and 35 s for a random 512-state 2×2 plant.
pub const MAX_ANALYSIS_STATES: usize = crate::limits::MAX_ANALYSIS_STATES;

/// One distinct eigenvalue of A.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SsEigenvalue {
    /// The eigenvalue (a cluster mean for a multiple one).
    pub value: Complex64,
    /// Algebraic multiplicity.
    pub algebraic: usize,
    /// Geometric multiplicity (independent eigenvectors).
    pub geometric: usize,
    /// True when algebraic = geometric (no Jordan block).
    pub semisimple: bool,
}

/// A mode of A (one per real eigenvalue or conjugate pair, upper member), with its shapes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SsMode {
    /// The eigenvalue λ.
    pub value: Complex64,
    /// Its algebraic multiplicity (the number of shapes is the geometric one).
    pub algebraic: usize,
    /// Natural frequency |λ| (rad/s).
    pub wn: f64,
    /// Damping ratio −Re λ/|λ| (NaN at λ = 0).
    pub zeta: f64,
    /// Time constant −1/Re λ (s); `None` unless Re λ < 0.
    pub tau: Option<f64>,
    /// Mode shapes: an orthonormal basis of the eigenspace (one unit-norm column per
    /// independent eigenvector), `shapes[j][i]` = component i of vector j.
    #[serde(skip)]
    pub shapes: Vec<Vec<Complex64>>,
    /// ‖Av − λv‖₂/(‖A‖·‖v‖₂) of each shape.
    pub residuals: Vec<f64>,
}

/// Rank of a staircase and the tolerance it used.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StaircaseRank {
    /// Dimension of the controllable (observable) subspace.
    pub rank: usize,
    /// The absolute rank tolerance (n²·ε·‖[A B]‖_F, resp. ‖[Aᵀ Cᵀ]‖_F).
    pub tol: f64,
}

/// The dc gain of one channel.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DcGain {
    /// G(0) = D − C·A⁻¹·B (finite).
    Finite(f64),
    /// The channel's minimal realisation has an eigenvalue at 0 (within its cluster radius
    /// ν·(64·n·ε)^(1/m) of 0, see [`crate::numeric::linalg::structure`], or A singular to the
    /// LU solve): |G(s)| → ∞ as s → 0.
    Infinite,
}

/// Largest order for which each invariant zero's residual is computed (one complex SVD of
/// the (n + p)×(n + m) Rosenbrock matrix per distinct zero, O(n³) each).
pub const MAX_RESIDUAL_STATES: usize = 64;

/// The Kronecker structure of the system pencil besides its finite zeros, with the evidence
/// for the zeros (see [`crate::numeric::linalg::zeros`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ZeroStructure {
    /// Normal rank of the transfer matrix (its rank at all but finitely many s).
    pub normal_rank: usize,
    /// Orders of the zeros at infinity, ascending, with repetition.
    pub infinite_orders: Vec<usize>,
    /// Left Kronecker (row minimal) indices, ascending (p − normal rank of them).
    pub left_indices: Vec<usize>,
    /// Right Kronecker (column minimal) indices, ascending (m − normal rank of them).
    pub right_indices: Vec<usize>,
    /// Per entry of `invariant_zeros`: the (n + r)-th singular value of the Rosenbrock matrix
    /// \[A − zI B; C D\] at the zero over its Frobenius norm (r the normal rank; ≈ ε for a
    /// zero, see [`crate::numeric::linalg::zeros::pencil_residual`]); empty beyond
    /// [`MAX_RESIDUAL_STATES`] states.
    pub residuals: Vec<f64>,
}

/// The state-space analysis of a model (see the [module docs](self)).
#[derive(Debug, Clone, Serialize)]
pub struct SsAnalysis {
    /// States, inputs, outputs.
    pub n: usize,
    /// Number of inputs.
    pub m: usize,
    /// Number of outputs.
    pub p: usize,
    /// Distinct eigenvalues of A with multiplicities, sorted as polynomial roots (decreasing
    /// real part, then decreasing imaginary part).
    pub eigenvalues: Vec<SsEigenvalue>,
    /// Controllability staircase of (A, B).
    pub controllability: StaircaseRank,
    /// Observability staircase of (A, C).
    pub observability: StaircaseRank,
    /// Order of the minimal realisation of the whole model.
    pub minimal_order: usize,
    /// Eigenvalues of the removed uncontrollable part (with repetition; each one that lies
    /// within twice its cluster radius of an eigenvalue of A is given that eigenvalue's value,
    /// so that the lists read alike).
    pub uncontrollable_modes: Vec<Complex64>,
    /// Eigenvalues of the removed unobservable (controllable) part (as the uncontrollable
    /// ones).
    pub unobservable_modes: Vec<Complex64>,
    /// Invariant zeros, with multiplicities: the finite zeros of the regular part of the
    /// system pencil \[A − λI B; C D\] for any numbers of inputs and outputs (square or not,
    /// of full normal rank or not); `None` when not computable, with the reason in
    /// `invariant_zeros_note`.
    pub invariant_zeros: Option<Vec<(Complex64, usize)>>,
    /// Why `invariant_zeros` is `None`.
    pub invariant_zeros_note: Option<String>,
    /// The rest of the pencil's Kronecker structure (normal rank, infinite zeros, minimal
    /// indices) and each zero's residual; `None` with `invariant_zeros`.
    pub zero_structure: Option<ZeroStructure>,
    /// `dc_gain[j][i]`: the dc gain from input i to output j.
    pub dc_gain: Vec<Vec<DcGain>>,
    /// Internal stability: every eigenvalue of A in the open left half plane.
    pub internally_stable: bool,
    /// Why (the first eigenvalue that decides it).
    pub internal_reason: String,
    /// `bibo_stable[j][i]`: every pole of the channel's minimal realisation in the open left
    /// half plane.
    pub bibo_stable: Vec<Vec<bool>>,
    /// The modes with their shapes, in the order of `eigenvalues`.
    pub modes: Vec<SsMode>,
}

impl StateSpace {
    /// The state-space analysis of the whole model, computed once (see [`SsAnalysis`]).
    ///
    /// Errors: those of the kernels (practically never for a finite model).
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::StateSpace;
    /// // Two decoupled first-order lags, the second input reaching only the second state.
    /// let ss = StateSpace::new(
    ///     DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -2.0]),
    ///     DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 1.0]),
    ///     DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 4.0]),
    ///     DMatrix::zeros(2, 2),
    /// ).unwrap();
    /// let r = ss.analysis().unwrap();
    /// assert!(r.internally_stable);
    /// assert_eq!(r.minimal_order, 2);
    /// use ltikit::analysis::ss::DcGain;
    /// assert!(matches!(r.dc_gain[1][1], DcGain::Finite(g) if (g - 2.0).abs() < 1e-15));
    /// assert_eq!(r.modes.len(), 2);
    /// ```
    pub fn analysis(&self) -> Result<SsAnalysis> {
        let (n, m, p) = (self.order(), self.b.ncols(), self.c.nrows());
        let (a, b, c, d) = (&self.a, &self.b, &self.c, &self.d);
        // the model's A, recognised once (a second-order A answers from its modes)
        let (mut sets, st) = StateMatrix::recognise(a).eigenvectors()?;
        let scale = st.scale;
        // An eigenvalue within its cluster radius of 0 is 0 for a matrix within ε‖A‖ of A
        // (an integrator, a free translation), one with a real part within it is on the axis
        // (an undamped oscillator): see the module docs.
        for s in &mut sets {
            s.value = snap(s.value, s.algebraic, n, scale);
        }
        sets.sort_by(|x, y| {
            y.value
                .re
                .total_cmp(&x.value.re)
                .then(y.value.im.total_cmp(&x.value.im))
        });
        let eigenvalues: Vec<SsEigenvalue> = sets
            .iter()
            .map(|s| SsEigenvalue {
                value: s.value,
                algebraic: s.algebraic,
                geometric: s.vectors.ncols(),
                semisimple: s.vectors.ncols() == s.algebraic,
            })
            .collect();
        let ctrl = controllability_staircase(a, b, c, None, false)?;
        let obs = observability_staircase(a, b, c, None, false)?;
        let min = minimal_realization(a, b, c, d, None)?;
        let (invariant, invariant_note, zero_structure) = if n == 0 && m.min(p) == 0 {
            (Some(Vec::new()), None, None)
        } else {
            // A zero structure that cannot be decided is a property of the model, not a
            // failure of the rest of the analysis: said, not raised.
            match invariant_zeros(a, b, c, d, None) {
                // the eigenvalue rule for the zeros too (a zero at the origin computed as
                // 1e-31, the undamped lattice's zeros with real parts of 1e-16)
                Ok(z) => {
                    let mut zs: Vec<(Complex64, usize)> = z
                        .distinct
                        .into_iter()
                        .map(|(v, k)| (snap(v, k, n, scale), k))
                        .collect();
                    // sorted as roots: decreasing real, then imaginary part
                    zs.sort_by(|x, y| y.0.re.total_cmp(&x.0.re).then(y.0.im.total_cmp(&x.0.im)));
                    let k = &z.structure;
                    let residuals = if n <= MAX_RESIDUAL_STATES {
                        zs.iter()
                            .map(|&(v, _)| pencil_residual(a, b, c, d, v, k.normal_rank))
                            .collect::<Result<Vec<f64>>>()?
                    } else {
                        Vec::new()
                    };
                    let structure = ZeroStructure {
                        normal_rank: k.normal_rank,
                        infinite_orders: k.infinite_orders.clone(),
                        left_indices: k.left_indices.clone(),
                        right_indices: k.right_indices.clone(),
                        residuals,
                    };
                    (Some(zs), None, Some(structure))
                }
                Err(e) => (None, Some(e.to_string()), None),
            }
        };
        let removed = |v: &[Complex64]| -> Vec<Complex64> {
            v.iter()
                .map(|&z| {
                    let near = eigenvalues
                        .iter()
                        .map(|e| ((z - e.value).norm(), e))
                        .min_by(|x, y| x.0.total_cmp(&y.0));
                    match near {
                        Some((dist, e)) if dist <= 2.0 * radius(e.algebraic, n, scale) => e.value,
                        _ => snap(z, 1, n, scale),
                    }
                })
                .collect()
        };
        let uncontrollable_modes = removed(&min.uncontrollable);
        let unobservable_modes = removed(&min.unobservable);
        let dt = self.domain.dt();
        let (internally_stable, internal_reason) = internal_stability(&eigenvalues, dt.is_some());
        let mut dc_gain = vec![vec![DcGain::Infinite; m]; p];
        let mut bibo_stable = vec![vec![true; m]; p];
        for j in 0..p {
            for i in 0..m {
                let ch = self.channel_matrices(i, j);
                let mr = minimal_realization(&ch.0, &ch.1, &ch.2, &ch.3, None)?;
                let (at_origin, stable) = if mr.order() == 0 {
                    (false, true)
                } else {
                    // The channel's A comes from A by orthogonal similarities: its rounding
                    // is relative to ‖A‖, so are the tests for an eigenvalue at 0 and on the
                    // axis (the rule of the module docs).
                    let st = eigen_structure(&mr.a)?;
                    let r = |c: &EigenCluster| radius(c.algebraic, n, scale.max(st.scale));
                    match dt {
                        // in z: an eigenvalue at 1 makes the dc gain infinite; stable inside
                        // the unit circle
                        Some(_) => (
                            st.clusters
                                .iter()
                                .any(|c| (c.value - Complex64::new(1.0, 0.0)).norm() <= r(c)),
                            st.clusters.iter().all(|c| {
                                c.value.norm() < 1.0 - r(c)
                                    && circle_side(c.value) == HalfPlane::Left
                            }),
                        ),
                        None => (
                            st.clusters.iter().any(|c| c.value.norm() <= r(c)),
                            st.clusters.iter().all(|c| {
                                c.value.re < -r(c) && half_plane(c.value) == HalfPlane::Left
                            }),
                        ),
                    }
                };
                dc_gain[j][i] = if at_origin {
                    DcGain::Infinite
                } else if dt.is_some() {
                    // G(1) = D + C (I − A)⁻¹ B
                    let eye = DMatrix::<f64>::identity(mr.a.nrows(), mr.a.nrows());
                    dc_of(&(&mr.a - eye), &mr.b, &mr.c, &mr.d)
                } else {
                    dc_of(&mr.a, &mr.b, &mr.c, &mr.d)
                };
                bibo_stable[j][i] = stable;
            }
        }
        let modes =
            sets.iter()
                .filter(|s| s.value.im >= 0.0)
                .map(|s| {
                    // in z, the equivalent s = ln(z)/T (MATLAB `damp`); z = 0 has none
                    let l = match dt {
                        Some(dt) => equivalent_s(s.value, dt)
                            .unwrap_or(Complex64::new(f64::NEG_INFINITY, 0.0)),
                        None => s.value,
                    };
                    SsMode {
                        value: s.value,
                        algebraic: s.algebraic,
                        wn: l.norm(),
                        // 0 − Re λ: an eigenvalue on the axis has ζ = +0, not −0.
                        zeta: if l.re == f64::NEG_INFINITY {
                            1.0 // z = 0: a deadbeat mode
                        } else if l.norm() > 0.0 {
                            (0.0 - l.re) / l.norm()
                        } else {
                            f64::NAN
                        },
                        tau: (l.re < 0.0).then(|| -1.0 / l.re),
                        shapes: s
                            .vectors
                            .column_iter()
                            .map(|v| v.iter().copied().collect())
                            .collect(),
                        residuals: s.residuals.clone(),
                    }
                })
                .collect();
        Ok(SsAnalysis {
            n,
            m,
            p,
            eigenvalues,
            // The minimal realisation's eigenvector test can find a mode that the
            // staircases' block-wise rank decisions kept (numeric::linalg::minreal): each
            // removed mode is a genuinely uncontrollable (unobservable) one, so the ranks
            // stated never exceed what the removed modes leave.
            controllability: StaircaseRank {
                rank: ctrl.dim.min(min.n_controllable),
                tol: ctrl.abs_tol,
            },
            observability: StaircaseRank {
                rank: obs.dim.min(n.saturating_sub(min.unobservable.len())),
                tol: obs.abs_tol,
            },
            minimal_order: min.order(),
            uncontrollable_modes,
            unobservable_modes,
            invariant_zeros: invariant,
            invariant_zeros_note: invariant_note,
            zero_structure,
            dc_gain,
            internally_stable,
            internal_reason,
            bibo_stable,
            modes,
        })
    }

    /// Transmission zeros of the channel from input `input` to output `output` (0-based),
    /// with multiplicities: the invariant zeros of the channel's minimal realisation.
    ///
    /// Errors: a channel that does not exist.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use ltikit::StateSpace;
    /// // G(s) = (s − 1)/((s + 2)(s + 3)) in controllable canonical form.
    /// let ss = StateSpace::new(
    ///     DMatrix::from_row_slice(2, 2, &[-5.0, -6.0, 1.0, 0.0]),
    ///     DMatrix::from_row_slice(2, 1, &[1.0, 0.0]),
    ///     DMatrix::from_row_slice(1, 2, &[1.0, -1.0]),
    ///     DMatrix::zeros(1, 1),
    /// ).unwrap();
    /// let z = ss.channel_zeros(0, 0).unwrap();
    /// assert!((z[0].0.re - 1.0).abs() < 1e-14 && z[0].1 == 1);
    /// assert!(ss.channel_zeros(1, 0).is_err());
    /// ```
    pub fn channel_zeros(&self, input: usize, output: usize) -> Result<Vec<(Complex64, usize)>> {
        if input >= self.b.ncols() || output >= self.c.nrows() {
            return Err(crate::error::LtiError::invalid(format!(
                "channel input {} → output {} does not exist: the model has inputs 1…{} and outputs 1…{}",
                input + 1,
                output + 1,
                self.b.ncols(),
                self.c.nrows()
            )));
        }
        let (a, b, c, d) = self.channel_matrices(input, output);
        Ok(transmission_zeros(&a, &b, &c, &d, None)?.distinct)
    }

    /// (A, B column `input`, C row `output`, D entry); the indices must exist.
    fn channel_matrices(
        &self,
        input: usize,
        output: usize,
    ) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>, DMatrix<f64>) {
        (
            self.a.clone(),
            self.b.columns(input, 1).clone_owned(),
            self.c.rows(output, 1).clone_owned(),
            self.d.view((output, input), (1, 1)).clone_owned(),
        )
    }
}

/// The eigenvalue rule of the module docs: exactly 0 within the cluster radius of 0, exactly
/// on the imaginary axis when the real part is within it.
fn snap(v: Complex64, algebraic: usize, n: usize, scale: f64) -> Complex64 {
    crate::numeric::linalg::structure::snap(v, radius(algebraic, n, scale))
}

/// D − C·A⁻¹·B of a SISO minimal realisation, `Infinite` when A is singular to the solve.
fn dc_of(a: &DMatrix<f64>, b: &DMatrix<f64>, c: &DMatrix<f64>, d: &DMatrix<f64>) -> DcGain {
    let d0 = d.get((0, 0)).copied().unwrap_or(0.0);
    if a.nrows() == 0 {
        return DcGain::Finite(d0);
    }
    let Some(x) = a.clone().lu().solve(b) else {
        return DcGain::Infinite;
    };
    match (c * x).get((0, 0)) {
        Some(v) if (d0 - v).is_finite() => DcGain::Finite(d0 - v),
        _ => DcGain::Infinite,
    }
}

/// Internal stability from the eigenvalues: all in the open left half plane; an eigenvalue on
/// the axis makes A marginally stable when semisimple and unstable when defective.
fn internal_stability(ev: &[SsEigenvalue], discrete: bool) -> (bool, String) {
    let side = |v: Complex64| {
        if discrete {
            circle_side(v)
        } else {
            half_plane(v)
        }
    };
    let (outside, on, inside) = if discrete {
        (
            "outside the unit circle",
            "on the unit circle",
            "strictly inside the unit circle",
        )
    } else {
        (
            "in the right half plane",
            "on the imaginary axis",
            "in the open left half plane",
        )
    };
    if let Some(e) = ev.iter().find(|e| side(e.value) == HalfPlane::Right) {
        return (
            false,
            format!("unstable: eigenvalue {} {outside}", fmt_root(e.value, 6)),
        );
    }
    if let Some(e) = ev
        .iter()
        .find(|e| side(e.value) == HalfPlane::Axis && !e.semisimple)
    {
        return (
            false,
            format!(
                "unstable: eigenvalue {} {on} is defective (a Jordan block of algebraic multiplicity {}, geometric {}): the state grows like a polynomial in {}",
                fmt_root(e.value, 6),
                e.algebraic,
                e.geometric,
                if discrete { "k" } else { "t" }
            ),
        );
    }
    if let Some(e) = ev.iter().find(|e| side(e.value) == HalfPlane::Axis) {
        return (
            false,
            format!(
                "marginally stable: eigenvalue {} {on} (semisimple{}), none {outside}",
                fmt_root(e.value, 6),
                if e.algebraic > 1 {
                    format!(", multiplicity {}", e.algebraic)
                } else {
                    String::new()
                }
            ),
        );
    }
    (true, format!("stable: every eigenvalue of A {inside}"))
}
