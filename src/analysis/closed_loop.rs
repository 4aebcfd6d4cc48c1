//! A controller C in front of a plant G with unity negative feedback: the loop L = C·G (its
//! factors kept), the closed-loop characteristic polynomial D_C·D_G + N_C·N_G formed once
//! before any cancellation, and from it the four transfer functions of the loop — T = L/(1+L),
//! S = 1/(1+L), C·S and G·S — with their roots known (no further root finding).
//!
//! Internal stability is decided on the characteristic polynomial: a pole–zero cancellation
//! between C and G (or within either) is a *hidden mode* of the loop, a root of the
//! characteristic polynomial that one or more of the four transfer functions does not show;
//! an unstable hidden mode makes the loop internally unstable whatever T looks like.
//!
//! Robustness margins ([`ClosedLoop::robustness`]): the peak sensitivity Ms = max|S(jω)| and
//! the peak complementary sensitivity Mt = max|T(jω)| (local maxima of |S|², |T|² as roots of
//! polynomials in ω², polished on the factored form; the limits at ω = 0 and ω → ∞ included;
//! checked against the certified L∞ norm of S and T, `analysis::norms`),
//! and the delay margin min over gain crossings ω_c of PM/ω_c (the phase margin taken in
//! [0°, 360°), as MATLAB `allmargin`).
//!
//! ```
//! use ltikit::TransferFunction;
//! use ltikit::analysis::{ClosedLoop, LoopSystem};
//! let f = |n: &[f64], d: &[f64]| TransferFunction::from_descending(n, d).unwrap().factored().unwrap();
//! // C = 2, G = 1/(s(s + 1)): T = 2/(s² + s + 2)
//! let cl = ClosedLoop::new(&f(&[2.0], &[1.0]), &f(&[1.0], &[1.0, 1.0, 0.0])).unwrap();
//! assert_eq!(cl.characteristic().coeffs(), &[1.0, 1.0, 2.0]);
//! let t = cl.system(LoopSystem::ClosedLoop).unwrap();
//! assert!((t.dc_gain().unwrap() - 1.0).abs() < 1e-15);
//! assert!(cl.internal_stability().stable);
//! let r = cl.robustness().unwrap();
//! assert!(r.ms.value > 1.0 && r.delay_margin > 0.0);
//! ```

use serde::Serialize;

use super::factored::{Factored, close, series_parts};
use super::margins::local_maxima;
use super::stability::classify_in;
use crate::error::{LtiError, Result};
pub use crate::lti::controller::LoopSystem;
use crate::lti::{Controller, Plant, TransferFunction};
use crate::poly::{HalfPlane, Poly, Root};

/// A controller and a plant in a unity negative feedback loop (see the [module docs](self)).
#[derive(Debug, Clone)]
pub struct ClosedLoop {
    c: Factored,
    g: Factored,
    l: Factored,
    characteristic: Poly,
    poles: Vec<Root>,
    hidden: Vec<Root>,
}

/// Internal stability of the loop.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InternalStability {
    /// Every root of the characteristic polynomial in the open left half plane.
    pub stable: bool,
    /// Why (the worst closed-loop pole, or "all closed-loop poles in the left half plane").
    pub reason: String,
    /// The hidden modes (cancelled in the loop) in the closed right half plane.
    pub unstable_hidden: Vec<Root>,
}

/// A peak of |F(jω)|.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Peak {
    /// max over ω ≥ 0 of |F(jω)| (∞ for a closed-loop pole on the imaginary axis).
    pub value: f64,
    /// Where: rad/s (0 for the dc value, ∞ — JSON null — for the limit ω → ∞).
    pub w: f64,
}

/// Robustness margins of the loop.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Robustness {
    /// Peak sensitivity Ms = max|S(jω)| (1/Ms is the distance of L(jω) from −1).
    pub ms: Peak,
    /// Peak complementary sensitivity Mt = max|T(jω)|.
    pub mt: Peak,
    /// Delay margin (s): the smallest extra loop delay that makes the loop unstable, min over
    /// gain crossings of PM/ω_c with PM in [0°, 360°).
    pub delay_margin: f64,
    /// The gain crossing where it is attained (rad/s).
    pub delay_margin_w: f64,
    /// True when the closed loop is internally stable (the margins mean robustness only then).
    pub closed_loop_stable: bool,
}

impl ClosedLoop {
    /// The loop of controller `c` and plant `g` (unity negative feedback).
    ///
    /// Errors: a controller and a plant of different domains ([`crate::lti::Domain::join`]),
    /// an improper loop L = C·G (an unfiltered derivative on a plant without enough roll-off:
    /// give the filter time constant), a loop that is not well posed (1 + L(∞) = 0), the root
    /// finder's.
    pub fn new(c: &Factored, g: &Factored) -> Result<ClosedLoop> {
        let l = loop_form(c, g)?;
        l.require_proper("the loop L = C·G", false)?;
        let (characteristic, poles, hidden) = close(l.zeros(), l.poles(), l.gain(), -1.0)?;
        Ok(ClosedLoop {
            c: c.clone(),
            g: g.clone(),
            l,
            characteristic,
            poles,
            hidden,
        })
    }

    /// The loop L = C·G in factored form (every factor as given; cancellations kept as
    /// characteristic roots).
    pub fn loop_tf(&self) -> &Factored {
        &self.l
    }

    /// The characteristic polynomial D_C·D_G + N_C·N_G (monic D, before any cancellation).
    pub fn characteristic(&self) -> &Poly {
        &self.characteristic
    }

    /// The closed-loop poles: every root of the characteristic polynomial.
    pub fn poles(&self) -> &[Root] {
        &self.poles
    }

    /// The modes hidden by pole–zero cancellations in the loop.
    pub fn hidden(&self) -> &[Root] {
        &self.hidden
    }

    /// One of the loop's transfer functions, factored (its poles are the closed-loop poles
    /// as given; a hidden mode cancels in it or not, as the algebra says).
    ///
    /// Errors: the polynomial arithmetic's (orders beyond [`crate::MAX_ORDER`]).
    pub fn system(&self, which: LoopSystem) -> Result<Factored> {
        let (zeros, gain) = match which {
            LoopSystem::Loop => return Ok(self.l.clone()),
            LoopSystem::ClosedLoop => (self.l.zeros().to_vec(), self.l.gain()),
            LoopSystem::Sensitivity => (self.l.poles().to_vec(), 1.0),
            LoopSystem::ControlSensitivity => {
                let mut z = self.c.zeros().to_vec();
                z.extend_from_slice(self.g.poles());
                (z, self.c.gain())
            }
        };
        self.over_characteristic(zeros, gain)
    }

    /// G·S = G/(1 + L) (input disturbance to output), the fourth of the loop's transfer
    /// functions.
    pub fn plant_sensitivity(&self) -> Result<Factored> {
        let mut z = self.g.zeros().to_vec();
        z.extend_from_slice(self.c.poles());
        self.over_characteristic(z, self.g.gain())
    }

    fn over_characteristic(&self, zeros: Vec<Root>, gain: f64) -> Result<Factored> {
        let zeros = if gain == 0.0 { Vec::new() } else { zeros };
        let num = Poly::from_root_list(&zeros)?.scale(gain);
        let tf =
            TransferFunction::new(num, self.characteristic.clone())?.with_domain(self.l.domain());
        Factored::from_parts(tf, self.poles.clone(), zeros)
    }

    /// Internal stability from the characteristic roots; an unstable hidden mode is named.
    pub fn internal_stability(&self) -> InternalStability {
        let discrete = self.l.domain().is_discrete();
        let (class, why) = classify_in(&self.poles, discrete);
        let side = |r: &Root| {
            if discrete {
                crate::analysis::discrete::circle_side(r.value)
            } else {
                r.half_plane()
            }
        };
        let unstable_hidden: Vec<Root> = self
            .hidden
            .iter()
            .filter(|r| side(r) != HalfPlane::Left)
            .copied()
            .collect();
        let stable = class == super::StabilityClass::Stable;
        let reason = if unstable_hidden.is_empty() {
            format!("closed loop: {why}")
        } else {
            let (_, hidden_why) = classify_in(&unstable_hidden, discrete);
            format!(
                "the loop is internally unstable: hidden mode (cancelled between controller and plant) {hidden_why}"
            )
        };
        InternalStability {
            stable,
            reason,
            unstable_hidden,
        }
    }

    /// Ms, Mt and the delay margin (see the [module docs](self)).
    ///
    /// Errors: a loop without a finite gain crossing (|L(jω)| never equals 1: the delay
    /// margin is undefined), those of the margins.
    pub fn robustness(&self) -> Result<Robustness> {
        let m = self.l.margins()?;
        let (delay_margin, delay_margin_w) =
            m.delay_margin
                .zip(m.delay_margin_w)
                .ok_or_else(|| LtiError::Undefined {
                    what: "the delay margin".into(),
                    reason: "the loop has no finite gain crossing (|L(jω)| never equals 1)".into(),
                })?;
        Ok(Robustness {
            ms: certified_peak(&self.system(LoopSystem::Sensitivity)?)?,
            mt: certified_peak(&self.system(LoopSystem::ClosedLoop)?)?,
            delay_margin,
            delay_margin_w,
            closed_loop_stable: self.internal_stability().stable,
        })
    }
}

/// L = C·G with every factor kept and, up to [`crate::MAX_ORDER`], its coefficients as the
/// source (so the margins of L come from the polynomials in ω², like a plant typed by its
/// coefficients); beyond that the factors alone ([`Factored::series`]).
fn loop_form(c: &Factored, g: &Factored) -> Result<Factored> {
    let domain = c.domain().join(g.domain(), "the loop L = C·G")?;
    let (zeros, poles, k) = series_parts(c, g);
    let n: usize = poles.iter().map(|r| r.multiplicity).sum();
    if k == 0.0 || n > crate::MAX_ORDER {
        return Ok(Factored::from_zpk(&zeros, &poles, k)?.with_domain(domain));
    }
    let num = Poly::from_root_list(&zeros)?.scale(k);
    let tf = TransferFunction::new(num, Poly::from_root_list(&poles)?)?.with_domain(domain);
    Factored::from_parts(tf, poles, zeros)
}

/// The controller of a plant's loop: its own, or C = 1 (`p:kp=1`) when a loop is selected
/// without one.
///
/// ```
/// use ltikit::lti::{Controller, Plant};
/// use ltikit::analysis::closed_loop::loop_controller;
/// let mut p = Plant::from_text(None, "1 1").unwrap();
/// assert_eq!(loop_controller(&p).unwrap().to_string(), "p:kp=1");
/// p.controller = Some(Controller::parse("pi:kp=2,ki=1").unwrap());
/// assert_eq!(loop_controller(&p).unwrap().to_string(), "pi:kp=2,ki=1");
/// ```
pub fn loop_controller(plant: &Plant) -> Result<Controller> {
    match &plant.controller {
        Some(c) => Ok(c.clone()),
        None => Controller::parse("p:kp=1"),
    }
}

/// What the analyses of `plant` read, given `g` (the plant, or its chosen channel, factored):
/// `g` itself, or — with a loop selection ([`Plant::selection`]) — that transfer function of
/// the loop with the plant's controller (C = 1, plain unity feedback, without one), with the
/// loop.
///
/// Errors: those of [`ClosedLoop::new`]; an improper loop caused by an unfiltered derivative
/// says to give the filter time constant.
///
/// ```
/// use ltikit::lti::{Controller, Plant, controller::LoopSystem};
/// use ltikit::analysis::closed_loop::select;
/// let mut p = Plant::from_text(Some("4"), "1 0.8 4").unwrap();
/// p.controller = Some(Controller::parse("pi:kp=1,ki=1").unwrap());
/// p.selection = Some(LoopSystem::ClosedLoop);
/// let (t, cl) = select(&p, p.factored().unwrap()).unwrap();
/// assert_eq!(t.order(), 3);
/// assert!(cl.unwrap().internal_stability().stable);
/// ```
pub fn select(plant: &Plant, g: Factored) -> Result<(Factored, Option<ClosedLoop>)> {
    let Some(which) = plant.selection else {
        return Ok((g, None));
    };
    let c = loop_controller(plant)?;
    // a continuous controller in front of a discrete-time plant: C(z) by its method
    let cf = c.tf()?.factored()?;
    let cf = match g.domain().dt() {
        // a controller given by coefficients is already in the loop's variable: C(z)
        Some(dt) if c.is_given_in_loop_variable() => {
            cf.with_domain(crate::lti::Domain::discrete(dt)?)
        }
        Some(dt) => cf.c2d(dt, c.method())?,
        None => cf,
    };
    if g.delay() > 0.0 {
        // L·e^(−sT) is the loop; its closed loop is not rational (`analysis::delay`)
        if which == LoopSystem::Loop {
            return Ok((cf.series(&g)?, None));
        }
        return Err(LtiError::invalid(format!(
            "{} around a dead time e^(-{} s) is not a rational transfer function: this \
             analysis needs one (analyze, step and response treat the delayed loop exactly; \
             or replace the delay by a Padé approximant, `pade`)",
            which.formula(),
            crate::fmt::fmt_num(g.delay())
        )));
    }
    let cl = ClosedLoop::new(&cf, &g).map_err(|e| match e {
        LtiError::Improper { .. } if c.is_improper() => LtiError::invalid(format!(
            "{e}: the controller {c} has an unfiltered derivative; give its filter time constant (e.g. tf=0.01)"
        )),
        e => e,
    })?;
    Ok((cl.system(which)?, Some(cl)))
}

/// [`peak`] checked against the certified L∞ norm of `f` (`analysis::norms`, the
/// Hamiltonian iteration): when that finds a gain higher by more than 1e-9 relative — a
/// peak the local maxima missed — its lower bound (an evaluation of |F| at its frequency) is
/// the peak. Ms and Mt of [`ClosedLoop::robustness`] come from here.
fn certified_peak(f: &Factored) -> Result<Peak> {
    let p = peak(f)?;
    if !p.value.is_finite() {
        return Ok(p);
    }
    match f.linf_norm() {
        Ok(n) if n.infinite.is_none() && n.lower > p.value * (1.0 + 1e-9) => Ok(Peak {
            value: n.lower,
            w: n.w,
        }),
        _ => Ok(p),
    }
}

/// max over ω ≥ 0 of |F(jω)|: the local maxima (roots of d|F|²/dω², polished), the value at
/// ω = 0 and the limit at ω → ∞; ∞ at the lowest imaginary-axis pole.
pub fn peak(f: &Factored) -> Result<Peak> {
    if let Some(dt) = f.domain().dt() {
        let (value, w) = crate::analysis::discrete::peak(f, dt);
        return Ok(Peak { value, w });
    }
    if let Some(beta) = f
        .reduced_poles()
        .iter()
        .filter(|p| p.half_plane() == HalfPlane::Axis)
        .map(|p| p.value.im.abs())
        .min_by(f64::total_cmp)
    {
        return Ok(Peak {
            value: f64::INFINITY,
            w: beta,
        });
    }
    let at = |w: f64| f.eval(num_complex::Complex64::new(0.0, w)).norm();
    let mut best = Peak {
        value: at(0.0),
        w: 0.0,
    };
    let inf = match f.relative_degree() {
        Some(0) => f.gain().abs(),
        _ => 0.0,
    };
    if inf > best.value {
        best = Peak {
            value: inf,
            w: f64::INFINITY,
        };
    }
    for w in local_maxima(f)? {
        let v = at(w);
        if v > best.value {
            best = Peak { value: v, w };
        }
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f(n: &[f64], d: &[f64]) -> Factored {
        TransferFunction::from_descending(n, d)
            .unwrap()
            .factored()
            .unwrap()
    }

    #[test]
    fn cancelled_unstable_plant_pole_is_named() {
        // C = (s − 1)/(s + 3), G = 1/((s − 1)(s + 2)): T looks stable, the loop is not
        let cl =
            ClosedLoop::new(&f(&[1.0, -1.0], &[1.0, 3.0]), &f(&[1.0], &[1.0, 1.0, -2.0])).unwrap();
        let st = cl.internal_stability();
        assert!(!st.stable);
        assert_eq!(st.unstable_hidden.len(), 1);
        assert!(st.reason.contains("hidden mode"), "{}", st.reason);
        assert!(st.reason.contains("s = 1"), "{}", st.reason);
        let t = cl.system(LoopSystem::ClosedLoop).unwrap();
        assert!(t.stability().bibo_stable);
        // G·S shows the unstable pole
        assert!(!cl.plant_sensitivity().unwrap().stability().bibo_stable);
    }

    #[test]
    fn no_gain_crossing_is_an_error() {
        let cl = ClosedLoop::new(&f(&[0.5], &[1.0]), &f(&[1.0], &[1.0, 1.0])).unwrap();
        let e = cl.robustness().unwrap_err().to_string();
        assert!(e.contains("no finite gain crossing"), "{e}");
    }
}
