//! The MEMS pull-in diagram: equilibrium gap l against voltage v, stable and unstable
//! branches, and the pull-in point (seed exercise 2.11).
//!
//! The gaps come from the equilibrium cubic l²(l0 − l) = εA v²/(2k) ([`Mems::equilibrium_gaps`]);
//! each physical equilibrium (0 < l ≤ l0) is classified by its exact linearisation. The
//! pull-in voltage is also *found* independently of the formula √(8 k l0³/(27 εA)): bisection
//! on v for the largest voltage at which a physical equilibrium is still asymptotically stable.

use serde::Serialize;

use crate::error::{LtiError, Result, check_finite};
use crate::nonlinear::equilibria::{EquilibriumSearch, equilibria};
use crate::nonlinear::linearize::{LocalStability, stability_at};
use crate::nonlinear::models::Mems;

/// Data of the pull-in diagram.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PullInDiagram {
    /// Rest gap l0 (the branches start at (0, l0) and (0, 0)).
    pub l0: f64,
    /// Stable equilibria as (v, l), by increasing v, ending at the pull-in point.
    pub stable: Vec<[f64; 2]>,
    /// Unstable physical equilibria as (v, l), by increasing v, ending at the pull-in point.
    pub unstable: Vec<[f64; 2]>,
    /// Pull-in voltage from the formula √(8 k l0³/(27 εA)).
    pub pull_in_voltage: f64,
    /// Pull-in gap from the formula 2 l0/3.
    pub pull_in_gap: f64,
    /// Pull-in voltage found by bisection on the linearised stability.
    pub pull_in_voltage_found: f64,
    /// Gap of the last stable equilibrium at the found pull-in voltage.
    pub pull_in_gap_found: f64,
}

/// Classifies the physical equilibria of `mems` at voltage v: (stable gaps, other gaps).
fn classify(mems: &Mems, v: f64) -> Result<(Vec<f64>, Vec<f64>)> {
    let m = mems.with_voltage(v)?;
    let mut stable = Vec::new();
    let mut other = Vec::new();
    for e in equilibria(&m, &[v], &EquilibriumSearch::default())? {
        if !e.physical {
            continue;
        }
        let (stability, _) = stability_at(&m, &e.x, &e.u)?;
        if stability == LocalStability::AsymptoticallyStable {
            stable.push(e.x[0]);
        } else {
            other.push(e.x[0]);
        }
    }
    Ok((stable, other))
}

/// Pull-in voltage and gap found by bisection on v ≥ 0 (to ~1e-15 relative): the largest v at
/// which the device still has an asymptotically stable physical equilibrium. The gap is the
/// mean of the stable and the unstable physical gap there (they straddle the fold
/// symmetrically to first order, l± ≈ l_pi ± c·√(v_pi − v), so the mean errs by O(v_pi − v)
/// rather than O(√(v_pi − v))).
///
/// ```
/// use ltikit::nonlinear::{find_pull_in, models::Mems};
/// let m = Mems::default();
/// let (v, l) = find_pull_in(&m).unwrap();
/// assert!((v - m.pull_in_voltage()).abs() < 1e-9);
/// assert!((l - 2.0).abs() < 1e-3);
/// ```
pub fn find_pull_in(mems: &Mems) -> Result<(f64, f64)> {
    let stable_at = |v: f64| -> Result<Option<f64>> {
        let (s, other) = classify(mems, v)?;
        Ok(s.into_iter().reduce(f64::min).map(|ls| {
            // The unstable partner just below the fold, if still distinct.
            match other.into_iter().filter(|&l| l < ls).reduce(f64::max) {
                Some(lu) => 0.5 * (ls + lu),
                None => ls,
            }
        }))
    };
    let mut lo = 0.0;
    let mut l_lo = stable_at(lo)?.ok_or_else(|| LtiError::Undefined {
        what: "the pull-in voltage".into(),
        reason: "the device has no stable equilibrium even at v = 0 (b = 0?)".into(),
    })?;
    // Bracket: double until no stable equilibrium is left.
    let mut hi = 1.0;
    let mut tries = 0;
    while stable_at(hi)?.is_some() {
        lo = hi;
        hi *= 2.0;
        tries += 1;
        if tries > 1100 {
            return Err(LtiError::NoConvergence {
                what: "the pull-in bracket".into(),
                iterations: tries,
            });
        }
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        match stable_at(mid)? {
            Some(l) => {
                lo = mid;
                l_lo = l;
            }
            None => hi = mid,
        }
    }
    Ok((lo, l_lo))
}

/// The pull-in diagram for voltages 0 … `v_max` at `points` equally spaced voltages, plus the
/// pull-in point appended to both branches (so that they meet in the picture).
///
/// ```
/// use ltikit::nonlinear::{mems_pullin, models::Mems};
/// let d = mems_pullin(&Mems::default(), 3.5, 71).unwrap();
/// assert!(d.stable.iter().all(|p| p[1] >= d.pull_in_gap - 1e-9));
/// assert!(d.unstable.iter().all(|p| p[1] <= d.pull_in_gap + 1e-9));
/// assert!((d.pull_in_voltage_found - d.pull_in_voltage).abs() < 1e-9);
/// ```
pub fn mems_pullin(mems: &Mems, v_max: f64, points: usize) -> Result<PullInDiagram> {
    check_finite(|| "the maximum voltage".into(), v_max)?;
    if v_max <= 0.0 {
        return Err(LtiError::InvalidParameter {
            name: "v_max".into(),
            value: v_max,
            reason: "the voltage range must end above 0".into(),
        });
    }
    if points < 2 {
        return Err(LtiError::invalid("at least 2 voltages are needed"));
    }
    let mut stable = Vec::new();
    let mut unstable = Vec::new();
    for k in 0..points {
        let v = v_max * k as f64 / (points - 1) as f64;
        let (s, o) = classify(mems, v)?;
        stable.extend(s.into_iter().map(|l| [v, l]));
        unstable.extend(o.into_iter().map(|l| [v, l]));
    }
    let (v_found, l_found) = find_pull_in(mems)?;
    let (v_pi, l_pi) = (mems.pull_in_voltage(), mems.pull_in_gap());
    if v_pi <= v_max {
        stable.push([v_pi, l_pi]);
        unstable.push([v_pi, l_pi]);
    }
    Ok(PullInDiagram {
        l0: mems.l0,
        stable,
        unstable,
        pull_in_voltage: v_pi,
        pull_in_gap: l_pi,
        pull_in_voltage_found: v_found,
        pull_in_gap_found: l_found,
    })
}
