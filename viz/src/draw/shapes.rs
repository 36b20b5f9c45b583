//! SVG of each kind of item over its key frames: static attributes from the first frame,
//! animated ones (`<animate>`, `<animateTransform>`) through all when a timing is given.

use super::scene::Shape;
use super::style::{CONSTRUCTION_DASH, CONSTRUCTION_WIDTH, Style};
use super::svg::{Timing, animate, animate_transform, num, pair, points, unwrap_degrees};
use std::fmt::Write;

/// Colours and timing for one layer: the mechanism itself, or its ghost at an event.
pub(crate) struct Pen<'a> {
    pub style: &'a Style,
    pub ink: &'a str,
    pub fill: &'a str,
    /// Thin outlines (earlier poses of a multi-exposure, poses at events).
    pub ghost: bool,
    /// Dashed strokes (poses at events).
    pub dashed: bool,
    pub timing: Option<Timing<'a>>,
}

impl Pen<'_> {
    fn width(&self) -> f64 {
        if self.ghost { 1.5 } else { self.style.link_width }
    }
}

/// Writes item `shapes` (one per key frame, all of one kind).
pub(crate) fn item(out: &mut String, pen: &Pen, shapes: &[&Shape]) {
    match shapes[0] {
        Shape::Link { closed, .. } => link(out, pen, shapes, *closed),
        Shape::Pivot { .. } => pivot(out, pen, shapes),
        Shape::Slider { .. } => slider(out, pen, shapes),
        Shape::Guide { .. } => link(out, pen, shapes, false),
        Shape::Gear { .. } => gear(out, pen, shapes),
        Shape::Outline { .. } => outline(out, pen, shapes),
        Shape::Joint { .. } => {}
        Shape::Construction { .. } => construction(out, pen, shapes),
    }
}

fn link(out: &mut String, pen: &Pen, shapes: &[&Shape], closed: bool) {
    let pts: Vec<String> = shapes
        .iter()
        .map(|s| match s {
            Shape::Link { pts, .. } => points(pts),
            // A turning guide is drawn as a bar, without joint circles at its ends.
            Shape::Guide { .. } => points(&s.guide_ends()),
            _ => String::new(),
        })
        .collect();
    let (tag, fill) = if closed { ("polygon", pen.fill) } else { ("polyline", "none") };
    let dash = if pen.dashed { r#" stroke-dasharray="5 3""# } else { "" };
    let _ = write!(
        out,
        r#"<{tag} points="{}" fill="{fill}" fill-opacity="0.7" stroke="{}" stroke-width="{}" stroke-linecap="round" stroke-linejoin="round"{dash}>"#,
        pts[0],
        pen.ink,
        num(pen.width())
    );
    animate(out, "points", &pts, pen.timing);
    let _ = write!(out, "</{tag}>");
}

/// A construction line: thin and dashed in every layer (the mechanism, its exposures, its
/// ghosts at events), with no joint circles (see `joints`), so that it never reads as a link.
fn construction(out: &mut String, pen: &Pen, shapes: &[&Shape]) {
    let pts: Vec<String> =
        shapes.iter().map(|s| if let Shape::Construction { pts } = s { points(pts) } else { String::new() }).collect();
    let _ = write!(
        out,
        r#"<polyline class="construction" points="{}" fill="none" stroke="{}" stroke-width="{}" stroke-dasharray="{CONSTRUCTION_DASH}">"#,
        pts[0],
        pen.ink,
        num(CONSTRUCTION_WIDTH)
    );
    animate(out, "points", &pts, pen.timing);
    out.push_str("</polyline>");
}

/// Opens `<g>` translated to `at` (animated), returns nothing: close with `</g>`.
fn open_translated(out: &mut String, pen: &Pen, at: &[[f64; 2]]) {
    let values: Vec<String> = at.iter().map(|p| pair(*p)).collect();
    let _ = write!(out, r#"<g transform="translate({})">"#, values[0]);
    animate_transform(out, "translate", &values, pen.timing);
}

/// Opens `<g>` rotated by `deg` (animated, continuous): close with `</g>`.
fn open_rotated(out: &mut String, pen: &Pen, deg: &[f64]) {
    let values: Vec<String> = unwrap_degrees(deg).into_iter().map(num).collect();
    let _ = write!(out, r#"<g transform="rotate({})">"#, values[0]);
    animate_transform(out, "rotate", &values, pen.timing);
}

fn pivot(out: &mut String, pen: &Pen, shapes: &[&Shape]) {
    let at: Vec<[f64; 2]> =
        shapes.iter().filter_map(|s| if let Shape::Pivot { at } = s { Some(*at) } else { None }).collect();
    open_translated(out, pen, &at);
    let g = if pen.ghost { pen.ink } else { pen.style.ground.as_str() };
    let _ = write!(
        out,
        r#"<path d="M0,0L-9,14H9Z" fill="white" stroke="{g}" stroke-width="1.5"/><path d="M-15,14H15" stroke="{g}" stroke-width="2"/>"#
    );
    hatch(out, g, [-13.0, 14.0], [1.0, 0.0], 26.0);
    out.push_str("</g>");
}

/// Ground hatching below the line from `from` along unit direction `u` for `len` pixels.
fn hatch(out: &mut String, colour: &str, from: [f64; 2], u: [f64; 2], len: f64) {
    let n = [-u[1], u[0]];
    let mut d = String::new();
    let mut t = 0.0;
    while t <= len {
        let p = [from[0] + u[0] * t, from[1] + u[1] * t];
        let _ =
            write!(d, "M{},{}l{},{}", num(p[0]), num(p[1]), num(6.0 * n[0] - 5.0 * u[0]), num(6.0 * n[1] - 5.0 * u[1]));
        t += 6.0;
    }
    let _ = write!(out, r#"<path d="{d}" stroke="{colour}" stroke-width="1"/>"#);
}

fn slider(out: &mut String, pen: &Pen, shapes: &[&Shape]) {
    let (at, deg): (Vec<[f64; 2]>, Vec<f64>) = shapes
        .iter()
        .filter_map(|s| if let Shape::Slider { at, angle, .. } = s { Some((*at, *angle)) } else { None })
        .unzip();
    let [l, h] = pen.style.block;
    open_translated(out, pen, &at);
    open_rotated(out, pen, &deg);
    let fill = if pen.ghost { "none" } else { pen.fill };
    let _ = write!(
        out,
        r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{fill}" stroke="{}" stroke-width="1.5"/></g></g>"#,
        num(-l / 2.0),
        num(-h / 2.0),
        num(l),
        num(h),
        pen.ink
    );
}

/// The guide of a slider on a fixed direction: a ground line under the block over its whole
/// stroke (every pose in `shapes`), hatched on the far side; cut to the picture of `size`
/// pixels (a stroke far outside a window would take as many hatch strokes).
pub(crate) fn guide(out: &mut String, style: &Style, shapes: &[&Shape], size: [f64; 2]) {
    let Some(Shape::Slider { at, angle, fixed: true }) = shapes.first() else { return };
    let a = angle.to_radians();
    let (u, n) = ([a.cos(), a.sin()], [-a.sin(), a.cos()]);
    let along = |p: &[f64; 2]| p[0] * u[0] + p[1] * u[1];
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for s in shapes {
        if let Shape::Slider { at, .. } = s {
            (lo, hi) = (lo.min(along(at)), hi.max(along(at)));
        }
    }
    let [l, h] = style.block;
    let (lo, hi) = (lo - 0.5 * l - 8.0, hi + 0.5 * l + 8.0);
    // The part of the line over the picture lies between the corners' positions along it.
    let corners = [[0.0, 0.0], [size[0], 0.0], [0.0, size[1]], size].map(|c| along(&c));
    let (first, last) = corners.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| (a.min(*c), b.max(*c)));
    let (lo, hi) = (lo.max(first - 8.0), hi.min(last + 8.0));
    if lo > hi {
        return;
    }
    let off = at[0] * n[0] + at[1] * n[1] + 0.5 * h;
    let p = |t: f64| [u[0] * t + n[0] * off, u[1] * t + n[1] * off];
    let (a0, a1) = (p(lo), p(hi));
    let _ = write!(
        out,
        r#"<path d="M{},{}L{},{}" stroke="{}" stroke-width="2"/>"#,
        num(a0[0]),
        num(a0[1]),
        num(a1[0]),
        num(a1[1]),
        style.ground
    );
    hatch(out, &style.ground, a0, u, hi - lo);
}

fn gear(out: &mut String, pen: &Pen, shapes: &[&Shape]) {
    let mut at = Vec::with_capacity(shapes.len());
    let mut deg = Vec::with_capacity(shapes.len());
    let (mut r, mut turns) = (0.0, false);
    for s in shapes {
        if let Shape::Gear { centre, radius, angle, turning } = s {
            (r, turns) = (*radius, *turning);
            at.push(*centre);
            deg.push(*angle);
        }
    }
    open_translated(out, pen, &at);
    open_rotated(out, pen, &deg);
    let (ink, rr) = (pen.ink, num(r));
    // Teeth as a dashed thick circle (they turn with the gear), the pitch circle inside, and
    // for a turning gear a spoke that shows its angle.
    let _ = write!(
        out,
        r#"<circle r="{rr}" fill="none" stroke="{ink}" stroke-width="5" stroke-dasharray="3 3" opacity="0.8"/><circle r="{}" fill="none" stroke="{ink}" stroke-width="1"/>"#,
        num((r - 4.0).max(0.0)),
    );
    if turns {
        let _ = write!(out, r#"<path d="M0,0H{rr}" stroke="{ink}" stroke-width="2"/>"#);
    }
    out.push_str("</g></g>");
}

/// A rigid outline: its corners written once in the body's frame (pixels, y down), the frame
/// moved and turned with the body.
fn outline(out: &mut String, pen: &Pen, shapes: &[&Shape]) {
    let mut at = Vec::with_capacity(shapes.len());
    let mut deg = Vec::with_capacity(shapes.len());
    let mut corners = String::new();
    for s in shapes {
        if let Shape::Outline { centre, angle, pts, scale, .. } = s {
            if corners.is_empty() {
                corners = points(&pts.iter().map(|p| [p[0] * scale, -p[1] * scale]).collect::<Vec<_>>());
            }
            at.push(*centre);
            deg.push(*angle);
        }
    }
    open_translated(out, pen, &at);
    open_rotated(out, pen, &deg);
    let (fill, dash) = if pen.ghost { ("none", r#" stroke-dasharray="5 3""#) } else { (pen.fill, "") };
    let _ = write!(
        out,
        r#"<polygon points="{corners}" fill="{fill}" fill-opacity="0.35" stroke="{}" stroke-width="1.5" stroke-linejoin="round"{dash}/></g></g>"#,
        pen.ink
    );
}

/// The joint circles of item `shapes` (every point of a link, or a lone joint).
pub(crate) fn joints(out: &mut String, pen: &Pen, shapes: &[&Shape]) {
    let count = match shapes[0] {
        Shape::Link { pts, .. } => pts.len(),
        Shape::Joint { .. } => 1,
        _ => 0,
    };
    for j in 0..count {
        let at: Vec<[f64; 2]> = shapes
            .iter()
            .filter_map(|s| match s {
                Shape::Link { pts, .. } => pts.get(j).copied(),
                Shape::Joint { at } => Some(*at),
                _ => None,
            })
            .collect();
        dot(out, pen, &at, pen.style.joint_radius, if pen.ghost { "none" } else { "white" }, pen.ink);
    }
}

/// A circle of radius `r` following `at` (one position per key frame).
pub(crate) fn dot(out: &mut String, pen: &Pen, at: &[[f64; 2]], r: f64, fill: &str, stroke: &str) {
    let values: Vec<String> = at.iter().map(|p| pair(*p)).collect();
    let _ = write!(
        out,
        r#"<circle r="{}" fill="{fill}" stroke="{stroke}" stroke-width="1.5" transform="translate({})">"#,
        num(r),
        values[0]
    );
    animate_transform(out, "translate", &values, pen.timing);
    out.push_str("</circle>");
}
