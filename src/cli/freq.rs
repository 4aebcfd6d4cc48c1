//! `ltikit freq`: M(ω), dB and continuous phase.

use anyhow::{Result, bail};
use clap::Args;
use serde::Serialize;

use super::output::{finite, print, print_json};
use super::{PlantArgs, parse};
use crate::analysis::{FrequencyResponse, auto_frequency_grid};
use crate::poly::fmt_sig;

#[derive(Args, Debug)]
pub struct FreqArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// Frequencies in rad/s, e.g. --w "0.1 1 10".
    #[arg(long, value_name = "RAD/S", allow_hyphen_values = true, conflicts_with_all = ["wmin", "wmax"])]
    pub w: Option<String>,
    /// Lowest frequency of a log-spaced grid (rad/s).
    #[arg(long, requires = "wmax", allow_hyphen_values = true)]
    pub wmin: Option<f64>,
    /// Highest frequency of a log-spaced grid (rad/s).
    #[arg(long, requires = "wmin", allow_hyphen_values = true)]
    pub wmax: Option<f64>,
    /// Number of points of the log-spaced (or automatic) grid.
    #[arg(long, default_value_t = 50)]
    pub points: usize,
    /// Print one JSON document instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// Log-spaced frequencies from `lo` to `hi` inclusive.
pub fn logspace(lo: f64, hi: f64, n: usize) -> Result<Vec<f64>> {
    if !(lo.is_finite() && hi.is_finite()) || lo <= 0.0 || hi <= lo {
        bail!("--wmin/--wmax: need 0 < wmin < wmax (finite), got {lo} and {hi}");
    }
    if n < 2 {
        bail!("--points must be at least 2");
    }
    let (a, b) = (lo.log10(), hi.log10());
    Ok((0..n)
        .map(|i| {
            if i + 1 == n {
                hi
            } else {
                10f64.powf(a + (b - a) * i as f64 / (n - 1) as f64)
            }
        })
        .collect())
}

pub fn run(a: &FreqArgs) -> Result<()> {
    let plant = a.plant.single()?;
    let f = a.plant.factored(&plant)?;
    let w = match (&a.w, a.wmin, a.wmax) {
        (Some(w), _, _) => parse::numbers(w, "--w")?,
        (None, Some(lo), Some(hi)) => logspace(lo, hi, a.points)?,
        _ => auto_frequency_grid(&f, a.points)?,
    };
    let fr = f.freq_response(&w)?;
    if a.json {
        print_json(&FreqJson::from(&fr))
    } else {
        let mut s = format!("{}\n\n", super::text::g_text(&plant, &f));
        s.push_str(&table(&fr));
        print(&s)
    }
}

/// The `freq` JSON contract: `{"points": [{"w", "magnitude", "magnitude_db", "phase_deg"}]}`.
#[derive(Serialize)]
pub struct FreqJson {
    points: Vec<FreqPointJson>,
}

#[derive(Serialize)]
struct FreqPointJson {
    w: f64,
    magnitude: Option<f64>,
    magnitude_db: Option<f64>,
    phase_deg: Option<f64>,
}

impl From<&FrequencyResponse> for FreqJson {
    fn from(f: &FrequencyResponse) -> Self {
        FreqJson {
            points: (0..f.w.len())
                .map(|i| FreqPointJson {
                    w: f.w[i],
                    magnitude: finite(f.magnitude[i]),
                    magnitude_db: finite(f.magnitude_db[i]),
                    phase_deg: finite(f.phase_deg[i]),
                })
                .collect(),
        }
    }
}

/// A text table of the response.
pub fn table(f: &FrequencyResponse) -> String {
    let mut s = format!(
        "{:>14} {:>14} {:>12} {:>12}\n",
        "w [rad/s]", "M(w)", "M [dB]", "phi [deg]"
    );
    for i in 0..f.w.len() {
        s.push_str(&format!(
            "{:>14} {:>14} {:>12} {:>12}\n",
            fmt_sig(f.w[i], 6),
            fmt_sig(f.magnitude[i], 6),
            fmt_sig(f.magnitude_db[i], 6),
            fmt_sig(f.phase_deg[i], 6)
        ));
    }
    s
}
