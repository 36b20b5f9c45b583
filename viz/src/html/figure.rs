//! The mechanism's picture on the page: every item as an SVG element the script moves
//! (marked with its item index), the traced paths, the guides of fixed sliders and the poses
//! at the motion's events as dashed ghosts.

use super::chart::px;
use super::frames::{Frames, Slot};
use crate::draw::{CONSTRUCTION_DASH, CONSTRUCTION_WIDTH, Style};
use crate::escape::escape;
use std::fmt::Write;

/// Tenths of a pixel as written: `123.4`, `12` (the script writes the same).
pub(crate) fn t(v: i64) -> String {
    px(v as f64 / 10.0)
}

fn pair(f: &[i64], o: usize) -> [f64; 2] {
    [f[o] as f64 / 10.0, f[o + 1] as f64 / 10.0]
}

/// Ground hatching below the line from `from` along unit direction `u` for `len` pixels.
fn hatch(out: &mut String, colour: &str, from: [f64; 2], u: [f64; 2], len: f64) {
    let n = [-u[1], u[0]];
    let mut d = String::new();
    let mut s = 0.0;
    while s <= len {
        let p = [from[0] + u[0] * s, from[1] + u[1] * s];
        let _ = write!(d, "M{},{}l{},{}", px(p[0]), px(p[1]), px(6.0 * n[0] - 5.0 * u[0]), px(6.0 * n[1] - 5.0 * u[1]));
        s += 6.0;
    }
    let _ = write!(out, r#"<path d="{d}" stroke="{colour}" stroke-width="1"/>"#);
}

/// The guide of fixed slider `k` over every frame: a ground line under the block along its
/// whole stroke, hatched on the far side; cut to the picture of `size` pixels, as the
/// drawings' guides are (a stroke far outside a window would take as many hatch strokes).
fn guide(out: &mut String, style: &Style, frames: &[Vec<i64>], o: usize, size: [f64; 2]) {
    let deg = -(frames[0][o + 2] as f64 / 10.0);
    let u = [deg.to_radians().cos(), -deg.to_radians().sin()];
    let n = [-u[1], u[0]];
    let [l, h] = style.block;
    let at = |f: &Vec<i64>| pair(f, o);
    let p0 = at(&frames[0]);
    let along = |p: [f64; 2]| (p[0] - p0[0]) * u[0] + (p[1] - p0[1]) * u[1];
    let (lo, hi) = frames.iter().map(|f| along(at(f))).fold((0.0f64, 0.0f64), |(a, b), s| (a.min(s), b.max(s)));
    let (lo, hi) = (lo - l / 2.0 - 6.0, hi + l / 2.0 + 6.0);
    // The part of the line over the picture lies between the corners' positions along it.
    let corners = [[0.0, 0.0], [size[0], 0.0], [0.0, size[1]], size].map(along);
    let (first, last) = corners.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| (a.min(*c), b.max(*c)));
    let (lo, hi) = (lo.max(first - 8.0), hi.min(last + 8.0));
    if lo > hi {
        return;
    }
    let a = [p0[0] + lo * u[0] + h / 2.0 * n[0], p0[1] + lo * u[1] + h / 2.0 * n[1]];
    let b = [p0[0] + hi * u[0] + h / 2.0 * n[0], p0[1] + hi * u[1] + h / 2.0 * n[1]];
    let _ = write!(
        out,
        r#"<path class="kl-guide" d="M{},{}L{},{}" stroke="{}" stroke-width="2"/>"#,
        px(a[0]),
        px(a[1]),
        px(b[0]),
        px(b[1]),
        style.ground
    );
    hatch(out, &style.ground, a, u, hi - lo);
}

/// How a layer looks: the mechanism itself or its ghost at an event.
struct Pen<'a> {
    ink: &'a str,
    fill: &'a str,
    ghost: bool,
}

/// The items of the drawing at frame `f` (the moving ones marked for the script when `live`).
/// `names`: the names of the joints of each item (`point` outputs), written on the live ones.
fn items(out: &mut String, style: &Style, slots: &[Slot], f: &[i64], pen: &Pen, names: Option<&[Vec<Option<String>>]>) {
    let live = names.is_some();
    let mut o = 0;
    let width = if pen.ghost { 1.5 } else { style.link_width };
    let dash = if pen.ghost { r#" stroke-dasharray="5 3""# } else { "" };
    let mark_as =
        |k: usize, class: &str| if live { format!(r#" class="{class}" data-item="{k}""#) } else { String::new() };
    let mark = |k: usize| mark_as(k, "kl-shape");
    for (k, slot) in slots.iter().enumerate() {
        // The position of a pivot, slider or gear (a link's points are its own; a link through
        // no point has no numbers in the frame).
        let at = || (t(f[o]), t(f[o + 1]));
        match slot {
            Slot::Link { n, closed } => {
                let pts: Vec<String> =
                    (0..*n).map(|j| format!("{},{}", t(f[o + 2 * j]), t(f[o + 2 * j + 1]))).collect();
                let (tag, fill) = if *closed && !pen.ghost {
                    ("polygon", pen.fill)
                } else if *closed {
                    ("polygon", "none")
                } else {
                    ("polyline", "none")
                };
                let _ = write!(
                    out,
                    r#"<{tag}{} points="{}" fill="{fill}" fill-opacity="0.7" stroke="{}" stroke-width="{}" stroke-linecap="round" stroke-linejoin="round"{dash}/>"#,
                    mark(k),
                    pts.join(" "),
                    pen.ink,
                    px(width)
                );
            }
            Slot::Pivot => {
                let (x, y) = at();
                let g = if pen.ghost { pen.ink } else { style.ground.as_str() };
                let _ = write!(
                    out,
                    r#"<g{} transform="translate({x} {y})"><path d="M0,0L-9,14H9Z" fill="white" stroke="{g}" stroke-width="1.5"/><path d="M-15,14H15" stroke="{g}" stroke-width="2"/>"#,
                    // The frame's pivots stay drawn where a grid's page hides the mechanism.
                    mark_as(k, "kl-shape kl-pivot")
                );
                hatch(out, g, [-13.0, 14.0], [1.0, 0.0], 26.0);
                out.push_str("</g>");
            }
            Slot::Slider { .. } => {
                let (x, y) = at();
                let [l, h] = style.block;
                let fill = if pen.ghost { "none" } else { pen.fill };
                let _ = write!(
                    out,
                    r#"<g{} transform="translate({x} {y}) rotate({})"><rect x="{}" y="{}" width="{}" height="{}" fill="{fill}" stroke="{}" stroke-width="1.5"/></g>"#,
                    mark(k),
                    t(f[o + 2]),
                    px(-l / 2.0),
                    px(-h / 2.0),
                    px(l),
                    px(h),
                    pen.ink
                );
            }
            Slot::Gear { radius, turning } => {
                let (x, y) = at();
                let ink = pen.ink;
                let rr = px(*radius);
                let _ = write!(
                    out,
                    r#"<g{} transform="translate({x} {y}) rotate({})"><circle r="{rr}" fill="none" stroke="{ink}" stroke-width="5" stroke-dasharray="3 3" opacity="0.8"/><circle r="{}" fill="none" stroke="{ink}" stroke-width="1"/>"#,
                    mark(k),
                    t(f[o + 2]),
                    px((radius - 4.0).max(0.0))
                );
                if *turning {
                    let _ = write!(out, r#"<path d="M0,0H{rr}" stroke="{ink}" stroke-width="2"/>"#);
                }
                out.push_str("</g>");
            }
            Slot::Outline { corners } => {
                let (x, y) = at();
                let pts: Vec<String> = corners.iter().map(|c| format!("{},{}", px(c[0]), px(c[1]))).collect();
                let fill = if pen.ghost { "none" } else { pen.fill };
                let _ = write!(
                    out,
                    r#"<g{} transform="translate({x} {y}) rotate({})"><polygon points="{}" fill="{fill}" fill-opacity="0.35" stroke="{}" stroke-width="1.5" stroke-linejoin="round"{dash}/></g>"#,
                    mark(k),
                    t(f[o + 2]),
                    pts.join(" "),
                    pen.ink
                );
            }
            Slot::Joint => {}
            Slot::Guide => {
                let pts: Vec<String> = (0..2).map(|j| format!("{},{}", t(f[o + 2 * j]), t(f[o + 2 * j + 1]))).collect();
                let _ = write!(
                    out,
                    r#"<polyline{} points="{}" fill="none" stroke="{}" stroke-width="{}" stroke-linecap="round"{dash}/>"#,
                    mark(k),
                    pts.join(" "),
                    pen.ink,
                    px(width)
                );
            }
            // Thin and dashed in the ghosts too (their own colour tells them apart).
            Slot::Construction => {
                let pts: Vec<String> = (0..2).map(|j| format!("{},{}", t(f[o + 2 * j]), t(f[o + 2 * j + 1]))).collect();
                let _ = write!(
                    out,
                    r#"<polyline{} points="{}" fill="none" stroke="{}" stroke-width="{}" stroke-dasharray="{CONSTRUCTION_DASH}"/>"#,
                    mark_as(k, "kl-shape kl-construction"),
                    pts.join(" "),
                    pen.ink,
                    px(CONSTRUCTION_WIDTH)
                );
            }
        }
        o += slot.len();
    }
    // Joint circles on top of every item (a construction line has none).
    let mut o = 0;
    let (fill, r) = if pen.ghost { ("none", 2.5) } else { ("white", style.joint_radius) };
    for (k, slot) in slots.iter().enumerate() {
        let count = match slot {
            Slot::Link { n, .. } => *n,
            Slot::Joint => 1,
            _ => 0,
        };
        for j in 0..count {
            let tag = match names {
                Some(names) => {
                    let name = names[k].get(j).cloned().flatten();
                    let name = name.map_or(String::new(), |n| format!(r#" data-name="{}""#, escape(&n)));
                    format!(r#" class="kl-joint" data-item="{k}" data-point="{j}"{name}"#)
                }
                None => String::new(),
            };
            let _ = write!(
                out,
                r#"<circle{tag} cx="{}" cy="{}" r="{}" fill="{fill}" stroke="{}" stroke-width="1.5"/>"#,
                t(f[o + 2 * j]),
                t(f[o + 2 * j + 1]),
                px(r),
                pen.ink
            );
        }
        o += slot.len();
    }
}

/// The picture at frame `first`, with the ghosts of `events` titled by `labels` (one per event).
/// `joints`: the names of each item's joints, `traces`: of each traced point (`point` outputs);
/// `marks`: fixed points (mechanism units) marked and numbered from 1 (a synthesis's targets).
pub(crate) fn figure(
    fr: &Frames,
    style: &Style,
    first: usize,
    joints: &[Vec<Option<String>>],
    traces: &[Option<String>],
    labels: &[String],
    marks: &[[f64; 2]],
) -> String {
    let (w, h) = (px(fr.view.width), px(fr.view.height));
    let origin = fr.view.px([0.0, 0.0]);
    let mut s = String::new();
    let _ = write!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" id="kl-drawing" width="{w}" height="{h}" viewBox="0 0 {w} {h}" data-scale="{}" data-origin="{} {}" data-frame="{first}"><rect width="{w}" height="{h}" fill="white"/>"#,
        fr.view.scale, origin[0], origin[1]
    );
    for (k, runs) in fr.paths.iter().enumerate() {
        let colour = style.traces.get(k % style.traces.len().max(1)).map_or("#d95f02", String::as_str);
        // The runs of a grid's rows are many: thinner and fainter than a sweep's one path.
        let (width, opacity) =
            if runs.len() > 1 { (px(0.6 * style.trace_width), "0.45") } else { (px(style.trace_width), "0.7") };
        for pieces in runs {
            let pts =
                |piece: &Vec<[i64; 2]>| piece.iter().map(|p| format!("{},{}", t(p[0]), t(p[1]))).collect::<Vec<_>>();
            let look = format!(
                r#"fill="none" stroke="{colour}" stroke-width="{width}" stroke-linejoin="round" opacity="{opacity}""#
            );
            match pieces.as_slice() {
                [piece] => {
                    let _ = write!(
                        s,
                        r#"<polyline class="kl-trace" data-trace="{k}" points="{}" {look}/>"#,
                        pts(piece).join(" ")
                    );
                }
                // A path that retraces itself, in pieces: one element (a polyline each would
                // outweigh their few points).
                _ => {
                    let d: Vec<String> = pieces.iter().map(|piece| format!("M{}", pts(piece).join("L"))).collect();
                    let _ = write!(s, r#"<path class="kl-trace" data-trace="{k}" d="{}" {look}/>"#, d.concat());
                }
            }
        }
    }
    let mut o = 0;
    for slot in &fr.slots {
        if let Slot::Slider { fixed: true } = slot {
            guide(&mut s, style, &fr.frames, o, [fr.view.width, fr.view.height]);
        }
        o += slot.len();
    }
    // The events' labels are written in the page's list under the picture, each with the
    // ghosts' colour as its key, not over the picture, where they would cover the mechanism
    // (the picture is cropped to it, so any spot in it may be drawn on); a ghost has its label
    // as its title (shown on hover, read by assistive technology).
    for (ev, label) in fr.events.iter().zip(labels) {
        let _ = write!(s, r#"<g class="kl-event"><title>{}</title>"#, escape(label));
        items(&mut s, style, &fr.slots, ev, &Pen { ink: &style.event, fill: "none", ghost: true }, None);
        s.push_str("</g>");
    }
    for (i, m) in marks.iter().enumerate() {
        let [x, y] = fr.view.px(*m);
        let _ = write!(
            s,
            r##"<circle class="kl-target" data-index="{i}" cx="{}" cy="{}" r="4.5" fill="none" stroke="#111" stroke-width="1.5"/><text class="kl-target-label" x="{}" y="{}" font-family="sans-serif" font-size="11" fill="#111" stroke="white" stroke-width="3" paint-order="stroke">{}</text>"##,
            px(x),
            px(y),
            px(x + 6.0),
            px(y - 6.0),
            i + 1
        );
    }
    let f = &fr.frames[first];
    // The live mechanism in one group: a grid's page hides it where the grid did not reach.
    s.push_str(r#"<g id="kl-mechanism">"#);
    items(&mut s, style, &fr.slots, f, &Pen { ink: &style.ink, fill: &style.fill, ghost: false }, Some(joints));
    for (k, name) in traces.iter().enumerate() {
        let o = fr.traces_at + 2 * k;
        let colour = style.traces.get(k % style.traces.len().max(1)).map_or("#d95f02", String::as_str);
        let name = name.as_ref().map_or(String::new(), |n| format!(r#" data-name="{}""#, escape(n)));
        let _ = write!(
            s,
            r#"<circle class="kl-dot" data-trace="{k}"{name} cx="{}" cy="{}" r="2.5" fill="{colour}" stroke="{colour}" stroke-width="1.5"/>"#,
            t(f[o]),
            t(f[o + 1])
        );
    }
    s.push_str("</g></svg>");
    s
}
