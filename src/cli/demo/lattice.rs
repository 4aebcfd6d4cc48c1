//! The seed's linear lattice (§2.4): dispersion and modes (fig. 2.16), zone-edge and
//! zone-centre phonon packets simulated exactly (figs. 2.17–2.18), and the force →
//! displacement channels ([`super::lattice_channel`]).

use anyhow::Result;
use std::f64::consts::PI;
use std::time::Instant;

use super::context::{Ctx, fig};
use super::md::Md;
use crate::fmt::fmt_sig;
use crate::lti::lattice::{Boundary, Envelope, Lattice, Modes, Output, Packet, Trajectory};
use crate::plot::{
    ColorMap, Curve, HeatMap, LineStyle, Marker, MarkerShape, XyPlot, heatmap_png, series_color,
    xy_png,
};

/// Particles of the seed's simulation.
const N: usize = 128;
/// The perturbed middle block.
const WIDTH: usize = 16;
/// Simulated time span (s, with ω0 = 1 rad/s) and its sample spacing.
const T_END: f64 = 100.0;
const DT: f64 = 0.05;

/// The lattice section.
pub fn section(ctx: &mut Ctx, md: &mut Md, index: usize) -> Result<()> {
    md.h2(&format!("{index}. The linear lattice (seed §2.4)"));
    md.p(&format!(
        "N = {N} particles of mass m joined by springs φ(r) = αβr²/2: q̈ₙ = ω0²(qₙ₊₁ − 2qₙ + \
         qₙ₋₁), ω0² = αβ/m (eq. 2.69), or q̈ = Ωq (2.75), with ω0 = 1 rad/s and lattice spacing \
         a = 1. As a model (`ltikit::lti::lattice::Lattice`) it has 2N = {} states x = [q; q̇], \
         the force on one particle as input and the displacement of one particle (or of all) \
         as output; optional damping γq̇ to the ground and ηΩq̇ in the springs keeps the modes \
         uncoupled. Periodic: the ring of eq. 2.69. Fixed: N moving particles between walls \
         q₀ = q_(N+1) = 0 (the seed's fixed lattice of N + 1 sites has N − 1 moving ones).",
        2 * N
    ));
    let periodic = Lattice::new(N, Boundary::Periodic, 1.0)?;
    let modes = modes_part(ctx, md, &periodic)?;
    packets_part(ctx, md, &periodic, &modes)?;
    damped_part(ctx, md)?;
    let channel = periodic
        .clone()
        .with_input(1)?
        .with_output(Output::Particle(1))?;
    let ss = channel.state_space()?;
    super::lattice_channel::channel_analysis(ctx, md, &channel, &ss)?;
    super::lattice_channel::damped_channel(ctx, md)?;
    Ok(())
}

/// Largest |a − b| over two lists.
fn worst(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Modes of both boundaries against the closed forms; the dispersion figure.
fn modes_part(ctx: &mut Ctx, md: &mut Md, periodic: &Lattice) -> Result<Modes> {
    md.h3("Dispersion and modes (§2.4.1.1–2.4.1.2)");
    md.p(
        "The modal matrix T comes from the symmetric eigenproblem of Ω (nalgebra's \
         `SymmetricEigen`), modes sorted by increasing ωₖ. The frequencies are taken as \
         ωₖ = ω0‖D tₖ‖ (D the bond-stretch matrix, Ω = −ω0²DᵀD): the square root of the \
         eigenvalue −λₖ(Ω) itself turns its rounding error of ~eps·‖Ω‖ into ~1e-8 for the rigid \
         mode ω = 0. Closed forms: ωₚ = 2ω0 sin(πp/N) for the periodic lattice (p = 0…N−1; \
         the pairs p, N − p are degenerate), ωₖ = 2ω0 sin(πk/(2(N + 1))), k = 1…N, for fixed \
         ends (qₙ = sin(πkn/(N + 1)) vanishes at both walls). The eigenvalues of A are ±jωₖ. \
         The wave number of each computed mode is read off its shape (the peak of its Fourier \
         or sine transform), so the markers of the figure test the dispersion law \
         ω(k) = 2ω0 sin(ka/2) (eq. 2.71) itself.",
    );
    let mut rows = Vec::new();
    let mut periodic_modes = None;
    for lat in [periodic.clone(), Lattice::new(N, Boundary::Fixed, 1.0)?] {
        let start = Instant::now();
        let modes = lat.modes()?;
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let exact = lat.frequencies_closed_form();
        let err = worst(&modes.omega, &exact) / lat.w0();
        let naive: Vec<f64> = modes.omega_sq.iter().map(|x| x.max(0.0).sqrt()).collect();
        let naive_err = worst(&naive, &exact) / lat.w0();
        let k_err = worst(&modes.wavenumber, &lat.wavenumbers_closed_form());
        let c = modes.diagonal_check(&lat)?;
        let name = lat.boundary().name();
        rows.push(vec![
            name.to_string(),
            fmt_sig(err, 2),
            fmt_sig(naive_err, 2),
            fmt_sig(k_err, 2),
            fmt_sig(c.off_diagonal, 2),
            fmt_sig(c.diagonal, 2),
            fmt_sig(c.orthogonality, 2),
            fmt_sig(ms, 3),
        ]);
        if lat.boundary() == Boundary::Periodic {
            periodic_modes = Some(modes);
        }
    }
    md.table(
        &[
            "boundary",
            "max \\|ωₖ − closed form\\|/ω0",
            "same with ω0√(−λₖ)",
            "max \\|kₖa − closed form\\|",
            "TᵀΩT off-diagonal",
            "TᵀΩT diagonal error",
            "‖TᵀT − I‖max",
            "eigensolver (ms)",
        ],
        &rows,
    );
    let modes = periodic_modes.ok_or_else(|| anyhow::anyhow!("no periodic modes"))?;
    dispersion_figure(ctx, md)?;
    Ok(modes)
}

/// Seed fig. 2.16 with computed eigenfrequencies as markers: N = 32 (at N = 128 the 256
/// markers would hide the curve), periodic and fixed ends, each at its shape's wave number.
fn dispersion_figure(ctx: &mut Ctx, md: &mut Md) -> Result<()> {
    const NF: usize = 32;
    let curve: Vec<(f64, f64)> = (0..=400)
        .map(|i| {
            let x = -1.0 + i as f64 / 200.0;
            (x, 2.0 * (0.5 * PI * x).sin().abs())
        })
        .collect();
    let sound: Vec<(f64, f64)> = [(-1.0, PI), (0.0, 0.0), (1.0, PI)].to_vec();
    let mut markers = Vec::new();
    for (b, shape, color) in [
        (Boundary::Periodic, MarkerShape::Circle, series_color(1)),
        (Boundary::Fixed, MarkerShape::Cross, series_color(2)),
    ] {
        let modes = Lattice::new(NF, b, 1.0)?.modes()?;
        for (w, k) in modes.omega.iter().zip(&modes.wavenumber) {
            for sign in [-1.0, 1.0] {
                markers.push(Marker::new((sign * k / PI, *w), shape).color(color));
            }
        }
    }
    let plot = XyPlot {
        curves: vec![
            Curve::new(curve)
                .label("ω(k) = 2ω_{0} sin(ka/2)  (2.71)")
                .color(series_color(0)),
            Curve::new(sound)
                .label("sound line ω = aω_{0}|k|")
                .style(LineStyle::Dashed)
                .color(series_color(7)),
        ],
        markers,
        x_label: "wave number ka/π (Brillouin zone −π/a ≤ k ≤ π/a)".into(),
        y_label: "frequency ω/ω_{0}".into(),
        x_range: Some((-1.0, 1.0)),
        y_range: Some((0.0, 2.25)),
        notes: vec![
            format!("○ computed ω_{{k}}, periodic, N = {NF}"),
            format!("× computed ω_{{k}}, fixed ends, N = {NF}"),
            "at the wave number of each mode's shape".into(),
        ],
        ..Default::default()
    };
    let file = "lattice-dispersion.png";
    xy_png(
        ctx.figure(file),
        &plot,
        &fig("Dispersion curve of the linear lattice (seed fig. 2.16)"),
    )?;
    md.image("Dispersion curve with the computed eigenfrequencies", file);
    Ok(())
}

/// Simulates one packet from rest.
fn run(lat: &Lattice, modes: &Modes, p: Packet, t: &[f64]) -> Result<Trajectory> {
    let q0 = p.displacements(lat)?;
    Ok(lat.simulate(modes, &q0, &vec![0.0; lat.n()], t)?)
}

/// Zone-edge and zone-centre packets: heat maps and the energy in the middle block.
fn packets_part(ctx: &mut Ctx, md: &mut Md, lat: &Lattice, modes: &Modes) -> Result<()> {
    md.h3("Zone-edge and zone-centre phonons (figs. 2.17–2.18)");
    md.p(&format!(
        "The seed perturbs the middle {WIDTH} of {N} particles without giving the shape. \
         Here the particles n = {}…{} are displaced and released from rest, \
         qₙ(0) = w(j)·cos(k₀a·j), j = n − {}, with a Hann envelope w(j) = sin²(π(j + 1)/{}) \
         and the carrier k₀a = π (zone edge, neighbours in antiphase, group velocity \
         aω0 cos(k₀a/2) = 0) or k₀a = 0 (zone centre, group velocity aω0). With a flat \
         (rectangular) envelope the zone-centre plateau has all its strain at its two ends and \
         an energy spectrum ω²|q̂|² = 4 sin²({WIDTH}ka/2) spread evenly over the whole zone; \
         its curves are shown dashed for comparison. Every mode is an exact oscillator: \
         z(t) in closed form, q = Tz; no time stepping. In the space–time pictures the dashed \
         lines are fronts leaving the block's edges at the speed of sound aω0 (wrapping \
         around the ring).",
        N / 2 - WIDTH / 2 + 1,
        N / 2 + WIDTH / 2,
        N / 2 - WIDTH / 2 + 1,
        WIDTH + 1
    ));
    let t: Vec<f64> = (0..=(T_END / DT).round() as usize)
        .map(|i| i as f64 * DT)
        .collect();
    let block = lat.middle(WIDTH)?;
    let cases = [
        ("zone edge, Hann", Packet::zone_edge(WIDTH)),
        ("zone centre, Hann", Packet::zone_centre(WIDTH)),
        (
            "zone edge, flat",
            Packet::zone_edge(WIDTH).with_envelope(Envelope::Rectangular),
        ),
        (
            "zone centre, flat",
            Packet::zone_centre(WIDTH).with_envelope(Envelope::Rectangular),
        ),
    ];
    let (mut curves, mut rows, mut timing) = (Vec::new(), Vec::new(), 0.0);
    for (i, (name, p)) in cases.iter().enumerate() {
        let start = Instant::now();
        let tr = run(lat, modes, *p, &t)?;
        timing = start.elapsed().as_secs_f64() * 1e3;
        let total = lat.total_energy(&tr);
        let mid = lat.block_energy(&tr, block.clone());
        let e0 = total[0];
        let at = |s: f64| fmt_sig(mid[((s / DT).round() as usize).min(mid.len() - 1)] / e0, 3);
        rows.push(vec![
            name.to_string(),
            fmt_sig(e0, 4),
            at(0.0),
            at(10.0),
            at(25.0),
            at(50.0),
            at(100.0),
        ]);
        let style = if i < 2 {
            LineStyle::Solid
        } else {
            LineStyle::Dashed
        };
        curves.push(
            Curve::new(t.iter().zip(&mid).map(|(t, e)| (*t, e / e0)))
                .label(*name)
                .style(style)
                .color(series_color(i % 2))
                .width(if i < 2 { 1.0 } else { 0.7 }),
        );
        if i < 2 {
            let slug = if i == 0 { "edge" } else { "centre" };
            let what = if i == 0 { "zone-edge" } else { "zone-centre" };
            heat_figure(ctx, md, &tr, what, slug)?;
        }
    }
    md.p(&format!(
        "The exact simulation of one packet ({N} particles, {} samples, modes and packet \
         given) took {} ms.",
        t.len(),
        fmt_sig(timing, 3)
    ));
    md.table(
        &[
            "packet",
            "H(0) (J/kg)",
            "E₁₆(0)/H",
            "t = 10 s",
            "t = 25 s",
            "t = 50 s",
            "t = 100 s",
        ],
        &rows,
    );
    let plot = XyPlot {
        curves,
        x_label: "time t (s)".into(),
        y_label: format!("energy in the middle {WIDTH} / total"),
        x_range: Some((0.0, T_END)),
        y_range: Some((0.0, 1.05)),
        ..Default::default()
    };
    let file = "lattice-energy.png";
    xy_png(
        ctx.figure(file),
        &plot,
        &fig(format!(
            "Energy in the middle {WIDTH} of {N} particles (seed fig. 2.18)"
        )),
    )?;
    md.image("Energy in the middle 16 particles against time", file);
    md.p(
        "The zone-edge packet's energy stays in the middle (its phonons have group velocities \
         near zero and leave only slowly), the zone-centre packet's leaves at the speed of \
         sound aω0 within about 20 s, as the seed describes. The flat zone-centre plateau \
         keeps a share of its energy behind: the zone-edge content of its two steps.",
    );
    Ok(())
}

/// The space–time picture qₙ(t) of one packet (seed fig. 2.17), with the sound cone.
fn heat_figure(ctx: &mut Ctx, md: &mut Md, tr: &Trajectory, name: &str, slug: &str) -> Result<()> {
    let (n, m) = (tr.q.nrows(), tr.t.len());
    let values: Vec<f64> = (0..m)
        .flat_map(|i| tr.q.column(i).iter().copied().collect::<Vec<_>>())
        .collect();
    let t_lo = tr.t.first().copied().unwrap_or(0.0) - 0.5 * DT;
    let t_hi = tr.t.last().copied().unwrap_or(T_END) + 0.5 * DT;
    let mut h = HeatMap::new(values, n, m, (0.5, n as f64 + 0.5), (t_lo, t_hi))?;
    h.colormap = ColorMap::Diverging;
    h.x_label = "particle n".into();
    h.y_label = "time t (s)".into();
    h.z_label = "displacement q_{n}(t) (m)".into();
    // Fronts travelling at the speed of sound from the block's edges, wrapping around the ring.
    let c = 0.5 * (n as f64 + 1.0);
    for (x0, dir) in [
        (c - 0.5 * WIDTH as f64, -1.0),
        (c + 0.5 * WIDTH as f64, 1.0),
    ] {
        let mut pts = Vec::new();
        for shift in [0.0, n as f64, -(n as f64)] {
            pts.push((x0 + shift, 0.0));
            pts.push((x0 + shift + dir * T_END, T_END));
            pts.push((f64::NAN, f64::NAN));
        }
        h.curves.push(
            Curve::new(pts)
                .style(LineStyle::Dashed)
                .color(crate::plot::Color(60, 60, 60))
                .width(0.6),
        );
    }
    let file = format!("lattice-{slug}.png");
    let opts = crate::plot::PlotOptions {
        size: (1000, 800),
        ..fig(format!(
            "{} packet in the middle {WIDTH} of {n} particles (seed fig. 2.17)",
            capitalise(name)
        ))
    };
    heatmap_png(ctx.figure(&file), &h, &opts)?;
    md.image(&format!("Space–time picture of the {name} packet"), &file);
    Ok(())
}

fn capitalise(s: &str) -> String {
    let mut c = s.chars();
    c.next()
        .map(|f| f.to_uppercase().chain(c).collect())
        .unwrap_or_default()
}

/// A damped fixed-end lattice: every modal energy decays (dHₖ/dt = −cₖżₖ² ≤ 0).
fn damped_part(ctx: &mut Ctx, md: &mut Md) -> Result<()> {
    let lat = Lattice::new(N, Boundary::Fixed, 1.0)?.with_damping(0.005, 0.01)?;
    let modes = lat.modes()?;
    let t: Vec<f64> = (0..=400).map(|i| i as f64 * 0.1).collect();
    let tr = run(&lat, &modes, Packet::zone_edge(WIDTH), &t)?;
    let h = tr.modal_energies(&modes);
    let e0: f64 = h.column(0).sum();
    let mut rise = 0.0f64;
    for k in 0..h.nrows() {
        for i in 1..h.ncols() {
            rise = rise.max(h[(k, i)] - h[(k, i - 1)]);
        }
    }
    ctx.checks.add(
        "lattice damped modal energies never increase (relative to H(0))",
        format!("{}, zone-edge packet", lat.describe()),
        rise.max(0.0) / e0,
        1e-13,
    );
    let last: f64 = h.column(h.ncols() - 1).sum();
    md.p(&format!(
        "Damped ({}): each mode is an exact damped oscillator with cₖ = γ + ηωₖ²; the \
         zone-edge packet keeps {} of its energy after 40 s, and no modal energy ever grows.",
        lat.describe(),
        fmt_sig(last / e0, 3)
    ));
    Ok(())
}
