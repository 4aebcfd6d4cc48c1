//! State-space analysis of whole (MIMO) models (`StateSpace::analysis`,
//! `StateSpace::channel_zeros`, `StateSpace::freq_response_mimo`).

use std::f64::consts::PI;

use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

use ltikit::StateSpace;
use ltikit::analysis::ss::DcGain;
use ltikit::lti::lattice::{Boundary, Lattice, Output};

/// A 2-input, 2-output model with a third state that no input reaches:
/// x1' = −x1 + u1, x2' = −2x2 + u2, x3' = −7x3 (uncontrollable), an integrator x4' = u1
/// seen by output 2: y1 = x1 + x3, y2 = x2 + x4, D = 0.
/// Channels: G11 = 1/(s+1), G21 = 1/s, G12 = 0, G22 = 1/(s+2).
fn mimo() -> StateSpace {
    let a = DMatrix::from_diagonal(&DVector::from_vec(vec![-1.0, -2.0, -7.0, 0.0]));
    let b = DMatrix::from_row_slice(4, 2, &[1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0]);
    let c = DMatrix::from_row_slice(2, 4, &[1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0]);
    StateSpace::new(a, b, c, DMatrix::zeros(2, 2)).unwrap()
}

#[test]
fn mimo_structure_dc_gains_and_stability() {
    let r = mimo().analysis().unwrap();
    assert_eq!((r.n, r.m, r.p), (4, 2, 2));
    assert_eq!(r.controllability.rank, 3);
    assert_eq!(r.observability.rank, 4);
    assert!(r.controllability.tol > 0.0 && r.controllability.tol < 1e-12);
    assert_eq!(r.minimal_order, 3);
    assert_eq!(r.uncontrollable_modes.len(), 1);
    assert!((r.uncontrollable_modes[0].re + 7.0).abs() < 1e-14);
    // Closed forms of the channels: G11(0) = 1, G21 = 1/s (infinite), G12 = 0, G22(0) = 1/2.
    let near =
        |g: DcGain, v: f64| matches!(g, DcGain::Finite(x) if (x - v).abs() <= 4.0 * f64::EPSILON);
    assert!(near(r.dc_gain[0][0], 1.0), "{:?}", r.dc_gain);
    assert_eq!(r.dc_gain[1][0], DcGain::Infinite);
    assert!(near(r.dc_gain[0][1], 0.0), "{:?}", r.dc_gain);
    assert!(near(r.dc_gain[1][1], 0.5), "{:?}", r.dc_gain);
    assert!(!r.internally_stable && r.internal_reason.contains("marginally"));
    assert_eq!(r.bibo_stable, vec![vec![true, true], vec![false, true]]);
    // 4 real eigenvalues, all simple; modes: ωn = |λ|, ζ = 1 for the stable ones, τ = 1/|λ|.
    assert_eq!(r.eigenvalues.len(), 4);
    assert!(
        r.eigenvalues
            .iter()
            .all(|e| e.semisimple && e.algebraic == 1)
    );
    for md in &r.modes {
        assert!(md.residuals.iter().all(|&x| x < 1e-15));
        let norm: f64 = md.shapes[0]
            .iter()
            .map(|z| z.norm_sqr())
            .sum::<f64>()
            .sqrt();
        assert!((norm - 1.0).abs() < 1e-15);
        if md.value.re < 0.0 {
            assert!((md.zeta - 1.0).abs() < 1e-15);
            assert!((md.tau.unwrap() * md.wn - 1.0).abs() < 1e-15);
        }
    }
    // Square: the transmission zeros come from det G = 1/((s+1)(s+2)) against the McMillan
    // poles s(s+1)(s+2) (the minimal order is 3): Π(s − z) = s, one zero at 0. The invariant
    // zeros add the input-decoupling zero −7 (the uncontrollable mode).
    let mut z: Vec<f64> = r
        .invariant_zeros
        .unwrap()
        .iter()
        .map(|(v, _)| v.re)
        .collect();
    z.sort_by(f64::total_cmp);
    assert_eq!(z.len(), 2, "{z:?}");
    assert!((z[0] + 7.0).abs() < 1e-13 && z[1].abs() < 1e-13, "{z:?}");
    assert!(mimo().channel_zeros(0, 0).unwrap().is_empty());
    assert!(mimo().channel_zeros(2, 0).is_err());
}

/// The periodic lattice of seed §2.4 (N = 128, 256 states, ω0 = 1, force on particle 1,
/// displacement of particle 1): ±2j·sin(πk/N) semisimple doubles for 0 < k < N/2, ±2j simple,
/// 0 a 2×2 Jordan block (the free translation), so A is unstable (a defective eigenvalue on
/// the axis: the centre of mass drifts like t); mode shapes with residuals ≤ 1e-13.
#[test]
fn lattice_report() {
    let n = 128;
    let ss = Lattice::new(n, Boundary::Periodic, 1.0)
        .unwrap()
        .with_input(1)
        .unwrap()
        .with_output(Output::Particle(1))
        .unwrap()
        .state_space()
        .unwrap();
    let r = ss.analysis().unwrap();
    let mut doubles = 0;
    for e in &r.eigenvalues {
        let k = (e.value.im.abs() / 2.0).min(1.0).asin() * n as f64 / PI;
        let exact = 2.0 * (PI * k.round() / n as f64).sin();
        assert!((e.value.norm() - exact).abs() < 1e-12, "{}", e.value);
        match k.round() as usize {
            0 => assert_eq!((e.algebraic, e.geometric, e.semisimple), (2, 1, false)),
            64 => assert_eq!(e.algebraic, 1),
            _ => {
                assert_eq!((e.algebraic, e.geometric), (2, 2));
                doubles += 1;
            }
        }
    }
    assert_eq!(doubles, 126);
    assert!(
        !r.internally_stable && r.internal_reason.contains("defective"),
        "{}",
        r.internal_reason
    );
    let worst = r
        .modes
        .iter()
        .flat_map(|m| m.residuals.iter().copied())
        .fold(0.0, f64::max);
    eprintln!("lattice mode shapes: worst residual {worst:e}");
    assert!(worst < 1e-13);
}

/// All channels at once against the closed forms, and a continuous phase past −180°:
/// G11 = 1/(s+1)⁴ (a chain of four unit lags), G21 = 2/(s+1) (output 2 reads the first lag).
#[test]
fn mimo_frequency_response_and_continuous_phase() {
    let mut a = DMatrix::from_diagonal(&DVector::from_element(4, -1.0));
    for i in 1..4 {
        a[(i, i - 1)] = 1.0;
    }
    let b = DMatrix::from_row_slice(4, 1, &[1.0, 0.0, 0.0, 0.0]);
    let c = DMatrix::from_row_slice(2, 4, &[0.0, 0.0, 0.0, 1.0, 2.0, 0.0, 0.0, 0.0]);
    let ss = StateSpace::new(a, b, c, DMatrix::zeros(2, 1)).unwrap();
    let w: Vec<f64> = (0..=60)
        .map(|k| 10f64.powf(-2.0 + k as f64 / 20.0))
        .collect();
    let r = ss.freq_response_mimo(&w).unwrap();
    for (k, &x) in w.iter().enumerate() {
        let s = Complex64::new(1.0, x);
        let g11 = 1.0 / (s * s * s * s);
        assert!((r.magnitude[0][0][k] - g11.norm()).abs() <= 1e-14 * g11.norm());
        // Continuous phase of 1/(1 + jω)⁴: −4·atan ω (reaches −336° at ω = 10).
        let ph = -4.0 * x.atan().to_degrees();
        assert!(
            (r.phase_deg[0][0][k] - ph).abs() < 1e-11,
            "{x}: {}",
            r.phase_deg[0][0][k]
        );
        let g21 = 2.0 / s;
        assert!((r.magnitude[1][0][k] - g21.norm()).abs() <= 1e-15 * g21.norm() * 4.0);
    }
    assert!(ss.freq_response_mimo(&[-1.0]).is_err());
    assert!(ss.freq_response_mimo(&[f64::NAN]).is_err());
}

/// Two decoupled first-order lags x1' = −x1 + 2u, x2' = −3x2 (the input reaches only x1),
/// both states measured (y = x). Closed forms: G1 = 2/(s + 1) (dc gain 2), G2 = 0 (dc gain 0);
/// the mode −3 is uncontrollable, so the minimal order is 1; modes −1 and −3 with ζ = 1,
/// τ = 1 and 1/3 s, shapes e₁ and e₂ (A is diagonal: every value below is exact; the
/// kernels' balancing and Schur rotations leave at most a few ulps).
#[test]
fn decoupled_lags_one_input() {
    let ss = StateSpace::new(
        DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -3.0]),
        DMatrix::from_row_slice(2, 1, &[2.0, 0.0]),
        DMatrix::identity(2, 2),
        DMatrix::zeros(2, 1),
    )
    .unwrap();
    let r = ss.analysis().unwrap();
    assert_eq!((r.n, r.m, r.p), (2, 1, 2));
    assert_eq!(r.controllability.rank, 1);
    assert_eq!(r.observability.rank, 2);
    assert_eq!(r.minimal_order, 1);
    assert_eq!(r.uncontrollable_modes, vec![Complex64::new(-3.0, 0.0)]);
    assert!(r.unobservable_modes.is_empty());
    let ulps = 4.0 * f64::EPSILON;
    let near = |g: DcGain, v: f64| matches!(g, DcGain::Finite(x) if (x - v).abs() <= ulps * 2.0);
    assert!(
        near(r.dc_gain[0][0], 2.0) && near(r.dc_gain[1][0], 0.0),
        "{:?}",
        r.dc_gain
    );
    assert_eq!(r.bibo_stable, vec![vec![true], vec![true]]);
    assert!(r.internally_stable, "{}", r.internal_reason);
    assert!(
        r.internal_reason.starts_with("stable"),
        "{}",
        r.internal_reason
    );
    // One input, two outputs (issue 24: no longer refused). By hand, P(λ) = [−1−λ 0 2;
    // 0 −3−λ 0; 1 0 0; 0 1 0] has the left null vector (0, 1, 0, 3 + λ): left index 1, the
    // infinite zero of 2/(s + 1) (order 1), no finite zero (the uncontrollable −3 is absorbed
    // by the singular part: P(−3) keeps rank 3).
    assert_eq!(r.invariant_zeros, Some(Vec::new()));
    let k = r.zero_structure.as_ref().unwrap();
    assert_eq!(
        (
            k.normal_rank,
            &k.left_indices,
            &k.right_indices,
            &k.infinite_orders
        ),
        (1, &vec![1], &vec![], &vec![1])
    );
    // Sorted by decreasing real part: −1, then −3.
    let values: Vec<Complex64> = r.eigenvalues.iter().map(|e| e.value).collect();
    assert_eq!(values.len(), 2);
    assert!(values.iter().all(|v| v.im == 0.0));
    assert!((values[0].re + 1.0).abs() <= ulps && (values[1].re + 3.0).abs() <= 3.0 * ulps);
    let (m1, m3) = (&r.modes[0], &r.modes[1]);
    let close = |x: f64, v: f64| (x - v).abs() <= ulps * v.abs();
    assert!(close(m1.wn, 1.0) && m1.zeta == 1.0 && close(m1.tau.unwrap(), 1.0));
    assert!(close(m3.wn, 3.0) && m3.zeta == 1.0 && close(m3.tau.unwrap(), 1.0 / 3.0));
    for (md, k) in [(m1, 0), (m3, 1)] {
        assert_eq!((md.algebraic, md.shapes.len()), (1, 1));
        for (i, z) in md.shapes[0].iter().enumerate() {
            let want = if i == k { 1.0 } else { 0.0 };
            assert!(
                (z.norm() - want).abs() <= ulps,
                "shape of {}: {:?}",
                md.value,
                md.shapes[0]
            );
        }
        assert!(md.residuals[0] <= ulps, "{:?}", md.residuals);
    }
}

/// Resonance x'' + x = z, z'' + z = u: A has ±j as a 2×2 Jordan block each (the solution
/// grows like t·sin t), so A is unstable although every eigenvalue is on the axis; the
/// channel G = 1/(s² + 1)² is not BIBO stable.
#[test]
fn jordan_block_on_the_axis_is_unstable() {
    let a = DMatrix::from_row_slice(
        4,
        4,
        &[
            0.0, 1.0, 0.0, 0.0, //
            -1.0, 0.0, 1.0, 0.0, //
            0.0, 0.0, 0.0, 1.0, //
            0.0, 0.0, -1.0, 0.0,
        ],
    );
    let b = DMatrix::from_row_slice(4, 1, &[0.0, 0.0, 0.0, 1.0]);
    let c = DMatrix::from_row_slice(1, 4, &[1.0, 0.0, 0.0, 0.0]);
    let ss = StateSpace::new(a, b, c, DMatrix::zeros(1, 1)).unwrap();
    let r = ss.analysis().unwrap();
    assert_eq!(r.eigenvalues.len(), 2);
    for e in &r.eigenvalues {
        // Exactly on the axis (the rule of the factored core), ±1 to rounding.
        assert_eq!(e.value.re, 0.0, "{}", e.value);
        assert!((e.value.im.abs() - 1.0).abs() < 1e-14, "{}", e.value);
        assert_eq!((e.algebraic, e.geometric, e.semisimple), (2, 1, false));
    }
    assert!(!r.internally_stable);
    assert!(
        r.internal_reason
            .starts_with("unstable: eigenvalue ±1j on the imaginary axis is defective"),
        "{}",
        r.internal_reason
    );
    assert_eq!(r.bibo_stable, vec![vec![false]]);
    assert_eq!(r.minimal_order, 4);
    // One mode (the upper member), one shape (geometric 1), ζ = 0, no time constant.
    assert_eq!(r.modes.len(), 1);
    let md = &r.modes[0];
    assert_eq!(
        (md.algebraic, md.shapes.len(), md.zeta, md.tau),
        (2, 1, 0.0, None)
    );
    // G(0) = 1: the channel's poles are ±j, not 0, so the dc gain is finite.
    assert!(matches!(r.dc_gain[0][0], DcGain::Finite(g) if (g - 1.0).abs() < 1e-14));
}

/// Two identical undamped oscillators x'' = −x: ±j with algebraic and geometric multiplicity
/// 2 (A = diag(J, J), semisimple), so A is marginally stable: bounded, not asymptotically
/// stable.
#[test]
fn semisimple_double_eigenvalue_on_the_axis_is_marginal() {
    let a = DMatrix::from_row_slice(
        4,
        4,
        &[
            0.0, 1.0, 0.0, 0.0, //
            -1.0, 0.0, 0.0, 0.0, //
            0.0, 0.0, 0.0, 1.0, //
            0.0, 0.0, -1.0, 0.0,
        ],
    );
    let b = DMatrix::from_row_slice(4, 2, &[0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
    let c = DMatrix::from_row_slice(2, 4, &[1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    let ss = StateSpace::new(a, b, c, DMatrix::zeros(2, 2)).unwrap();
    let r = ss.analysis().unwrap();
    assert_eq!(r.eigenvalues.len(), 2);
    for e in &r.eigenvalues {
        assert_eq!(e.value.re, 0.0, "{}", e.value);
        assert!((e.value.im.abs() - 1.0).abs() < 1e-14, "{}", e.value);
        assert_eq!((e.algebraic, e.geometric, e.semisimple), (2, 2, true));
    }
    assert!(!r.internally_stable);
    assert!(
        r.internal_reason.starts_with(
            "marginally stable: eigenvalue ±1j on the imaginary axis (semisimple, multiplicity 2)"
        ),
        "{}",
        r.internal_reason
    );
    // Two independent shapes, each an exact eigenvector.
    let md = &r.modes[0];
    assert_eq!(md.shapes.len(), 2);
    assert!(
        md.residuals.iter().all(|&x| x < 1e-15),
        "{:?}",
        md.residuals
    );
    // G = diag(1/(s² + 1), 1/(s² + 1)): dc gains 1 and 0, no channel BIBO stable or coupled.
    assert_eq!(r.bibo_stable, vec![vec![false, true], vec![true, false]]);
    let near = |g: DcGain, v: f64| matches!(g, DcGain::Finite(x) if (x - v).abs() < 1e-14);
    assert!(near(r.dc_gain[0][0], 1.0) && near(r.dc_gain[1][1], 1.0));
    assert!(near(r.dc_gain[0][1], 0.0) && near(r.dc_gain[1][0], 0.0));
    // Square and invertible: det G = 1/(s² + 1)² has no finite zeros.
    assert_eq!(r.invariant_zeros, Some(vec![]));
}

/// The README's two tanks: A = [[−1, 0.5], [0.5, −2]], B = C = I, D = 0. By hand:
/// det A = 2 − 0.25 = 1.75, so G(0) = −C·A⁻¹·B = −A⁻¹ = [[2, 0.5], [0.5, 1]]/1.75
/// = [[8/7, 2/7], [2/7, 4/7]]; eigenvalues (−3 ± √2)/2 from λ² + 3λ + 1.75 = 0; minimal,
/// no invariant zeros (G = (sI − A)⁻¹, det G = 1/det(sI − A)).
#[test]
fn two_tanks_dc_gain_matrix_by_hand() {
    let ss = StateSpace::new(
        DMatrix::from_row_slice(2, 2, &[-1.0, 0.5, 0.5, -2.0]),
        DMatrix::identity(2, 2),
        DMatrix::identity(2, 2),
        DMatrix::zeros(2, 2),
    )
    .unwrap();
    let r = ss.analysis().unwrap();
    let want = [[8.0 / 7.0, 2.0 / 7.0], [2.0 / 7.0, 4.0 / 7.0]];
    for (j, row) in want.iter().enumerate() {
        for (i, &g) in row.iter().enumerate() {
            let DcGain::Finite(x) = r.dc_gain[j][i] else {
                panic!("infinite dc gain {j},{i}");
            };
            assert!((x - g).abs() <= 4.0 * f64::EPSILON, "{j},{i}: {x} vs {g}");
        }
    }
    let s2 = 2f64.sqrt();
    let ev: Vec<f64> = r.eigenvalues.iter().map(|e| e.value.re).collect();
    assert_eq!(
        r.eigenvalues.iter().filter(|e| e.value.im == 0.0).count(),
        2
    );
    assert!((ev[0] - (-3.0 + s2) / 2.0).abs() < 1e-15, "{ev:?}");
    assert!((ev[1] - (-3.0 - s2) / 2.0).abs() < 1e-15, "{ev:?}");
    assert_eq!(r.minimal_order, 2);
    assert!(r.uncontrollable_modes.is_empty() && r.unobservable_modes.is_empty());
    assert_eq!(r.invariant_zeros, Some(vec![]));
    assert!(r.internally_stable);
    assert_eq!(r.bibo_stable, vec![vec![true; 2]; 2]);
    // A is symmetric: its eigenvectors are orthogonal, (1, s)/|·| with s = (λ + 1)/0.5.
    for md in &r.modes {
        let v = &md.shapes[0];
        let ratio = v[1].re / v[0].re;
        assert!((ratio - (md.value.re + 1.0) / 0.5).abs() < 1e-14, "{v:?}");
    }
}

/// A square system whose transfer matrix is singular for every s (both inputs enter the same
/// way, B = [b b]): refused before issue 24, now its zeros come from the regular part of the
/// pencil. By hand, P(λ) = [−1−λ 0 1 1; 0 −2−λ 1 1; 1 0 0 0; 0 1 0 0] has the constant right
/// null vector (0, 0, 1, −1) (right index 0), the left null vector (1, −1, 1 + λ, −2 − λ)
/// (left index 1) and G's infinite zero of order 1: 1 + 2 + 2 columns of blocks, 4 rows —
/// no finite zero. The rest of the analysis is computed as for any model.
#[test]
fn normal_rank_deficient_square_system_keeps_the_rest() {
    let ss = StateSpace::new(
        DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -2.0]),
        DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0]),
        DMatrix::identity(2, 2),
        DMatrix::zeros(2, 2),
    )
    .unwrap();
    let r = ss.analysis().unwrap();
    assert_eq!(
        r.invariant_zeros,
        Some(Vec::new()),
        "{:?}",
        r.invariant_zeros_note
    );
    let k = r.zero_structure.as_ref().unwrap();
    assert_eq!(k.normal_rank, 1);
    assert_eq!(k.left_indices, vec![1]);
    assert_eq!(k.right_indices, vec![0]);
    assert_eq!(k.infinite_orders, vec![1]);
    // G = [[1/(s+1), 1/(s+1)], [1/(s+2), 1/(s+2)]]: dc gains 1, 1, 1/2, 1/2.
    let want = [[1.0, 1.0], [0.5, 0.5]];
    for (j, row) in want.iter().enumerate() {
        for (i, &g) in row.iter().enumerate() {
            assert!(
                matches!(r.dc_gain[j][i], DcGain::Finite(x) if (x - g).abs() <= 4.0 * f64::EPSILON),
                "{:?}",
                r.dc_gain
            );
        }
    }
}

/// The periodic 16-ring (seed §2.4, eq. 2.71): ωₚ = 2 sin(πp/16); p = 0 is the free
/// translation, a 2×2 Jordan block at 0; p and 16 − p are degenerate (semisimple doubles
/// ±jωₚ, p = 1…7); p = 8 is the simple ±2j. Every eigenvalue but 0 lies exactly on the axis
/// (real part 0, not ±1e-16), with ζ = 0 and no time constant.
#[test]
fn periodic_lattice_eigenvalues_on_the_axis() {
    let n = 16;
    let ss = Lattice::new(n, Boundary::Periodic, 1.0)
        .unwrap()
        .with_output(Output::Particle(3))
        .unwrap()
        .state_space()
        .unwrap();
    let r = ss.analysis().unwrap();
    assert!(!r.internally_stable);
    assert!(
        r.internal_reason
            .starts_with("unstable: eigenvalue 0 on the imaginary axis is defective (a Jordan block of algebraic multiplicity 2, geometric 1)"),
        "{}",
        r.internal_reason
    );
    let mut seen = [0usize; 9];
    for e in &r.eigenvalues {
        assert_eq!(e.value.re, 0.0, "{}", e.value);
        let w = e.value.im.abs();
        let p = ((w / 2.0).min(1.0).asin() * n as f64 / PI).round() as usize;
        let exact = 2.0 * (PI * p as f64 / n as f64).sin();
        assert!((w - exact).abs() < 1e-14, "{} vs {exact}", e.value);
        let want = match p {
            0 => (2, 1, false),
            8 => (1, 1, true),
            _ => (2, 2, true),
        };
        assert_eq!((e.algebraic, e.geometric, e.semisimple), want, "p = {p}");
        seen[p] += 1;
    }
    // 0 once, ±jωₚ twice (both signs) for p = 1…8.
    assert_eq!(seen, [1, 2, 2, 2, 2, 2, 2, 2, 2]);
    for md in r.modes.iter().filter(|m| m.wn > 0.0) {
        assert_eq!((md.zeta, md.tau), (0.0, None), "{}", md.value);
    }
    // The removed modes are given the eigenvalues' values: exactly on the axis.
    assert!(
        r.uncontrollable_modes
            .iter()
            .chain(&r.unobservable_modes)
            .all(|z| z.re == 0.0)
    );
    // The channel force 1 → displacement 3 has the double pole at 0: not BIBO stable.
    assert_eq!(r.bibo_stable, vec![vec![false]]);
    assert_eq!(r.dc_gain, vec![vec![DcGain::Infinite]]);
}

/// The fixed 16-chain without damping: ωₖ = 2 sin(πk/34), k = 1…16, all simple and exactly on
/// the axis: marginally stable.
#[test]
fn fixed_lattice_is_marginally_stable() {
    let n = 16;
    let ss = Lattice::new(n, Boundary::Fixed, 1.0)
        .unwrap()
        .with_output(Output::Particle(3))
        .unwrap()
        .state_space()
        .unwrap();
    let r = ss.analysis().unwrap();
    assert_eq!(r.eigenvalues.len(), 2 * n);
    let mut w: Vec<f64> = r
        .eigenvalues
        .iter()
        .filter(|e| e.value.im > 0.0)
        .map(|e| e.value.im)
        .collect();
    w.sort_by(f64::total_cmp);
    for (k, w) in w.iter().enumerate() {
        let exact = 2.0 * (PI * (k + 1) as f64 / (2.0 * (n + 1) as f64)).sin();
        assert!((w - exact).abs() < 1e-14, "k = {}: {w} vs {exact}", k + 1);
    }
    assert!(
        r.eigenvalues
            .iter()
            .all(|e| e.value.re == 0.0 && e.algebraic == 1 && e.semisimple)
    );
    assert!(!r.internally_stable);
    assert!(
        r.internal_reason.starts_with("marginally stable"),
        "{}",
        r.internal_reason
    );
    assert_eq!(r.bibo_stable, vec![vec![false]]);
}

/// `StateSpace::dc_gain_direct` (one LU solve) against the whole-model analysis, channel by
/// channel, on a stable model with a mode it cannot see; `None` when A has an eigenvalue at 0
/// (the integrator of `mimo()`), in continuous and discrete time.
#[test]
fn direct_dc_gain_matches_the_analysis() {
    let mut m = mimo();
    m.a[(3, 3)] = -0.5; // the integrator becomes 1/(s + 0.5): every gain finite
    let direct = m.dc_gain_direct().unwrap().unwrap();
    let r = m.analysis().unwrap();
    for (i, row) in r.dc_gain.iter().enumerate() {
        for (j, g) in row.iter().enumerate() {
            let DcGain::Finite(g) = g else {
                panic!("finite expected: {g:?}")
            };
            assert!((direct[(i, j)] - g).abs() <= 1e-14, "{i},{j}: {direct} {g}");
        }
    }
    // G21 = 1/(s + 0.5): 2
    assert!((direct[(1, 0)] - 2.0).abs() <= 1e-15);
    assert!(mimo().dc_gain_direct().unwrap().is_none());
    // discrete time: x[k+1] = 0.5·x[k] + u, y = x: G(1) = 1/(1 − 0.5) = 2; a pole at z = 1: None
    let d = |a: f64| {
        StateSpace::new(
            DMatrix::from_element(1, 1, a),
            DMatrix::from_element(1, 1, 1.0),
            DMatrix::from_element(1, 1, 1.0),
            DMatrix::zeros(1, 1),
        )
        .unwrap()
        .with_domain(ltikit::lti::Domain::Discrete { dt: 0.1 })
    };
    let g = d(0.5).dc_gain_direct().unwrap().unwrap();
    assert!((g[(0, 0)] - 2.0).abs() <= 1e-15);
    assert!(d(1.0).dc_gain_direct().unwrap().is_none());
}
