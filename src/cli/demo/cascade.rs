//! The diagram section: a two-loop cascade on the seed's spring-mass-damper (inner PI velocity
//! loop, outer P position loop) written as a diagram file of named blocks and signals,
//! connected into one plant and analysed like any other — against the closed loop derived
//! by hand.

use anyhow::Result;
use num_complex::Complex64;

use super::context::{Ctx, fig};
use super::md::Md;
use crate::analysis::Factored;
use crate::fmt::{fmt_root, fmt_sig};
use crate::lti::Plant;
use crate::plot::{StepSeries, step_png};
use crate::poly::Poly;

const GROUP: &str = "diagram: the connected model against the loop derived by hand";
/// The diagram, shipped in `data/diagrams/` and written next to the report.
const DIAGRAM: &str = include_str!("../../../data/diagrams/smd_cascade.toml");
/// Its gains (kept equal to the file's: the closed form below uses them).
const KP_V: f64 = 6.0;
const KI_V: f64 = 20.0;
const KP_X: f64 = 3.0;
/// The seed's spring-mass-damper, M x'' + C x' + K x = F.
const M: f64 = 1.0;
const C: f64 = 0.4;
const K: f64 = 4.0;

pub fn section(ctx: &mut Ctx, md: &mut Md, index: usize) -> Result<()> {
    md.h2(&format!(
        "{index}. Systems from systems: a cascade from a diagram file"
    ));
    // the diagram beside the report (through a temporary name: never half written)
    let path = ctx.out.join("smd_cascade.toml");
    let tmp = ctx.out.join("smd_cascade.toml.tmp");
    std::fs::write(&tmp, DIAGRAM)?;
    std::fs::rename(&tmp, &path)?;
    let plant = Plant::from_file(&path)?;
    let ss = plant.state_space()?;
    let f = Factored::from_state_space(&ss)?;
    // by hand: the inner loop (kp s + ki)/s · s/(M s² + C s + K) closes to
    // (kp s + ki)/(M s² + (C + kp) s + K + ki); x = v/s; the outer P loop then gives
    // T = kx (kp s + ki) / (M s³ + (C + kp) s² + (K + ki + kx kp) s + kx ki)
    let num = [KP_X * KP_V, KP_X * KI_V];
    let den = [M, C + KP_V, K + KI_V + KP_X * KP_V, KP_X * KI_V];
    let t_hand = |s: Complex64| {
        let n = num[0] * s + num[1];
        let d = ((den[0] * s + den[1]) * s + den[2]) * s + den[3];
        n / d
    };
    let points = [
        Complex64::new(0.0, 0.5),
        Complex64::new(0.0, 5.0),
        Complex64::new(-1.0, 2.0),
        Complex64::new(3.0, -1.0),
        Complex64::new(0.0, 100.0),
    ];
    let mut err = 0.0f64;
    for s in points {
        let g = crate::analysis::point::value_at(&f, s)?;
        err = err.max((g - t_hand(s)).norm() / t_hand(s).norm());
    }
    ctx.checks.add(
        GROUP,
        "cascade diagram: G(s) of the connected model against the hand-derived loop at 5 points, relative",
        err,
        1e-12,
    );
    let cubic = Poly::from_descending(&den)?;
    let hand_poles = cubic.roots()?;
    let pole_err = f
        .poles()
        .iter()
        .map(|p| {
            hand_poles
                .iter()
                .map(|q| (p.value - q.value).norm() / q.value.norm())
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max);
    ctx.checks.add(
        GROUP,
        "cascade diagram: poles of the connected model = roots of the hand-derived characteristic polynomial",
        pole_err,
        1e-12,
    );
    let dc = f.dc_gain().unwrap_or(f64::NAN);
    ctx.checks.add(
        GROUP,
        "cascade diagram: dc gain 1 (the inner integrator and the position feedback), absolute",
        (dc - 1.0).abs(),
        1e-13,
    );
    let info = f.step_info()?;
    let t = crate::analysis::auto_time_grid(&f, 600)?;
    let step = f.step_response(&t)?;
    md.p(&format!(
        "The seed's spring-mass-damper (M = {M} kg, C = {C} N·s/m, K = {K} N/m, eq. 3.1) with both \
         its position x and velocity v measured, an inner PI loop on the velocity (kp = {KP_V}, \
         ki = {KI_V}) and an outer P loop on the position (kp = {KP_X}) — written as a diagram \
         file of named blocks and signals (`smd_cascade.toml` beside this report, also \
         `data/diagrams/`), with the summing junctions e_x = r − x and e_v = v_ref − v. Any \
         command takes it as a plant (`--plant smd_cascade.toml`); `ltikit connect` prints \
         the model it becomes: {} states, G(s) = {}, poles {}, dc gain {}.",
        ss.order(),
        f,
        f.poles()
            .iter()
            .filter(|p| p.value.im >= 0.0) // a pair is printed once, as a ± b j
            .map(|p| fmt_root(p.value, 6))
            .collect::<Vec<_>>()
            .join(", "),
        fmt_sig(dc, 12),
    ));
    md.code(DIAGRAM.trim_end());
    if let Some(si) = &info {
        md.p(&format!(
            "By hand the loop is T(s) = kx(kp s + ki)/(M s³ + (C + kp)s² + (K + ki + kx·kp)s + \
             kx·ki) (the PI's pole at 0 cancels the velocity's zero at 0 inside the inner loop); \
             the connected model agrees with it to {} at five points. Step: rise time {} s, \
             settling time {} s, overshoot {} %.",
            fmt_sig(err, 2),
            si.rise_time.map_or("—".into(), |v| fmt_sig(v, 4)),
            si.settling_time.map_or("—".into(), |v| fmt_sig(v, 4)),
            si.overshoot_percent.map_or("0".into(), |v| fmt_sig(v, 3)),
        ));
    }
    let path = ctx.figure("smd_cascade_step.png");
    let mut series = StepSeries::new(&step).label("r → x, cascade");
    if let Some(si) = &info {
        series = series.info(si);
    }
    step_png(
        &path,
        &[series],
        &fig("Position cascade on the spring-mass-damper: step in the reference"),
    )?;
    md.image("cascade step", "smd_cascade_step.png");
    Ok(())
}
