//! The disc cam of a flat-faced follower: the envelope of the face's positions seen from the
//! cam (see the [`cam`](super) module's documentation for the definitions and formulas).

use super::FollowerSample;
use super::plane::{apply, cross, dot, largest, length_unit, norm, per_unit, quarter, rotate, scale, sub, unit};
use crate::error::Error;
use crate::number::{Count, Number};
use std::f64::consts::FRAC_PI_2;

/// Where a flat-faced follower's face is, and how the follower moves: along a guide or about a
/// pivot. Angles in radians, counter-clockwise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FlatFace {
    /// A translating follower: the face passes through the follower's point, square to the guide
    /// (the samples' `direction`, the same at every sample) turned by `tilt` (less than a quarter
    /// turn either way; 0 for the usual face square to the guide). The face's direction (in which
    /// the offsets count) is the guide's turned a quarter clockwise, then by `tilt`: for the guide
    /// (0, 1) and no tilt, +x.
    Translating {
        /// The face's angle from square to the guide.
        tilt: f64,
    },
    /// A rocking follower pivoted at `pivot`, the samples' point on its arm: the face parallel to
    /// the arm (its direction from the pivot to the point) turned by `tilt`, at the signed distance `offset`
    /// from the pivot (positive on the left of the face's direction; 0 for a face through the
    /// pivot). The samples' `direction` is not used: the point moves square to the arm.
    Rocking {
        /// The rocker's pivot, in the fixed frame.
        pivot: [f64; 2],
        /// The face's distance from the pivot, signed.
        offset: f64,
        /// The face's angle from the arm.
        tilt: f64,
    },
}

/// A flat-faced follower's disc cam over the samples ([`flat_face_profile`]); see the
/// [`cam`](super) module's documentation for the definitions.
#[derive(Clone, Debug, PartialEq)]
pub struct FlatFaceProfile {
    /// The points of contact, in the cam's frame (its origin at the pivot, its axes those of the
    /// fixed frame at cam angle 0): the cam's profile where it is convex.
    pub profile: Vec<[f64; 2]>,
    /// The profile's radius of curvature at each sample, `h + d2h/dpsi2`: positive where it is
    /// convex; zero or negative where the envelope of the face has a cusp, so that no cam moves
    /// the flat face as the samples say (see [`FlatFaceProfile::not_convex`]).
    pub radius: Vec<f64>,
    /// The contact's place along the face (in the face's direction), from the follower's point
    /// for a translating follower and from the foot of the pivot on the face for a rocking one
    /// (for a radial translating follower, `s'` under a cam turning counter-clockwise and `-s'`
    /// under one turning clockwise): the face must reach over all of them.
    pub offset: Vec<f64>,
    /// The pressure angle at each sample (radians, from 0 to pi/2): between the face's normal
    /// and the direction the follower's material point at the contact can move in.
    pub pressure_angle: Vec<f64>,
}

impl FlatFaceProfile {
    /// The smallest and the largest offset of the contact along the face, over the samples
    /// ([`flat_face_extremes`](super::flat_face_extremes) locates them between the samples).
    pub fn offset_range(&self) -> (f64, f64) {
        self.offset.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)))
    }

    /// The least width of the face, over the samples: the largest offset less the smallest (the
    /// extremes between the samples are missed: [`flat_face_extremes`](super::flat_face_extremes)
    /// locates them).
    pub fn face_width(&self) -> f64 {
        let (lo, hi) = self.offset_range();
        hi - lo
    }

    /// The smallest radius of curvature of the profile, with its sample. Of the samples only
    /// ([`flat_face_extremes`](super::flat_face_extremes) locates it between them).
    pub fn min_radius(&self) -> (usize, f64) {
        self.radius
            .iter()
            .copied()
            .enumerate()
            .fold((0, f64::INFINITY), |best, (k, r)| if r < best.1 { (k, r) } else { best })
    }

    /// The samples where the profile is not convex (its radius of curvature zero or negative):
    /// the face's envelope turns back on itself there, and the law cannot be made with a flat face.
    /// Of the samples only: a cusp between them is missed
    /// ([`flat_face_extremes`](super::flat_face_extremes) looks between them).
    pub fn not_convex(&self) -> Vec<usize> {
        (0..self.radius.len()).filter(|&k| self.radius[k] <= 0.0).collect()
    }

    /// `Ok` where the profile is convex at every sample; otherwise `InvalidArgument` naming the
    /// samples where it is not.
    pub fn check_convex(&self) -> Result<(), Error> {
        let bad = self.not_convex();
        match (bad.first(), bad.last()) {
            (Some(&a), Some(&b)) => Err(Error::InvalidArgument(format!(
                "flat_face_profile: the profile is not convex at {} (from sample {a} to sample {b}; radius of \
                 curvature {} at sample {a}): a flat face cannot follow the law there",
                Count(bad.len(), "sample"),
                Number(self.radius[a])
            ))),
            _ => Ok(()),
        }
    }

    /// The largest pressure angle, with its sample. Of the samples only
    /// ([`flat_face_extremes`](super::flat_face_extremes) locates it between them).
    pub fn max_pressure_angle(&self) -> (usize, f64) {
        largest(&self.pressure_angle)
    }
}

/// The face at one sample, in the fixed frame, in units of the sample's length unit: its
/// direction `t` (unit), the angle's first two derivatives, and a point of it (relative to the
/// cam's pivot) with its first two derivatives.
struct Face {
    t: [f64; 2],
    turn: [f64; 2],
    at: [[f64; 2]; 3],
}

/// The profile of the disc cam turning about `pivot` that moves the flat-faced follower `face`
/// as `samples` say: the envelope of the face's positions in the cam's frame. See the
/// [`cam`](super) module's documentation.
///
/// The cam lies on its pivot's side of the face at every sample. Errors (`InvalidArgument`,
/// naming the sample): no samples; a value that is not finite; a translating follower's tilt of
/// a quarter turn or more, its guide of zero length or not the same at every sample; a rocking
/// follower's point at its pivot; a face through the cam's pivot or beyond it; a sample where
/// the face does not turn relative to the cam, or turns the other way than at the first sample.
/// A profile that is not convex is returned, its radius of curvature negative there (see
/// [`FlatFaceProfile::check_convex`]).
///
/// ```
/// use kinloop_runtime::analysis::cam::{FlatFace, FollowerSample, flat_face_profile};
/// // A radial translating follower on the Y axis, its face square to the guide, lifted by
/// // s = 2 (1 - cos phi) above a base circle of radius 10: at phi = pi / 2 the profile's
/// // radius of curvature is 10 + s + s'' = 12 and the contact is s' = 2 along the face.
/// let at = |phi: f64| {
///     let (s, ds, d2s) = (2.0 * (1.0 - phi.cos()), 2.0 * phi.sin(), 2.0 * phi.cos());
///     FollowerSample { cam: [phi, 1.0, 0.0], point: [[0.0, 10.0 + s], [0.0, ds], [0.0, d2s]], direction: [0.0, 1.0] }
/// };
/// let samples = [at(0.0), at(std::f64::consts::FRAC_PI_2)];
/// let cam = flat_face_profile(&samples, [0.0, 0.0], FlatFace::Translating { tilt: 0.0 })?;
/// assert!((cam.radius[1] - 12.0).abs() < 1e-14 && (cam.offset[1] - 2.0).abs() < 1e-15);
/// assert_eq!(cam.pressure_angle, [0.0, 0.0]);
/// // At phi = 0 the face touches the base circle at the top, the radius 10 + 0 + 2 there too;
/// // the face reaches from the axis (s' = 0) to s' = 2.
/// assert_eq!(cam.profile[0], [0.0, 10.0]);
/// assert!((cam.radius[0] - 12.0).abs() < 1e-14 && (cam.face_width() - 2.0).abs() < 1e-15);
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
pub fn flat_face_profile(
    samples: &[FollowerSample],
    pivot: [f64; 2],
    face: FlatFace,
) -> Result<FlatFaceProfile, Error> {
    let bad = |message: String| Err(Error::InvalidArgument(format!("flat_face_profile: {message}")));
    if samples.is_empty() {
        return bad("no samples".into());
    }
    if !pivot.iter().all(|v| v.is_finite()) {
        return bad(format!("the pivot {pivot:?} is not finite"));
    }
    match face {
        FlatFace::Translating { tilt } if tilt.is_nan() || tilt.abs() >= FRAC_PI_2 => {
            return bad(format!(
                "the face's tilt {} must be finite and less than a quarter turn either way (the face square to \
                 the guide at 0)",
                Number(tilt)
            ));
        }
        FlatFace::Rocking { pivot: a, offset, tilt } if ![a[0], a[1], offset, tilt].iter().all(|v| v.is_finite()) => {
            return bad(format!(
                "the rocker's pivot {a:?}, the face's offset {} and tilt {} must be finite",
                Number(offset),
                Number(tilt)
            ));
        }
        _ => {}
    }
    let n = samples.len();
    let mut out = FlatFaceProfile {
        profile: Vec::with_capacity(n),
        radius: Vec::with_capacity(n),
        offset: Vec::with_capacity(n),
        pressure_angle: Vec::with_capacity(n),
    };
    // The guide of a translating follower (sample 0's), the side of the face the cam is on and
    // the sense in which the face turns relative to the cam, all fixed at the first sample.
    let (mut guide, mut side, mut winding) = (None, 0.0, 0.0);
    for (k, s) in samples.iter().enumerate() {
        let values = s.cam.iter().chain(s.point.iter().flatten()).chain(&s.direction);
        if !values.into_iter().all(|v| v.is_finite()) {
            return bad(format!("sample {k} has a value that is not finite: {s:?}"));
        }
        let [theta, dtheta, d2theta] = s.cam;
        let [p, dp, d2p] = s.point;
        // Lengths in units of a power of two near the sample's (exact): the formulas are linear
        // in the lengths, and the unit keeps their products with the angles' rates normal.
        let (unit, face_at) = match face {
            FlatFace::Translating { tilt } => {
                let e = unit(s.direction).ok_or_else(|| {
                    Error::InvalidArgument(format!(
                        "flat_face_profile: sample {k}'s direction (the guide) {:?} has no length",
                        s.direction
                    ))
                })?;
                let g = *guide.get_or_insert(e);
                // A fixed guide: the face does not turn. Directions equal to rounding (1e-12 rad,
                // a thousand times a unit vector's) pass, whatever computed them.
                if cross(g, e).abs() > 1e-12 || dot(g, e) < 0.0 {
                    return bad(format!(
                        "sample {k}'s guide {:?} is not sample 0's: a translating follower's guide is fixed",
                        s.direction
                    ));
                }
                let q = sub(p, pivot);
                let unit = length_unit([q, dp, d2p].iter().flatten());
                // The guide turned a quarter clockwise: for the guide (0, 1), +x.
                let t = apply(rotate(tilt), [g[1], -g[0]]);
                (unit, Face { t, turn: [0.0, 0.0], at: [per_unit(q, unit), per_unit(dp, unit), per_unit(d2p, unit)] })
            }
            FlatFace::Rocking { pivot: a, offset, tilt } => {
                let (arm, base) = (sub(p, a), sub(a, pivot));
                if arm == [0.0, 0.0] {
                    return bad(format!("at sample {k} the follower's point {p:?} is at the rocker's pivot"));
                }
                let unit = length_unit([arm, base, dp, d2p, [offset, 0.0]].iter().flatten());
                let (arm, dp, d2p) = (per_unit(arm, unit), per_unit(dp, unit), per_unit(d2p, unit));
                let l2 = dot(arm, arm);
                // The arm's square underflows in the unit of the largest length: an offset (or a
                // pivot) some 1e150 times the arm's length, beyond what `f64` relates to it.
                if l2 == 0.0 {
                    return bad(format!(
                        "at sample {k} the arm from the rocker's pivot to the follower's point {p:?} is too short \
                         beside the face's offset {} and the pivots' distance (their ratio is beyond what f64 \
                         computes with)",
                        Number(offset)
                    ));
                }
                // The arm's angle gamma = atan2(arm): gamma' = (arm x arm') / |arm|^2, and
                // gamma'' = (arm x arm'') / |arm|^2 - 2 (arm . arm') (arm x arm') / |arm|^4.
                let d1 = cross(arm, dp) / l2;
                let d2 = cross(arm, d2p) / l2 - 2.0 * dot(arm, dp) / l2 * d1;
                let t = apply(rotate(tilt), scale(1.0 / norm(arm), arm));
                // The face's foot of the pivot, a + d J t, and its derivatives as t turns:
                // t' = gamma' J t, (J t)' = -gamma' t.
                let d = offset / unit;
                let jt = quarter(t);
                let base = per_unit(base, unit);
                let foot = [base[0] + d * jt[0], base[1] + d * jt[1]];
                let dfoot = scale(-d * d1, t);
                let d2foot = [-d * (d2 * t[0] + d1 * d1 * jt[0]), -d * (d2 * t[1] + d1 * d1 * jt[1])];
                (unit, Face { t, turn: [d1, d2], at: [foot, dfoot, d2foot] })
            }
        };
        let Face { t, turn: [db, d2b], at: [q, dq, d2q] } = face_at;
        // The face's normal towards the follower (away from the cam, which lies on its pivot's
        // side), and its distance h from the cam's pivot: the support function of the profile.
        let across = dot(quarter(t), q);
        if side == 0.0 {
            side = across.signum();
        }
        let h = side * across;
        if h.is_nan() || h <= 0.0 {
            return bad(format!(
                "at sample {k} the face passes through the cam's pivot or beyond it ({} past it): the cam must lie \
                 on its pivot's side of the face at every sample",
                Number(-h * unit)
            ));
        }
        let nrm = scale(side, quarter(t));
        let jn = quarter(nrm);
        // h = n . q, with n' = beta' J n and n'' = beta'' J n - beta'^2 n.
        let h1 = db * dot(jn, q) + dot(nrm, dq);
        let h2 = d2b * dot(jn, q) - db * db * h + 2.0 * db * dot(jn, dq) + dot(nrm, d2q);
        // The normal's angle in the cam's frame, psi = beta - theta (+ a constant).
        let (w, w1) = (db - dtheta, d2b - d2theta);
        if w == 0.0 {
            return bad(format!(
                "at sample {k} the face does not turn relative to the cam (its angle's rate {} is the cam's): it \
                 touches no profile there",
                Number(db)
            ));
        }
        if winding == 0.0 {
            winding = w.signum();
        } else if w.signum() != winding {
            return bad(format!(
                "at sample {k} the face turns relative to the cam the other way than at sample 0: the profile is \
                 not traced once around"
            ));
        }
        let hp = h1 / w;
        let hpp = (h2 - hp * w1) / (w * w);
        // The contact, h n + dh/dpsi J n, in the fixed frame relative to the cam's pivot.
        let c = [h * nrm[0] + hp * jn[0], h * nrm[1] + hp * jn[1]];
        let offset = dot(sub(c, q), t);
        // The direction the follower's material point at the contact can move in.
        let moves = match face {
            FlatFace::Translating { .. } => guide.unwrap_or(t),
            FlatFace::Rocking { pivot: a, .. } => quarter(sub(c, per_unit(sub(a, pivot), unit))),
        };
        let (sin, cos) = (cross(nrm, moves).abs(), dot(nrm, moves).abs());
        // A contact at the rocker's pivot pushes through it: no leverage at all.
        let pressure = if sin == 0.0 && cos == 0.0 { FRAC_PI_2 } else { sin.atan2(cos) };
        let radius = (h + hpp) * unit;
        let contact = apply(rotate(-theta), scale(unit, c));
        if !(radius.is_finite() && contact.iter().all(|v| v.is_finite())) {
            return bad(format!(
                "at sample {k} the face barely turns relative to the cam (rate {}): its contact is out of reach",
                Number(w)
            ));
        }
        out.profile.push(contact);
        out.radius.push(radius);
        out.offset.push(offset * unit);
        out.pressure_angle.push(pressure);
    }
    Ok(out)
}
