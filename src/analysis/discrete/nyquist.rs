//! The Nyquist contour in z: G along the unit circle z = e^(jθ), θ from −π to π, with arcs
//! outside the circle around the poles on it (see [`crate::analysis::nyquist`]).

use std::f64::consts::PI;

use num_complex::Complex64;

use crate::analysis::nyquist::{
    ContourPart, NyquistContour, NyquistPoint, Piece, mirrored, sample_piece,
    winding_about_minus_one,
};
use crate::analysis::{Factored, HalfPlane};
use crate::error::Result;

/// Indentation radius relative to the pole's neighbourhood (as in s).
const INDENT_REL: f64 = 1e-3;

/// A pole on the unit circle in the upper half (0 ≤ α ≤ π), its multiplicity, the radius ε of
/// its arc, the half-angle δ of the circle it skips (|e^(jδ) − 1| = ε) and its neighbourhood.
#[derive(Debug, Clone, Copy)]
struct CirclePole {
    alpha: f64,
    m: usize,
    eps: f64,
    delta: f64,
    scale: f64,
}

impl CirclePole {
    /// The arc around the pole from ψ = `from` to `to`, in units of its full half-sweep
    /// π/2 + δ/2 (−1: the circle point before the pole, +1: after, 0: farthest out).
    fn bump(&self, from: f64, to: f64) -> Piece {
        let half = 0.5 * PI + 0.5 * self.delta;
        Piece::Bump {
            alpha: self.alpha,
            eps: self.eps,
            psi0: from * half,
            psi1: to * half,
            m: self.m,
        }
    }
}

/// The poles on the unit circle (upper half, sorted by angle) and the count outside it.
fn circle_poles(g: &Factored) -> (Vec<CirclePole>, usize) {
    let roots: Vec<Complex64> = g
        .reduced_poles()
        .iter()
        .chain(g.reduced_zeros())
        .map(|r| r.value)
        .collect();
    let mut on = Vec::new();
    let mut outside = 0usize;
    for p in g.reduced_poles() {
        match g.side_of(p.value) {
            HalfPlane::Right => outside += p.multiplicity,
            HalfPlane::Axis if p.value.im >= 0.0 => {
                let alpha = p.value.im.abs().atan2(p.value.re);
                // the exact place on the circle: |e^(jα)| = 1
                let here = Complex64::from_polar(1.0, alpha);
                let scale = roots
                    .iter()
                    .map(|r| (r - here).norm())
                    .filter(|&d| d > 1e-9)
                    .fold(1.0, f64::min);
                let eps = INDENT_REL * scale;
                on.push(CirclePole {
                    alpha,
                    m: p.multiplicity,
                    eps,
                    delta: 2.0 * (0.5 * eps).asin(),
                    scale,
                });
            }
            _ => {}
        }
    }
    on.sort_by(|a, b| a.alpha.total_cmp(&b.alpha));
    (on, outside)
}

/// The angle where the first stretch of the circle starts when z = 1 is not a pole: 10⁻³ of
/// the smallest |ln r| (the equivalent |s|·T) of the roots off z = 1, at most 10⁻³.
fn first_angle(g: &Factored) -> f64 {
    g.reduced_poles()
        .iter()
        .chain(g.reduced_zeros())
        .map(|r| Complex64::new(r.value.norm().ln(), r.value.im.atan2(r.value.re)).norm())
        .filter(|v| v.is_finite() && *v > 1e-12)
        .fold(1.0, f64::min)
        * 1e-3
}

/// Samples the pieces in order, dropping a point shared by two adjacent pieces.
fn sample_all(g: &Factored, pieces: &[Piece]) -> Vec<NyquistPoint> {
    let mut out: Vec<NyquistPoint> = Vec::new();
    for &piece in pieces {
        let before = out.len();
        sample_piece(g, piece, &mut out);
        if before > 0 && out.len() > before {
            let (a, b) = (out[before - 1].s, out[before].s);
            if (a - b).norm() <= 1e-12 {
                out.remove(before);
            }
        }
    }
    out
}

/// The contour of a discrete plant with period `dt` (G proper; `g_inf` = G(∞); `ill_posed`
/// when 1 + G(∞) = 0).
#[allow(clippy::float_cmp)] // atan2(0, x) is exactly 0 or π for a real pole at z = ±1
pub(crate) fn nyquist_contour(
    g: &Factored,
    dt: f64,
    g_inf: f64,
    ill_posed: bool,
) -> Result<NyquistContour> {
    let (on, outside) = circle_poles(g);
    let at_one = on.first().filter(|p| p.alpha == 0.0).copied();
    let at_minus_one = on.last().filter(|p| p.alpha == PI).copied();
    // The upper half θ ∈ [0, π]: stretches of the circle between the arcs.
    let mut pieces = Vec::new();
    let mut start = match at_one {
        Some(p) => p.delta,
        None => first_angle(g),
    };
    let mut first = true;
    for p in on.iter().filter(|p| p.alpha > 0.0 && p.alpha < PI) {
        pieces.push(Piece::Unit {
            a: start,
            b: p.alpha - p.delta,
            log: first,
        });
        pieces.push(p.bump(-1.0, 1.0));
        start = p.alpha + p.delta;
        first = false;
    }
    match at_minus_one {
        Some(p) => {
            pieces.push(Piece::Unit {
                a: start,
                b: PI - p.delta,
                log: first,
            });
            // up to the arc's farthest point −1 − ε, on the real axis
            pieces.push(p.bump(-1.0, 0.0));
        }
        None => pieces.push(Piece::Unit {
            a: start,
            b: PI,
            log: first,
        }),
    }
    let positive = sample_all(g, &pieces);
    let mut middle = Vec::new();
    match at_one {
        Some(p) => {
            sample_piece(g, p.bump(-1.0, 1.0), &mut middle);
            // the arc's ends e^(∓jδ) start the mirror's last and the upper half's first stretch
            middle.remove(0);
            middle.pop();
        }
        None => {
            let z = Complex64::new(1.0, 0.0);
            middle.push(NyquistPoint {
                s: z,
                g: g.eval(z),
                part: ContourPart::UnitCircle,
            });
        }
    }
    // The upper half ends on the real axis (z = −1, or −1 − ε on the arc around a pole there)
    // where its mirror starts: the curve is closed.
    let mut points = mirrored(&positive);
    points.extend(middle);
    points.extend(positive);
    let display_radius = display_radius(&points, &on);
    let path: Vec<(Option<f64>, Complex64)> = points
        .iter()
        .map(|p| {
            (
                (p.part == ContourPart::UnitCircle).then(|| p.s.im.atan2(p.s.re)),
                p.g,
            )
        })
        .collect();
    let encirclements = if ill_posed {
        None
    } else {
        winding_about_minus_one(&path, |th| g.eval(Complex64::from_polar(1.0, th)))
    };
    Ok(NyquistContour {
        dt: Some(dt),
        points,
        g_at_infinity: g_inf,
        axis_poles: on.iter().map(|p| p.alpha / dt).collect(),
        indent_radius: on.iter().map(|p| p.eps).collect(),
        display_radius,
        open_loop_rhp_poles: outside,
        encirclements,
        closed_loop_rhp_poles: encirclements.map(|n| n + outside as i64),
    })
}

/// 1.5 × the largest of 1 and |G| on the circle away from its poles (farther than half the
/// pole's neighbourhood in angle); `None` without poles on the circle.
fn display_radius(points: &[NyquistPoint], on: &[CirclePole]) -> Option<f64> {
    if on.is_empty() {
        return None;
    }
    let near = |th: f64| {
        on.iter()
            .any(|p| (th.abs() - p.alpha).abs() < 0.5 * p.scale)
    };
    let finite = points
        .iter()
        .filter(|p| p.part == ContourPart::UnitCircle && !near(p.s.im.atan2(p.s.re)))
        .map(|p| p.g.norm())
        .filter(|v| v.is_finite())
        .fold(1.0, f64::max);
    Some(1.5 * finite)
}
