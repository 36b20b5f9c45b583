//! The cam found by inversion (`cam::find`) added to a mechanism's drawing: its profile turning
//! about its pivot with the input, and what touches it (the roller about the follower's point, or
//! the flat face through it), so that `kinloop animate --cam` shows the cam that makes the
//! declared motion.

use crate::cam::{Found, Shape};
use kinloop_runtime::analysis::cam::FlatFace;
use kinloop_viz::draw::{DefaultDrawing, Pt, Scalar};

/// Samples of the turn the drawn cam is found from: a corner every half degree.
pub const SAMPLES: usize = 721;

/// `drawing` with the cam of `found` added; `columns` are the output columns of the follower's
/// point `point` (`NAME.x`, `NAME.y`).
pub fn with_cam(drawing: DefaultDrawing, found: &Found, point: &str, columns: (usize, usize)) -> DefaultDrawing {
    let (pivot, turn) = (found.pivot, found.turn);
    let profile = found.profile().to_vec();
    // The profile's size, for the flat face's margins beyond its contacts.
    let size = profile.iter().fold(0.0f64, |r, p| r.max(p[0].hypot(p[1])));
    let touching = match &found.shape {
        Shape::Roller(cam) if cam.roller > 0.0 => Touching::Roller(point.to_string(), cam.roller),
        Shape::Roller(_) => Touching::KnifeEdge,
        Shape::Flat(cam, line) => {
            let (lo, hi) = cam.offset_range();
            let margin = 0.1 * (hi - lo) + 0.05 * size;
            Touching::Face(*line, lo - margin, hi + margin)
        }
    };
    drawing.extend(move |d| {
        let d = d.pivot(pivot).outline(pivot, profile, Scalar::expr(move |s| turn * s.x[0]));
        match touching {
            Touching::Roller(point, radius) => d.circle(point.as_str(), radius).note(format!(
                "the cam's profile for a roller of radius {radius}, by inversion of the follower's motion"
            )),
            Touching::KnifeEdge => d.note("the cam's profile for a knife edge, by inversion of the follower's motion"),
            Touching::Face(line, lo, hi) => {
                let end = |along: f64| Pt::expr(move |s| line.point([s.out[columns.0], s.out[columns.1]], along));
                d.link([end(lo), end(hi)])
                    .note("the cam's profile for the flat face, by inversion of the follower's motion")
            }
        }
    })
}

/// What touches the cam, as drawn.
enum Touching {
    /// A roller of the radius about the named point.
    Roller(String, f64),
    /// A knife edge: the follower's point itself, drawn by the declaration.
    KnifeEdge,
    /// A flat face, drawn from the first offset along it to the second.
    Face(FaceLine, f64, f64),
}

/// Where a flat face lies, given its follower's point: the runtime's [`FlatFace`] with a
/// translating follower's guide.
#[derive(Clone, Copy, Debug)]
pub struct FaceLine {
    /// The face.
    pub face: FlatFace,
    /// A translating follower's guide (any length but zero); not read for a rocking one.
    pub guide: [f64; 2],
}

impl FaceLine {
    /// The point of the face at `along` in its direction from its origin, where the follower's
    /// point is at `p`: the origin is the point itself for a translating follower and the foot
    /// of the rocker's pivot on the face for a rocking one, as `flat_face_profile` counts the
    /// contact's offsets.
    pub fn point(&self, p: [f64; 2], along: f64) -> [f64; 2] {
        let turned = |tilt: f64, v: [f64; 2]| {
            let (s, c) = tilt.sin_cos();
            [c * v[0] - s * v[1], s * v[0] + c * v[1]]
        };
        match self.face {
            FlatFace::Translating { tilt } => {
                let g = self.guide;
                let n = g[0].hypot(g[1]);
                // The guide turned a quarter clockwise, then by the tilt.
                let t = turned(tilt, [g[1] / n, -g[0] / n]);
                [p[0] + along * t[0], p[1] + along * t[1]]
            }
            FlatFace::Rocking { pivot: a, offset, tilt } => {
                let arm = [p[0] - a[0], p[1] - a[1]];
                let n = arm[0].hypot(arm[1]);
                let t = turned(tilt, [arm[0] / n, arm[1] / n]);
                // The foot of the pivot on the face: `offset` to the left of the face's direction.
                let foot = [a[0] - offset * t[1], a[1] + offset * t[0]];
                [foot[0] + along * t[0], foot[1] + along * t[1]]
            }
        }
    }
}
