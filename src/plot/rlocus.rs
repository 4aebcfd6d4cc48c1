//! Root locus PNG: the branches with direction arrows, the asymptotes, the open-loop poles and
//! zeros, break points and imaginary-axis crossings with their gains, and the closed-loop
//! poles at a chosen gain. Equal scales on both axes. A discrete-time locus draws the unit
//! circle (its stability boundary) and marks the unit-circle crossings instead.

use std::path::Path;

use num_complex::Complex64;

use super::legend::LegendEntry;
use super::options::PlotOptions;
use super::raster::Color;
use super::style::{LineStyle, MarkerShape, series_color};
use super::xy::{Curve, Marker, XyPlot, xy_png_with};
use crate::analysis::rlocus::RootLocus;
use crate::error::Result;
use crate::fmt::fmt_sig;
use crate::poly::Root;

/// What to draw: the locus, its label, and optionally the closed-loop poles at one gain.
///
/// ```
/// use ltikit::Poly;
/// use ltikit::analysis::rlocus::{root_locus, RootLocusOptions};
/// use ltikit::plot::RootLocusPlot;
/// let l = root_locus(&Poly::from_descending(&[1.0]).unwrap(),
///     &Poly::from_descending(&[1.0, 3.0, 2.0, 0.0]).unwrap(), &RootLocusOptions::default()).unwrap();
/// let p = RootLocusPlot { locus: &l, label: Some("1/(s(s+1)(s+2))"), marked: None };
/// assert!(p.view().0 .0 < -2.0);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct RootLocusPlot<'a> {
    /// The locus.
    pub locus: &'a RootLocus,
    /// The plant's name or transfer function, for the title.
    pub label: Option<&'a str>,
    /// A gain and the closed-loop poles there, marked with triangles.
    pub marked: Option<(f64, &'a [Root])>,
}

/// Colour of the asymptotes and the imaginary axis.
const GUIDE: Color = Color(120, 120, 120);
/// Colour of the closed-loop poles at the chosen gain.
const MARKED: Color = Color::BLACK;

impl RootLocusPlot<'_> {
    /// The points that must be in view: poles, zeros, break points, crossings, the centroid
    /// and the marked poles.
    fn features(&self) -> Vec<Complex64> {
        let l = self.locus;
        let mut v: Vec<Complex64> = l.poles.iter().map(|r| r.value).collect();
        v.extend(l.zeros.iter().map(|r| r.value));
        v.extend(l.break_points.iter().map(|b| Complex64::new(b.s, 0.0)));
        v.extend(
            l.crossings
                .iter()
                .map(|c| c.z.unwrap_or(Complex64::new(0.0, c.omega))),
        );
        if l.dt.is_some() {
            // the whole unit circle in view
            v.extend([Complex64::new(-1.0, 1.0), Complex64::new(1.0, -1.0)]);
        }
        if let Some(a) = &l.asymptotes {
            v.push(Complex64::new(a.centroid, 0.0));
        }
        if let Some((_, r)) = self.marked {
            v.extend(r.iter().map(|r| r.value));
        }
        v.retain(|z| z.re.is_finite() && z.im.is_finite());
        v
    }

    /// The drawn ranges ((x0, x1), (y0, y1)): the features, the imaginary axis, symmetric in
    /// y, with room around them for the branches' shapes.
    pub fn view(&self) -> ((f64, f64), (f64, f64)) {
        let f = self.features();
        let (mut x0, mut x1, mut y) = (0.0f64, 0.0f64, 0.0f64);
        for z in &f {
            x0 = x0.min(z.re);
            x1 = x1.max(z.re);
            y = y.max(z.im.abs());
        }
        let mut span = (x1 - x0).max(2.0 * y);
        if !(span > 0.0 && span.is_finite()) {
            span = f.iter().map(|z| z.norm()).fold(0.0, f64::max).max(1.0);
        }
        let pad = 0.5 * span;
        ((x0 - pad, x1 + pad), (-(y + pad), y + pad))
    }
}

/// The branch as polylines: the runs of points inside a box three times the view (branches
/// that go to infinity leave it; one that escapes at a finite gain comes back in a new run).
fn runs(path: &[Complex64], view: ((f64, f64), (f64, f64))) -> Vec<Vec<(f64, f64)>> {
    let ((x0, x1), (y0, y1)) = view;
    let (wx, wy) = (x1 - x0, y1 - y0);
    let inside =
        |z: &Complex64| z.re >= x0 - wx && z.re <= x1 + wx && z.im >= y0 - wy && z.im <= y1 + wy;
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    for z in path {
        if inside(z) {
            cur.push((z.re, z.im));
        } else {
            if !cur.is_empty() {
                // one point beyond, so the run reaches the frame's edge
                cur.push((z.re, z.im));
                out.push(std::mem::take(&mut cur));
            }
        }
    }
    if cur.len() > 1 {
        out.push(cur);
    }
    out
}

/// Branch colours: the palette without its red and grey (kept for nothing else, but they read
/// as guides or warnings).
fn branch_color(i: usize) -> Color {
    const ORDER: [usize; 8] = [0, 2, 3, 4, 5, 6, 8, 9];
    series_color(ORDER[i % ORDER.len()])
}

fn gain_text(k: f64) -> String {
    format!("K = {}", fmt_sig(k, 4))
}

/// The legend rows of the markers drawn.
fn legend(p: &RootLocusPlot) -> Vec<LegendEntry> {
    let l = p.locus;
    let black = Color::BLACK;
    let mut v = vec![
        LegendEntry::text(
            format!(
                "arrows: K from 0 to {}",
                if l.negative { "−∞" } else { "∞" }
            ),
            black,
        ),
        LegendEntry::marker("open-loop poles (K = 0)", MarkerShape::Cross, black),
    ];
    if !l.zeros.is_empty() {
        v.push(LegendEntry::marker(
            "open-loop zeros",
            MarkerShape::Circle,
            black,
        ));
    }
    if !l.fixed.is_empty() {
        v.push(LegendEntry::marker(
            "fixed poles (roots of N and D)",
            MarkerShape::CircledCross,
            black,
        ));
    }
    if !l.break_points.is_empty() {
        v.push(LegendEntry::marker(
            "break points",
            MarkerShape::Diamond,
            black,
        ));
    }
    if !l.crossings.is_empty() {
        v.push(LegendEntry::marker(
            if l.dt.is_some() {
                "unit-circle crossings"
            } else {
                "imaginary-axis crossings"
            },
            MarkerShape::Square,
            black,
        ));
    }
    if let Some((k, _)) = p.marked {
        v.push(LegendEntry::marker(
            format!("closed-loop poles at K = {}", fmt_sig(k, 4)),
            MarkerShape::Triangle,
            MARKED,
        ));
    }
    v
}

/// The x–y plot of a root locus (see [`RootLocusPlot`]).
fn xy(p: &RootLocusPlot) -> XyPlot {
    let l = p.locus;
    let view = p.view();
    let far = 10.0 * ((view.0.1 - view.0.0).abs() + (view.1.1 - view.1.0).abs());
    let discrete = l.dt.is_some();
    let mut curves = vec![if discrete {
        Curve::new((0..=256).map(|i| {
            let a = std::f64::consts::TAU * f64::from(i) / 256.0;
            (a.cos(), a.sin())
        }))
        .color(GUIDE)
        .width(0.9)
        .label("unit circle".to_string())
    } else {
        Curve::new([(0.0, view.1.0 - far), (0.0, view.1.1 + far)])
            .color(GUIDE)
            .width(0.6)
    }];
    for (i, path) in l.branches.paths.iter().enumerate() {
        let mut rs = runs(path, view);
        rs.sort_by_key(|r| std::cmp::Reverse(r.len()));
        for (j, r) in rs.into_iter().enumerate() {
            let c = Curve::new(r).color(branch_color(i)).width(1.3);
            curves.push(if j == 0 { c.arrows(1) } else { c });
        }
    }
    if let Some(a) = &l.asymptotes {
        for (j, ang) in a.angles_deg.iter().enumerate() {
            let t = ang.to_radians();
            let c = Curve::new([
                (a.centroid, 0.0),
                (a.centroid + far * t.cos(), far * t.sin()),
            ])
            .style(LineStyle::Dashed)
            .color(GUIDE);
            curves.push(if j == 0 {
                c.label(format!("asymptotes from σ = {}", fmt_sig(a.centroid, 4)))
            } else {
                c
            });
        }
    }
    let mut markers: Vec<Marker> = Vec::new();
    for r in &l.poles {
        markers.push(Marker::new((r.value.re, r.value.im), MarkerShape::Cross));
    }
    for r in &l.zeros {
        markers.push(Marker::new((r.value.re, r.value.im), MarkerShape::Circle));
    }
    for r in &l.fixed {
        markers.push(Marker::new(
            (r.value.re, r.value.im),
            MarkerShape::CircledCross,
        ));
    }
    for b in &l.break_points {
        markers.push(Marker::new((b.s, 0.0), MarkerShape::Diamond).label(gain_text(b.gain)));
    }
    for c in &l.crossings {
        let at = c.z.unwrap_or(Complex64::new(0.0, c.omega));
        markers.push(Marker::new((at.re, at.im), MarkerShape::Square).label(gain_text(c.gain)));
        if at.im > 0.0 {
            markers.push(Marker::new((at.re, -at.im), MarkerShape::Square));
        }
    }
    if let Some((k, roots)) = p.marked {
        for (i, r) in roots.iter().enumerate() {
            let m = Marker::new((r.value.re, r.value.im), MarkerShape::Triangle).color(MARKED);
            markers.push(if i == 0 { m.label(gain_text(k)) } else { m });
        }
    }
    XyPlot {
        curves,
        markers,
        x_label: if discrete { "Re z" } else { "Re s (1/s)" }.into(),
        y_label: if discrete { "Im z" } else { "Im s (rad/s)" }.into(),
        equal_aspect: true,
        x_range: Some(view.0),
        y_range: Some(view.1),
        notes: Vec::new(),
        title: match p.label {
            Some(t) => format!("Root locus of {t}"),
            None => "Root locus".into(),
        },
        x_log: false,
    }
}

/// Writes a root locus PNG.
///
/// Errors: bad options, an unwritable path (no partial file is left).
pub fn rlocus_png(path: impl AsRef<Path>, plot: &RootLocusPlot, opts: &PlotOptions) -> Result<()> {
    xy_png_with(path.as_ref(), &xy(plot), &legend(plot), opts)
}
