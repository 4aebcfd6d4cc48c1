//! The digital-control section: the spring–mass–damper sampled with a zero-order hold at
//! several periods (poles on e^(pT), aliasing once ω_d·T > π), the sampled tank against the
//! closed form of the exponential, and a PID run by a computer: the sampled-data loop (plant
//! through its ZOH, C(z) by Tustin) against the continuous design — margins shrinking with T,
//! step responses as staircases, the closed form y\[k\] against the recursion.

use anyhow::Result;
use num_complex::Complex64;

use super::context::Ctx;
use super::md::Md;
use crate::analysis::discrete::equivalent_s;
use crate::analysis::{ClosedLoop, Factored, Input, LoopSystem};
use crate::cli::plots;
use crate::fmt::{fmt_opt, fmt_root, fmt_sig};
use crate::lti::{Controller, Discretization, Plant, TransferFunction};

const GROUP_POLES: &str = "digital control: ZOH poles against e^(pT)";
const GROUP_TANK: &str = "digital control: ZOH of the tank against its closed form";
const GROUP_SEQ: &str = "digital control: closed form y[k] against the recursion";

pub fn section(ctx: &mut Ctx, md: &mut Md, index: usize) -> Result<()> {
    md.h2(&format!("{index}. Digital control"));
    md.p(
        "A controller that runs on a computer sees the plant at the samples t = kT only: the \
         plant through a zero-order hold is G(z) = (1 − z⁻¹)·Z{G(s)/s}, exact at the samples \
         (`ltikit c2d --method zoh`). Every analysis of ltikit takes such a plant (`--dt T` for \
         a plant given in z, `--sample T` to sample a continuous one): poles and stability \
         against the unit circle, modes of the equivalent s = ln(z)/T, G(e^(jωT)) up to the \
         Nyquist frequency π/T, margins, the closed form y[k] and step metrics on the samples.",
    );
    sampled_poles(ctx, md)?;
    tank(ctx, md)?;
    digital_pid(ctx, md)
}

/// The spring–mass–damper sampled at several T: each ZOH pole is e^(pT) of a continuous pole.
fn sampled_poles(ctx: &mut Ctx, md: &mut Md) -> Result<()> {
    let g = Plant::from_model("spring-mass-damper", &[])?.factored()?;
    md.h3("Sampling the spring–mass–damper");
    let p = g
        .poles()
        .iter()
        .find(|r| r.value.im > 0.0)
        .map_or(Complex64::new(0.0, 0.0), |r| r.value);
    md.p(&format!(
        "G(s) = {g}, poles s = {} (ω_d = {} rad/s). Sampled with a ZOH, each pole moves to \
         z = e^(pT) with its multiplicity — mapped from the factored form, not re-rooted from \
         the coefficients in z. Once ω_d·T > π the samples cannot tell ω_d from ω_d − 2π/T: \
         the equivalent s = ln(z)/T of the sampled pole is an alias.",
        fmt_root(p, 6),
        fmt_sig(p.im, 6)
    ));
    let mut rows = Vec::new();
    let mut at_half = None;
    for &dt in &[0.05, 0.2, 0.5, 1.0, 2.0] {
        let gz = g.c2d(dt, Discretization::Zoh)?;
        if (dt - 0.5f64).abs() < 1e-12 {
            at_half = Some(gz.clone());
        }
        let z = gz
            .poles()
            .iter()
            .find(|r| r.value.im > 0.0)
            .map_or(Complex64::new(0.0, 0.0), |r| r.value);
        // the upper pole of z may be the image of the lower one of s once the pair aliases
        let exact = [(p * dt).exp(), (p * dt).exp().conj()]
            .into_iter()
            .min_by(|a, b| (z - a).norm().total_cmp(&(z - b).norm()))
            .unwrap_or((p * dt).exp());
        ctx.checks.add(
            GROUP_POLES,
            format!("spring–mass–damper, T = {dt} s: |z − e^(pT)|/|e^(pT)|"),
            (z - exact).norm() / exact.norm(),
            1e-15,
        );
        let s = equivalent_s(z, dt).unwrap_or(Complex64::new(f64::NAN, f64::NAN));
        let aliased = p.im * dt > std::f64::consts::PI;
        let st = gz.stability();
        rows.push(vec![
            fmt_sig(dt, 3),
            fmt_root(z, 6),
            fmt_sig(z.norm(), 6),
            fmt_root(s, 6),
            if aliased {
                "aliased (ω_d·T > π)".to_string()
            } else {
                "= p".to_string()
            },
            if st.bibo_stable {
                "stable"
            } else {
                "not stable"
            }
            .to_string(),
        ]);
    }
    md.table(
        &["T [s]", "z = e^(pT)", "|z|", "ln(z)/T", "", "stability"],
        &rows,
    );
    let Some(gz) = at_half else {
        return Ok(());
    };
    let file = "digital-smd-pzmap.png";
    plots::pzmap_figure(
        &ctx.figure(file),
        &format!("{gz}"),
        &gz,
        false,
        &super::context::fig("Spring–mass–damper sampled at T = 0.5 s (ZOH): z-plane"),
    )?;
    md.image("Pole-zero map of the sampled spring–mass–damper", file);
    Ok(())
}

/// The tank 1/(s + a) sampled with a ZOH: (1 − e^(−aT))/a / (z − e^(−aT)) in closed form.
fn tank(ctx: &mut Ctx, md: &mut Md) -> Result<()> {
    let a = 0.5;
    let g = TransferFunction::from_descending(&[1.0], &[1.0, a])?;
    md.h3("The tank through a zero-order hold");
    let mut rows = Vec::new();
    for &dt in &[0.1, 1.0, 10.0] {
        let gz = g.c2d(dt, Discretization::Zoh)?;
        let e = (-a * dt).exp();
        let b = -(-a * dt).exp_m1() / a;
        let lead = gz.den().leading();
        let (n, d) = (gz.num().coeffs(), gz.den().coeffs());
        let err = ((n.last().copied().unwrap_or(0.0) / lead - b).abs() / b)
            .max((d.last().copied().unwrap_or(0.0) / lead + e).abs() / e);
        ctx.checks.add(
            GROUP_TANK,
            format!("h' + 0.5 h = u, T = {dt} s: coefficients of G(z), relative"),
            err,
            1e-14,
        );
        rows.push(vec![fmt_sig(dt, 3), gz.to_string(), fmt_sig(err, 2)]);
    }
    md.p(
        "The seed's tank h' + 0.5 h = u (eq. 3.6) sampled with a ZOH has the closed form \
         G(z) = (1 − e^(−aT))/a / (z − e^(−aT)), a = 0.5; the computed coefficients (the \
         exponential of the augmented matrix [[A, B], [0, 0]]·T) against it:",
    );
    md.table(&["T [s]", "G(z)", "relative error"], &rows);
    Ok(())
}

/// The PID of the closed-loop section on the spring–mass–damper, continuous and digital.
fn digital_pid(ctx: &mut Ctx, md: &mut Md) -> Result<()> {
    let c = Controller::parse("pid:kp=2,ki=1,kd=0.5,tf=0.05")?;
    let g = Plant::from_model("spring-mass-damper", &[])?.factored()?;
    md.h3("A PID run by a computer");
    md.p(&format!(
        "C(s) = {c} around the spring–mass–damper, against the same PID discretised by Tustin \
         (C(z)) in front of the plant sampled with a ZOH (`--controller … --sample T`). The \
         hold delays the loop by about T/2, so the phase margin shrinks by about ω_c·T/2 and \
         the overshoot grows; at a long enough period the loop goes unstable.",
    ));
    let cf = c.tf()?.factored()?;
    let cont = ClosedLoop::new(&cf, &g)?;
    let mut rows = Vec::new();
    let mut series: Vec<(String, Factored)> = Vec::new();
    let describe = |label: String, cl: &ClosedLoop| -> Result<Vec<String>> {
        let m = cl.loop_tf().margins()?;
        let t = cl.system(LoopSystem::ClosedLoop)?;
        let st = cl.internal_stability();
        let si = if st.stable { t.step_info()? } else { None };
        Ok(vec![
            label,
            fmt_opt(m.phase_margin_deg, 4),
            fmt_opt(m.gain_crossover, 4),
            m.gain_margin.map_or("∞".into(), |x| fmt_sig(x, 4)),
            if st.stable { "stable" } else { "unstable" }.into(),
            si.map_or("—".into(), |s| fmt_opt(s.overshoot_percent, 3)),
        ])
    };
    rows.push(describe("continuous".into(), &cont)?);
    series.push(("continuous".into(), cont.system(LoopSystem::ClosedLoop)?));
    let pm0 = cont.loop_tf().margins()?;
    for &dt in &[0.02, 0.1, 0.3, 0.6, 1.0] {
        let gz = g.c2d(dt, Discretization::Zoh)?;
        let cz = cf.c2d(dt, Discretization::Tustin { prewarp: None })?;
        let cl = ClosedLoop::new(&cz, &gz)?;
        rows.push(describe(format!("T = {dt} s"), &cl)?);
        if dt <= 0.3 {
            series.push((format!("T = {dt} s"), cl.system(LoopSystem::ClosedLoop)?));
        }
        if (dt - 0.1f64).abs() < 1e-12 {
            // the closed form y[k] of the sampled loop against the recursion, 2000 samples
            let t: Vec<f64> = (0..2000).map(|k| k as f64 * dt).collect();
            let r = cl
                .system(LoopSystem::ClosedLoop)?
                .response(&Input::Step, &[], &t)?;
            ctx.checks.add(
                GROUP_SEQ,
                "PID loop sampled at T = 0.1 s: step, 2000 samples (relative to max|y|)",
                r.samples.closed_form_error / r.samples.max_abs_y,
                1e-12,
            );
            md.p(&format!(
                "At T = 0.1 s the closed loop's step response in closed form is {} — it agrees \
                 with the recursion to {} of max|y| over 2000 samples.",
                r.closed_form,
                fmt_sig(r.samples.closed_form_error / r.samples.max_abs_y, 2)
            ));
        }
    }
    md.table(
        &[
            "loop",
            "PM [°]",
            "ω_c [rad/s]",
            "GM",
            "closed loop",
            "overshoot [%]",
        ],
        &rows,
    );
    if let Some(wc) = pm0.gain_crossover {
        md.p(&format!(
            "The continuous loop crosses 0 dB at ω_c = {} rad/s: a half-sample delay costs \
             ω_c·T/2 = {}° at T = 0.1 s.",
            fmt_sig(wc, 4),
            fmt_sig((wc * 0.05).to_degrees(), 3)
        ));
    }
    let file = "digital-pid-step.png";
    plots::step_figure(
        &ctx.figure(file),
        &series,
        &Input::Step,
        None,
        &super::context::fig("PID on the spring–mass–damper: continuous and sampled loops"),
    )?;
    md.image(
        "Step responses of the continuous and sampled PID loops",
        file,
    );
    Ok(())
}
