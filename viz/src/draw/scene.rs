//! A drawing evaluated over a motion: every item's geometry at every pose, in pixels.

use super::annotate::{FONT, LABEL_OFFSET, text_width};
use super::error::DrawError;
use super::motion::{Motion, Pose};
use super::spec::{Drawing, Item, PointFn, Pt, Scalar, StateRef};
use super::style::{CONSTRUCTION_WIDTH, Style};
use super::view::{FAR, View};
use std::sync::Arc;

/// The geometry of one item at one pose (world units, then pixels after [`Shape::to_px`]).
/// Angles are radians counter-clockwise in world units and degrees clockwise (SVG) in pixels.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Shape {
    Link {
        pts: Vec<[f64; 2]>,
        closed: bool,
    },
    Pivot {
        at: [f64; 2],
    },
    Slider {
        at: [f64; 2],
        angle: f64,
        fixed: bool,
    },
    /// A turning guide: a bar from `at + span[0] u` to `at + span[1] u`, `u` the unit vector
    /// of `angle`. Unlike the other shapes' angles, `angle` stays in radians in pixels (there
    /// clockwise, the y axis down), so that one formula gives the ends in both.
    Guide {
        at: [f64; 2],
        angle: f64,
        span: [f64; 2],
    },
    Gear {
        centre: [f64; 2],
        radius: f64,
        angle: f64,
        turning: bool,
    },
    /// `pts` in the body's frame in mechanism units, drawn times `scale` (1 in world units, the
    /// view's scale in pixels, the y axis turned down): shared by every pose, not copied.
    /// `radius`: the farthest corner's distance from the centre, times `scale`.
    Outline {
        centre: [f64; 2],
        angle: f64,
        pts: Arc<Vec<[f64; 2]>>,
        scale: f64,
        radius: f64,
    },
    Joint {
        at: [f64; 2],
    },
    /// A construction line between its two ends.
    Construction {
        pts: [[f64; 2]; 2],
    },
}

impl Shape {
    /// The points that must fit in the picture (and that tell two poses apart).
    pub(crate) fn extent(&self, mut add: impl FnMut([f64; 2])) {
        match self {
            Shape::Link { pts, .. } => pts.iter().for_each(|p| add(*p)),
            Shape::Construction { pts } => pts.iter().for_each(|p| add(*p)),
            Shape::Pivot { at } | Shape::Slider { at, .. } | Shape::Joint { at } => add(*at),
            Shape::Guide { .. } => self.guide_ends().into_iter().for_each(add),
            Shape::Gear { centre: [x, y], radius: r, .. } | Shape::Outline { centre: [x, y], radius: r, .. } => {
                add([x - r, y - r]);
                add([x + r, y + r]);
            }
        }
    }

    /// Everything drawn of the shape in pixels (the shape in pixels): its points with the
    /// strokes, circles, blocks, guides and ground symbols drawn around them.
    fn ink(&self, style: &Style, mut add: impl FnMut([f64; 2])) {
        let mut square = |[x, y]: [f64; 2], r: f64| {
            add([x - r, y - r]);
            add([x + r, y + r]);
        };
        let joint = style.joint_radius + 1.5;
        match self {
            Shape::Link { pts, .. } => pts.iter().for_each(|p| square(*p, joint.max(0.5 * style.link_width))),
            Shape::Guide { .. } => self.guide_ends().into_iter().for_each(|p| square(p, 0.5 * style.link_width)),
            Shape::Construction { pts } => pts.iter().for_each(|p| square(*p, 0.5 * CONSTRUCTION_WIDTH)),
            Shape::Joint { at } => square(*at, joint),
            Shape::Gear { centre, radius, .. } => square(*centre, radius + 3.0),
            Shape::Outline { centre, radius, .. } => square(*centre, radius + 1.5),
            Shape::Pivot { at: [x, y] } => {
                // The triangle, ground line and hatching (see `shapes::pivot`).
                add([x - 18.0, y - joint]);
                add([x + 16.0, y + 21.0]);
            }
            Shape::Slider { at: [x, y], angle, fixed } => {
                let [l, h] = style.block;
                // The block, and for a fixed guide its line and hatching beside the block.
                let (u0, u1, n0, n1) = if *fixed {
                    (-0.5 * l - 13.0, 0.5 * l + 8.0, -0.5 * h, 0.5 * h + 7.0)
                } else {
                    (-0.5 * l, 0.5 * l, -0.5 * h, 0.5 * h)
                };
                let (sin, cos) = angle.to_radians().sin_cos();
                for (a, b) in [(u0, n0), (u0, n1), (u1, n0), (u1, n1)] {
                    add([x + a * cos - b * sin, y + a * sin + b * cos]);
                }
            }
        }
    }

    /// A guide's ends (world units or pixels, as the shape).
    pub(crate) fn guide_ends(&self) -> [[f64; 2]; 2] {
        match self {
            Shape::Guide { at, angle, span } => guide_ends(*at, *angle, *span),
            _ => [[f64::NAN; 2]; 2],
        }
    }

    fn to_px(&self, v: &View) -> Shape {
        // Beyond about 3e306 radians the degrees overflow: there the angle is first reduced
        // to a turn (such an angle has no digits left below a turn anyway).
        let deg = |a: f64| {
            let d = -a.to_degrees();
            if d.is_finite() { d } else { -(a % std::f64::consts::TAU).to_degrees() }
        };
        match self {
            Shape::Link { pts, closed } => Shape::Link { pts: pts.iter().map(|p| v.px(*p)).collect(), closed: *closed },
            Shape::Pivot { at } => Shape::Pivot { at: v.px(*at) },
            Shape::Slider { at, angle, fixed } => Shape::Slider { at: v.px(*at), angle: deg(*angle), fixed: *fixed },
            Shape::Guide { at, angle, span } => {
                Shape::Guide { at: v.px(*at), angle: -angle, span: span.map(|t| t * v.scale) }
            }
            Shape::Gear { centre, radius, angle, turning } => {
                Shape::Gear { centre: v.px(*centre), radius: radius * v.scale, angle: deg(*angle), turning: *turning }
            }
            Shape::Outline { centre, angle, pts, scale, radius } => Shape::Outline {
                centre: v.px(*centre),
                angle: deg(*angle),
                pts: Arc::clone(pts),
                scale: scale * v.scale,
                radius: radius * v.scale,
            },
            Shape::Joint { at } => Shape::Joint { at: v.px(*at) },
            Shape::Construction { pts } => Shape::Construction { pts: pts.map(|p| v.px(p)) },
        }
    }
}

/// The ends of a guide through `at` in direction `angle` (radians) over `span` along it.
pub(crate) fn guide_ends(at: [f64; 2], angle: f64, span: [f64; 2]) -> [[f64; 2]; 2] {
    let (s, c) = angle.sin_cos();
    span.map(|t| [at[0] + t * c, at[1] + t * s])
}

/// A drawing's point, bound to a motion's output columns.
enum Bound<'d> {
    Cols(usize, usize),
    Fixed([f64; 2]),
    Expr(&'d PointFn),
}

fn bind<'d>(p: &'d Pt, motion: &Motion) -> Result<Bound<'d>, DrawError> {
    Ok(match p {
        Pt::Point(name) => {
            let (ix, iy) = motion.point_columns(name)?;
            Bound::Cols(ix, iy)
        }
        Pt::Fixed(xy) => Bound::Fixed(*xy),
        Pt::Expr(f) => Bound::Expr(f),
    })
}

/// Evaluates bound points and scalars at one pose, checking that each is finite.
struct Eval<'a> {
    state: StateRef<'a>,
    pose: usize,
}

impl Eval<'_> {
    fn point(&self, b: &Bound, p: &Pt) -> Result<[f64; 2], DrawError> {
        let v = match b {
            Bound::Cols(ix, iy) => [self.state.out[*ix], self.state.out[*iy]],
            Bound::Fixed(xy) => *xy,
            Bound::Expr(f) => f(&self.state),
        };
        self.check(v, || p.describe())
    }

    fn scalar(&self, s: &Scalar, what: impl FnOnce() -> String) -> Result<f64, DrawError> {
        let v = match s {
            Scalar::Const(v) => *v,
            Scalar::Expr(f) => f(&self.state),
        };
        Ok(self.check([v, 0.0], what)?[0])
    }

    fn check(&self, v: [f64; 2], what: impl FnOnce() -> String) -> Result<[f64; 2], DrawError> {
        if v.iter().all(|c| c.is_finite()) {
            Ok(v)
        } else {
            Err(DrawError::NonFinite { what: what(), pose: self.pose })
        }
    }
}

/// The items of a drawing with their points bound to a motion.
struct BoundItems<'d> {
    items: Vec<(&'d Item, Vec<Bound<'d>>)>,
    traces: Vec<(&'d Pt, Bound<'d>)>,
    /// Each outline's corners, shared by its shapes at every pose, and its farthest corner's
    /// distance from its centre (`None` for the other items).
    outlines: Vec<Option<Corners>>,
    /// Each guide's span along it over the whole motion (`None` for the other items).
    spans: Vec<Option<[f64; 2]>>,
}

fn item_points(item: &Item) -> Vec<&Pt> {
    match item {
        Item::Link { through, .. } => through.iter().collect(),
        Item::Pivot { at } | Item::Slider { at, .. } | Item::Joint { at } => vec![at],
        Item::Gear { centre, .. } | Item::Outline { centre, .. } => vec![centre],
        Item::Guide { from, block, body, .. } => [from, block].into_iter().chain(body).collect(),
        Item::Construction { from, to } => vec![from, to],
    }
}

impl<'d> BoundItems<'d> {
    fn new(d: &'d Drawing, motion: &Motion) -> Result<Self, DrawError> {
        let mut items = Vec::with_capacity(d.items.len());
        for item in &d.items {
            let bound = item_points(item).into_iter().map(|p| bind(p, motion)).collect::<Result<_, _>>()?;
            items.push((item, bound));
        }
        let traces = d.traces.iter().map(|p| Ok((p, bind(p, motion)?))).collect::<Result<_, DrawError>>()?;
        let outlines = d.items.iter().enumerate().map(|(k, item)| outline(k, item)).collect::<Result<_, _>>()?;
        let mut bound = BoundItems { items, traces, outlines, spans: vec![None; d.items.len()] };
        bound.spans = bound.guide_spans(motion)?;
        Ok(bound)
    }

    /// Each guide's span over every pose of `motion`: what reaches farthest along it, at any
    /// pose, sets its length at all (see [`Item::Guide`]).
    fn guide_spans(&self, motion: &Motion) -> Result<Vec<Option<[f64; 2]>>, DrawError> {
        let mut spans: Vec<Option<[f64; 2]>> = vec![None; self.items.len()];
        for (i, pose) in motion.all_poses().enumerate() {
            let e = Eval { state: state(pose), pose: i };
            for (k, (item, bound)) in self.items.iter().enumerate() {
                let Item::Guide { angle, .. } = item else { continue };
                let pts = item_points(item);
                let at = |j: usize| e.point(&bound[j], pts[j]);
                let a = e.scalar(angle, || format!("angle of item {k} (guide)"))?;
                let (from, u) = (at(0)?, [a.cos(), a.sin()]);
                let along = |p: [f64; 2]| (p[0] - from[0]) * u[0] + (p[1] - from[1]) * u[1];
                // The block a tenth past its farthest place, so that the guide shows beyond it
                // there; the body's points (fixed on the guide) exactly.
                let block = GUIDE_BEYOND * along(at(1)?);
                let [mut lo, mut hi] = spans[k].unwrap_or([0.0, 0.0]);
                (lo, hi) = (lo.min(block), hi.max(block));
                for j in 2..pts.len() {
                    let t = along(at(j)?);
                    (lo, hi) = (lo.min(t), hi.max(t));
                }
                spans[k] = Some([lo, hi]);
            }
        }
        Ok(spans)
    }

    fn shapes(&self, e: &Eval) -> Result<Vec<Shape>, DrawError> {
        let mut shapes = Vec::with_capacity(self.items.len());
        for (k, (item, bound)) in self.items.iter().enumerate() {
            let pts = item_points(item);
            let p = |i: usize| e.point(&bound[i], pts[i]);
            shapes.push(match item {
                Item::Link { closed, .. } => {
                    Shape::Link { pts: (0..bound.len()).map(p).collect::<Result<_, _>>()?, closed: *closed }
                }
                Item::Pivot { .. } => Shape::Pivot { at: p(0)? },
                Item::Joint { .. } => Shape::Joint { at: p(0)? },
                Item::Construction { .. } => Shape::Construction { pts: [p(0)?, p(1)?] },
                Item::Outline { angle, .. } => {
                    let (pts, radius) = self.outlines[k].clone().unwrap_or_default();
                    let centre = p(0)?;
                    // The outline must fit in the plane of f64 too: its extent is fitted.
                    let [x, y] = centre;
                    e.check([x - radius, y - radius], || format!("extent of item {k} (outline)"))?;
                    e.check([x + radius, y + radius], || format!("extent of item {k} (outline)"))?;
                    let angle = e.scalar(angle, || format!("angle of item {k} (outline)"))?;
                    Shape::Outline { centre, angle, pts, scale: 1.0, radius }
                }
                Item::Guide { angle, .. } => Shape::Guide {
                    at: p(0)?,
                    angle: e.scalar(angle, || format!("angle of item {k} (guide)"))?,
                    span: self.spans[k].unwrap_or_default(),
                },
                Item::Slider { angle, .. } => Shape::Slider {
                    at: p(0)?,
                    angle: e.scalar(angle, || format!("angle of item {k} (slider)"))?,
                    fixed: matches!(angle, Scalar::Const(_)),
                },
                Item::Gear { radius, angle, .. } => {
                    let what = || format!("radius of item {k} (gear)");
                    let (centre, radius) = (p(0)?, e.scalar(&Scalar::Const(*radius), what)?);
                    if radius < 0.0 {
                        return Err(DrawError::InvalidSetting(format!("{} {radius} is negative", what())));
                    }
                    // The circle must fit in the plane of f64 too: its extent is fitted.
                    let [x, y] = centre;
                    e.check([x - radius, y - radius], || format!("extent of item {k} (gear)"))?;
                    e.check([x + radius, y + radius], || format!("extent of item {k} (gear)"))?;
                    Shape::Gear {
                        centre,
                        radius,
                        angle: e.scalar(angle, || format!("angle of item {k} (gear)"))?,
                        turning: matches!(angle, Scalar::Expr(_)),
                    }
                }
            });
        }
        Ok(shapes)
    }
}

/// How far a turning guide reaches past its block's farthest place, as a multiple of that
/// distance from the guide's joint: the block then never sits at the guide's very end.
const GUIDE_BEYOND: f64 = 1.1;

/// A drawing's turning guides over a motion: each guide's span along it over every pose
/// (`None` for the other items), for drawing the guide at any pose with [`guide_at`].
///
/// # Errors
/// As the drawing's: a name that is not a point, a non-finite coordinate or angle.
pub(crate) fn guide_spans(d: &Drawing, motion: &Motion) -> Result<Vec<Option<[f64; 2]>>, DrawError> {
    Ok(BoundItems::new(d, motion)?.spans)
}

/// The ends of guide `item` of span `span` at pose `pose` (numbered `i` in errors), in the
/// mechanism's units; `None` for another item.
///
/// # Errors
/// As [`guide_spans`].
pub(crate) fn guide_at(
    item: &Item,
    span: [f64; 2],
    motion: &Motion,
    pose: &Pose,
    i: usize,
) -> Result<Option<[[f64; 2]; 2]>, DrawError> {
    let Item::Guide { from, angle, .. } = item else { return Ok(None) };
    let e = Eval { state: state(pose), pose: i };
    let at = e.point(&bind(from, motion)?, from)?;
    let a = e.scalar(angle, || "angle of a guide".to_string())?;
    Ok(Some(guide_ends(at, a, span)))
}

/// An outline's corners, shared by its shapes at every pose, and the farthest one's distance
/// from its centre.
type Corners = (Arc<Vec<[f64; 2]>>, f64);

/// The corners of item `k` when it is an outline, checked (at least two, each finite), with
/// the farthest one's distance from the centre; `None` for another item.
fn outline(k: usize, item: &Item) -> Result<Option<Corners>, DrawError> {
    let Item::Outline { points, .. } = item else { return Ok(None) };
    if points.len() < 2 {
        return Err(DrawError::InvalidSetting(format!(
            "item {k} (outline) has {} corners: give at least 2",
            points.len()
        )));
    }
    if let Some(j) = points.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
        return Err(DrawError::InvalidSetting(format!(
            "corner {j} of item {k} (outline), {:?}, is not finite",
            points[j]
        )));
    }
    // Scaled by the largest coordinate first, so that no distance overflows.
    let big = points.iter().fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    let radius =
        if big > 0.0 { big * points.iter().map(|p| (p[0] / big).hypot(p[1] / big)).fold(0.0, f64::max) } else { 0.0 };
    Ok(Some((Arc::new(points.clone()), radius)))
}

/// A label of the drawing: its text, where the middle of its line sits relative to its point
/// (pixels) and how it is anchored (`start`, `middle`, `end`).
pub(crate) struct Label {
    pub text: String,
    pub offset: [f64; 2],
    pub anchor: &'static str,
}

impl Label {
    /// The corners of the label's text at point `p` (pixels).
    fn ink(&self, [x, y]: [f64; 2], mut add: impl FnMut([f64; 2])) {
        let w = text_width(&self.text);
        let left = x + self.offset[0]
            - match self.anchor {
                "end" => w,
                "middle" => 0.5 * w,
                _ => 0.0,
            };
        let cy = y + self.offset[1];
        add([left, cy - 0.5 * FONT]);
        add([left + w, cy + 0.5 * FONT]);
    }
}

/// Pixels reserved around the points when fitting, for what is drawn around them (pivot
/// symbols, slider blocks, labels); the picture is then cropped to what is drawn.
const RESERVE: f64 = 24.0;

/// A drawing evaluated at the poses of a motion, in pixels.
pub(crate) struct Scene {
    pub view: View,
    /// The shapes of the items at each pose: the samples, then the events.
    pub frames: Vec<Vec<Shape>>,
    /// The traced points at each pose (same order as `frames`).
    pub traced: Vec<Vec<[f64; 2]>>,
    /// The labels and their points at each pose (same order as `frames`).
    pub labels: Vec<Label>,
    pub labelled: Vec<Vec<[f64; 2]>>,
    /// How many of the poses are samples (the rest are events).
    pub samples: usize,
}

/// The labels of a drawing: each named point of its items and traces with its name (when
/// joint labels are on), then the drawing's own labels, which rename (or, empty, remove) the
/// label of the same named point.
fn label_points(d: &Drawing) -> Vec<(&Pt, String)> {
    let mut out: Vec<(&Pt, String)> = Vec::new();
    if d.annotate.joint_labels {
        for p in d.items.iter().flat_map(item_points).chain(&d.traces) {
            if let Pt::Point(name) = p
                && !out.iter().any(|(q, _)| matches!(q, Pt::Point(n) if n == name))
            {
                out.push((p, name.clone()));
            }
        }
    }
    for (p, text) in &d.labels {
        let same = |q: &Pt| matches!((p, q), (Pt::Point(a), Pt::Point(b)) if a == b);
        match out.iter().position(|(q, _)| same(q)) {
            Some(i) => out[i].1 = text.clone(),
            None => out.push((p, text.clone())),
        }
    }
    out.retain(|(_, t)| !t.is_empty());
    out
}

impl Scene {
    /// The drawing over the motion, fitted and cropped to its items, traced paths and labels.
    pub fn new(d: &Drawing, motion: &Motion) -> Result<Scene, DrawError> {
        Scene::build(d, motion, true)
    }

    /// The drawing over the motion without its labels (their points still checked), fitted and
    /// cropped to its items and traced paths alone: the picture of an interactive page, which
    /// writes no label over the mechanism.
    pub fn unlabelled(d: &Drawing, motion: &Motion) -> Result<Scene, DrawError> {
        Scene::build(d, motion, false)
    }

    fn build(d: &Drawing, motion: &Motion, labelled_too: bool) -> Result<Scene, DrawError> {
        d.canvas.check()?;
        d.style.check()?;
        if motion.poses.is_empty() {
            return Err(DrawError::EmptyMotion);
        }
        motion.check()?;
        let bound = BoundItems::new(d, motion)?;
        let label_pts = label_points(d);
        let label_bound = label_pts.iter().map(|(p, _)| bind(p, motion)).collect::<Result<Vec<_>, _>>()?;
        let mut world = Vec::with_capacity(motion.poses.len() + motion.events.len());
        let mut traced = Vec::with_capacity(world.capacity());
        let mut labelled = Vec::with_capacity(world.capacity());
        for (i, pose) in motion.all_poses().enumerate() {
            let e = Eval { state: state(pose), pose: i };
            world.push(bound.shapes(&e)?);
            traced.push(bound.traces.iter().map(|(p, b)| e.point(b, p)).collect::<Result<Vec<_>, _>>()?);
            let at = label_bound.iter().zip(&label_pts).map(|(b, (p, _))| e.point(b, p));
            labelled.push(at.collect::<Result<Vec<_>, _>>()?);
        }
        let mut pts = Vec::new();
        for shape in world.iter().flatten() {
            shape.extent(|p| pts.push(p));
        }
        pts.extend(traced.iter().flatten());
        if labelled_too {
            pts.extend(labelled.iter().flatten());
        }
        let fitted = d.canvas.view(&pts, RESERVE)?;
        let mut scene = Scene::at(fitted, &world, &traced, &labelled, Vec::new(), motion.poses.len());
        near(d, &scene.frames, &scene.traced)?;
        if labelled_too {
            scene.labels = scene.place_labels(label_pts.into_iter().map(|(_, t)| t).collect(), &d.style);
        }
        if d.canvas.window.is_none() {
            // Cropped to everything drawn over the whole motion, plus the margin.
            let [x0, y0, x1, y1] = scene.ink(&d.style);
            let pad = d.canvas.margin;
            let view = fitted.cropped([pad - x0, pad - y0], x1 - x0 + 2.0 * pad, y1 - y0 + 2.0 * pad);
            let labels = std::mem::take(&mut scene.labels);
            scene = Scene::at(view, &world, &traced, &labelled, labels, motion.poses.len());
        }
        Ok(scene)
    }

    /// The scene of the world shapes and points through `view`.
    fn at(
        view: View,
        world: &[Vec<Shape>],
        traced: &[Vec<[f64; 2]>],
        labelled: &[Vec<[f64; 2]>],
        labels: Vec<Label>,
        samples: usize,
    ) -> Scene {
        let px = |t: &Vec<[f64; 2]>| t.iter().map(|p| view.px(*p)).collect();
        Scene {
            view,
            frames: world.iter().map(|f| f.iter().map(|s| s.to_px(&view)).collect()).collect(),
            traced: traced.iter().map(px).collect(),
            labelled: labelled.iter().map(px).collect(),
            labels,
            samples,
        }
    }

    /// Each label placed beside its own point at the first pose, in a free direction: off the
    /// links, the guides and the pivot symbols, clear of the other joints and labels, nearer
    /// its own point than any other joint, and as far as it can be from the links and guides
    /// meeting at its point (the middle of the widest gap between them); among equally good
    /// places, away from the middle of the mechanism (outside it rather than across it).
    fn place_labels(&self, texts: Vec<String>, style: &Style) -> Vec<Label> {
        let shapes = &self.frames[0];
        let mut bars: Vec<[[f64; 2]; 2]> = Vec::new();
        let mut boxes: Vec<[f64; 4]> = Vec::new();
        let mut dots: Vec<[f64; 2]> = self.traced[0].clone();
        for shape in shapes {
            match shape {
                Shape::Link { pts, closed } => {
                    bars.extend(pts.windows(2).map(|w| [w[0], w[1]]));
                    if *closed && pts.len() > 2 {
                        bars.push([pts[pts.len() - 1], pts[0]]);
                    }
                    dots.extend(pts);
                }
                Shape::Guide { .. } => bars.push(shape.guide_ends()),
                // Kept clear of as a bar is, so that no label covers it; its ends are no joints.
                Shape::Construction { pts } => bars.push(*pts),
                Shape::Pivot { at: [x, y] } => {
                    // The triangle, ground line and hatching (see `Shape::ink`).
                    boxes.push([x - 15.0, y + 2.0, x + 15.0, y + 21.0]);
                    dots.push([*x, *y]);
                }
                Shape::Slider { .. } => {
                    let mut b = [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
                    shape.ink(style, |[x, y]| b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)]);
                    boxes.push(b);
                }
                Shape::Joint { at } => dots.push(*at),
                Shape::Gear { .. } | Shape::Outline { .. } => {}
            }
        }
        let mut all = Vec::new();
        shapes.iter().for_each(|s| s.extent(|p| all.push(p)));
        let n = all.len().max(1) as f64;
        let mid = all.iter().fold([0.0, 0.0], |m, p| [m[0] + p[0] / n, m[1] + p[1] / n]);
        let mut placed: Vec<[f64; 4]> = Vec::new();
        texts
            .into_iter()
            .zip(&self.labelled[0])
            .map(|(text, &p)| {
                let label = best_label(text, p, mid, &bars, &boxes, &dots, &placed, style);
                let mut b = [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
                label.ink(p, |[x, y]| b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)]);
                placed.push(b);
                label
            })
            .collect()
    }

    /// The bounding box `[x0, y0, x1, y1]` in pixels of everything drawn at every pose.
    pub fn ink(&self, style: &Style) -> [f64; 4] {
        let mut b = [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
        let mut add = |[x, y]: [f64; 2]| {
            if x.is_finite() && y.is_finite() {
                b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
            }
        };
        for (k, shapes) in self.frames.iter().enumerate() {
            shapes.iter().for_each(|s| s.ink(style, &mut add));
            for p in &self.traced[k] {
                add([p[0] - style.trace_width, p[1] - style.trace_width]);
                add([p[0] + style.trace_width, p[1] + style.trace_width]);
            }
            for (l, p) in self.labels.iter().zip(&self.labelled[k]) {
                l.ink(*p, &mut add);
            }
        }
        if b[0] > b[2] { [0.0, 0.0, self.view.width, self.view.height] } else { b }
    }

    /// Poses `i` and `j` look the same: every point within 0.05 px (the SVG's rounding).
    pub fn same_look(&self, i: usize, j: usize) -> bool {
        let pts = |k: usize| {
            let mut v = Vec::new();
            self.frames[k].iter().for_each(|s| s.extent(|p| v.push(p)));
            v.extend(&self.traced[k]);
            v
        };
        let (a, b) = (pts(i), pts(j));
        a.len() == b.len() && a.iter().zip(&b).all(|(p, q)| (p[0] - q[0]).abs() <= 0.05 && (p[1] - q[1]).abs() <= 0.05)
    }

    /// The poses along the motion's path: the samples, then the event where it stopped.
    pub fn path(&self, motion: &Motion) -> Vec<usize> {
        let mut path: Vec<usize> = (0..self.samples).collect();
        if motion.stopped && !motion.events.is_empty() {
            path.push(self.frames.len() - 1);
        }
        path
    }
}

/// Gap in pixels between a joint's centre and the nearest edge of its label.
const LABEL_GAP: f64 = LABEL_OFFSET;

/// Directions tried for a label, besides the middles of the gaps between the bars at its
/// point: every 15 degrees.
const LABEL_DIRECTIONS: usize = 24;

/// The label `text` of the joint at `p` (pixels) placed in the best of the directions tried:
/// the fewest links, guides, pivot symbols, blocks, other joints and labels `placed` under it
/// and no other joint nearer to it than `p`; then the widest angle from the bars meeting at
/// `p`; then the nearest to pointing away from `mid`.
#[allow(clippy::too_many_arguments)]
fn best_label(
    text: String,
    p: [f64; 2],
    mid: [f64; 2],
    bars: &[[[f64; 2]; 2]],
    boxes: &[[f64; 4]],
    dots: &[[f64; 2]],
    placed: &[[f64; 4]],
    style: &Style,
) -> Label {
    let (w, h) = (text_width(&text), FONT);
    let near = |q: [f64; 2]| (q[0] - p[0]).hypot(q[1] - p[1]) <= 1.0;
    // The directions of the bars leaving `p` (both ways along one passing through it).
    let mut leaving: Vec<f64> = Vec::new();
    for &[a, b] in bars {
        let towards = |q: [f64; 2]| (q[1] - p[1]).atan2(q[0] - p[0]);
        match (near(a), near(b)) {
            (true, false) => leaving.push(towards(b)),
            (false, true) => leaving.push(towards(a)),
            (false, false) if segment_distance(p, a, b) <= 1.0 => leaving.extend([towards(a), towards(b)]),
            _ => {}
        }
    }
    leaving.sort_by(f64::total_cmp);
    let mut tried: Vec<f64> =
        (0..LABEL_DIRECTIONS).map(|k| std::f64::consts::TAU * k as f64 / LABEL_DIRECTIONS as f64).collect();
    for (k, a) in leaving.iter().enumerate() {
        let next = if k + 1 < leaving.len() { leaving[k + 1] } else { leaving[0] + std::f64::consts::TAU };
        tried.push(0.5 * (a + next));
    }
    let away = (p[1] - mid[1]).atan2(p[0] - mid[0]);
    // At the middle itself: above and to the right.
    let away = if (p[0] - mid[0]).hypot(p[1] - mid[1]) > 1.0 { away } else { (-0.8f64).atan2(0.6) };
    let width = 0.5 * style.link_width + 1.0;
    let dot = style.joint_radius + 1.5;
    let mut best: Option<(f64, [f64; 2])> = None;
    for a in tried {
        let u = [a.cos(), a.sin()];
        let c = label_centre(u, w, h);
        let b = [p[0] + c[0] - 0.5 * w, p[1] + c[1] - 0.5 * h, p[0] + c[0] + 0.5 * w, p[1] + c[1] + 0.5 * h];
        let own = box_distance(b, p);
        let mut cost = 0.0;
        cost += 1000.0 * bars.iter().filter(|&&[s, e]| segment_box_distance(s, e, b) < width).count() as f64;
        cost += 1000.0 * boxes.iter().filter(|o| overlap(b, **o)).count() as f64;
        cost += 1000.0 * placed.iter().filter(|o| overlap(b, **o)).count() as f64;
        for &q in dots.iter().filter(|q| !near(**q)) {
            let d = box_distance(b, q);
            if d < dot {
                cost += 1000.0;
            }
            if d <= own {
                cost += 1000.0;
            }
        }
        let clear = leaving.iter().map(|l| angle_between(a, *l)).fold(std::f64::consts::PI, f64::min);
        cost -= 100.0 * clear;
        cost += 10.0 * angle_between(a, away);
        if best.is_none_or(|(c, _)| cost < c) {
            best = Some((cost, c));
        }
    }
    let offset = best.map_or([LABEL_OFFSET, 0.0], |(_, c)| c);
    Label { text, offset, anchor: "middle" }
}

/// The centre of a label `w` by `h` pixels in direction `u` from its joint: the nearest to the
/// joint that keeps the label [`LABEL_GAP`] from the joint's centre.
fn label_centre(u: [f64; 2], w: f64, h: f64) -> [f64; 2] {
    let gap = |t: f64| ((t * u[0]).abs() - 0.5 * w).max(0.0).hypot(((t * u[1]).abs() - 0.5 * h).max(0.0));
    let (mut lo, mut hi) = (0.0, LABEL_GAP + w + h);
    for _ in 0..40 {
        let t = 0.5 * (lo + hi);
        if gap(t) < LABEL_GAP { lo = t } else { hi = t }
    }
    [hi * u[0], hi * u[1]]
}

/// The angle between directions `a` and `b` (radians), from 0 to pi.
fn angle_between(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

/// Distance from `q` to the box `[x0, y0, x1, y1]` (0 inside).
fn box_distance(b: [f64; 4], q: [f64; 2]) -> f64 {
    let dx = (b[0] - q[0]).max(q[0] - b[2]).max(0.0);
    let dy = (b[1] - q[1]).max(q[1] - b[3]).max(0.0);
    dx.hypot(dy)
}

/// Boxes `a` and `b` overlap.
fn overlap(a: [f64; 4], b: [f64; 4]) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// Distance from `q` to the segment from `a` to `b`.
fn segment_distance(q: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx * dx + dy * dy;
    let t = if len > 0.0 { (((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / len).clamp(0.0, 1.0) } else { 0.0 };
    (q[0] - a[0] - t * dx).hypot(q[1] - a[1] - t * dy)
}

/// Distance from the segment from `a` to `b` to the box `[x0, y0, x1, y1]` (0 when it
/// crosses it): the least of the corners' distances to the segment and the ends' to the box,
/// unless the segment crosses the box.
fn segment_box_distance(a: [f64; 2], b: [f64; 2], bx: [f64; 4]) -> f64 {
    let corners = [[bx[0], bx[1]], [bx[2], bx[1]], [bx[2], bx[3]], [bx[0], bx[3]]];
    let edges = [0, 1, 2, 3].map(|k| (corners[k], corners[(k + 1) % 4]));
    if box_distance(bx, a) == 0.0 || box_distance(bx, b) == 0.0 || edges.iter().any(|&(c, d)| crosses(a, b, c, d)) {
        return 0.0;
    }
    let from_corners = corners.iter().map(|c| segment_distance(*c, a, b)).fold(f64::INFINITY, f64::min);
    from_corners.min(box_distance(bx, a)).min(box_distance(bx, b))
}

/// Segments `a`-`b` and `c`-`d` cross.
fn crosses(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let side = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
    let (d1, d2) = (side(a, b, c), side(a, b, d));
    let (d3, d4) = (side(c, d, a), side(c, d, b));
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

/// Every pixel coordinate and size within [`FAR`] of the origin (a window can put points
/// anywhere, even at infinite pixels).
fn near(d: &Drawing, frames: &[Vec<Shape>], traced: &[Vec<[f64; 2]>]) -> Result<(), DrawError> {
    let far = |v: f64| v.is_nan() || v.abs() > FAR;
    for (pose, (shapes, traced)) in frames.iter().zip(traced).enumerate() {
        for (k, shape) in shapes.iter().enumerate() {
            let mut out = false;
            shape.extent(|[x, y]| out |= far(x) || far(y));
            if let Shape::Gear { radius, .. } | Shape::Outline { radius, .. } = shape {
                out |= far(*radius);
            }
            if out {
                return Err(DrawError::OffCanvas { what: format!("item {k} ({:?})", d.items[k]), pose });
            }
        }
        if let Some(t) = traced.iter().position(|[x, y]| far(*x) || far(*y)) {
            return Err(DrawError::OffCanvas { what: format!("traced {}", d.traces[t].describe()), pose });
        }
    }
    Ok(())
}

fn state(p: &Pose) -> StateRef<'_> {
    StateRef { x: &p.x, q: &p.q, out: &p.out }
}
