//! Curves on a sphere drawn as an orthographic projection on an x–y plot: the polhodes of the
//! free rigid body on its momentum sphere (seed fig. 2.11). The hemisphere facing the viewer
//! is drawn solid, the far one dashed and thinner; the sphere's outline and the three
//! coordinate axes (where they leave the sphere) are drawn for orientation. Built on
//! [`xy_png`], so it inherits its fonts, legend and atomic file writing.

use std::path::Path;

use super::options::PlotOptions;
use super::style::{Color, LineStyle, MarkerShape};
use super::xy::{Curve, Marker, XyPlot, xy_png};
use crate::error::{LtiError, Result};

/// An orthographic camera: looking at the origin from the direction given by azimuth (about
/// the third axis, from the first) and elevation (above the plane of the first two axes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Azimuth (degrees).
    pub azimuth_deg: f64,
    /// Elevation (degrees).
    pub elevation_deg: f64,
}

impl Default for View {
    fn default() -> Self {
        View {
            azimuth_deg: 35.0,
            elevation_deg: 25.0,
        }
    }
}

impl View {
    /// Screen coordinates (x right, y up) and depth (> 0 towards the viewer) of a point.
    ///
    /// ```
    /// use ltikit::plot::View;
    /// let v = View { azimuth_deg: 0.0, elevation_deg: 0.0 };
    /// // Looking down the first axis: it points at the viewer, the second to the right.
    /// let (x, y, d) = v.project([1.0, 0.0, 0.0]);
    /// assert!(x.abs() < 1e-15 && y.abs() < 1e-15 && (d - 1.0).abs() < 1e-15);
    /// let (x, _, _) = v.project([0.0, 1.0, 0.0]);
    /// assert!((x - 1.0).abs() < 1e-15);
    /// ```
    pub fn project(&self, p: [f64; 3]) -> (f64, f64, f64) {
        let (sa, ca) = self.azimuth_deg.to_radians().sin_cos();
        let (se, ce) = self.elevation_deg.to_radians().sin_cos();
        let toward = [ce * ca, ce * sa, se];
        let right = [-sa, ca, 0.0];
        let up = [-se * ca, -se * sa, ce];
        let dot = |a: [f64; 3]| a[0] * p[0] + a[1] * p[1] + a[2] * p[2];
        (dot(right), dot(up), dot(toward))
    }
}

/// A curve in three dimensions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Curve3 {
    /// Points in drawing order.
    pub points: Vec<[f64; 3]>,
    /// Legend text.
    pub label: Option<String>,
    /// Colour (`None`: the next palette colour).
    pub color: Option<Color>,
}

/// A marked point in three dimensions.
#[derive(Debug, Clone, PartialEq)]
pub struct Point3 {
    /// Position.
    pub at: [f64; 3],
    /// Marker shape.
    pub shape: MarkerShape,
    /// Text next to it.
    pub label: Option<String>,
}

/// Curves and points on (or near) a sphere of radius `radius` about the origin.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SpherePlot {
    /// Radius of the sphere drawn as the outline.
    pub radius: f64,
    /// Curves (split into a solid near part and a dashed far part).
    pub curves: Vec<Curve3>,
    /// Marked points (far ones get a lighter marker colour).
    pub points: Vec<Point3>,
    /// Names of the three coordinate axes, drawn where the axes leave the sphere.
    pub axis_names: [String; 3],
    /// The camera.
    pub view: View,
    /// Extra legend rows.
    pub notes: Vec<String>,
    /// Axis titles of the projection plane.
    pub x_label: String,
    /// Axis titles of the projection plane.
    pub y_label: String,
}

/// Splits a projected curve into runs on either side of the picture plane.
fn runs(view: &View, pts: &[[f64; 3]]) -> Vec<(bool, Vec<(f64, f64)>)> {
    let mut out: Vec<(bool, Vec<(f64, f64)>)> = Vec::new();
    for p in pts {
        let (x, y, d) = view.project(*p);
        let front = d >= 0.0;
        match out.last_mut() {
            Some((f, run)) if *f == front => run.push((x, y)),
            Some((_, run)) => {
                // Join the runs so the curve stays continuous.
                let last = run.last().copied();
                let mut next = Vec::new();
                if let Some(l) = last {
                    next.push(l);
                }
                next.push((x, y));
                out.push((front, next));
            }
            None => out.push((front, vec![(x, y)])),
        }
    }
    out
}

/// Writes the projection (see [`SpherePlot`]).
///
/// ```no_run
/// use ltikit::plot::{sphere_png, Curve3, PlotOptions, SpherePlot};
/// let equator: Vec<[f64; 3]> = (0..=72).map(|k| { let a = (k as f64 * 5.0).to_radians(); [a.cos(), a.sin(), 0.0] }).collect();
/// let p = SpherePlot { radius: 1.0, curves: vec![Curve3 { points: equator, ..Default::default() }],
///                      ..Default::default() };
/// sphere_png("sphere.png", &p, &PlotOptions::default()).unwrap();
/// ```
pub fn sphere_png(path: impl AsRef<Path>, plot: &SpherePlot, opts: &PlotOptions) -> Result<()> {
    let r = plot.radius;
    if !(r.is_finite() && r > 0.0) {
        return Err(LtiError::Plot(format!(
            "sphere radius {r} must be finite and > 0"
        )));
    }
    let grey = Color(120, 120, 120);
    let mut curves = Vec::new();
    let outline: Vec<(f64, f64)> = (0..=360)
        .map(|k| {
            let a = (k as f64).to_radians();
            (r * a.cos(), r * a.sin())
        })
        .collect();
    curves.push(Curve::new(outline).color(grey).width(0.8));
    let mut markers = Vec::new();
    for (k, name) in plot.axis_names.iter().enumerate() {
        for sign in [1.0, -1.0] {
            let mut a = [0.0; 3];
            let mut b = [0.0; 3];
            a[k] = sign * r;
            b[k] = sign * 1.25 * r;
            let (xa, ya, d) = plot.view.project(a);
            let (xb, yb, _) = plot.view.project(b);
            let style = if d >= 0.0 {
                LineStyle::Solid
            } else {
                LineStyle::Dotted
            };
            curves.push(Curve::new([(xa, ya), (xb, yb)]).color(grey).style(style));
            if sign > 0.0 && !name.is_empty() {
                let mut c = [0.0; 3];
                c[k] = 1.33 * r;
                let (xc, yc, _) = plot.view.project(c);
                let mut m = Marker::new((xc, yc), MarkerShape::Plus).color(grey);
                m.label = Some(name.clone());
                markers.push(m);
            }
        }
    }
    for (i, c) in plot.curves.iter().enumerate() {
        let color = c.color.unwrap_or_else(|| super::style::series_color(i));
        let mut labelled = false;
        for (front, pts) in runs(&plot.view, &c.points) {
            let mut curve = Curve::new(pts).color(color);
            if front {
                if !labelled {
                    if let Some(l) = &c.label {
                        curve = curve.label(l.clone());
                    }
                    labelled = true;
                }
            } else {
                curve = curve.style(LineStyle::Dashed).width(0.6);
            }
            curves.push(curve);
        }
    }
    for p in &plot.points {
        let (x, y, d) = plot.view.project(p.at);
        let mut m = Marker::new((x, y), p.shape).color(if d >= 0.0 { Color::BLACK } else { grey });
        m.label = p.label.clone();
        markers.push(m);
    }
    let lim = 1.45 * r;
    let xy = XyPlot {
        curves,
        markers,
        x_label: plot.x_label.clone(),
        y_label: plot.y_label.clone(),
        equal_aspect: true,
        x_range: Some((-lim, lim)),
        y_range: Some((-lim, lim)),
        notes: plot.notes.clone(),
        title: "Projection".into(),
        x_log: false,
    };
    xy_png(path, &xy, opts)
}
