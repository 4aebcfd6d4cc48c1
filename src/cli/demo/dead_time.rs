//! The dead-time section: the seed's tank (h' + 0.5 h = u, eq. 3.6) fed through a pipe that
//! delays the inflow by 2 s, under PI control. The delay is kept exact: the loop's margins and
//! delay margin, the delays for which the loop is stable (crossing frequencies and delays of
//! D(s) + N(s)e^(−sT)), the rightmost characteristic roots, the closed-loop step by the method
//! of steps — against Padé approximants of order 1, 3 and 10 — and the Nyquist spiral.

use anyhow::Result;

use super::context::Ctx;
use super::md::Md;
use crate::analysis::{ClosedLoop, Factored, Input, LoopSystem, TimeResponse, nyquist_contour};
use crate::fmt::{fmt_root, fmt_sig};
use crate::lti::{Controller, TransferFunction};
use crate::plot::{NyquistSeries, StepSeries, nyquist_png, step_png};

const GROUP: &str = "dead time: two independent computations agree";
/// The pipe's dead time (s) and the PI controller.
const DELAY: f64 = 2.0;
const KP: f64 = 0.4;
const KI: f64 = 0.15;

pub fn section(ctx: &mut Ctx, md: &mut Md, index: usize) -> Result<()> {
    md.h2(&format!("{index}. Dead time"));
    let g = TransferFunction::from_descending(&[1.0], &[1.0, 0.5])?.with_delay(DELAY)?;
    let c = Controller::new("pi", &[("kp".into(), KP), ("ki".into(), KI)])?;
    let cf = c.tf()?.factored()?;
    let gf = g.factored()?;
    let l = cf.series(&gf.rational())?; // the rational part of the loop
    let ld = l.clone().with_delay(DELAY)?; // L·e^(−sT)
    md.p(&format!(
        "The seed's tank h' + 0.5 h = u (eq. 3.6) filled through a pipe: the inflow arrives \
         T = {DELAY} s after the valve moves, G(s) = {g}. Under the PI controller C = {c} the \
         loop is L(s)·e^(−sT) with L = {l}. The closed loop L·e^(−sT)/(1 + L·e^(−sT)) has no \
         rational transfer function — python-control's answer is a Padé approximant — but \
         every analysis here keeps e^(−sT) exact: the phase loses ωT, the characteristic \
         equation D(s) + N(s)e^(−sT) = 0 is analysed for every T, and the closed-loop step is \
         a finite sum of shifted closed forms on [0, t] (the method of steps: \
         y(t) = Σ (−1)^(k+1) h_k(t − kT), h_k the step response of L^k, exact from the factors)."
    ));
    margins_and_intervals(ctx, md, &l, &ld)?;
    step_against_pade(ctx, md, &cf, &gf, &l)?;
    spiral(ctx, md, &ld)
}

/// Margins of L·e^(−sT) against the stability-in-the-delay analysis of the same loop.
fn margins_and_intervals(ctx: &mut Ctx, md: &mut Md, l: &Factored, ld: &Factored) -> Result<()> {
    md.h3("Margins, the delay margin and the stable delays");
    let m = ld.margins()?;
    let st = l.delay_stability()?;
    let roots = l.closed_loop_delay_roots(DELAY, 4)?;
    let critical = st.critical_delay.unwrap_or(f64::NAN);
    let dm = m.delay_margin.unwrap_or(f64::NAN);
    // the delay margin of L·e^(−sT) (phase margin over crossover) plus T is the critical
    // delay of the crossing analysis (arg(−L(jω_c)) over ω_c): two routes to one number
    ctx.checks.add(
        GROUP,
        "delay margin + T = critical delay (margins vs crossing delays), relative",
        ((dm + DELAY - critical) / critical).abs(),
        1e-12,
    );
    // the count of unstable roots by the crossing delays against the delayed Nyquist winding
    let mut worst: f64 = 0.0;
    for t in [1.0, 4.0, 6.0, 20.0, 30.0] {
        let by_crossings = st.unstable_roots_at(t)? as f64;
        let by_winding = l.delayed_nyquist_count(t)? as f64;
        worst = worst.max((by_crossings - by_winding).abs());
    }
    ctx.checks.add(
        GROUP,
        "unstable roots at T = 1, 4, 6, 20, 30 s: crossing delays vs Nyquist winding",
        worst,
        0.0,
    );
    let interval = st.stable_intervals.first().map_or("none".to_string(), |i| {
        format!("[{}, {}) s", fmt_sig(i.from, 7), fmt_sig(i.to, 7))
    });
    let rows = vec![
        vec![
            "gain margin".into(),
            format!(
                "{} ({} dB) at ω = {} rad/s",
                fmt_sig(m.gain_margin.unwrap_or(f64::NAN), 6),
                fmt_sig(m.gain_margin_db.unwrap_or(f64::NAN), 4),
                fmt_sig(m.phase_crossover.unwrap_or(f64::NAN), 6)
            ),
        ],
        vec![
            "phase margin".into(),
            format!(
                "{}° at ω_c = {} rad/s (−ω_c·T = {}° of it is the delay's)",
                fmt_sig(m.phase_margin_deg.unwrap_or(f64::NAN), 6),
                fmt_sig(m.gain_crossover.unwrap_or(f64::NAN), 6),
                fmt_sig(-(m.gain_crossover.unwrap_or(0.0) * DELAY).to_degrees(), 4)
            ),
        ],
        vec![
            "delay margin (what the loop can still take)".into(),
            format!("{} s", fmt_sig(dm, 7)),
        ],
        vec![
            "critical delay".into(),
            format!("{} s", fmt_sig(critical, 10)),
        ],
        vec!["stable for T in".into(), interval],
        vec![
            "phase crossings listed".into(),
            format!(
                "{} up to ω = {} rad/s (a delay makes infinitely many)",
                m.phase_crossings.len(),
                fmt_sig(m.crossings_listed_to.unwrap_or(f64::NAN), 4)
            ),
        ],
    ];
    md.table(&["quantity", "value"], &rows);
    let listed: Vec<String> = roots
        .roots
        .iter()
        .filter(|r| r.value.im >= 0.0)
        .map(|r| {
            format!(
                "{} (residual {})",
                fmt_root(r.value, 6),
                fmt_sig(r.relative_residual, 2)
            )
        })
        .collect();
    md.p(&format!(
        "The characteristic equation has infinitely many roots; the rightmost at T = {DELAY} s \
         (Newton on D(s) + N(s)e^(−sT) from Padé starting points) are {}. A pair crosses the \
         imaginary axis at ω = {} rad/s when T reaches the critical delay, and again every \
         {} s after it.",
        listed.join(", "),
        fmt_sig(st.crossings.first().map_or(f64::NAN, |c| c.frequency), 6),
        fmt_sig(st.crossings.first().map_or(f64::NAN, |c| c.period()), 6)
    ));
    Ok(())
}

/// The exact closed-loop step against the closed loops of Padé approximants.
fn step_against_pade(
    ctx: &mut Ctx,
    md: &mut Md,
    cf: &Factored,
    gf: &Factored,
    l: &Factored,
) -> Result<()> {
    md.h3("The closed-loop step: exact against Padé");
    let t_end = 20.0;
    let t: Vec<f64> = (0..=2000).map(|i| t_end * i as f64 / 2000.0).collect();
    let exact = l.delayed_feedback_response(DELAY, &Input::Step, &t)?;
    ctx.checks.add(
        GROUP,
        "closed-loop step over 10 delays: closed form of the pieces vs their exact march",
        exact.closed_form_error,
        1e-10,
    );
    let mut rows = Vec::new();
    let mut curves = Vec::new();
    for n in [1usize, 3, 10] {
        let approx = gf.pade(n)?;
        let cl = ClosedLoop::new(cf, &approx)?;
        let y = cl.system(LoopSystem::ClosedLoop)?.step_response(&t)?.y;
        let err = y
            .iter()
            .zip(&exact.y)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        rows.push(vec![
            format!("Padé [{n}/{n}]"),
            fmt_sig(err, 3),
            format!("{}", cl.system(LoopSystem::ClosedLoop)?.order()),
        ]);
        if n < 10 {
            curves.push((format!("Padé [{n}/{n}]"), y));
        }
    }
    md.p(&format!(
        "The step of T over [0, {t_end}] s ({} delays, one shifted closed form per delay) \
         against the rational closed loops with e^(−sT) replaced by its [n/n] Padé approximant \
         (`--pade n`): the largest difference over 2001 samples.",
        t_end / DELAY
    ));
    md.table(
        &["approximant", "max |y − y_exact|", "closed-loop order"],
        &rows,
    );
    let info = l.delayed_step_info(DELAY, t_end, true, &Default::default())?;
    let exact_r = TimeResponse {
        t: t.clone(),
        y: exact.y.clone(),
        final_value: Some(1.0),
    };
    let approx_r: Vec<(String, TimeResponse)> = curves
        .into_iter()
        .map(|(label, y)| {
            (
                label,
                TimeResponse {
                    t: t.clone(),
                    y,
                    final_value: Some(1.0),
                },
            )
        })
        .collect();
    let mut series = vec![StepSeries::new(&exact_r).label("exact (method of steps)")];
    if let Some(i) = &info {
        series[0] = series[0].clone().info(i);
    }
    for (label, r) in &approx_r {
        series.push(StepSeries::new(r).label(label));
    }
    let file = "dead-time-step.png";
    step_png(
        ctx.figure(file),
        &series,
        &super::context::fig("PI loop around the tank with a 2 s pipe delay: exact and Padé"),
    )?;
    md.image(
        "Closed-loop step with the exact dead time and Padé approximants",
        file,
    );
    if let Some(i) = info {
        md.p(&format!(
            "Exact step metrics of the delayed loop: rise time {} s, overshoot {} %, settling \
             time {} s (2 %).",
            fmt_sig(i.rise_time.unwrap_or(f64::NAN), 5),
            fmt_sig(i.overshoot_percent.unwrap_or(f64::NAN), 4),
            fmt_sig(i.settling_time.unwrap_or(f64::NAN), 5)
        ));
    }
    Ok(())
}

/// The Nyquist spiral of L·e^(−sT).
fn spiral(ctx: &mut Ctx, md: &mut Md, ld: &Factored) -> Result<()> {
    let n = nyquist_contour(ld)?;
    let file = "dead-time-nyquist.png";
    nyquist_png(
        ctx.figure(file),
        &[NyquistSeries::new(&n).label("L·e^(−2s)")],
        &super::context::fig("Nyquist diagram of the delayed loop"),
    )?;
    md.p(&format!(
        "The delay winds L(jω)e^(−jωT) into a spiral about the origin; it encircles −1 {} \
         times (P = {} open-loop poles in the right half plane), so Z = N + P = {} closed-loop \
         roots are unstable.",
        n.encirclements
            .map_or("an undetermined number of".into(), |e| e.to_string()),
        n.open_loop_rhp_poles,
        n.closed_loop_rhp_poles
            .map_or("an undetermined number of".into(), |z| z.to_string())
    ));
    md.image("Nyquist spiral of the loop with its dead time", file);
    Ok(())
}
