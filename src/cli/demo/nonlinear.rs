//! The nonlinear section: pendulum, MEMS mirror, Lorenz, van der Pol.

use anyhow::Result;

use super::context::{Ctx, fig};
use super::md::Md;
use crate::cli::text::vector_text;
use crate::fmt::{fmt_root, fmt_sig};
use crate::nonlinear::models::{Lorenz, Mems, Pendulum, VanDerPol};
use crate::nonlinear::{
    EquilibriumSearch, Linearization, LocalStability, PeriodPoint, linearize, pendulum_periods,
};
use crate::nonlinear::{
    InputSignal, Simulation, lorenz_divergence, pendulum_separatrices, sample_times, simulate,
    trajectories,
};
use crate::numeric::rk45::Rk45Options;
use crate::plot::{
    Curve, Equilibrium, LineStyle, Marker, MarkerShape, PhasePortrait, XyPlot, phase_portrait_png,
    series_color, time_plot_png, xy_png,
};

fn stability_text(s: LocalStability) -> &'static str {
    match s {
        LocalStability::AsymptoticallyStable => "asymptotically stable",
        LocalStability::Unstable => "unstable",
        LocalStability::Undetermined => "undetermined (not hyperbolic)",
    }
}

/// The equilibria table of a linearisation.
pub fn equilibria_table(md: &mut Md, lin: &Linearization, show_physical: bool) {
    let mut header = vec!["x̄", "eigenvalues of A", "local stability"];
    if show_physical {
        header.push("physical");
    }
    header.push("linearised G(s)");
    let rows: Vec<Vec<String>> = lin
        .equilibria
        .iter()
        .map(|e| {
            let ev = e
                .eigenvalues
                .iter()
                .filter(|z| z.im >= 0.0)
                .map(|z| fmt_root(*z, 5))
                .collect::<Vec<_>>()
                .join(", ");
            let mut r = vec![
                vector_text(&e.x),
                ev,
                stability_text(e.stability).to_string(),
            ];
            if show_physical {
                r.push(if e.physical { "yes" } else { "no" }.into());
            }
            r.push(
                e.tf.as_ref()
                    .map(|t| t.g.to_string())
                    .unwrap_or_else(|| "– (no input)".into()),
            );
            r
        })
        .collect();
    md.table(&header, &rows);
}

/// Equilibria of a linearisation as portrait markers on states (i, j).
fn markers(lin: &Linearization, i: usize, j: usize) -> Vec<Equilibrium> {
    lin.equilibria
        .iter()
        .map(|e| Equilibrium {
            at: (e.x[i], e.x[j]),
            stable: e.stability == LocalStability::AsymptoticallyStable,
            label: None,
        })
        .collect()
}

/// The (x_i, x_j) curve of a simulation.
fn projection(s: &Simulation, i: usize, j: usize) -> Curve {
    Curve::new(s.states.iter().map(|x| (x[i], x[j])))
}

fn accurate() -> Rk45Options {
    Rk45Options {
        rtol: 1e-10,
        atol: 1e-12,
        ..Default::default()
    }
}

/// Pendulum: equilibria, linearisation, periods. Returns the linearisation.
pub fn pendulum(ctx: &mut Ctx, md: &mut Md) -> Result<Linearization> {
    let p = Pendulum::default();
    md.h3("Pendulum (seed eq. 2.15)");
    md.p(&format!(
        "θ̈ = −(3C/(ML²)) θ̇ − (3g/(2L)) sin θ + 3τ/(ML²), x = [θ, θ̇], u = τ, y = θ; \
         M = {} kg, L = {} m, C = {} N·m·s, g = {} m/s².",
        fmt_sig(p.m, 4),
        fmt_sig(p.l, 4),
        fmt_sig(p.c, 4),
        fmt_sig(p.g, 4)
    ));
    let lin = linearize(&p, None, &EquilibriumSearch::default())?;
    equilibria_table(md, &lin, false);
    md.p(
        "The hanging equilibrium θ = 0 is a stable focus; the upright θ = π is a saddle \
          (seed §2.3.1): its linearisation has one eigenvalue in each half plane.",
    );
    let rows = period_table(md, &p)?;
    let (portrait, undamped) = portraits(ctx, &p, &lin)?;
    let period = period_figure(ctx, &p, &rows)?;
    md.image("Damped pendulum phase portrait", portrait);
    md.image(
        "Undamped pendulum phase portrait with separatrices",
        undamped,
    );
    md.image("Pendulum period against amplitude", period);
    Ok(lin)
}

/// The pendulum's period against amplitude: exact, simulated and small-angle, in a table.
fn period_table(md: &mut Md, p: &Pendulum) -> Result<Vec<PeriodPoint>> {
    md.p(
        "**Period against amplitude** (undamped, C = 0): the exact T = 4K(k)/ω with \
          k = sin(θ₀/2), ω² = 3g/(2L) (seed §2.3.1.1), the period measured on the simulated \
          pendulum, and the small-angle 2π/ω.",
    );
    let amps = [0.1, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.1];
    let opts = Rk45Options {
        rtol: 1e-12,
        atol: 1e-14,
        ..Default::default()
    };
    let rows = pendulum_periods(p, &amps, &opts)?;
    let table: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                format!(
                    "{} rad ({}°)",
                    fmt_sig(r.amplitude, 3),
                    fmt_sig(r.amplitude.to_degrees(), 4)
                ),
                fmt_sig(r.exact, 10),
                fmt_sig(r.simulated, 10),
                fmt_sig(r.small_angle, 6),
                fmt_sig(r.exact / r.small_angle, 6),
            ]
        })
        .collect();
    md.table(
        &[
            "amplitude θ₀",
            "exact 4K(k)/ω [s]",
            "simulated [s]",
            "2π/ω [s]",
            "T / (2π/ω)",
        ],
        &table,
    );
    Ok(rows)
}

/// The damped and the undamped phase portraits (with separatrices); returns their file names.
fn portraits(
    ctx: &mut Ctx,
    p: &Pendulum,
    lin: &Linearization,
) -> Result<(&'static str, &'static str)> {
    // Phase portraits: the damped pendulum, and the undamped one with its separatrices.
    let pi = std::f64::consts::PI;
    let t = sample_times(12.0, 2401)?;
    let starts: Vec<Vec<f64>> = vec![
        vec![1.0, 0.0],
        vec![2.0, 0.0],
        vec![3.0, 0.0],
        vec![-2.5, 0.0],
        vec![-pi, 9.0],
        vec![pi, -9.0],
        vec![-pi, 6.5],
    ];
    let damped = trajectories(
        p,
        &starts,
        &InputSignal::constant(vec![0.0]),
        &t,
        &accurate(),
    )?;
    let portrait = "pendulum-phase.png";
    let mut eq = markers(lin, 0, 1);
    eq.extend(markers(lin, 0, 1).into_iter().map(|mut e| {
        e.at.0 -= 2.0 * pi;
        e
    }));
    phase_portrait_png(
        ctx.figure(portrait),
        &PhasePortrait {
            trajectories: damped.iter().map(|s| projection(s, 0, 1)).collect(),
            equilibria: eq,
            x_label: "θ (rad)".into(),
            y_label: "θ̇ (rad/s)".into(),
            x_range: Some((-2.0 * pi - 0.5, 2.0 * pi + 0.5)),
            ..Default::default()
        },
        &fig("Damped pendulum: trajectories spiral into θ = 0 (mod 2π)"),
    )?;
    let p0 = Pendulum::new(p.m, p.l, 0.0, p.g)?;
    let t = sample_times(6.0, 1801)?;
    let starts: Vec<Vec<f64>> = vec![
        vec![0.5, 0.0],
        vec![1.5, 0.0],
        vec![2.5, 0.0],
        vec![3.0, 0.0],
        vec![-pi, 8.5],
        vec![pi, -8.5],
    ];
    let free = trajectories(
        &p0,
        &starts,
        &InputSignal::constant(vec![0.0]),
        &t,
        &accurate(),
    )?;
    let [upper, lower] = pendulum_separatrices(&p0, -pi, pi, 401)?;
    let sep = |v: &[[f64; 2]]| Curve::new(v.iter().map(|q| (q[0], q[1])));
    let undamped = "pendulum-phase-undamped.png";
    phase_portrait_png(
        ctx.figure(undamped),
        &PhasePortrait {
            trajectories: free.iter().map(|s| projection(s, 0, 1)).collect(),
            separatrices: vec![sep(&upper).label("separatrices (energy 2ω²)"), sep(&lower)],
            equilibria: vec![
                Equilibrium {
                    at: (0.0, 0.0),
                    stable: true,
                    label: Some("centre".into()),
                },
                Equilibrium {
                    at: (-pi, 0.0),
                    stable: false,
                    label: None,
                },
                Equilibrium {
                    at: (pi, 0.0),
                    stable: false,
                    label: None,
                },
            ],
            x_label: "θ (rad)".into(),
            y_label: "θ̇ (rad/s)".into(),
            x_range: Some((-pi - 0.3, pi + 0.3)),
            ..Default::default()
        },
        &fig("Undamped pendulum (C = 0): oscillations inside the separatrices, rotations outside"),
    )?;
    Ok((portrait, undamped))
}

/// The period against amplitude: the exact curve, the small-angle line, the simulated periods.
fn period_figure(ctx: &mut Ctx, p: &Pendulum, rows: &[PeriodPoint]) -> Result<&'static str> {
    let pi = std::f64::consts::PI;
    // Period against amplitude.
    let dense: Vec<(f64, f64)> = (1..=313)
        .map(|k| {
            let a = 0.01 * k as f64;
            crate::nonlinear::pendulum_period_exact(p.omega(), a).map(|t| (a, t))
        })
        .collect::<crate::Result<_>>()?;
    let period = "pendulum-period.png";
    xy_png(
        ctx.figure(period),
        &XyPlot {
            curves: vec![
                Curve::new(dense).label("exact T = 4K(k)/ω"),
                Curve::new([(0.0, rows[0].small_angle), (pi, rows[0].small_angle)])
                    .label("small angle 2π/ω")
                    .style(LineStyle::Dashed),
            ],
            markers: rows
                .iter()
                .map(|r| Marker::new((r.amplitude, r.simulated), MarkerShape::Circle))
                .collect(),
            x_label: "amplitude θ_{0} (rad)".into(),
            y_label: "period T (s)".into(),
            x_range: Some((0.0, pi)),
            notes: vec!["○ measured on the simulated pendulum".into()],
            ..Default::default()
        },
        &fig("Pendulum period against amplitude (seed §2.3.1.1)"),
    )?;
    Ok(period)
}

/// MEMS mirror: equilibria below pull-in, the pull-in voltage.
pub fn mems(ctx: &mut Ctx, md: &mut Md) -> Result<(Mems, Linearization)> {
    let m = Mems::default();
    md.h3("Electrostatic MEMS mirror (exercises 1.4, 2.11)");
    md.p(&format!(
        "m l̈ = −k (l − l0) − b l̇ − q²/(2εA), R q̇ = v − q l/(εA); x = [l, l̇, q], u = v, y = l. \
         Exercise 2.11's values ε = A = m = k = 1, l0 = 3, b = 0.02, with R = {} and the \
         operating voltage v = {}.",
        fmt_sig(m.r, 4),
        fmt_sig(m.v, 4)
    ));
    let lin = linearize(&m, None, &EquilibriumSearch::default())?;
    equilibria_table(md, &lin, true);
    let v_pi = m.pull_in_voltage();
    let (v_found, l_found) = crate::nonlinear::find_pull_in(&m)?;
    md.p(&format!(
        "Equilibria satisfy l²(l0 − l) = εA v²/(2k), q = εA v/l: three real ones below the \
         pull-in voltage √(8 k l0³/(27 εA)) = {} V, one above. Of the three, only the largest \
         gap is stable; the middle one is the saddle that merges with it at pull-in \
         (l = 2 l0/3 = {}). Found numerically (where the stable branch disappears): v = {} V, \
         l = {}.",
        fmt_sig(v_pi, 10),
        fmt_sig(2.0 * m.l0 / 3.0, 6),
        fmt_sig(v_found, 10),
        fmt_sig(l_found, 6)
    ));
    let pull = "mems-pullin.png";
    super::super::pullin::pullin_figure(
        &ctx.figure(pull),
        &m,
        None,
        &fig("MEMS mirror: pull-in diagram"),
    )?;
    // Exercise 2.11: l(t) and q(t) below and above pull-in, from rest at l = l0, q = 0.
    let t = sample_times(60.0, 3001)?;
    let mut gap = Vec::new();
    let mut charge = Vec::new();
    let mut notes = Vec::new();
    for (k, v) in [0.8 * v_pi, 1.1 * v_pi].into_iter().enumerate() {
        let mv = m.with_voltage(v)?;
        let sim = simulate(
            &mv,
            &[m.l0, 0.0, 0.0],
            &InputSignal::constant(vec![v]),
            &t,
            &accurate(),
        )?;
        let label = format!(
            "v = {} V ({} × pull-in)",
            fmt_sig(v, 4),
            if k == 0 { "0.8" } else { "1.1" }
        );
        let l: Vec<f64> = sim.states.iter().map(|x| x[0]).collect();
        let q: Vec<f64> = sim.states.iter().map(|x| x[2]).collect();
        let n = sim.t.len();
        gap.push(
            Curve::from_xy(&sim.t, &l)?
                .label(label.clone())
                .color(series_color(k)),
        );
        charge.push(
            Curve::from_xy(&sim.t[..n], &q)?
                .label(label.clone())
                .color(series_color(k)),
        );
        match &sim.stop {
            Some(st) => notes.push(format!(
                "At {label} the plates touch (l = 0) at t = {} s: pull-in.",
                fmt_sig(st.t, 5)
            )),
            None => notes.push(format!(
                "At {label} the mirror settles to the stable gap l = {}.",
                fmt_sig(l[n - 1], 5)
            )),
        }
    }
    let gap_png = "mems-gap.png";
    time_plot_png(
        ctx.figure(gap_png),
        &gap,
        "gap l (m)",
        &fig("MEMS mirror: gap l(t) below and above pull-in (exercise 2.11)"),
    )?;
    let charge_png = "mems-charge.png";
    time_plot_png(
        ctx.figure(charge_png),
        &charge,
        "charge q (C)",
        &fig("MEMS mirror: charge q(t) below and above pull-in"),
    )?;
    md.bullets(&notes);
    md.image("MEMS pull-in diagram", pull);
    md.image("MEMS gap against time", gap_png);
    md.image("MEMS charge against time", charge_png);
    Ok((m, lin))
}

/// Lorenz: equilibria, the attractor and the divergence of nearby trajectories.
pub fn lorenz(ctx: &mut Ctx, md: &mut Md) -> Result<Linearization> {
    let l = Lorenz::default();
    md.h3("Lorenz weather model (seed eqs. 2.38–2.40)");
    md.p(&format!(
        "ẋ₁ = σ(x₂ − x₁), ẋ₂ = r x₁ − x₂ − x₁x₃, ẋ₃ = x₁x₂ − b x₃ with σ = {}, r = {}, b = {}. \
         Equilibria: the origin and C± = (±√(b(r−1)), ±√(b(r−1)), r − 1).",
        fmt_sig(l.sigma, 4),
        fmt_sig(l.r, 4),
        fmt_sig(l.b, 6)
    ));
    let lin = linearize(&l, None, &EquilibriumSearch::default())?;
    equilibria_table(md, &lin, false);
    md.p(
        "All three equilibria are unstable for r = 28: the origin is a saddle with one \
          positive eigenvalue, C± are saddle-foci with a complex pair in the right half plane — \
          trajectories wander between them forever (the attractor below).",
    );
    let t = sample_times(50.0, 25001)?;
    let sim = simulate(&l, &[1.0, 0.0, 0.0], &InputSignal::none(), &t, &accurate())?;
    let attractor = "lorenz-attractor.png";
    phase_portrait_png(
        ctx.figure(attractor),
        &PhasePortrait {
            trajectories: vec![projection(&sim, 0, 2).width(0.6)],
            equilibria: markers(&lin, 0, 2),
            x_label: "x_{1}".into(),
            y_label: "x_{3}".into(),
            ..Default::default()
        },
        &fig("Lorenz attractor from [1, 0, 0], 0 ≤ t ≤ 50 (seed fig. 2.9)"),
    )?;
    let t = sample_times(40.0, 8001)?;
    let d = lorenz_divergence(&l, 1e-3, &t, &accurate())?;
    let x1a: Vec<f64> = d.a.states.iter().map(|x| x[0]).collect();
    let x1b: Vec<f64> = d.b.states.iter().map(|x| x[0]).collect();
    let div = "lorenz-divergence.png";
    time_plot_png(
        ctx.figure(div),
        &[
            Curve::from_xy(&d.a.t, &x1a)?.label("x_{1}(t) from [1, 0, 0]"),
            Curve::from_xy(&d.b.t, &x1b)?
                .label("x_{1}(t) from [1.001, 0, 0]")
                .style(LineStyle::Dashed),
        ],
        "x_{1}",
        &fig("Sensitivity to initial conditions: two starts 0.001 apart (seed fig. 2.10)"),
    )?;
    let ts = d.separation_time(1.0);
    md.p(&format!(
        "Two trajectories started 0.001 apart stay together for a while and then part: their \
         distance first exceeds 1 at t = {} s (the seed: \"the solutions diverge rapidly around \
         twenty seconds\").",
        ts.map(|t| fmt_sig(t, 4)).unwrap_or_else(|| "—".into())
    ));
    md.image("Lorenz attractor", attractor);
    md.image("Divergence of nearby Lorenz trajectories", div);
    Ok(lin)
}

/// van der Pol: the unstable origin and the unit-circle limit cycle.
pub fn vanderpol(ctx: &mut Ctx, md: &mut Md) -> Result<Linearization> {
    md.h3("van der Pol oscillator (seed eqs. 2.36–2.37)");
    md.p(
        "ẋ₁ = −x₂ − x₁(x₁² + x₂² − 1), ẋ₂ = x₁ − x₂(x₁² + x₂² − 1): in polar form ṙ = r(1 − r²), \
          θ̇ = 1, so the unit circle is a periodic orbit that attracts every other trajectory.",
    );
    let lin = linearize(&VanDerPol, None, &EquilibriumSearch::default())?;
    equilibria_table(md, &lin, false);
    let t = sample_times(20.0, 4001)?;
    let starts: Vec<Vec<f64>> = vec![
        vec![0.001, 0.0],
        vec![2.0, 0.0],
        vec![0.0, -1.8],
        vec![-1.5, 1.5],
        vec![0.3, 0.2],
    ];
    let tr = trajectories(&VanDerPol, &starts, &InputSignal::none(), &t, &accurate())?;
    let circle: Vec<(f64, f64)> = (0..=360)
        .map(|k| {
            let a = (k as f64).to_radians();
            (a.cos(), a.sin())
        })
        .collect();
    let png = "vanderpol-phase.png";
    phase_portrait_png(
        ctx.figure(png),
        &PhasePortrait {
            trajectories: tr.iter().map(|s| projection(s, 0, 1)).collect(),
            separatrices: vec![Curve::new(circle).label("limit cycle r = 1")],
            equilibria: markers(&lin, 0, 1),
            x_label: "x_{1}".into(),
            y_label: "x_{2}".into(),
            equal_aspect: true,
            ..Default::default()
        },
        &fig("van der Pol oscillator: every trajectory tends to the unit circle (seed fig. 2.8)"),
    )?;
    md.image("van der Pol phase portrait", png);
    Ok(lin)
}
