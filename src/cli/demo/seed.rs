//! The seed's second-order cases: the four damping cases of figs. 2.3/2.5/2.6 (the seed's
//! analytic responses, eqs. 3.33–3.35, are checked against the computed ones in
//! tests/response.rs).

use anyhow::Result;

use super::super::plots;
use super::context::Ctx;
use super::linear::roots_text;
use super::md::Md;
use crate::analysis::{Factored, Input};
use crate::fmt::{fmt_opt, fmt_sig};
use crate::lti::build_plant;
use crate::plot::{Curve, Equilibrium, PhasePortrait, phase_portrait_png, series_color};

/// The `second-order` textbook model ẍ + 2ζωₙẋ + ωₙ²x = u with ωₙ = 1, factored.
fn second_order(zeta: f64) -> Result<Factored> {
    let (g, _) = build_plant("second-order", &[("wn".into(), 1.0), ("zeta".into(), zeta)])?;
    Ok(g.factored()?)
}

/// The damping cases of the seed's figures.
const CASES: [f64; 4] = [0.0, 0.1, 1.0, 2.0];

/// Initial displacement of fig. 2.6.
const X0: f64 = std::f64::consts::PI / 36.0;

#[allow(clippy::float_cmp)] // ζ = 0 exactly selects the undamped window
pub fn damping_cases(ctx: &mut Ctx, md: &mut Md, index: usize) -> Result<()> {
    md.h2(&format!("{index}. The four damping cases of the seed"));
    md.p(
        "ẍ + 2ζωₙẋ + ωₙ²x = u with ωₙ = 1 and ζ = 0 (undamped), 0.1 (underdamped), 1 \
          (critically damped) and 2 (overdamped), as in seed figs. 2.3 and 2.5; the free \
          responses start from x(0) = π/36, ẋ(0) = 0 as in fig. 2.6. Critical damping is \
          recognised exactly: one pole of multiplicity 2, and the response has the \
          (c₁ + c₂t)e^(−t) form of eq. 3.35.",
    );
    let mut rows = Vec::new();
    let plants: Vec<(String, Factored)> = CASES
        .iter()
        .map(|&z| Ok((format!("ζ = {z}"), second_order(z)?)))
        .collect::<Result<_>>()?;
    for (&z, (_, g)) in CASES.iter().zip(&plants) {
        let a = g.analyze()?;
        let t: Vec<f64> = (0..=400).map(|i| 0.1 * i as f64).collect();
        let free = g.response(&Input::None, &[X0, 0.0], &t)?;
        let step = a.step_info.as_ref().map(|s| {
            format!(
                "rise {} s, settling {} s, overshoot {} %",
                fmt_opt(s.rise_time, 4),
                fmt_opt(s.settling_time, 4),
                fmt_opt(s.overshoot_percent, 4)
            )
        });
        rows.push(vec![
            fmt_sig(z, 2),
            a.second_order
                .map(|s| s.class.words().to_string())
                .unwrap_or_default(),
            roots_text(&a.pole_zero.poles),
            format!("`{}`", free.closed_form.formula("x(t)")),
            step.unwrap_or_else(|| "does not settle".into()),
        ]);
        let s = &free.samples;
        ctx.checks.add(
            "closed form vs exact simulation (relative to max|y|)",
            format!("damping case ζ = {z}: free response from π/36"),
            s.closed_form_error / s.max_abs_y,
            1e-8,
        );
    }
    md.table(
        &[
            "ζ",
            "class",
            "poles",
            "free response from x(0) = π/36",
            "step metrics",
        ],
        &rows,
    );
    let step = "damping-step.png";
    plots::step_figure(
        &ctx.figure(step),
        &plants,
        &Input::Step,
        Some(40.0),
        &super::context::fig("Step responses for ζ = 0, 0.1, 1, 2 (ωn = 1; seed figs. 2.3, 2.5)"),
    )?;
    let bode = "damping-bode.png";
    plots::bode_figure(
        &ctx.figure(bode),
        &plants,
        Some((0.01, 100.0)),
        false,
        false,
        &super::context::fig("Bode diagrams for ζ = 0, 0.1, 1, 2 (ωn = 1; exercise 3.2)"),
    )?;
    // Phase plots ẋ against x from x(0) = π/36 (fig. 2.6), from the exact closed forms.
    let mut curves = Vec::new();
    for (k, (&z, (_, g))) in CASES.iter().zip(&plants).enumerate() {
        let free = g.inverse_laplace(&Input::None, &[X0, 0.0])?;
        let t_end = if z == 0.0 {
            2.0 * std::f64::consts::PI
        } else {
            40.0
        };
        let pts: Vec<(f64, f64)> = (0..=2000)
            .map(|i| {
                let t = t_end * i as f64 / 2000.0;
                (
                    free.closed_form.eval(t),
                    free.closed_form.eval_derivative(t),
                )
            })
            .collect();
        curves.push(
            Curve::new(pts)
                .label(format!("ζ = {z}"))
                .color(series_color(k)),
        );
    }
    let phase = "damping-phase.png";
    phase_portrait_png(
        ctx.figure(phase),
        &PhasePortrait {
            trajectories: curves,
            equilibria: vec![Equilibrium {
                at: (0.0, 0.0),
                stable: true,
                label: None,
            }],
            x_label: "x (rad)".into(),
            y_label: "ẋ (rad/s)".into(),
            equal_aspect: true,
            ..Default::default()
        },
        &super::context::fig("Phase plot ẋ against x from x(0) = π/36 (seed fig. 2.6)"),
    )?;
    md.image("Step responses of the four damping cases", step);
    md.image("Bode diagrams of the four damping cases", bode);
    md.image("Phase plot of the four damping cases", phase);
    Ok(())
}
