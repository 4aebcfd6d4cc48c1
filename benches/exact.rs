//! `cargo bench --bench exact`: the exact path (issue 11) against the numerical `Poly::roots`
//! on the same polynomials. Degrees 4, 10 and 50 are the fixed random polynomials of
//! `benches/compare/inputs.toml` (uniform(−1, 1) coefficients, ≤ 17 significant digits);
//! degree 20 is drawn the same way from a fixed linear congruential generator. The exact
//! benches start from the coefficient *text* (shortest round-trip decimal), as a plant typed
//! by a user would.

mod common;

use divan::{Bencher, black_box};
use ltikit::Poly;
use ltikit::poly::exact::{ExactPoly, certify};

fn main() {
    divan::main();
}

/// Descending coefficients of the fixed random polynomial of degree `deg`.
fn coeffs(deg: usize) -> Vec<f64> {
    match deg {
        4 | 10 | 50 => common::root_poly(deg),
        _ => {
            let mut s: u64 = 0x2545_f491_4f6c_dd1d ^ deg as u64;
            (0..=deg)
                .map(|_| {
                    s = s
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
                })
                .collect()
        }
    }
}

/// The coefficients as text (shortest round-trip decimal).
fn tokens(deg: usize) -> Vec<String> {
    coeffs(deg).iter().map(|x| format!("{x:?}")).collect()
}

/// Numerical path: `Poly::roots` (eigenvalues, multiplicities, polishing).
#[divan::bench(args = [4, 10, 20, 50])]
fn numerical_roots(bencher: Bencher, deg: usize) {
    let p = Poly::from_descending(&coeffs(deg)).unwrap();
    bencher.bench(|| black_box(&p).roots().unwrap());
}

/// Exact path from text: parse, square-free factorisation, exact half-plane counts, roots of
/// the square-free factors refined and certified.
#[divan::bench(args = [4, 10, 20, 50])]
fn exact_from_text(bencher: Bencher, deg: usize) {
    let t = tokens(deg);
    let one = ExactPoly::parse_descending(&["1"]).unwrap();
    bencher.bench(|| {
        let p = ExactPoly::parse_descending(black_box(&t)).unwrap();
        certify(&one, &p).unwrap()
    });
}

/// The exact half-plane counts alone (Routh–Hurwitz through Cauchy indices).
#[divan::bench(args = [4, 10, 20, 50])]
fn exact_counts_only(bencher: Bencher, deg: usize) {
    let p = ExactPoly::parse_descending(&tokens(deg)).unwrap();
    bencher.bench(|| black_box(&p).half_plane_counts().unwrap());
}

/// Parsing the text alone.
#[divan::bench(args = [4, 10, 20, 50])]
fn parse_only(bencher: Bencher, deg: usize) {
    let t = tokens(deg);
    bencher.bench(|| ExactPoly::parse_descending(black_box(&t)).unwrap());
}

/// (s+3)⁶(s+3.03)⁶ (degree 12, two 6-fold roots 1 % apart), exact from text.
#[divan::bench]
fn exact_clustered_degree12(bencher: Bencher) {
    // Expanded exactly (sympy), the coefficients as a user would type them.
    let t = [
        "1",
        "36.18",
        "599.9535",
        "6029.50554",
        "40902.38209215",
        "197311.3152517458",
        "694034.742784862529",
        "1793559.855638369322",
        "3379686.117748379415",
        "4528697.87319093666",
        "4096124.271530703135",
        "2245370.324781480282",
        "564135.330355546041",
    ];
    let one = ExactPoly::parse_descending(&["1"]).unwrap();
    bencher.bench(|| {
        let p = ExactPoly::parse_descending(black_box(&t)).unwrap();
        certify(&one, &p).unwrap()
    });
}
