//! A drawing evaluated over a motion: every item's geometry at every pose, in pixels.

use super::error::DrawError;
use super::motion::{Motion, Pose};
use super::spec::{Drawing, Item, PointFn, Pt, Scalar, StateRef};
use super::view::{FAR, View};

/// The geometry of one item at one pose (world units, then pixels after [`Shape::to_px`]).
/// Angles are radians counter-clockwise in world units and degrees clockwise (SVG) in pixels.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Shape {
    Link { pts: Vec<[f64; 2]>, closed: bool },
    Pivot { at: [f64; 2] },
    Slider { at: [f64; 2], angle: f64, fixed: bool },
    Gear { centre: [f64; 2], radius: f64, angle: f64, turning: bool },
    Joint { at: [f64; 2] },
}

impl Shape {
    /// The points that must fit in the picture (and that tell two poses apart).
    pub(crate) fn extent(&self, mut add: impl FnMut([f64; 2])) {
        match self {
            Shape::Link { pts, .. } => pts.iter().for_each(|p| add(*p)),
            Shape::Pivot { at } | Shape::Slider { at, .. } | Shape::Joint { at } => add(*at),
            Shape::Gear { centre: [x, y], radius: r, .. } => {
                add([x - r, y - r]);
                add([x + r, y + r]);
            }
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
            Shape::Gear { centre, radius, angle, turning } => {
                Shape::Gear { centre: v.px(*centre), radius: radius * v.scale, angle: deg(*angle), turning: *turning }
            }
            Shape::Joint { at } => Shape::Joint { at: v.px(*at) },
        }
    }
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
}

fn item_points(item: &Item) -> Vec<&Pt> {
    match item {
        Item::Link { through, .. } => through.iter().collect(),
        Item::Pivot { at } | Item::Slider { at, .. } | Item::Joint { at } => vec![at],
        Item::Gear { centre, .. } => vec![centre],
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
        Ok(BoundItems { items, traces })
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

/// A drawing evaluated at the poses of a motion, in pixels.
pub(crate) struct Scene {
    pub view: View,
    /// The shapes of the items at each pose: the samples, then the events.
    pub frames: Vec<Vec<Shape>>,
    /// The traced points at each pose (same order as `frames`).
    pub traced: Vec<Vec<[f64; 2]>>,
    /// How many of the poses are samples (the rest are events).
    pub samples: usize,
}

impl Scene {
    pub fn new(d: &Drawing, motion: &Motion) -> Result<Scene, DrawError> {
        d.canvas.check()?;
        d.style.check()?;
        if motion.poses.is_empty() {
            return Err(DrawError::EmptyMotion);
        }
        motion.check()?;
        let bound = BoundItems::new(d, motion)?;
        let mut frames = Vec::with_capacity(motion.poses.len() + motion.events.len());
        let mut traced = Vec::with_capacity(frames.capacity());
        for (i, pose) in motion.all_poses().enumerate() {
            let e = Eval { state: state(pose), pose: i };
            frames.push(bound.shapes(&e)?);
            traced.push(bound.traces.iter().map(|(p, b)| e.point(b, p)).collect::<Result<Vec<_>, _>>()?);
        }
        let mut pts = Vec::new();
        for shape in frames.iter().flatten() {
            shape.extent(|p| pts.push(p));
        }
        pts.extend(traced.iter().flatten());
        let view = d.canvas.view(&pts)?;
        let frames: Vec<Vec<Shape>> = frames.iter().map(|f| f.iter().map(|s| s.to_px(&view)).collect()).collect();
        let traced: Vec<Vec<[f64; 2]>> = traced.iter().map(|t| t.iter().map(|p| view.px(*p)).collect()).collect();
        near(d, &frames, &traced)?;
        Ok(Scene { view, frames, traced, samples: motion.poses.len() })
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

/// Every pixel coordinate and size within [`FAR`] of the origin (a window can put points
/// anywhere, even at infinite pixels).
fn near(d: &Drawing, frames: &[Vec<Shape>], traced: &[Vec<[f64; 2]>]) -> Result<(), DrawError> {
    let far = |v: f64| v.is_nan() || v.abs() > FAR;
    for (pose, (shapes, traced)) in frames.iter().zip(traced).enumerate() {
        for (k, shape) in shapes.iter().enumerate() {
            let mut out = false;
            shape.extent(|[x, y]| out |= far(x) || far(y));
            if let Shape::Gear { radius, .. } = shape {
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
