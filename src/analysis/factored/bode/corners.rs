//! The frequency scales of a factored form: corner frequencies, lightly damped pairs, the
//! decade range of the automatic grids and a sampling grid for sign-change searches.

use super::form::BodeForm;

impl BodeForm {
    /// Corner frequencies |p| of every non-zero reduced pole and zero (with repetition).
    pub fn corner_frequencies(&self) -> Vec<f64> {
        let mut out = Vec::new();
        for s in [&self.num, &self.den] {
            out.extend(s.real_p.iter().map(|p| p.abs()));
            out.extend(s.quad.iter().map(|q| q.r));
            out.extend(s.axis.iter().copied());
        }
        out
    }

    /// Lightly damped pairs (ζ < `zeta_max`, including undamped ones with ζ = 0) of the
    /// numerator and denominator, as (ωn, ζ).
    pub fn light_pairs(&self, zeta_max: f64) -> Vec<(f64, f64)> {
        let mut out = Vec::new();
        for s in [&self.num, &self.den] {
            out.extend(s.axis.iter().map(|&b| (b, 0.0)));
            out.extend(
                s.quad
                    .iter()
                    .map(|q| (q.r, q.sn.abs()))
                    .filter(|&(_, z)| z < zeta_max),
            );
        }
        out
    }

    /// The plotting range: two decades below the smallest corner frequency and above the
    /// largest, rounded out to whole decades; 0.01…100 rad/s without corners. Returned as
    /// (log₁₀ ω_min, log₁₀ ω_max).
    pub fn decade_range(&self) -> (f64, f64) {
        let c = self.corner_frequencies();
        let lo = c.iter().copied().reduce(f64::min);
        let hi = c.iter().copied().reduce(f64::max);
        match (lo, hi) {
            (Some(lo), Some(hi)) => (
                (lo.log10() - 2.0).floor().max(-300.0),
                (hi.log10() + 2.0).ceil().min(300.0),
            ),
            _ => (-2.0, 2.0),
        }
    }

    /// A dense sampling grid for bracketing: `per_decade` log-spaced points per decade over
    /// [`BodeForm::decade_range`] plus points around every lightly damped pair within a
    /// few bandwidths ζ·ωn of ωn. Sorted, unique, finite, positive.
    pub fn sampling_grid(&self, per_decade: usize) -> Vec<f64> {
        let (a, b) = self.decade_range();
        let n = ((b - a) * per_decade as f64).ceil().max(1.0) as usize;
        let mut xs: Vec<f64> = (0..=n)
            .map(|i| 10f64.powf(a + (b - a) * i as f64 / n as f64))
            .collect();
        for (wn, z) in self.light_pairs(0.5) {
            let z = z.max(1e-6);
            for k in -40..=40 {
                let x = wn * (1.0 + 0.25 * z * k as f64);
                if x > 0.0 {
                    xs.push(x);
                }
            }
        }
        xs.retain(|x| x.is_finite() && *x > 0.0);
        xs.sort_by(f64::total_cmp);
        xs.dedup();
        xs
    }
}
