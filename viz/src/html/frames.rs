//! The drawing evaluated at the poses the page shows, as the integers the page holds:
//! coordinates in tenths of a pixel, angles in tenths of a degree.
//!
//! Tenths of a pixel is the resolution of the kinloop SVG drawings: below what a screen shows,
//! and a mechanism drawn 600 pixels wide is resolved to 1/6000 of its extent. Integers keep the
//! page small and cannot hold a NaN.

use super::HtmlError;
use crate::draw::retrace::unretraced;
use crate::draw::{Drawing, Item, Motion, Pose, Pt, Scalar, StateRef, View, guide_at, guide_spans};
use std::f64::consts::TAU;

/// Largest pixel coordinate written (as the drawings: beyond it a renderer loses precision).
const FAR: f64 = 1e9;

/// What one item of the drawing is on the page, and where its numbers sit in a frame.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Slot {
    /// A bar, chain of bars or filled body through `n` points: `2 n` numbers.
    Link { n: usize, closed: bool },
    /// A fixed pivot: its position, 2 numbers.
    Pivot,
    /// A slider block: position and angle, 3 numbers; `fixed` when its guide does not turn.
    Slider { fixed: bool },
    /// A gear: centre and angle, 3 numbers, with its pitch radius in pixels.
    Gear { radius: f64, turning: bool },
    /// A rigid outline: centre and angle, 3 numbers, with its corners in pixels in the body's
    /// frame (y down).
    Outline { corners: Vec<[f64; 2]> },
    /// A lone joint: 2 numbers.
    Joint,
    /// A turning guide: a bar between its two ends, 4 numbers, with no joint circles.
    Guide,
    /// A construction line: a thin dashed line between its two ends, 4 numbers, with no joint
    /// circles.
    Construction,
}

impl Slot {
    /// How many numbers the item takes in a frame.
    pub(crate) fn len(&self) -> usize {
        match self {
            Slot::Link { n, .. } => 2 * n,
            Slot::Pivot | Slot::Joint => 2,
            Slot::Guide | Slot::Construction => 4,
            Slot::Slider { .. } | Slot::Gear { .. } | Slot::Outline { .. } => 3,
        }
    }
}

/// The drawing at the page's frames and at the motion's events.
pub(crate) struct Frames {
    /// Mechanism units to pixels (the drawings' fit of the motion, cropped to what the page
    /// draws: [`Drawing::page_view`]).
    pub view: View,
    /// The items, in drawing order.
    pub slots: Vec<Slot>,
    /// Where the traced points start in a frame (after every item), one pair each.
    pub traces_at: usize,
    /// The poses shown, as indices of the motion's samples followed by its events.
    pub poses: Vec<usize>,
    /// Per frame: the numbers of every item, then of every traced point.
    pub frames: Vec<Vec<i64>>,
    /// The same numbers at each event of the motion.
    pub events: Vec<Vec<i64>>,
    /// Every traced point along the whole path of the motion (all samples), in tenths of a
    /// pixel, consecutive equal ones merged and segments that retrace ones already drawn left
    /// out (`unretraced`): per traced point, its runs (one for a sweep; on a grid, one per run
    /// of reachable cells along the first input), each in pieces (one unless it retraces
    /// itself).
    pub paths: Vec<Vec<Vec<Vec<[i64; 2]>>>>,
}

/// The poses along the motion: its samples, then the event where it stopped (as the drawings).
pub(crate) fn path(motion: &Motion) -> Vec<usize> {
    let mut path: Vec<usize> = (0..motion.poses.len()).collect();
    if motion.stopped && !motion.events.is_empty() {
        path.push(motion.poses.len() + motion.events.len() - 1);
    }
    path
}

/// At most `count` of `path`, one every so many poses from the first, and the last: the page
/// plays its frames at one rate, so equal steps along the path move the inputs at one speed
/// (picked by rounding, 1000 poses in 721 frames were steps of one and two poses: the crank
/// jerked ahead at every other frame). Only the step to the last may be shorter.
pub(crate) fn spread(path: &[usize], count: usize) -> Vec<usize> {
    let n = path.len();
    if count >= n || count < 2 {
        return path.to_vec();
    }
    let step = (n - 1).div_ceil(count - 1);
    let mut out: Vec<usize> = path.iter().step_by(step).copied().collect();
    if out.last() != path.last() {
        out.push(path[n - 1]);
    }
    out
}

/// Pose `i` of the motion: a sample, or an event after the samples.
pub(crate) fn pose(motion: &Motion, i: usize) -> &Pose {
    motion.poses.get(i).unwrap_or_else(|| &motion.events[i - motion.poses.len()].pose)
}

pub(crate) fn state(p: &Pose) -> StateRef<'_> {
    StateRef { x: &p.x, q: &p.q, out: &p.out }
}

/// A value in tenths (of a pixel, of a degree), checked finite and near.
fn tenths(v: f64, what: impl FnOnce() -> String, pose: usize) -> Result<i64, HtmlError> {
    if v.is_finite() && v.abs() <= FAR {
        Ok((v * 10.0).round() as i64)
    } else {
        Err(HtmlError::NonFinite { what: what(), pose })
    }
}

/// The page's angle of a direction `a` (radians counter-clockwise, mechanism): degrees
/// clockwise (SVG's `rotate`), reduced to a turn first so that any finite angle is written.
fn svg_degrees(a: f64) -> f64 {
    -(a % TAU).to_degrees()
}

/// The points of an item (as the drawings bind them).
fn item_points(item: &Item) -> Vec<&Pt> {
    match item {
        Item::Link { through, .. } => through.iter().collect(),
        Item::Pivot { at } | Item::Slider { at, .. } | Item::Joint { at } => vec![at],
        Item::Gear { centre, .. } | Item::Outline { centre, .. } => vec![centre],
        // Its ends, which its span over the whole motion places (`Eval::frame`).
        Item::Guide { .. } => Vec::new(),
        Item::Construction { from, to } => vec![from, to],
    }
}

struct Eval<'a> {
    motion: &'a Motion,
    view: View,
    /// Each turning guide's span over the motion (as the drawings').
    spans: Vec<Option<[f64; 2]>>,
}

impl Eval<'_> {
    /// Point `p` at pose `i` in tenths of a pixel.
    fn point(&self, p: &Pt, i: usize) -> Result<[i64; 2], HtmlError> {
        let pose = pose(self.motion, i);
        let xy = match p {
            Pt::Point(name) => {
                let (ix, iy) = self.motion.point_columns(name)?;
                [pose.out[ix], pose.out[iy]]
            }
            Pt::Fixed(xy) => *xy,
            Pt::Expr(f) => f(&state(pose)),
        };
        let what = || format!("pixel of {}", p.describe());
        if !(xy[0].is_finite() && xy[1].is_finite()) {
            return Err(HtmlError::NonFinite { what: p.describe(), pose: i });
        }
        let [x, y] = self.view.px(xy);
        Ok([tenths(x, what, i)?, tenths(y, what, i)?])
    }

    /// Angle `s` at pose `i` in tenths of a degree (SVG's sense).
    fn angle(&self, s: &Scalar, i: usize, k: usize) -> Result<i64, HtmlError> {
        let a = match s {
            Scalar::Const(v) => *v,
            Scalar::Expr(f) => f(&state(pose(self.motion, i))),
        };
        let what = || format!("angle of item {k}");
        if !a.is_finite() {
            return Err(HtmlError::NonFinite { what: what(), pose: i });
        }
        tenths(svg_degrees(a), what, i)
    }

    /// Every item's numbers, then every traced point's, at pose `i`.
    fn frame(&self, d: &Drawing, i: usize) -> Result<Vec<i64>, HtmlError> {
        let mut out = Vec::new();
        for (k, item) in d.items.iter().enumerate() {
            for p in item_points(item) {
                out.extend(self.point(p, i)?);
            }
            match item {
                Item::Slider { angle, .. } | Item::Gear { angle, .. } | Item::Outline { angle, .. } => {
                    out.push(self.angle(angle, i, k)?)
                }
                Item::Guide { .. } => {
                    let span = self.spans[k].unwrap_or_default();
                    for end in guide_at(item, span, self.motion, pose(self.motion, i), i)?.unwrap_or_default() {
                        out.extend(self.point(&Pt::Fixed(end), i)?);
                    }
                }
                _ => {}
            }
        }
        for t in &d.traces {
            out.extend(self.point(t, i)?);
        }
        Ok(out)
    }
}

impl Frames {
    /// `d` at the poses `poses` of `motion`, its traced paths through the poses of each of
    /// `runs`; in `view`, or fitted to the drawing over the motion.
    pub(crate) fn build(
        d: &Drawing,
        motion: &Motion,
        poses: Vec<usize>,
        runs: &[Vec<usize>],
        view: Option<View>,
    ) -> Result<Frames, HtmlError> {
        // The drawings' own checks (names, shapes of poses, finite points, style, canvas) and
        // their fit of the picture to every pose, without what the page does not draw over it
        // (labels, the strip of annotations under an SVG drawing).
        let fitted = d.page_view(motion)?;
        let view = view.unwrap_or(fitted);
        let e = Eval { motion, view, spans: guide_spans(d, motion)? };
        let mut slots = Vec::with_capacity(d.items.len());
        for item in &d.items {
            slots.push(match item {
                Item::Link { through, closed } => Slot::Link { n: through.len(), closed: *closed },
                Item::Pivot { .. } => Slot::Pivot,
                Item::Slider { angle, .. } => Slot::Slider { fixed: matches!(angle, Scalar::Const(_)) },
                Item::Gear { radius, angle, .. } => {
                    Slot::Gear { radius: radius * view.scale, turning: matches!(angle, Scalar::Expr(_)) }
                }
                Item::Outline { points, .. } => {
                    Slot::Outline { corners: points.iter().map(|p| [p[0] * view.scale, -p[1] * view.scale]).collect() }
                }
                Item::Joint { .. } => Slot::Joint,
                Item::Guide { .. } => Slot::Guide,
                Item::Construction { .. } => Slot::Construction,
            });
        }
        let traces_at = slots.iter().map(Slot::len).sum();
        let frames = poses.iter().map(|&i| e.frame(d, i)).collect::<Result<Vec<_>, _>>()?;
        let events =
            (0..motion.events.len()).map(|j| e.frame(d, motion.poses.len() + j)).collect::<Result<Vec<_>, _>>()?;
        let mut paths = vec![Vec::new(); d.traces.len()];
        for run in runs {
            for (t, p) in d.traces.iter().enumerate() {
                let points = run.iter().map(|&i| e.point(p, i)).collect::<Result<Vec<_>, _>>()?;
                // Segments that retrace ones already drawn (a sweep of many turns) are left out.
                let (pieces, _) = unretraced(points);
                paths[t].push(pieces);
            }
        }
        Ok(Frames { view, slots, traces_at, poses, frames, events, paths })
    }
}

/// Where each event sits on the slider, in frame indices (fractional): on the segment between
/// two consecutive frames nearest to the event's inputs.
pub(crate) fn event_positions(motion: &Motion, poses: &[usize]) -> Vec<f64> {
    let x = |i: usize| &pose(motion, i).x;
    motion
        .events
        .iter()
        .map(|ev| {
            let mut best = (f64::INFINITY, 0.0);
            for (k, w) in poses.windows(2).enumerate() {
                let (a, b) = (x(w[0]), x(w[1]));
                let d: Vec<f64> = b.iter().zip(a).map(|(b, a)| b - a).collect();
                let dd: f64 = d.iter().map(|v| v * v).sum();
                let s = if dd > 0.0 {
                    (ev.pose.x.iter().zip(a).zip(&d).map(|((e, a), d)| (e - a) * d).sum::<f64>() / dd).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let dist: f64 = ev.pose.x.iter().zip(a).zip(&d).map(|((e, a), d)| (e - a - s * d).powi(2)).sum::<f64>();
                if dist < best.0 {
                    best = (dist, k as f64 + s);
                }
            }
            best.1
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::spread;

    /// Equal steps along the path, at most the count asked, the first and last kept; only the
    /// step to the last may be shorter.
    #[test]
    fn frames_are_equal_steps_along_the_path() {
        for (n, count) in [(1000, 721), (181, 90), (12, 4), (11, 4), (10, 4), (5, 5), (5, 9), (3, 2)] {
            let path: Vec<usize> = (0..n).collect();
            let got = spread(&path, count);
            assert!(got.len() <= count.max(2) && got.len() >= 2, "{n} {count}: {got:?}");
            assert_eq!((got[0], got[got.len() - 1]), (0, n - 1), "{n} {count}");
            let steps: Vec<usize> = got.windows(2).map(|w| w[1] - w[0]).collect();
            let first = steps[0];
            assert!(steps[..steps.len() - 1].iter().all(|&s| s == first), "{n} {count}: {steps:?}");
            assert!(steps[steps.len() - 1] <= first && steps[steps.len() - 1] > 0, "{n} {count}: {steps:?}");
        }
    }
}
