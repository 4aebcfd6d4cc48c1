//! The gimbal gyroscope (seed eqs. 1.103–1.106, exercise 2.14): the multi-input
//! linearisation about steady spin and the exercise's two claims.

use anyhow::Result;
use num_complex::Complex64;

use super::super::context::{Ctx, fig};
use super::super::md::Md;
use super::{eigen_text, tight};
use crate::fmt::fmt_sig;
use crate::nonlinear::models::{Gyroscope, GyroscopeDiscFrame};
use crate::nonlinear::{EquilibriumSearch, InputSignal, linearize, sample_times, simulate};
use crate::plot::{Curve, LineStyle, XyPlot, series_color, xy_png};

fn matrix_text(name: &str, m: &[Vec<f64>]) -> String {
    let rows: Vec<String> = m
        .iter()
        .map(|r| {
            r.iter()
                .map(|v| format!("{:>8}", fmt_sig(if v.abs() < 1e-12 { 0.0 } else { *v }, 5)))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    let mut s = String::new();
    for (i, r) in rows.iter().enumerate() {
        let lead = if i == 0 {
            format!("{name} =")
        } else {
            String::new()
        };
        s.push_str(&format!("{lead:<4}[ {r} ]\n"));
    }
    s
}

pub fn section(ctx: &mut Ctx, md: &mut Md) -> Result<()> {
    let g = Gyroscope::default();
    let nu = g.nutation_frequency();
    md.h3("Gimbal gyroscope (seed eqs. 1.103–1.106, exercise 2.14)");
    md.p(&format!(
        "A disc (Il = I1 = {} kg·m² about a diameter, Iz = I3 = {} kg·m² about its axis) in two \
         massless gimbals; inputs the torques u₁ (outer gimbal axis e₃), u₂ (inner gimbal axis) \
         and u₃ (spin axis), outputs the gimbal angles θ₁, θ₂ (3-1-3 Euler angles, eq. 1.106). \
         The seed's disc-frame equations with its torque map T = M(θ)u are the Lagrange \
         equations of L = ½Il(θ̇₂² + θ̇₁² sin²θ₂) + ½Iz Ω₃² with generalised forces u, and the \
         spin angle θ₃ is cyclic, so x = [θ₁, θ₂, θ̇₁, θ̇₂, Ω₃]: steady spin Ω₃ = ω = {} rad/s \
         is an equilibrium for every gimbal angle away from gimbal lock (sin θ₂ = 0).",
        g.i1, g.i3, g.w
    ));
    let lin = linearize(&g, None, &EquilibriumSearch::default())?;
    let e = lin
        .equilibria
        .first()
        .ok_or_else(|| anyhow::anyhow!("the gyroscope has no steady spin"))?;
    md.p(&format!(
        "Linearised at θ₁ = 0, θ₂ = π/2 (a multi-input model, reported channel by channel with \
         the SISO transfer function of each column of B and row of C until the state-space \
         layer's MIMO analysis lands); eigenvalues {} — the nutation frequency \
         ν = Iz ω/Il = {} rad/s and three zeros (the two gimbal angles and the spin are \
         neutral):",
        eigen_text(&e.eigenvalues),
        fmt_sig(nu, 6)
    ));
    md.code(&format!(
        "{}{}{}{}",
        matrix_text("A", &e.a),
        matrix_text("B", &e.b),
        matrix_text("C", &e.c),
        matrix_text("D", &e.d)
    ));
    let mut worst: f64 = 0.0;
    let mut rows = Vec::new();
    for c in &e.channels {
        for w in [0.1, 7.0, 39.0, 45.0, 300.0] {
            let s = Complex64::new(0.0, w);
            let want = g.channel_closed_form(c.input, c.output, s);
            // relative to the channel, or to the gimbal channel's size where the closed form
            // is 0 (the linearisation at θ₂ = π/2 carries cos(π/2) = 6e-17, not 0)
            let scale = want.norm().max(g.channel_closed_form(0, 0, s).norm());
            worst = worst.max((c.g.eval(s) - want).norm() / scale);
        }
        let zero = c.reduced.num().coeffs().iter().all(|v| *v == 0.0);
        rows.push(vec![
            format!("{} → {}", c.input_name, c.output_name),
            if zero {
                "0".into()
            } else {
                c.reduced.to_string()
            },
        ]);
    }
    md.table(&["channel", "G(s) (common factors cancelled)"], &rows);
    md.p(&format!(
        "In closed form G₁₁ = G₂₂ = 1/(Il(s² + ν²)), G₂₁ = −G₁₂ = −ν/(Il s(s² + ν²)), and u₃ \
         reaches neither gimbal at θ₂ = π/2: the gyroscopic coupling turns a torque about one \
         gimbal axis into motion about the other. Each channel agrees with it to {} on the \
         imaginary axis.",
        fmt_sig(worst, 2)
    ));
    // The Euler-angle model against the seed's own disc-frame form (1.103–1.106).
    let (t1, t2, d1, d2, w3, th3): (f64, f64, f64, f64, f64, f64) =
        (0.3, 1.1, 0.7, -0.2, 20.0, 0.4);
    let o1 = d1 * t2.sin() * th3.sin() + d2 * th3.cos();
    let o2 = d1 * t2.sin() * th3.cos() - d2 * th3.sin();
    let u = InputSignal::constant(vec![0.3, -0.1, 0.05]);
    let t = sample_times(3.0, 601)?;
    let a = simulate(&g, &[t1, t2, d1, d2, w3], &u, &t, &tight())?;
    let b = simulate(
        &GyroscopeDiscFrame(g),
        &[t1, t2, th3, o1, o2, w3],
        &u,
        &t,
        &tight(),
    )?;
    let diff = a
        .outputs
        .iter()
        .zip(&b.outputs)
        .flat_map(|(p, q)| p.iter().zip(q).map(|(x, y)| (x - y).abs()))
        .fold(0.0, f64::max);
    claims(ctx, md, &g, diff)
}

/// Exercise 2.14: no torque, no motion of the spin axis; a torque about the outer gimbal axis
/// moves the inner gimbal.
fn claims(ctx: &mut Ctx, md: &mut Md, g: &Gyroscope, cross: f64) -> Result<()> {
    let nu = g.nutation_frequency();
    let x0 = [0.3, 1.1, 0.0, 0.0, g.w];
    let t = sample_times(5.0, 501)?;
    let free = simulate(g, &x0, &InputSignal::constant(vec![0.0; 3]), &t, &tight())?;
    let still = free
        .states
        .iter()
        .map(|x| (x[0] - x0[0]).abs().max((x[1] - x0[1]).abs()))
        .fold(0.0, f64::max);
    let u1 = 1.0;
    let t = sample_times(1.0, 2001)?;
    let spin = g.steady_spin();
    let forced = simulate(
        g,
        &spin,
        &InputSignal::constant(vec![u1, 0.0, 0.0]),
        &t,
        &tight(),
    )?;
    // The linearisation's step response (the model's closed form).
    let lin = |t: f64| g.outer_torque_response(u1, t);
    let end = forced.t.len() - 1;
    let drift2 = forced.states[end][1] - spin[1];
    let rel = (drift2 - lin(1.0)[1]).abs() / lin(1.0)[1].abs();
    ctx.checks.add(
        "gyroscope: exercise 2.14 (2) inner-gimbal motion under u₁ vs the linearisation (relative)",
        "u₁ = 1 N·m for 1 s from steady spin",
        rel,
        1e-2,
    );
    md.p(&format!(
        "**Exercise 2.14.** (1) Started spinning only about the spin axis (θ̇₁ = θ̇₂ = 0) and \
         left without torque, the gimbal angles stay at their initial values (moved by {} rad \
         over 5 s): the spin axis keeps its direction. (2) A constant torque u₁ = {u1} N·m about \
         the *outer* gimbal axis turns the *inner* gimbal: θ₂ moves at the mean rate \
         −u₁/(Iz ω) = {} rad/s (precession), with nutation loops of size u₁/(Il ν²) = {} rad, \
         while θ₁ only nutates — the step response of G₂₁ and G₁₁. After 1 s θ₂ has moved \
         {} rad, the linearisation says {} rad (relative difference {}: the second-order \
         terms). The Euler-angle model agrees with the seed's disc-frame form to {} rad.",
        fmt_sig(still, 2),
        fmt_sig(g.precession_rate(u1), 6),
        fmt_sig(u1 / (g.i1 * nu * nu), 4),
        fmt_sig(drift2, 8),
        fmt_sig(lin(1.0)[1], 8),
        fmt_sig(rel, 2),
        fmt_sig(cross, 2)
    ));
    let path: Vec<(f64, f64)> = forced
        .states
        .iter()
        .map(|x| (1e3 * (x[1] - spin[1]), 1e3 * x[0]))
        .collect();
    let linear: Vec<(f64, f64)> = forced
        .t
        .iter()
        .map(|&t| {
            let [d1, d2] = lin(t);
            (1e3 * d2, 1e3 * d1)
        })
        .collect();
    let png = "gyroscope-precession.png";
    xy_png(
        ctx.figure(png),
        &XyPlot {
            curves: vec![
                Curve::new(path)
                    .label("simulated gimbal angles")
                    .color(series_color(0)),
                Curve::new(linear)
                    .label("linearisation (step response of G_{21}, G_{11})")
                    .style(LineStyle::Dashed)
                    .color(series_color(1)),
            ],
            y_range: Some((-0.1, 3.4)),
            x_label: "inner gimbal θ_{2} − π/2 (mrad)".into(),
            y_label: "outer gimbal θ_{1} (mrad)".into(),
            notes: vec![format!("u_{{1}} = {u1} N·m from t = 0 to 1 s")],
            ..Default::default()
        },
        &fig("Gyroscope: a torque about the outer gimbal axis turns the inner gimbal"),
    )?;
    md.image("Gyroscope precession under an outer-gimbal torque", png);
    Ok(())
}
