//! The profile of a disc cam, found by kinematic inversion from the motion its follower needs.
//!
//! A mechanism declared with a prescribed follower motion (a displacement law of the cam angle,
//! as in a rise-dwell-return-dwell drive) says where the follower's roller centre P must be at
//! every cam angle; the cam that makes it so is whatever curve the roller rolls on. Seen from
//! the cam (turning by `theta` about its pivot O), P traces the **pitch curve**
//! `r = R(-theta) (P - O)`; the cam's working **profile** is the inner offset of the pitch curve
//! by the roller's radius (the pitch curve itself for a knife edge). Everything a cam designer
//! checks follows from `r` and its first two derivatives, which the mechanism's analogs give
//! exactly (`u` is the sweep's input, `q = P - O`, `J` the quarter turn `(x, y) -> (-y, x)`):
//!
//! * `r' = R(-theta) (q' - theta' J q)`,
//!   `r'' = R(-theta) (q'' - theta'' J q - 2 theta' J q' - theta'^2 q)`;
//! * the pitch curve's **radius of curvature** `|r'|^3 / (r' x r'')`, here signed so that it is
//!   positive where the curve bulges away from the cam's centre (convex) and negative where it
//!   is hollow (concave); the profile's is that less the roller's radius. Where the pitch curve
//!   is convex with a radius below the roller's, the offset folds over itself: the profile is
//!   **undercut** and the follower cannot follow the law there;
//! * the **pressure angle** between the common normal at the contact (the pitch curve's normal)
//!   and the direction the follower's point can move in (its guide, or square to its rocker's
//!   arm): the larger, the more of the contact force pushes the follower sideways instead of
//!   along its motion. Designers keep it within about 30° for a translating follower and 45° for
//!   a rocking one.
//!
//! The pitch curve must wind around the cam's centre (`r x r'` of one sign at every sample):
//! that is what makes the inner side, and so the profile, well defined.
//!
//! # Flat-faced followers
//!
//! A flat-faced follower carries a straight face (a line) instead of a roller
//! ([`flat_face_profile`], the face given by [`FlatFace`]): square to the guide of a translating
//! follower through its point (or tilted), or along the arm of a rocking one, through its pivot
//! or at a distance from it. The cam is the **envelope** of the face's positions seen from the
//! cam. With the face's direction `t` at the angle `beta` in the fixed frame, its normal `n`
//! (square to `t`, pointing away from the cam, which lies on its pivot's side), `q` a point of
//! the face relative to the pivot O and `h = n . q` the face's distance from O (invariant under
//! the inversion, a rotation about O), the face in the cam's frame is the line `x . n_c = h` whose
//! normal `n_c` lies at the angle `psi = beta - theta` (plus a constant): `h` as a function of
//! `psi` is the profile's **support function**, and
//!
//! * `n' = beta' J n`, `n'' = beta'' J n - beta'^2 n`, so `h' = n' . q + n . q'` and
//!   `h'' = n'' . q + 2 n' . q' + n . q''`; `psi' = beta' - theta'`, `psi'' = beta'' - theta''`,
//!   `dh/dpsi = h' / psi'`, `d2h/dpsi2 = (h'' - (dh/dpsi) psi'') / psi'^2`;
//! * the **contact** (the envelope's point) is `h n + (dh/dpsi) J n` from O, turned into the cam's
//!   frame by `R(-theta)`; its **offset** along the face is `(contact - q) . t`;
//! * the profile's **radius of curvature** is `h + d2h/dpsi2`: for a radial translating follower
//!   lifted by `s(theta)` above the base circle `R_b`, `R_b + s + s''`, and the contact lies
//!   `s'` from the follower's axis (towards where the cam's surface comes from; so the face is
//!   at least `max s' - min s'` wide). Where the radius is zero or negative the envelope has a cusp (a swallowtail): no
//!   convex cam moves the face as the law says, and a flat face cannot be used (a larger base
//!   circle, or a gentler law);
//! * the **pressure angle**, between `n` and the direction the follower's material point at the
//!   contact can move in: the face's tilt from square to the guide for a translating follower
//!   (0 for a face square to it), constant; for a rocking follower the contact moves square to
//!   the line from the pivot A to it, so that `tan(pressure angle) = |d| / |l|`, `d` the face's
//!   distance from A and `l` the contact's place along the face from A's foot: 0 throughout for
//!   a face through the pivot, growing as the contact nears the foot.
//!
//! The face must turn relative to the cam the same way at every sample (`psi'` of one sign):
//! the profile is then traced once around.
//!
//! Lengths come out in the mechanism's unit and angles in radians: the same profile, scaled, at
//! any unit of length.
//!
//! # Between the samples
//!
//! [`cam_profile`] and [`flat_face_profile`] see the samples alone, and so do the checks of
//! what they return ([`CamProfile::max_pressure_angle`], [`CamProfile::min_convex_radius`],
//! [`CamProfile::undercut`], their flat face's): a feature of the law narrower than the sample
//! spacing (a rise over two degrees, sampled every degree) has its sharpest point and its
//! steepest flank between samples, or no sample in it at all, and the samples' checks call a
//! cam good that is not. [`cam_extremes`] and [`flat_face_extremes`] locate the checks between
//! the samples, evaluating the follower's motion there with a function the caller gives (the
//! mechanism's state at any input on the sweep's branch, as
//! [`SampledOf::at`](crate::analysis::SampledOf::at) gives it):
//!
//! 1. **Resolved.** Each interval between neighbouring points is halved until the pitch curve's
//!    jets at its ends (the follower's point seen from the cam, `r`, with its analogs `r'`,
//!    `r''`) agree as those of a curve varying smoothly over the interval `h` do: the corrected
//!    trapezoid rules `r_b - r_a = h (r'_a + r'_b) / 2 - h^2 (r''_b - r''_a) / 12` and
//!    `r'_b - r'_a = h (r''_a + r''_b) / 2` hold to a thousandth of the interval's change
//!    (`h |r'|`, and `h (|r''| + |r'|)`). A smooth law sampled every degree agrees to some
//!    1e-5; a rise between two samples of a dwell (both ends at rest, the point moved) fails by
//!    the whole lift. An interval with a corner of the motion never agrees and is halved to a
//!    billionth of its width. A feature that starts and ends between two samples, leaving the
//!    motion's jets there as they would be without it, is not seen: sample finely enough that
//!    one lands in it.
//! 2. **Located.** Each check's largest values over the resolved points are refined by Brent's
//!    search ([`maximize`](crate::analysis::extremes::maximize)) between their neighbours, as
//!    [`SampledOf::peak`](crate::analysis::SampledOf::peak) refines a peak: the location to
//!    `sqrt(eps)` of the bracket, the value to rounding. The pitch curve's radius of curvature
//!    passes through infinity where the curve straightens: its smallest convex value is located
//!    as the largest curvature, its reciprocal.

mod flat_face;
mod located;
mod plane;

pub use flat_face::{FlatFace, FlatFaceProfile, flat_face_profile};
pub use located::{CamExtremes, FlatFaceExtremes, Located, cam_extremes, flat_face_extremes};

use crate::error::Error;
use crate::number::Number;
use plane::{apply, cross, dot, largest, length_unit, norm, per_unit, quarter, rotate, scale, sub, unit};

/// One sample of the follower's motion: the cam's angle and the follower point's position, each
/// with its first and second derivative with respect to the sweep's input (a mechanism's
/// positions and analogs at one input), and the direction the point can move in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FollowerSample {
    /// The cam's angle (radians, counter-clockwise) and its first and second derivatives: `[phi,
    /// 1, 0]` for a cam on the input shaft, `[-phi, -1, 0]` for one turning the other way.
    pub cam: [f64; 3],
    /// The follower's point (the roller's centre, or the knife edge) in the fixed frame: its
    /// position, velocity analog and acceleration analog.
    pub point: [[f64; 2]; 3],
    /// The direction the point can move in, in the fixed frame (any length but zero): the guide
    /// of a translating follower, square to the arm of a rocking one.
    pub direction: [f64; 2],
}

/// A disc cam's profile over the samples ([`cam_profile`]); see the
/// [module documentation](self) for the definitions.
#[derive(Clone, Debug, PartialEq)]
pub struct CamProfile {
    /// The pitch curve (the follower point's path relative to the cam), in the cam's frame: its
    /// origin at the pivot, its axes those of the fixed frame at cam angle 0.
    pub pitch: Vec<[f64; 2]>,
    /// The working profile (the points of contact), in the cam's frame: the pitch curve offset
    /// towards the cam's centre by the roller's radius.
    pub profile: Vec<[f64; 2]>,
    /// The pitch curve's radius of curvature at each sample: positive where convex, negative
    /// where concave, infinite where straight.
    pub pitch_radius: Vec<f64>,
    /// The pressure angle at each sample (radians, from 0 to pi/2).
    pub pressure_angle: Vec<f64>,
    /// The roller's radius the profile was made for (0: a knife edge).
    pub roller: f64,
}

impl CamProfile {
    /// The profile's radius of curvature at sample `k`: the pitch curve's less the roller's.
    /// Positive where the profile is convex; negative where it is hollow (the pitch curve
    /// concave) or undercut (convex, but sharper than the roller: see [`CamProfile::undercut`]).
    pub fn profile_radius(&self, k: usize) -> f64 {
        self.pitch_radius[k] - self.roller
    }

    /// The samples where the profile is undercut: the pitch curve convex with a radius of
    /// curvature not above the roller's, so that the offset folds over itself there. Of the
    /// samples only: an undercut between them is missed ([`cam_extremes`] looks between them).
    pub fn undercut(&self) -> Vec<usize> {
        (0..self.pitch_radius.len())
            .filter(|&k| self.pitch_radius[k] > 0.0 && self.pitch_radius[k] <= self.roller)
            .collect()
    }

    /// The smallest radius of curvature of the pitch curve where it is convex, with its sample
    /// (`None` where it is nowhere convex). Less the roller's radius, the sharpest point of the
    /// profile. Of the samples only ([`cam_extremes`] locates it between them).
    pub fn min_convex_radius(&self) -> Option<(usize, f64)> {
        self.pitch_radius.iter().copied().enumerate().filter(|&(_, r)| r > 0.0).min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// The largest pressure angle, with its sample. Of the samples only ([`cam_extremes`]
    /// locates it between them).
    pub fn max_pressure_angle(&self) -> (usize, f64) {
        largest(&self.pressure_angle)
    }
}

/// The profile of the disc cam turning about `pivot` that moves the follower as `samples` say,
/// for a roller of radius `roller` (0 for a knife edge). See the [module documentation](self).
///
/// Errors (`InvalidArgument`, naming the sample): no samples; a value that is not finite; a
/// `roller` that is negative or not finite; a direction of zero length; a sample where the
/// follower's point does not move relative to the cam (`r' = 0`), or where it turns around the
/// cam's centre the other way than at the first sample (the pitch curve does not wind around
/// the centre, so the profile's side is undefined).
///
/// ```
/// use kinloop_runtime::analysis::cam::{FollowerSample, cam_profile};
/// // A radial translating follower on the Y axis, lifted by s = 2 (1 - cos phi) above a base
/// // circle of radius 10: at phi = pi / 2, tan(pressure angle) = s' / (10 + s) = 2 / 12.
/// let at = |phi: f64| {
///     let (s, ds, d2s) = (2.0 * (1.0 - phi.cos()), 2.0 * phi.sin(), 2.0 * phi.cos());
///     FollowerSample { cam: [phi, 1.0, 0.0], point: [[0.0, 10.0 + s], [0.0, ds], [0.0, d2s]], direction: [0.0, 1.0] }
/// };
/// let cam = cam_profile(&[at(0.0), at(std::f64::consts::FRAC_PI_2)], [0.0, 0.0], 1.0)?;
/// assert!((cam.pressure_angle[1] - (2.0f64 / 12.0).atan()).abs() < 1e-15);
/// // At phi = 0 the pitch curve is the base circle's neighbour: the point (0, 10), the contact
/// // a roller's radius nearer the centre.
/// assert_eq!(cam.pitch[0], [0.0, 10.0]);
/// assert!((cam.profile[0][1] - 9.0).abs() < 1e-15);
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
pub fn cam_profile(samples: &[FollowerSample], pivot: [f64; 2], roller: f64) -> Result<CamProfile, Error> {
    let bad = |message: String| Err(Error::InvalidArgument(format!("cam_profile: {message}")));
    if samples.is_empty() {
        return bad("no samples".into());
    }
    if !(roller >= 0.0 && roller.is_finite()) {
        return bad(format!("the roller's radius {} must be finite and not negative", Number(roller)));
    }
    if !pivot.iter().all(|v| v.is_finite()) {
        return bad(format!("the pivot {pivot:?} is not finite"));
    }
    let n = samples.len();
    let mut out = CamProfile {
        pitch: Vec::with_capacity(n),
        profile: Vec::with_capacity(n),
        pitch_radius: Vec::with_capacity(n),
        pressure_angle: Vec::with_capacity(n),
        roller,
    };
    let mut winding = 0.0;
    for (k, s) in samples.iter().enumerate() {
        let values = s.cam.iter().chain(s.point.iter().flatten()).chain(&s.direction);
        if !values.into_iter().all(|v| v.is_finite()) {
            return bad(format!("sample {k} has a value that is not finite: {s:?}"));
        }
        let e = unit(s.direction).ok_or_else(|| {
            Error::InvalidArgument(format!("cam_profile: sample {k}'s direction {:?} has no length", s.direction))
        })?;
        let [theta, dtheta, d2theta] = s.cam;
        let [p, dp, d2p] = s.point;
        let q = [p[0] - pivot[0], p[1] - pivot[1]];
        // The derivatives in units of a power of two near the sample's lengths (exact), so that
        // the cube of the speed and the cross products neither overflow nor underflow at any
        // scale: the radius is scaled back, the angles and the normal are free of it.
        let unit = length_unit([q, dp, d2p].iter().flatten());
        let (qs, dps, d2ps) = (per_unit(q, unit), per_unit(dp, unit), per_unit(d2p, unit));
        // In the fixed frame, then turned into the cam's by R(-theta) (see the module docs).
        let dr = sub(dps, scale(dtheta, quarter(qs)));
        let d2r = [
            d2ps[0] - d2theta * quarter(qs)[0] - 2.0 * dtheta * quarter(dps)[0] - dtheta * dtheta * qs[0],
            d2ps[1] - d2theta * quarter(qs)[1] - 2.0 * dtheta * quarter(dps)[1] - dtheta * dtheta * qs[1],
        ];
        // The turn of the point around the cam's centre, r x r' (the same in either frame).
        let turn = cross(qs, dr);
        let speed = norm(dr);
        if turn == 0.0 || speed == 0.0 {
            // The velocity as every other number of a message is written (`(0, 0)`, not Rust's
            // `[0.0, 0.0]`).
            let [vx, vy] = scale(unit, dr);
            return bad(format!(
                "at sample {k} the follower's point does not move around the cam's centre (r' = ({}, {}) relative \
                 to the cam): the pitch curve must wind around it",
                Number(vx),
                Number(vy)
            ));
        }
        if winding == 0.0 {
            winding = turn.signum();
        } else if turn.signum() != winding {
            return bad(format!(
                "at sample {k} the follower's point turns around the cam's centre the other way than at sample 0: \
                 the pitch curve does not wind around the centre"
            ));
        }
        // The normal towards the inside (the cam's centre side): J r' points to the left of the
        // motion, which is the inside where the curve winds counter-clockwise.
        let inward = scale(winding / speed, quarter(dr));
        let radius = winding * speed * speed * speed / cross(dr, d2r) * unit;
        let back = rotate(-theta);
        out.pitch.push(apply(back, q));
        out.profile.push(apply(back, [q[0] + roller * inward[0], q[1] + roller * inward[1]]));
        out.pitch_radius.push(radius);
        // The contact normal is the same line in the fixed frame, `inward` being computed there.
        // atan2 of the sine and cosine: accurate near 0 and pi/2 alike, where acos is not.
        let (sin, cos) = (cross(inward, e).abs(), dot(inward, e).abs());
        out.pressure_angle.push(sin.atan2(cos));
    }
    Ok(out)
}
