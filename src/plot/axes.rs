//! Axes: tick choice (1-2-2.5-5 steps, multiples of 45°/90° for phase, decades for log ω),
//! tick labels with a common ×10^k factor for tiny or huge values.

use super::raster::Canvas;
use super::text::{cap_height, descent};

/// Linear or base-10 logarithmic axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Scale {
    Linear,
    Log10,
}

/// A labelled tick.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Tick {
    pub v: f64,
    pub label: String,
}

/// One axis: range, scale, ticks.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Axis {
    pub lo: f64,
    pub hi: f64,
    pub scale: Scale,
    pub ticks: Vec<Tick>,
    pub minor: Vec<f64>,
    /// Common factor of the tick labels, e.g. "×10^{-6}".
    pub factor: Option<String>,
}

/// Replaces an ASCII minus with the typographic one and removes "−0".
pub(crate) fn typographic(s: String) -> String {
    let t = s.replace('-', "−");
    if t.trim_start_matches('−')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        t.trim_start_matches('−').to_string()
    } else {
        t
    }
}

/// Number of decimals needed to print multiples of `step` exactly (up to 10).
fn decimals_for(step: f64) -> usize {
    (0..=10)
        .find(|&d| {
            let x = step * 10f64.powi(d as i32);
            (x - x.round()).abs() < 1e-6 * x.abs().max(1.0)
        })
        .unwrap_or(10)
}

/// A "nice" step (1, 2, 2.5, 5 × 10^k) giving at most `max_ticks` intervals over `span`.
pub(crate) fn nice_step(span: f64, max_ticks: usize) -> f64 {
    nice_step_from(span, max_ticks, &[1.0, 2.0, 2.5, 5.0, 10.0])
}

/// The smallest step m × 10^k (m from `mults`, ascending, ending with 10) giving at most
/// `max_ticks` intervals over `span`.
pub(crate) fn nice_step_from(span: f64, max_ticks: usize, mults: &[f64]) -> f64 {
    let raw = span / max_ticks.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    for &m in mults {
        if m * mag >= raw * (1.0 - 1e-9) {
            return m * mag;
        }
    }
    10.0 * mag
}

/// Widens a degenerate range [v, v].
pub(crate) fn widen(lo: f64, hi: f64) -> (f64, f64) {
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
    let size = lo.abs().max(hi.abs());
    if hi - lo > 1e-9 * size && hi - lo > 1e-300 {
        (lo, hi)
    } else if size > 0.0 {
        (lo - 0.1 * size, hi + 0.1 * size)
    } else {
        (-1.0, 1.0)
    }
}

impl Axis {
    /// Axis coordinate of a data value (log10 on a log axis; NaN for v ≤ 0 there).
    pub fn t(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Linear => v,
            Scale::Log10 => {
                if v > 0.0 {
                    v.log10()
                } else {
                    f64::NAN
                }
            }
        }
    }

    /// A linear axis over [lo, hi] with at most `max_ticks` intervals; `tight` keeps the limits,
    /// otherwise they are rounded outwards to ticks.
    pub fn linear(lo: f64, hi: f64, max_ticks: usize, tight: bool) -> Axis {
        Self::linear_from(lo, hi, max_ticks, tight, &[1.0, 2.0, 2.5, 5.0, 10.0])
    }

    /// [`Axis::linear`] with steps m × 10^k for m in `mults` (e.g. no 2.5 for decibels).
    pub fn linear_from(lo: f64, hi: f64, max_ticks: usize, tight: bool, mults: &[f64]) -> Axis {
        let (lo, hi) = widen(lo, hi);
        let step = nice_step_from(hi - lo, max_ticks, mults);
        let (lo, hi) = if tight {
            (lo, hi)
        } else {
            // Round a limit out to the next tick only when that costs little room.
            let span = hi - lo;
            let rlo = (lo / step + 1e-9).floor() * step;
            let rhi = (hi / step - 1e-9).ceil() * step;
            (
                if lo - rlo <= 0.06 * span { rlo } else { lo },
                if rhi - hi <= 0.06 * span { rhi } else { hi },
            )
        };
        Self::with_step(lo, hi, step)
    }

    /// A linear axis over [lo, hi] with ticks at the multiples of `step` inside it.
    pub fn with_step(lo: f64, hi: f64, step: f64) -> Axis {
        let amax = lo.abs().max(hi.abs());
        let exp = if amax >= 1e5 || (amax > 0.0 && amax < 1e-2) {
            let e = amax.log10().floor() as i32;
            3 * e.div_euclid(3)
        } else {
            0
        };
        let unit = 10f64.powi(exp);
        let d = decimals_for(step / unit);
        let k0 = (lo / step - 1e-9).ceil() as i64;
        let k1 = (hi / step + 1e-9).floor() as i64;
        let ticks = (k0..=k1.min(k0 + 200))
            .map(|k| {
                let v = k as f64 * step;
                Tick {
                    v,
                    label: typographic(format!("{:.*}", d, v / unit)),
                }
            })
            .collect();
        Axis {
            lo,
            hi,
            scale: Scale::Linear,
            ticks,
            minor: vec![],
            factor: (exp != 0).then(|| format!("×10^{{{exp}}}")),
        }
    }

    /// A phase axis in degrees: limits rounded out to, and ticks at, multiples of 45°, 90°,
    /// 180° or 360° (at most `max_ticks` intervals).
    pub fn degrees(lo: f64, hi: f64, max_ticks: usize) -> Axis {
        // Absurd ranges (a corrupt phase) get a plain linear axis.
        if !(hi - lo).is_finite() || hi - lo > 2880.0 * max_ticks.max(1) as f64 {
            return Self::linear(lo, hi, max_ticks, false);
        }
        let (lo, hi) = if hi - lo < 1e-6 {
            (lo - 1.0, hi + 1.0)
        } else {
            (lo, hi)
        };
        // A little room so that a curve at a multiple of the step does not sit on the frame.
        let pad = 0.02 * (hi - lo).max(45.0);
        let (lo, hi) = (lo - pad, hi + pad);
        let mut step = 45.0;
        for s in [45.0, 90.0, 180.0, 360.0, 720.0, 1440.0, 2880.0] {
            step = s;
            let n = ((hi / s - 1e-9).ceil() - (lo / s + 1e-9).floor()) as usize;
            if n <= max_ticks {
                break;
            }
        }
        // Limits at multiples of half the tick step (45° when ticks are every 90°).
        let unit = if step > 45.0 { step / 2.0 } else { step };
        let lo = (lo / unit + 1e-9).floor() * unit;
        let hi = (hi / unit - 1e-9).ceil() * unit;
        let mut a = Self::with_step(lo, hi, step);
        // Half-steps as minor grid lines (every 45° when labelled every 90°).
        if step > 45.0 {
            let half = step / 2.0;
            let k0 = (lo / half).round() as i64;
            let k1 = (hi / half).round() as i64;
            a.minor = (k0..=k1.min(k0 + 400))
                .filter(|k| k % 2 != 0)
                .map(|k| k as f64 * half)
                .collect();
        }
        a
    }

    /// A log axis over [lo, hi] (both > 0): ticks at decades labelled 10^k, minor grid at
    /// 2…9 × 10^k; over less than about a decade, ticks at 1, 2, 5 × 10^k with plain labels.
    pub fn log(lo: f64, hi: f64, max_ticks: usize) -> Axis {
        let (mut lo, mut hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        if lo.is_nan() || lo <= 0.0 || !hi.is_finite() {
            lo = 0.1;
            hi = 10.0;
        }
        if hi / lo < 1.0 + 1e-9 {
            lo /= 2.0;
            hi *= 2.0;
        }
        let (tlo, thi) = (lo.log10(), hi.log10());
        let d0 = (tlo - 1e-9).floor() as i64;
        let d1 = (thi + 1e-9).ceil() as i64;
        let within = |v: f64| v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9);
        let decades: Vec<i64> = (d0..=d1)
            .filter(|&k| within(10f64.powi(k as i32)))
            .collect();
        let mut ticks = Vec::new();
        let mut minor = Vec::new();
        if decades.len() >= 2 {
            // Labels every 1, 2, 5, 10, 20, 50, … decades; over many decades the grid marks
            // fifths of the labelled step instead of every decade (600 decades would grey the
            // whole panel).
            let need = decades.len().div_ceil(max_ticks.max(1)).max(1) as i64;
            let every = [1, 2, 5]
                .iter()
                .flat_map(|&m| (0..18).map(move |e| m * 10i64.pow(e)))
                .filter(|&s| s >= need)
                .min()
                .unwrap_or(need);
            let minor_every = if every <= 5 { 1 } else { every / 5 };
            for &k in &decades {
                let v = 10f64.powi(k as i32);
                if k.rem_euclid(every) == 0 {
                    ticks.push(Tick {
                        v,
                        label: format!("10^{{{k}}}"),
                    });
                } else if k.rem_euclid(minor_every) == 0 {
                    minor.push(v);
                }
            }
            if every == 1 && decades.len() <= 14 {
                for k in d0..=d1 {
                    for m in 2..=9 {
                        let v = f64::from(m) * 10f64.powi(k as i32);
                        if within(v) {
                            minor.push(v);
                        }
                    }
                }
            }
        } else {
            for mults in [
                &[1.0, 2.0, 5.0][..],
                &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0][..],
            ] {
                ticks.clear();
                minor.clear();
                for k in d0..=d1 {
                    let p = 10f64.powi(k as i32);
                    for m in 1..=9 {
                        let v = f64::from(m) * p;
                        if !within(v) {
                            continue;
                        }
                        if mults.contains(&f64::from(m)) {
                            ticks.push(Tick {
                                v,
                                label: typographic(crate::fmt::fmt_sig(v, 3)),
                            });
                        } else {
                            minor.push(v);
                        }
                    }
                }
                if ticks.len() >= 3 {
                    break;
                }
            }
        }
        Axis {
            lo,
            hi,
            scale: Scale::Log10,
            ticks,
            minor,
            factor: None,
        }
    }

    /// Widest tick label (px) at font size `size`.
    pub fn max_label_width(&self, size: f64) -> f64 {
        self.ticks
            .iter()
            .map(|t| Canvas::text_width(&t.label, size))
            .fold(0.0, f64::max)
    }

    /// Whether some tick label carries a superscript (decade labels 10^k).
    pub fn has_superscripts(&self) -> bool {
        self.ticks.iter().any(|t| t.label.contains('^'))
    }

    /// Height (px) of a row of these tick labels at font size `size`, with room for
    /// superscripts when a label has one.
    pub fn label_row_height(&self, size: f64) -> f64 {
        let base = cap_height(size) + descent(size);
        if self.has_superscripts() {
            base + 0.3 * size
        } else {
            base
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps() {
        assert!((nice_step(10.0, 5) - 2.0).abs() < 1e-12);
        assert!((nice_step(1.0, 4) - 0.25).abs() < 1e-12);
        assert!((nice_step(7.3, 8) - 1.0).abs() < 1e-12);
        // −0.13 rounds out to the tick −0.2 (cheap), 1.07 stays (1.2 would waste 11 %).
        let a = Axis::linear(-0.13, 1.07, 6, false);
        assert!((a.lo + 0.2).abs() < 1e-12 && (a.hi - 1.07).abs() < 1e-12);
        let labels: Vec<&str> = a.ticks.iter().map(|t| t.label.as_str()).collect();
        assert_eq!(labels, ["−0.2", "0.0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
        let a = Axis::linear(0.0, 0.97, 5, false);
        assert!((a.hi - 1.0).abs() < 1e-12);
    }

    #[test]
    fn factor_for_tiny_values() {
        let a = Axis::linear(0.0, 3.2e-6, 5, false);
        assert_eq!(a.factor.as_deref(), Some("×10^{-6}"));
        assert_eq!(a.ticks.last().unwrap().label, "3");
        assert!((a.hi - 3.2e-6).abs() < 1e-18);
    }

    #[test]
    fn phase_ticks_are_multiples_of_45_or_90() {
        let a = Axis::degrees(-270.0, -270.0, 8);
        assert!(a.ticks.iter().any(|t| (t.v + 270.0).abs() < 1e-9));
        let a = Axis::degrees(-180.0, 0.0, 8);
        assert!(a.ticks.iter().all(|t| (t.v / 45.0).fract().abs() < 1e-12));
        let a = Axis::degrees(-1000.0, 0.0, 8);
        assert!(a.ticks.iter().all(|t| (t.v / 90.0).fract().abs() < 1e-12));
        assert!(a.ticks.len() <= 9);
    }

    #[test]
    fn log_ticks_over_many_decades_are_round() {
        // 601 decades, at most 9 labels: every 100 decades, grid every 20.
        let a = Axis::log(1e-300, 1e300, 9);
        let labels: Vec<&str> = a.ticks.iter().map(|t| t.label.as_str()).collect();
        assert_eq!(
            labels,
            [
                "10^{-300}",
                "10^{-200}",
                "10^{-100}",
                "10^{0}",
                "10^{100}",
                "10^{200}",
                "10^{300}"
            ]
        );
        assert_eq!(a.minor.len(), 30 - 6);
        // 13 decades, at most 10 labels: every second decade, every decade in the grid.
        let a = Axis::log(1e-6, 1e6, 10);
        assert_eq!(a.ticks.len(), 7);
        assert_eq!(a.minor.len(), 6);
    }

    #[test]
    fn log_ticks_at_decades() {
        let a = Axis::log(0.01, 100.0, 10);
        let labels: Vec<&str> = a.ticks.iter().map(|t| t.label.as_str()).collect();
        assert_eq!(labels, ["10^{-2}", "10^{-1}", "10^{0}", "10^{1}", "10^{2}"]);
        assert_eq!(a.minor.len(), 4 * 8);
        let a = Axis::log(2.0, 9.0, 10);
        assert!(a.ticks.len() >= 3);
    }
}
