//! The branches of a root locus: the roots of D + K·N at chosen gains, matched from one gain
//! to the next.
//!
//! # Method
//! Roots at one gain are the eigenvalues of the balanced companion matrix (the candidates of
//! [`crate::Poly::roots`], without the multiplicity resolution: at a break point the merged
//! roots are wanted as separate branch points) with exact zero roots deflated. Consecutive
//! gains are matched greedily by distance to each branch's linear prediction.
//!
//! Gains ([`trace`]): |K| = 0, a geometric grid from 10⁻⁹·K_end to K_end, and the gains of
//! the break points and crossings (so the drawn branches pass through them). A step is
//! subdivided (geometric mean) while some root moves more than [`MAX_STEP`] of the plot scale
//! (relative to |s| far out), up to the gain budget. K_end starts at 100× the largest
//! special gain (or the gain that moves roots by the plot scale) and grows ×100 until the
//! branches have reached their zeros or gone beyond 5× the plot scale.

use num_complex::Complex64;
use serde::Serialize;

use crate::error::{LtiError, Result};
use crate::poly::roots::candidates;
use crate::poly::{Poly, Root};

/// The largest move of a root between two traced gains, relative to the plot scale (or to
/// |s| beyond it): 1/40 gives smooth curves at plot resolution.
pub const MAX_STEP: f64 = 0.025;

/// Total work budget of one trace, in n³ units (companion QR is ~10n³ flops per gain, ~3 ms
/// at n = 100 on a 2.6 GHz core): an order-10 locus gets the gain cap, order 50 ~1 200
/// gains, order 100 150, order 200 the floor of 32 — about half a second at most.
const WORK_BUDGET: f64 = 1.5e8;

/// The traced branches.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Branches {
    /// The gains K, increasing in |K| (0 first).
    pub gains: Vec<f64>,
    /// One branch per closed-loop pole: its position at each gain.
    #[serde(rename = "branches")]
    pub paths: Vec<Vec<Complex64>>,
}

/// The roots of D + K·N (with repetition, unordered).
///
/// ```
/// use ltikit::Poly;
/// use ltikit::analysis::rlocus::locus_roots;
/// // s² + 2s + K at K = 1: a double root at −1 (here as two close roots).
/// let r = locus_roots(&Poly::from_descending(&[1.0]).unwrap(),
///     &Poly::from_descending(&[1.0, 2.0, 0.0]).unwrap(), 1.0).unwrap();
/// assert_eq!(r.len(), 2);
/// assert!(r.iter().all(|z| (z + 1.0).norm() < 1e-7));
/// ```
pub fn locus_roots(num: &Poly, den: &Poly, k: f64) -> Result<Vec<Complex64>> {
    let q = den + &num.scale(k);
    if q.is_zero() {
        return Err(LtiError::invalid(format!(
            "D + K·N vanishes identically at K = {k}"
        )));
    }
    let n = q.degree();
    let k0 = q.zero_root_multiplicity();
    let mut out = vec![Complex64::new(0.0, 0.0); k0];
    if n > k0 {
        let rest = Poly::from_descending(&q.coeffs()[..=n - k0])?;
        out.extend(candidates(&rest)?);
    }
    Ok(out)
}

/// Assigns `new` roots to branches: greedy by distance to each branch's prediction.
fn match_roots(pred: &[Complex64], new: &[Complex64]) -> Vec<Complex64> {
    let n = pred.len();
    let mut pairs: Vec<(f64, usize, usize)> = Vec::with_capacity(n * new.len());
    for (i, p) in pred.iter().enumerate() {
        for (j, z) in new.iter().enumerate() {
            pairs.push(((p - z).norm(), i, j));
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out = vec![Complex64::new(f64::NAN, f64::NAN); n];
    let mut used_i = vec![false; n];
    let mut used_j = vec![false; new.len()];
    for (_, i, j) in pairs {
        if !used_i[i] && !used_j[j] {
            used_i[i] = true;
            used_j[j] = true;
            out[i] = new[j];
        }
    }
    out
}

/// The branches at the given gains (sorted by |K|, all of one sign or zero), matched.
///
/// ```
/// use ltikit::Poly;
/// use ltikit::analysis::rlocus::trace_at_gains;
/// // 1/(s(s + 2)): s² + 2s + K; at K = 2 the roots are −1 ± j.
/// let b = trace_at_gains(&Poly::from_descending(&[1.0]).unwrap(),
///     &Poly::from_descending(&[1.0, 2.0, 0.0]).unwrap(), &[0.0, 0.5, 2.0]).unwrap();
/// assert_eq!(b.paths.len(), 2);
/// assert!(b.paths.iter().any(|p| (p[2] - num_complex::Complex64::new(-1.0, 1.0)).norm() < 1e-14));
/// ```
pub fn trace_at_gains(num: &Poly, den: &Poly, gains: &[f64]) -> Result<Branches> {
    let mut t = Tracer::default();
    for &k in gains {
        let r = locus_roots(num, den, k)?;
        t.push(k, r)?;
    }
    t.finish(den.degree())
}

/// The gains and matched roots so far.
#[derive(Default)]
struct Tracer {
    gains: Vec<f64>,
    /// Roots per gain, in branch order.
    rows: Vec<Vec<Complex64>>,
}

impl Tracer {
    /// Each branch's predicted position at `k` (linear in K from the last two gains).
    fn predict(&self, k: f64) -> Vec<Complex64> {
        let Some(last) = self.rows.last() else {
            return Vec::new();
        };
        let m = self.rows.len();
        if m < 2 {
            return last.clone();
        }
        let (ka, kp) = (self.gains[m - 1], self.gains[m - 2]);
        // gains are strictly increasing in |K|: ka − kp ≠ 0 (a non-finite ratio predicts no move)
        let f = ((k - ka) / (ka - kp)).clamp(0.0, 1.0);
        let f = if f.is_finite() { f } else { 0.0 };
        last.iter()
            .zip(&self.rows[m - 2])
            .map(|(a, p)| a + (a - p) * f)
            .collect()
    }

    /// The roots `r` at `k`, matched to the branches.
    fn matched(&self, k: f64, r: &[Complex64]) -> Vec<Complex64> {
        if self.rows.is_empty() {
            return r.to_vec();
        }
        match_roots(&self.predict(k), r)
    }

    fn push(&mut self, k: f64, r: Vec<Complex64>) -> Result<()> {
        if let Some(last) = self.rows.last() {
            if last.len() != r.len() {
                return Err(LtiError::invalid(format!(
                    "D + K·N changes degree at K = {k}: pick gains away from it"
                )));
            }
        }
        let row = self.matched(k, &r);
        self.gains.push(k);
        self.rows.push(row);
        Ok(())
    }

    fn finish(self, n: usize) -> Result<Branches> {
        let width = self.rows.first().map_or(n, Vec::len);
        let mut paths = vec![Vec::with_capacity(self.gains.len()); width];
        for row in &self.rows {
            for (p, z) in paths.iter_mut().zip(row) {
                p.push(*z);
            }
        }
        Ok(Branches {
            gains: self.gains,
            paths,
        })
    }
}

/// What the adaptive trace needs from the locus features.
pub(super) struct Plan<'a> {
    /// +1 for K ≥ 0, −1 for K ≤ 0.
    pub sign: f64,
    /// Gains at break points and crossings (with the locus's sign).
    pub special: &'a [f64],
    /// The gain at which a branch leaves through infinity (deg N = deg D), to be avoided.
    pub escape_gain: Option<f64>,
    /// Points that set the plot scale (poles, zeros, break points, crossings, centroid).
    pub scale_points: &'a [Complex64],
    /// The open-loop poles (the branches at K = 0, with their exact multiplicities).
    pub poles: &'a [Root],
    /// The finite zeros (branch ends).
    pub zeros: &'a [Root],
    /// Gain cap.
    pub max_gains: usize,
}

/// The adaptive trace (see the module docs).
pub(super) fn trace(num: &Poly, den: &Poly, plan: &Plan) -> Result<Branches> {
    let n = den.degree().max(1) as f64;
    let budget = plan
        .max_gains
        .min((WORK_BUDGET / (n * n * n)).max(32.0) as usize);
    let scale = plan
        .scale_points
        .iter()
        .map(|z| z.norm())
        .filter(|x| x.is_finite())
        .fold(0.0, f64::max);
    let scale = if scale > 0.0 { scale } else { 1.0 };
    // the gain that moves roots by about the plot scale: |D/N| at s = j·scale
    let probe = Complex64::new(0.0, scale);
    let k_ref = (den.eval_complex(probe) / num.eval_complex(probe)).norm();
    let k_special = plan
        .special
        .iter()
        .map(|k| k.abs())
        .chain(plan.escape_gain.map(f64::abs))
        .fold(0.0, f64::max);
    let mut k_end = 100.0 * k_special.max(k_ref);
    if !(k_end.is_finite() && k_end > 0.0) {
        k_end = 1.0;
    }
    let avoid = |k: f64| {
        plan.escape_gain
            .is_some_and(|e| (k.abs() - e.abs()).abs() <= 1e-9 * e.abs())
    };
    let first = (budget / 3).clamp(8, 48);
    let mut targets: Vec<f64> = (0..first)
        .map(|i| k_end * 10f64.powf(-9.0 + 9.0 * i as f64 / (first - 1) as f64))
        .chain(plan.special.iter().map(|k| k.abs()))
        .filter(|k| k.is_finite() && *k > 0.0 && !avoid(*k))
        .collect();
    let mut t = Tracer::default();
    // K = 0: the poles themselves (a multiple pole as one point, not scattered by rounding)
    t.push(0.0, crate::poly::roots::flatten(plan.poles))?;
    for _ in 0..6 {
        targets.sort_by(f64::total_cmp);
        targets.dedup();
        let room = budget.saturating_sub(t.gains.len());
        run(num, den, plan.sign, scale, &mut t, &targets, room)?;
        if done(&t, scale, plan.zeros) || t.gains.len() >= budget {
            break;
        }
        let k0 = k_end;
        k_end *= 100.0;
        targets = (1..=16)
            .map(|i| k0 * 100f64.powf(i as f64 / 16.0))
            .filter(|k| k.is_finite() && !avoid(*k))
            .collect();
    }
    let mut b = t.finish(den.degree())?;
    for k in &mut b.gains {
        *k *= plan.sign;
    }
    Ok(b)
}

/// Traces to each target |K| in turn, subdividing steps that move a root too far.
fn run(
    num: &Poly,
    den: &Poly,
    sign: f64,
    scale: f64,
    t: &mut Tracer,
    targets: &[f64],
    room: usize,
) -> Result<()> {
    let mut pending: Vec<(f64, Option<Vec<Complex64>>)> =
        targets.iter().rev().map(|k| (*k, None)).collect();
    let start = t.gains.len();
    while let Some((kb, cached)) = pending.pop() {
        if t.gains.len() - start >= room {
            break;
        }
        let ka = t.gains.last().copied().unwrap_or(0.0);
        if kb <= ka {
            continue;
        }
        let rb = match cached {
            Some(r) => r,
            None => locus_roots(num, den, sign * kb)?,
        };
        let row = t.matched(kb, &rb);
        let last = t.rows.last().cloned().unwrap_or_default();
        if row.len() != last.len() {
            // the degree drops exactly here: skip this gain
            continue;
        }
        let moved = last
            .iter()
            .zip(&row)
            .map(|(a, b)| (a - b).norm() / scale.max(a.norm().min(b.norm())))
            .fold(0.0, f64::max);
        let used = t.gains.len() - start + pending.len();
        // the geometric mean in logarithms (ka·kb can underflow or overflow); a step that
        // cannot be split inside (ka, kb) is taken as it is
        let mid = if ka > 0.0 {
            (0.5 * (ka.ln() + kb.ln())).exp()
        } else {
            kb / 16.0
        };
        let splittable = mid > ka && mid < kb && kb - ka > 1e-12 * kb;
        if moved > MAX_STEP && used + 2 < room && splittable {
            pending.push((kb, Some(rb)));
            pending.push((mid, None));
            continue;
        }
        t.gains.push(kb);
        t.rows.push(row);
    }
    Ok(())
}

/// True when every branch has reached a zero (within [`MAX_STEP`] of the scale) or gone
/// beyond 5× the scale.
fn done(t: &Tracer, scale: f64, zeros: &[Root]) -> bool {
    let Some(last) = t.rows.last() else {
        return true;
    };
    last.iter().all(|z| {
        z.norm() > 5.0 * scale
            || zeros
                .iter()
                .any(|r| (z - r.value).norm() <= MAX_STEP * scale)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matching_follows_the_prediction() {
        let pred = [Complex64::new(0.0, 1.0), Complex64::new(0.0, -1.0)];
        let new = [Complex64::new(0.1, -1.0), Complex64::new(0.1, 1.0)];
        let m = match_roots(&pred, &new);
        assert_eq!(m, vec![new[1], new[0]]);
    }
}
