//! The mechanical systems of seed chapters 1–2: the free rigid body, the heavy top, the gimbal
//! gyroscope and the double pendulum, each compared with its closed forms.

mod double;
mod gyro;
mod rigid;
mod top;

use anyhow::Result;
use num_complex::Complex64;

use super::context::Ctx;
use super::md::Md;
use crate::cli::text::vector_text;
use crate::nonlinear::{Linearization, LocalStability};
use crate::numeric::rk45::Rk45Options;

/// The four sections, numbered `number`.1 … `number`.4 under one heading.
pub fn sections(ctx: &mut Ctx, md: &mut Md, number: usize) -> Result<()> {
    md.h2(&format!("{number}. Mechanical systems (seed chapters 1–2)"));
    md.p(
        "The free rigid body, the heavy top, the gimbal gyroscope and the double pendulum, \
         with exact (AD) linearisations. Where the eigenvalues sit on the imaginary axis the \
         linearisation cannot decide (seed §2.3); the energy–Casimir test does: an \
         equilibrium that is a strict extremum of the energy on the level set of the other \
         conserved quantities is Lyapunov stable. Simulations at rtol 10⁻¹² are compared \
         with the closed forms and report the drift of every conserved quantity.",
    );
    ctx.progress("rigid body");
    rigid::section(ctx, md)?;
    ctx.progress("heavy top");
    top::section(ctx, md)?;
    ctx.progress("gyroscope");
    gyro::section(ctx, md)?;
    ctx.progress("double pendulum");
    double::section(ctx, md)?;
    Ok(())
}

/// Integration tolerances of the section's simulations.
fn tight() -> Rk45Options {
    Rk45Options {
        rtol: 1e-12,
        atol: 1e-14,
        ..Default::default()
    }
}

/// Eigenvalues for a table (one per conjugate pair, rounding noise shown as 0).
fn eigen_text(e: &[Complex64]) -> String {
    crate::cli::linearize::eigenvalues_text(e, 5)
}

fn linear_words(s: LocalStability) -> &'static str {
    match s {
        LocalStability::AsymptoticallyStable => "asymptotically stable",
        LocalStability::Unstable => "unstable",
        LocalStability::Undetermined => "undetermined (centre)",
    }
}

/// Equilibria with the linear verdict and the energy–Casimir verdict.
fn verdict_table(md: &mut Md, lin: &Linearization, first: &str, names: &[String]) {
    let rows: Vec<Vec<String>> = lin
        .equilibria
        .iter()
        .enumerate()
        .map(|(k, e)| {
            vec![
                names.get(k).cloned().unwrap_or_default(),
                vector_text(&e.x),
                eigen_text(&e.eigenvalues),
                linear_words(e.stability).to_string(),
                e.energy_casimir
                    .as_ref()
                    .map(|c| {
                        format!(
                            "{} ⇒ {}",
                            serde_json::to_value(c.extremum)
                                .ok()
                                .and_then(|v| v.as_str().map(|s| s.replace('_', " ")))
                                .unwrap_or_default(),
                            if c.lyapunov_stable {
                                "Lyapunov stable"
                            } else {
                                "not shown stable"
                            }
                        )
                    })
                    .unwrap_or_else(|| "–".into()),
            ]
        })
        .collect();
    md.table(
        &[
            first,
            "x̄",
            "eigenvalues of A",
            "linearisation",
            "energy–Casimir",
        ],
        &rows,
    );
}

/// Largest distance from each wanted eigenvalue to the nearest computed one, relative to the
/// largest |wanted| (1 when there is none).
fn eig_error(got: &[Complex64], want: &[Complex64]) -> f64 {
    let scale = want
        .iter()
        .map(|z| z.norm())
        .fold(0.0, f64::max)
        .max(1e-300);
    want.iter()
        .map(|w| {
            got.iter()
                .map(|g| (g - w).norm())
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
        / scale
}
