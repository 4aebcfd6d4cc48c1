//! Inputs and reference loops shared by the divan benches (`benches/ltikit.rs`) and the
//! timing example behind the python comparison (`examples/bench_json.rs`, included with
//! `#[path]`). The numbers come from `benches/compare/inputs.toml`, which
//! `benches/compare/compare.py` reads too, so both sides time identical inputs.
#![allow(dead_code)] // each including target uses a different subset

pub mod discrete;
pub mod equations;
pub mod ss;

use ltikit::TransferFunction;
use ltikit::analysis::{FrequencyResponse, auto_frequency_grid};
use ltikit::plot::{BodeSeries, PlotOptions, bode_png};
use num_complex::Complex64;
use serde::Deserialize;

const INPUTS: &str = include_str!("../compare/inputs.toml");

#[derive(Deserialize)]
struct Inputs {
    roots: RootInputs,
    order8: Order8,
}

#[derive(Deserialize)]
struct RootInputs {
    deg4: Vec<f64>,
    deg10: Vec<f64>,
    deg50: Vec<f64>,
}

#[derive(Deserialize)]
struct Order8 {
    den_pairs: Vec<[f64; 2]>,
    num_gain: f64,
    num_zeros: Vec<f64>,
}

fn inputs() -> Inputs {
    toml::from_str(INPUTS).expect("benches/compare/inputs.toml parses")
}

/// The fixed random polynomial of degree 4, 10 or 50 (descending coefficients).
pub fn root_poly(deg: usize) -> Vec<f64> {
    let r = inputs().roots;
    match deg {
        4 => r.deg4,
        10 => r.deg10,
        50 => r.deg50,
        _ => panic!("no fixed polynomial of degree {deg}"),
    }
}

/// Convolution of descending coefficient lists, summed in the order of `numpy.convolve`
/// (what `np.polymul` uses), so the expanded coefficients are bitwise those of compare.py.
pub fn polymul(a: &[f64], b: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; a.len() + b.len() - 1];
    for (k, o) in out.iter_mut().enumerate() {
        let mut s = 0.0;
        for (i, &x) in a.iter().enumerate() {
            if k >= i && k - i < b.len() {
                s += x * b[k - i];
            }
        }
        *o = s;
    }
    out
}

/// The order-8 plant of compare.py as (num, den), descending:
/// den = Π(s² + 2ζωₙ s + ωₙ²) over (ωₙ, ζ) = (1, 0.1), (2, 0.3), (5, 0.5), (10, 0.7),
/// num = 100 (s + 3)(s + 0.5).
pub fn order8_coeffs() -> (Vec<f64>, Vec<f64>) {
    let o = inputs().order8;
    let mut den = vec![1.0];
    for [w, z] in o.den_pairs {
        den = polymul(&den, &[1.0, 2.0 * z * w, w * w]);
    }
    let mut num = vec![1.0];
    for z in o.num_zeros {
        num = polymul(&num, &[1.0, -z]);
    }
    let num = num.iter().map(|c| o.num_gain * c).collect();
    (num, den)
}

/// The order-8 plant as a transfer function.
pub fn order8() -> TransferFunction {
    let (num, den) = order8_coeffs();
    TransferFunction::from_descending(&num, &den).expect("the order-8 plant is valid")
}

/// `n` log-spaced frequencies from 1e-2 to 1e3 rad/s (`np.logspace(-2, 3, n)`).
pub fn freq_grid(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| 10f64.powf(-2.0 + 5.0 * i as f64 / (n - 1) as f64))
        .collect()
}

/// `n` equally spaced times from 0 to 60 s (`np.linspace(0, 60, n)`).
pub fn time_grid(n: usize) -> Vec<f64> {
    let step = 60.0 / (n - 1) as f64;
    let mut t: Vec<f64> = (0..n).map(|i| i as f64 * step).collect();
    t[n - 1] = 60.0;
    t
}

/// P(jω) by Horner's rule on descending real coefficients, in plain f64.
#[inline(always)]
pub fn horner_axis(c: &[f64], w: f64) -> Complex64 {
    let (mut re, mut im) = (0.0f64, 0.0f64);
    for &a in c {
        // (re + j·im)(jω) + a
        let nre = a - w * im;
        im = w * re;
        re = nre;
    }
    Complex64::new(re, im)
}

/// The bare reference loop, complex G only: G(jω) = N(jω)/D(jω) by f64 Horner at each ω —
/// no magnitude, no dB, no phase, no overflow protection, no accuracy check.
pub fn horner_complex(num: &[f64], den: &[f64], w: &[f64]) -> Vec<Complex64> {
    w.iter()
        .map(|&x| horner_axis(num, x) / horner_axis(den, x))
        .collect()
}

/// The bare reference loop with the outputs of `freq_response`: f64 Horner for G(jω), then
/// |G| (hypot), 20·log₁₀|G| and the principal phase atan2 in degrees — still no unwrapping,
/// no overflow protection, no accuracy check.
pub fn horner_full(num: &[f64], den: &[f64], w: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = w.len();
    let (mut mag, mut db, mut ph) = (
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    );
    for &x in w {
        let g = horner_axis(num, x) / horner_axis(den, x);
        let m = g.norm();
        mag.push(m);
        db.push(20.0 * m.log10());
        ph.push(g.im.atan2(g.re).to_degrees());
    }
    (mag, db, ph)
}

/// One Bode PNG of `g` from scratch, as `ltikit` draws it: the automatic frequency grid
/// (500 points plus extras), the frequency response, the margins, the asymptotes, and the
/// 1000 × 700 PNG written to `path`.
pub fn bode_png_of(g: &TransferFunction, path: &std::path::Path) -> ltikit::Result<()> {
    let f = g.factored()?;
    let w = auto_frequency_grid(&f, 500)?;
    let fr: FrequencyResponse = f.freq_response(&w)?;
    let m = f.margins()?;
    let asym = f.bode_asymptotes(w[0], w[w.len() - 1])?;
    let series = [BodeSeries::new(&fr)
        .label("order-8 plant")
        .margins(&m)
        .asymptotes(&asym)];
    bode_png(path, &series, &PlotOptions::default())
}
