//! The linear textbook plants: one section each, and the seed's four damping cases.

use anyhow::Result;

use super::super::plots;
use super::context::Ctx;
use super::md::Md;
use crate::TransferFunction;
use crate::analysis::Factored;
use crate::analysis::{Analysis, Input, auto_time_span};
pub use crate::cli::text::roots_text;
use crate::fmt::{fmt_num, fmt_opt, fmt_root, fmt_sig};
use crate::lti::{Plant, PlantFile};

/// A plant of the tour, factored once.
pub struct DemoPlant {
    /// File-name stem for its pictures.
    pub slug: &'static str,
    /// Its plant file (name, description, source, units).
    pub file: PlantFile,
    /// Its name.
    pub name: String,
    /// The plant as given.
    pub tf: TransferFunction,
    /// The factored form every analysis of the section reads.
    pub f: Factored,
}

/// The shipped plant files, compiled in so the demo runs from any directory.
pub fn plants() -> Result<Vec<DemoPlant>> {
    let sources: [(&str, &str); 6] = [
        (
            "spring-mass-damper",
            include_str!("../../../data/plants/spring-mass-damper.toml"),
        ),
        (
            "suspension",
            include_str!("../../../data/plants/suspension.toml"),
        ),
        ("tank", include_str!("../../../data/plants/tank.toml")),
        ("rc", include_str!("../../../data/plants/rc.toml")),
        ("rlc", include_str!("../../../data/plants/rlc.toml")),
        ("two-dof", include_str!("../../../data/plants/two-dof.toml")),
    ];
    sources
        .iter()
        .map(|(slug, text)| {
            let file = PlantFile::parse(text)?;
            let plant = Plant::from_record(&file)?;
            let f = plant.factored()?;
            let tf = plant.tf().cloned().ok_or_else(|| {
                anyhow::anyhow!("the textbook plant files hold transfer functions")
            })?;
            Ok(DemoPlant {
                slug,
                file,
                name: plant.name,
                tf,
                f,
            })
        })
        .collect()
}

/// "y''" for the k-th derivative of `v`.
fn derivative(v: &str, k: usize) -> String {
    match k {
        0 => v.to_string(),
        1..=3 => format!("{v}{}", "'".repeat(k)),
        _ => format!("{v}^({k})"),
    }
}

/// The ODE a_n y^(n) + … = b_m u^(m) + … with the plant's numbers.
pub fn ode_of(g: &TransferFunction) -> String {
    let side = |p: &crate::Poly, v: &str| {
        let n = p.degree();
        let mut s = String::new();
        for (i, &a) in p.coeffs().iter().enumerate() {
            if a == 0.0 {
                continue;
            }
            let term = derivative(v, n - i);
            let mag = a.abs();
            let body = if mag.to_bits() == 1f64.to_bits() {
                term
            } else {
                format!("{} {term}", fmt_num(mag))
            };
            if s.is_empty() {
                s = if a < 0.0 { format!("-{body}") } else { body };
            } else {
                s.push_str(&format!(" {} {body}", if a < 0.0 { "-" } else { "+" }));
            }
        }
        if s.is_empty() { "0".into() } else { s }
    };
    format!("{} = {}", side(g.den(), "y"), side(g.num(), "u"))
}

/// Summary table rows of an analysis.
pub fn analysis_rows(g: &Factored, a: &Analysis) -> Vec<Vec<String>> {
    let pz = &a.pole_zero;
    let mut rows = vec![
        vec!["transfer function".into(), format!("G(s) = {g}")],
        vec![
            "order, relative degree".into(),
            match a.relative_degree {
                Some(r) => format!("{}, {r}", a.order),
                None => format!("{}, – (G = 0)", a.order),
            },
        ],
        vec!["poles".into(), roots_text(&pz.poles)],
        vec![
            "zeros".into(),
            format!(
                "{}{}",
                roots_text(&pz.zeros),
                match pz.zeros_at_infinity {
                    Some(k) if k > 0 => format!("; {k} at infinity"),
                    _ => String::new(),
                }
            ),
        ],
    ];
    if !pz.cancelled.is_empty() {
        rows.push(vec!["cancelled".into(), roots_text(&pz.cancelled)]);
    }
    rows.push(vec![
        "dc gain".into(),
        a.dc_gain
            .map(|d| fmt_sig(d, 6))
            .unwrap_or_else(|| "∞".into()),
    ]);
    rows.push(vec![
        "stability".into(),
        format!(
            "{}, {}: {}",
            if a.stability.bibo_stable {
                "BIBO stable"
            } else {
                "not BIBO stable"
            },
            if a.stability.internally_stable {
                "internally stable"
            } else {
                "not internally stable"
            },
            a.stability.reason
        ),
    ]);
    if let Some(so) = &a.second_order {
        let mut s = so.class.words().to_string();
        if let (Some(wn), Some(z)) = (so.wn, so.zeta) {
            s.push_str(&format!(
                ": ωn = {} rad/s, ζ = {}",
                fmt_sig(wn, 6),
                fmt_sig(z, 6)
            ));
        }
        if let Some(wd) = so.wd {
            s.push_str(&format!(", ωd = {} rad/s", fmt_sig(wd, 6)));
        }
        rows.push(vec!["second order".into(), s]);
    }
    rows
}

/// The modes table.
pub fn modes_table(md: &mut Md, a: &Analysis) {
    let rows: Vec<Vec<String>> = a
        .modes
        .iter()
        .filter(|m| m.pole.im >= 0.0)
        .map(|m| {
            vec![
                format!(
                    "{}{}",
                    fmt_root(m.pole, 6),
                    if m.multiplicity > 1 {
                        format!(" (×{})", m.multiplicity)
                    } else {
                        String::new()
                    }
                ),
                fmt_sig(m.wn, 6),
                m.zeta.map(|z| fmt_sig(z, 6)).unwrap_or_else(|| "–".into()),
                m.time_constant
                    .map(|t| fmt_sig(t, 6))
                    .unwrap_or_else(|| "–".into()),
            ]
        })
        .collect();
    md.table(
        &["mode (pole)", "ωn [rad/s]", "ζ", "time constant [s]"],
        &rows,
    );
}

/// Writes the closed-form response for `input` and `ics`, records the closed form vs exact
/// simulation check, and returns the response (closed form and samples from one call).
pub fn closed_form_block(
    ctx: &mut Ctx,
    md: &mut Md,
    name: &str,
    g: &Factored,
    input: &Input,
    ics: &[f64],
) -> Result<crate::analysis::Response> {
    let t_end = auto_time_span(g)?.t_end;
    let t: Vec<f64> = (0..=400).map(|i| t_end * i as f64 / 400.0).collect();
    let resp = g.response(input, ics, &t)?;
    let mut text = resp.closed_form.formula("y(t)");
    text.push_str(&format!(
        "\n  transient (system poles):   {}",
        resp.transient.expression()
    ));
    text.push_str(&format!(
        "\n  steady state (input poles): {}",
        resp.steady_state.expression()
    ));
    md.code(&text);
    let s = &resp.samples;
    let rel = if s.max_abs_y > 0.0 {
        s.closed_form_error / s.max_abs_y
    } else {
        s.closed_form_error
    };
    let what = if ics.is_empty() {
        format!("{name}: {input} response")
    } else {
        format!("{name}: initial conditions {ics:?}, input {input}")
    };
    ctx.checks.add(
        "closed form vs exact simulation (relative to max|y|)",
        what,
        rel,
        1e-8,
    );
    Ok(resp)
}

/// Frequencies for the M(ω), φ(ω) table: a decade below, at, and a decade above the
/// characteristic frequency (geometric mean of the non-zero pole magnitudes).
fn table_frequencies(a: &Analysis) -> Vec<f64> {
    let mags: Vec<f64> = a
        .pole_zero
        .poles
        .iter()
        .map(|r| r.value.norm())
        .filter(|m| *m > 0.0)
        .collect();
    let wc = if mags.is_empty() {
        1.0
    } else {
        (mags.iter().map(|m| m.ln()).sum::<f64>() / mags.len() as f64).exp()
    };
    let p = 10f64.powf(wc.log10().round());
    [0.1, 0.5, 1.0, 2.0, 10.0].iter().map(|k| k * p).collect()
}

/// One plant's section.
pub fn plant_section(ctx: &mut Ctx, md: &mut Md, index: usize, p: &DemoPlant) -> Result<Analysis> {
    let g = &p.f;
    let name = p.name.as_str();
    md.h2(&format!("{index}. {name}"));
    let mut intro = String::new();
    if let Some(d) = &p.file.description {
        intro.push_str(d);
    }
    if let Some(s) = &p.file.source {
        intro.push_str(&format!(" (*{s}*)"));
    }
    if let (Some(i), Some(o)) = (&p.file.input, &p.file.output) {
        intro.push_str(&format!(" Input: {i}; output: {o}."));
    }
    md.p(&intro);
    md.p(&format!("ODE: `{}`", ode_of(&p.tf)));
    let a = g.analyze()?;
    md.table(&["property", "value"], &analysis_rows(g, &a));
    modes_table(md, &a);

    step_block(ctx, md, name, g, &a)?;
    ic_block(ctx, md, name, g)?;
    frequency_block(ctx, md, name, g, &a)?;
    figures(ctx, md, p)?;
    Ok(a)
}

/// The closed-form step response and the step metrics (checked on the exact response).
fn step_block(ctx: &mut Ctx, md: &mut Md, name: &str, g: &Factored, a: &Analysis) -> Result<()> {
    md.h3("Step response");
    md.p(
        "Closed form of L⁻¹{G(s)/s}; the transient part comes from the system poles, the \
          steady state from the input pole (seed eqs. 3.39–3.40).",
    );
    closed_form_block(ctx, md, name, g, &Input::Step, &[])?;
    match &a.step_info {
        Some(si) => {
            md.table(
                &[
                    "rise time (10–90 %)",
                    "settling time (2 %)",
                    "overshoot",
                    "peak",
                    "peak time",
                    "final value",
                ],
                &[vec![
                    format!("{} s", fmt_opt(si.rise_time, 6)),
                    format!("{} s", fmt_opt(si.settling_time, 6)),
                    format!("{} %", fmt_opt(si.overshoot_percent, 6)),
                    fmt_opt(si.peak, 6),
                    match si.peak_time {
                        Some(t) if t.is_finite() => format!("{} s", fmt_sig(t, 6)),
                        Some(_) => "approached as t → ∞".into(),
                        None => "not computed".into(),
                    },
                    fmt_sig(si.steady_state, 6),
                ]],
            );
            ctx.checks.step_metrics(name, g, si)?;
        }
        None => md.p("The step response does not settle: no step metrics."),
    }

    Ok(())
}

/// The free response from y(0) = 1.
fn ic_block(ctx: &mut Ctx, md: &mut Md, name: &str, g: &Factored) -> Result<()> {
    md.h3("Initial-condition response");
    let n = g.order();
    let mut ics = vec![0.0; n];
    ics[0] = 1.0;
    let ic_text: Vec<String> = (0..n)
        .map(|k| format!("y{}(0) = {}", "'".repeat(k), if k == 0 { 1 } else { 0 }))
        .collect();
    md.p(&format!(
        "Free response (no input) from {} (seed eqs. 3.13, 3.30):",
        ic_text.join(", ")
    ));
    closed_form_block(ctx, md, name, g, &Input::None, &ics)?;

    Ok(())
}

/// M(ω), φ(ω) at a few frequencies, margins, bandwidth and resonance (checked on G(jω)).
fn frequency_block(
    ctx: &mut Ctx,
    md: &mut Md,
    name: &str,
    g: &Factored,
    a: &Analysis,
) -> Result<()> {
    md.h3("Frequency response");
    let w = table_frequencies(a);
    let fr = g.freq_response(&w)?;
    let rows: Vec<Vec<String>> = (0..w.len())
        .map(|i| {
            vec![
                fmt_sig(w[i], 4),
                fmt_sig(fr.magnitude[i], 6),
                fmt_sig(fr.magnitude_db[i], 5),
                fmt_sig(fr.phase_deg[i], 5),
            ]
        })
        .collect();
    md.table(&["ω [rad/s]", "M(ω)", "M [dB]", "φ(ω) [deg]"], &rows);
    let m = g.margins()?;
    let inf = |x: Option<f64>, unit: &str| match x {
        Some(v) if v.is_finite() => format!("{}{unit}", fmt_sig(v, 6)),
        _ => "∞".into(),
    };
    md.bullets(&[
        format!(
            "gain margin {} ({}){}",
            inf(m.gain_margin, ""),
            inf(m.gain_margin_db, " dB"),
            m.phase_crossover
                .map(|w| format!(" at ω = {} rad/s", fmt_sig(w, 6)))
                .unwrap_or_default()
        ),
        format!(
            "phase margin {}{}",
            inf(m.phase_margin_deg, "°"),
            m.gain_crossover
                .map(|w| format!(" at ω = {} rad/s", fmt_sig(w, 6)))
                .unwrap_or_default()
        ),
        format!(
            "bandwidth (−3 dB): {}",
            m.bandwidth
                .map(|b| format!("{} rad/s", fmt_sig(b, 6)))
                .unwrap_or_else(|| "not defined".into())
        ),
        match (m.resonant_peak, m.resonant_frequency) {
            (Some(mr), Some(wr)) => format!(
                "resonant peak Mr = {} ({} dB) at ωr = {} rad/s",
                fmt_sig(mr, 6),
                fmt_sig(20.0 * mr.log10(), 4),
                fmt_sig(wr, 6)
            ),
            _ => "no resonant peak".into(),
        },
    ]);
    ctx.checks.margins(name, g, &m)?;

    Ok(())
}

/// Bode, step and pole-zero pictures of the plant.
fn figures(ctx: &mut Ctx, md: &mut Md, p: &DemoPlant) -> Result<()> {
    let g = &p.f;
    let name = p.name.as_str();
    let label = format!("G(s) = {g}");
    let plant = [(label.clone(), g.clone())];
    let bode = format!("{}-bode.png", p.slug);
    plots::bode_figure(
        &ctx.figure(&bode),
        &plant,
        None,
        true,
        true,
        &super::context::fig(format!("{}: Bode diagram", name)),
    )?;
    let step = format!("{}-step.png", p.slug);
    plots::step_figure(
        &ctx.figure(&step),
        &plant,
        &Input::Step,
        None,
        &super::context::fig(format!("{}: step response", name)),
    )?;
    let pz = format!("{}-pzmap.png", p.slug);
    plots::pzmap_figure(
        &ctx.figure(&pz),
        &label,
        g,
        true,
        &super::context::fig(format!("{}: poles and zeros", name)),
    )?;
    md.image(&format!("Bode diagram of the {}", name), &bode);
    md.image(&format!("Step response of the {}", name), &step);
    md.image(&format!("Pole-zero map of the {}", name), &pz);
    Ok(())
}
