//! y′(t) of a closed form on the bracketing grid, without transcendental functions per point.
//!
//! Every transient term is e^(σt)·Σₖ Aₖ tᵏ cos(ωt + φₖ) (ω = 0, φ = 0 for a real pole), so
//! its derivative needs z(t) = e^(σt)·e^(jωt) only. Along a grid of constant spacing h,
//! z(t + h) = z(t)·e^((σ + jω)h): one complex multiplication per term and point instead of
//! an `exp` and a `sincos`. z is recomputed exactly every [`RESYNC`] steps and whenever the
//! spacing changes, so the recurrence's rounding stays below ~1e-14 relative. Grid values
//! are used only for their signs (which interval brackets a critical point); a value within
//! [`UNSURE_REL`] of zero relative to the size of its terms is recomputed by the exact
//! closed form, so no sign is ever decided by the recurrence's rounding. The critical points
//! themselves are refined by Brent's method on the exact closed form.

use num_complex::Complex64;

use crate::analysis::closed_form::ClosedFormTerm;

/// Steps between exact recomputations of z(t).
const RESYNC: usize = 32;

/// A grid value |y′| ≤ UNSURE_REL·Σ|parts| is recomputed exactly (the recurrence is good
/// to ~1e-14 relative, so larger values have the right sign).
const UNSURE_REL: f64 = 1e-9;

struct Mode {
    sigma: f64,
    omega: f64,
    amps: Vec<f64>,
    /// cos φₖ and sin φₖ.
    cphi: Vec<f64>,
    sphi: Vec<f64>,
    /// |p|: the rate that sets the grid spacing while the mode is alive.
    rate: f64,
    /// The envelope decreases after this time.
    t_max: f64,
    /// e^(σt)·e^(jωt) at the current grid time.
    z: Complex64,
    /// e^((σ + jω)h) for the current spacing h.
    step: Complex64,
}

/// Transient terms advanced along the grid.
pub(super) struct GridDerivative {
    modes: Vec<Mode>,
    t: f64,
    h: f64,
    since_sync: usize,
}

/// The rate |p| of a term and the time after which its envelope decreases (k/|σ| for the
/// highest power k of t; 0 for a term that does not decay).
pub(super) fn mode_scales(t: &ClosedFormTerm) -> (f64, f64) {
    let p = t.pole().unwrap_or_default();
    let k = t.max_power() as f64;
    (p.norm(), if p.re < 0.0 { k / -p.re } else { 0.0 })
}

fn exact_z(sigma: f64, omega: f64, t: f64) -> Complex64 {
    let m = (sigma * t).exp();
    if omega == 0.0 {
        Complex64::new(m, 0.0)
    } else {
        let (s, c) = (omega * t).sin_cos();
        Complex64::new(m * c, m * s)
    }
}

impl GridDerivative {
    /// The grid state at time `t0` for the transient `terms` (impulse terms are ignored).
    pub(super) fn new(terms: &[ClosedFormTerm], t0: f64) -> GridDerivative {
        let modes = terms
            .iter()
            .filter_map(|t| {
                let (sigma, omega, amps, phases): (f64, f64, Vec<f64>, Vec<f64>) = match t {
                    ClosedFormTerm::Impulse { .. } => return None,
                    ClosedFormTerm::Real { pole, coefficients } => (
                        *pole,
                        0.0,
                        coefficients.clone(),
                        vec![0.0; coefficients.len()],
                    ),
                    ClosedFormTerm::Oscillatory {
                        sigma,
                        omega,
                        amplitudes,
                        phases,
                    } => (*sigma, *omega, amplitudes.clone(), phases.clone()),
                };
                let (rate, t_max) = mode_scales(t);
                Some(Mode {
                    sigma,
                    omega,
                    cphi: phases.iter().map(|p| p.cos()).collect(),
                    sphi: phases.iter().map(|p| p.sin()).collect(),
                    amps,
                    rate,
                    t_max,
                    z: exact_z(sigma, omega, t0),
                    step: Complex64::new(1.0, 0.0),
                })
            })
            .collect();
        GridDerivative {
            modes,
            t: t0,
            h: 0.0,
            since_sync: 0,
        }
    }

    /// Indices of the modes by decreasing rate.
    pub(super) fn by_rate(&self) -> Vec<usize> {
        let mut order: Vec<usize> = (0..self.modes.len()).collect();
        order.sort_by(|&a, &b| self.modes[b].rate.total_cmp(&self.modes[a].rate));
        order
    }

    /// Rate |p| of mode `k`.
    pub(super) fn rate(&self, k: usize) -> f64 {
        self.modes[k].rate
    }

    /// Whether mode `k` is alive at the current grid time: before the peak of its envelope,
    /// or with its envelope Σ|Aₖ|tᵏe^(σt) above `dead`.
    pub(super) fn alive(&self, k: usize, dead: f64) -> bool {
        let m = &self.modes[k];
        if self.t <= m.t_max {
            return true;
        }
        let t = self.t.abs();
        let poly = m.amps.iter().rev().fold(0.0, |acc, &x| acc * t + x.abs());
        poly * m.z.norm() > dead
    }

    fn sync(&mut self, t: f64) {
        for m in &mut self.modes {
            m.z = exact_z(m.sigma, m.omega, t);
        }
        self.t = t;
        self.since_sync = 0;
    }

    /// Moves to `u` = (current t) + `h`, or to `u` < t + h when the step is `clipped` at the
    /// end of the interval, and returns y′(u), exact in sign: values too close to zero for the
    /// recurrence come from `exact`.
    pub(super) fn advance(
        &mut self,
        u: f64,
        h: f64,
        clipped: bool,
        exact: &impl Fn(f64) -> f64,
    ) -> f64 {
        if clipped || self.since_sync + 1 >= RESYNC {
            self.sync(u);
        } else {
            if h.to_bits() != self.h.to_bits() {
                for m in &mut self.modes {
                    m.step = exact_z(m.sigma, m.omega, h);
                }
                self.h = h;
            }
            for m in &mut self.modes {
                m.z *= m.step;
            }
            self.t = u;
            self.since_sync += 1;
        }
        let (v, size) = self.value();
        if v.abs() <= UNSURE_REL * size || !v.is_finite() {
            exact(u)
        } else {
            v
        }
    }

    /// y′ at the current time and Σ|parts| (the scale its rounding is relative to).
    fn value(&self) -> (f64, f64) {
        let t = self.t;
        let (mut v, mut size) = (0.0, 0.0);
        for m in &self.modes {
            let (zr, zi) = (m.z.re, m.z.im);
            let zn = zr.abs() + zi.abs();
            let (mut tk, mut tkm1) = (1.0, 0.0);
            for (k, &a) in m.amps.iter().enumerate() {
                // e^(σt)cos(ωt + φ) and e^(σt)sin(ωt + φ)
                let c = m.cphi[k] * zr - m.sphi[k] * zi;
                let s = m.cphi[k] * zi + m.sphi[k] * zr;
                let dp = k as f64 * tkm1 + m.sigma * tk;
                v += a * (dp * c - m.omega * tk * s);
                size += a.abs() * (dp.abs() + m.omega * tk) * zn;
                tkm1 = tk;
                tk *= t;
            }
        }
        (v, size)
    }
}
