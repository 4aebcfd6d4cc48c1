//! The root locus itself ([`root_locus`], [`RootLocus`]): its features and traced branches in
//! one struct (see the [module docs](super)).

use num_complex::Complex64;
use serde::Serialize;

use super::features::{Asymptotes, BreakPoint, LocusAngle, LocusCrossing};
use super::trace::Branches;
use crate::analysis::factored::Factored;
use crate::error::{LtiError, Result};
use crate::poly::{Poly, Root};

/// Default cap on the number of gains of a traced locus.
pub const DEFAULT_MAX_GAINS: usize = 2000;

/// Options of [`root_locus`].
#[derive(Debug, Clone, PartialEq)]
pub struct RootLocusOptions {
    /// Trace K from 0 to −∞ (the complementary, 0° locus) instead of 0 to +∞.
    pub negative: bool,
    /// At most this many gains on the traced branches (≥ 16).
    pub max_gains: usize,
}

impl Default for RootLocusOptions {
    fn default() -> Self {
        RootLocusOptions {
            negative: false,
            max_gains: DEFAULT_MAX_GAINS,
        }
    }
}

/// A root locus: the features and the traced branches.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RootLocus {
    /// K runs from 0 to −∞ (the 0° locus).
    pub negative: bool,
    /// Open-loop poles (roots of D as given), the branches' starting points.
    pub poles: Vec<Root>,
    /// Open-loop finite zeros (roots of N as given), where branches end.
    pub zeros: Vec<Root>,
    /// Roots shared by N and D: closed-loop poles for every K (hidden modes of the loop).
    pub fixed: Vec<Root>,
    /// The asymptotes of the branches that go to infinity (`None` when deg N = deg D).
    pub asymptotes: Option<Asymptotes>,
    /// Break-away and break-in points on the real axis, by increasing σ.
    pub break_points: Vec<BreakPoint>,
    /// Crossings of the stability boundary at K ≠ 0 on this locus, by increasing ω: the
    /// imaginary axis, or in discrete time the unit circle.
    pub crossings: Vec<LocusCrossing>,
    /// Departure angles at the poles of G in lowest terms.
    pub departures: Vec<LocusAngle>,
    /// Arrival angles at the zeros of G in lowest terms.
    pub arrivals: Vec<LocusAngle>,
    /// When deg N = deg D: the gain −d/n (ratio of the leading coefficients) at which a
    /// branch leaves through infinity, if it is on this locus.
    pub escape_gain: Option<f64>,
    /// The sampling period of a discrete-time locus (in z: crossings of the unit circle);
    /// `None` in continuous time. (Not in JSON: the command's document carries `"dt"`.)
    #[serde(skip)]
    pub dt: Option<f64>,
    /// What was not computed and why.
    pub notes: Vec<String>,
    /// The traced branches.
    #[serde(flatten)]
    pub branches: Branches,
}

/// The root locus of D + K·N = 0 (G = N/D, coefficients as given, descending powers).
///
/// Errors: N ≡ 0, an improper G (deg N > deg D), the root finder's errors.
///
/// ```
/// use ltikit::Poly;
/// use ltikit::analysis::rlocus::{root_locus, RootLocusOptions};
/// // 1/(s(s + 1)(s + 2)): break-away at −1 + 1/√3, axis crossing ω = √2 at K = 6,
/// // asymptotes from −1 at ±60° and 180°.
/// let n = Poly::from_descending(&[1.0]).unwrap();
/// let d = Poly::from_descending(&[1.0, 3.0, 2.0, 0.0]).unwrap();
/// let l = root_locus(&n, &d, &RootLocusOptions::default()).unwrap();
/// let a = l.asymptotes.as_ref().unwrap();
/// assert!((a.centroid + 1.0).abs() < 1e-15);
/// assert_eq!(a.angles_deg, vec![-60.0, 60.0, 180.0]);
/// let b = &l.break_points[0];
/// assert!((b.s - (-1.0 + 1.0 / 3f64.sqrt())).abs() < 1e-14);
/// assert!((b.gain - 2.0 / (3.0 * 3f64.sqrt())).abs() < 1e-14);
/// assert!((l.crossings[0].omega - 2f64.sqrt()).abs() < 1e-14);
/// assert!((l.crossings[0].gain - 6.0).abs() < 1e-13);
/// assert_eq!(l.branches.paths.len(), 3);
/// ```
pub fn root_locus(num: &Poly, den: &Poly, opts: &RootLocusOptions) -> Result<RootLocus> {
    locus_in(num, den, opts, None)
}

/// The root locus of D(z) + K·N(z) = 0 in discrete time (period `dt`): the same algebra as
/// [`root_locus`] (asymptotes, break points and angles are properties of the polynomials),
/// with the crossings of the unit circle — z = 1, z = −1, pairs e^(±jωT) — instead of the
/// imaginary axis.
///
/// Errors: those of [`root_locus`]; `dt` not finite and > 0.
///
/// ```
/// use ltikit::Poly;
/// use ltikit::analysis::rlocus::{root_locus_z, RootLocusOptions};
/// // K(z + 0.5)/(z(z − 1)): z² + (K − 1)z + 0.5K leaves the circle at e^(±j2π/3), K = 2.
/// let n = Poly::from_descending(&[1.0, 0.5]).unwrap();
/// let d = Poly::from_descending(&[1.0, -1.0, 0.0]).unwrap();
/// let l = root_locus_z(&n, &d, 0.1, &RootLocusOptions::default()).unwrap();
/// let c = l.crossings.iter().find(|c| c.omega > 0.0).unwrap();
/// assert!((c.gain - 2.0).abs() < 1e-13);
/// assert!((c.omega * 0.1 - 2.0 * std::f64::consts::FRAC_PI_3).abs() < 1e-13);
/// ```
pub fn root_locus_z(num: &Poly, den: &Poly, dt: f64, opts: &RootLocusOptions) -> Result<RootLocus> {
    crate::lti::Domain::discrete(dt)?;
    locus_in(num, den, opts, Some(dt))
}

fn locus_in(num: &Poly, den: &Poly, opts: &RootLocusOptions, dt: Option<f64>) -> Result<RootLocus> {
    check(num, den)?;
    let poles = den.roots()?;
    let zeros = num.roots()?;
    let (fixed, red_poles, red_zeros) = super::features::cancel(&poles, &zeros);
    let sign = if opts.negative { -1.0 } else { 1.0 };
    let k0 = num.leading() / den.leading();
    // the 180° locus when K·k0 > 0, the 0° locus otherwise
    let base = if sign * k0 > 0.0 { 180.0 } else { 0.0 };
    let asymptotes = super::features::asymptotes(num, den, base);
    let mut notes = Vec::new();
    let break_points = match super::features::break_points(num, den, sign)? {
        Some(b) => b,
        None => {
            notes.push(format!(
                "break points not computed: N·D′ − N′·D has degree {} > {}",
                num.degree() + den.degree() - 1,
                crate::poly::MAX_ORDER
            ));
            Vec::new()
        }
    };
    let found = match dt {
        None => super::features::crossings(num, den, sign)?,
        Some(dt) => super::features::circle_crossings(num, den, sign, dt)?,
    };
    let crossings = match found {
        Some(c) => c,
        None => {
            notes.push(format!(
                "{} crossings not computed: their polynomial has degree up to {} > {}",
                if dt.is_some() {
                    "unit-circle"
                } else {
                    "imaginary-axis"
                },
                2 * num.degree().max(den.degree()),
                crate::poly::MAX_ORDER
            ));
            Vec::new()
        }
    };
    let departures = super::features::departures(&red_poles, &red_zeros, base);
    let arrivals = super::features::arrivals(&red_poles, &red_zeros, base);
    let escape_gain = (num.degree() == den.degree())
        .then(|| -den.leading() / num.leading())
        .filter(|k| k.is_finite() && k * sign > 0.0);
    let mut special: Vec<f64> = break_points.iter().map(|b| b.gain).collect();
    special.extend(crossings.iter().map(|c| c.gain));
    let mut scale_points: Vec<Complex64> = poles.iter().map(|r| r.value).collect();
    scale_points.extend(zeros.iter().map(|r| r.value));
    scale_points.extend(break_points.iter().map(|b| Complex64::new(b.s, 0.0)));
    scale_points.extend(
        crossings
            .iter()
            .map(|c| c.z.unwrap_or(Complex64::new(0.0, c.omega))),
    );
    if let Some(a) = &asymptotes {
        scale_points.push(Complex64::new(a.centroid, 0.0));
    }
    let branches = super::trace::trace(
        num,
        den,
        &super::trace::Plan {
            sign,
            special: &special,
            escape_gain,
            scale_points: &scale_points,
            poles: &poles,
            zeros: &zeros,
            max_gains: crate::limits::GAINS
                .check_usize("`max_gains`", opts.max_gains)?
                .max(16),
        },
    )?;
    Ok(RootLocus {
        negative: opts.negative,
        poles,
        zeros,
        fixed,
        asymptotes,
        break_points,
        crossings,
        departures,
        arrivals,
        escape_gain,
        dt,
        notes,
        branches,
    })
}

/// The errors every locus entry point shares.
fn check(num: &Poly, den: &Poly) -> Result<()> {
    if num.is_zero() {
        return Err(LtiError::invalid(
            "the root locus needs a nonzero numerator: with N = 0 no gain acts",
        ));
    }
    if num.degree() > den.degree() {
        return Err(LtiError::Improper {
            operation: "the root locus".into(),
            required: "proper".into(),
            num_degree: num.degree(),
            den_degree: den.degree(),
            limit: den.degree(),
        });
    }
    if den.degree() == 0 {
        return Err(LtiError::invalid(
            "the root locus needs a denominator of degree ≥ 1 (a static gain has no poles)",
        ));
    }
    Ok(())
}

impl Factored {
    /// The root locus of unity negative feedback around K·G (see [`root_locus`]; for a
    /// discrete plant [`root_locus_z`], with the unit-circle crossings), on G's coefficients
    /// as given (a plant without coefficients is expanded from its factors).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::analysis::rlocus::RootLocusOptions;
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 3.0, 2.0, 0.0]).unwrap();
    /// let l = g.factored().unwrap().root_locus(&RootLocusOptions::default()).unwrap();
    /// assert_eq!(l.poles.len(), 3);
    /// ```
    pub fn root_locus(&self, opts: &RootLocusOptions) -> Result<RootLocus> {
        let (num, den) = self.locus_polys()?;
        match self.domain().dt() {
            None => root_locus(&num, &den, opts),
            Some(dt) => root_locus_z(&num, &den, dt, opts),
        }
    }

    /// N and D as given (expanded from the factors when the plant has no coefficients).
    pub fn locus_polys(&self) -> Result<(Poly, Poly)> {
        if let Some(tf) = self.transfer_function() {
            return Ok((tf.num().clone(), tf.den().clone()));
        }
        let num = Poly::from_root_list(self.zeros())?.scale(self.gain());
        let den = Poly::from_root_list(self.poles())?;
        Ok((num, den))
    }
}
