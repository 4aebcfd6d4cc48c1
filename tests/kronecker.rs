//! Zeros and Kronecker structure of the system pencil \[A − λI B; C D\] for any p×m system
//! (issue 24 item 1): square, non-square and rank-deficient systems; the normal rank, the
//! infinite zero structure and the left/right Kronecker indices; the minimal realisation of
//! defective eigenvalues and of identically zero channels.
//!
//! References: ControlSystems.jl `lib/ControlSystemsBase/test/test_analysis.jl` (commit
//! b2b7dc43, the Emami-Naeini & Van Dooren 1982 examples with their stated values and
//! tolerances); closed forms stated beside each test.

use nalgebra::DMatrix;
use num_complex::Complex64;

use ltikit::numeric::linalg::{invariant_zeros, minimal_realization, transmission_zeros};

fn m(r: usize, c: usize, v: &[f64]) -> DMatrix<f64> {
    DMatrix::from_row_slice(r, c, v)
}

/// Sorted by real part, then imaginary part.
fn sorted(mut z: Vec<Complex64>) -> Vec<Complex64> {
    z.sort_by(|a, b| a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im)));
    z
}

fn assert_zeros(got: &[Complex64], want: &[Complex64], tol: f64) {
    let (g, w) = (sorted(got.to_vec()), sorted(want.to_vec()));
    assert_eq!(g.len(), w.len(), "zeros {g:?}, expected {w:?}");
    for (x, y) in g.iter().zip(&w) {
        assert!(
            (x - y).norm() <= tol,
            "zeros {g:?}, expected {w:?} (tol {tol:e})"
        );
    }
}

fn re(v: &[f64]) -> Vec<Complex64> {
    v.iter().map(|&x| Complex64::new(x, 0.0)).collect()
}

/// ControlSystems.jl example 3 (EN–VD): 2×2, six integrators, D of rank 1.
#[test]
fn envd_example_3_rank_deficient_d() {
    let mut a = DMatrix::zeros(6, 6);
    for (i, j) in [(0, 1), (1, 2), (3, 4), (4, 5)] {
        a[(i, j)] = 1.0;
    }
    let mut b = DMatrix::zeros(6, 2);
    b[(2, 0)] = 1.0;
    b[(5, 1)] = 1.0;
    let c = m(2, 6, &[1., 1., 0., 0., 0., 0., 0., 0., 0., 1., -1., 0.]);
    let d = m(2, 2, &[1., 0., 1., 0.]);
    let z = invariant_zeros(&a, &b, &c, &d, None).unwrap();
    let want = [
        Complex64::new(0.3411639019140099, 1.161541399997252),
        Complex64::new(0.3411639019140099, -1.161541399997252),
        Complex64::new(0.9999999999999999, 0.0),
        Complex64::new(-0.6823278038280199, 0.0),
    ];
    assert_zeros(&z.zeros, &want, 1e-6);
    assert_eq!(z.structure.normal_rank, 2);
    assert!(z.structure.left_indices.is_empty() && z.structure.right_indices.is_empty());
}

/// ControlSystems.jl example 4 (EN–VD): 5 states, 2×2, D = 0.
#[test]
fn envd_example_4() {
    let a = m(
        5,
        5,
        &[
            -0.129, 0.0, 0.396e-1, 0.25e-1, 0.191e-1, //
            0.329e-2, 0.0, -0.779e-4, 0.122e-3, -0.621, //
            0.718e-1, 0.0, -0.1, 0.887e-3, -0.385e1, //
            0.411e-1, 0.0, 0.0, -0.822e-1, 0.0, //
            0.361e-3, 0.0, 0.35e-4, 0.426e-4, -0.743e-1,
        ],
    );
    let b = m(
        5,
        2,
        &[
            0.0, 0.139e-2, 0.0, 0.359e-4, 0.0, -0.989e-2, 0.249e-4, 0.0, 0.0, -0.534e-5,
        ],
    );
    let c = m(2, 5, &[1., 0., 0., 0., 0., 0., 1., 0., 0., 0.]);
    let z = invariant_zeros(&a, &b, &c, &DMatrix::zeros(2, 2), None).unwrap();
    // Julia's `≈` with no atol: rtol √ε of the vector norm
    assert_zeros(
        &z.zeros,
        &re(&[-0.06467751189940692, -0.3680512036036696]),
        1e-8,
    );
}

/// ControlSystems.jl example 6 (EN–VD): the singular part is extracted, the regular pencil
/// holds the single zero 2.
#[test]
fn envd_example_6_single_zero_at_two() {
    let a = m(3, 3, &[2., -1., 0., 0., 0., 0., -1., 0., 0.]);
    let b = m(3, 1, &[0., 0., 1.]);
    let c = m(1, 3, &[0., -1., 0.]);
    let z = invariant_zeros(&a, &b, &c, &DMatrix::zeros(1, 1), None).unwrap();
    assert_zeros(&z.zeros, &re(&[2.0]), 1e-14);
}

/// ControlSystems.jl example 7: ss(0₂ₓ₂, \[0; 1\], \[−1 0\], 0): G = C·B/s = 0 identically,
/// no zero. The pencil \[−λ 0 0; 0 −λ 1; −1 0 0\] has the right null vector (0, 1, λ) and the
/// left one (1, 0, −λ): normal rank 0, one left and one right index, both 1.
#[test]
fn envd_example_7_double_integrator() {
    let z = invariant_zeros(
        &DMatrix::zeros(2, 2),
        &m(2, 1, &[0., 1.]),
        &m(1, 2, &[-1., 0.]),
        &DMatrix::zeros(1, 1),
        None,
    )
    .unwrap();
    assert!(z.zeros.is_empty());
    assert_eq!(z.structure.normal_rank, 0);
    assert_eq!(z.structure.left_indices, vec![1]);
    assert_eq!(z.structure.right_indices, vec![1]);
    assert!(z.structure.infinite_orders.is_empty());
}

/// ControlSystems.jl example 8: a double zero at −1 (their tolerance 1e-6 in f64).
#[test]
fn envd_example_8_double_zero() {
    let a = m(
        6,
        6,
        &[
            -2., 1., 0., 0., 0., 0., //
            1., -2., 1., 0., 1., -1., //
            0., 1., -2., 1., 0., 0., //
            0., 0., 1., -1., 0., 1., //
            0., -1., 0., 0., 0., 0., //
            0., 1., 0., -1., 0., 0.,
        ],
    );
    let b = m(6, 1, &[1., 0., 0., 0., 1., 0.]);
    let c = m(1, 6, &[0., 0., 0., 1., 0., 0.]);
    let z = invariant_zeros(&a, &b, &c, &DMatrix::zeros(1, 1), None).unwrap();
    assert_zeros(&z.zeros, &re(&[-1.0, -1.0]), 1e-6);
}

fn example_11() -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>, DMatrix<f64>) {
    let a = m(
        5,
        5,
        &[
            -2., -6., 3., -7., 6., //
            0., -5., 4., -4., 8., //
            0., 2., 0., 2., -2., //
            0., 6., -3., 5., -6., //
            0., -2., 2., -2., 5.,
        ],
    );
    let b = m(5, 2, &[-2., 7., -8., -5., -3., 0., 1., 5., -8., 0.]);
    let c = m(
        3,
        5,
        &[
            0., -1., 2., -1., -1., 1., 1., 1., 0., -1., 0., 3., -2., 3., -1.,
        ],
    );
    (a, b, c, DMatrix::zeros(3, 2))
}

/// ControlSystems.jl example 11: a 3-output 2-input system (non-square) with zeros 4 and −3
/// (their tolerance 1e-5 in f64); one left Kronecker index (p − normal rank = 3 − 2), and the
/// dual (2×3) has the same zeros with the indices exchanged.
#[test]
fn envd_example_11_non_square() {
    let (a, b, c, d) = example_11();
    let z = invariant_zeros(&a, &b, &c, &d, None).unwrap();
    assert_zeros(&z.zeros, &re(&[4.0, -3.0]), 1e-5);
    assert_eq!(z.structure.normal_rank, 2);
    assert_eq!(z.structure.left_indices.len(), 1);
    assert!(z.structure.right_indices.is_empty());
    let dual = invariant_zeros(
        &a.transpose(),
        &c.transpose(),
        &b.transpose(),
        &d.transpose(),
        None,
    )
    .unwrap();
    assert_zeros(&dual.zeros, &re(&[4.0, -3.0]), 1e-5);
    assert_eq!(dual.structure.right_indices, z.structure.left_indices);
    assert!(dual.structure.left_indices.is_empty());
}

/// G = −1/s² (double integrator with the chain): one infinite zero of order 2 (the relative
/// degree), no finite zero, full normal rank.
#[test]
fn double_integrator_infinite_zero_of_order_two() {
    let z = invariant_zeros(
        &m(2, 2, &[0., 1., 0., 0.]),
        &m(2, 1, &[0., 1.]),
        &m(1, 2, &[-1., 0.]),
        &DMatrix::zeros(1, 1),
        None,
    )
    .unwrap();
    assert!(z.zeros.is_empty());
    assert_eq!(z.structure.infinite_orders, vec![2]);
    assert_eq!(z.structure.normal_rank, 1);
}

/// A square system of normal rank 1 < 2, refused before: x₁' = −x₁ + u₁ + u₂,
/// x₂' = −2x₂ + u₁, y₁ = y₂ = x₁, so G = \[1; 1\]·\[1 1\]/(s + 1). By hand, the 4×4 pencil
/// \[−1−λ 0 1 1; 0 −2−λ 1 0; 1 0 0 0; 1 0 0 0\] has normal rank 3, the constant left null
/// vector (0, 0, 1, −1) (left index 0), the right null vector (0, 1, 2 + λ, −2 − λ) (right
/// index 1), and the infinite zero of G (relative degree 1): 1 + 2 + 2 = 4 columns leave no
/// regular finite part — no invariant zero, although x₂ is unobservable (at λ = −2 the
/// pencil keeps rank 3: the decoupling zero is absorbed by the singular part).
#[test]
fn rank_deficient_square_system() {
    let a = m(2, 2, &[-1., 0., 0., -2.]);
    let b = m(2, 2, &[1., 1., 1., 0.]);
    let c = m(2, 2, &[1., 0., 1., 0.]);
    let d = DMatrix::zeros(2, 2);
    let z = invariant_zeros(&a, &b, &c, &d, None).unwrap();
    assert_eq!(z.structure.normal_rank, 1);
    assert_eq!(z.structure.left_indices, vec![0]);
    assert_eq!(z.structure.right_indices, vec![1]);
    assert_eq!(z.structure.infinite_orders, vec![1]);
    assert!(z.zeros.is_empty(), "{:?}", z.zeros);
}

/// Rank deficient with a genuine zero: G = \[1; 1\]·\[(s − 3)/((s + 1)(s + 2))\] (one input,
/// two equal outputs, p = 2 > m = 1, normal rank 1): the zero 3 of the channel is the zero of
/// the system, one left index (the two outputs are equal: index 0).
#[test]
fn tall_system_with_equal_outputs() {
    // controllable canonical form of (s − 3)/(s² + 3s + 2)
    let a = m(2, 2, &[-3., -2., 1., 0.]);
    let b = m(2, 1, &[1., 0.]);
    let c = m(2, 2, &[1., -3., 1., -3.]);
    let d = DMatrix::zeros(2, 1);
    let z = invariant_zeros(&a, &b, &c, &d, None).unwrap();
    assert_zeros(&z.zeros, &re(&[3.0]), 1e-14);
    assert_eq!(z.structure.normal_rank, 1);
    assert_eq!(z.structure.left_indices, vec![0]);
    assert!(z.structure.right_indices.is_empty());
    assert_eq!(z.structure.infinite_orders, vec![1]);
}

/// An orthogonal n×n matrix from a seed: a product of Givens rotations at angles from a
/// linear congruential sequence.
fn orthogonal(n: usize, seed: u64) -> DMatrix<f64> {
    let mut q = DMatrix::<f64>::identity(n, n);
    let mut x = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    for _ in 0..3 {
        for i in 0..n {
            for j in i + 1..n {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let t = (x >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::TAU;
                let (c, s) = (t.cos(), t.sin());
                for k in 0..n {
                    let (a, b) = (q[(k, i)], q[(k, j)]);
                    q[(k, i)] = c * a - s * b;
                    q[(k, j)] = s * a + c * b;
                }
            }
        }
    }
    q
}

/// Issue 24: two Jordan blocks of size 2 at λ, both driven, one output seeing the sum of
/// their leading states: controllable (rank 4), observable rank 2, minimal order 2 (the
/// channel's G = 1/(s − λ)² + 1/(s − λ)² per input), the unobservable modes λ (×2). Hidden by
/// orthogonal similarities, for several λ and scales.
#[test]
fn minimal_realisation_of_two_jordan_blocks() {
    for (k, &(lambda, scale)) in [
        (-1.0, 1.0),
        (-3.0, 1.0),
        (-0.5, 1e3),
        (-2.0, 1e-3),
        (0.0, 1.0),
        (-1e3, 1.0),
    ]
    .iter()
    .enumerate()
    {
        let a0 = m(
            4,
            4,
            &[
                lambda, scale, 0., 0., 0., lambda, 0., 0., 0., 0., lambda, scale, 0., 0., 0.,
                lambda,
            ],
        );
        let b0 = m(4, 2, &[0., 0., 1., 0., 0., 0., 0., 1.]);
        let c0 = m(1, 4, &[1., 0., 1., 0.]);
        let q = orthogonal(4, 7 + k as u64);
        let (a, b, c) = (q.transpose() * &a0 * &q, q.transpose() * &b0, &c0 * &q);
        let d = DMatrix::zeros(1, 2);
        let mr = minimal_realization(&a, &b, &c, &d, None).unwrap();
        assert_eq!(
            mr.order(),
            2,
            "λ = {lambda}, scale {scale}: uncontrollable {:?}, unobservable {:?}",
            mr.uncontrollable,
            mr.unobservable
        );
        assert_eq!(mr.unobservable.len() + mr.uncontrollable.len(), 2);
    }
}

/// Issue 24: a channel that is identically zero (input 1 drives the Jordan block at −1, output
/// 2 sees only the modes −2, −3) has minimal order 0: no poles, no zeros, G = 0 — not the
/// eigenvalues of A as its poles (before: "Poles: −1 (×2), −2, −3").
#[test]
fn identically_zero_channel_has_no_poles() {
    use ltikit::StateSpace;
    use ltikit::analysis::factored::Factored;
    let ss = StateSpace::new(
        m(
            4,
            4,
            &[
                -1., 1., 0., 0., 0., -1., 0., 0., 0., 0., -2., 1., 0., 0., 0., -3.,
            ],
        ),
        m(4, 2, &[0., 0., 1., 0., 0., 0., 0., 1.]),
        m(2, 4, &[1., 0., 0., 0., 0., 0., 1., 0.]),
        DMatrix::zeros(2, 2),
    )
    .unwrap();
    for (i, o) in [(0, 1), (1, 0)] {
        let f = Factored::from_state_space(&ss.channel(i, o).unwrap()).unwrap();
        assert!(f.is_zero());
        assert_eq!(f.order(), 0, "channel {i} → {o}: poles {:?}", f.poles());
        assert!(f.reduced_poles().is_empty());
    }
    // the non-zero channel 1 → 1 keeps the model's eigenvalues as given, −2 and −3 cancelled
    let f = Factored::from_state_space(&ss.channel(0, 0).unwrap()).unwrap();
    assert_eq!(f.order(), 4);
    assert_eq!(f.reduced_poles().len(), 1); // −1 (×2)
}
