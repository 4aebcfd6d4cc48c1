//! The lattice's force → displacement channels in the demo: the 256-state channel through the
//! state-space layer against the closed-form modal sum, and a damped, non-collocated channel
//! whose zeros are known in closed form (Rayleigh damping).

use anyhow::Result;
use num_complex::Complex64;

use super::context::Ctx;
use super::md::Md;
use crate::StateSpace;
use crate::fmt::fmt_sig;
use crate::lti::lattice::{Boundary, Lattice, Output};

/// The force → displacement channel through the state-space layer: the factored form from
/// the eigenvalues of A, the transmission zeros and the minimal realisation (no coefficients),
/// checked against the closed-form modal sum G(s) = Σ wₖ/(s² + cₖs + ωₖ²); the whole-model
/// eigen-structure (degenerate pairs semisimple, the rigid mode a Jordan block); its Bode plot.
pub(super) fn channel_analysis(
    ctx: &mut Ctx,
    md: &mut Md,
    lat: &Lattice,
    ss: &StateSpace,
) -> Result<()> {
    md.h3("The force → displacement channel");
    let Output::Particle(out) = lat.output() else {
        return Ok(());
    };
    let sum = lat.modal_sum(out, lat.input())?;
    let f = crate::analysis::Factored::from_state_space(ss)?;
    let whole = ss.analysis()?;
    let order = |r: &[crate::poly::Root]| r.iter().map(|r| r.multiplicity).sum::<usize>();
    let minimal = order(f.reduced_poles());
    let semisimple_pairs = whole
        .eigenvalues
        .iter()
        .filter(|e| e.algebraic == 2 && e.semisimple && e.value.norm() > 0.0)
        .count();
    let jordan: Vec<String> = whole
        .eigenvalues
        .iter()
        .filter(|e| !e.semisimple)
        .map(|e| {
            format!(
                "{} (algebraic {}, geometric {})",
                crate::fmt::fmt_root(e.value, 6),
                e.algebraic,
                e.geometric
            )
        })
        .collect();
    md.p(&format!(
        "Force on particle {} → displacement of particle {out}, {} states, analysed without \
         coefficients (`Factored::from_state_space`: A is recognised as second order, [[0, I], \
         [−G, −E]] with G symmetric, and the modes come from the symmetric eigenproblem of G — \
         half the order; the minimal realisation is formed in modal coordinates and the zeros \
         through w = s², from the channel of G itself). In closed form G(s) = Σₖ wₖ/(s² + cₖ s + \
         ωₖ²) over the {} distinct frequencies; the sine partner of every degenerate pair has a \
         node at the driven particle (it can be neither excited nor seen), so the minimal \
         realisation has order {} — found: {minimal}. The eigenvalues of A: {} degenerate \
         values ±jωₖ of multiplicity 2, all semisimple (two independent mode shapes each); not \
         semisimple: {} — the rigid translation p = 0, a Jordan block at 0 (q = c₁ + c₂t), so \
         the lattice is not internally stable and the channel has a double pole at 0.",
        lat.input(),
        ss.order(),
        sum.omega.len(),
        sum.minimal_order(),
        semisimple_pairs,
        if jordan.is_empty() {
            "none".to_string()
        } else {
            jordan.join(", ")
        },
    ));
    ctx.checks.add(
        "lattice channel: minimal order from the state-space layer vs the modal sum (difference)",
        format!("{}, particle {} → {out}", lat.describe(), lat.input()),
        (minimal as f64 - sum.minimal_order() as f64).abs(),
        0.0,
    );
    // Every closed-form pole of the reduced G among the reduced poles (relative to ω0).
    let found: Vec<Complex64> = f.reduced_poles().iter().map(|r| r.value).collect();
    let pole_err = sum
        .poles()
        .iter()
        .map(|p| {
            found
                .iter()
                .map(|q| (p - q).norm())
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
        / lat.w0();
    ctx.checks.add(
        "lattice channel: reduced poles vs the closed form ±jωₖ of the visible modes (relative to ω0)",
        format!("{}, particle {} → {out}", lat.describe(), lat.input()),
        pole_err,
        1e-12,
    );
    let mut err = 0.0f64;
    for w in [0.1, 0.77, 1.3, 2.5] {
        let s = Complex64::new(0.0, w);
        let exact = sum.eval(s);
        err = err.max((f.eval(s) - exact).norm() / exact.norm());
    }
    ctx.checks.add(
        "lattice channel G(jω) from the state-space layer vs the closed-form modal sum (relative)",
        format!(
            "{}, particle {} → {out}, 4 frequencies",
            lat.describe(),
            lat.input()
        ),
        err,
        1e-10,
    );
    let name = "lattice-channel-bode.png";
    let opts = crate::plot::PlotOptions {
        title: Some(format!(
            "Lattice (N = {}): force on particle {} → displacement of particle {out}",
            lat.n(),
            lat.input()
        )),
        ..Default::default()
    };
    crate::cli::plots::bode_figure(
        &ctx.figure(name),
        &[(format!("{} states", ss.order()), f)],
        Some((0.01, 10.0)),
        false,
        false,
        &opts,
    )?;
    md.image("Bode diagram of the lattice channel", name);
    Ok(())
}

/// A damped, non-collocated channel: Rayleigh damping (γ to the ground, η in the springs)
/// makes every mode's factor s² + (γ + ηλ)s + λ = (1 + ηs)(w + λ) with w = (s² + γs)/(1 + ηs),
/// so G(s) = H(w)/(1 + ηs) — the zeros in closed form and an exact multiple zero at −1/η, which
/// the pencil of the same model with its states interleaved (no visible structure) cannot
/// resolve.
pub(super) fn damped_channel(ctx: &mut Ctx, md: &mut Md) -> Result<()> {
    let (n, i, j, gamma, eta) = (64usize, 10usize, 20usize, 0.02, 0.01);
    let lat = Lattice::new(n, Boundary::Fixed, 1.0)?
        .with_damping(gamma, eta)?
        .with_input(i)?
        .with_output(Output::Particle(j))?;
    let ss = lat.state_space()?;
    let f = crate::analysis::Factored::from_state_space(&ss)?;
    // the closed form of the model (its derivation: lti::lattice::closed_form), checked
    // against this channel's factored form in tests/ss_second_order.rs
    let cf = lat.channel_zeros_closed_form()?;
    let (rho, extra) = (cf.w_relative_degree, cf.eta_zero_multiplicity);
    let multiple = f
        .reduced_zeros()
        .iter()
        .find(|z| (z.value.re + 1.0 / eta).abs() < 1e-9 / eta)
        .map_or(0, |z| z.multiplicity);
    // the same model with its states interleaved: the general path (Schur form, staircases,
    // the pencil of the whole model)
    let m = ss.order();
    let old = |k: usize| if k % 2 == 0 { k / 2 } else { n + k / 2 };
    let mixed = StateSpace::new(
        nalgebra::DMatrix::from_fn(m, m, |r, c| ss.a[(old(r), old(c))]),
        nalgebra::DMatrix::from_fn(m, 1, |r, _| ss.b[(old(r), 0)]),
        nalgebra::DMatrix::from_fn(1, m, |_, c| ss.c[(0, old(c))]),
        ss.d.clone(),
    )?;
    let g = crate::analysis::Factored::from_state_space(&mixed)?;
    let count = |r: &[crate::poly::Root]| r.iter().map(|x| x.multiplicity).sum::<usize>();
    let far = g
        .reduced_zeros()
        .iter()
        .map(|z| z.value.norm())
        .fold(0.0, f64::max);
    md.p(&format!(
        "Damped and not collocated: fixed ends, N = {n}, γ = {gamma} to the ground and η = \
         {eta} in the springs (Rayleigh damping: cₖ = γ + ηωₖ²), force on particle {i}, \
         displacement of particle {j}. Every mode's factor is s² + cₖs + ωₖ² = (1 + ηs)(w + \
         ωₖ²) with w = (s² + γs)/(1 + ηs), so G(s) = H(w)/(1 + ηs) where H(w) = e_{j}ᵀ(wI + \
         K)⁻¹e_{i} is the undamped channel with s² replaced by w. H's zeros are known in closed \
         form (the cofactor of the tridiagonal wI + K: −4 sin²(πl/{}) and −4 sin²(πl/{}), {} of \
         them after the values shared with a mode cancel) and its relative degree is ρ = {rho}; \
         so G has two zeros per zero of H, a zero of multiplicity ρ − 1 = {extra} exactly at \
         −1/η = {}, relative degree {} and gain η^{extra} = {}. Found: relative degree {}, \
         {} zeros, the zero at {} with multiplicity {multiple}, gain {}. The same model with \
         its states interleaved (q₁, q̇₁, q₂, …: the structure is no longer visible) goes the \
         general way — the pencil of the {m}-state model, whose first non-zero Markov \
         parameter is {} of the scale — and finds relative degree {} and {} zeros reaching \
         |s| = {}: its high-frequency asymptote would be off by {} dB/decade. Beyond the band \
         edge ω = 2 the channel is evanescent and falls by 20·12 = 240 dB/decade from the \
         corner at 1/η on.",
        2 * i,
        2 * (n - j + 1),
        cf.w_zeros.len(),
        fmt_sig(-1.0 / eta, 6),
        cf.relative_degree,
        fmt_sig(cf.gain, 3),
        f.relative_degree().unwrap_or(0),
        count(f.reduced_zeros()),
        fmt_sig(-1.0 / eta, 6),
        fmt_sig(f.gain(), 6),
        fmt_sig(cf.gain, 3),
        g.relative_degree().unwrap_or(0),
        count(g.reduced_zeros()),
        fmt_sig(far, 3),
        20 * (g.relative_degree().unwrap_or(0) - f.relative_degree().unwrap_or(0)),
    ));
    let name = "lattice-damped-channel-bode.png";
    let opts = crate::plot::PlotOptions {
        title: Some(format!(
            "Damped lattice (N = {n}, γ = {gamma}, η = {eta}): force on {i} → displacement of {j}"
        )),
        ..Default::default()
    };
    crate::cli::plots::bode_figure(
        &ctx.figure(name),
        &[("128 states, factored".to_string(), f)],
        Some((0.01, 1000.0)),
        false,
        false,
        &opts,
    )?;
    md.image("Bode diagram of the damped channel", name);
    Ok(())
}
