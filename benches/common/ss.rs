//! The state-space bench inputs shared by `benches/ltikit.rs` (module `ss`) and the timing
//! example behind the python comparison (`examples/bench_ss_json.rs`): the seed's periodic
//! lattice (§2.4, N = 128, ω0 = 1, 256 states) with the force on particle 1 and the
//! displacement of particle 6 measured, its grids, and the modal-sum reference loop.
#![allow(dead_code)] // each including target uses a different subset

use std::f64::consts::PI;

use ltikit::StateSpace;
use ltikit::lti::lattice::{Boundary, Lattice, Output};
use num_complex::Complex64;

/// Particles.
pub const N: usize = 128;
/// The measured particle (1-based); the force acts on particle 1.
pub const OUT: usize = 6;

/// The 256-state lattice channel.
pub fn lattice() -> StateSpace {
    Lattice::new(N, Boundary::Periodic, 1.0)
        .and_then(|l| l.with_input(1))
        .and_then(|l| l.with_output(Output::Particle(OUT)))
        .and_then(|l| l.state_space())
        .expect("the bench lattice")
}

/// The same channel with its states interleaved (q₁, q̇₁, q₂, q̇₂, …): no longer in the
/// second-order block pattern, so every kernel takes the general (Schur) path — what a
/// model without mechanical structure of this size costs.
pub fn lattice_interleaved() -> StateSpace {
    let ss = lattice();
    let n = ss.order();
    let d = n / 2;
    let old = |k: usize| if k % 2 == 0 { k / 2 } else { d + k / 2 };
    StateSpace::new(
        nalgebra::DMatrix::from_fn(n, n, |i, j| ss.a[(old(i), old(j))]),
        nalgebra::DMatrix::from_fn(n, 1, |i, _| ss.b[(old(i), 0)]),
        nalgebra::DMatrix::from_fn(1, n, |_, j| ss.c[(0, old(j))]),
        ss.d.clone(),
    )
    .expect("the interleaved lattice")
}

/// logspace(−2, 1, n) (rad/s).
pub fn freq_grid(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| 10f64.powf(-2.0 + 3.0 * k as f64 / (n - 1) as f64))
        .collect()
}

/// linspace(0, 100, n) (s).
pub fn time_grid(n: usize) -> Vec<f64> {
    (0..n).map(|k| 100.0 * k as f64 / (n - 1) as f64).collect()
}

/// The channel's modal form (Ω circulant, Fourier modes): G(s) = 1/(N·s²) + Σ_{k≥1} over the
/// 2(N − 1) simple poles λ = ±jω_k of r/(s − λ), r = ±c_k/(2jω_k·N), c_k = cos(2πk(OUT−1)/N),
/// ω_k = 2 sin(πk/N).
pub fn modal_form() -> (Vec<Complex64>, Vec<Complex64>) {
    let mut poles = Vec::with_capacity(2 * N);
    let mut res = Vec::with_capacity(2 * N);
    for k in 1..N {
        let wk = 2.0 * (PI * k as f64 / N as f64).sin();
        let ck = (2.0 * PI * (k * (OUT - 1)) as f64 / N as f64).cos();
        let r = Complex64::new(0.0, -ck / (2.0 * wk * N as f64));
        poles.push(Complex64::new(0.0, wk));
        res.push(r);
        poles.push(Complex64::new(0.0, -wk));
        res.push(-r);
    }
    (poles, res)
}

/// Reference loop: G(jω) by the modal sum, 2N − 1 complex terms per frequency.
pub fn modal_sum(poles: &[Complex64], res: &[Complex64], w: &[f64]) -> Vec<Complex64> {
    w.iter()
        .map(|&x| {
            let s = Complex64::new(0.0, x);
            let mut g = 1.0 / (N as f64 * s * s);
            for (p, r) in poles.iter().zip(res) {
                g += r / (s - p);
            }
            g
        })
        .collect()
}

/// Uniform in [−1, 1) from xorshift64 (the same numbers in `benches/compare/compare_ss.py`).
fn uniform(seed: &mut u64) -> f64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    (*seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
}

/// A random dense stable SISO system without structure: A = R/16 − I with R (256×256) uniform
/// in [−1, 1) (the spectrum of R/16 lies in a disc of radius ≈ 0.58, so A's in Re s < −0.4),
/// then b and c uniform; xorshift64 from seed 0x5eed_0256, filled row by row A, b, c.
pub fn random_dense() -> StateSpace {
    let n = 256;
    let mut s = 0x5eed_0256u64;
    let mut a = nalgebra::DMatrix::zeros(n, n);
    for i in 0..n {
        for j in 0..n {
            a[(i, j)] = uniform(&mut s) / 16.0 - if i == j { 1.0 } else { 0.0 };
        }
    }
    let b = nalgebra::DMatrix::from_fn(n, 1, |_, _| 0.0);
    let mut b = b;
    for i in 0..n {
        b[(i, 0)] = uniform(&mut s);
    }
    let mut c = nalgebra::DMatrix::zeros(1, n);
    for j in 0..n {
        c[(0, j)] = uniform(&mut s);
    }
    StateSpace::new(a, b, c, nalgebra::DMatrix::zeros(1, 1)).expect("the random dense model")
}
