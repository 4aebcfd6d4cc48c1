//! Near cancellations: pole-zero pairs that are close but not equal, listed with their
//! distance, and cancelled on request within a tolerance (MATLAB's and python-control's
//! `minreal(sys, tol)`).
//!
//! The factored form cancels only what is the same root: exactly (the exact path) or within
//! the numerical path's tolerance. A zero at −2.00000000001 beside a pole at −2 is a genuine
//! part of G — its residue is 1e-11 — and stays; the report lists it so that the user can see
//! it, and [`Factored::minreal`] removes such pairs when asked.

use num_complex::Complex64;
use serde::Serialize;

use super::form::assemble;
use super::pole_zero::count;
use super::source::Source;
use super::{Factored, PoleZero};
use crate::error::{LtiError, Result};
use crate::poly::Root;

/// Pairs whose relative distance |z − p|/max(|z|, |p|) is below this are listed as near
/// cancellations in the reports (python-control's and MATLAB's default `minreal` tolerance
/// is √eps ≈ 1.5e-8; pairs up to 1e-6 are worth a look).
pub const NEAR_PAIR_REL: f64 = 1e-6;

/// A zero of G close to one of its poles (not cancelled).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NearPair {
    /// The zero (for a conjugate pair, the upper member; the pair is listed once).
    pub zero: Complex64,
    /// The pole.
    pub pole: Complex64,
    /// How many times the pair occurs (the smaller of the two multiplicities).
    pub multiplicity: usize,
    /// |z − p|.
    pub distance: f64,
    /// |z − p| / max(|z|, |p|).
    pub relative: f64,
}

/// |z − p| / max(|z|, |p|); 0 for equal values (both at 0 included).
fn relative_distance(z: Complex64, p: Complex64) -> f64 {
    let d = (z - p).norm();
    if d == 0.0 {
        0.0
    } else {
        d / z.norm().max(p.norm())
    }
}

/// Greedy pairing of the reduced zeros with the reduced poles, closest (relatively) first,
/// among pairs within `rel`; conjugate members pair with conjugate members (both are listed
/// in the root lists).
fn pairs(zeros: &[Root], poles: &[Root], rel: f64) -> Vec<NearPair> {
    let mut cand: Vec<(f64, usize, usize)> = Vec::new();
    for (i, z) in zeros.iter().enumerate() {
        for (j, p) in poles.iter().enumerate() {
            let r = relative_distance(z.value, p.value);
            // a pair on different sides of the real axis is not a cancellation
            let same_side = match (z.value.im == 0.0, p.value.im == 0.0) {
                (true, true) => true,
                (false, false) => (z.value.im > 0.0) == (p.value.im > 0.0),
                _ => false,
            };
            if r <= rel && same_side {
                cand.push((r, i, j));
            }
        }
    }
    cand.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut zm: Vec<usize> = zeros.iter().map(|r| r.multiplicity).collect();
    let mut pm: Vec<usize> = poles.iter().map(|r| r.multiplicity).collect();
    let mut out = Vec::new();
    for (r, i, j) in cand {
        let k = zm[i].min(pm[j]);
        if k == 0 {
            continue;
        }
        zm[i] -= k;
        pm[j] -= k;
        out.push(NearPair {
            zero: zeros[i].value,
            pole: poles[j].value,
            multiplicity: k,
            distance: (zeros[i].value - poles[j].value).norm(),
            relative: r,
        });
    }
    out
}

impl Factored {
    /// Zeros of the reduced G within a relative `rel` of one of its poles (each pair once; a
    /// conjugate pair as its upper member), closest first. [`NEAR_PAIR_REL`] is the
    /// reports' threshold.
    ///
    /// ```
    /// use ltikit::analysis::Factored;
    /// use ltikit::poly::exact::ExactPoly;
    /// // (s + 2.00000000001)/((s + 2)(s + 1)) typed as text: nothing cancels exactly.
    /// let n = ExactPoly::parse_descending(&["1", "2.00000000001"]).unwrap();
    /// let d = ExactPoly::parse_descending(&["1", "3", "2"]).unwrap();
    /// let f = Factored::from_exact(&n, &d).unwrap();
    /// assert!(f.pole_zero().cancelled.is_empty());
    /// let near = f.near_cancellations(1e-6);
    /// assert_eq!(near.len(), 1);
    /// assert!((near[0].distance - 1e-11).abs() < 1e-15); // one ulp of 2
    /// ```
    pub fn near_cancellations(&self, rel: f64) -> Vec<NearPair> {
        pairs(
            &self.pole_zero().reduced_zeros,
            &self.pole_zero().reduced_poles,
            rel,
        )
        .into_iter()
        .filter(|p| p.zero.im >= 0.0)
        .collect()
    }

    /// G with the pole-zero pairs within a relative `tol` (|z − p| ≤ tol·max(|z|, |p|))
    /// cancelled, as MATLAB's and python-control's `minreal(sys, tol)`: the gain is kept, the
    /// removed poles are listed with the cancelled roots (so a removed unstable pole still
    /// makes the plant internally unstable), and the pairs removed are returned. The result's
    /// source is its factors. `tol` = 0 removes nothing.
    ///
    /// Errors: `tol` negative, not finite, or ≥ 1.
    ///
    /// ```
    /// use ltikit::analysis::Factored;
    /// use ltikit::poly::exact::ExactPoly;
    /// let n = ExactPoly::parse_descending(&["1", "2.00000000001"]).unwrap();
    /// let d = ExactPoly::parse_descending(&["1", "3", "2"]).unwrap();
    /// let f = Factored::from_exact(&n, &d).unwrap();
    /// let (g, removed) = f.minreal(1e-8).unwrap();
    /// assert_eq!(removed.len(), 1);
    /// assert_eq!(g.reduced_poles().len(), 1); // 1/(s + 1) is left
    /// assert!((g.reduced_poles()[0].value.re + 1.0).abs() < 1e-15);
    /// ```
    pub fn minreal(&self, tol: f64) -> Result<(Factored, Vec<NearPair>)> {
        if !(tol.is_finite() && (0.0..1.0).contains(&tol)) {
            return Err(LtiError::InvalidParameter {
                name: "minreal tolerance".into(),
                value: tol,
                reason: "must be a relative distance in [0, 1)".into(),
            });
        }
        let all = pairs(
            &self.pole_zero().reduced_zeros,
            &self.pole_zero().reduced_poles,
            tol,
        );
        if all.is_empty() {
            return Ok((self.clone(), Vec::new()));
        }
        let take = |roots: &[Root], f: &dyn Fn(&NearPair) -> Complex64| -> Vec<Root> {
            roots
                .iter()
                .filter_map(|r| {
                    let k: usize = all
                        .iter()
                        .filter(|p| f(p) == r.value)
                        .map(|p| p.multiplicity)
                        .sum();
                    (r.multiplicity > k).then(|| Root::new(r.value, r.multiplicity - k))
                })
                .collect()
        };
        let reduced_zeros = take(&self.pole_zero().reduced_zeros, &|p| p.zero);
        let reduced_poles = take(&self.pole_zero().reduced_poles, &|p| p.pole);
        let mut cancelled = self.pole_zero().cancelled.clone();
        for p in &all {
            cancelled.push(Root::new(p.pole, p.multiplicity));
        }
        let pz = PoleZero::from_parts(
            self.pole_zero().poles.clone(),
            self.pole_zero().zeros.clone(),
            cancelled,
            reduced_poles,
            reduced_zeros,
            self.is_zero(),
        );
        debug_assert_eq!(
            count(&pz.reduced_poles) + all.iter().map(|p| p.multiplicity).sum::<usize>(),
            count(&self.pole_zero().reduced_poles)
        );
        let g = assemble(pz, self.gain(), Source::Factors, self.decision().clone())
            .with_domain(self.domain());
        let upper = all.into_iter().filter(|p| p.zero.im >= 0.0).collect();
        Ok((g, upper))
    }
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact values are meant: the gain kept, a real part of exactly 0
mod tests {
    use super::*;
    use crate::lti::TransferFunction;

    #[test]
    fn conjugate_pairs_pair_with_conjugates_and_gain_is_kept() {
        // (s² + 2s + 5.0000001)/((s² + 2s + 5)(s + 3)): zeros −1 ± j√4.0000001 near the poles
        // −1 ± 2j: distance √4.0000001 − 2 ≈ 2.5e-8, relative 1.1e-8.
        let g = TransferFunction::from_descending(&[1.0, 2.0, 5.0000001], &[1.0, 5.0, 11.0, 15.0])
            .unwrap()
            .factored()
            .unwrap();
        let near = g.near_cancellations(NEAR_PAIR_REL);
        assert_eq!(near.len(), 1, "{near:?}");
        assert!(near[0].zero.im > 0.0 && near[0].pole.im > 0.0);
        let want = (4.0000001f64.sqrt() - 2.0) / 5.0000001f64.sqrt();
        assert!((near[0].relative - want).abs() < 1e-6 * want, "{near:?}");
        let (m, removed) = g.minreal(1e-6).unwrap();
        assert_eq!(removed.len(), 1);
        assert_eq!(count(m.reduced_poles()), 1);
        assert!(m.reduced_zeros().is_empty());
        assert_eq!(m.gain(), g.gain());
        // 1/(s + 3): the pair is gone, the gain kept
        let dc = m.dc_gain().unwrap();
        assert!((dc - 1.0 / 3.0).abs() < 1e-12, "{dc}");
        // nothing within 1e-9
        assert!(g.minreal(1e-9).unwrap().1.is_empty());
        assert!(g.minreal(-1.0).is_err() && g.minreal(f64::NAN).is_err());
    }

    #[test]
    fn a_removed_unstable_pole_keeps_the_plant_internally_unstable() {
        // (s − 1.0000001)/((s − 1)(s + 2))
        let g = TransferFunction::from_descending(&[1.0, -1.0000001], &[1.0, 1.0, -2.0])
            .unwrap()
            .factored()
            .unwrap();
        let (m, removed) = g.minreal(1e-6).unwrap();
        assert_eq!(removed.len(), 1);
        let st = m.stability();
        assert!(st.bibo_stable && !st.internally_stable, "{st:?}");
    }
}
