//! `ltikit pade`: the [N/N] Padé approximant of a dead time e^(−sT) — its coefficients, its
//! poles, and its phase error against the exact −ωT at chosen frequencies.

use anyhow::Result;
use clap::Args;
use serde::Serialize;

use super::output::{pair, print, print_json};
use crate::fmt::{fmt_root, fmt_sig};
use crate::lti::delay::pade;

#[derive(Args, Debug)]
pub struct PadeArgs {
    /// The dead time T in seconds.
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub delay: f64,
    /// The order N of the [N/N] approximant (1…20).
    #[arg(long, value_name = "N")]
    pub order: usize,
    /// Frequencies (rad/s) at which to compare the phase with −ωT (default 1/T, 2/T, 5/T,
    /// 10/T).
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub w: Option<String>,
    /// Print one JSON document: {"delay", "order", "num", "den", "poles", "phase", "w_within_1deg"}.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct PhasePoint {
    w: f64,
    approximant_deg: f64,
    exact_deg: f64,
    error_deg: f64,
}

#[derive(Serialize)]
struct PadeJson {
    delay: f64,
    order: usize,
    num: Vec<f64>,
    den: Vec<f64>,
    poles: Vec<[f64; 2]>,
    phase: Vec<PhasePoint>,
    w_within_1deg: Option<f64>,
}

pub fn run(a: &PadeArgs) -> Result<()> {
    if a.order == 0 || a.order > crate::limits::MAX_PADE_ORDER {
        anyhow::bail!(
            "--order: the order of a Padé approximant must be 1 to {} (found {})",
            crate::limits::MAX_PADE_ORDER,
            a.order
        );
    }
    let g = pade(a.delay, a.order)?;
    let t = a.delay;
    if t == 0.0 {
        anyhow::bail!("--delay 0: there is no dead time to approximate");
    }
    let w: Vec<f64> = match &a.w {
        Some(text) => super::parse::numbers(text, "--w")?,
        None => [1.0, 2.0, 5.0, 10.0].iter().map(|k| k / t).collect(),
    };
    crate::analysis::freq::check_frequencies(&w)?;
    crate::limits::POINTS.check_usize("`w`", w.len())?;
    let f = g.factored()?;
    let r = f.freq_response(&w)?;
    let phase: Vec<PhasePoint> = w
        .iter()
        .zip(&r.phase_deg)
        .map(|(&x, &p)| {
            let exact = -(x * t).to_degrees();
            PhasePoint {
                w: x,
                approximant_deg: p,
                exact_deg: exact,
                error_deg: p - exact,
            }
        })
        .collect();
    // the error grows with ωT: the last ω with |error| ≤ 1°, by bisection in ωT
    let err = |x: f64| -> Result<f64> {
        let p = f.freq_response(&[x])?.phase_deg[0];
        Ok((p + (x * t).to_degrees()).abs() - 1.0)
    };
    let mut lo = 0.0;
    let mut hi = (4.0 * a.order as f64 + 4.0) / t;
    let within = if err(hi)? <= 0.0 {
        None
    } else {
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if err(mid)? <= 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(lo)
    };
    if a.json {
        return print_json(&PadeJson {
            delay: t,
            order: a.order,
            num: g.num().coeffs().to_vec(),
            den: g.den().coeffs().to_vec(),
            poles: crate::poly::roots::flatten(f.poles())
                .into_iter()
                .map(pair)
                .collect(),
            phase,
            w_within_1deg: within,
        });
    }
    let n = a.order;
    let mut s = format!(
        "e^(-{} s) ≈ [{n}/{n}] Padé approximant P(s)/Q(s), Q(s) = Σ c_k (sT)^k, P(s) = Q(-s)\n\n",
        crate::fmt::fmt_num(t)
    );
    s.push_str(&format!("  {g}\n\n"));
    s.push_str(&format!(
        "Numerator (descending):   {}\n",
        list(g.num().coeffs())
    ));
    s.push_str(&format!(
        "Denominator (descending): {}\n",
        list(g.den().coeffs())
    ));
    let poles: Vec<String> = f
        .poles()
        .iter()
        .filter(|p| p.value.im >= 0.0)
        .map(|p| fmt_root(p.value, 6))
        .collect();
    s.push_str(&format!(
        "Poles:     {} (the zeros are their mirror images: |P/Q| = 1 on the imaginary axis)\n\n",
        poles.join(", ")
    ));
    s.push_str("       w [rad/s]   approximant [deg]      exact -wT [deg]      error [deg]\n");
    for p in &phase {
        s.push_str(&format!(
            "{:>16} {:>19} {:>20} {:>16}\n",
            fmt_sig(p.w, 7),
            fmt_sig(p.approximant_deg, 10),
            fmt_sig(p.exact_deg, 10),
            fmt_sig(p.error_deg, 3)
        ));
    }
    match within {
        Some(x) => s.push_str(&format!(
            "\nThe phase is within 1° of -wT up to w = {} rad/s (wT = {}).\n",
            fmt_sig(x, 6),
            fmt_sig(x * t, 4)
        )),
        None => s.push_str("\nThe phase is within 1° of -wT over the range examined.\n"),
    }
    print(&s)
}

fn list(c: &[f64]) -> String {
    c.iter()
        .map(|x| fmt_sig(*x, 10))
        .collect::<Vec<_>>()
        .join(" ")
}
