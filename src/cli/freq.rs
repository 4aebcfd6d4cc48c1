//! `ltikit freq`: M(ω), dB and continuous phase.

use anyhow::{Result, bail};
use clap::Args;

use super::channels::{self, Channels};
use super::output::Stream;
use super::{Plant, PlantArgs, parse};
use crate::analysis::grid::check_points;
use crate::analysis::{FrequencyResponse, auto_frequency_grid};
use crate::fmt::fmt_sig;

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
    check_range(lo, hi, n)?;
    Ok((0..n).map(|i| log_point(lo, hi, n, i)).collect())
}

fn check_range(lo: f64, hi: f64, n: usize) -> Result<()> {
    if !(lo.is_finite() && hi.is_finite()) || lo <= 0.0 || hi <= lo {
        bail!(
            "--wmin/--wmax: need 0 < wmin < wmax (finite), got {} and {}",
            crate::error::number(lo),
            crate::error::number(hi)
        );
    }
    Ok(check_points(n)?)
}

/// The i-th of n log-spaced points from lo to hi (the last exactly hi).
fn log_point(lo: f64, hi: f64, n: usize, i: usize) -> f64 {
    if i + 1 == n {
        hi
    } else {
        let (a, b) = (lo.log10(), hi.log10());
        10f64.powf(a + (b - a) * i as f64 / (n - 1) as f64)
    }
}

/// Frequencies per computed block: the output is written block by block.
const BLOCK: usize = 1 << 17;

pub fn run(a: &FreqArgs) -> Result<()> {
    let plant = a.plant.single()?;
    let chans = a.plant.channels(&plant)?;
    if chans.per_channel {
        return run_channels(a, &plant, &chans);
    }
    let Some(f) = chans.list.first().map(|c| &c.factored) else {
        bail!("no channel to analyse");
    };
    // The frequencies: a given list or an automatic grid (in memory: 8 bytes a point), or a
    // log grid generated block by block.
    let (list, n): (Option<Vec<f64>>, usize) = match (&a.w, a.wmin, a.wmax) {
        (Some(w), _, _) => {
            let w = parse::numbers(w, "--w")?;
            let n = w.len();
            (Some(w), n)
        }
        (None, Some(lo), Some(hi)) => {
            check_range(lo, hi, a.points)?;
            (None, a.points)
        }
        _ => {
            let w = auto_frequency_grid(f, a.points)?;
            let n = w.len();
            (Some(w), n)
        }
    };
    crate::analysis::freq::check_frequencies(list.as_deref().unwrap_or(&[]))?;
    let block_of = |k: usize| -> Vec<f64> {
        let r = k * BLOCK..((k + 1) * BLOCK).min(n);
        match (&list, a.wmin, a.wmax) {
            (Some(w), _, _) => w[r].to_vec(),
            (None, Some(lo), Some(hi)) => r.map(|i| log_point(lo, hi, n, i)).collect(),
            _ => Vec::new(),
        }
    };
    let mut out = Stream::stdout();
    let mut open = if a.json {
        out.put("{\n  \"points\": [")?
    } else {
        out.put(&format!(
            "{}\n\n{}",
            super::text::g_text(&plant, f),
            table_header()
        ))?
    };
    for k in 0..n.div_ceil(BLOCK) {
        if !open {
            break;
        }
        let fr = f.freq_response(&block_of(k))?;
        let mut text = String::new();
        for i in 0..fr.w.len() {
            if a.json {
                text.push_str(if k == 0 && i == 0 {
                    "\n    "
                } else {
                    ",\n    "
                });
                point_text(&fr, i, &mut text);
            } else {
                text.push_str(&table_row(&fr, i));
            }
        }
        open = out.put(&text)?;
    }
    if open && a.json {
        out.put(if n == 0 { "]\n}\n" } else { "\n  ]\n}\n" })?;
    }
    out.finish()
}

pub use crate::limits::MAX_CHANNEL_VALUES;

/// The frequencies of a per-channel result: the given list, the log grid, or a log grid over
/// the union of the channels' automatic ranges.
fn channel_grid(a: &FreqArgs, chans: &Channels) -> Result<Vec<f64>> {
    let w = match (&a.w, a.wmin, a.wmax) {
        (Some(w), _, _) => parse::numbers(w, "--w")?,
        (None, Some(lo), Some(hi)) => logspace(lo, hi, a.points)?,
        _ => {
            let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
            for ch in &chans.list {
                let g = auto_frequency_grid(&ch.factored, 2)?;
                lo = lo.min(g.iter().copied().fold(f64::INFINITY, f64::min));
                hi = hi.max(g.iter().copied().fold(0.0, f64::max));
            }
            logspace(lo, hi, a.points)?
        }
    };
    crate::analysis::freq::check_frequencies(&w)?;
    if w.len().saturating_mul(chans.list.len()) > MAX_CHANNEL_VALUES {
        bail!(
            "{} frequencies × {} channels exceeds {MAX_CHANNEL_VALUES} values: choose a channel \
             (--channel) or fewer points",
            w.len(),
            chans.list.len()
        );
    }
    Ok(w)
}

/// `freq` for every channel of a MIMO plant: a table with the channels as columns, or the
/// per-channel JSON document with each channel's `points`.
fn run_channels(a: &FreqArgs, plant: &Plant, chans: &Channels) -> Result<()> {
    let w = channel_grid(a, chans)?;
    let frs = chans
        .list
        .iter()
        .map(|c| c.factored.freq_response(&w))
        .collect::<crate::Result<Vec<_>>>()?;
    if a.json {
        let docs: Vec<(usize, usize, ChannelPoints)> = chans
            .list
            .iter()
            .zip(&frs)
            .map(|(c, fr)| {
                let points = (0..fr.w.len()).map(|i| point_json(fr, i)).collect();
                (c.input, c.output, ChannelPoints { points })
            })
            .collect();
        return super::output::print_json(&channels::mimo_json(plant, &docs)?);
    }
    let mut s = channels::plant_header(plant);
    s.push('\n');
    for (k, c) in chans.list.iter().enumerate() {
        s.push_str(&format!(
            "  [{}] {}: {}\n",
            k + 1,
            channels::heading(plant, c.input, c.output),
            super::text::channel_g_text(&c.factored)
        ));
    }
    s.push_str(&format!("\n{:>14}", "w [rad/s]"));
    for k in 1..=chans.list.len() {
        s.push_str(&format!(
            " {:>12} {:>10} {:>10}",
            format!("M[{k}]"),
            format!("dB[{k}]"),
            format!("phi[{k}]")
        ));
    }
    s.push('\n');
    for (i, wi) in w.iter().enumerate() {
        s.push_str(&format!("{:>14}", fmt_sig(*wi, 6)));
        for fr in &frs {
            s.push_str(&format!(
                " {:>12} {:>10} {:>10}",
                fmt_sig(fr.magnitude[i], 6),
                fmt_sig(fr.magnitude_db[i], 5),
                fmt_sig(fr.phase_deg[i], 5)
            ));
        }
        s.push('\n');
    }
    super::output::print(&s)
}

/// One channel's points in the per-channel JSON document.
#[derive(serde::Serialize)]
struct ChannelPoints {
    points: Vec<FreqPointJson>,
}

/// One point of the `freq` JSON contract:
/// `{"points": [{"w", "magnitude", "magnitude_db", "phase_deg"}]}`.
#[derive(serde::Serialize)]
struct FreqPointJson {
    w: f64,
    magnitude: Option<f64>,
    magnitude_db: Option<f64>,
    phase_deg: Option<f64>,
}

/// One point as the pretty printer writes it (the same text as [`point_json`] through
/// `print_json`, without building a JSON tree per point).
fn point_text(f: &FrequencyResponse, i: usize, out: &mut String) {
    use super::output::json_number;
    out.push_str("{\n      \"w\": ");
    out.push_str(&json_number(f.w[i]));
    out.push_str(",\n      \"magnitude\": ");
    out.push_str(&json_number(f.magnitude[i]));
    out.push_str(",\n      \"magnitude_db\": ");
    out.push_str(&json_number(f.magnitude_db[i]));
    out.push_str(",\n      \"phase_deg\": ");
    out.push_str(&json_number(f.phase_deg[i]));
    out.push_str("\n    }");
}

fn point_json(f: &FrequencyResponse, i: usize) -> FreqPointJson {
    FreqPointJson {
        w: f.w[i],
        magnitude: super::output::finite(f.magnitude[i]),
        magnitude_db: super::output::finite(f.magnitude_db[i]),
        phase_deg: super::output::finite(f.phase_deg[i]),
    }
}

fn table_header() -> String {
    format!(
        "{:>14} {:>14} {:>12} {:>12}\n",
        "w [rad/s]", "M(w)", "M [dB]", "phi [deg]"
    )
}

fn table_row(f: &FrequencyResponse, i: usize) -> String {
    format!(
        "{:>14} {:>14} {:>12} {:>12}\n",
        fmt_sig(f.w[i], 6),
        fmt_sig(f.magnitude[i], 6),
        fmt_sig(f.magnitude_db[i], 6),
        fmt_sig(f.phase_deg[i], 6)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streamed_points_match_the_pretty_printer() {
        let f = FrequencyResponse {
            w: vec![0.5, 2.0],
            magnitude: vec![1.25, f64::INFINITY],
            magnitude_db: vec![-0.0, f64::INFINITY],
            phase_deg: vec![-90.0, 1e-300],
        };
        for i in 0..2 {
            let mut fast = String::new();
            point_text(&f, i, &mut fast);
            let mut slow = String::new();
            let v = super::super::output::json_value(&point_json(&f, i)).unwrap();
            super::super::output::pretty(&v, 2, &mut slow);
            assert_eq!(fast, slow);
        }
    }
}
