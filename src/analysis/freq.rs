//! Frequency response G(jω): magnitude, dB and continuous phase.
//!
//! # Conventions
//! - ω in rad/s, finite and ≥ 0; magnitudes as ratios and in dB (20·log₁₀); phase in degrees.
//! - The phase is **continuous in ω** and independent of the grid: it is not unwrapped from
//!   samples but built from the factored (Bode) form of the reduced transfer function
//!
//!   G(jω) = K·(jω)^k·Π(1 − jω/zᵢ) / Π(1 − jω/pᵢ),
//!
//!   where the k zero roots (exactly: the trailing zero coefficients) are pulled into (jω)^k
//!   and K is the low-frequency asymptote gain (ratio of the lowest non-zero coefficients).
//!   φ(ω) = [K < 0 ? −180° : 0] + 90°·k + Σ∠(1 − jω/zᵢ) − Σ∠(1 − jω/pᵢ). Each factor's angle
//!   stays on one side of its branch cut, so the sum is continuous. Consequences (DESIGN
//!   §1.3): 1/s³ starts at −270°, a negative gain at −180°, a right-half-plane zero adds lag.
//! - Roots on the imaginary axis (within the relative tolerance
//!   [`AXIS_REL_TOL`](crate::numeric::tol::AXIS_REL_TOL) they are taken as exactly on it) follow
//!   the limit of vanishing damping: a pole pair ±jβ drops the phase by 180° as ω passes β, a
//!   zero pair raises it by 180°; at ω = β exactly the magnitude is +∞ (pole) or 0 (zero) and
//!   the phase is the midpoint.
//! - G ≡ 0 has magnitude 0 (−∞ dB) and, by convention, phase 0.
//! - Infinite magnitudes (a pole hit exactly, or ω = 0 with an integrator) are kept as f64
//!   infinities; −∞ / +∞ dB likewise.
//!
//! # Method and cost
//! The factors are grouped into real first-order factors (1 + jcω) and real quadratic factors
//! (1 − aω²) + jbω (a conjugate pair); each has a positive real part after pulling out an
//! exact half turn, so its angle lies in (−π/2, π/2]. The complex product of all factors is
//! accumulated with exact power-of-two rescaling (no overflow at high order or high ω), and
//! the branch of its argument is tracked by counting crossings of the negative real axis —
//! a few comparisons per factor instead of an `atan2` per factor. One `atan2` per ω then
//! gives the phase exactly to rounding. Frequencies so extreme that a single factor could
//! overflow (ω beyond ~1e60 × the corner frequency) use a per-factor logarithmic path.
//!
//! The factored form is only as good as the roots. When it is built it is compared with
//! Horner's rule in double-double arithmetic on the reduced coefficients at the corner
//! frequencies and across the plotting range; if they disagree by more than 1e-11
//! (relative magnitude, or radians of phase) — roots too ill-conditioned, e.g. an expanded
//! (s + 1)²⁰ — magnitude and principal phase come from double-double Horner and the factored
//! phase only selects the branch, so the phase stays continuous and the values match the
//! coefficients as given.
//!
//! The evaluation form and its kernels belong to the factored core, which builds it once per
//! plant and caches it (`analysis::factored::bode`); this module turns it into a
//! [`FrequencyResponse`], one block of frequencies per core for large grids.

use serde::Serialize;

use crate::analysis::factored::{BodeForm, Factored};
use crate::error::{LtiError, Result, check_finite};
use crate::lti::TransferFunction;

/// G(jω) sampled at the frequencies `w` (rad/s). All vectors have the same length.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrequencyResponse {
    /// Frequencies (rad/s), as requested.
    pub w: Vec<f64>,
    /// |G(jω)|.
    pub magnitude: Vec<f64>,
    /// 20·log₁₀|G(jω)| (dB); −∞ at an exact zero on the axis.
    pub magnitude_db: Vec<f64>,
    /// Phase in degrees, continuous in ω (DESIGN §1.3).
    pub phase_deg: Vec<f64>,
}

impl TransferFunction {
    /// Frequency response G(jω) at the frequencies `w` (rad/s, finite, ≥ 0, any order).
    ///
    /// Uses the reduced (lowest-terms) G in factored form; see the [module
    /// docs](crate::analysis::freq) for the phase convention. Magnitudes agree with Horner's
    /// rule on the coefficients to rounding (tested to 1e-10 relative).
    ///
    /// Errors: a NaN/infinite or negative frequency; root-finding failures of the polynomials.
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // 1/s³ starts at −270°, not +90°.
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 0.0, 0.0, 0.0]).unwrap();
    /// let r = g.freq_response(&[0.01, 1.0]).unwrap();
    /// assert!((r.phase_deg[0] + 270.0).abs() < 1e-12);
    /// assert!((r.magnitude_db[1]).abs() < 1e-12);
    /// // 1/(s² + 1) drops by 180° through ω = 1; the phase is −90° and |G| = ∞ exactly there.
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 0.0, 1.0]).unwrap();
    /// let r = g.freq_response(&[0.5, 1.0, 2.0]).unwrap();
    /// assert!(r.phase_deg[0].abs() < 1e-12);
    /// assert!((r.phase_deg[1] + 90.0).abs() < 1e-12 && r.magnitude[1].is_infinite());
    /// assert!((r.phase_deg[2] + 180.0).abs() < 1e-12);
    /// ```
    pub fn freq_response(&self, w: &[f64]) -> Result<FrequencyResponse> {
        check_frequencies(w)?;
        self.factored()?.freq_response(w)
    }
}

impl Factored {
    /// Frequency response G(jω) at the frequencies `w` (rad/s, finite, ≥ 0, any order), on
    /// the evaluation form built once per factorisation (see
    /// [`TransferFunction::freq_response`] and the [module docs](self)).
    ///
    /// ```
    /// use ltikit::analysis::Factored;
    /// use ltikit::Root;
    /// use num_complex::Complex64 as C;
    /// // 1/(s + 1)^40: −40·45° = −1800° at ω = 1, |G| = 2^−20.
    /// let f = Factored::from_zpk(&[], &[Root::new(C::new(-1.0, 0.0), 40)], 1.0).unwrap();
    /// let r = f.freq_response(&[1.0]).unwrap();
    /// assert!((r.phase_deg[0] + 1800.0).abs() < 1e-9);
    /// assert!((r.magnitude[0] - 2f64.powi(-20)).abs() < 1e-20);
    /// // a dead time T keeps |G| and subtracts ωT from the phase: e^(−2s)/(s + 1)^40 at ω = 1
    /// let d = f.with_delay(2.0).unwrap().freq_response(&[1.0]).unwrap();
    /// assert!((d.phase_deg[0] - (r.phase_deg[0] - 2f64.to_degrees())).abs() < 1e-12);
    /// ```
    pub fn freq_response(&self, w: &[f64]) -> Result<FrequencyResponse> {
        if let Some(dt) = self.domain().dt() {
            return crate::analysis::discrete::freq_response(self, dt, w);
        }
        check_frequencies(w)?;
        let form = self.bode();
        let n = w.len();
        let mut out_w = vec![0.0; n];
        let mut magnitude = vec![0.0; n];
        let mut magnitude_db = vec![0.0; n];
        let mut phase_deg = vec![0.0; n];
        let threads = worker_count(n);
        if threads <= 1 {
            out_w.copy_from_slice(w);
            form.response_fill(w, &mut magnitude, &mut magnitude_db, &mut phase_deg);
        } else {
            // Independent frequencies: split the grid into one contiguous block per core.
            // (Writing the fresh output pages is a good part of the cost at 10⁶ points, and
            // it parallelises too.)
            let chunk = n.div_ceil(threads);
            let blocks_count = n.div_ceil(chunk);
            let mut not_started = Vec::new();
            std::thread::scope(|scope| {
                let blocks = w
                    .chunks(chunk)
                    .zip(out_w.chunks_mut(chunk))
                    .zip(magnitude.chunks_mut(chunk))
                    .zip(magnitude_db.chunks_mut(chunk))
                    .zip(phase_deg.chunks_mut(chunk));
                for (k, ((((wc, ow), m), db), ph)) in blocks.enumerate() {
                    let form: &BodeForm = form;
                    let mut job = move || {
                        ow.copy_from_slice(wc);
                        form.response_fill(wc, m, db, ph);
                    };
                    if k + 1 == blocks_count {
                        job(); // the last block on the calling thread
                    } else if std::thread::Builder::new()
                        .spawn_scoped(scope, job)
                        .is_err()
                    {
                        not_started.push(k);
                    }
                }
            });
            // A block whose thread could not be started is done here.
            for k in not_started {
                let r = k * chunk..((k + 1) * chunk).min(n);
                out_w[r.clone()].copy_from_slice(&w[r.clone()]);
                form.response_fill(
                    &w[r.clone()],
                    &mut magnitude[r.clone()],
                    &mut magnitude_db[r.clone()],
                    &mut phase_deg[r],
                );
            }
        }
        let delay = self.delay();
        if delay > 0.0 {
            // e^(−jωT): |G| unchanged, the phase loses ωT (continuous in ω by construction)
            for (p, &x) in phase_deg.iter_mut().zip(w) {
                *p -= (x * delay).to_degrees();
            }
        }
        Ok(FrequencyResponse {
            w: out_w,
            magnitude,
            magnitude_db,
            phase_deg,
        })
    }
}

/// Frequencies per thread below which the response is computed on the calling thread
/// (starting a thread costs about as much as ~1000 frequencies).
const PER_THREAD: usize = 1 << 15;

/// Threads for a response at `n` frequencies: one per core, each with at least
/// [`PER_THREAD`] frequencies.
fn worker_count(n: usize) -> usize {
    if n < 2 * PER_THREAD {
        return 1;
    }
    crate::numeric::parallel::cores().min(n / PER_THREAD).max(1)
}

/// Checks that every frequency is finite and ≥ 0.
pub fn check_frequencies(w: &[f64]) -> Result<()> {
    for (i, &x) in w.iter().enumerate() {
        check_finite(|| format!("frequency w[{i}]"), x)?;
        if x < 0.0 {
            return Err(LtiError::InvalidParameter {
                name: format!("w[{i}]"),
                value: x,
                reason: "frequencies must be ≥ 0 rad/s".into(),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tf(n: &[f64], d: &[f64]) -> TransferFunction {
        TransferFunction::from_descending(n, d).unwrap()
    }

    #[test]
    fn bad_frequencies_are_rejected() {
        let g = tf(&[1.0], &[1.0, 1.0]);
        assert!(matches!(
            g.freq_response(&[1.0, f64::NAN]),
            Err(LtiError::NonFinite { .. })
        ));
        assert!(matches!(
            g.freq_response(&[-1.0]),
            Err(LtiError::InvalidParameter { .. })
        ));
        assert!(g.freq_response(&[f64::INFINITY]).is_err());
        assert!(g.freq_response(&[]).unwrap().w.is_empty());
    }
}
