//! Scratch timing: `freq_response` at 10⁶ frequencies against a bare Horner loop over the
//! same coefficients. Run with `cargo run --release --example freq_timing`.
//!
//! The Horner baseline computes what a user of `polyval` gets: N(jω)/D(jω), then |G|, dB and
//! the principal phase (atan2) — without unwrapping (python-control adds `np.unwrap`).

use ltikit::TransferFunction;
use num_complex::Complex64;
use std::hint::black_box;
use std::time::Instant;

fn horner(c: &[f64], w: f64) -> Complex64 {
    let (mut re, mut im) = (0.0f64, 0.0f64);
    for &a in c {
        let nre = a - w * im;
        im = w * re;
        re = nre;
    }
    Complex64::new(re, im)
}

fn best_of<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..reps {
        let t = Instant::now();
        let v = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(v);
    }
    (best, out.unwrap())
}

fn main() {
    let n = 1_000_000;
    let w: Vec<f64> = (0..n)
        .map(|i| 10f64.powf(-3.0 + 6.0 * i as f64 / (n - 1) as f64))
        .collect();
    let plants: Vec<(&str, TransferFunction)> = vec![
        (
            "order 2 (ζ=0.1)",
            TransferFunction::from_descending(&[1.0], &[1.0, 0.2, 1.0]).unwrap(),
        ),
        (
            "order 4, 1 zero",
            TransferFunction::from_descending(&[1.0, 2.0], &[1.0, 3.2, 5.1, 4.3, 1.2]).unwrap(),
        ),
        ("order 10, 3 zeros", {
            let p: Vec<Complex64> = (0..5)
                .flat_map(|k| {
                    let wn = 10f64.powf(-1.0 + 0.5 * k as f64);
                    let z = 0.05 + 0.15 * k as f64;
                    let im = wn * (1.0f64 - z * z).sqrt();
                    [Complex64::new(-z * wn, im), Complex64::new(-z * wn, -im)]
                })
                .collect();
            let z = [
                Complex64::new(-0.3, 0.0),
                Complex64::new(2.0, 1.0),
                Complex64::new(2.0, -1.0),
            ];
            TransferFunction::from_zpk(&z, &p, 3.0).unwrap()
        }),
        ("order 20", {
            let p: Vec<Complex64> = (0..10)
                .flat_map(|k| {
                    let wn = 10f64.powf(-1.0 + 0.25 * k as f64);
                    let z = 0.05 + 0.08 * k as f64;
                    let im = wn * (1.0f64 - z * z).sqrt();
                    [Complex64::new(-z * wn, im), Complex64::new(-z * wn, -im)]
                })
                .collect();
            TransferFunction::from_zpk(&[], &p, 1.0).unwrap()
        }),
    ];
    println!("{n} frequencies, best of 5 runs");
    println!(
        "{:<20} {:>12} {:>14} {:>16} {:>8}",
        "plant", "freq_response", "Horner G only", "Horner mag/dB/φ", "ratio"
    );
    for (name, g) in &plants {
        let (t_f, r) = best_of(5, || g.freq_response(black_box(&w)).unwrap());
        let num = g.num().coeffs().to_vec();
        let den = g.den().coeffs().to_vec();
        let (t_c, _) = best_of(5, || {
            let mut out = Vec::with_capacity(n);
            for &x in black_box(&w) {
                out.push(horner(&num, x) / horner(&den, x));
            }
            out
        });
        let (t_h, h) = best_of(5, || {
            let mut mag = Vec::with_capacity(n);
            let mut db = Vec::with_capacity(n);
            let mut ph = Vec::with_capacity(n);
            for &x in black_box(&w) {
                let gv = horner(&num, x) / horner(&den, x);
                let m = gv.norm();
                mag.push(m);
                db.push(20.0 * m.log10());
                ph.push(gv.arg().to_degrees());
            }
            (mag, db, ph)
        });
        let worst = r
            .magnitude
            .iter()
            .zip(&h.0)
            .map(|(a, b)| ((a - b) / b).abs())
            .fold(0.0, f64::max);
        println!(
            "{:<20} {:>9.1} ms {:>11.1} ms {:>13.1} ms {:>8.2}   (max |ΔM|/M vs f64 Horner {:.1e})",
            name,
            t_f * 1e3,
            t_c * 1e3,
            t_h * 1e3,
            t_f / t_h,
            worst
        );
    }
}
