//! State-space time responses (exact discretisation) against closed forms.

use ltikit::StateSpace;
use ltikit::analysis::ss::{Hold, InputSignal};
use nalgebra::DMatrix;

mod common;
use common::{grid, tf};

fn ss(a: &[f64], b: &[f64], c: &[f64], d: &[f64], n: usize, m: usize, p: usize) -> StateSpace {
    StateSpace::new(
        DMatrix::from_row_slice(n, n, a),
        DMatrix::from_row_slice(n, m, b),
        DMatrix::from_row_slice(p, n, c),
        DMatrix::from_row_slice(p, m, d),
    )
    .unwrap()
}

#[test]
fn oscillator_step_impulse_and_free_response() {
    // ẍ + 0.2ẋ + x = u (ζ = 0.1, ωₙ = 1), x = [y, ẏ]: the seed's underdamped closed forms
    // (eq. 3.33): step y = 1 − e^(−0.1t)(cos ω_d t + 0.1/ω_d sin ω_d t), impulse
    // y = e^(−0.1t) sin(ω_d t)/ω_d.
    let sys = ss(
        &[0.0, 1.0, -1.0, -0.2],
        &[0.0, 1.0],
        &[1.0, 0.0],
        &[0.0],
        2,
        1,
        1,
    );
    let wd = (1.0f64 - 0.01).sqrt();
    let t = grid(30.0, 3000);
    let step = sys.step_response_from(0, &t, true).unwrap();
    let imp = sys.impulse_response_from(0, &t, false).unwrap();
    let mut err: f64 = 0.0;
    for (k, &x) in t.iter().enumerate() {
        let e = (-0.1 * x).exp();
        let ys = 1.0 - e * ((wd * x).cos() + 0.1 / wd * (wd * x).sin());
        let yi = e * (wd * x).sin() / wd;
        err = err
            .max((step.y[0][k] - ys).abs())
            .max((imp.y[0][k] - yi).abs());
        // the second state is ẏ, the impulse response
        err = err.max((step.x.as_ref().unwrap()[1][k] - yi).abs());
    }
    assert!(err < 1e-13, "{err:e}");
    // free response from y(0) = 1: y = e^(−0.1t)(cos ω_d t + 0.1/ω_d sin ω_d t)
    let free = sys
        .initial_response(&[1.0, 0.0], &[0.0, 2.5, 7.0], false)
        .unwrap();
    for (k, &x) in [0.0f64, 2.5, 7.0].iter().enumerate() {
        let want = (-0.1 * x).exp() * ((wd * x).cos() + 0.1 / wd * (wd * x).sin());
        assert!((free.y[0][k] - want).abs() < 1e-14);
    }
}

#[test]
fn agrees_with_the_transfer_function_path() {
    // (s² + 5s + 5)/(s⁴ + 1.65s³ + 5s² + 6.5s + 2) in controllable canonical form.
    let g = tf(&[1.0, 5.0, 5.0], &[1.0, 1.65, 5.0, 6.5, 2.0]);
    let t = grid(40.0, 400);
    let a = g.step_response(&t).unwrap();
    let b = StateSpace::from_tf(&g)
        .unwrap()
        .step_response_from(0, &t, false)
        .unwrap();
    let err =
        a.y.iter()
            .zip(&b.y[0])
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
    assert!(err < 1e-12, "{err:e}");
}

#[test]
fn mimo_channels_are_independent() {
    // two decoupled first-order systems, y1 = x1 + x2: a step on input 2 moves x2 only
    let sys = ss(
        &[-1.0, 0.0, 0.0, -3.0],
        &[1.0, 0.0, 0.0, 2.0],
        &[1.0, 1.0, 0.0, 1.0],
        &[0.0, 0.5, 0.0, 0.0],
        2,
        2,
        2,
    );
    let r = sys.step_response_from(1, &[0.0, 1.0], true).unwrap();
    let x2 = 2.0 / 3.0 * (1.0 - (-3.0f64).exp());
    assert!((r.y[0][1] - (x2 + 0.5)).abs() < 1e-15); // D feeds input 2 to output 1
    assert!((r.y[1][1] - x2).abs() < 1e-15);
    assert_eq!(r.x.as_ref().unwrap()[0][1], 0.0);
    assert!(sys.step_response_from(2, &[1.0], false).is_err());
}

#[test]
fn lsim_holds() {
    // ẋ = −x + u, y = x with u = sin t sampled every 0.05 s. First-order hold: the exact
    // response to the piecewise-linear interpolant; zero-order hold: to the staircase. Both
    // against the closed forms integrated piece by piece (independent of the library).
    let sys = ss(&[-1.0], &[1.0], &[1.0], &[0.0], 1, 1, 1);
    let h = 0.05;
    let t: Vec<f64> = (0..=200).map(|k| k as f64 * h).collect();
    let sig = InputSignal {
        u: t.iter().map(|x| vec![x.sin()]).collect(),
        t: t.clone(),
    };
    let zoh = sys.lsim(&sig, Hold::Zero, None, false).unwrap();
    let foh = sys.lsim(&sig, Hold::First, None, false).unwrap();
    let (mut xz, mut xf) = (0.0f64, 0.0f64);
    let e = (-h).exp();
    for k in 0..t.len() - 1 {
        assert!((zoh.y[0][k] - xz).abs() < 1e-14 && (foh.y[0][k] - xf).abs() < 1e-14);
        let (u0, u1) = (t[k].sin(), t[k + 1].sin());
        let slope = (u1 - u0) / h;
        xz = e * xz + (1.0 - e) * u0;
        // ẋ = −x + u0 + slope·τ: x(h) = e x + (1 − e)(u0 − slope) + slope·h
        xf = e * xf + (1.0 - e) * (u0 - slope) + slope * h;
    }
    // and FOH tracks the continuous-input response closely: y → (sin t − cos t)/2 + e^(−t)/2
    let last = t.len() - 1;
    let tl = t[last];
    let want = (tl.sin() - tl.cos()) / 2.0 + (-tl).exp() / 2.0;
    assert!((foh.y[0][last] - want).abs() < 1e-3);
    // bad signals
    let bad = InputSignal {
        t: vec![0.0, 0.0],
        u: vec![vec![1.0], vec![1.0]],
    };
    assert!(sys.lsim(&bad, Hold::Zero, None, false).is_err());
    let ragged = InputSignal {
        t: vec![0.0, 1.0],
        u: vec![vec![1.0], vec![1.0, 2.0]],
    };
    assert!(sys.lsim(&ragged, Hold::Zero, None, false).is_err());
    assert!(sys.initial_response(&[1.0, 2.0], &[1.0], false).is_err());
}

/// A dense model with a closed-form response: A = H·Λ·H with Λ block diagonal (2×2 blocks
/// [[σ, ω], [−ω, σ]]) and H = I − 2vvᵀ/vᵀv a Householder reflector (orthogonal, symmetric),
/// B = H·b̂, C = ĉ·H. Then C·e^(At)·B = ĉ·e^(Λt)·b̂ and the step response is
/// ĉ·∫₀ᵗe^(Λτ)dτ·b̂, each block by (e^((σ+jω)t) − 1)/(σ + jω) = I_c + j·I_s acting as
/// [[I_c, I_s], [−I_s, I_c]].
struct RotatedBlocks {
    ss: StateSpace,
    sigma: Vec<f64>,
    omega: Vec<f64>,
    b: Vec<f64>,
    c: Vec<Vec<f64>>,
}

fn rotated_blocks(pairs: usize, outputs: usize) -> RotatedBlocks {
    let n = 2 * pairs;
    let sigma: Vec<f64> = (0..pairs)
        .map(|k| -0.1 - 1.9 * k as f64 / pairs as f64)
        .collect();
    let omega: Vec<f64> = (0..pairs)
        .map(|k| 0.5 + 4.5 * ((k * 7) % pairs) as f64 / pairs as f64)
        .collect();
    let mut lam = DMatrix::zeros(n, n);
    for k in 0..pairs {
        let i = 2 * k;
        lam[(i, i)] = sigma[k];
        lam[(i + 1, i + 1)] = sigma[k];
        lam[(i, i + 1)] = omega[k];
        lam[(i + 1, i)] = -omega[k];
    }
    let v = nalgebra::DVector::from_fn(n, |i, _| 1.0 + ((i * 5) % 11) as f64 / 3.0);
    let h = DMatrix::identity(n, n) - &v * v.transpose() * (2.0 / v.norm_squared());
    let b: Vec<f64> = (0..n).map(|i| (((i * 3) % 7) as f64 - 3.0) / 3.0).collect();
    let c: Vec<Vec<f64>> = (0..outputs)
        .map(|o| {
            (0..n)
                .map(|j| (((j + o) * 5 % 9) as f64 - 4.0) / 4.0)
                .collect()
        })
        .collect();
    let bm = DMatrix::from_column_slice(n, 1, &b);
    let cm = DMatrix::from_fn(outputs, n, |o, j| c[o][j]);
    let ss = StateSpace::new(&h * &lam * &h, &h * bm, cm * &h, DMatrix::zeros(outputs, 1)).unwrap();
    RotatedBlocks {
        ss,
        sigma,
        omega,
        b,
        c,
    }
}

impl RotatedBlocks {
    /// Output `o` at t: the step response (`step`) or the impulse response.
    fn exact(&self, o: usize, t: f64, step: bool) -> f64 {
        let mut y = 0.0;
        for (k, (&s, &w)) in self.sigma.iter().zip(&self.omega).enumerate() {
            let z = num_complex::Complex64::new(s, w);
            let e = (z * t).exp();
            let m = if step { (e - 1.0) / z } else { e };
            let (b1, b2) = (self.b[2 * k], self.b[2 * k + 1]);
            let x1 = m.re * b1 + m.im * b2;
            let x2 = -m.im * b1 + m.re * b2;
            y += self.c[o][2 * k] * x1 + self.c[o][2 * k + 1] * x2;
        }
        y
    }
}

#[test]
fn long_uniform_runs_marched_by_blocks_match_the_closed_form() {
    // 64 dense states without structure, two outputs, 5 001 samples over 50 s: the dense
    // march takes blocks of samples (block_march; its unit test checks that this size does);
    // the step and impulse responses against
    // the closed form, and against the sample-by-sample march (asking for the states turns
    // the blocks off)
    let m = rotated_blocks(32, 2);
    let t = grid(50.0, 5001);
    for step in [true, false] {
        let r = if step {
            m.ss.step_response_from(0, &t, false).unwrap()
        } else {
            m.ss.impulse_response_from(0, &t, false).unwrap()
        };
        let plain = if step {
            m.ss.step_response_from(0, &t, true).unwrap()
        } else {
            m.ss.impulse_response_from(0, &t, true).unwrap()
        };
        for o in 0..2 {
            let exact: Vec<f64> = t.iter().map(|&x| m.exact(o, x, step)).collect();
            let scale = exact.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let err = r.y[o]
                .iter()
                .zip(&exact)
                .fold(0.0f64, |a, (y, e)| a.max((y - e).abs()))
                / scale;
            let vs_plain = r.y[o]
                .iter()
                .zip(&plain.y[o])
                .fold(0.0f64, |a, (y, e)| a.max((y - e).abs()))
                / scale;
            assert!(err < 1e-12, "step {step}, output {o}: {err:e}");
            assert!(vs_plain < 1e-12, "step {step}, output {o}: {vs_plain:e}");
        }
    }
    // a grid that changes its step mid-way (blocks, then a settled state, then blocks again)
    let mut t2 = grid(20.0, 2001);
    t2.extend((1..=1000).map(|k| 20.0 + 0.037 * k as f64));
    let r = m.ss.step_response_from(0, &t2, false).unwrap();
    let worst = t2
        .iter()
        .zip(&r.y[1])
        .fold(0.0f64, |a, (&x, y)| a.max((y - m.exact(1, x, true)).abs()));
    assert!(worst < 1e-12, "{worst:e}");
}
