//! The result types of the margins (continuous and discrete alike) and the small rules they
//! share: the headline values, wrapping a phase, merging crossings (a leaf module).

use serde::Serialize;

/// A frequency where |G(jω)| = 1, with the phase margin there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GainCrossing {
    /// Gain-crossover frequency (rad/s).
    pub w: f64,
    /// 180° + φ(ω) wrapped into (−180°, 180°], the phase margin at this crossing (degrees).
    pub phase_margin_deg: f64,
}

/// A frequency where φ(ω) = −180° (mod 360°), with the gain margin there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhaseCrossing {
    /// Phase-crossover frequency (rad/s).
    pub w: f64,
    /// 1/|G(jω)| (ratio).
    pub gain_margin: f64,
    /// −20·log₁₀|G(jω)| (dB).
    pub gain_margin_db: f64,
}

/// Stability margins, bandwidth and resonant peak. `None` means "infinite" for margins (no
/// crossing) and "not defined" for bandwidth and resonance.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Margins {
    /// Gain margin closest to 0 dB over all phase crossings (ratio); `None` = infinite.
    pub gain_margin: Option<f64>,
    /// The same in dB.
    pub gain_margin_db: Option<f64>,
    /// Phase-crossover frequency of that gain margin (rad/s).
    pub phase_crossover: Option<f64>,
    /// Phase margin closest to 0° over all gain crossings (degrees); `None` = infinite.
    pub phase_margin_deg: Option<f64>,
    /// Gain-crossover frequency of that phase margin (rad/s).
    pub gain_crossover: Option<f64>,
    /// Every gain crossing, by increasing ω.
    pub gain_crossings: Vec<GainCrossing>,
    /// Every phase crossing, by increasing ω.
    pub phase_crossings: Vec<PhaseCrossing>,
    /// First ω where |G| falls 3 dB below the dc gain (rad/s); `None` when the dc gain is 0 or
    /// infinite or |G| never falls that far.
    pub bandwidth: Option<f64>,
    /// Resonant peak M_r = max|G(jω)| / |G(0)| when the maximum is at ω > 0 (ratio).
    pub resonant_peak: Option<f64>,
    /// Resonant frequency ω_r (rad/s).
    pub resonant_frequency: Option<f64>,
    /// Delay margin (s): the smallest extra loop delay that destabilises the loop, min over
    /// the gain crossings ω_c > 0 of PM/ω_c with the phase margin taken in [0°, 360°)
    /// (MATLAB `allmargin`'s `DelayMargin`); `None` without a gain crossing at ω > 0.
    pub delay_margin: Option<f64>,
    /// The gain crossing of that delay margin (rad/s).
    pub delay_margin_w: Option<f64>,
    /// For a loop with a dead time, whose phase crossings never end: the frequency (rad/s)
    /// up to which `phase_crossings` lists them all (the plotted range and at least three
    /// turns of the delay, at most 50 crossings); `None` for a rational loop.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub crossings_listed_to: Option<f64>,
}

impl Margins {
    /// The headline values (MATLAB `margin`): the gain margin closest to 0 dB and the phase
    /// margin closest to 0° among the crossings.
    pub(crate) fn headline(&mut self) {
        if let Some((d, w)) = self
            .gain_crossings
            .iter()
            .filter(|c| c.w > 0.0)
            .map(|c| (c.phase_margin_deg.rem_euclid(360.0).to_radians() / c.w, c.w))
            .min_by(|a, b| a.0.total_cmp(&b.0))
        {
            self.delay_margin = Some(d);
            self.delay_margin_w = Some(w);
        }
        if let Some(c) = self.gain_crossings.iter().min_by(|a, b| {
            a.phase_margin_deg
                .abs()
                .total_cmp(&b.phase_margin_deg.abs())
        }) {
            self.phase_margin_deg = Some(c.phase_margin_deg);
            self.gain_crossover = Some(c.w);
        }
        if let Some(c) = self
            .phase_crossings
            .iter()
            .min_by(|a, b| a.gain_margin_db.abs().total_cmp(&b.gain_margin_db.abs()))
        {
            self.gain_margin = Some(c.gain_margin);
            self.gain_margin_db = Some(c.gain_margin_db);
            self.phase_crossover = Some(c.w);
        }
    }
}

/// Wraps an angle in degrees into (−180, 180].
pub(crate) fn wrap_deg(x: f64) -> f64 {
    let mut y = x - 360.0 * (x / 360.0).round();
    if y <= -180.0 {
        y += 360.0;
    }
    if y > 180.0 {
        y -= 360.0;
    }
    y
}

/// Sorts by frequency and merges entries closer than 1e-10 relative.
pub(crate) fn dedup_by_w<T>(v: &mut Vec<T>, w: impl Fn(&T) -> f64) {
    v.sort_by(|a, b| w(a).total_cmp(&w(b)));
    v.dedup_by(|b, a| (w(a) - w(b)).abs() <= 1e-10 * w(a).abs().max(w(b).abs()));
}
