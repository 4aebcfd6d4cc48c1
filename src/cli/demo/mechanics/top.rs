//! The axi-symmetric heavy top (seed eqs. 1.101–1.102): the sleeping top, its threshold spin
//! from the eigenvalues and from the energy–Casimir test, nutation below and above it.

use anyhow::Result;

use super::super::context::{Ctx, fig};
use super::super::md::Md;
use super::{eigen_text, linear_words, tight};
use crate::fmt::fmt_sig;
use crate::nonlinear::models::HeavyTop;
use crate::nonlinear::models::heavy_top::{
    threshold_from_eigenvalues, threshold_from_energy_casimir,
};
use crate::nonlinear::{EquilibriumSearch, InputSignal, linearize, sample_times, simulate};
use crate::plot::{Curve, series_color, time_plot_png};

pub fn section(ctx: &mut Ctx, md: &mut Md) -> Result<()> {
    let base = HeavyTop::default();
    let wc = base.threshold_spin();
    md.h3("Axi-symmetric heavy top (seed eqs. 1.101–1.102)");
    md.p(&format!(
        "Γ̇ = Γ × Ω, I Ω̇ = IΩ × Ω + m g l Γ × e₃ with Γ the upward vertical in the body frame, \
         I = diag(I1, I1, I3); I1 = {} kg·m², I3 = {} kg·m², m = {} kg, g = {} m/s², l = {} m. \
         Conserved (seed 2.65–2.67): E = ½Ω·IΩ + m g l Γ₃, Π·Γ, |Γ|² and, for the axi-symmetric \
         top, Π₃. The **sleeping top** Γ = e₃, Ω = ω₃e₃ is an equilibrium for every spin; \
         linearised, its transverse motion e^(iσt) solves \
         I1σ² + (2I1 − I3)ω₃σ + (I1 − I3)ω₃² + m g l = 0, whose discriminant \
         I3²ω₃² − 4 I1 m g l gives the classical threshold ω₃ = √(4 I1 m g l)/I3 = {} rad/s: \
         below it a real part ±√(4I1mgl − I3²ω₃²)/(2I1), above it a centre.",
        base.i1,
        base.i3,
        base.m,
        base.g,
        base.l,
        fmt_sig(wc, 10)
    ));
    let mut rows = Vec::new();
    for factor in [0.5, 0.95, 1.05, 2.0] {
        let top = base.with_spin(factor * wc)?;
        let lin = linearize(&top, None, &EquilibriumSearch::default())?;
        for e in &lin.equilibria {
            let upright = e.x[2] > 0.0;
            rows.push(vec![
                format!(
                    "{} ω₃ = {} ω_c",
                    if upright { "sleeping," } else { "hanging," },
                    factor
                ),
                eigen_text(&e.eigenvalues),
                linear_words(e.stability).to_string(),
                e.energy_casimir
                    .as_ref()
                    .map(|c| {
                        if c.lyapunov_stable {
                            "Lyapunov stable".to_string()
                        } else {
                            "not shown stable".to_string()
                        }
                    })
                    .unwrap_or_default(),
            ]);
        }
    }
    md.table(
        &[
            "equilibrium",
            "eigenvalues of A",
            "linearisation",
            "energy–Casimir",
        ],
        &rows,
    );
    let from_eig = threshold_from_eigenvalues(&base)?;
    let from_ec = threshold_from_energy_casimir(&base)?;
    ctx.checks.add(
        "heavy top: threshold spin from the energy–Casimir test vs √(4 I1 m g l)/I3 (relative)",
        "default top",
        (from_ec - wc).abs() / wc,
        1e-7,
    );
    md.p(&format!(
        "Found by bisection on the eigenvalues (the spin where the last right-half-plane \
         eigenvalue reaches the axis): ω₃ = {} rad/s; by bisection on the energy–Casimir \
         verdict (the spin from which a definite combination of E, Π·Γ, |Γ|² and Π₃ exists — \
         Π·Γ, |Γ|² and Π₃ have dependent gradients at the sleeping top, so one multiplier is \
         free and is optimised): ω₃ = {} rad/s. Formula: {} rad/s. Above the threshold the \
         fast top is not only spectrally stable but Lyapunov stable.",
        fmt_sig(from_eig, 12),
        fmt_sig(from_ec, 12),
        fmt_sig(wc, 12)
    ));
    nutation(ctx, md, &base)
}

/// Released 0.1 rad from upright below and above the threshold: tilt and drifts.
fn nutation(ctx: &mut Ctx, md: &mut Md, base: &HeavyTop) -> Result<()> {
    let wc = base.threshold_spin();
    let t = sample_times(10.0, 2001)?;
    let mut curves = Vec::new();
    let mut notes = Vec::new();
    for (k, factor) in [0.9, 1.1, 2.0].into_iter().enumerate() {
        let top = base.with_spin(factor * wc)?;
        let x0 = crate::nonlinear::SystemInfo::default_initial_state(&top);
        let sim = simulate(&top, &x0, &InputSignal::none(), &t, &tight())?;
        let tilt: Vec<f64> = sim
            .states
            .iter()
            .map(|x| x[2].clamp(-1.0, 1.0).acos().to_degrees())
            .collect();
        let drift = sim
            .conserved
            .iter()
            .map(|c| c.relative_drift)
            .fold(0.0, f64::max);
        ctx.checks.add(
            "heavy top: drift of E, Π·Γ, |Γ|², Π₃ over 10 s (relative)",
            format!("ω₃ = {factor} ω_c, tilted 0.1 rad"),
            drift,
            1e-10,
        );
        let max_tilt = tilt.iter().copied().fold(0.0, f64::max);
        notes.push(format!(
            "ω₃ = {factor} ω_c: the tilt stays within {}° (drift of the conserved quantities {})",
            fmt_sig(max_tilt, 4),
            fmt_sig(drift, 2)
        ));
        curves.push(
            Curve::from_xy(&sim.t, &tilt)?
                .label(format!("ω_{{3}} = {factor} ω_{{c}}"))
                .color(series_color(k)),
        );
    }
    let png = "heavy-top-nutation.png";
    time_plot_png(
        ctx.figure(png),
        &curves,
        "tilt of the symmetry axis (deg)",
        &fig("Heavy top released 0.1 rad from upright: nutation below and above the threshold"),
    )?;
    md.bullets(&notes);
    md.image("Heavy top nutation", png);
    Ok(())
}
