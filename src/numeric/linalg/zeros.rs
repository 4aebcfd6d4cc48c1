//! Invariant and transmission zeros: the finite λ where the system pencil
//! P(λ) = [A − λI  B; C  D] loses rank below its normal rank, for any p×m system (square or
//! not, of full normal rank or not), with the rest of the pencil's Kronecker structure.
//!
//! # Method
//! Emami-Naeini & Van Dooren (1982), "Computation of zeros of linear multivariable systems",
//! Automatica 18(4), as in SLICOT `AB08ND`/`AB08NX`: a structure-preserving reduction by
//! orthogonal transformations that removes the left Kronecker blocks and infinite zeros, the
//! same on the dual for the right blocks, and leaves the regular part: a system with D_f
//! square and invertible, whose finite zeros are the eigenvalues of the n_f×n_f matrix
//! A_f − B_f·D_f⁻¹·C_f — a plain eigenvalue problem, no QZ. One reduction step on
//! (A, B, C, D), n states, m inputs, p outputs:
//! 1. compress the rows of D by a rank-revealing QR: UD = [D₁; 0], D₁ of full row rank ρ, and
//!    UC = [C₁; C₂]; if ρ = p, stop;
//! 2. compress the columns of C₂ (a rank-revealing QR of C₂ᵀ): C₂V = [Y 0], Y of full column
//!    rank μ; apply V as a state similarity, A ← VᵀAV, B ← VᵀB, C ← CV;
//! 3. the first μ states are determined by the outputs C₂ (Y has full column rank), so their
//!    columns are eliminated from the pencil together with μ rows of C₂ (a unimodular row
//!    operation: finite zeros are kept), rows of C₂ beyond μ are zero rows of the pencil
//!    (left minimal indices) and dropped; the state equations of those μ states carry no λ
//!    any more and become outputs: A ← A₂₂, B ← B₂, C ← [A₁₂; C₁₂], D ← [B₁; D₁].
//!
//! Steps repeat until D has full row rank; the same procedure on the dual (Aᵀ, Cᵀ, Bᵀ, Dᵀ)
//! then gives D_f of full column rank too, i.e. square and invertible.
//!
//! **Kronecker structure** ([`KroneckerStructure`]), read off the passes as `AB08NX` does:
//! at pass k (1-based) with p_k rows of D of rank ρ_k and μ_k the rank of C₂, the
//! p_k − ρ_k − μ_k zero rows are minimal indices k − 1 (left ones from the first reduction,
//! right ones from the dual), ρ_k − ρ_{k−1} infinite zeros have order k − 1 (both
//! reductions), and the normal rank of G is ρ of the first reduction's last pass.
//! [`pencil_residual`] gives the evidence for a zero: the (n + r)-th singular value of P(z).
//!
//! **Tolerance**: ranks are decided by [`super::rrqr`] with tol·‖[A B; C D]‖_F, default
//! tol = (n + p)(n + m)·ε (SLICOT `AB08ND`). The system is first scaled by powers of two
//! (A/α, B/β, C/γ, D·α/(βγ); zeros λ = α·λ'), exactly. For a SISO system the number of steps
//! is the relative degree and the product of the compressed norms the first non-zero
//! Markov parameter ([`super::markov`]).
//!
//! A normwise tolerance speaks for every system within that distance, including those with
//! a non-zero where the model has an exact zero: a Markov parameter far below it (the damped
//! lattice's C·A^11·B = 1e-20 with ‖A‖ ≈ 4) is called zero. The factored form of a single
//! channel decides its relative degree componentwise instead and forces this reduction to it
//! (`componentwise.rs`, internal).
//!
//! Invariant zeros include the decoupling zeros (uncontrollable and unobservable modes);
//! [`transmission_zeros`] are the invariant zeros of the minimal realisation.

use nalgebra::DMatrix;
use num_complex::Complex64;

use super::minreal::minimal_realization;
use super::rrqr::rank_revealing_qr;
use super::state_matrix::StateMatrix;
use crate::error::{LtiError, Result};
use crate::numeric::balance::{exponent, ldexp};

/// The finite zeros of a system pencil.
#[derive(Clone, Debug)]
pub struct InvariantZeros {
    /// The finite zeros, each as computed (a multiple zero appears with its scatter).
    pub zeros: Vec<Complex64>,
    /// The distinct zeros with their multiplicities (cluster means, see
    /// [`super::structure`]).
    pub distinct: Vec<(Complex64, usize)>,
    /// Zeros at infinity, counted as n − (number of finite zeros) (for SISO: the relative
    /// degree of the realisation's transfer function).
    pub n_infinite: usize,
    /// The relative rank tolerance of the reduction (of ‖[A B; C D]‖_F after the
    /// power-of-two scaling).
    pub tol: f64,
    /// The rest of the Kronecker structure of the system pencil.
    pub structure: KroneckerStructure,
}

/// The Kronecker structure of the system pencil P(λ) = \[A − λI  B; C  D\] besides its
/// finite zeros, read off the two reductions (see the [module docs](self)).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct KroneckerStructure {
    /// Normal rank of the transfer matrix G(s) = D + C(sI − A)⁻¹B (its rank for all but
    /// finitely many s; the pencil's normal rank is n plus this).
    pub normal_rank: usize,
    /// Orders of the zeros at infinity, ascending, with repetition (SLICOT `AB08ND`'s
    /// `INFZ`; a SISO system of relative degree r ≥ 1 has one, of order r).
    pub infinite_orders: Vec<usize>,
    /// Left Kronecker (row minimal) indices, ascending: p − normal rank of them.
    pub left_indices: Vec<usize>,
    /// Right Kronecker (column minimal) indices, ascending: m − normal rank of them.
    pub right_indices: Vec<usize>,
}

/// A system (A, B, C, D) being reduced.
#[derive(Clone, Debug)]
pub(crate) struct Sys {
    pub a: DMatrix<f64>,
    pub b: DMatrix<f64>,
    pub c: DMatrix<f64>,
    pub d: DMatrix<f64>,
}

impl Sys {
    fn transpose(&self) -> Sys {
        Sys {
            a: self.a.transpose(),
            b: self.c.transpose(),
            c: self.b.transpose(),
            d: self.d.transpose(),
        }
    }
}

/// What one reduction did: per step (ρ, μ, β) with β the (0, 0) entry of the compressed C₂
/// (for SISO the factor between successive Markov parameters), and the rows dropped as zero.
#[derive(Clone, Debug, Default)]
pub(crate) struct ReduceLog {
    pub steps: Vec<(usize, usize, f64)>,
    pub dropped: usize,
    /// Every pass of the loop: (p_k, ρ_k, μ_k), the rows of D, its rank and the rank of C₂
    /// (0 on the last pass, where D has full row rank or no C₂ is left).
    pub passes: Vec<(usize, usize, usize)>,
}

impl ReduceLog {
    /// The Kronecker indices this reduction removed: p_k − ρ_k − μ_k of index k − 1 at pass k
    /// (zero rows of the pencil, SLICOT `AB08NX`'s `KRONL`), ascending.
    fn kronecker_indices(&self) -> Vec<usize> {
        let mut out = Vec::new();
        for (k, &(p, rho, mu)) in self.passes.iter().enumerate() {
            out.extend(std::iter::repeat_n(k, p - rho - mu));
        }
        out
    }

    /// The infinite zeros this reduction met: ρ_k − ρ_{k−1} of order k − 1 at pass k ≥ 2
    /// (`AB08NX`'s `INFZ`), with repetition.
    fn infinite_orders(&self) -> Vec<usize> {
        let mut out = Vec::new();
        for k in 1..self.passes.len() {
            let (rho, prev) = (self.passes[k].1, self.passes[k - 1].1);
            out.extend(std::iter::repeat_n(k, rho.saturating_sub(prev)));
        }
        out
    }

    /// The rank of D when the reduction stopped (the normal rank of the transfer matrix
    /// after the first reduction).
    fn final_rank(&self) -> usize {
        self.passes.last().map_or(0, |&(_, rho, _)| rho)
    }
}

/// Power-of-two scaling of (A, B, C, D): returns the scaled system and (eα, eβ, eγ) with
/// A/2^eα, B/2^eβ, C/2^eγ, D·2^(eα−eβ−eγ).
pub(crate) fn scale_system(s: &Sys) -> (Sys, (i32, i32, i32)) {
    let e = |m: &DMatrix<f64>| exponent(super::norms::norm_1_inf(m)).unwrap_or(0);
    let (ea, eb, ec) = (e(&s.a), e(&s.b), e(&s.c));
    let scaled = Sys {
        a: s.a.map(|x| ldexp(x, -ea)),
        b: s.b.map(|x| ldexp(x, -eb)),
        c: s.c.map(|x| ldexp(x, -ec)),
        d: s.d.map(|x| ldexp(x, ea - eb - ec)),
    };
    (scaled, (ea, eb, ec))
}

/// One full reduction (steps 1–3 of the module docs until D has full row rank).
pub(crate) fn reduce(s: Sys, tol: f64) -> (Sys, ReduceLog) {
    reduce_with(s, |_, _| tol)
}

/// Which block a rank decision of the reduction is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Block {
    /// D (its rank is ρ).
    D,
    /// C₂ (its rank is μ).
    C2,
}

/// [`reduce`] with the absolute rank tolerance of every decision given by `tol(pass, block)`
/// (pass 0-based): the same steps, for a caller that has decided some ranks otherwise (see
/// [`siso_zeros_of_degree`]).
pub(crate) fn reduce_with(mut s: Sys, tol: impl Fn(usize, Block) -> f64) -> (Sys, ReduceLog) {
    let mut log = ReduceLog::default();
    loop {
        let (n, m, p) = (s.a.nrows(), s.b.ncols(), s.c.nrows());
        if p == 0 {
            return (s, log);
        }
        let pass = log.passes.len();
        let f = rank_revealing_qr(&s.d, tol(pass, Block::D));
        let rho = f.rank;
        log.passes.push((p, rho, 0));
        for r in &f.reflectors {
            r.apply_left(&mut s.d, 0..m);
            r.apply_left(&mut s.c, 0..n);
        }
        for j in 0..m {
            for i in rho..p {
                s.d[(i, j)] = 0.0;
            }
        }
        if rho == p {
            return (s, log);
        }
        let c2t = s.c.rows(rho, p - rho).transpose();
        let g = rank_revealing_qr(&c2t, tol(pass, Block::C2));
        let mu = g.rank;
        if let Some(last) = log.passes.last_mut() {
            last.2 = mu;
        }
        for r in &g.reflectors {
            r.apply_left(&mut s.a, 0..n);
            r.apply_right(&mut s.a, 0..n);
            r.apply_left(&mut s.b, 0..m);
            r.apply_right(&mut s.c, 0..p);
        }
        let beta = if mu > 0 { s.c[(rho, 0)] } else { 0.0 };
        log.steps.push((rho, mu, beta));
        log.dropped += p - rho - mu;
        if mu == 0 {
            // C₂ is negligible: its rows are zero rows of the pencil.
            s.c = s.c.rows(0, rho).clone_owned();
            s.d = s.d.rows(0, rho).clone_owned();
            return (s, log);
        }
        let nr = n - mu;
        let mut c_new = DMatrix::zeros(mu + rho, nr);
        c_new
            .view_mut((0, 0), (mu, nr))
            .copy_from(&s.a.view((0, mu), (mu, nr)));
        c_new
            .view_mut((mu, 0), (rho, nr))
            .copy_from(&s.c.view((0, mu), (rho, nr)));
        let mut d_new = DMatrix::zeros(mu + rho, m);
        d_new.view_mut((0, 0), (mu, m)).copy_from(&s.b.rows(0, mu));
        d_new
            .view_mut((mu, 0), (rho, m))
            .copy_from(&s.d.rows(0, rho));
        s = Sys {
            a: s.a.view((mu, mu), (nr, nr)).clone_owned(),
            b: s.b.rows(mu, nr).clone_owned(),
            c: c_new,
            d: d_new,
        };
    }
}

/// Default relative tolerance (n + p)(n + m)·ε of the reduction (SLICOT `AB08ND`).
pub fn default_tol(n: usize, m: usize, p: usize) -> f64 {
    ((n + p) * (n + m)).max(1) as f64 * f64::EPSILON
}

/// Invariant zeros of (A, B, C, D), A n×n, B n×m, C p×n, D p×m, any m and p, with the
/// Kronecker structure of the pencil (see the [module docs](self)); `tol` relative (`None`:
/// (n + p)(n + m)·ε).
///
/// Errors: inconsistent dimensions, non-finite entries, a zero beyond the range of f64, or
/// (not met in the tests) two reductions whose rank decisions leave no regular part.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::invariant_zeros;
/// // Two outputs, one input: G = [1; 1]·(s − 3)/((s + 1)(s + 2)). The zero 3, normal rank 1,
/// // one left index 0 (the two outputs are equal), one infinite zero of order 1.
/// let a = DMatrix::from_row_slice(2, 2, &[-3.0, -2.0, 1.0, 0.0]);
/// let b = DMatrix::from_row_slice(2, 1, &[1.0, 0.0]);
/// let c = DMatrix::from_row_slice(2, 2, &[1.0, -3.0, 1.0, -3.0]);
/// let z = invariant_zeros(&a, &b, &c, &DMatrix::zeros(2, 1), None).unwrap();
/// assert_eq!(z.zeros.len(), 1);
/// assert!((z.zeros[0].re - 3.0).abs() < 1e-14);
/// assert_eq!(z.structure.normal_rank, 1);
/// assert_eq!(z.structure.left_indices, vec![0]);
/// assert_eq!(z.structure.infinite_orders, vec![1]);
/// ```
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::invariant_zeros;
/// // G(s) = (s − 1)/((s + 2)(s + 3)) in controllable canonical form: zero at +1.
/// let a = DMatrix::from_row_slice(2, 2, &[-5.0, -6.0, 1.0, 0.0]);
/// let b = DMatrix::from_row_slice(2, 1, &[1.0, 0.0]);
/// let c = DMatrix::from_row_slice(1, 2, &[1.0, -1.0]);
/// let z = invariant_zeros(&a, &b, &c, &DMatrix::zeros(1, 1), None).unwrap();
/// assert_eq!(z.zeros.len(), 1);
/// assert!((z.zeros[0].re - 1.0).abs() < 1e-14 && z.zeros[0].im == 0.0);
/// assert_eq!(z.n_infinite, 1);
/// ```
pub fn invariant_zeros(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    tol: Option<f64>,
) -> Result<InvariantZeros> {
    let (n, m, p) = super::checks::check_system(a, b, c, d)?;
    let sys = Sys {
        a: a.clone(),
        b: b.clone(),
        c: c.clone(),
        d: d.clone(),
    };
    let (scaled, (ea, _, _)) = scale_system(&sys);
    let norm = super::norms::frobenius(
        scaled
            .a
            .iter()
            .chain(scaled.b.iter())
            .chain(scaled.c.iter())
            .chain(scaled.d.iter()),
    );
    let rel = tol.unwrap_or_else(|| default_tol(n, m, p));
    let abs = rel * norm;
    let (primal, log1) = reduce(scaled, abs);
    let (dual, log2) = reduce(primal.transpose(), abs);
    let f = dual.transpose();
    let (nf, mf, pf) = (f.a.nrows(), f.b.ncols(), f.c.nrows());
    let not_regular = || {
        LtiError::invalid(format!(
            "the system pencil's regular part could not be isolated ({pf} outputs and {mf} inputs left after the reductions, rank tolerance {rel:.1e}): its zeros are not decided"
        ))
    };
    let ldf = f.d.clone().lu();
    let structure = KroneckerStructure {
        normal_rank: log1.final_rank(),
        infinite_orders: {
            let mut v = log1.infinite_orders();
            v.extend(log2.infinite_orders());
            v.sort_unstable();
            v
        },
        left_indices: log1.kronecker_indices(),
        right_indices: log2.kronecker_indices(),
    };
    // After both reductions the pencil is regular: D_f square and invertible (Van Dooren
    // 1979; `AB08ND`'s "Y square invertible"). Anything else is a rank decision that the two
    // passes made inconsistently — said, not guessed.
    if mf != pf || (mf > 0 && !ldf.is_invertible()) {
        return Err(not_regular());
    }
    if nf == 0 {
        return Ok(InvariantZeros {
            zeros: Vec::new(),
            distinct: Vec::new(),
            n_infinite: n,
            tol: rel,
            structure,
        });
    }
    let m_f = if mf == 0 {
        f.a.clone()
    } else {
        let x = ldf.solve(&f.c).ok_or_else(not_regular)?;
        &f.a - &f.b * x
    };
    // the zero dynamics is a matrix of its own: its structure is recognised like a model's
    let st = StateMatrix::recognise(&m_f).eigen_structure()?;
    let back = |z: Complex64| Complex64::new(ldexp(z.re, ea), ldexp(z.im, ea));
    let mut zeros = Vec::with_capacity(nf);
    let mut distinct = Vec::new();
    for cl in &st.clusters {
        zeros.extend(cl.members.iter().map(|&z| back(z)));
        distinct.push((back(cl.value), cl.algebraic));
    }
    if let Some(z) = zeros
        .iter()
        .find(|z| !(z.re.is_finite() && z.im.is_finite()))
    {
        return Err(LtiError::NonFinite {
            what: "a zero (beyond the range of f64)".into(),
            value: z.norm(),
        });
    }
    Ok(InvariantZeros {
        n_infinite: n - zeros.len(),
        zeros,
        distinct,
        tol: rel,
        structure,
    })
}

/// The n − r invariant zeros of a single-input single-output system whose relative degree r
/// was decided elsewhere (by `super::componentwise`, on Markov parameters below this
/// reduction's normwise tolerance): the reduction takes r steps with D taken as zero and C₂ of
/// rank 1 unless exactly zero, and stops with D_f of rank 1 unless exactly zero. The
/// zeros are the eigenvalues of A_f − B_f·D_f⁻¹·C_f as computed (no clustering: the caller
/// refines them). `None` when the reduction cannot take those steps (an exactly zero C₂ or
/// D_f: r is not the realisation's) or r > n.
pub(crate) fn siso_zeros_of_degree(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    r: usize,
) -> Result<Option<Vec<Complex64>>> {
    let n = a.nrows();
    if r == 0 || r > n || b.ncols() != 1 || c.nrows() != 1 {
        return Ok(None);
    }
    let sys = Sys {
        a: a.clone(),
        b: b.clone(),
        c: c.clone(),
        d: DMatrix::zeros(1, 1),
    };
    let (scaled, (ea, _, _)) = scale_system(&sys);
    let (f, log) = reduce_with(scaled, |pass, block| match block {
        Block::D if pass < r => f64::INFINITY,
        _ => 0.0,
    });
    let steps_ok =
        log.steps.len() == r && log.steps.iter().all(|&(rho, mu, _)| (rho, mu) == (0, 1));
    if !steps_ok || f.d.shape() != (1, 1) || f.d[(0, 0)] == 0.0 {
        return Ok(None);
    }
    let nf = f.a.nrows();
    if nf == 0 {
        return Ok(Some(Vec::new()));
    }
    let m_f = &f.a - &f.b * (&f.c / f.d[(0, 0)]);
    if m_f.iter().any(|x| !x.is_finite()) {
        return Ok(None);
    }
    let ev = super::schur::schur_eigenvalues(&m_f)?;
    Ok(Some(
        ev.iter()
            .map(|z| Complex64::new(ldexp(z.re, ea), ldexp(z.im, ea)))
            .collect(),
    ))
}

/// Transmission zeros: the invariant zeros of the [minimal realisation](minimal_realization)
/// (decoupling zeros removed). `tol` is used for both steps.
///
/// ```
/// use nalgebra::DMatrix;
/// use ltikit::numeric::linalg::{invariant_zeros, transmission_zeros};
/// // (s + 1)/((s + 1)(s + 2)): the invariant zero −1 is a decoupling zero.
/// let a = DMatrix::from_row_slice(2, 2, &[-3.0, -2.0, 1.0, 0.0]);
/// let b = DMatrix::from_row_slice(2, 1, &[1.0, 0.0]);
/// let c = DMatrix::from_row_slice(1, 2, &[1.0, 1.0]);
/// let d = DMatrix::zeros(1, 1);
/// assert_eq!(invariant_zeros(&a, &b, &c, &d, None).unwrap().zeros.len(), 1);
/// assert!(transmission_zeros(&a, &b, &c, &d, None).unwrap().zeros.is_empty());
/// ```
pub fn transmission_zeros(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    tol: Option<f64>,
) -> Result<InvariantZeros> {
    let min = minimal_realization(a, b, c, d, tol)?;
    invariant_zeros(&min.a, &min.b, &min.c, &min.d, tol)
}

/// The residual of a zero z of (A, B, C, D) whose transfer matrix has normal rank r: the
/// (n + r)-th singular value of the Rosenbrock matrix P(z) = \[A − zI  B; C  D\] relative to
/// ‖P(z)‖_F. P has rank n + r for all but finitely many λ, and below it exactly at the
/// zeros: a value near ε says z is a zero of a system within that relative distance
/// (backward error), a value near 1 that it is not. O((n + p)(n + m)²) by a complex SVD.
///
/// Errors: inconsistent dimensions, non-finite entries or z, r > min(p, m), an SVD that does
/// not converge.
///
/// ```
/// use nalgebra::DMatrix;
/// use num_complex::Complex64;
/// use ltikit::numeric::linalg::zeros::pencil_residual;
/// // G(s) = (s − 1)/((s + 2)(s + 3)): the zero 1 has a residual near ε; at 2 the smallest
/// // singular value of P(2) is 0.0416 of σ = (9.29, 2.59, 0.0416), ‖P(2)‖_F = 9.64 (numpy).
/// let a = DMatrix::from_row_slice(2, 2, &[-5.0, -6.0, 1.0, 0.0]);
/// let b = DMatrix::from_row_slice(2, 1, &[1.0, 0.0]);
/// let c = DMatrix::from_row_slice(1, 2, &[1.0, -1.0]);
/// let d = DMatrix::zeros(1, 1);
/// assert!(pencil_residual(&a, &b, &c, &d, Complex64::new(1.0, 0.0), 1).unwrap() < 1e-15);
/// let r2 = pencil_residual(&a, &b, &c, &d, Complex64::new(2.0, 0.0), 1).unwrap();
/// assert!((r2 - 0.0043175).abs() < 1e-6);
/// ```
pub fn pencil_residual(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    z: Complex64,
    normal_rank: usize,
) -> Result<f64> {
    let (n, m, p) = super::checks::check_system(a, b, c, d)?;
    if !(z.re.is_finite() && z.im.is_finite()) {
        return Err(LtiError::NonFinite {
            what: "the zero whose residual is asked".into(),
            value: z.norm(),
        });
    }
    if normal_rank > m.min(p) {
        return Err(LtiError::invalid(format!(
            "a normal rank of {normal_rank} exceeds min(outputs, inputs) = {}",
            m.min(p)
        )));
    }
    let k = n + normal_rank;
    if k == 0 {
        return Ok(0.0);
    }
    let pz = DMatrix::<Complex64>::from_fn(n + p, n + m, |i, j| {
        let x = match (i < n, j < n) {
            (true, true) => a[(i, j)],
            (true, false) => b[(i, j - n)],
            (false, true) => c[(i - n, j)],
            (false, false) => d[(i - n, j - n)],
        };
        if i == j && i < n {
            Complex64::new(x, 0.0) - z
        } else {
            Complex64::new(x, 0.0)
        }
    });
    let norm = pz.norm();
    if norm == 0.0 {
        return Ok(0.0);
    }
    let scaled = pz.unscale(norm);
    let svd = scaled
        .try_svd(
            false,
            false,
            f64::EPSILON,
            crate::numeric::lstsq::MAX_SVD_ITER,
        )
        .ok_or_else(|| LtiError::invalid("the SVD of the Rosenbrock matrix did not converge"))?;
    let mut s: Vec<f64> = svd.singular_values.iter().copied().collect();
    s.sort_by(|x, y| y.total_cmp(x));
    Ok(s.get(k - 1).copied().unwrap_or(0.0))
}
