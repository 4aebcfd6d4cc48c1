//! `ltikit bode|step|pzmap|nyquist -o FILE.png` and the figure helpers shared with the demo.
//!
//! With `--json` each command prints one JSON document describing what it drew: the file
//! written and the figures the picture marks (margins, step metrics, poles and zeros, the
//! Nyquist encirclement count), and nothing else on stdout.

use anyhow::{Context, Result, bail};
use clap::Args;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

use super::output::{json_value, pair, print_json};
use crate::analysis::{Margins, StepInfo};
use crate::poly::roots::flatten;

use super::PlantArgs;
use crate::analysis::{Factored, Input, TimeResponse, auto_frequency_grid, auto_time_span};
use crate::lti::controller::LoopSystem;
use crate::plot::{
    BodeGrid, BodeSeries, NyquistSeries, PlotOptions, PzMap, StepSeries, bode_grid_png, bode_png,
    nyquist_png, parse_size, pzmap_png, step_png,
};

/// Options common to every picture.
#[derive(Args, Debug, Clone)]
pub struct PlotArgs {
    /// Output PNG file.
    #[arg(short = 'o', long = "output", value_name = "FILE.png", value_parser = super::png_path)]
    pub output: PathBuf,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "1000x700", value_name = "WxH")]
    pub size: String,
    /// Title (default: names the plant; "" for none).
    #[arg(long)]
    pub title: Option<String>,
    /// Font scale, like a dpi setting (1 = default; 0.25 … 8).
    #[arg(long, default_value_t = 1.0, value_name = "SCALE")]
    pub font_scale: f64,
    /// Print one JSON document describing what was drawn: the file written and the figures
    /// the picture marks (margins, step metrics, poles and zeros, encirclements).
    #[arg(long)]
    pub json: bool,
}

impl PlotArgs {
    pub fn options(&self) -> Result<PlotOptions> {
        let opts = PlotOptions {
            size: parse_size(&self.size)?,
            title: self.title.clone(),
            font_scale: self.font_scale,
            ..Default::default()
        };
        opts.validate()?;
        Ok(opts)
    }
}

/// A grid over [w_min, w_max]: 600 log-spaced points plus the plant's own automatic points
/// (which refine lightly damped resonances) inside the range.
fn merged_grid(tf: &Factored, w_min: f64, w_max: f64) -> Result<Vec<f64>> {
    let mut w = super::freq::logspace(w_min, w_max, 600)?;
    w.extend(
        auto_frequency_grid(tf, 400)?
            .into_iter()
            .filter(|x| *x > w_min && *x < w_max),
    );
    w.sort_by(f64::total_cmp);
    w.dedup();
    Ok(w)
}

/// What a Bode diagram shows: its frequency range and each plant's margins (when drawn).
pub struct BodeDrawn {
    /// The frequency range (rad/s).
    pub range: (f64, f64),
    /// The margins of each plant, `None` when not drawn or not computable.
    pub margins: Vec<Option<Margins>>,
}

/// Writes a Bode diagram of `plants` (labels, factored plants), with their margins when
/// `margins`; the frequency range covers every plant's automatic range unless given.
pub fn bode_figure(
    path: &Path,
    plants: &[(String, Factored)],
    range: Option<(f64, f64)>,
    asymptotes: bool,
    margins: bool,
    opts: &PlotOptions,
) -> Result<BodeDrawn> {
    let (lo, hi) = match range {
        Some(r) => r,
        None => {
            let mut lo = f64::INFINITY;
            let mut hi: f64 = 0.0;
            for (_, g) in plants {
                let w = auto_frequency_grid(g, 100)?;
                let (Some(&first), Some(&last)) = (w.first(), w.last()) else {
                    anyhow::bail!("no frequency range for this plant: give --wmin and --wmax");
                };
                lo = lo.min(first);
                hi = hi.max(last);
            }
            (lo, hi)
        }
    };
    let mut data = Vec::new();
    for (label, g) in plants {
        let w = merged_grid(g, lo, hi)?;
        let fr = g.freq_response(&w)?;
        // A plant whose margins cannot be computed is still drawn (and a warning says why).
        let m = if margins {
            g.margins()
                .map_err(|e| super::warn(format!("{label}: margins not marked: {e}")))
                .ok()
        } else {
            None
        };
        let asym = if asymptotes {
            Some(g.bode_asymptotes(lo, hi)?)
        } else {
            None
        };
        data.push((label, fr, m, asym, g.domain().dt()));
    }
    let series: Vec<BodeSeries> = data
        .iter()
        .map(|(label, fr, m, asym, dt)| {
            let mut s = BodeSeries::new(fr).label(label);
            // a discrete plant: the Nyquist frequency π/T is marked
            if let Some(dt) = dt {
                s = s.sampling_period(*dt);
            }
            if let Some(m) = m {
                s = s.margins(m);
            }
            if let Some(a) = asym {
                s = s.asymptotes(a);
            }
            s
        })
        .collect();
    bode_png(path, &series, opts)?;
    Ok(BodeDrawn {
        range: (lo, hi),
        margins: data.into_iter().map(|(_, _, m, _, _)| m).collect(),
    })
}

/// What a response plot shows: its end time and, per plant, the step metrics (steps only)
/// and whether the response grows without bound.
pub struct StepDrawn {
    /// End of the time axis (s).
    pub t_end: f64,
    /// Per plant: step metrics, divergence.
    pub plants: Vec<(Option<StepInfo>, bool)>,
}

/// Step, impulse or ramp responses of `plants` on one plot, with step metrics for steps.
pub fn step_figure(
    path: &Path,
    plants: &[(String, Factored)],
    input: &Input,
    t_end: Option<f64>,
    opts: &PlotOptions,
) -> Result<StepDrawn> {
    let t_end = match t_end {
        Some(t) if t.is_finite() && t > 0.0 => t,
        Some(t) => bail!("--t-end must be > 0, got {}", crate::error::number(t)),
        None => {
            let mut t: f64 = 0.0;
            for (_, g) in plants {
                t = t.max(auto_time_span(g)?.t_end);
            }
            t
        }
    };
    let t: Vec<f64> = (0..=1000).map(|i| t_end * i as f64 / 1000.0).collect();
    let kind = input;
    let mut data: Vec<(
        &String,
        TimeResponse,
        Option<crate::analysis::StepInfo>,
        bool,
    )> = Vec::new();
    for (label, g) in plants {
        // equally spaced, but locked onto an oscillation too fast for the spacing
        let r = g.response_for_drawing(input, t_end, t.len())?;
        // A plant whose step metrics cannot be computed is still drawn (a warning says why).
        let info = if matches!(input, Input::Step) {
            g.step_info()
                .map_err(|e| super::warn(format!("{label}: step metrics not marked: {e}")))
                .ok()
                .flatten()
        } else {
            None
        };
        let unstable = response_diverges(g, input);
        data.push((label, r, info, unstable));
    }
    let series: Vec<StepSeries> = data
        .iter()
        .map(|(label, r, info, unstable)| {
            let mut s = StepSeries::new(r)
                .label(label)
                .input(*kind)
                .unstable(*unstable);
            if let Some(i) = info {
                s = s.info(i);
            }
            s
        })
        .collect();
    step_png(path, &series, opts)?;
    Ok(StepDrawn {
        t_end,
        plants: data.into_iter().map(|(_, _, i, u)| (i, u)).collect(),
    })
}

/// True when the response of G to `input` grows without bound: a pole of G in lowest terms or
/// of U(s) lies in the right half plane, or a pole on the imaginary axis is repeated (counting
/// a system pole that coincides with an input pole, e.g. the step response of 1/s).
pub fn response_diverges(g: &Factored, input: &Input) -> bool {
    use crate::poly::HalfPlane;
    let mut poles: Vec<crate::Root> = g.reduced_poles().to_vec();
    let dt = g.domain().dt();
    for (v, m) in input.poles() {
        // in z the input's pole s = v is e^(vT)
        let v = dt.map_or(v, |dt| (v * dt).exp());
        match poles.iter_mut().find(|p| p.same_as(v)) {
            Some(p) => p.multiplicity += m,
            None => poles.push(crate::Root::new(v, m)),
        }
    }
    let side = |p: &crate::Root| match dt {
        Some(_) => crate::analysis::discrete::circle_side(p.value),
        None => p.half_plane(),
    };
    poles.iter().any(|p| match side(p) {
        HalfPlane::Right => true,
        HalfPlane::Axis => p.multiplicity > 1,
        HalfPlane::Left => false,
    })
}

/// The default title of a picture of one discrete-time plant names G(z) and the period (the
/// pictures' own default says G(s)); a title given by the user is kept.
fn discrete_title(opts: &PlotOptions, kind: &str, plants: &[(String, Factored)]) -> PlotOptions {
    let mut opts = opts.clone();
    if let ([(label, g)], None) = (plants, &opts.title)
        && let Some(dt) = g.domain().dt()
    {
        opts.title = Some(format!(
            "{kind} of G(z) = {label}, T = {} s",
            crate::fmt::fmt_num(dt)
        ));
    }
    opts
}

/// Pole-zero map of one plant.
pub fn pzmap_figure(
    path: &Path,
    label: &str,
    g: &Factored,
    guides: bool,
    opts: &PlotOptions,
) -> Result<()> {
    pzmap_png(
        path,
        &PzMap::new(g.pole_zero())
            .label(label)
            .damping_guides(guides)
            .unit_circle(g.domain().is_discrete()),
        opts,
    )?;
    Ok(())
}

/// The plants with their names, each factored once: the chosen channel of a MIMO plant, or
/// without `--channel` each of its channels labelled "input → output"; with a controller, the
/// loop system (`default` unless an option chooses).
fn labelled(args: &PlantArgs, default: LoopSystem) -> Result<Vec<(String, Factored)>> {
    let plants = args.resolve_for(default)?;
    let several = plants.len() > 1;
    let mut out = Vec::new();
    for p in plants {
        let chans = args.channels(&p)?;
        for ch in chans.list {
            let label = if !chans.per_channel {
                p.name.clone()
            } else if several {
                format!("{}: {}", p.name, channel_label(&p, ch.input, ch.output))
            } else {
                channel_label(&p, ch.input, ch.output)
            };
            out.push((label, ch.factored));
        }
    }
    Ok(out)
}

/// "u1 → y2" with the plant's signal names.
fn channel_label(p: &crate::lti::Plant, i: usize, o: usize) -> String {
    let name = |v: &[String], k: usize, stem: &str| {
        v.get(k)
            .cloned()
            .unwrap_or_else(|| format!("{stem}{}", k + 1))
    };
    format!(
        "{} → {}",
        name(&p.signals.inputs, i, "u"),
        name(&p.signals.outputs, o, "y")
    )
}

/// The automatic frequency range covering every plant.
fn auto_range(plants: &[(String, Factored)]) -> Result<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi: f64 = 0.0;
    for (_, g) in plants {
        let w = auto_frequency_grid(g, 100)?;
        lo = lo.min(w.first().copied().unwrap_or(lo));
        hi = hi.max(w.last().copied().unwrap_or(hi));
    }
    Ok((lo, hi))
}

/// The Bode grid of one MIMO plant: rows = outputs, columns = inputs.
fn bode_grid_figure(
    path: &Path,
    plant: &crate::lti::Plant,
    chans: &super::channels::Channels,
    range: Option<(f64, f64)>,
    opts: &PlotOptions,
) -> Result<(f64, f64)> {
    let labelled: Vec<(String, Factored)> = chans
        .list
        .iter()
        .map(|c| (String::new(), c.factored.clone()))
        .collect();
    let (lo, hi) = match range {
        Some(r) => r,
        None => auto_range(&labelled)?,
    };
    let frs = chans
        .list
        .iter()
        .map(|c| {
            Ok(c.factored
                .freq_response(&merged_grid(&c.factored, lo, hi)?)?)
        })
        .collect::<Result<Vec<_>>>()?;
    let grid = BodeGrid {
        inputs: plant.signals.inputs.clone(),
        outputs: plant.signals.outputs.clone(),
        cells: chans
            .list
            .iter()
            .zip(&frs)
            .map(|(c, fr)| (c.input, c.output, fr))
            .collect(),
        // a discrete plant: the Nyquist frequency π/T is marked in every cell
        nyquist_frequency: plant.domain().dt().map(|dt| std::f64::consts::PI / dt),
    };
    let mut opts = opts.clone();
    if opts.title.is_none() {
        opts.title = Some(format!("Bode diagram of {}", plant.name));
    }
    bode_grid_png(path, &grid, &opts)?;
    Ok((lo, hi))
}

#[derive(Args, Debug)]
pub struct BodeArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    #[command(flatten)]
    pub plot: PlotArgs,
    /// Draw the straight-line asymptotes too.
    #[arg(long)]
    pub asymptotes: bool,
    /// Lowest frequency (rad/s); default from the poles and zeros.
    #[arg(long, requires = "wmax")]
    pub wmin: Option<f64>,
    /// Highest frequency (rad/s).
    #[arg(long, requires = "wmin")]
    pub wmax: Option<f64>,
}

pub fn bode(a: &BodeArgs) -> Result<()> {
    let opts = a.plot.options()?;
    let range = match (a.wmin, a.wmax) {
        (Some(lo), Some(hi)) => {
            if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && hi > lo) {
                bail!(
                    "--wmin/--wmax: need 0 < wmin < wmax, got {} and {}",
                    crate::error::number(lo),
                    crate::error::number(hi)
                );
            }
            Some((lo, hi))
        }
        _ => None,
    };
    let mut list = a.plant.resolve_for(LoopSystem::Loop)?;
    if list.len() == 1
        && list[0].selection.is_none()
        && !list[0].model.is_siso()
        && a.plant.channel.is_none()
    {
        let plant = list.remove(0);
        let chans = a.plant.channels(&plant)?;
        let drawn = bode_grid_figure(&a.plot.output, &plant, &chans, range, &opts)
            .with_context(|| format!("Bode plot {}", a.plot.output.display()))?;
        if a.plot.json {
            let channels: Vec<Value> = chans
                .list
                .iter()
                .map(|c| {
                    json!({
                        "input": c.input + 1,
                        "output": c.output + 1,
                        "label": channel_label(&plant, c.input, c.output),
                    })
                })
                .collect();
            return print_json(&json!({
                "file": a.plot.output.display().to_string(),
                "plant": plant.name,
                "w_range": [drawn.0, drawn.1],
                "channels": channels,
            }));
        }
        return Ok(());
    }
    let plants = labelled(&a.plant, LoopSystem::Loop)?;
    let opts = discrete_title(&opts, "Bode diagram", &plants);
    // stability margins belong to a loop: not drawn for T, S or C·S
    let p = &a.plant;
    let margins = !(p.closed_loop || p.sensitivity || p.control_sensitivity);
    let drawn = bode_figure(&a.plot.output, &plants, range, a.asymptotes, margins, &opts)
        .with_context(|| format!("Bode plot {}", a.plot.output.display()))?;
    if !a.plot.json {
        return Ok(());
    }
    let list = labelled_json(&plants, &drawn.margins, |m| {
        Ok(json!({ "margins": optional_json(m.as_ref())? }))
    })?;
    print_json(&json!({
        "file": a.plot.output.display().to_string(),
        "w_range": [drawn.range.0, drawn.range.1],
        "plants": list,
    }))
}

#[derive(Args, Debug)]
pub struct StepArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    #[command(flatten)]
    pub plot: PlotArgs,
    /// step, impulse or ramp (or any response input: exp:A, sin:W, cos:W).
    #[arg(long, default_value = "step", allow_hyphen_values = true)]
    pub input: String,
    /// End time (s); default from the slowest mode.
    #[arg(long = "t-end", allow_hyphen_values = true)]
    pub t_end: Option<f64>,
}

pub fn step(a: &StepArgs) -> Result<()> {
    let opts = a.plot.options()?;
    let input: Input = a.input.parse()?;
    if matches!(input, Input::None) {
        bail!("--input none has no response to draw (use `ltikit response --ic ...`)");
    }
    let plants = labelled(&a.plant, LoopSystem::ClosedLoop)?;
    let opts = discrete_title(&opts, &format!("{} response", input.title()), &plants);
    let drawn = step_figure(&a.plot.output, &plants, &input, a.t_end, &opts)
        .with_context(|| format!("response plot {}", a.plot.output.display()))?;
    if !a.plot.json {
        return Ok(());
    }
    let list = labelled_json(&plants, &drawn.plants, |(info, diverges)| {
        Ok(json!({
            // the analyze contract's step metrics (null with a `…_note` where not computed)
            "step_info": optional_json(
                info.as_ref()
                    .map(super::analyze::json::StepInfoJson::from)
                    .as_ref()
            )?,
            "diverges": diverges,
        }))
    })?;
    print_json(&json!({
        "file": a.plot.output.display().to_string(),
        "input": a.input,
        "t_end": drawn.t_end,
        "plants": list,
    }))
}

#[derive(Args, Debug)]
pub struct PzmapArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    #[command(flatten)]
    pub plot: PlotArgs,
    /// Draw constant-ζ lines and constant-ωn circles.
    #[arg(long)]
    pub guides: bool,
}

pub fn pzmap(a: &PzmapArgs) -> Result<()> {
    let opts = a.plot.options()?;
    let p = a.plant.single()?;
    let chans = a.plant.channels(&p)?;
    if !chans.per_channel {
        let Some(ch) = chans.list.first() else {
            bail!("no channel to draw");
        };
        let opts = discrete_title(
            &opts,
            "Pole-zero map",
            &[(p.name.clone(), ch.factored.clone())],
        );
        pzmap_figure(&a.plot.output, &p.name, &ch.factored, a.guides, &opts)
            .with_context(|| format!("pole-zero map {}", a.plot.output.display()))?;
        if a.plot.json {
            let mut doc = json!({"file": a.plot.output.display().to_string(), "label": p.name});
            if let (Some(m), Value::Object(roots)) = (doc.as_object_mut(), roots_json(&ch.factored))
            {
                m.extend(roots);
            }
            return print_json(&doc);
        }
        return Ok(());
    }
    // A MIMO plant: one map per channel (the poles of A, the channel's transmission zeros),
    // FILE-i-j.png for input i → output j.
    let mut written = String::new();
    let mut docs = Vec::new();
    for ch in &chans.list {
        let path = channel_path(&a.plot.output, ch.input, ch.output);
        let label = format!("{}, {}", p.name, channel_label(&p, ch.input, ch.output));
        pzmap_figure(&path, &label, &ch.factored, a.guides, &opts)
            .with_context(|| format!("pole-zero map {}", path.display()))?;
        written.push_str(&format!(
            "{}: {}\n",
            path.display(),
            super::channels::heading(&p, ch.input, ch.output)
        ));
        let mut doc = json!({
            "file": path.display().to_string(),
            "input": ch.input + 1,
            "output": ch.output + 1,
            "label": label,
        });
        if let (Some(m), Value::Object(roots)) = (doc.as_object_mut(), roots_json(&ch.factored)) {
            m.extend(roots);
        }
        docs.push(doc);
    }
    if a.plot.json {
        return print_json(&json!({ "channels": docs }));
    }
    super::output::print(&written)
}

/// One JSON object per plant: `"label"` first, then the fields `fields` gives for its item.
fn labelled_json<T>(
    plants: &[(String, Factored)],
    items: &[T],
    fields: impl Fn(&T) -> Result<Value>,
) -> Result<Vec<Value>> {
    plants
        .iter()
        .zip(items)
        .map(|((label, _), item)| {
            let mut doc = serde_json::Map::new();
            doc.insert("label".into(), json!(label));
            if let Value::Object(m) = fields(item)? {
                doc.extend(m);
            }
            Ok(Value::Object(doc))
        })
        .collect()
}

/// A library struct as JSON, `null` when absent.
pub(super) fn optional_json<T: serde::Serialize>(x: Option<&T>) -> Result<Value> {
    Ok(match x {
        Some(x) => json_value(x)?,
        None => Value::Null,
    })
}

/// The roots a pole-zero map marks, as the JSON contract lists them: `[re, im]` with
/// repetition.
fn roots_json(g: &Factored) -> Value {
    let list = |r: &[crate::Root]| -> Vec<[f64; 2]> { flatten(r).into_iter().map(pair).collect() };
    let pz = g.pole_zero();
    json!({
        "poles": list(&pz.poles),
        "zeros": list(&pz.zeros),
        "cancelled": list(&pz.cancelled),
    })
}

/// `FILE.png` → `FILE-i-j.png` (1-based input i, output j).
fn channel_path(path: &Path, i: usize, o: usize) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "pzmap".into());
    let ext = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    path.with_file_name(format!("{stem}-{}-{}{ext}", i + 1, o + 1))
}

#[derive(Args, Debug)]
pub struct NyquistArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    #[command(flatten)]
    pub plot: PlotArgs,
}

pub fn nyquist(a: &NyquistArgs) -> Result<()> {
    let opts = a.plot.options()?;
    let plants = labelled(&a.plant, LoopSystem::Loop)?;
    let contours = plants
        .iter()
        .map(|(_, g)| g.nyquist())
        .collect::<crate::Result<Vec<_>>>()?;
    let opts = discrete_title(&opts, "Nyquist diagram", &plants);
    let series: Vec<NyquistSeries> = plants
        .iter()
        .zip(&contours)
        .map(|((label, _), c)| NyquistSeries::new(c).label(label))
        .collect();
    nyquist_png(&a.plot.output, &series, &opts)
        .with_context(|| format!("Nyquist plot {}", a.plot.output.display()))?;
    if !a.plot.json {
        return Ok(());
    }
    let list = labelled_json(&plants, &contours, |c| {
        Ok(json!({
            "open_loop_rhp_poles": c.open_loop_rhp_poles,
            "encirclements": c.encirclements,
            "closed_loop_rhp_poles": c.closed_loop_rhp_poles,
            "g_at_infinity": c.g_at_infinity,
            "axis_poles": c.axis_poles,
            // where P and Z are counted
            "region": if c.dt.is_some() { "outside the unit circle" } else { "right half plane" },
        }))
    })?;
    print_json(&json!({
        "file": a.plot.output.display().to_string(),
        "plants": list,
    }))
}
