//! Margins of a discrete-time loop: every gain and phase crossing on 0 < ω ≤ π/T, found as
//! sign changes on a grid in θ = ωT adapted to the factors and refined by Brent's method on
//! G(e^(jθ)) itself; bandwidth and resonant peak likewise.

use std::f64::consts::{PI, TAU};

use super::circle_side;
use super::freq::eval;
use crate::analysis::margins::crossing::{
    GainCrossing, Margins, PhaseCrossing, dedup_by_w, wrap_deg,
};
use crate::analysis::{Factored, HalfPlane};
use crate::error::Result;
use crate::numeric::scalar::all_crossings;

/// Uniform points on (0, π].
const UNIFORM: usize = 4096;

/// θ in (0, π], sorted: uniform, logarithmic towards 0, and geometric clusters about the
/// angle of every root near the unit circle (a lightly damped pair crosses within its
/// distance to the circle of its angle).
fn theta_grid(f: &Factored) -> Vec<f64> {
    let mut g: Vec<f64> = (1..=UNIFORM)
        .map(|i| PI * i as f64 / UNIFORM as f64)
        .collect();
    g.extend((1..=200).map(|k| PI / UNIFORM as f64 * 10f64.powf(-(k as f64) / 20.0)));
    for r in f.reduced_poles().iter().chain(f.reduced_zeros()) {
        let a = r.value.im.atan2(r.value.re).abs();
        let d = (r.value.norm() - 1.0).abs().max(1e-14);
        if d > 0.5 {
            continue;
        }
        for k in 0..60 {
            let h = d * 1.5f64.powi(k - 10);
            if h > 0.5 {
                break;
            }
            g.extend([a - h, a + h]);
        }
        g.push(a);
    }
    g.retain(|&x| x > 0.0 && x <= PI);
    g.sort_by(f64::total_cmp);
    g.dedup();
    g
}

/// max over 0 ≤ ω ≤ π/T of |G(e^(jωT))| and where (∞ at the lowest-frequency pole on the
/// unit circle): the largest sample of the grid refined by golden sections.
pub(crate) fn peak(f: &Factored, dt: f64) -> (f64, f64) {
    if let Some(a) = f
        .reduced_poles()
        .iter()
        .filter(|p| circle_side(p.value) == HalfPlane::Axis)
        .map(|p| p.value.im.atan2(p.value.re).abs())
        .min_by(f64::total_cmp)
    {
        return (f64::INFINITY, a / dt);
    }
    let mut grid = theta_grid(f);
    grid.insert(0, 0.0);
    let ln_mag = |th: f64| eval(f, th).0;
    let mags: Vec<f64> = grid.iter().map(|&t| ln_mag(t)).collect();
    let Some((i, _)) = mags
        .iter()
        .enumerate()
        .filter(|(_, m)| !m.is_nan())
        .max_by(|a, b| a.1.total_cmp(b.1))
    else {
        return (0.0, 0.0);
    };
    let (th, lm) = golden_max(&ln_mag, &grid, i);
    (lm.exp(), th / dt)
}

/// The maximum of `f` about grid point `i`, by golden sections between its neighbours.
fn golden_max(f: &impl Fn(f64) -> f64, grid: &[f64], i: usize) -> (f64, f64) {
    let (mut a, mut b) = (grid[i.saturating_sub(1)], grid[(i + 1).min(grid.len() - 1)]);
    let r = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..200 {
        if b - a <= 1e-15 * b.max(1e-300) {
            break;
        }
        let (c, d) = (b - r * (b - a), a + r * (b - a));
        if f(c) > f(d) {
            b = d;
        } else {
            a = c;
        }
    }
    let mid = 0.5 * (a + b);
    if f(mid) >= f(grid[i]) {
        (mid, f(mid))
    } else {
        (grid[i], f(grid[i]))
    }
}

/// Margins, bandwidth and resonance of a discrete-time plant (see the module docs).
pub(crate) fn margins(f: &Factored, dt: f64) -> Result<Margins> {
    let mut out = Margins::default();
    if f.is_zero() {
        return Ok(out);
    }
    let grid = theta_grid(f);
    let ln_mag = |th: f64| eval(f, th).0;
    let phase = |th: f64| eval(f, th).1;
    let mags: Vec<f64> = grid.iter().map(|&t| ln_mag(t)).collect();
    let tol = 1e-15;

    // points within rounding of |G| = 1 carry no sign (a tangency, e.g. at θ = 0, is no
    // crossing): drop them before looking for sign changes
    let (gx, gf): (Vec<f64>, Vec<f64>) = grid
        .iter()
        .zip(&mags)
        .filter(|(_, m)| m.abs() > 1e-12)
        .map(|(x, m)| (*x, *m))
        .unzip();
    for th in all_crossings(ln_mag, &gx, &gf, tol) {
        out.gain_crossings.push(GainCrossing {
            w: th / dt,
            phase_margin_deg: wrap_deg(180.0 + phase(th).to_degrees()),
        });
    }
    dedup_by_w(&mut out.gain_crossings, |c| c.w);

    // phase crossings: ω = 0 for a finite negative dc gain, the branch changes of φ between
    // grid points, and ω = π/T where G(−1) is real and negative
    let push_phase = |out: &mut Margins, th: f64| {
        let l = ln_mag(th);
        if l.is_finite() {
            out.phase_crossings.push(PhaseCrossing {
                w: th / dt,
                gain_margin: (-l).exp(),
                gain_margin_db: -l * 20.0 / std::f64::consts::LN_10,
            });
        }
    };
    let (l0, p0) = eval(f, 0.0);
    if l0.is_finite() && wrap_deg(p0.to_degrees()).abs() > 90.0 && !f.reduced_poles().is_empty() {
        push_phase(&mut out, 0.0);
    }
    let branch = |p: f64| ((p - PI) / TAU).ceil();
    let phases: Vec<f64> = grid.iter().map(|&t| phase(t)).collect();
    for i in 0..grid.len().saturating_sub(1) {
        let (ka, kb) = (branch(phases[i]), branch(phases[i + 1]));
        if !ka.is_finite() || !kb.is_finite() || (ka - kb).abs() < 0.5 {
            continue;
        }
        if !(mags[i].is_finite() && mags[i + 1].is_finite()) {
            continue; // a pole or zero on the circle: the phase jumps, it does not cross
        }
        let target = PI * (2.0 * ka.max(kb) - 1.0);
        let h = |t: f64| phase(t) - target;
        let xs = [grid[i], grid[i + 1]];
        let fs = [h(xs[0]), h(xs[1])];
        for th in all_crossings(h, &xs, &fs, tol) {
            push_phase(&mut out, th);
        }
    }
    let (lp, pp) = eval(f, PI);
    if lp.is_finite() && (wrap_deg(pp.to_degrees()).abs() - 180.0).abs() < 1e-9 {
        push_phase(&mut out, PI);
    }
    dedup_by_w(&mut out.phase_crossings, |c| c.w);
    out.headline();

    // dc gain |G(1)|: bandwidth and resonance relative to it
    if !(l0.is_finite()) {
        return Ok(out);
    }
    let level = l0 - 0.15 * std::f64::consts::LN_10;
    let below: Vec<f64> = mags.iter().map(|m| m - level).collect();
    if let Some(th) = all_crossings(|t| ln_mag(t) - level, &grid, &below, tol).first() {
        out.bandwidth = Some(th / dt);
    }
    let circle_pole = f
        .reduced_poles()
        .iter()
        .filter(|p| circle_side(p.value) == HalfPlane::Axis)
        .map(|p| p.value.im.atan2(p.value.re).abs())
        .min_by(f64::total_cmp);
    if let Some(a) = circle_pole {
        out.resonant_peak = Some(f64::INFINITY);
        out.resonant_frequency = Some(a / dt);
        return Ok(out);
    }
    if let Some((i, &m)) = mags
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .filter(|(_, m)| m.is_finite())
    {
        let (th, lm) = golden_max(&ln_mag, &grid, i);
        let lm = lm.max(m);
        if lm > l0 + 1e-12 && th > 0.0 {
            out.resonant_peak = Some((lm - l0).exp());
            out.resonant_frequency = Some(th / dt);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::TransferFunction;
    use crate::lti::Domain;

    fn zf(num: &[f64], den: &[f64], dt: f64) -> Factored {
        TransferFunction::from_descending(num, den)
            .unwrap()
            .with_domain(Domain::discrete(dt).unwrap())
            .factored()
            .unwrap()
    }

    #[test]
    fn gain_margin_of_k_over_z_minus_half() {
        // L = K/(z − 0.5): the closed-loop pole z = 0.5 − K leaves the unit circle at K = 1.5
        // (z = −1, θ = π): GM = 1.5/K at ω = π/T
        let dt = 0.2;
        let m = margins(&zf(&[0.5], &[1.0, -0.5], dt), dt).unwrap();
        assert!((m.gain_margin.unwrap() - 3.0).abs() < 1e-12, "{m:?}");
        assert!((m.phase_crossover.unwrap() - PI / dt).abs() < 1e-12);
        // |G| = 1 where |e^{jθ} − 0.5| = 0.5: never (|·| ≥ 0.5, = 0.5 only at θ = 0)
        assert!(m.gain_crossings.is_empty());
    }

    #[test]
    fn integrator_loop_phase_margin_closed_form() {
        // L = K T/(z − 1) (a sampled integrator): |L| = 1 at 2 sin(θ/2) = KT; φ = −90° − θ/2,
        // so PM = 90° − θc/2
        let (k, dt) = (2.0, 0.1);
        let m = margins(&zf(&[k * dt], &[1.0, -1.0], dt), dt).unwrap();
        let th = 2.0 * (k * dt / 2.0f64).asin();
        assert!((m.gain_crossover.unwrap() - th / dt).abs() < 1e-12, "{m:?}");
        assert!((m.phase_margin_deg.unwrap() - (90.0 - th.to_degrees() / 2.0)).abs() < 1e-10);
        // the closed loop z − 1 + KT is unstable for KT > 2: GM = 2/(KT) at θ = π
        assert!((m.gain_margin.unwrap() - 2.0 / (k * dt)).abs() < 1e-12);
    }
}
