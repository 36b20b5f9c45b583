//! The cam found by inversion (`cam::find`) added to a mechanism's drawing: its profile turning
//! about its pivot with the input, and what touches it (the roller about the follower's point, or
//! the flat face's plate, moving and turning with the follower), so that `kinloop animate --cam`
//! shows the cam that makes the declared motion.

use crate::cam::{Found, Shape};
use kinloop_model::Count;
use kinloop_runtime::Number;
use kinloop_runtime::analysis::cam::FlatFace;
use kinloop_viz::draw::{DefaultDrawing, Pt, Scalar, StateRef};

/// Samples of the turn the drawn cam is found from: a corner every half degree.
pub const SAMPLES: usize = 721;

/// `drawing` with the cam of `found` added, `point` the follower's point.
pub fn with_cam(drawing: DefaultDrawing, found: &Found, point: &str) -> DefaultDrawing {
    let (pivot, turn, columns) = (found.pivot, found.turn, found.columns);
    let profile = found.profile().to_vec();
    let touching = match &found.shape {
        Shape::Roller(cam, _) if cam.roller > 0.0 => Touching::Roller(point.to_string(), cam.roller),
        Shape::Roller(..) => Touching::KnifeEdge,
        Shape::Flat(_, line, _) => Touching::Face(*line, plate(found).unwrap_or_default()),
    };
    let warning = warning(found);
    drawing.extend(move |d| {
        let d = d.pivot(pivot).outline(pivot, profile, Scalar::expr(move |s| turn * s.x[0]));
        let d = match touching {
            Touching::Roller(point, radius) => d.circle(point.as_str(), radius).note(format!(
                "the cam's profile for a roller of radius {}, by inversion of the follower's motion",
                Number(radius)
            )),
            Touching::KnifeEdge => d.note("the cam's profile for a knife edge, by inversion of the follower's motion"),
            Touching::Face(line, plate) => {
                let at = move |s: &StateRef| [s.out[columns.0], s.out[columns.1]];
                let origin = Pt::expr(move |s| line.point(at(s), 0.0));
                let angle = Scalar::expr(move |s| {
                    let t = line.direction(at(s));
                    t[1].atan2(t[0])
                });
                d.outline(origin, plate, angle)
                    .note("the cam's profile for the flat face, by inversion of the follower's motion")
            }
        };
        match warning {
            Some(w) => d.note(w),
            None => d,
        }
    })
}

/// The size of the cam's profile: its farthest point from the pivot.
fn size(found: &Found) -> f64 {
    found.profile().iter().fold(0.0f64, |r, p| r.max(p[0].hypot(p[1])))
}

/// A flat face's plate, in the face's frame (its origin, its direction along x): as long as the
/// contacts with a margin, a thirtieth of the cam's size thick, on the side of the face away
/// from the cam. `None` for a roller or a knife edge.
fn plate(found: &Found) -> Option<Vec<[f64; 2]>> {
    let Shape::Flat(cam, line, _) = &found.shape else { return None };
    let size = size(found);
    let (lo, hi) = cam.offset_range();
    let margin = 0.1 * (hi - lo) + 0.05 * size;
    let thick = line.away * size / 30.0;
    let (lo, hi) = (lo - margin, hi + margin);
    Some(vec![[lo, 0.0], [hi, 0.0], [hi, thick], [lo, thick]])
}

/// The most a coordinate of what [`with_cam`] draws can reach from the origin over the turn (a
/// bound: the drawing's own extent is no larger): the cam about its pivot; the roller about
/// the follower's point, which lies within the cam's size and the roller's radius of the
/// pivot; a flat face's plate about its origin, the follower's point (within the cam's size
/// of the pivot) or the foot of the rocker's pivot on the face.
fn reach(found: &Found) -> f64 {
    let far = |p: [f64; 2]| p[0].abs().max(p[1].abs());
    let (pivot, size) = (far(found.pivot), size(found));
    match &found.shape {
        Shape::Roller(cam, _) => pivot + size + 2.0 * cam.roller,
        Shape::Flat(_, line, _) => {
            let plate = plate(found).unwrap_or_default().iter().fold(0.0f64, |r, p| r.max(p[0].hypot(p[1])));
            let origin = match line.face {
                FlatFace::Translating { .. } => pivot + size,
                FlatFace::Rocking { pivot: a, offset, .. } => far(a) + offset.abs(),
            };
            (pivot + size).max(origin + plate)
        }
    }
}

/// Refuses a cam whose drawing would reach farther from the origin than an `f64` holds (a
/// pivot or a rocker's pivot near the largest finite number, `--pivot 1e308,0`): a usage error
/// naming the follower's options (`options`) and the bound, where the drawing failed with its
/// own "extent of item 5 (outline) is not finite" and exit code 1.
pub fn fits(found: &Found, options: &str) -> Result<(), crate::Failed> {
    let reach = reach(found);
    if reach <= f64::MAX {
        return Ok(());
    }
    // The sum overflows to infinity where it is beyond the largest double: no number to say.
    let reaches = match reach.is_finite() {
        true => format!("reaches {} from the origin", Number(reach)),
        false => "reaches farther from the origin".to_string(),
    };
    Err(crate::exit::usage(format!(
        "the cam of the follower given ({options}) cannot be drawn: the cam about its pivot (its pivot's distance from \
         the origin and its radius added, and what touches it) {reaches} than the largest coordinate a drawing \
         holds, {}; give the cam's pivot (and a rocker's) nearer the follower's path",
        Number(f64::MAX)
    )))
}

/// The warning written into the drawing where the cam cannot make the motion (as the checks on
/// standard error say): a roller larger than the pitch curve's curvature (the profile drawn
/// crosses itself), or a flat face's profile that is not convex (the face's envelope folds),
/// at samples, or between them where no sample falls (the checks located between them).
/// A drawing read without the command's standard error would show such a cam as if it worked.
fn warning(found: &Found) -> Option<String> {
    let (unit, angle) = if found.deg { ("°", 180.0 / std::f64::consts::PI) } else { (" rad", 1.0) };
    // Short, as a line under the picture (which is widened to its longest line): what and
    // where, the rest is on standard error.
    let (what, at, why) = match &found.shape {
        Shape::Roller(cam, _) => ("UNDERCUT", cam.undercut(), "the profile crosses itself; use a smaller roller"),
        Shape::Flat(cam, ..) => ("NOT CONVEX", cam.not_convex(), "a flat face cannot follow the law"),
    };
    if at.is_empty() {
        // Where no sample falls in it, the located checks still see it (the summary says so).
        let between = match &found.shape {
            Shape::Roller(_, c) if c.undercut() => c.min_convex_radius.map(|r| r.x),
            Shape::Flat(_, _, c) if !c.convex() => Some(c.min_radius.x),
            _ => None,
        };
        return between.map(|x| format!("{what} between the samples, at {}{unit}: {why}", Number(x * angle)));
    }
    let input = |k: usize| found.inputs.get(k).copied().unwrap_or(f64::NAN);
    // Each stretch of consecutive samples on its own: one span from the first to the last
    // said the whole of it was bad where a three-lobed cam has three stretches apart.
    let mut stretches: Vec<(usize, usize)> = Vec::new();
    for &k in &at {
        match stretches.last_mut() {
            Some((_, last)) if *last + 1 == k => *last = k,
            _ => stretches.push((k, k)),
        }
    }
    let mut spans: Vec<String> = stretches
        .iter()
        .take(SHOWN_STRETCHES)
        .map(|&(a, b)| match a == b {
            true => format!("{}{unit}", Number(input(a))),
            false => format!("{}{unit} to {}{unit}", Number(input(a)), Number(input(b))),
        })
        .collect();
    if stretches.len() > SHOWN_STRETCHES {
        spans.push(format!("and {} more", stretches.len() - SHOWN_STRETCHES));
    }
    Some(format!("{what} at {} ({}): {why}", Count(at.len(), "sample"), spans.join(", ")))
}

/// The stretches of bad samples a drawing's warning lists (the rest counted): a line under the
/// picture, which is widened to its longest line.
const SHOWN_STRETCHES: usize = 3;

/// What touches the cam, as drawn.
enum Touching {
    /// A roller of the radius about the named point.
    Roller(String, f64),
    /// A knife edge: the follower's point itself, drawn by the declaration.
    KnifeEdge,
    /// A flat face, drawn as a plate: its corners in the face's frame.
    Face(FaceLine, Vec<[f64; 2]>),
}

/// Where a flat face lies, given its follower's point: the runtime's [`FlatFace`] with a
/// translating follower's guide.
#[derive(Clone, Copy, Debug)]
pub struct FaceLine {
    /// The face.
    pub face: FlatFace,
    /// A translating follower's guide (any length but zero); not read for a rocking one.
    pub guide: [f64; 2],
    /// The side of the face away from the cam: 1 on the left of the face's direction, -1 on
    /// its right.
    pub away: f64,
}

impl FaceLine {
    /// The point of the face at `along` in its direction from its origin, where the follower's
    /// point is at `p`: the origin is the point itself for a translating follower and the foot
    /// of the rocker's pivot on the face for a rocking one, as `flat_face_profile` counts the
    /// contact's offsets.
    pub fn point(&self, p: [f64; 2], along: f64) -> [f64; 2] {
        let t = self.direction(p);
        let origin = match self.face {
            FlatFace::Translating { .. } => p,
            // The foot of the pivot on the face: `offset` to the left of the face's direction.
            FlatFace::Rocking { pivot: a, offset, .. } => [a[0] - offset * t[1], a[1] + offset * t[0]],
        };
        [origin[0] + along * t[0], origin[1] + along * t[1]]
    }

    /// The face's direction (a unit vector), where the follower's point is at `p`: the guide
    /// turned a quarter clockwise, or the arm from the rocker's pivot to `p`, then by the tilt.
    pub fn direction(&self, p: [f64; 2]) -> [f64; 2] {
        let (v, tilt) = match self.face {
            FlatFace::Translating { tilt } => ([self.guide[1], -self.guide[0]], tilt),
            FlatFace::Rocking { pivot: a, tilt, .. } => ([p[0] - a[0], p[1] - a[1]], tilt),
        };
        let n = v[0].hypot(v[1]);
        let (s, c) = tilt.sin_cos();
        [(c * v[0] - s * v[1]) / n, (s * v[0] + c * v[1]) / n]
    }

    /// The side of the face away from the cam's pivot `centre` where the follower's point is at
    /// `p` (see [`FaceLine::away`]).
    pub fn side_away(&self, p: [f64; 2], centre: [f64; 2]) -> f64 {
        let (o, t) = (self.point(p, 0.0), self.direction(p));
        if -t[1] * (o[0] - centre[0]) + t[0] * (o[1] - centre[1]) >= 0.0 { 1.0 } else { -1.0 }
    }
}
