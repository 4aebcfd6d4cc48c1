//! Robustness of the numerical core on extreme but finite input (issue 14): random
//! coefficients and matrix entries of 1e±300, subnormals, mixed scales, exact zeros, repeated
//! factors, degrees up to MAX_ORDER, into `Poly::roots`, `numeric::eigenvalues`,
//! `numeric::expm` and `StateSpace::balanced`. Every call must return — no panic, no hang — with
//! finite values of the right shape, or an error.
//!
//! Fixed seed and a bounded case count, so CI stays fast. A longer campaign:
//! `LTIKIT_FUZZ_CASES=20000 LTIKIT_FUZZ_SEED=7 cargo test --release --test robust_numeric`.

use ltikit::numeric::{eigenvalues, expm};
use ltikit::{LtiError, MAX_ORDER, Poly, StateSpace};
use nalgebra::DMatrix;

/// xorshift64*: small, deterministic, good enough to spread cases.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    /// A finite value from one of several extreme families.
    fn extreme(&mut self) -> f64 {
        let sign = if self.next() & 1 == 0 { 1.0 } else { -1.0 };
        let mag = match self.below(8) {
            0 => 0.0,
            1 => 10f64.powf(600.0 * self.unit() - 300.0), // 1e±300
            2 => f64::from_bits(1 + self.next() % (1u64 << 52)), // subnormal
            3 => f64::MAX * self.unit(),
            4 => 10f64.powf(40.0 * self.unit() - 20.0), // mixed scales
            5 => [1.0, 2.0, 0.5, 3.0][self.below(4)],   // exact small values
            _ => self.unit() * 2.0,
        };
        sign * mag
    }
}

fn cases(default: usize) -> usize {
    std::env::var("LTIKIT_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn rng() -> Rng {
    let seed = std::env::var("LTIKIT_FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0x5EED_1234_u64);
    Rng(seed | 1)
}

/// A random polynomial: independent extreme coefficients, or a product of repeated factors
/// with extreme roots, at a degree that is usually small and sometimes MAX_ORDER.
fn random_poly(r: &mut Rng) -> Vec<f64> {
    let degree = match r.below(10) {
        0 => MAX_ORDER,
        1 | 2 => 20 + r.below(MAX_ORDER - 20),
        _ => 1 + r.below(12),
    };
    if r.below(3) == 0 {
        // (s − a)^k products with extreme a.
        let mut p = Poly::constant(1.0);
        while p.degree() < degree.min(24) {
            let a = r.extreme();
            let k = 1 + r.below(4);
            let f = Poly::from_descending(&[1.0, -a]).unwrap();
            for _ in 0..k {
                p = &p * &f;
            }
        }
        if p.coeffs().iter().all(|c| c.is_finite()) {
            return p.coeffs().to_vec();
        }
    }
    let mut c: Vec<f64> = (0..=degree).map(|_| r.extreme()).collect();
    if c[0] == 0.0 {
        c[0] = 1.0;
    }
    c
}

#[test]
fn roots_of_extreme_polynomials_are_finite_or_an_error() {
    let mut r = rng();
    let (mut ok, mut err) = (0, 0);
    for case in 0..cases(60) {
        let c = random_poly(&mut r);
        let p = Poly::from_descending(&c).unwrap();
        match p.roots() {
            Ok(roots) => {
                ok += 1;
                let total: usize = roots.iter().map(|x| x.multiplicity).sum();
                assert_eq!(total, p.degree(), "case {case}: {c:?}");
                for x in &roots {
                    assert!(x.multiplicity >= 1);
                    assert!(
                        x.value.re.is_finite() && x.value.im.is_finite(),
                        "case {case}: non-finite root {} of {c:?}",
                        x.value
                    );
                }
            }
            Err(e) => {
                err += 1;
                assert!(!e.to_string().is_empty());
            }
        }
    }
    eprintln!("roots: {ok} solved, {err} errors");
    assert!(ok > 0);
}

fn random_matrix(r: &mut Rng, n: usize) -> DMatrix<f64> {
    match r.below(3) {
        // Companion matrix of an extreme polynomial (a controllable canonical A).
        0 => {
            let mut a = DMatrix::zeros(n, n);
            for j in 0..n {
                a[(0, j)] = r.extreme();
            }
            for i in 1..n {
                a[(i, i - 1)] = 1.0;
            }
            a
        }
        // Sparse: mostly zeros, a few extreme entries.
        1 => DMatrix::from_fn(n, n, |_, _| if r.below(3) == 0 { r.extreme() } else { 0.0 }),
        _ => DMatrix::from_fn(n, n, |_, _| r.extreme()),
    }
}

#[test]
fn eigenvalues_of_extreme_matrices_are_finite_or_an_error() {
    let mut r = rng();
    let total = cases(60);
    let (mut ok, mut beyond) = (0, 0);
    for case in 0..total {
        let n = if r.below(8) == 0 { 40 } else { 1 + r.below(8) };
        let m = random_matrix(&mut r, n);
        match eigenvalues(&m) {
            Ok(ev) => {
                ok += 1;
                assert_eq!(ev.len(), n, "case {case}");
                assert!(
                    ev.iter().all(|z| z.re.is_finite() && z.im.is_finite()),
                    "case {case}: {ev:?}"
                );
            }
            // the one refusal allowed: an eigenvalue whose magnitude f64 cannot hold
            Err(LtiError::NonFinite { .. }) => beyond += 1,
            Err(e) => panic!("case {case}: {e}"),
        }
    }
    eprintln!("eigenvalues: {ok} finite, {beyond} beyond f64");
    // The default seed gives 57 of 60: most extreme matrices have representable eigenvalues,
    // so an eigenvalue routine that refused everything fails here.
    assert!(2 * ok >= total, "only {ok} of {total} answered");
}

#[test]
fn expm_of_extreme_matrices_is_finite_or_an_error() {
    let mut r = rng();
    let (mut ok, mut err) = (0, 0);
    for case in 0..cases(60) {
        let n = if r.below(10) == 0 { 24 } else { 1 + r.below(6) };
        let m = random_matrix(&mut r, n);
        match expm(&m) {
            Ok(e) => {
                ok += 1;
                assert_eq!(e.shape(), (n, n));
                assert!(e.iter().all(|x| x.is_finite()), "case {case}: {m}");
            }
            Err(_) => err += 1,
        }
    }
    eprintln!("expm: {ok} finite, {err} errors (overflow)");
    assert!(ok > 0);
}

#[test]
fn balancing_extreme_realisations_is_exact_and_finite() {
    let mut r = rng();
    for case in 0..cases(60) {
        let n = 1 + r.below(10);
        let a = random_matrix(&mut r, n);
        let b = DMatrix::from_fn(n, 1, |_, _| r.extreme());
        let c = DMatrix::from_fn(1, n, |_, _| r.extreme());
        let ss = StateSpace::new(a, b, c, DMatrix::zeros(1, 1)).unwrap();
        let bal = ss.balanced();
        for m in [&bal.a, &bal.b, &bal.c] {
            assert!(m.iter().all(|x| x.is_finite()), "case {case}");
        }
        // A diagonal similarity by powers of two: every |entry| of A is scaled by d_j/d_i, so
        // zero pattern and diagonal are unchanged.
        for i in 0..n {
            assert_eq!(
                bal.a[(i, i)].to_bits(),
                ss.a[(i, i)].to_bits(),
                "case {case}"
            );
            for j in 0..n {
                assert_eq!(bal.a[(i, j)] == 0.0, ss.a[(i, j)] == 0.0, "case {case}");
            }
        }
    }
}

#[test]
fn issue_14_reproducers_at_the_library_level() {
    // s³ − 1e308 s² + 1e100: the roots of `ltikit analyze --den "1 -1e308 0 1e100"`.
    let r = Poly::from_descending(&[1.0, -1e308, 0.0, 1e100])
        .unwrap()
        .roots()
        .unwrap();
    assert_eq!(r.len(), 3);
    // The step response of 1/(s + 1e200): A = [[−1e200, 0], [1, 0]] after realisation.
    let a = DMatrix::from_row_slice(2, 2, &[-1e200, 0.0, 1.0, 0.0]);
    let e = expm(&a).unwrap();
    // e^{At} = [[e^{−at}, 0], [(1 − e^{−at})/a, 1]] at t = 1, a = 1e200 (closed form).
    assert_eq!(e[(0, 0)], 0.0);
    assert!((e[(1, 0)] - 1e-200).abs() <= 2.0 * f64::EPSILON * 1e-200);
    // Spring–mass–damper with C = 1e200: eigenvalues of [[0, 1], [−4, −1e200]] are
    // −1e200 and −4e-200 (product 4, sum −1e200).
    let m = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, -1e200]);
    let mut ev: Vec<f64> = eigenvalues(&m).unwrap().iter().map(|z| z.re).collect();
    ev.sort_by(f64::total_cmp);
    assert!(
        (ev[0] + 1e200).abs() <= 4.0 * f64::EPSILON * 1e200,
        "{ev:?}"
    );
    assert!((ev[1] + 4e-200).abs() <= 1e-12 * 4e-200, "{ev:?}");
    // 1/(s − 1e50): e^{1e50} overflows — an error, not 2⁶⁴ squarings.
    let a = DMatrix::from_row_slice(2, 2, &[1e50, 0.0, 1.0, 0.0]);
    assert!(expm(&a).is_err());
}

#[test]
fn badly_scaled_two_by_two_keeps_its_small_eigenvalue() {
    // Spring–mass–damper linearised with C = 1e200 (M = 1, K = 4): λ² + 1e200 λ + 4 = 0 has
    // the roots −1e200 and −4/1e200 = −4e-200 (product 4, sum −1e200, exact to rounding).
    let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, -1e200]);
    let mut ev: Vec<f64> = eigenvalues(&a).unwrap().iter().map(|z| z.re).collect();
    ev.sort_by(f64::total_cmp);
    assert_eq!(ev[0], -1e200);
    assert!(
        (ev[1] + 4e-200).abs() <= 4e-200 * 4.0 * f64::EPSILON,
        "{ev:?}"
    );
    // And the linearisation calls it asymptotically stable (it was "undetermined").
    let sys = ltikit::nonlinear::build_model("spring-mass-damper", &[("C".into(), 1e200)]).unwrap();
    let lin = ltikit::nonlinear::linearize(
        sys.as_ref(),
        None,
        &ltikit::nonlinear::EquilibriumSearch::default(),
    )
    .unwrap();
    assert_eq!(
        lin.equilibria[0].stability,
        ltikit::nonlinear::LocalStability::AsymptoticallyStable
    );
}

#[test]
fn nyquist_with_a_subnormal_pole_is_bounded() {
    // Found by the long fuzz campaign: a pole at −3.9e-322 made the first axis piece start at
    // log10(0) = −∞ and ask for usize::MAX samples (2.7 GB in 4 s, then killed). Now the
    // contour is bounded; this one has no finite point to draw.
    let g = ltikit::TransferFunction::from_descending(
        &[-4.396047048225206e-298],
        &[3.006310, 1.18e-321],
    )
    .unwrap();
    let n = g
        .nyquist()
        .unwrap_or_else(|e| panic!("a subnormal pole is still a pole: {e}"));
    assert!(n.points.len() <= 200_000, "{}", n.points.len());
}

#[test]
fn overflowing_schur_forms_do_not_reach_a_panicking_svd() {
    // Found by the CLI fuzzer (seed 20261124, case 312): eigenvalues near 1e298 made the
    // eigen-structure's reduced problem overflow and nalgebra's `svd()` panicked ("Singular
    // value was NaN"). Now the SVD runs on a scaled copy with a cap, and an overflowed block
    // keeps its eigenvalues simple.
    let a = nalgebra::DMatrix::from_row_slice(
        3,
        3,
        &[
            2.0,
            0.0,
            0.000928,
            3.863538767256927e-167,
            1.6176470106156244e238,
            68.855146,
            3.1525814145940795e298,
            -8.081031924361808e-299,
            7.972305912785204e298,
        ],
    );
    let r = std::panic::catch_unwind(|| ltikit::numeric::linalg::eigen_structure(&a));
    assert!(r.is_ok(), "panicked");
}

#[test]
fn the_exact_path_refuses_big_degree_times_bits() {
    // Found by the CLI fuzzer: degree 49 with decimals spanning 1e±300 (~2000-bit integer
    // coefficients) kept the exact path busy for 11.5 s; degree × bits is now bounded and the
    // numerical path runs instead.
    use ltikit::poly::exact::{ExactPoly, MAX_EXACT_WORK};
    let tokens: Vec<String> = (0..50)
        .map(|k| format!("{}e{}", 1 + k % 7, if k % 2 == 0 { 290 } else { -290 }))
        .collect();
    let p = ExactPoly::parse_descending(&tokens).unwrap();
    let e = p.half_plane_counts().unwrap_err().to_string();
    assert!(e.contains(&MAX_EXACT_WORK.to_string()), "{e}");
    // a small one stays exact
    let q = ExactPoly::parse_descending(&["1", "2e-300", "1e300"]).unwrap();
    assert!(q.half_plane_counts().is_ok());
}
