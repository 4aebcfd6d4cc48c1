//! The one time-marching skeleton of the exact responses: a state advanced through the
//! requested times in increasing order by a map built once per step length.
//!
//! Every exact response in ltikit — a transfer function's realisation, a state-space model
//! (dense, with held inputs), its modal form — is "times, a map for a step length, a step": the
//! map (e^(Ah), the Van Loan blocks, the modal factors) depends only on the step h, so one map
//! serves every step of an equally spaced grid, recognised to a few ulps of t. The marched time
//! is kept as base + k·h from the time the map was built, so it does not drift from the grid
//! over 10⁵ steps; values come back in the caller's order.

use crate::error::Result;

/// Two step lengths within this many ulps of the time are one step length.
const SAME_STEP_ULPS: f64 = 8.0;

/// Marches `state` from t = 0 through the times `t` (finite, ≥ 0, any order; equal times are
/// recorded once each): for each time in increasing order the state is advanced over the gap
/// to it by `step(&map, &mut state, from, to)` — `from` is the previous time asked for (0 at
/// the start) and `to` this one, as given (an input held between samples is looked up there) —
/// with `map` built by `map_for(h, tᵢ, run)` for each new step length h (tᵢ: the time the first
/// step with it reaches, for messages; `run`: how many consecutive steps of that length follow
/// in the sorted times, this one included — a caller may build a map that advances whole
/// blocks of a long run at once, see `analysis::ss::block_march`); then `record(i, tᵢ, &state)`
/// is called with the index of that time in `t`. (x(t) = e^(−t)·x(0) is `map_for` = e^(−h),
/// `step` x ← map·x; see the unit test.)
pub(crate) fn march<S, M>(
    t: &[f64],
    state: &mut S,
    mut map_for: impl FnMut(f64, f64, usize) -> Result<M>,
    mut step: impl FnMut(&M, &mut S, f64, f64) -> Result<()>,
    mut record: impl FnMut(usize, f64, &S) -> Result<()>,
) -> Result<()> {
    let mut order: Vec<usize> = (0..t.len()).collect();
    order.sort_by(|&i, &j| t[i].total_cmp(&t[j]));
    let mut map: Option<(f64, M)> = None;
    let mut base = 0.0; // the time at which the current map was built
    let mut steps = 0.0; // steps taken with it since then
    let mut now = 0.0; // the time the state stands for
    let mut asked = 0.0; // the previous time asked for
    for (pos, &i) in order.iter().enumerate() {
        let ti = t[i];
        let dt = ti - now;
        if dt > 0.0 {
            let tol = SAME_STEP_ULPS * f64::EPSILON * ti.max(dt);
            if map.as_ref().is_none_or(|(h, _)| (dt - h).abs() > tol) {
                let run = run_length(t, &order[pos..], dt);
                map = Some((dt, map_for(dt, ti, run)?));
                base = now;
                steps = 0.0;
            }
            if let Some((h, m)) = &map {
                step(m, state, asked, ti)?;
                steps += 1.0;
                now = base + steps * h;
            }
        }
        record(i, ti, state)?;
        asked = ti;
    }
    Ok(())
}

/// The number of consecutive steps of length ≈ `h` at the head of the sorted times `ahead`
/// (the first of which is one step of `h` past the state): gaps within the ulps tolerance of
/// `h` count, repeated times are skipped, the first other gap ends the run. Linear in the run,
/// so the lookahead costs O(len) over a whole march.
fn run_length(t: &[f64], ahead: &[usize], h: f64) -> usize {
    let mut run = 1;
    for w in ahead.windows(2) {
        let (a, b) = (t[w[0]], t[w[1]]);
        let gap = b - a;
        if gap == 0.0 {
            continue;
        }
        if (gap - h).abs() > SAME_STEP_ULPS * f64::EPSILON * b.max(gap) {
            break;
        }
        run += 1;
    }
    run
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_map_per_step_length_and_values_in_the_callers_order() {
        // x(t) = e^(−t): 10⁵ uniform steps of 1e-3 with one map, then two other lengths
        let mut t: Vec<f64> = (0..=100_000).rev().map(|k| k as f64 * 1e-3).collect();
        t.extend([100.5, 101.0]);
        let mut maps = 0;
        let mut runs = Vec::new();
        let mut y = vec![0.0; t.len()];
        let mut x = 1.0f64;
        march(
            &t,
            &mut x,
            |h, _, run| {
                maps += 1;
                runs.push(run);
                Ok((-h).exp())
            },
            |m, x, _, _| {
                *x *= m;
                Ok(())
            },
            |i, ti, x| {
                y[i] = *x - (-ti).exp();
                Ok(())
            },
        )
        .unwrap();
        assert_eq!(
            maps, 2,
            "one map for the grid, one for the two steps of 0.5"
        );
        // the lookahead: 10⁵ steps of 1e-3 from 0 (the time 0 itself is no step), then two
        assert_eq!(runs, [100_000, 2]);
        let worst = y.iter().fold(0.0f64, |a, e| a.max(e.abs()));
        // 10⁵ products of e^(−h): rounding grows like k·eps
        assert!(worst < 1e-12, "{worst}");
    }
}
