//! The closed-loop section: a PID controller on the spring–mass–damper (closed-loop poles,
//! step metrics of T, margins and robustness of L, Ms checked on a dense grid), an unstable
//! pole cancelled by the controller, flagged, and the root loci of the quarter-car suspension
//! (`rlocus.rs`). The loop's characteristic polynomial and the hidden mode are checked against
//! closed forms in tests/closed_loop.rs.

use anyhow::Result;
use num_complex::Complex64;

use super::context::Ctx;
use super::md::Md;
use crate::analysis::{ClosedLoop, LoopSystem};
use crate::fmt::{fmt_opt, fmt_root, fmt_sig};
use crate::lti::{Controller, Plant};

const GROUP: &str = "closed loop: Ms against |1/(1 + L(jω))| on a dense grid";

pub fn section(ctx: &mut Ctx, md: &mut Md, index: usize) -> Result<()> {
    md.h2(&format!("{index}. Closing the loop"));
    md.p(
        "A controller C in front of the plant G with unity negative feedback: the loop \
         L = C·G keeps the factors of both, the characteristic polynomial D_C·D_G + N_C·N_G is \
         formed once before any cancellation, and T = L/(1 + L), S = 1/(1 + L) and C·S share \
         its roots. On the command line: `--controller \"pid:kp=2,ki=1,kd=0.5,tf=0.01\"`, \
         with `--loop`, `--closed-loop`, `--sensitivity` or `--control-sensitivity`.",
    );
    pid(ctx, md)?;
    hidden(md)?;
    super::rlocus::section(ctx, md)
}

fn pid(ctx: &mut Ctx, md: &mut Md) -> Result<()> {
    let c = Controller::parse("pid:kp=2,ki=1,kd=0.5,tf=0.01")?;
    let g = Plant::from_model("spring-mass-damper", &[])?.factored()?;
    let cl = ClosedLoop::new(&c.tf()?.factored()?, &g)?;
    md.h3("PID on the spring–mass–damper");
    md.p(&format!(
        "G = 1/(s² + 0.4 s + 4), C(s) = kp + ki/s + kd·s/(tf·s + 1) with {c}. \
         Characteristic polynomial (monic): {}.",
        cl.characteristic()
    ));
    let t = cl.system(LoopSystem::ClosedLoop)?;
    let poles: Vec<String> = cl
        .poles()
        .iter()
        .filter(|r| r.value.im >= 0.0)
        .map(|r| fmt_root(r.value, 6))
        .collect();
    let mut rows = vec![vec!["closed-loop poles".to_string(), poles.join(", ")]];
    if let Some(si) = t.step_info()? {
        rows.push(vec![
            "step of T".into(),
            format!(
                "rise {} s, settling {} s (2 %), overshoot {} %",
                fmt_opt(si.rise_time, 4),
                fmt_opt(si.settling_time, 4),
                fmt_opt(si.overshoot_percent, 3)
            ),
        ]);
    }
    let m = cl.loop_tf().margins()?;
    let r = cl.robustness()?;
    rows.push(vec![
        "margins of L".into(),
        format!(
            "PM {}° at {} rad/s, GM {}",
            fmt_sig(m.phase_margin_deg.unwrap_or(f64::NAN), 4),
            fmt_sig(m.gain_crossover.unwrap_or(f64::NAN), 4),
            m.gain_margin.map_or("∞".into(), |x| fmt_sig(x, 4))
        ),
    ]);
    rows.push(vec![
        "robustness".into(),
        format!(
            "Ms {} at {} rad/s, Mt {} at {} rad/s, delay margin {} s",
            fmt_sig(r.ms.value, 5),
            fmt_sig(r.ms.w, 4),
            fmt_sig(r.mt.value, 5),
            fmt_sig(r.mt.w, 4),
            fmt_sig(r.delay_margin, 4)
        ),
    ]);
    md.table(&["quantity", "value"], &rows);
    // Ms is the maximum of |1/(1 + L(jω))|: no sample of a dense grid may exceed it
    let l = cl.loop_tf();
    let grid_max = (0..=4000)
        .map(|i| 10f64.powf(-2.0 + 4.0 * f64::from(i) / 4000.0))
        .map(|w| 1.0 / (1.0 + l.eval(Complex64::new(0.0, w))).norm())
        .fold(0.0, f64::max);
    ctx.checks.add(
        GROUP,
        "PID loop: Ms ≥ max|1/(1 + L(jω))| on 4001 log-spaced ω (relative excess)",
        ((grid_max - r.ms.value) / r.ms.value).max(0.0),
        1e-12,
    );
    Ok(())
}

fn hidden(md: &mut Md) -> Result<()> {
    let g = crate::lti::TransferFunction::from_descending(&[1.0], &[1.0, 1.0, -2.0])?.factored()?;
    let c = Controller::parse("pi:kp=10,ki=-10")?;
    let cl = ClosedLoop::new(&c.tf()?.factored()?, &g)?;
    let st = cl.internal_stability();
    md.h3("An unstable pole cancelled by the controller");
    md.p(&format!(
        "G = 1/((s − 1)(s + 2)) with C = 10 (s − 1)/s ({c}): L = 10/(s(s + 2)) and \
         T = 10/(s² + 2 s + 10) look stable, but the plant's pole at s = 1 is cancelled by the \
         controller's zero — a hidden mode, still a root of the characteristic polynomial \
         {}. Verdict: {}.",
        cl.characteristic(),
        st.reason
    ));
    Ok(())
}
