//! `ltikit rlocus`: the root locus of unity negative feedback around K·L (L = G, or C·G with a
//! controller): asymptotes, break points, imaginary-axis crossings (unit-circle crossings for
//! a discrete plant), departure and arrival angles, the stable gains, the closed-loop poles
//! at --gain K; a PNG with -o, JSON with --json.

use anyhow::{Context, Result, bail};
use clap::Args;
use serde::Serialize;
use std::path::PathBuf;

use super::PlantArgs;
use super::output::{json_value, print, print_json};
use super::text::{g_text, roots_text};
use crate::analysis::rlocus::{BreakKind, RootLocus, RootLocusOptions};
use crate::analysis::{discrete_stable_gains, stable_gains};
use crate::fmt::{fmt_root, fmt_sig};
use crate::lti::controller::LoopSystem;
use crate::plot::{PlotOptions, RootLocusPlot, parse_size, rlocus_png};
use crate::poly::{HalfPlane, Poly, Root};

#[derive(Args, Debug)]
pub struct RlocusArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// Mark (and list) the closed-loop poles at this gain.
    #[arg(long, value_name = "K", allow_hyphen_values = true)]
    pub gain: Option<f64>,
    /// Trace K from 0 to −∞ (the complementary, 0° locus).
    #[arg(long)]
    pub negative: bool,
    /// At most this many traced gains (16 … 100000).
    #[arg(long, default_value_t = crate::analysis::rlocus::DEFAULT_MAX_GAINS, value_name = "N")]
    pub max_gains: usize,
    /// Write the root locus PNG here.
    #[arg(short = 'o', long = "output", value_name = "FILE.png", value_parser = super::png_path)]
    pub output: Option<PathBuf>,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "900x800", value_name = "WxH")]
    pub size: String,
    /// Title (default: names the loop; "" for none).
    #[arg(long)]
    pub title: Option<String>,
    /// Font scale (1 = default; 0.25 … 8).
    #[arg(long, default_value_t = 1.0, value_name = "SCALE")]
    pub font_scale: f64,
    /// Print one JSON document: the features, "stable_gains", "at_gain" and the traced
    /// "gains" and "branches" ([re, im] per gain) instead of the report.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct AtGain<'a> {
    gain: f64,
    poles: &'a [Root],
}

#[derive(Serialize)]
struct Doc<'a> {
    #[serde(flatten)]
    locus: &'a RootLocus,
    /// `null` when not computed (a loop of order above the limit).
    stable_gains: Option<Vec<[Option<f64>; 2]>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    at_gain: Option<AtGain<'a>>,
}

pub fn run(a: &RlocusArgs) -> Result<()> {
    if a.max_gains < 16 {
        bail!("--max-gains {} is below 16", a.max_gains);
    }
    crate::limits::GAINS.check_usize("`max_gains`", a.max_gains)?;
    let opts = if a.output.is_some() {
        let o = PlotOptions {
            size: parse_size(&a.size)?,
            title: a.title.clone(),
            font_scale: a.font_scale,
            ..Default::default()
        };
        o.validate()?;
        Some(o)
    } else {
        None
    };
    let plant = a.plant.single_for(LoopSystem::Loop)?;
    if plant.selection.is_some_and(|s| s != LoopSystem::Loop) {
        bail!(
            "rlocus traces the closed-loop poles of 1 + K·L for the loop L = C·G: --closed-loop, --sensitivity and --control-sensitivity do not apply"
        );
    }
    let f = a.plant.factored(&plant)?;
    let (num, den) = f.locus_polys()?;
    let locus = f.root_locus(&RootLocusOptions {
        negative: a.negative,
        max_gains: a.max_gains,
    })?;
    let at = match a.gain {
        None => None,
        Some(k) if k.is_finite() => {
            let q = &den + &num.scale(k);
            if q.degree() < den.degree() {
                bail!(
                    "at K = {k} the closed loop 1 + K·L loses its leading term (a pole at infinity): choose another gain"
                );
            }
            Some((k, q.roots()?))
        }
        Some(k) => bail!("--gain must be finite, got {}", crate::error::number(k)),
    };
    // the stable-gain set needs the crossing polynomial (degree ≤ deg N + deg D)
    let discrete = f.domain().is_discrete();
    let gains = (2 * num.degree().max(den.degree()) <= crate::poly::MAX_ORDER)
        .then(|| {
            if discrete {
                // every interval decided exactly (the f64 coefficients' binary values)
                discrete_stable_gains(&num, &den)
            } else {
                stable_gains(&num, &den)
            }
            .map(|g| on_locus(g, a.negative))
        })
        .transpose()?;
    if let (Some(path), Some(o)) = (&a.output, &opts) {
        let label = plant.name.clone();
        rlocus_png(
            path,
            &RootLocusPlot {
                locus: &locus,
                label: Some(&label),
                marked: at.as_ref().map(|(k, r)| (*k, r.as_slice())),
            },
            o,
        )
        .with_context(|| format!("root locus plot {}", path.display()))?;
    }
    if a.json {
        let finite = |x: f64| x.is_finite().then_some(x);
        let doc = Doc {
            locus: &locus,
            stable_gains: gains
                .as_ref()
                .map(|g| g.iter().map(|(l, h)| [finite(*l), finite(*h)]).collect()),
            at_gain: at.as_ref().map(|(k, r)| AtGain { gain: *k, poles: r }),
        };
        return print_json(&json_value(&doc)?);
    }
    let mut s = format!("{}\n\n", g_text(&plant, &f));
    s.push_str(&report(&locus, gains.as_deref(), &num, &den));
    if let Some((k, r)) = &at {
        // roots on the imaginary axis to the library's tolerance print with Re = 0 (the JSON
        // keeps the computed values)
        let shown: Vec<Root> = r
            .iter()
            .map(|x| {
                let mut x = *x;
                if !discrete && x.half_plane() == HalfPlane::Axis {
                    x.value.re = 0.0;
                }
                x
            })
            .collect();
        s.push_str(&format!(
            "\nClosed-loop poles at K = {}: {}",
            fmt_sig(*k, 10),
            roots_text(&shown)
        ));
    }
    if let Some(path) = &a.output {
        s.push_str(&format!("\nFigure: {}", path.display()));
    }
    s.push('\n');
    print(&s)
}

/// The stable-gain intervals restricted to this locus's sign of K.
fn on_locus(v: Vec<(f64, f64)>, negative: bool) -> Vec<(f64, f64)> {
    v.into_iter()
        .filter_map(|(lo, hi)| {
            let (lo, hi) = if negative {
                (lo, hi.min(0.0))
            } else {
                (lo.max(0.0), hi)
            };
            (lo < hi).then_some((lo, hi))
        })
        .collect()
}

fn k_text(x: f64) -> String {
    if x.is_finite() {
        fmt_sig(x, 10)
    } else if x > 0.0 {
        "∞".into()
    } else {
        "−∞".into()
    }
}

fn angles_text(v: &[f64]) -> String {
    v.iter()
        .map(|a| format!("{}°", fmt_sig(*a, 6)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The text report of the features.
fn report(l: &RootLocus, gains: Option<&[(f64, f64)]>, num: &Poly, den: &Poly) -> String {
    let v = if l.dt.is_some() { "z" } else { "s" };
    let mut s = format!(
        "Root locus of D({v}) + K·N({v}) = 0 (unity negative feedback around K·L), K from 0 to {}\n  D({v}) = {}\n  N({v}) = {}\n",
        if l.negative { "−∞" } else { "∞" },
        crate::poly::format_poly(den, v),
        crate::poly::format_poly(num, v),
    );
    s.push_str(&format!(
        "Open-loop poles: {}\nOpen-loop zeros: {}\n",
        roots_text(&l.poles),
        roots_text(&l.zeros)
    ));
    if !l.fixed.is_empty() {
        s.push_str(&format!(
            "Fixed closed-loop poles (roots of both N and D, every K): {}\n",
            roots_text(&l.fixed)
        ));
    }
    match &l.asymptotes {
        Some(a) => s.push_str(&format!(
            "Asymptotes: {} from σ = {} at {}\n",
            a.count,
            fmt_sig(a.centroid, 10),
            angles_text(&a.angles_deg)
        )),
        None => s.push_str("Asymptotes: none (deg N = deg D)\n"),
    }
    if let Some(k) = l.escape_gain {
        s.push_str(&format!(
            "A branch leaves through infinity at K = {} (the leading coefficient of D + K·N vanishes)\n",
            k_text(k)
        ));
    }
    s.push_str("Break points:");
    if l.break_points.is_empty() {
        s.push_str(" none\n");
    } else {
        s.push('\n');
        for b in &l.break_points {
            let kind = match b.kind {
                BreakKind::BreakAway => "break-away",
                BreakKind::BreakIn => "break-in",
                BreakKind::Crossing => "branches cross",
            };
            s.push_str(&format!(
                "  {} = {} ({kind}, {} branches) at K = {}\n",
                if l.dt.is_some() { "z" } else { "σ" },
                fmt_sig(b.s, 10),
                b.branches,
                k_text(b.gain)
            ));
        }
    }
    s.push_str(if l.dt.is_some() {
        "Unit-circle crossings:"
    } else {
        "Imaginary-axis crossings:"
    });
    if l.crossings.is_empty() {
        s.push_str(" none\n");
    } else {
        s.push('\n');
        for c in &l.crossings {
            let at = match c.z {
                Some(z) if z.im == 0.0 => format!("z = {}", fmt_sig(z.re, 10)),
                Some(z) => format!(
                    "z = {} ± {}j (ωT = {} rad, ω = {} rad/s)",
                    fmt_sig(z.re, 10),
                    fmt_sig(z.im, 10),
                    fmt_sig(z.im.atan2(z.re), 10),
                    fmt_sig(c.omega, 10)
                ),
                None if c.omega == 0.0 => "s = 0".to_string(),
                None => format!("s = ±{}j", fmt_sig(c.omega, 10)),
            };
            s.push_str(&format!("  {at} at K = {}\n", k_text(c.gain)));
        }
    }
    let angle_block = |title: &str, v: &[crate::analysis::rlocus::LocusAngle]| {
        if v.is_empty() {
            return String::new();
        }
        let mut t = format!("{title}:\n");
        for x in v {
            let m = if x.multiplicity > 1 {
                format!(" (×{})", x.multiplicity)
            } else {
                String::new()
            };
            let mirror = if x.at.im > 0.0 {
                " (the conjugate: the negatives)"
            } else {
                ""
            };
            t.push_str(&format!(
                "  at {}{m}: {}{mirror}\n",
                fmt_root(num_complex::Complex64::new(x.at.re, x.at.im.abs()), 6)
                    .replace(" ± ", " + "),
                angles_text(&x.angles_deg)
            ));
        }
        t
    };
    s.push_str(&angle_block("Departure angles", &l.departures));
    s.push_str(&angle_block("Arrival angles", &l.arrivals));
    if let Some(gains) = gains {
        let text: Vec<String> = gains
            .iter()
            .map(|(lo, hi)| format!("{} < K < {}", k_text(*lo), k_text(*hi)))
            .collect();
        s.push_str(&format!(
            "Closed loop stable for: {} ({})\n",
            if text.is_empty() {
                "no gain on this locus".to_string()
            } else {
                text.join(", ")
            },
            if l.dt.is_some() {
                "every root strictly inside the unit circle; Jury, each interval decided exactly"
            } else {
                "Routh–Hurwitz"
            }
        ));
    }
    for n in &l.notes {
        s.push_str(&format!("Note: {n}\n"));
    }
    s.push_str(&format!(
        "Traced: {} gains, {} branches\n",
        l.branches.gains.len(),
        l.branches.paths.len()
    ));
    s
}
