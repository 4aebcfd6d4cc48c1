//! Root loci of the quarter-car suspension G = 1/(250 s² + 1000 s + 16000): with a
//! proportional gain (two branches on the vertical line Re s = −2) and with a PI controller
//! C = K·(s + 8)/s (stable for 0 < K < 16000, crossing at ±j·8√2), checked against the closed
//! forms and the Routh stable-gain set.

use anyhow::Result;
use num_complex::Complex64;

use super::context::Ctx;
use super::md::Md;
use crate::analysis::rlocus::{RootLocus, RootLocusOptions};
use crate::analysis::stable_gains;
use crate::fmt::fmt_sig;
use crate::plot::{RootLocusPlot, rlocus_png};
use crate::poly::Poly;

const GROUP: &str = "root locus vs closed forms";

pub fn section(ctx: &mut Ctx, md: &mut Md) -> Result<()> {
    md.h3("Root locus of the quarter-car suspension");
    md.p(
        "The closed-loop poles of 1 + K·L(s) as the gain K runs from 0 to ∞ \
         (`ltikit rlocus --plant data/plants/suspension.toml -o rlocus.png`): asymptotes, \
         break points (real roots of N·D′ − N′·D), imaginary-axis crossings (real roots of \
         Im D(jω)·conj N(jω)), departure angles — each from a polynomial, not read off the \
         traced branches.",
    );
    proportional(ctx, md)?;
    pi(ctx, md)
}

fn den() -> Result<Poly> {
    Ok(Poly::from_descending(&[250.0, 1000.0, 16000.0])?)
}

/// Max over the traced points of |Re s + 2| relative to |s|.
fn off_line(l: &RootLocus) -> f64 {
    l.branches
        .paths
        .iter()
        .flatten()
        .map(|z| (z.re + 2.0).abs() / z.norm().max(1.0))
        .fold(0.0, f64::max)
}

fn proportional(ctx: &mut Ctx, md: &mut Md) -> Result<()> {
    let (n, d) = (Poly::constant(1.0), den()?);
    let l = crate::analysis::rlocus::root_locus(&n, &d, &RootLocusOptions::default())?;
    let file = "suspension-rlocus-p.png";
    rlocus_png(
        ctx.figure(file),
        &RootLocusPlot {
            locus: &l,
            label: Some("K/(250 s² + 1000 s + 16000)"),
            marked: Some((16000.0, &(&d + &n.scale(16000.0)).roots()?)),
        },
        &super::context::fig("Suspension with a proportional gain K: root locus"),
    )?;
    md.p(
        "Proportional gain: 250 s² + 1000 s + 16000 + K has the roots −2 ± j·√(60 + K/250) — \
         the branches leave the poles −2 ± j√60 vertically and stay on Re s = −2; gain adds \
         stiffness, not damping (ζ = 2/√(64 + K/250) falls). At K = 16000 (marked) the poles \
         are −2 ± j√124.",
    );
    md.image(
        "Root locus of the suspension with a proportional gain",
        file,
    );
    let a = l.asymptotes.as_ref();
    let err = a.map_or(f64::INFINITY, |a| {
        (a.centroid + 2.0)
            .abs()
            .max((a.angles_deg[0] + 90.0).abs())
            .max((a.angles_deg[1] - 90.0).abs())
    });
    ctx.checks.add(
        GROUP,
        "suspension, K: asymptotes from σ = −2 at ±90° (closed form)",
        err,
        1e-13,
    );
    ctx.checks.add(
        GROUP,
        "suspension, K: every traced point on Re s = −2 (relative)",
        off_line(&l),
        1e-12,
    );
    let dep = l
        .departures
        .first()
        .map_or(f64::INFINITY, |x| (x.angles_deg[0] - 90.0).abs());
    ctx.checks.add(
        GROUP,
        "suspension, K: departure angle 90° from −2 + j√60",
        dep,
        1e-10,
    );
    Ok(())
}

fn pi(ctx: &mut Ctx, md: &mut Md) -> Result<()> {
    // L = K·(s + 8)/(s·(250 s² + 1000 s + 16000))
    let n = Poly::from_descending(&[1.0, 8.0])?;
    let d = &den()? * &Poly::s();
    let l = crate::analysis::rlocus::root_locus(&n, &d, &RootLocusOptions::default())?;
    let file = "suspension-rlocus-pi.png";
    let k_mark = 4000.0;
    let marked = (&d + &n.scale(k_mark)).roots()?;
    rlocus_png(
        ctx.figure(file),
        &RootLocusPlot {
            locus: &l,
            label: Some("K·(s + 8)/(s (250 s² + 1000 s + 16000))"),
            marked: Some((k_mark, &marked)),
        },
        &super::context::fig("Suspension with PI control K·(s + 8)/s: root locus"),
    )?;
    let cross = l.crossings.first();
    let stable = stable_gains(&n, &d)?;
    md.p(&format!(
        "PI control C = K·(s + 8)/s (`--controller pi:kp=1,ki=8`, gain K): by Routh, \
         250 s³ + 1000 s² + (16000 + K) s + 8K is stable iff 1000·(16000 + K) > 250·8K, i.e. \
         0 < K < 16000, where s² = −(16000 + K)/250 = −128: the crossing ±j·8√2. ltikit: \
         asymptotes from σ = {} at ±90° (the integrator pulls the centroid (−4 + 8)/2 = 2 into \
         the right half plane), crossing ±{}j at K = {}, stable for {}.",
        l.asymptotes
            .as_ref()
            .map_or("—".into(), |a| fmt_sig(a.centroid, 6)),
        cross.map_or("—".into(), |c| fmt_sig(c.omega, 10)),
        cross.map_or("—".into(), |c| fmt_sig(c.gain, 10)),
        stable
            .iter()
            .map(|(a, b)| format!("{} < K < {}", fmt_sig(*a, 10), fmt_sig(*b, 10)))
            .collect::<Vec<_>>()
            .join(", ")
    ));
    md.image("Root locus of the suspension with PI control", file);
    let want_w = 8.0 * 2f64.sqrt();
    let err = cross.map_or(f64::INFINITY, |c| {
        ((c.omega - want_w) / want_w)
            .abs()
            .max(((c.gain - 16000.0) / 16000.0).abs())
    });
    ctx.checks.add(
        GROUP,
        "suspension, PI: crossing ω = 8√2 at K = 16000 (Routh by hand), relative",
        err,
        1e-10,
    );
    let err = match stable.as_slice() {
        [(lo, hi)] => lo.abs().max(((hi - 16000.0) / 16000.0).abs()),
        _ => f64::INFINITY,
    };
    ctx.checks.add(
        GROUP,
        "suspension, PI: stable-gain set 0 < K < 16000 (Routh), relative",
        err,
        1e-10,
    );
    // at the crossing gain the closed loop has roots ±j·8√2 (root finder, independent)
    let q = &d + &n.scale(16000.0);
    let r = q.roots()?;
    let err = r
        .iter()
        .map(|x| (x.value - Complex64::new(0.0, want_w)).norm() / want_w)
        .fold(f64::INFINITY, f64::min);
    ctx.checks.add(
        GROUP,
        "suspension, PI: a closed-loop root at j·8√2 for K = 16000",
        err,
        1e-12,
    );
    Ok(())
}
