//! The delayed Nyquist criterion: the unstable roots of D(s) + N(s)·e^(−sT) counted by the
//! argument principle on F(s) = 1 + L(s)·e^(−sT) = Δ(s)/D(s), independently of the crossing
//! frequencies — a cross-check of [`super::DelayStability::unstable_roots_at`].

use num_complex::Complex64;

use super::parts::DelayedLoop;
use super::stability::check_delay;
use crate::analysis::factored::Factored;
use crate::error::{LtiError, Result};

/// Most evaluations of F along the contour.
const MAX_EVALUATIONS: usize = 4_000_000;

impl Factored {
    /// The number of characteristic roots of D(s) + N(s)·e^(−sT) with Re s > σ, σ = 10⁻⁹
    /// times the largest root magnitude of L (so roots on the imaginary axis are not
    /// counted), by the argument principle: along the line Re s = σ from ω = 0 to a radius Ω
    /// beyond which |L| < (1 + |L(∞)|)/2 on the right half circle, the continuous change of
    /// arg F(σ + jω), F = 1 + L·e^(−sT), gives Z = P − (Δarg F − arg F(σ + jΩ))/π with P the
    /// poles of L right of the line. An independent check of
    /// [`super::DelayStability::unstable_roots_at`] (the delayed Nyquist criterion).
    ///
    /// Errors: those of [`Factored::delay_stability`]; a delay so long, or a loop so wide,
    /// that the contour needs more than four million evaluations.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // 2/(s + 1) with T = 1.5 > 2π/(3√3) ≈ 1.21: one unstable pair
    /// let f = TransferFunction::from_descending(&[2.0], &[1.0, 1.0]).unwrap().factored().unwrap();
    /// assert_eq!(f.delayed_nyquist_count(1.5).unwrap(), 2);
    /// assert_eq!(f.delayed_nyquist_count(1.0).unwrap(), 0);
    /// ```
    pub fn delayed_nyquist_count(&self, delay: f64) -> Result<usize> {
        let t = check_delay(delay)?;
        let l = DelayedLoop::new(self, "the delayed Nyquist count")?;
        winding_count(&l, t)
    }
}

fn winding_count(l: &DelayedLoop, t: f64) -> Result<usize> {
    let scale = l
        .poles
        .iter()
        .chain(&l.zeros)
        .map(|r| r.norm())
        .fold(0.0_f64, f64::max)
        .max(l.gain.abs().powf(1.0 / (l.poles.len().max(1) as f64)))
        .max(f64::MIN_POSITIVE.sqrt());
    let sigma = 1e-9 * scale;
    let f = |w: f64| -> Complex64 {
        let s = Complex64::new(sigma, w);
        Complex64::new(1.0, 0.0) + (l.log_loop(s) - s * t).exp()
    };
    // the radius: |L| small enough on the right half circle
    let bound = 0.5 * (1.0 + l.at_infinity().map_or(0.0, f64::abs));
    let loop_at = |s: Complex64| l.log_loop(s).re.exp();
    let mut omega = 4.0 * scale;
    let mut tries = 0;
    while (0..=32).any(|i| {
        let phi = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * f64::from(i) / 32.0;
        loop_at(Complex64::from_polar(omega, phi) + sigma) >= bound
    }) {
        omega *= 2.0;
        tries += 1;
        if tries > 200 {
            return Err(LtiError::invalid(
                "the delayed Nyquist count: no radius found beyond which |L| < 1",
            ));
        }
    }
    // the grid: uniform in ω (e^(−jωT) turns by ≤ π/8 per step) and 200 points a decade
    let uniform = if t > 0.0 {
        (omega * t / (std::f64::consts::PI / 8.0)).ceil()
    } else {
        0.0
    };
    if uniform > MAX_EVALUATIONS as f64 / 4.0 {
        return Err(LtiError::LimitExceeded {
            field: "`delay`".into(),
            value: uniform as u128,
            max: (MAX_EVALUATIONS / 4) as u64,
            unit: "contour steps".into(),
            limit: "the delayed Nyquist contour".into(),
        });
    }
    let mut grid: Vec<f64> = (0..=uniform as usize)
        .map(|i| omega * i as f64 / uniform.max(1.0))
        .collect();
    let low = omega * 1e-12;
    let decades = (omega / low).log10();
    let m = (200.0 * decades).ceil() as usize;
    grid.extend((0..=m).map(|i| low * 10f64.powf(decades * i as f64 / m as f64)));
    for r in l.poles.iter().chain(&l.zeros) {
        let w = r.im.abs();
        if w > 0.0 && w < omega {
            let d = r.re.abs().max(1e-6 * w);
            grid.extend(
                (-8..=8)
                    .map(|i| w + d * f64::from(i) / 2.0)
                    .filter(|&x| x > 0.0),
            );
        }
    }
    grid.push(0.0);
    grid.push(omega);
    grid.retain(|&w| (0.0..=omega).contains(&w));
    grid.sort_by(f64::total_cmp);
    grid.dedup();
    // continuous change of arg F along the grid, each step subdivided until it turns < π/4
    let mut evaluations = grid.len();
    let mut change = 0.0;
    let mut prev = f(grid[0]);
    for pair in grid.windows(2) {
        let mut stack = vec![(pair[0], pair[1])];
        let mut a_val = prev;
        // depth-first from the left end: the pieces are taken in order
        while let Some((a, b)) = stack.pop() {
            let fb = f(b);
            evaluations += 1;
            let d = (fb / a_val).arg();
            if d.abs() > std::f64::consts::FRAC_PI_4 && b - a > 4.0 * f64::EPSILON * b {
                let mid = 0.5 * (a + b);
                stack.push((mid, b));
                stack.push((a, mid));
                continue;
            }
            change += d;
            a_val = fb;
            if evaluations > MAX_EVALUATIONS {
                return Err(LtiError::invalid(
                    "the delayed Nyquist count: the contour needs more than four million evaluations",
                ));
            }
        }
        prev = a_val;
    }
    let end = f(omega).arg();
    let open_loop_unstable = l.poles.iter().filter(|p| p.re > sigma).count() as f64;
    let z = open_loop_unstable - (change - end) / std::f64::consts::PI;
    let rounded = z.round();
    if (z - rounded).abs() > 0.1 || rounded < 0.0 {
        return Err(LtiError::invalid(format!(
            "the delayed Nyquist count: the winding number {z} is not an integer (the contour passes too close to a root)"
        )));
    }
    Ok(rounded as usize)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::poly::Root;

    /// A small linear congruential generator: the loops are the same on every run.
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn range(&mut self, a: f64, b: f64) -> f64 {
            a + (b - a) * self.next()
        }
    }

    fn random_loop(g: &mut Lcg) -> Factored {
        let c = |re: f64, im: f64| Complex64::new(re, im);
        let mut poles = Vec::new();
        let n = 1 + (g.next() * 4.0) as usize;
        while poles.len() < n {
            if g.next() < 0.5 {
                poles.push(Root::new(c(g.range(-3.0, 0.5), 0.0), 1));
            } else {
                let (re, im) = (g.range(-2.0, 0.3), g.range(0.2, 3.0));
                poles.push(Root::new(c(re, im), 1));
                poles.push(Root::new(c(re, -im), 1));
            }
        }
        let mut zeros = Vec::new();
        if g.next() < 0.5 && poles.len() > 1 {
            zeros.push(Root::new(c(g.range(-4.0, 2.0), 0.0), 1));
        }
        let k = g.range(-6.0, 6.0);
        Factored::from_zpk(&zeros, &poles, k).unwrap()
    }

    #[test]
    fn the_argument_principle_agrees_with_the_crossing_count_on_random_loops() {
        let mut g = Lcg(21);
        let mut checked = 0;
        let mut unstable_seen = 0;
        let mut stable_seen = 0;
        for _ in 0..40 {
            let f = random_loop(&mut g);
            let d = f.delay_stability().unwrap();
            for t in [0.0, 0.05, 0.3, 1.0, 2.5, 7.0] {
                // away from a crossing delay: the pair would sit on the contour
                let near = d
                    .crossings
                    .iter()
                    .any(|c| (0..200).any(|k| (c.delay(k) - t).abs() <= 1e-3 * t.max(1e-3)));
                if near {
                    continue;
                }
                let by_crossings = d.unstable_roots_at(t).unwrap();
                let by_winding = f.delayed_nyquist_count(t).unwrap();
                assert_eq!(by_crossings, by_winding, "{f:?} at T = {t}: {d:?}");
                // and the root search finds as many unstable roots, each to its rounding
                let r = f.closed_loop_delay_roots(t, 4).unwrap();
                assert!(r.agrees, "{f:?} at T = {t}: {r:?}");
                assert!(
                    r.roots.iter().all(|q| q.relative_residual <= 1e-12),
                    "{r:?}"
                );
                checked += 1;
                if by_crossings == 0 {
                    stable_seen += 1;
                } else {
                    unstable_seen += 1;
                }
            }
        }
        assert!(checked > 150, "{checked}");
        assert!(
            stable_seen > 20 && unstable_seen > 20,
            "{stable_seen} {unstable_seen}"
        );
    }
}
