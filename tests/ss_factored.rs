//! The factored core reached from state space (`Factored::from_state_space`): poles are the
//! eigenvalues of A, zeros the transmission zeros, the gain the first non-zero Markov
//! parameter, removed modes the cancelled roots — no coefficients formed.

use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

use ltikit::StateSpace;
use ltikit::TransferFunction;
use ltikit::analysis::Factored;
use ltikit::lti::lattice::{Boundary, Lattice, Output};
use ltikit::poly::{Poly, Root};

/// G(s) = Σ_{k=1}^{20} 1/(s + k) = D'(s)/D(s), D = (s + 1)(s + 2)…(s + 20), given as
/// A = diag(−1, …, −20), B = C = ones (exact integer data).
fn wilkinson_ss() -> StateSpace {
    let a = DMatrix::from_diagonal(&DVector::from_fn(20, |k, _| -((k + 1) as f64)));
    StateSpace::new(
        a,
        DMatrix::from_element(20, 1, 1.0),
        DMatrix::from_element(1, 20, 1.0),
        DMatrix::zeros(1, 1),
    )
    .unwrap()
}

/// The same G through coefficients: D expanded in f64 (its coefficients reach 20! ≈ 2.4e18
/// and are rounded), N = D'.
fn wilkinson_tf() -> TransferFunction {
    let roots: Vec<Root> = (1..=20)
        .map(|k| Root::new(Complex64::new(-(k as f64), 0.0), 1))
        .collect();
    let d = Poly::from_root_list(&roots).unwrap();
    TransferFunction::new(d.derivative(), d).unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// References: 50-digit mpmath on the exact partial fractions y(t) = Σ (1 − e^(−kt))/k
/// (y∞ = H₂₀) and G(jω) = Σ 1/(jω + k): the 10 %, 90 % and 98 % crossings by findroot (the
/// response is monotone: its impulse response Σ e^(−kt) is positive, so the 2 % settling time
/// is the 98 % crossing), |G(jω_c)| = 1 and |G(jω_b)| = 10^(−3/20)·H₂₀ (the bandwidth
/// convention of `margins`) by findroot.
const Y_INF: f64 = 3.597739657143681911483769068908387793836710245379;
const T10: f64 = 0.019891175906998635767020230574457745831543632551853;
const T90: f64 = 1.1967788849410608681089377241945504503258038081173;
const T98: f64 = 2.6674789072109822499435464360666851367555388796676;
const W_C: f64 = 16.051740826154981524040687125382511169834828264857;
const PM_DEG: f64 = 118.90638710135078583693764438994970795711451231574;
const W_B: f64 = 2.183940763598877737675315991473960261704974844839;

struct Errors {
    poles: f64,
    dc: f64,
    rise: f64,
    settling: f64,
    pm: f64,
    wc: f64,
    wb: f64,
}

fn errors(f: &Factored) -> Errors {
    let mut poles: Vec<f64> = f
        .poles()
        .iter()
        .flat_map(|r| std::iter::repeat_n(r.value, r.multiplicity))
        .map(|v| v.re + v.im.abs())
        .collect();
    poles.sort_by(|a, b| b.total_cmp(a));
    let pole_err = if poles.len() == 20 {
        poles
            .iter()
            .enumerate()
            .map(|(k, p)| rel(*p, -((k + 1) as f64)))
            .fold(0.0, f64::max)
    } else {
        f64::INFINITY
    };
    let info = f.step_info().unwrap().unwrap();
    let m = f.margins().unwrap();
    Errors {
        poles: pole_err,
        dc: rel(f.dc_gain().unwrap(), Y_INF),
        rise: rel(info.rise_time.unwrap(), T90 - T10),
        settling: rel(info.settling_time.unwrap(), T98),
        pm: rel(m.phase_margin_deg.unwrap(), PM_DEG),
        wc: rel(m.gain_crossover.unwrap(), W_C),
        wb: rel(m.bandwidth.unwrap(), W_B),
    }
}

#[test]
fn wilkinson_poles_exact_from_state_space() {
    let f = Factored::from_state_space(&wilkinson_ss()).unwrap();
    let e = errors(&f);
    eprintln!(
        "state space: poles {:e}, dc {:e}, rise {:e}, settling {:e}, PM {:e}, ωc {:e}, ωb {:e}",
        e.poles, e.dc, e.rise, e.settling, e.pm, e.wc, e.wb
    );
    assert!(e.poles <= 1e-15, "{:e}", e.poles);
    assert_eq!(f.order(), 20);
    assert_eq!(f.relative_degree(), Some(1));
    assert!(f.pole_zero().cancelled.is_empty());
    assert!(
        (f.gain() - 20.0).abs() <= 1e-13 * 20.0,
        "CB = 20: {}",
        f.gain()
    );
    assert!(e.dc < 1e-14, "{:e}", e.dc);
    for (what, err) in [
        ("rise", e.rise),
        ("settling", e.settling),
        ("PM", e.pm),
        ("ωc", e.wc),
        ("ωb", e.wb),
    ] {
        assert!(err < 1e-11, "{what}: {err:e}");
    }
    assert!(
        f.margins().unwrap().gain_margin.is_none(),
        "phase never reaches −180°"
    );
}

/// The coefficient path on the same plant, for comparison (its errors are printed, not
/// bounded: the root finder sees the rounded coefficients of D, whose roots move by up to 1e-2
/// (Wilkinson)). Run with `--nocapture` to see both paths' errors.
#[test]
fn wilkinson_through_coefficients_for_comparison() {
    let f = wilkinson_tf().factored().unwrap();
    let pole_err = {
        let mut p: Vec<f64> = f
            .poles()
            .iter()
            .flat_map(|r| std::iter::repeat_n(r.value.re, r.multiplicity))
            .collect();
        p.sort_by(|a, b| b.total_cmp(a));
        p.iter()
            .enumerate()
            .map(|(k, v)| rel(*v, -((k + 1) as f64)))
            .fold(0.0, f64::max)
    };
    eprintln!("coefficients: poles {pole_err:e}");
    let info = f.step_info();
    let m = f.margins();
    if let (Ok(Some(info)), Ok(m)) = (&info, &m) {
        eprintln!(
            "coefficients: dc {:e}, rise {:e}, settling {:e}, PM {:?}, ωc {:?}, ωb {:?}",
            rel(f.dc_gain().unwrap_or(f64::NAN), Y_INF),
            rel(info.rise_time.unwrap(), T90 - T10),
            rel(info.settling_time.unwrap(), T98),
            m.phase_margin_deg.map(|x| rel(x, PM_DEG)),
            m.gain_crossover.map(|x| rel(x, W_C)),
            m.bandwidth.map(|x| rel(x, W_B)),
        );
    } else {
        eprintln!("coefficients: step_info {info:?}, margins {m:?}");
    }
    // The coefficient path must at least see 20 poles; the state-space path is the accurate one.
    assert_eq!(f.order(), 20);
}

/// A mode that the input cannot reach is reported as cancelled, and the reduced G is that of
/// the minimal part: diag(−1, −2, −7) with B = (1, 1, 0): G = 1/(s+1) + 1/(s+2), −7 removed.
#[test]
fn uncontrollable_mode_is_cancelled() {
    let a = DMatrix::from_diagonal(&DVector::from_vec(vec![-1.0, -2.0, -7.0]));
    let b = DMatrix::from_column_slice(3, 1, &[1.0, 1.0, 0.0]);
    let c = DMatrix::from_row_slice(1, 3, &[1.0, 1.0, 1.0]);
    let ss = StateSpace::new(a, b, c, DMatrix::zeros(1, 1)).unwrap();
    let f = Factored::from_state_space(&ss).unwrap();
    assert_eq!(f.order(), 3);
    let pz = f.pole_zero();
    assert_eq!(pz.cancelled.len(), 1);
    assert!((pz.cancelled[0].value.re + 7.0).abs() < 1e-14);
    assert_eq!(f.reduced_poles().len(), 2);
    // G = (2s + 3)/((s + 1)(s + 2)): zero −1.5, gain 2, dc 1.5.
    assert_eq!(f.reduced_zeros().len(), 1);
    assert!((f.reduced_zeros()[0].value.re + 1.5).abs() < 1e-14);
    assert!((f.gain() - 2.0).abs() < 1e-14);
    assert!((f.dc_gain().unwrap() - 1.5).abs() < 1e-15);
    let s = Complex64::new(0.3, 2.0);
    let exact = 1.0 / (s + 1.0) + 1.0 / (s + 2.0);
    assert!((f.eval(s) - exact).norm() < 1e-15 * exact.norm() * 4.0);
}

/// A 256-state channel of the seed's lattice (§2.4, N = 128, fixed ends, light damping): the
/// whole factored analysis runs without coefficients.
#[test]
fn lattice_channel_256_states() {
    let lat = Lattice::new(128, Boundary::Fixed, 1.0)
        .unwrap()
        .with_damping(0.02, 0.0)
        .unwrap()
        .with_input(10)
        .unwrap()
        .with_output(Output::Particle(20))
        .unwrap();
    let ss = lat.state_space().unwrap();
    assert_eq!(ss.order(), 256);
    let f = Factored::from_state_space(&ss).unwrap();
    assert_eq!(f.order(), 256);
    let a = f.analyze().unwrap();
    assert!(a.stability.bibo_stable);
    let m = f.margins().unwrap();
    let fr = f.freq_response(&[0.1, 1.0, 1.9]).unwrap();
    let t: Vec<f64> = (0..200).map(|k| k as f64 * 0.5).collect();
    let y = f.step_response(&t).unwrap();
    let _ = (f.nyquist().unwrap(), f.bode_asymptotes(1e-2, 1e1).unwrap());
    // dc gain by a solve against G(j·1e-9) from the Hessenberg kernel.
    let dc = f.dc_gain().unwrap();
    let g0 = f.eval(Complex64::new(0.0, 1e-9)).re;
    assert!((dc - g0).abs() <= 1e-6 * dc.abs(), "{dc} vs {g0}");
    assert!(y.y.iter().all(|v| v.is_finite()));
    assert_eq!(fr.magnitude.len(), 3);
    let _ = m;
}

/// A dense 5-state channel with integer data and relative degree 1 (C·B = 4): its zeros come
/// from the staircases' Hessenberg form (the zero dynamics, one Hessenberg eigenproblem), to
/// near working precision. Reference: the numerator C·adj(sI − A)·B = 4s⁴ + 37s³ + 123s² +
/// 500s + 1280, formed exactly (sympy, integer arithmetic), its roots by mpmath.polyroots at
/// 40 digits (printed to 30).
#[test]
#[allow(clippy::excessive_precision)] // the references as mpmath printed them
fn hessenberg_zeros_match_a_30_digit_reference() {
    let ss = StateSpace::new(
        DMatrix::from_row_slice(
            5,
            5,
            &[
                -3.0, 1.0, 0.0, 2.0, -1.0, //
                2.0, -4.0, 1.0, 0.0, 1.0, //
                -1.0, 2.0, -5.0, 1.0, 0.0, //
                0.0, 1.0, -2.0, -2.0, 3.0, //
                1.0, 0.0, 1.0, -3.0, -6.0,
            ],
        ),
        DMatrix::from_column_slice(5, 1, &[1.0, -2.0, 0.0, 3.0, 1.0]),
        DMatrix::from_row_slice(1, 5, &[2.0, 1.0, -1.0, 0.0, 4.0]),
        DMatrix::zeros(1, 1),
    )
    .unwrap();
    let reference = [
        Complex64::new(-6.199_092_570_058_240_086_463_652_356_69, 0.0),
        Complex64::new(-3.664_620_455_139_228_924_371_567_031_66, 0.0),
        Complex64::new(
            0.306_856_512_598_734_505_417_609_694_179,
            3.740_589_098_726_605_672_966_592_519_98,
        ),
        Complex64::new(
            0.306_856_512_598_734_505_417_609_694_179,
            -3.740_589_098_726_605_672_966_592_519_98,
        ),
    ];
    let f = Factored::from_state_space(&ss).unwrap();
    assert!(
        f.structure_note()
            .contains("zero dynamics of the staircases' Hessenberg form"),
        "{}",
        f.structure_note()
    );
    let zeros: Vec<Complex64> = f
        .zeros()
        .iter()
        .flat_map(|r| std::iter::repeat_n(r.value, r.multiplicity))
        .collect();
    assert_eq!(zeros.len(), 4);
    for z in &reference {
        let err = zeros
            .iter()
            .map(|w| (w - z).norm() / z.norm())
            .fold(f64::INFINITY, f64::min);
        assert!(err < 1e-14, "zero {z}: relative error {err:e}");
    }
    assert!(
        (f.gain() - 4.0).abs() < 1e-14 * 4.0,
        "C·B = 4: {}",
        f.gain()
    );
}

/// C·B tiny against ‖C‖·‖B‖ (2⁻³⁰ against ≈ 3.7): relative degree 1 still, but eliminating
/// with that pivot would grow the zero dynamics ~10⁹-fold — the system pencil finds the
/// zeros instead (the bound of `numeric::linalg::hessenberg_zeros`).
#[test]
fn a_tiny_markov_parameter_takes_the_pencil() {
    let ss = StateSpace::new(
        DMatrix::from_row_slice(
            4,
            4,
            &[
                -2.0, 1.0, 0.0, 1.0, //
                1.0, -3.0, 2.0, 0.0, //
                0.0, 1.0, -4.0, 1.0, //
                1.0, 0.0, 1.0, -5.0,
            ],
        ),
        DMatrix::from_column_slice(4, 1, &[1.0, 1.0, 0.0, 0.0]),
        DMatrix::from_row_slice(1, 4, &[1.0, -1.0 + 2f64.powi(-30), 1.0, 2.0]),
        DMatrix::zeros(1, 1),
    )
    .unwrap();
    let f = Factored::from_state_space(&ss).unwrap();
    assert_eq!(f.relative_degree(), Some(1));
    let note = f.structure_note();
    assert!(note.contains("zeros by the system pencil"), "{note}");
    assert!(!note.contains("Hessenberg form"), "{note}");
}
