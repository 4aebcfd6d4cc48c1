//! The norm bench and test input (`benches/ltikit.rs` module `norms`, `tests/norms.rs`,
//! `benches/compare/compare_norms.py`): a random stable 2×2 model of 30 states with 15
//! lightly damped modes, drawn from a 64-bit LCG so that python rebuilds it exactly:
//! s ← s·6364136223846793005 + 1442695040888963407 (mod 2⁶⁴), u = (s >> 11)·2⁻⁵³ ∈ \[0, 1).
//!
//! Draws in order: per mode k, ω_k = 10^(−1 + 2u) and ζ_k = 0.005 + 0.2u (the block
//! \[\[−ζω, ω√(1−ζ²)\], \[−ω√(1−ζ²), −ζω\]\]); T = I + (2u − 1)/√n row by row; B, C (2u − 1) and
//! D 0.1·(2u − 1) row by row. A = T·Λ·T⁻¹.
#![allow(dead_code)]

use ltikit::StateSpace;
use nalgebra::DMatrix;

/// The generator of the module docs.
pub struct Lcg(u64);

impl Lcg {
    /// Seeded.
    pub fn new(seed: u64) -> Lcg {
        Lcg(seed)
    }

    /// The next uniform number in \[0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// The random stable model of the module docs: `n` states (even), `m` inputs, `p` outputs.
pub fn random_stable(n: usize, m: usize, p: usize, seed: u64) -> StateSpace {
    let mut r = Lcg::new(seed);
    let mut lam = DMatrix::<f64>::zeros(n, n);
    for k in 0..n / 2 {
        let w = 10f64.powf(-1.0 + 2.0 * r.next());
        let z = 0.005 + 0.2 * r.next();
        let (re, im) = (-z * w, w * (1.0 - z * z).sqrt());
        let i = 2 * k;
        lam[(i, i)] = re;
        lam[(i + 1, i + 1)] = re;
        lam[(i, i + 1)] = im;
        lam[(i + 1, i)] = -im;
    }
    let s = 1.0 / (n as f64).sqrt();
    let mut t = DMatrix::<f64>::identity(n, n);
    for i in 0..n {
        for j in 0..n {
            t[(i, j)] += (2.0 * r.next() - 1.0) * s;
        }
    }
    let mut fill = |rows: usize, cols: usize, scale: f64| {
        let mut x = DMatrix::<f64>::zeros(rows, cols);
        for i in 0..rows {
            for j in 0..cols {
                x[(i, j)] = scale * (2.0 * r.next() - 1.0);
            }
        }
        x
    };
    let b = fill(n, m, 1.0);
    let c = fill(p, n, 1.0);
    let d = fill(p, m, 0.1);
    let t_inv = t.clone().try_inverse().expect("T invertible");
    let a = &t * lam * t_inv;
    StateSpace::new(a, b, c, d).expect("the random model")
}
