//! Timings and values of ltikit's exact dead-time paths (issue 21), as JSON on stdout, for
//! `benches/compare/compare_delay.py` (which times python-control's Padé loops on the same
//! inputs in the same run and builds the accuracy table). For each loop (name, plant
//! numerator/denominator, dead time, PI gains kp and ki, horizon): the exact closed-loop step
//! at 10⁴ samples over the horizon (method of steps) with its median time in seconds, the
//! margins of L·e^(−sT) (gain margin and phase crossover, phase margin and gain crossover,
//! delay margin), and the critical delay of the stability-in-the-delay analysis.

use std::hint::black_box;
use std::time::Instant;

use ltikit::TransferFunction;
use ltikit::analysis::Input;
use ltikit::lti::Controller;

/// Median seconds per call over `repeat` batches (examples/bench_json.rs's scheme).
fn median_time<T>(repeat: usize, min_time: f64, mut f: impl FnMut() -> T) -> f64 {
    black_box(f());
    let mut n = 1usize;
    loop {
        let t0 = Instant::now();
        for _ in 0..n {
            black_box(f());
        }
        if t0.elapsed().as_secs_f64() >= min_time / 5.0 || n > 1_000_000 {
            break;
        }
        n *= 4;
    }
    let mut s: Vec<f64> = (0..repeat)
        .map(|_| {
            let t0 = Instant::now();
            for _ in 0..n {
                black_box(f());
            }
            t0.elapsed().as_secs_f64() / n as f64
        })
        .collect();
    s.sort_by(f64::total_cmp);
    s[s.len() / 2]
}

/// The loops of the comparison: (name, num, den, delay, kp, ki, horizon).
type Case = (
    &'static str,
    &'static [f64],
    &'static [f64],
    f64,
    f64,
    f64,
    f64,
);
const LOOPS: &[Case] = &[
    ("fopdt", &[1.0], &[1.0, 1.0], 1.0, 0.5, 1.0 / 3.0, 10.0),
    ("tank", &[1.0], &[1.0, 0.5], 2.0, 0.4, 0.15, 20.0),
    (
        "second_order",
        &[1.0],
        &[1.0, 1.0, 1.0],
        1.0,
        0.3,
        0.2,
        10.0,
    ),
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut out = Vec::new();
    for &(name, num, den, delay, kp, ki, horizon) in LOOPS {
        let g = TransferFunction::from_descending(num, den)?.factored()?;
        let c = Controller::new("pi", &[("kp".into(), kp), ("ki".into(), ki)])?
            .tf()?
            .factored()?;
        let l = c.series(&g)?;
        let ld = l.clone().with_delay(delay)?;
        let n = 10_000;
        let t: Vec<f64> = (0..n)
            .map(|i| horizon * i as f64 / (n - 1) as f64)
            .collect();
        let step = l.delayed_feedback_response(delay, &Input::Step, &t)?;
        let time = median_time(7, 0.5, || {
            l.delayed_feedback_response(delay, &Input::Step, &t)
                .map(|r| r.y.len())
        });
        let m = ld.margins()?;
        let st = l.delay_stability()?;
        out.push(serde_json::json!({
            "name": name, "num": num, "den": den, "delay": delay, "kp": kp, "ki": ki,
            "horizon": horizon,
            "t": t, "y": step.y,
            "closed_form_error": step.closed_form_error,
            "step_seconds": time,
            "gain_margin": m.gain_margin, "phase_crossover": m.phase_crossover,
            "phase_margin_deg": m.phase_margin_deg, "gain_crossover": m.gain_crossover,
            "delay_margin": m.delay_margin,
            "critical_delay": st.critical_delay,
        }));
    }
    println!("{}", serde_json::to_string(&out)?);
    Ok(())
}
