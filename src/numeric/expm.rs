//! Matrix exponential by scaling and squaring with a Padé approximant, overflow-safe.
//!
//! # Method
//! Al-Mohy & Higham's 2009 algorithm ("A new scaling and squaring algorithm for the matrix
//! exponential", SIAM J. Matrix Anal. Appl. 31(3), Algorithm 5.1, without balancing): the Padé
//! degree m ∈ {3, 5, 7, 9, 13} and the number of squarings s are chosen from
//! dₖ = ‖Aᵏ‖₁^(1/k) (exact norms of the powers; a test dₖ ≤ θ is first tried on the bound
//! from the norms at hand, ‖A⁶‖ ≤ ‖A⁴‖·‖A²‖ and the like, and the power is formed only when
//! the bound does not settle it — the same decisions as with the exact norms) and the
//! backward-error correction ℓ(A, m) from ‖|A|^(2m+1)‖₁, then e^A = r₁₃(A/2ˢ)^(2ˢ). In the
//! degree-13 branch with s > 0 the powers of A/2ˢ are those of A scaled by 2^(−ks), not new
//! products.
//!
//! What is added to the published algorithm, and why (nalgebra 0.35's `exp()`, which follows
//! the same paper, turns an overflowing ‖A⁸‖ into s = 2⁶⁴ squarings and panics on a singular
//! denominator):
//! - **Scaling front end.** When ‖A‖₁ exceeds 2¹⁶·θ₁₃, A is first divided by an exact power of
//!   two 2^s₀ that brings the norm to ≤ 2¹⁶·θ₁₃; the powers A², …, A¹⁰ and the norms then
//!   cannot overflow. Every norm is computed with a power-of-two scale as well.
//! - **Bounded squarings.** s ≤ s₀ + 16 + ℓ, and s₀ ≤ 1035 because ‖A‖₁ < 200·f64::MAX; the
//!   cap [`MAX_SQUARINGS`] makes the bound explicit. The squaring loop stops early when the
//!   iterate is exactly zero or exactly idempotent (X·X = X bitwise: later squarings cannot
//!   change it), and with an error at the first non-finite entry (e^A overflows).
//! - **Errors, not panics**: a singular Padé denominator (impossible in exact arithmetic for
//!   the chosen θ) is an [`LtiError::NoConvergence`].
//!
//! Accuracy (measured against 50-digit references; `tests/robust_numeric.rs`): rotations,
//! Jordan blocks, stiff diagonals and the state-space matrices of the textbook plants to
//! ~1e-15 relative, as nalgebra's `exp()` where that terminates.

use nalgebra::DMatrix;

use crate::error::{LtiError, Result};
use crate::numeric::balance::{exponent_range, ldexp};

/// Upper bound on the number of squarings (never reached for finite input; see the module
/// docs).
pub const MAX_SQUARINGS: u32 = 1100;

/// θₘ: the largest ‖A‖ (in the sense of the dₖ) for which the degree-m Padé approximant
/// has backward error ≤ 2⁻⁵³ (Al-Mohy & Higham 2009, Table 3.1; θ₁₃ from §5).
const THETA_3: f64 = 1.495_585_217_958_292e-2;
const THETA_5: f64 = 2.539_398_330_063_23e-1;
const THETA_7: f64 = 9.504_178_996_162_932e-1;
const THETA_9: f64 = 2.097_847_961_257_068e0;
const THETA_13: f64 = 4.25;

/// log₂ of the norm headroom before the scaling front end divides A by a power of two.
/// With ‖A‖₁ ≤ 2^98 the norms of A², …, A¹⁰ stay below 2^990: no overflow.
const PRESCALE_BITS: i32 = 96;

/// Padé coefficients b₀ … bₘ of r_m(x) = p_m(x)/p_m(−x) (Higham 2005, eq. 2.5: exact
/// integers).
const B3: [f64; 4] = [120.0, 60.0, 12.0, 1.0];
const B5: [f64; 6] = [30240.0, 15120.0, 3360.0, 420.0, 30.0, 1.0];
const B7: [f64; 8] = [
    17_297_280.0,
    8_648_640.0,
    1_995_840.0,
    277_200.0,
    25_200.0,
    1_512.0,
    56.0,
    1.0,
];
const B9: [f64; 10] = [
    17_643_225_600.0,
    8_821_612_800.0,
    2_075_673_600.0,
    302_702_400.0,
    30_270_240.0,
    2_162_160.0,
    110_880.0,
    3_960.0,
    90.0,
    1.0,
];
const B13: [f64; 14] = [
    64_764_752_532_480_000.0,
    32_382_376_266_240_000.0,
    7_771_770_303_897_600.0,
    1_187_353_796_428_800.0,
    129_060_195_264_000.0,
    10_559_470_521_600.0,
    670_442_572_800.0,
    33_522_128_640.0,
    1_323_241_920.0,
    40_840_800.0,
    960_960.0,
    16_380.0,
    182.0,
    1.0,
];

/// e^M for a square, finite matrix. See the [module docs](self) for the method.
///
/// Errors: a non-square or non-finite matrix, an exponential that overflows
/// ([`LtiError::NonFinite`]).
///
/// ```
/// use nalgebra::DMatrix;
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, 0.0]);
/// let e = ltikit::numeric::expm(&(a * std::f64::consts::FRAC_PI_2)).unwrap();
/// assert!((e[(0, 1)] - 1.0).abs() < 1e-14);
/// // A pole at −1e200 (nalgebra's exp() never returns on the 2×2 version of this).
/// let stiff = DMatrix::from_row_slice(2, 2, &[-1e200, 0.0, 1.0, 0.0]);
/// let e = ltikit::numeric::expm(&stiff).unwrap();
/// assert_eq!(e[(0, 0)], 0.0);
/// assert!((e[(1, 0)] - 1e-200).abs() < 1e-214);
/// ```
pub fn expm(m: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    if !m.is_square() {
        return Err(LtiError::invalid(format!(
            "matrix exponential needs a square matrix, got {}×{}",
            m.nrows(),
            m.ncols()
        )));
    }
    if let Some(x) = m.iter().find(|x| !x.is_finite()) {
        return Err(LtiError::NonFinite {
            what: "a matrix entry".into(),
            value: *x,
        });
    }
    let e = match m.nrows() {
        0 => return Ok(m.clone()),
        1 => m.map(f64::exp),
        // e^A = (e^{Aᵀ})ᵀ: a lower triangular A gets the exact-diagonal treatment too.
        _ if is_lower_triangular(m) && !is_upper_triangular(m) => {
            scaling_and_squaring(&m.transpose())?.transpose()
        }
        _ => scaling_and_squaring(m)?,
    };
    if e.iter().any(|x| !x.is_finite()) {
        return Err(LtiError::Overflow {
            what: "the matrix exponential".into(),
            reason: String::new(),
        });
    }
    Ok(e)
}

/// log₂ of the 1-norm (max column sum of magnitudes), computed without overflow; −∞ for 0.
fn log2_one_norm(a: &DMatrix<f64>) -> f64 {
    let Some((_, hi)) = exponent_range(a.iter().copied()) else {
        return f64::NEG_INFINITY;
    };
    let max_sum = a
        .column_iter()
        .map(|c| c.iter().map(|x| ldexp(x.abs(), -hi)).sum::<f64>())
        .fold(0.0, f64::max);
    max_sum.log2() + f64::from(hi)
}

/// ‖A‖₁ of a matrix whose norm is known not to overflow.
fn one_norm(a: &DMatrix<f64>) -> f64 {
    a.column_iter()
        .map(|c| c.iter().map(|x| x.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// ℓ(A, m) = max(⌈log₂(α/u)/(2m)⌉, 0) with α = |c₂ₘ₊₁|·‖|A|^(2m+1)‖₁/‖A‖₁ (Al-Mohy & Higham
/// 2009, eq. 5.1): the extra squarings that keep the backward error ≤ u for a non-normal A.
/// ‖|A|ᵏ‖₁ = ‖1ᵀ|A|ᵏ‖_∞ exactly, from k vector–matrix products.
fn ell(a: &DMatrix<f64>, m: usize) -> u32 {
    let norm = one_norm(a);
    if norm == 0.0 {
        return 0;
    }
    let n = a.nrows();
    // Row vector 1ᵀ|A|ᵏ, rescaled by a power of two (exact) whenever its largest entry leaves
    // [2^−256, 2^256] — scaling commutes with the products' rounding, so rescaling only then
    // gives the same bits as rescaling at every step: entry j is the dot product of the
    // previous vector with |column j|.
    const RANGE: f64 = 1.157_920_892_373_162e77; // ≈ 2^256 (a threshold: need not be exact)
    // |c_{2m+1}| = (m!)² / ((2m)!·(2m+1)!), as a log to stay finite.
    let ln_fact = |k: usize| (1..=k).map(|i| (i as f64).ln()).sum::<f64>();
    let log2_c = (2.0 * ln_fact(m) - ln_fact(2 * m) - ln_fact(2 * m + 1)) / std::f64::consts::LN_2;
    let log2_norm = norm.log2();
    let mut v = vec![1.0; n];
    let mut next = vec![0.0; n];
    let mut log2_scale = 0i32;
    let mut vmax: f64 = 1.0;
    for k in 1..=2 * m + 1 {
        // ‖1ᵀ|A|^(2m+1)‖_∞ ≤ ‖1ᵀ|A|^(k−1)‖_∞·‖A‖₁^(2m+2−k): once that bound puts α below u
        // the value is 0, whatever the remaining products give
        let bound = vmax.log2() + f64::from(log2_scale) + (2 * m + 2 - k) as f64 * log2_norm;
        if log2_c + bound - log2_norm + 53.0 <= 0.0 {
            return 0;
        }
        for (nj, col) in next.iter_mut().zip(a.column_iter()) {
            *nj = abs_dot(col.as_slice(), &v);
        }
        std::mem::swap(&mut v, &mut next);
        vmax = v.iter().copied().fold(0.0, f64::max);
        if vmax > 0.0 && !(1.0 / RANGE..=RANGE).contains(&vmax) {
            let e = vmax.log2().floor() as i32;
            v.iter_mut().for_each(|x| *x = ldexp(*x, -e));
            vmax = ldexp(vmax, -e);
            log2_scale += e;
        }
    }
    if vmax == 0.0 {
        return 0;
    }
    let log2_alpha = log2_c + vmax.log2() + f64::from(log2_scale) - log2_norm;
    let value = ((log2_alpha + 53.0) / (2.0 * m as f64)).ceil();
    if value > 0.0 {
        (value as u32).min(MAX_SQUARINGS)
    } else {
        0
    }
}

/// Σ |xᵢ|·vᵢ with four partial sums (vectorised; the order of a sum of non-negative terms
/// only moves its last bits).
fn abs_dot(x: &[f64], v: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (xc, vc) = (x.chunks_exact(4), v.chunks_exact(4));
    let tail: f64 = xc
        .remainder()
        .iter()
        .zip(vc.remainder())
        .map(|(a, b)| a.abs() * b)
        .sum();
    for (a, b) in xc.zip(vc) {
        for k in 0..4 {
            acc[k] += a[k].abs() * b[k];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// A and its powers A², A⁴ (every approximant and every dₖ test needs them), A⁶ when an
/// approximant or a test needs it, and the norms ‖A⁸‖₁, ‖A¹⁰‖₁ computed on demand. A dₖ test
/// dₖ ≤ θ first tries the bound from the norms at hand (‖A⁶‖ ≤ ‖A⁴‖·‖A²‖, ‖A⁸‖ ≤ ‖A⁴‖²,
/// ‖A¹⁰‖ ≤ ‖A⁴‖·‖A⁶‖): when the bound passes the exact norm passes too, so the decisions are
/// those of the exact norms, and the product behind an exact norm is formed only when the
/// bound does not settle the test.
struct Powers {
    a: DMatrix<f64>,
    a2: DMatrix<f64>,
    a4: DMatrix<f64>,
    a6: Option<DMatrix<f64>>,
    /// ‖A²‖₁, ‖A⁴‖₁.
    n2: f64,
    n4: f64,
    n6: Option<f64>,
    n8: Option<f64>,
    n10: Option<f64>,
}

impl Powers {
    fn new(a: DMatrix<f64>) -> Self {
        let a2 = &a * &a;
        let a4 = &a2 * &a2;
        Powers {
            n2: one_norm(&a2),
            n4: one_norm(&a4),
            a,
            a2,
            a4,
            a6: None,
            n6: None,
            n8: None,
            n10: None,
        }
    }

    /// The powers of A/2ˢ from those of A: exact scalings by 2^(−ks) (the same products up
    /// to underflow), instead of three new products.
    fn scaled(self, s: u32) -> Self {
        let e = -(s as i32);
        let scale = |m: DMatrix<f64>, k: i32| m.map(|x| ldexp(x, k * e));
        let a6 = self.a6.map(|m| scale(m, 6));
        let a4 = scale(self.a4, 4);
        let a2 = scale(self.a2, 2);
        Powers {
            n2: one_norm(&a2),
            n4: one_norm(&a4),
            n6: a6.as_ref().map(one_norm),
            a: scale(self.a, 1),
            a2,
            a4,
            a6,
            n8: None,
            n10: None,
        }
    }

    /// A⁶, formed on first use.
    fn a6(&mut self) -> &DMatrix<f64> {
        let (a4, a2) = (&self.a4, &self.a2);
        self.a6.get_or_insert_with(|| a4 * a2)
    }

    /// A⁶ moved out (formed if needed), for an approximant.
    fn take_a6(&mut self) -> DMatrix<f64> {
        self.a6.take().unwrap_or_else(|| &self.a4 * &self.a2)
    }

    /// ‖Aᵏ‖₁, k ∈ {4, 6, 8, 10}, exact (the products formed on first use).
    fn norm(&mut self, k: u32) -> f64 {
        match k {
            4 => self.n4,
            6 => match self.n6 {
                Some(v) => v,
                None => {
                    let v = one_norm(self.a6());
                    self.n6 = Some(v);
                    v
                }
            },
            8 => *self
                .n8
                .get_or_insert_with(|| one_norm(&(&self.a4 * &self.a4))),
            _ => match self.n10 {
                Some(v) => v,
                None => {
                    let a6 = self.take_a6();
                    let v = one_norm(&(&self.a4 * &a6));
                    self.a6 = Some(a6);
                    self.n10 = Some(v);
                    v
                }
            },
        }
    }

    /// An upper bound of ‖Aᵏ‖₁ from the norms already at hand (the exact norm when known).
    fn norm_bound(&self, k: u32) -> f64 {
        match k {
            4 => self.n4,
            6 => self.n6.unwrap_or(self.n4 * self.n2),
            8 => self.n8.unwrap_or(self.n4 * self.n4),
            _ => self
                .n10
                .unwrap_or(self.n4 * self.n6.unwrap_or(self.n4 * self.n2)),
        }
    }

    /// dₖ = ‖Aᵏ‖₁^(1/k), exact.
    fn d(&mut self, k: u32) -> f64 {
        self.norm(k).powf(1.0 / f64::from(k))
    }

    /// dₖ ≤ θ, decided by the bound when it passes, else by the exact norm.
    fn d_at_most(&mut self, k: u32, theta: f64) -> bool {
        let root = |v: f64| v.powf(1.0 / f64::from(k));
        root(self.norm_bound(k)) <= theta || root(self.norm(k)) <= theta
    }
}

/// True when every entry below the diagonal is zero.
fn is_upper_triangular(m: &DMatrix<f64>) -> bool {
    (0..m.ncols()).all(|j| m.column(j).iter().skip(j + 1).all(|x| *x == 0.0))
}

/// True when every entry above the diagonal is zero.
fn is_lower_triangular(m: &DMatrix<f64>) -> bool {
    (0..m.ncols()).all(|j| m.column(j).iter().take(j).all(|x| *x == 0.0))
}

/// The scaling-and-squaring core for n ≥ 2 (finite input).
fn scaling_and_squaring(m: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let (x, squarings) = approximant(m)?;
    let triangular = is_upper_triangular(m).then_some(m);
    square(x, squarings, triangular)
}

/// r_m(A/2ˢ) and s (see the module docs).
fn approximant(m: &DMatrix<f64>) -> Result<(DMatrix<f64>, u32)> {
    let log2_norm = log2_one_norm(m);
    if log2_norm == f64::NEG_INFINITY {
        return Ok((DMatrix::identity(m.nrows(), m.ncols()), 0));
    }
    // Scaling front end: A = 2^s0·B with ‖B‖₁ ≤ 2^PRESCALE_BITS·θ₁₃.
    let excess = (log2_norm - THETA_13.log2()).ceil() as i32 - PRESCALE_BITS;
    let s0 = excess.max(0);
    let b = if s0 > 0 {
        m.map(|x| ldexp(x, -s0))
    } else {
        m.clone()
    };
    let mut pw = Powers::new(b);
    if s0 == 0 {
        // η₁ = max(d₄, d₆) ≤ θ and η₃ = max(d₆, d₈) ≤ θ, as conjunctions
        let eta1_at_most = |pw: &mut Powers, theta| pw.d(4) <= theta && pw.d_at_most(6, theta);
        if eta1_at_most(&mut pw, THETA_3) && ell(&pw.a, 3) == 0 {
            return Ok((pade_solve(&pade_low(&mut pw, &B3))?, 0));
        }
        if eta1_at_most(&mut pw, THETA_5) && ell(&pw.a, 5) == 0 {
            return Ok((pade_solve(&pade_low(&mut pw, &B5))?, 0));
        }
        let eta3_at_most =
            |pw: &mut Powers, theta| pw.d_at_most(6, theta) && pw.d_at_most(8, theta);
        if eta3_at_most(&mut pw, THETA_7) && ell(&pw.a, 7) == 0 {
            return Ok((pade_solve(&pade_low(&mut pw, &B7))?, 0));
        }
        if eta3_at_most(&mut pw, THETA_9) && ell(&pw.a, 9) == 0 {
            return Ok((pade_solve(&pade_low(&mut pw, &B9))?, 0));
        }
    }
    // s₁ = ⌈log₂(η₅/θ₁₃)⌉⁺, η₅ = min(η₃, η₄): zero when the bounds already say η₅ ≤ θ₁₃
    let bounded = |pw: &Powers, k: u32| pw.norm_bound(k).powf(1.0 / f64::from(k));
    let eta5_bound = bounded(&pw, 6)
        .max(bounded(&pw, 8))
        .min(bounded(&pw, 8).max(bounded(&pw, 10)));
    let eta5 = if eta5_bound <= THETA_13 {
        eta5_bound
    } else {
        let eta3 = pw.d(6).max(pw.d(8));
        let eta4 = pw.d(8).max(pw.d(10));
        eta3.min(eta4)
    };
    let s1 = if eta5 <= THETA_13 {
        0
    } else {
        (eta5 / THETA_13).log2().ceil().max(0.0) as u32
    };
    let scaled = pw.a.map(|x| ldexp(x, -(s1 as i32)));
    let s = s1 + ell(&scaled, 13);
    let total = s0 as u32 + s;
    if total > MAX_SQUARINGS {
        return Err(LtiError::NoConvergence {
            what: "matrix exponential (scaling and squaring)".into(),
            iterations: total as usize,
        });
    }
    let mut a = if s == 0 { pw } else { pw.scaled(s) };
    Ok((pade_solve(&pade13(&mut a))?, total))
}

/// Squares `x` = r(A/2ˢ) s times. For an upper triangular A the diagonal and the first
/// superdiagonal of each iterate are replaced by their exact values (Al-Mohy & Higham 2009,
/// Code Fragment 2.1): a stiff diagonal then comes out exact instead of losing ~2ˢ·eps.
/// Otherwise the loop stops early when the iterate is exactly zero or exactly idempotent.
fn square(
    mut x: DMatrix<f64>,
    squarings: u32,
    triangular: Option<&DMatrix<f64>>,
) -> Result<DMatrix<f64>> {
    let total = squarings as i32;
    if let Some(a) = triangular {
        exact_triangle_entries(&mut x, a, -total);
    }
    for j in 1..=total {
        let mut next = &x * &x;
        if next.iter().any(|v| !v.is_finite()) {
            return Err(LtiError::Overflow {
                what: "the matrix exponential".into(),
                reason: String::new(),
            });
        }
        let done = match triangular {
            Some(a) => {
                exact_triangle_entries(&mut next, a, j - total);
                false
            }
            None => next == x || next.iter().all(|v| *v == 0.0),
        };
        x = next;
        if done {
            break;
        }
    }
    Ok(x)
}

/// Sets the diagonal and first superdiagonal of `x` ≈ e^{2^e·A} (A upper triangular) to
/// their exact values: e^{λᵢ} and t·(e^{λ₂} − e^{λ₁})/(λ₂ − λ₁), the latter as
/// t·e^{(λ₁+λ₂)/2}·sinh(δ)/δ, δ = (λ₂ − λ₁)/2, when the two are close (no cancellation).
fn exact_triangle_entries(x: &mut DMatrix<f64>, a: &DMatrix<f64>, e: i32) {
    let n = a.nrows();
    for i in 0..n {
        x[(i, i)] = ldexp(a[(i, i)], e).exp();
    }
    for i in 0..n - 1 {
        let t = ldexp(a[(i, i + 1)], e);
        let (l1, l2) = (ldexp(a[(i, i)], e), ldexp(a[(i + 1, i + 1)], e));
        let d = l2 - l1;
        x[(i, i + 1)] = if d.abs() <= 1.0 {
            let half = 0.5 * d;
            let sinhc = if half == 0.0 { 1.0 } else { half.sinh() / half };
            t * (0.5 * (l1 + l2)).exp() * sinhc
        } else {
            t * (l2.exp() - l1.exp()) / d
        };
    }
}

/// out ← (((out + c₁·M₁) + c₂·M₂) + …) + c₀·I, one pass per term and no temporaries (the
/// order of the sums written out term by term: the same roundings).
fn add_terms(mut out: DMatrix<f64>, terms: &[(&DMatrix<f64>, f64)], identity: f64) -> DMatrix<f64> {
    for (m, c) in terms {
        out.zip_apply(*m, |o, x| *o += x * c);
    }
    for i in 0..out.nrows() {
        out[(i, i)] += identity;
    }
    out
}

/// c·I.
fn scaled_identity(n: usize, c: f64) -> DMatrix<f64> {
    DMatrix::from_diagonal_element(n, n, c)
}

/// (U, V) of the degree-m Padé approximant for m ≤ 9: U = A·Σ b_{2k+1} A^{2k},
/// V = Σ b_{2k} A^{2k}.
fn pade_low(pw: &mut Powers, b: &[f64]) -> (DMatrix<f64>, DMatrix<f64>) {
    let n = pw.a.nrows();
    let high = b.len() / 2; // even powers A^{2k}, 1 ≤ k < high
    let a6 = (high > 3).then(|| pw.take_a6());
    let a8 = (high > 4).then(|| &pw.a4 * &pw.a4);
    let evens: Vec<&DMatrix<f64>> = [Some(&pw.a2), Some(&pw.a4), a6.as_ref(), a8.as_ref()]
        .into_iter()
        .flatten()
        .take(high - 1)
        .collect();
    let odd: Vec<_> = evens
        .iter()
        .enumerate()
        .map(|(k, m)| (*m, b[2 * k + 3]))
        .collect();
    let even: Vec<_> = evens
        .iter()
        .enumerate()
        .map(|(k, m)| (*m, b[2 * k + 2]))
        .collect();
    let u = add_terms(scaled_identity(n, b[1]), &odd, 0.0);
    let v = add_terms(scaled_identity(n, b[0]), &even, 0.0);
    (&pw.a * u, v)
}

/// (U, V) of the degree-13 approximant with six matrix products (Higham 2005, eq. 2.6).
fn pade13(pw: &mut Powers) -> (DMatrix<f64>, DMatrix<f64>) {
    let n = pw.a.nrows();
    let b = &B13;
    let a6 = pw.take_a6();
    let (a2, a4, a6) = (&pw.a2, &pw.a4, &a6);
    let zero = || DMatrix::zeros(n, n);
    let inner_u = add_terms(zero(), &[(a6, b[13]), (a4, b[11]), (a2, b[9])], 0.0);
    let outer_u = add_terms(a6 * inner_u, &[(a6, b[7]), (a4, b[5]), (a2, b[3])], b[1]);
    let u = &pw.a * outer_u;
    let inner_v = add_terms(zero(), &[(a6, b[12]), (a4, b[10]), (a2, b[8])], 0.0);
    let v = add_terms(a6 * inner_v, &[(a6, b[6]), (a4, b[4]), (a2, b[2])], b[0]);
    (u, v)
}

/// r = (V − U)⁻¹(V + U).
fn pade_solve((u, v): &(DMatrix<f64>, DMatrix<f64>)) -> Result<DMatrix<f64>> {
    let p = v + u;
    let q = v - u;
    crate::numeric::linalg::lu::lu_solve(q, p).ok_or_else(|| LtiError::NoConvergence {
        what: "matrix exponential (singular Padé denominator)".into(),
        iterations: 0,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)] // exact values where stated
    use super::*;

    /// ℓ(A, m) as eq. 5.1 reads: ‖|A|^(2m+1)‖₁ from the formed powers of |A|.
    fn ell_by_powers(a: &DMatrix<f64>, m: usize) -> u32 {
        let norm = one_norm(a);
        if norm == 0.0 {
            return 0;
        }
        let abs = a.abs();
        let mut p = abs.clone();
        for _ in 0..2 * m {
            p = &p * &abs;
        }
        let power = one_norm(&p);
        if power == 0.0 {
            return 0;
        }
        let ln_fact = |k: usize| (1..=k).map(|i| (i as f64).ln()).sum::<f64>();
        let c = (2.0 * ln_fact(m) - ln_fact(2 * m) - ln_fact(2 * m + 1)).exp();
        let v = ((c * power / norm / f64::EPSILON * 2.0).log2() / (2.0 * m as f64)).ceil();
        if v > 0.0 { v as u32 } else { 0 }
    }

    #[test]
    fn ell_with_its_early_exit_is_eq_5_1() {
        // dense, triangular (non-normal: ℓ > 0) and nilpotent matrices over a range of
        // norms, every degree: the vector recursion with its rescaling and its early exit
        // gives the formed powers' value
        let mut x: u64 = 0x2545_F491_4F6C_DD1D;
        let mut r = move || crate::numeric::test_rng::unit(&mut x) - 0.5;
        let mut positive = 0;
        for case in 0..60 {
            let n = 2 + case % 7;
            let scale = 10f64.powf(-3.0 + 6.0 * (case as f64) / 60.0);
            let mut a = DMatrix::from_fn(n, n, |_, _| scale * r());
            if case % 3 == 1 {
                a.fill_lower_triangle(0.0, 1);
                a[(0, n - 1)] *= 1e4;
            }
            if case % 3 == 2 {
                a.fill_lower_triangle(0.0, 0);
            }
            for m in [3, 5, 7, 9, 13] {
                let (got, want) = (ell(&a, m), ell_by_powers(&a, m));
                // the two sums round differently: equal, or off by one at a boundary
                assert!(
                    got.abs_diff(want) <= 1,
                    "case {case}, m {m}: {got} vs {want}"
                );
                positive += usize::from(got > 0);
            }
        }
        assert!(
            positive > 10,
            "{positive} positive values: the test must see both branches"
        );
    }

    #[test]
    fn rotation_and_jordan_closed_forms() {
        // e^{[[0, θ], [−θ, 0]]} = [[cos θ, sin θ], [−sin θ, cos θ]].
        for &th in &[1e-8, 0.3, 1.0, 10.0, 100.0] {
            let a = DMatrix::from_row_slice(2, 2, &[0.0, th, -th, 0.0]);
            let e = expm(&a).unwrap();
            let want = DMatrix::from_row_slice(2, 2, &[th.cos(), th.sin(), -th.sin(), th.cos()]);
            let err = (&e - &want).abs().max();
            assert!(err <= 1e-14 * th.max(1.0), "θ = {th}: {err:e}");
        }
        // Jordan block λI + N (4×4): e^{λ}·Σ Nᵏ/k!.
        let lam = -2.0;
        let a = DMatrix::from_fn(4, 4, |i, j| {
            if i == j {
                lam
            } else if j == i + 1 {
                1.0
            } else {
                0.0
            }
        });
        let e = expm(&a).unwrap();
        let fact = [1.0, 1.0, 2.0, 6.0];
        for i in 0..4 {
            for j in 0..4 {
                let want = if j >= i { lam.exp() / fact[j - i] } else { 0.0 };
                assert!((e[(i, j)] - want).abs() <= 2e-16, "({i},{j})");
            }
        }
    }

    #[test]
    fn huge_norms_are_bounded_and_exact_in_the_limit() {
        // Stable: e^{-1e300} = 0 and the integrator column keeps 1/a.
        let a = DMatrix::from_row_slice(2, 2, &[-1e300, 0.0, 1.0, 0.0]);
        let e = expm(&a).unwrap();
        assert_eq!(e[(0, 0)], 0.0);
        assert!((e[(1, 0)] - 1e-300).abs() <= 1e-315);
        assert_eq!(e[(1, 1)], 1.0);
        // Unstable: a clear overflow error, not 2⁶⁴ squarings.
        let a = DMatrix::from_row_slice(2, 2, &[1e50, 0.0, 1.0, 0.0]);
        assert!(matches!(expm(&a), Err(LtiError::Overflow { .. })));
        let a = DMatrix::from_element(3, 3, f64::MAX);
        assert!(expm(&a).is_err());
    }

    /// A non-normal 12×12 test matrix: a decaying diagonal and a large, structured strictly
    /// upper part (‖A⁶‖ far below ‖A⁴‖·‖A²‖), scaled by `c`.
    fn non_normal(c: f64) -> DMatrix<f64> {
        DMatrix::from_fn(12, 12, |i, j| {
            let v = if i == j {
                -0.1 * (i as f64 + 1.0)
            } else if j > i {
                (((i * 7 + j * 3) % 5) as f64 - 2.0) * 0.8
            } else {
                0.0
            };
            c * v
        })
    }

    #[test]
    fn norm_bounds_decide_as_the_exact_norms() {
        // every dₖ test, for thresholds around the exact value, gives the exact answer
        for &c in &[0.01, 0.05, 0.2, 1.0] {
            let mut exact = Powers::new(non_normal(c));
            for k in [6, 8, 10] {
                let d = exact.d(k);
                for theta in [THETA_3, THETA_5, THETA_7, THETA_9, THETA_13, d, 0.999 * d] {
                    let mut pw = Powers::new(non_normal(c));
                    assert_eq!(
                        pw.d_at_most(k, theta),
                        d <= theta,
                        "c = {c}, k = {k}, θ = {theta}"
                    );
                }
                // and the bound is a bound
                let pw = Powers::new(non_normal(c));
                assert!(pw.norm_bound(k) >= exact.norm(k), "c = {c}, k = {k}");
            }
        }
    }

    #[test]
    fn scaled_powers_are_the_powers_of_the_scaled_matrix() {
        // scaling by 2^(−ks) is exact away from underflow: the same bits as new products
        let a = non_normal(3.0);
        let mut pw = Powers::new(a.clone());
        pw.a6();
        let scaled = pw.scaled(3);
        let mut direct = Powers::new(a.map(|x| x / 8.0));
        assert_eq!(scaled.a, direct.a);
        assert_eq!(scaled.a2, direct.a2);
        assert_eq!(scaled.a4, direct.a4);
        assert_eq!(scaled.a6.as_ref(), Some(direct.a6()));
    }

    #[test]
    fn zero_and_rejections() {
        let z = DMatrix::<f64>::zeros(3, 3);
        assert_eq!(expm(&z).unwrap(), DMatrix::identity(3, 3));
        assert!(expm(&DMatrix::<f64>::zeros(2, 3)).is_err());
        let nan = DMatrix::from_row_slice(2, 2, &[1.0, f64::NAN, 0.0, 1.0]);
        assert!(expm(&nan).is_err());
    }
}
