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
