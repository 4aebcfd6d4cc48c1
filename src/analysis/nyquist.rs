//! The Nyquist contour: G(s) along the D contour, with indentations around imaginary-axis
//! poles, and the encirclement count of −1.
//!
//! The D contour runs up the imaginary axis from s = −j∞ to +j∞ and closes through the right
//! half plane at infinity (clockwise). Poles of G on the imaginary axis are passed on small
//! semicircles s = jω_p + ε e^{jθ}, θ from −90° to +90°, i.e. to their **right**, so they count
//! as outside the contour: P is the number of poles with Re p > 0 strictly, and Nyquist's
//! criterion reads Z = N + P, with N the clockwise encirclements of −1 by G and Z the
//! closed-loop poles (of G/(1 + G)) in the right half plane.
//!
//! G is used **in lowest terms** (common pole-zero factors cancelled, as the input-output map
//! it is). ε is 10⁻³ of the distance from the pole to its nearest other root (of the scale of
//! the lowest corner frequency for a pole at s = 0), so the semicircle's image is the
//! textbook arc of radius ~|residue|/ε^m sweeping m·180° clockwise for an m-fold pole.
//!
//! The samples are adaptive: between neighbours the angle of G and of 1 + G may turn by at
//! most 8° (and |G| change by at most 30 %), so a resonance or a pass near −1 is resolved
//! and the winding number is exact.
//!
//! **In discrete time** (a plant with a sampling period T) the contour is the unit circle
//! z = e^(jθ), θ = ωT from −π to π (the image for θ in [0, π] and its conjugate), traversed
//! counterclockwise: the exterior of the disc, the unstable region, lies on its right, as the
//! right half plane lies on the right of the D contour — so it is gone round clockwise, and
//! z = ∞ belongs to it (a proper G is finite there and D + N keeps the degree of D, so the
//! closed loop has no pole there). Poles of G on the circle, e^(jα), are passed on small arcs
//! z = e^(jα)(1 + ε e^(jψ)) **outside** the circle (ψ through 0, from the circle point
//! e^(j(α − δ)) to e^(j(α + δ)), ε = 2 sin(δ/2)), so they count as inside: P is the number of
//! poles with |p| > 1 strictly, and the criterion is the same Z = N + P, N the clockwise
//! encirclements of −1 and Z the closed-loop poles outside the unit circle. The arc around an
//! integrator z = 1 maps, as the indentation around s = 0 does, to a large clockwise arc of
//! radius ~|residue|/ε. ε is 10⁻³ of the distance from the pole to its nearest other pole or
//! zero (at most 10⁻³). The curve closes on itself at z = −1 (or on the arc around a pole
//! there), and the winding of G + 1 is refined in θ as it is in ω. An improper G (non-causal,
//! a pole at z = ∞) is refused; with 1 + G(∞) = 0 the loop is not causal and N is `None`.

use num_complex::Complex64;
use serde::Serialize;

use crate::analysis::factored::Factored;
use crate::error::Result;
use crate::lti::TransferFunction;
use crate::poly::{HalfPlane, half_plane};

/// Which part of the D contour a point lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ContourPart {
    /// s = jω on the imaginary axis.
    Axis,
    /// On a small semicircle around an imaginary-axis pole (or, in z, a small arc outside the
    /// unit circle around a pole on it).
    Indentation,
    /// z = e^(jωT) on the unit circle (a discrete-time plant; −π/T ≤ ω ≤ π/T).
    UnitCircle,
}

/// One sample of the contour.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NyquistPoint {
    /// The point s of the D contour (Im s < 0 on the mirror half, ω < 0); for a discrete plant
    /// the point z of the unit-circle contour.
    pub s: Complex64,
    /// G(s) (G(z) in discrete time).
    pub g: Complex64,
    /// Axis, unit circle or indentation.
    pub part: ContourPart,
}

/// G along the Nyquist D contour, in contour order (ω from −∞ to +∞); for a discrete plant G
/// along the unit circle z = e^(jωT), ω from −π/T to π/T (see the [module
/// documentation](self)).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NyquistContour {
    /// The sampling period T of a discrete plant (`None`: continuous time, the D contour).
    pub dt: Option<f64>,
    /// The samples, ω from −∞ to +∞ (the ω < 0 half is the mirror image of the ω > 0 half);
    /// in discrete time from −π/T to π/T.
    pub points: Vec<NyquistPoint>,
    /// lim G(jω) for ω → ±∞ (the whole infinite semicircle maps to this real number: the
    /// direct feedthrough, 0 for a strictly proper G). In discrete time G(z → ∞), the
    /// feedthrough, which is not on the contour.
    pub g_at_infinity: f64,
    /// Frequencies ω ≥ 0 of the imaginary-axis poles of G (0 for poles at the origin), each
    /// passed on a semicircle of radius `indent_radius[k]`. In discrete time the frequencies
    /// ω = θ/T, 0 ≤ θ ≤ π, of the poles e^(jθ) on the unit circle (0 for z = 1, π/T for
    /// z = −1), each passed outside the circle on an arc of radius `indent_radius[k]`.
    pub axis_poles: Vec<f64>,
    /// Indentation radii, one per entry of `axis_poles`.
    pub indent_radius: Vec<f64>,
    /// With imaginary-axis poles, a radius that contains the finite part of the curve (1.5 ×
    /// the largest of 1, |G(∞)| and |G(jω)| for ω farther than half the pole's neighbourhood
    /// scale from every imaginary-axis pole); beyond it the curve only heads off to infinity.
    /// `None` when the curve is bounded.
    pub display_radius: Option<f64>,
    /// P: poles of G (lowest terms) with Re p > 0, with multiplicity; in discrete time the
    /// poles strictly outside the unit circle.
    pub open_loop_rhp_poles: usize,
    /// N: clockwise encirclements of −1 by G; `None` when the curve passes through −1.
    pub encirclements: Option<i64>,
    /// Z = N + P: closed-loop right-half-plane poles of G/(1 + G) (in discrete time: poles
    /// outside the unit circle); `None` with N.
    pub closed_loop_rhp_poles: Option<i64>,
}

/// Maximum turn of the angle of G or 1 + G between neighbouring samples.
const MAX_TURN: f64 = 8.0 * std::f64::consts::PI / 180.0;
/// Maximum relative change of |G| between neighbouring samples.
const MAX_REL: f64 = 0.3;
/// Bisection depth limit per initial interval.
const MAX_DEPTH: u32 = 12;
/// Cap on the number of samples of one half of the contour.
const MAX_POINTS: usize = 40_000;
/// Indentation radius relative to the pole's neighbourhood.
const INDENT_REL: f64 = 1e-3;

/// A parametrised piece of the positive-frequency half of the contour.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Piece {
    /// s = j·10^u for u in [a, b].
    Axis { a: f64, b: f64 },
    /// s = jω + ε e^{jθ} for θ in [−π/2, π/2].
    Arc { w: f64, eps: f64, m: usize },
    /// z = e^{jθ} for θ in [a, b] (0 < a: log-spaced in θ when `log`).
    Unit { a: f64, b: f64, log: bool },
    /// z = e^{jα}(1 + ε e^{jψ}) for ψ in [psi0, psi1]: around a pole e^{jα} on the unit
    /// circle, outside it (ψ = 0 points away from the origin).
    Bump {
        alpha: f64,
        eps: f64,
        psi0: f64,
        psi1: f64,
        m: usize,
    },
}

impl Piece {
    fn s(&self, t: f64) -> Complex64 {
        match *self {
            Piece::Axis { a, b } => Complex64::new(0.0, 10f64.powf(a + (b - a) * t)),
            Piece::Arc { w, eps, .. } => {
                let th = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * t;
                Complex64::new(eps * th.cos(), w + eps * th.sin())
            }
            Piece::Unit { a, b, log } => {
                let th = if log {
                    10f64.powf(a.log10() + (b.log10() - a.log10()) * t)
                } else {
                    a + (b - a) * t
                };
                Complex64::from_polar(1.0, th)
            }
            Piece::Bump {
                alpha,
                eps,
                psi0,
                psi1,
                ..
            } => {
                let psi = psi0 + (psi1 - psi0) * t;
                Complex64::from_polar(1.0, alpha)
                    * (Complex64::new(1.0, 0.0) + Complex64::from_polar(eps, psi))
            }
        }
    }

    fn initial(&self) -> usize {
        match *self {
            // 60 per decade; a span that is not finite (a log of 0) gets the minimum, and no
            // piece starts with more than MAX_POINTS samples.
            Piece::Axis { a, b } if (b - a).is_finite() => {
                (((b - a) * 60.0).ceil() as usize).clamp(8, MAX_POINTS)
            }
            Piece::Axis { .. } => 8,
            Piece::Arc { m, .. } => 16 * m.max(1),
            Piece::Unit { a, b, log: true } if a > 0.0 && (b / a).is_finite() => {
                (((b / a).log10() * 60.0).ceil() as usize).clamp(16, MAX_POINTS)
            }
            Piece::Unit { a, b, .. } => {
                ((200.0 * (b - a) / std::f64::consts::PI).ceil() as usize).clamp(16, MAX_POINTS)
            }
            Piece::Bump { psi0, psi1, m, .. } => ((16.0 * m.max(1) as f64 * (psi1 - psi0).abs()
                / std::f64::consts::PI)
                .ceil() as usize)
                .clamp(8, MAX_POINTS),
        }
    }

    fn part(&self) -> ContourPart {
        match self {
            Piece::Axis { .. } => ContourPart::Axis,
            Piece::Arc { .. } | Piece::Bump { .. } => ContourPart::Indentation,
            Piece::Unit { .. } => ContourPart::UnitCircle,
        }
    }
}

/// True when the step from `a` to `b` is too coarse.
fn too_coarse(a: Complex64, b: Complex64) -> bool {
    let one = Complex64::new(1.0, 0.0);
    let turn = |x: Complex64, y: Complex64| {
        if x.norm() == 0.0 || y.norm() == 0.0 {
            0.0
        } else {
            (y / x).arg().abs()
        }
    };
    let (na, nb) = (a.norm(), b.norm());
    let rel = (na - nb).abs() / na.max(nb).max(1e-300);
    turn(a, b) > MAX_TURN
        || turn(a + one, b + one) > MAX_TURN
        || (rel > MAX_REL && na.max(nb) > 1e-6)
}

/// Samples one piece adaptively, appending to `out` (without duplicating a shared endpoint).
pub(crate) fn sample_piece(g: &Factored, piece: Piece, out: &mut Vec<NyquistPoint>) {
    let n = piece.initial();
    let eval = |t: f64| {
        let s = piece.s(t);
        (t, s, g.eval_delayed(s))
    };
    let mut prev = eval(0.0);
    out.push(NyquistPoint {
        s: prev.1,
        g: prev.2,
        part: piece.part(),
    });
    for k in 1..=n {
        let next = eval(k as f64 / n as f64);
        // Depth-first bisection of [prev, next].
        let mut stack = vec![(next, 0u32)];
        let mut left = prev;
        while let Some((right, depth)) = stack.pop() {
            if depth < MAX_DEPTH && out.len() < MAX_POINTS && too_coarse(left.2, right.2) {
                let mid = eval(0.5 * (left.0 + right.0));
                stack.push((right, depth + 1));
                stack.push((mid, depth + 1));
                continue;
            }
            out.push(NyquistPoint {
                s: right.1,
                g: right.2,
                part: piece.part(),
            });
            left = right;
        }
        prev = next;
    }
}

/// The Nyquist contour of `g` (see the module documentation).
///
/// Errors: an improper G (G(jω) → ∞ as ω → ∞), or a failure of the root finder.
///
/// ```
/// use ltikit::TransferFunction;
/// use ltikit::analysis::nyquist_contour;
/// // K/(s + 1)³ with K = 10 is unstable in unity feedback (K > 8): two closed-loop RHP poles.
/// let g = TransferFunction::from_descending(&[10.0], &[1.0, 3.0, 3.0, 1.0]).unwrap();
/// let n = nyquist_contour(&g.factored().unwrap()).unwrap();
/// assert_eq!(n.open_loop_rhp_poles, 0);
/// assert_eq!(n.encirclements, Some(2));
/// assert_eq!(n.closed_loop_rhp_poles, Some(2));
/// ```
pub fn nyquist_contour(g: &Factored) -> Result<NyquistContour> {
    g.require_proper("Nyquist plot", false)?;
    let g_inf = if g.relative_degree() == Some(0) {
        g.gain()
    } else {
        0.0
    };
    if let Some(dt) = g.domain().dt() {
        // 1 + G(∞) = 0: D + N drops degree, the loop is not causal (a pole at z = ∞).
        let ill_posed = tiny_about_minus_one(Complex64::new(1.0 + g_inf, 0.0), g_inf.into());
        return crate::analysis::discrete::nyquist_contour(g, dt, g_inf, ill_posed);
    }
    if g.delay() > 0.0 && g_inf != 0.0 {
        return Err(crate::LtiError::invalid(format!(
            "Nyquist plot of a biproper loop with a dead time: G(∞)·e^(−jωT) circles at radius \
             {} for ever (the curve never closes); add a pole, or replace the delay by a Padé \
             approximant (`pade`)",
            crate::fmt::fmt_sig(g_inf.abs(), 6)
        )));
    }
    let mut geo = Geometry::of(g);
    if g.delay() > 0.0 {
        geo.w_end = spiral_end(g, geo.w_end);
    }
    let positive = geo.positive_half(g);
    let middle = geo.middle(g);
    let mut points = mirrored(&positive);
    points.extend(middle);
    points.extend(positive.iter().copied());
    let display_radius = geo.display_radius(&points, g_inf);
    // The axis ends join ω = ±∞, where G = G(∞); a segment on the axis that turns too far is
    // refined in ω.
    let at_inf = Complex64::new(g_inf, 0.0);
    let path: Vec<(Option<f64>, Complex64)> = std::iter::once((Some(f64::NEG_INFINITY), at_inf))
        .chain(
            points
                .iter()
                .map(|p| ((p.part == ContourPart::Axis).then_some(p.s.im), p.g)),
        )
        .chain(std::iter::once((Some(f64::INFINITY), at_inf)))
        .collect();
    let encirclements = winding_about_minus_one(&path, |w| g.eval_delayed(Complex64::new(0.0, w)));
    Ok(NyquistContour {
        dt: None,
        points,
        g_at_infinity: g_inf,
        axis_poles: geo.axis.iter().map(|a| a.0).collect(),
        indent_radius: geo.eps,
        display_radius,
        open_loop_rhp_poles: geo.rhp,
        encirclements,
        closed_loop_rhp_poles: encirclements.map(|n| n + geo.rhp as i64),
    })
}

/// The mirror half of the contour: the conjugates of the positive half, in reverse order.
pub(crate) fn mirrored(positive: &[NyquistPoint]) -> Vec<NyquistPoint> {
    positive
        .iter()
        .rev()
        .map(|p| NyquistPoint {
            s: p.s.conj(),
            g: p.g.conj(),
            part: p.part,
        })
        .collect()
}

/// Where the contour must go around poles: the imaginary-axis poles (ω ≥ 0, sorted, with
/// multiplicity), their neighbourhood scales and indentation radii, the right-half-plane pole
/// count and the span of the corner frequencies.
struct Geometry {
    axis: Vec<(f64, usize)>,
    scales: Vec<f64>,
    eps: Vec<f64>,
    rhp: usize,
    w_lo: f64,
    /// Where the axis part ends (the curve is at G(∞) beyond it).
    w_end: f64,
}

/// Where the spiral of a strictly proper loop with a dead time may end: beyond twice the
/// last frequency (on the factored form's sampling grid, up to `w_end`) at which |G| ≥ 0.02,
/// the curve stays inside a circle of radius 0.02 about the origin, far from −1 — it can
/// encircle nothing more, and its remaining turns are invisible.
fn spiral_end(g: &Factored, w_end: f64) -> f64 {
    let last = g
        .bode()
        .sampling_grid(50)
        .into_iter()
        .filter(|&w| w <= w_end && g.eval(Complex64::new(0.0, w)).norm() >= 0.02)
        .fold(0.0, f64::max);
    if last <= 0.0 {
        return w_end;
    }
    // past the grid's end |G| may still be large (a high-gain loop): double until it is not
    // (up to 1000 × the usual end, where the sampling cap would not follow the turns anyway)
    let mut w = last;
    while w < 1e3 * w_end && g.eval(Complex64::new(0.0, w)).norm() >= 0.02 {
        w *= 2.0;
    }
    2.0 * w
}

impl Geometry {
    fn of(g: &Factored) -> Geometry {
        let pz = g.pole_zero();
        let mut axis: Vec<(f64, usize)> = Vec::new();
        let mut rhp = 0usize;
        for p in &pz.reduced_poles {
            match half_plane(p.value) {
                HalfPlane::Axis if p.value.im >= 0.0 => axis.push((p.value.im, p.multiplicity)),
                HalfPlane::Right => rhp += p.multiplicity,
                _ => {}
            }
        }
        axis.sort_by(|a, b| a.0.total_cmp(&b.0));
        let roots: Vec<Complex64> = pz
            .reduced_poles
            .iter()
            .chain(pz.reduced_zeros.iter())
            .map(|r| r.value)
            .collect();
        let corners: Vec<f64> = roots
            .iter()
            .map(|r| r.norm())
            .filter(|&w| w > 0.0)
            .collect();
        let (w_lo, w_hi) = if corners.is_empty() {
            (1.0, 1.0)
        } else {
            (
                corners.iter().copied().fold(f64::INFINITY, f64::min),
                corners.iter().copied().fold(0.0, f64::max),
            )
        };
        // Neighbourhood scale and indentation radius of each axis pole.
        let scale_of = |w: f64| {
            if w == 0.0 {
                return w_lo;
            }
            let here = Complex64::new(0.0, w);
            roots
                .iter()
                .map(|r| (r - here).norm())
                .filter(|&d| d > 1e-12 * w)
                .fold(w, f64::min)
        };
        let scales: Vec<f64> = axis.iter().map(|&(w, _)| scale_of(w)).collect();
        let eps: Vec<f64> = scales.iter().map(|s| INDENT_REL * s).collect();
        Geometry {
            axis,
            scales,
            eps,
            rhp,
            w_lo,
            w_end: 1e3 * w_hi,
        }
    }

    /// Multiplicity of a pole at the origin.
    fn origin_pole(&self) -> Option<usize> {
        self.axis.first().filter(|a| a.0 == 0.0).map(|a| a.1)
    }

    /// The ω > 0 half after the origin: axis pieces between the indentations.
    fn positive_half(&self, g: &Factored) -> Vec<NyquistPoint> {
        let mut pieces = Vec::new();
        let mut start = if self.origin_pole().is_some() {
            self.eps[0]
        } else {
            1e-3 * self.w_lo
        };
        for (k, &(w, m)) in self.axis.iter().enumerate() {
            if w == 0.0 {
                continue;
            }
            pieces.push(Piece::Axis {
                a: start.max(f64::MIN_POSITIVE).log10(),
                b: (w - self.eps[k]).log10(),
            });
            pieces.push(Piece::Arc {
                w,
                eps: self.eps[k],
                m,
            });
            start = w + self.eps[k];
        }
        pieces.push(Piece::Axis {
            a: start.max(f64::MIN_POSITIVE).log10(),
            b: self.w_end.max(start * 10.0).log10(),
        });
        let mut positive = Vec::new();
        for piece in pieces {
            let before = positive.len();
            sample_piece(g, piece, &mut positive);
            // Adjacent pieces meet exactly (ω_p ± ε on both): drop the duplicate.
            if before > 0 && positive.len() > before {
                let (a, b) = (positive[before - 1].s, positive[before].s);
                if (a - b).norm() <= 1e-12 * a.norm().max(1.0) {
                    positive.remove(before);
                }
            }
        }
        positive
    }

    /// The middle: the semicircle around a pole at the origin, or the point ω = 0.
    fn middle(&self, g: &Factored) -> Vec<NyquistPoint> {
        let mut middle = Vec::new();
        if let Some(m) = self.origin_pole() {
            sample_piece(
                g,
                Piece::Arc {
                    w: 0.0,
                    eps: self.eps[0],
                    m,
                },
                &mut middle,
            );
            // The arc's ends are ∓jε: the mirror and the positive half start there.
            middle.remove(0);
            middle.pop();
        } else {
            let s = Complex64::new(0.0, 0.0);
            middle.push(NyquistPoint {
                s,
                g: g.eval(s),
                part: ContourPart::Axis,
            });
        }
        middle
    }

    /// Display radius: 1.5 × the largest |G| on the axis away from the imaginary-axis poles
    /// (None without such poles).
    fn display_radius(&self, points: &[NyquistPoint], g_inf: f64) -> Option<f64> {
        if self.axis.is_empty() {
            return None;
        }
        let near = |w: f64| {
            self.axis
                .iter()
                .zip(&self.scales)
                .any(|(&(wp, _), &sc)| (w - wp).abs() < 0.5 * sc)
        };
        let finite = points
            .iter()
            .filter(|p| p.part == ContourPart::Axis && p.s.im >= 0.0 && !near(p.s.im))
            .map(|p| p.g.norm())
            .filter(|v| v.is_finite())
            .fold(1.0f64.max(g_inf.abs()), f64::max);
        Some(1.5 * finite)
    }
}

/// Clockwise encirclements of −1 by the closed curve `path`: (parameter, G) pairs in contour
/// order, the last joined to the first by the caller's closing entries. The parameter is the
/// point's ω on the imaginary axis (±∞ for the ends of the axis; in z the angle θ on the unit
/// circle), `None` on an indentation.
///
/// The angle of G + 1 is summed segment by segment; a segment between two parametrised points
/// whose turn is too large to tell the way round (the curve sweeps close by −1 between two
/// samples: 1e8/(s + 1)² passes 2e-4 below −1 near ω = 1e4) is subdivided with `eval` (G at a
/// parameter; bisection, geometric for parameters of one sign) until every piece turns by
/// less than 0.9π. `None` when the curve passes through −1 (|G + 1| ≤ 1e-10·max(1, |G|)) or
/// refinement does not resolve it. The counterclockwise winding is negated: N counts
/// clockwise turns, the direction in which the contour goes round the unstable region.
pub(crate) fn winding_about_minus_one(
    path: &[(Option<f64>, Complex64)],
    eval: impl Fn(f64) -> Complex64,
) -> Option<i64> {
    let one = Complex64::new(1.0, 0.0);
    let mut total = 0.0;
    let mut prev: Option<(Option<f64>, Complex64)> = None;
    for &(w, g) in path {
        let z = g + one;
        if !(z.re.is_finite() && z.im.is_finite()) || tiny_about_minus_one(z, g) {
            return None;
        }
        if let Some((pw, pz)) = prev {
            total += segment_turn(pw, w, pz, z, &eval)?;
        }
        prev = Some((w, z));
    }
    let w = total / (2.0 * std::f64::consts::PI);
    ((w - w.round()).abs() < 0.05).then(|| -(w.round() as i64))
}

/// Largest angle of G + 1 per segment that still tells the way round.
const TURN_LIMIT: f64 = 0.9 * std::f64::consts::PI;

/// Deepest subdivision of one segment of the axis (2⁻⁶⁰ of it).
const MAX_REFINE_DEPTH: u32 = 60;

/// |G + 1| negligible against |G|: the curve passes through −1.
pub(crate) fn tiny_about_minus_one(z: Complex64, g: Complex64) -> bool {
    z.norm() <= 1e-10 * g.norm().max(1.0)
}

/// The turn of G + 1 along one segment of the contour from `za` to `zb`; `wa`, `wb` the
/// parameters of its ends (ω on the imaginary axis, ±∞ for the ends of the axis; θ on the
/// unit circle). `None` when it turns too far to tell the way round and cannot be refined.
fn segment_turn(
    wa: Option<f64>,
    wb: Option<f64>,
    za: Complex64,
    zb: Complex64,
    eval: &impl Fn(f64) -> Complex64,
) -> Option<f64> {
    let turn = (zb / za).arg();
    if turn.abs() <= TURN_LIMIT {
        return Some(turn);
    }
    match (wa, wb) {
        (Some(a), Some(b)) if !(a.is_infinite() && b.is_infinite()) => {
            refined_turn(a, b, za, zb, eval, 0)
        }
        _ => None,
    }
}

/// The turn of G + 1 from the parameter `wa` (value `za`) to `wb` (value `zb`), subdividing until
/// each piece turns by less than [`TURN_LIMIT`]; one end may be ±∞ (then the split point
/// moves out geometrically, ×16 per level).
fn refined_turn(
    wa: f64,
    wb: f64,
    za: Complex64,
    zb: Complex64,
    eval: &impl Fn(f64) -> Complex64,
    depth: u32,
) -> Option<f64> {
    let turn = (zb / za).arg();
    if turn.abs() <= TURN_LIMIT {
        return Some(turn);
    }
    if depth >= MAX_REFINE_DEPTH {
        return None;
    }
    let wm = if wa.is_infinite() || wb.is_infinite() {
        let finite = if wa.is_infinite() { wb } else { wa };
        let far = if wa.is_infinite() { wa } else { wb };
        if finite == 0.0 {
            far.signum()
        } else if finite.signum() == far.signum() {
            16.0 * finite
        } else {
            0.0
        }
    } else if wa * wb > 0.0 {
        wa.signum() * (wa * wb).abs().sqrt()
    } else {
        0.5 * (wa + wb)
    };
    // No split point strictly between the ends (they are adjacent doubles): give up.
    if !(wm.is_finite() && (wa < wm && wm < wb || wb < wm && wm < wa)) {
        return None;
    }
    let gm = eval(wm);
    let zm = gm + Complex64::new(1.0, 0.0);
    if !(zm.re.is_finite() && zm.im.is_finite()) || tiny_about_minus_one(zm, gm) {
        return None;
    }
    Some(
        refined_turn(wa, wm, za, zm, eval, depth + 1)?
            + refined_turn(wm, wb, zm, zb, eval, depth + 1)?,
    )
}

impl TransferFunction {
    /// The Nyquist contour (see [`nyquist_contour`]).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// // 1/(s(s + 1)): one pole at the origin, indented; stable in unity feedback.
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0, 0.0]).unwrap();
    /// let n = g.nyquist().unwrap();
    /// assert_eq!(n.axis_poles, vec![0.0]);
    /// assert_eq!(n.closed_loop_rhp_poles, Some(0));
    /// ```
    pub fn nyquist(&self) -> Result<NyquistContour> {
        nyquist_contour(&self.factored()?)
    }
}

impl Factored {
    /// The Nyquist contour ([`nyquist_contour`]).
    pub fn nyquist(&self) -> Result<NyquistContour> {
        nyquist_contour(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_close_pass_by_minus_one_is_resolved_not_undefined() {
        // 1e8/(s + 1)² passes about 2e-4 below −1 near ω = 1e4, beyond the sampled axis; the
        // closed loop s² + 2s + 1 + 1e8 is stable: N = 0, Z = 0. Also with 1e12 (2e-6 below).
        for k in [1e8, 1e12] {
            let g = crate::TransferFunction::from_descending(&[k], &[1.0, 2.0, 1.0]).unwrap();
            let n = g.nyquist().unwrap();
            assert_eq!(n.encirclements, Some(0), "{k}");
            assert_eq!(n.closed_loop_rhp_poles, Some(0), "{k}");
        }
        // −1e8/(s + 1)²: the curve starts at −1e8 and crosses the negative real axis once:
        // one clockwise encirclement... the closed loop s² + 2s + 1 − 1e8 has one RHP root.
        let g = crate::TransferFunction::from_descending(&[-1e8], &[1.0, 2.0, 1.0]).unwrap();
        assert_eq!(g.nyquist().unwrap().closed_loop_rhp_poles, Some(1));
    }
    use crate::analysis::stability::half_plane;

    fn tf(num: &[f64], den: &[f64]) -> TransferFunction {
        TransferFunction::from_descending(num, den).unwrap()
    }

    /// Closed-loop RHP poles counted directly from the roots of N + D.
    fn closed_loop_rhp(g: &TransferFunction) -> i64 {
        let cl = &(g.num() + g.den());
        cl.roots()
            .unwrap()
            .iter()
            .filter(|r| half_plane(r.value) == HalfPlane::Right)
            .map(|r| r.multiplicity as i64)
            .sum()
    }

    #[test]
    fn nyquist_criterion_matches_closed_loop_roots() {
        let cases: [(&[f64], &[f64]); 9] = [
            (&[10.0], &[1.0, 3.0, 3.0, 1.0]), // K/(s+1)³, K = 10 > 8: unstable
            (&[4.0], &[1.0, 3.0, 3.0, 1.0]),  // K = 4 < 8: stable
            (&[2.0], &[1.0, 3.0, 2.0, 0.0]),  // 2/(s(s+1)(s+2)): GM = 3, stable
            (&[10.0], &[1.0, 3.0, 2.0, 0.0]), // K = 10 > 6: unstable
            (&[2.0], &[1.0, -1.0]),           // 2/(s−1): P = 1, N = −1, stable
            (&[0.5], &[1.0, -1.0]),           // 0.5/(s−1): P = 1, unstable
            (&[1.0, 1.0], &[1.0, 0.0, 0.0]),  // (s+1)/s²: two poles at the origin
            (&[1.0], &[1.0, 0.2, 1.0, 0.0]),  // integrator with a resonance
            (&[1.0, 0.5], &[1.0, 0.0, 4.0, 0.0]), // poles at 0 and ±2j
        ];
        for (num, den) in cases {
            let g = tf(num, den);
            let n = g.nyquist().unwrap();
            assert_eq!(
                n.closed_loop_rhp_poles,
                Some(closed_loop_rhp(&g)),
                "G = {g}: N = {:?}, P = {}",
                n.encirclements,
                n.open_loop_rhp_poles
            );
        }
    }

    #[test]
    fn indentation_goes_round_the_poles_to_the_right() {
        let g = tf(&[1.0, 0.5], &[1.0, 0.0, 4.0, 0.0]);
        let n = g.nyquist().unwrap();
        assert_eq!(n.axis_poles, vec![0.0, 2.0]);
        let ind: Vec<_> = n
            .points
            .iter()
            .filter(|p| p.part == ContourPart::Indentation)
            .collect();
        assert!(!ind.is_empty());
        assert!(ind.iter().all(|p| p.s.re >= 0.0));
        // The samples near a pole are on the circle of the indentation radius.
        for p in ind.iter().filter(|p| (p.s.im - 2.0).abs() < 0.1) {
            assert!(((p.s - Complex64::new(0.0, 2.0)).norm() - n.indent_radius[1]).abs() < 1e-12);
        }
        assert!(n.display_radius.is_some());
        // Mirror symmetry: G(s̄) = conj G(s).
        let k = n.points.len();
        assert!(
            (n.points[0].g - n.points[k - 1].g.conj()).norm()
                < 1e-12 * n.points[0].g.norm().max(1.0)
        );
    }

    #[test]
    fn bounded_curve_has_no_display_radius_and_ends_at_g_infinity() {
        let g = tf(&[2.0, 1.0], &[1.0, 1.0]); // (2s + 1)/(s + 1): G(0) = 1, G(∞) = 2
        let n = g.nyquist().unwrap();
        assert!(n.display_radius.is_none());
        assert!((n.g_at_infinity - 2.0).abs() < 1e-15);
        assert!((n.points.last().unwrap().g - Complex64::new(2.0, 0.0)).norm() < 1e-2);
        assert_eq!(n.encirclements, Some(0));
    }

    #[test]
    fn rejects_improper_and_handles_cancellation() {
        assert!(tf(&[1.0, 0.0, 0.0], &[1.0, 1.0]).nyquist().is_err());
        // s/(s(s+1)): the origin pole cancels, no indentation.
        let n = tf(&[1.0, 0.0], &[1.0, 1.0, 0.0]).nyquist().unwrap();
        assert!(n.axis_poles.is_empty());
    }

    #[test]
    fn passing_through_minus_one_is_undetermined() {
        // G = −1 constant: the whole curve is the point −1.
        let n = tf(&[-1.0], &[1.0]).nyquist().unwrap();
        assert_eq!(n.encirclements, None);
    }

    #[test]
    fn origin_indentation_maps_to_the_textbook_arc() {
        // 1/(s(s + 1)): near s = 0, G ≈ 1/s = (1/ε) e^{−jθ}: radius 1/ε, sweeping from +90° to
        // −90° (clockwise) as θ goes from −90° to +90°.
        let n = tf(&[1.0], &[1.0, 1.0, 0.0]).nyquist().unwrap();
        let eps = n.indent_radius[0];
        let arc: Vec<_> = n
            .points
            .iter()
            .filter(|p| p.part == ContourPart::Indentation)
            .collect();
        assert!(arc.len() >= 16);
        for p in &arc {
            assert!((p.s.norm() - eps).abs() < 1e-12 * eps.max(1e-300) + 1e-18);
            assert!(
                (p.g.norm() * eps - 1.0).abs() < 2e-3,
                "|G|ε = {}",
                p.g.norm() * eps
            );
        }
        let first = arc.first().unwrap().g.arg().to_degrees();
        let last = arc.last().unwrap().g.arg().to_degrees();
        assert!(first > 80.0 && last < -80.0, "arc from {first}° to {last}°");
        // Clockwise: the angle decreases along the arc.
        assert!(arc.windows(2).all(|w| (w[1].g / w[0].g).arg() <= 1e-12));
    }
}
