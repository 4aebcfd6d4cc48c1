//! Pole-zero map in the s-plane (the stable left half plane shaded) or the z-plane (the unit
//! circle drawn and the stable unit disc shaded), with equal scales on both axes.

use std::path::Path;

use num_complex::Complex64;

use super::frame::Frame;
use super::layout::{bounds, check_span, draw_title, equal_axes, layout_single};
use super::legend::{Corner, LegendEntry, Swatch, draw_legend};
use super::options::{PlotOptions, check_text};
use super::raster::Canvas;
use super::raster::Color;
use super::render::render;
use super::style::{LineStyle, MarkerShape, Theme};
use super::text::{HAlign, VAlign};
use crate::analysis::PoleZero;
use crate::error::Result;
use crate::fmt::fmt_sig;
use crate::poly::Root;

/// What to draw on a pole-zero map.
///
/// ```
/// use ltikit::TransferFunction;
/// use ltikit::plot::PzMap;
/// let g = TransferFunction::from_descending(&[1.0, 2.0], &[1.0, 2.0, 5.0]).unwrap();
/// let pz = g.pole_zero().unwrap();
/// let map = PzMap::new(&pz).label("(s + 2)/(s^2 + 2 s + 5)").damping_guides(true);
/// assert!(map.damping_guides);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct PzMap<'a> {
    /// Poles, zeros and cancellations.
    pub pz: &'a PoleZero,
    /// The plant's name or transfer function, for the title.
    pub label: Option<&'a str>,
    /// Draw lines of constant damping ζ and circles of constant natural frequency ωₙ
    /// (s-plane only).
    pub damping_guides: bool,
    /// A z-plane map (discrete time): the unit circle is the stability boundary, the unit disc
    /// is shaded as the stable region, the axes read Re z and Im z.
    pub unit_circle: bool,
}

impl<'a> PzMap<'a> {
    /// A map of `pz` without guides.
    pub fn new(pz: &'a PoleZero) -> Self {
        PzMap {
            pz,
            label: None,
            damping_guides: false,
            unit_circle: false,
        }
    }

    /// A z-plane map (see [`PzMap::unit_circle`]).
    ///
    /// ```
    /// use ltikit::TransferFunction;
    /// use ltikit::plot::PzMap;
    /// let g = TransferFunction::from_descending(&[1.0], &[1.0, -0.5]).unwrap();
    /// let pz = g.pole_zero().unwrap();
    /// assert!(PzMap::new(&pz).unit_circle(true).unit_circle);
    /// ```
    pub fn unit_circle(mut self, on: bool) -> Self {
        self.unit_circle = on;
        self
    }

    /// Sets the label.
    pub fn label(mut self, label: &'a str) -> Self {
        self.label = Some(label);
        self
    }

    /// Turns the ζ/ωₙ guides on or off.
    pub fn damping_guides(mut self, on: bool) -> Self {
        self.damping_guides = on;
        self
    }
}

/// Colour of poles and zeros.
const ROOT_COLOR: Color = Color(31, 119, 180);
/// Colour of cancelled pole-zero pairs.
const CANCEL_COLOR: Color = Color(230, 110, 0);
/// Shading of the stable half plane.
const STABLE_SHADE: Color = Color(44, 160, 44);

/// Writes a pole-zero map: poles ×, zeros ○, cancelled pairs ⊗ (orange), multiplicities
/// labelled "×m", the imaginary axis, the stable left half plane shaded, equal units per
/// pixel on both axes, and optionally lines of constant ζ (0.1, 0.3, 0.5, 0.7, 0.9) and
/// half-circles of constant ωₙ.
///
/// Errors: bad options, a title or label longer than
/// [`MAX_TEXT_CHARS`](super::options::MAX_TEXT_CHARS) characters, or an unwritable path; no file is
/// left behind. A map with no finite
/// poles or zeros (a constant G) is drawn with a note.
///
/// ```no_run
/// use ltikit::TransferFunction;
/// use ltikit::plot::{pzmap_png, PlotOptions, PzMap};
/// let g = TransferFunction::from_descending(&[1.0, 2.0], &[1.0, 4.0, 5.0, 2.0]).unwrap();
/// let pz = g.pole_zero().unwrap();
/// pzmap_png("/tmp/pz.png", &PzMap::new(&pz).damping_guides(true), &PlotOptions::default()).unwrap();
/// ```
pub fn pzmap_png(path: impl AsRef<Path>, map: &PzMap, opts: &PlotOptions) -> Result<()> {
    if let Some(l) = map.label {
        check_text("the label", l)?;
    }
    let v = if map.unit_circle { "z" } else { "s" };
    let title = opts.title_or(|| match map.label {
        Some(l) => format!("Pole-zero map of G({v}) = {l}"),
        None => "Pole-zero map".into(),
    });
    render(path.as_ref(), opts, |c, th| {
        draw(c, th, map, opts, title.as_deref())
    })
}

fn finite(r: &Root) -> bool {
    r.value.re.is_finite() && r.value.im.is_finite()
}

/// Equal-aspect axes around every finite root and the origin, with room around them.
fn layout(c: &Canvas, th: &Theme, pz: &PoleZero, has_title: bool, circle: bool) -> Result<Frame> {
    let mut all = finite_roots(pz);
    if circle {
        all.extend([Complex64::new(-1.0, -1.0), Complex64::new(1.0, 1.0)]);
    }
    let (xlo, xhi) = bounds(all.iter().map(|z| z.re).chain([0.0])).unwrap_or((0.0, 0.0));
    let (ylo, yhi) = bounds(all.iter().map(|z| z.im).chain([0.0])).unwrap_or((0.0, 0.0));
    let span = (xhi - xlo).max(yhi - ylo);
    let span = if span > 0.0 { span } else { 2.0 };
    let pad = 0.18 * span;
    let xr = (xlo - pad, xhi + pad);
    let yr = (ylo - pad, yhi + pad);
    check_span("real parts", xr)?;
    check_span("imaginary parts", yr)?;
    Ok(layout_single(c, th, has_title, true, true, |w, h| {
        equal_axes(xr, yr, w, h, th)
    }))
}

/// Every finite pole, zero and cancelled root.
fn finite_roots(pz: &PoleZero) -> Vec<Complex64> {
    pz.reduced_poles
        .iter()
        .chain(&pz.reduced_zeros)
        .chain(&pz.cancelled)
        .filter(|r| finite(r))
        .map(|r| r.value)
        .collect()
}

/// The unit circle as a polyline of `n` segments.
fn unit_circle_points(n: usize) -> Vec<(f64, f64)> {
    (0..=n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            (a.cos(), a.sin())
        })
        .collect()
}

/// The stable half plane (or unit disc) shaded, then the grid.
fn draw_background(c: &mut Canvas, th: &Theme, frame: &Frame, grid: bool, circle: bool) {
    let (x0, x1, y0, y1) = (frame.x.lo, frame.x.hi, frame.y.lo, frame.y.hi);
    if circle {
        let disc: Vec<(f64, f64)> = unit_circle_points(256)
            .into_iter()
            .map(|p| frame.px(p))
            .collect();
        c.fill_polygon(&disc, STABLE_SHADE, 0.08);
    } else if x0 < 0.0 {
        let p = frame.px((x0, y0));
        let q = frame.px((0.0f64.min(x1), y1));
        c.fill_rect(p.0, p.1, q.0, q.1, STABLE_SHADE, 0.08);
    }
    if grid {
        frame.draw_grid(c, th);
    }
}

/// Colour of the ζ/ωₙ guides and of their labels.
const GUIDE: Color = Color(150, 150, 150);
const GUIDE_TEXT: Color = Color(110, 110, 110);

/// The largest distance from the origin to a corner of the frame.
fn corner_radius(frame: &Frame) -> f64 {
    [frame.x.lo, frame.x.hi]
        .iter()
        .flat_map(|&x| [frame.y.lo, frame.y.hi].map(|y| (x * x + y * y).sqrt()))
        .fold(0.0, f64::max)
}

/// Rays of constant damping ζ through the origin, labelled where the upper ray leaves the
/// frame.
fn draw_zeta_rays(c: &mut Canvas, th: &Theme, frame: &Frame) -> Result<()> {
    let thin = (th.line * 0.6).max(1.0);
    let r_max = corner_radius(frame);
    for zeta in [0.1f64, 0.3, 0.5, 0.7, 0.9] {
        let dir = Complex64::new(-zeta, (1.0 - zeta * zeta).sqrt());
        for sign in [1.0, -1.0] {
            let end = (dir.re * r_max, sign * dir.im * r_max);
            frame.plot_line(c, [(0.0, 0.0), end], thin, GUIDE, LineStyle::Dashed);
        }
        let t_exit = [
            if dir.re < 0.0 {
                frame.x.lo / dir.re
            } else {
                f64::INFINITY
            },
            if dir.im > 0.0 {
                frame.y.hi / dir.im
            } else {
                f64::INFINITY
            },
        ]
        .into_iter()
        .fold(f64::INFINITY, f64::min);
        if t_exit.is_finite() && t_exit > 0.0 {
            let at = (dir.re * t_exit * 0.94, dir.im * t_exit * 0.94);
            if frame.contains(at) {
                let p = frame.px(at);
                c.text_on_box(
                    &format!("ζ = {zeta}"),
                    p,
                    th.note * 0.85,
                    GUIDE_TEXT,
                    (HAlign::Center, VAlign::Middle),
                )?;
            }
        }
    }
    Ok(())
}

/// Half-circles of constant ωₙ at the tick spacing of the real axis, labelled on the negative
/// real axis.
fn draw_wn_circles(c: &mut Canvas, th: &Theme, frame: &Frame) -> Result<()> {
    let thin = (th.line * 0.6).max(1.0);
    let r_max = corner_radius(frame);
    let (x0, x1) = (frame.x.lo, frame.x.hi);
    let step = frame
        .x
        .ticks
        .windows(2)
        .map(|w| w[1].v - w[0].v)
        .next()
        .unwrap_or(1.0);
    let mut k = 1;
    while (k as f64) * step <= r_max && k < 50 {
        let r = k as f64 * step;
        let arc: Vec<(f64, f64)> = (0..=96)
            .map(|i| {
                let a = std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * i as f64 / 96.0;
                (r * a.cos(), r * a.sin())
            })
            .collect();
        frame.plot_line(c, arc, thin, GUIDE, LineStyle::Dotted);
        if frame.contains((-r, 0.0)) && -r > x0 + 0.02 * (x1 - x0) {
            let p = frame.px((-r, 0.0));
            c.text_on_box(
                &format!("ω_{{n}} = {}", fmt_sig(r, 3)),
                (p.0 - 3.0 * th.s, p.1 + 5.0 * th.s),
                th.note * 0.8,
                GUIDE_TEXT,
                (HAlign::Right, VAlign::Top),
            )?;
        }
        k += 1;
    }
    Ok(())
}

/// Zeros ○, poles ×, cancelled pairs ⊗, with multiplicities; returns their pixel positions.
fn draw_roots(c: &mut Canvas, th: &Theme, frame: &Frame, pz: &PoleZero) -> Result<Vec<(f64, f64)>> {
    let r = 7.0 * th.s;
    let lw = th.line * 1.1;
    let mut avoid = Vec::new();
    let mult = |c: &mut Canvas, root: &Root, color: Color| -> Result<()> {
        let p = (root.value.re, root.value.im);
        if root.multiplicity > 1 && frame.contains(p) {
            let q = frame.px(p);
            c.text(
                &format!("×{}", root.multiplicity),
                (q.0 + r + 2.0 * th.s, q.1 - r),
                th.note,
                color,
                (HAlign::Left, VAlign::Bottom),
            )?;
        }
        Ok(())
    };
    let groups = [
        (&pz.reduced_zeros, MarkerShape::Circle, r, ROOT_COLOR),
        (&pz.reduced_poles, MarkerShape::Cross, r, ROOT_COLOR),
        (
            &pz.cancelled,
            MarkerShape::CircledCross,
            r * 1.25,
            CANCEL_COLOR,
        ),
    ];
    for (roots, shape, size, color) in groups {
        for z in roots.iter().filter(|r| finite(r)) {
            let p = (z.value.re, z.value.im);
            frame.plot_marker(c, p, shape, size, color, lw);
            mult(c, z, color)?;
            avoid.push(frame.px(p));
        }
    }
    Ok(avoid)
}

/// The legend rows: the marker kinds present, notes, the shaded half plane.
fn legend_rows(pz: &PoleZero, circle: bool) -> Vec<LegendEntry> {
    let mut legend = vec![LegendEntry::marker("pole", MarkerShape::Cross, ROOT_COLOR)];
    if !pz.reduced_zeros.is_empty() {
        legend.push(LegendEntry::marker("zero", MarkerShape::Circle, ROOT_COLOR));
    }
    if !pz.cancelled.is_empty() {
        legend.push(LegendEntry::marker(
            "cancelled pole-zero pair",
            MarkerShape::CircledCross,
            CANCEL_COLOR,
        ));
    }
    if let Some(k) = pz.zeros_at_infinity.filter(|&k| k > 0) {
        legend.push(LegendEntry::text(
            format!("{k} zero(s) at infinity"),
            Theme::NOTE,
        ));
    }
    if finite_roots(pz).is_empty() {
        legend.push(LegendEntry::text("no finite poles or zeros", Theme::NOTE));
    }
    legend.push(LegendEntry {
        swatch: Swatch::Patch {
            color: STABLE_SHADE,
            alpha: 0.25,
        },
        text: if circle {
            "stable region |z| < 1".into()
        } else {
            "stable half plane".into()
        },
        color: Color::BLACK,
    });
    legend
}

fn draw(
    c: &mut Canvas,
    th: &Theme,
    map: &PzMap,
    opts: &PlotOptions,
    title: Option<&str>,
) -> Result<()> {
    let pz = map.pz;
    let circle = map.unit_circle;
    let frame = layout(c, th, pz, title.is_some(), circle)?;
    draw_background(c, th, &frame, opts.grid, circle);
    if map.damping_guides && !circle {
        draw_zeta_rays(c, th, &frame)?;
        draw_wn_circles(c, th, &frame)?;
    }
    // Axes through the origin; the stability boundary: the imaginary axis or the unit circle.
    let thin = (th.line * 0.6).max(1.0);
    let dark = Color(60, 60, 60);
    if circle {
        frame.vline(c, 0.0, thin, Color(120, 120, 120), LineStyle::Solid);
        frame.plot_line(
            c,
            unit_circle_points(256),
            th.line * 0.75,
            dark,
            LineStyle::Solid,
        );
    } else {
        frame.vline(c, 0.0, th.line * 0.75, dark, LineStyle::Solid);
    }
    frame.hline(c, 0.0, thin, Color(120, 120, 120), LineStyle::Solid);
    let avoid = draw_roots(c, th, &frame, pz)?;
    frame.draw_axes(c, th, true, true)?;
    let (xt, yt) = if circle {
        ("Re z", "Im z")
    } else {
        ("Real axis σ (1/s)", "Imaginary axis ω (rad/s)")
    };
    frame.draw_axis_titles(c, th, Some(xt), Some(yt), th.pad)?;
    draw_legend(
        c,
        &frame,
        th,
        &legend_rows(pz, circle),
        &avoid,
        &[
            Corner::TopRight,
            Corner::TopLeft,
            Corner::BottomRight,
            Corner::BottomLeft,
        ],
        &[],
    )?;
    if let Some(t) = title {
        draw_title(c, th, t)?;
    }
    Ok(())
}
