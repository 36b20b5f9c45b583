//! A flat-faced follower's disc cam (`analysis::cam::flat_face_profile`, the envelope of the
//! face) against what is known without it: the radial translating follower's closed forms of the
//! 3-4-5 dwell law by hand; an eccentric circular disc, which the envelope must give back as
//! that circle under a translating face (by hand, tilted or not) and under a rocking one (a
//! declared mechanism whose loop keeps the face tangent to the disc and says where along it the
//! contact is); and a rocking face moved by a law, its envelope found by brute force as the
//! meeting point of the face's lines at neighbouring cam angles.
//!
//! Sign conventions (derived here, independently of the library). The cam turns by `theta`
//! about the origin; a point X of the fixed frame is `R(-theta) X` in the cam's frame. A radial
//! translating follower on the guide `g`, its face square to `g` at the distance `R_b + s` from
//! the pivot: in the cam's frame the face's outward normal is `n = R(-theta) g` at the angle
//! `psi`, and the face is the line `x . n = h(psi)` with `h = R_b + s`. The envelope of such
//! lines is `x = h n + (dh/dpsi) J n` (J the quarter turn counter-clockwise), its radius of
//! curvature `h + d2h/dpsi2`. With the guide on +x and the cam turning clockwise
//! (`theta = -phi`), `psi = phi`: the contact is `x = (R_b + s) cos phi - s' sin phi`,
//! `y = (R_b + s) sin phi + s' cos phi` (the textbook's form), and in the fixed frame it lies at
//! `(R_b + s, s')`: `s'` towards +y from the axis, `-s'` along the face's direction (the guide
//! turned a quarter clockwise, -y). With the guide on +y and the cam counter-clockwise
//! (`theta = phi`, the fixtures'), `psi = pi/2 - phi`, `dh/dpsi = -s'`: the contact is
//! `((R_b + s) sin phi + s' cos phi, (R_b + s) cos phi - s' sin phi)`, in the fixed frame
//! `(s', R_b + s)`, `s'` along the face's direction +x. Either way the radius is `R_b + s + s''`.

use kinloop::Error;
use kinloop::analysis::cam::{FlatFace, FlatFaceProfile, FollowerSample, flat_face_profile};
use kinloop_fixtures::cam_linkage::DwellCamRocker;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

kinloop::mechanism! {
    /// An eccentric disc (radius `r`, its centre at `e @ phi` on the shaft at the origin) under
    /// a flat-faced rocking follower pivoted at (`a_x`, `a_y`): the arm at the angle `gamma`, its
    /// face parallel to it and `d` below it (on its right), the disc touching the face from
    /// below at the contact, `w` along the face from the pivot's foot. The contact is the disc's
    /// top point along the face's normal, `C + r @ (gamma + pi/2)`, and on the face: loop
    /// `contact`. `arm` is a point of the arm `l` from the pivot.
    pub struct DiscFlatRocker {
        params e = 10.0, r = 40.0, a_x = -60.0, a_y = 60.0, d = 5.0, l = 100.0;
        input phi;
        unknowns gamma = -0.25, w = 0.62 * l;
        loop contact: e @ phi + r @ (gamma + pi / 2) == (a_x, a_y) + d @ (gamma - pi / 2) + w @ gamma;
        /// A point of the arm.
        point arm = (a_x, a_y) + l @ gamma;
    }
}

/// The translating follower's samples on the guide `guide` (a unit vector) for the lift `law`
/// (`[s, s', s'']` of the cam angle `phi`) above the base circle `base`, the cam turning by
/// `turn * phi`, every `360 / (n - 1)` degrees.
fn translating(n: usize, base: f64, guide: [f64; 2], turn: f64, law: impl Fn(f64) -> [f64; 3]) -> Vec<FollowerSample> {
    (0..n)
        .map(|k| {
            let phi = TAU * k as f64 / (n - 1) as f64;
            let [s, ds, d2s] = law(phi);
            let along = |v: f64| [v * guide[0], v * guide[1]];
            FollowerSample {
                cam: [turn * phi, turn, 0.0],
                point: [along(base + s), along(ds), along(d2s)],
                direction: guide,
            }
        })
        .collect()
}

#[test]
fn a_radial_translating_face_matches_the_closed_forms_of_the_dwell_law() -> Result<(), Error> {
    let m = DwellCamRocker::default();
    let base = m.y0;
    let face = FlatFace::Translating { tilt: 0.0 };
    // The textbook's arrangement: the guide on +x, the cam turning clockwise.
    let samples = translating(721, base, [1.0, 0.0], -1.0, |phi| m.law_by_hand(phi));
    let cam = flat_face_profile(&samples, [0.0, 0.0], face)?;
    // The fixtures': the guide on +y, the cam turning counter-clockwise, from the mechanism's
    // own solution (its follower point's positions and analogs).
    let start = m.solve(0.0)?;
    let mut declared = Vec::new();
    for s in m.sweep(0.0, TAU, 721, &start.q)? {
        let s = s?;
        let f = |x: f64, y: f64| [x, y];
        declared.push(FollowerSample {
            cam: [s.input.phi, 1.0, 0.0],
            point: [
                f(s.out.follower.x, s.out.follower.y),
                f(s.dout.follower.x, s.dout.follower.y),
                f(s.d2out.follower.x, s.d2out.follower.y),
            ],
            direction: [0.0, 1.0],
        });
    }
    let ccw = flat_face_profile(&declared, [0.0, 0.0], face)?;
    let (mut lo, mut hi, mut sharpest) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
    for k in 0..samples.len() {
        let phi = TAU * k as f64 / 720.0;
        let [s, ds, d2s] = m.law_by_hand(phi);
        let r = base + s;
        let (sin, cos) = phi.sin_cos();
        let rho = r + d2s;
        // Lengths to 1e-13 of the base circle: the law here and the declaration's are the same
        // polynomial evaluated in other orders (a few ulps of the lift and its analogs).
        let close = |a: f64, b: f64, what: &str| assert!((a - b).abs() <= 1e-13 * base, "{k}: {what} {a} vs {b}");
        close(cam.profile[k][0], r * cos - ds * sin, "cw x");
        close(cam.profile[k][1], r * sin + ds * cos, "cw y");
        close(ccw.profile[k][0], r * sin + ds * cos, "ccw x");
        close(ccw.profile[k][1], r * cos - ds * sin, "ccw y");
        close(cam.offset[k], -ds, "cw offset");
        close(ccw.offset[k], ds, "ccw offset");
        for c in [&cam, &ccw] {
            close(c.radius[k], rho, "radius");
            assert_eq!(c.pressure_angle[k], 0.0, "a face square to its guide");
        }
        lo = lo.min(ds);
        hi = hi.max(ds);
        sharpest = sharpest.min(rho);
    }
    for c in [&cam, &ccw] {
        assert!((c.face_width() - (hi - lo)).abs() <= 1e-13 * base);
        assert!((c.min_radius().1 - sharpest).abs() <= 1e-13 * base);
        assert!(c.not_convex().is_empty());
        c.check_convex()?;
    }
    // On a base circle of 10 the return's deceleration (s'' down to -5.77 h / beta^2 = -38 mm
    // over its 100 degrees, where s = 18.7) folds the face's envelope: R_b + s + s'' < 0 there.
    let small = translating(721, 10.0, [1.0, 0.0], -1.0, |phi| m.law_by_hand(phi));
    let folded = flat_face_profile(&small, [0.0, 0.0], face)?;
    let by_hand: Vec<usize> = (0..721)
        .filter(|&k| {
            let [s, _, d2s] = m.law_by_hand(TAU * k as f64 / 720.0);
            10.0 + s + d2s <= 0.0
        })
        .collect();
    assert!(!by_hand.is_empty());
    assert_eq!(folded.not_convex(), by_hand);
    let e = folded.check_convex().unwrap_err();
    let says = format!("not convex at {} samples (from sample {}", by_hand.len(), by_hand[0]);
    assert!(matches!(e, Error::InvalidArgument(_)) && e.to_string().contains(&says), "{e}");
    Ok(())
}

/// The eccentric disc (centre `e @ phi`, radius `r`) under a translating face on the +y guide,
/// tilted by `tilt` from square to it: the follower's point on the guide where the face is
/// tangent to the disc, `y = (r - e cos phi sin tilt) / cos tilt + e sin phi` (the face's normal
/// `(-sin tilt, cos tilt)` at the distance `r` from the disc's centre), and its derivatives.
fn disc_under_a_tilted_face(e: f64, r: f64, tilt: f64, n: usize) -> Vec<FollowerSample> {
    let (st, ct) = tilt.sin_cos();
    (0..n)
        .map(|k| {
            let phi = TAU * k as f64 / (n - 1) as f64;
            let (sp, cp) = phi.sin_cos();
            let y = [(r - e * cp * st) / ct + e * sp, e * sp * st / ct + e * cp, e * cp * st / ct - e * sp];
            FollowerSample { cam: [phi, 1.0, 0.0], point: y.map(|v| [0.0, v]), direction: [0.0, 1.0] }
        })
        .collect()
}

#[test]
fn an_eccentric_disc_is_recovered_under_a_translating_face() -> Result<(), Error> {
    let (e, r) = (10.0, 40.0);
    for tilt in [0.0, 0.3, -0.5] {
        let cam =
            flat_face_profile(&disc_under_a_tilted_face(e, r, tilt, 145), [0.0, 0.0], FlatFace::Translating { tilt })?;
        for k in 0..145 {
            // In the cam's frame the disc's centre stays at (e, 0).
            let [x, y] = cam.profile[k];
            assert!(((x - e).hypot(y) - r).abs() <= 1e-13 * r, "{tilt} {k}: {:?}", cam.profile[k]);
            assert!((cam.radius[k] - r).abs() <= 1e-13 * r, "{tilt} {k}: {}", cam.radius[k]);
            assert!((cam.pressure_angle[k] - tilt.abs()).abs() <= 1e-15, "{tilt} {k}");
        }
        if tilt == 0.0 {
            // The contact is s' = e cos phi along the face: a face at least 2 e wide.
            for k in 0..145 {
                let phi = TAU * k as f64 / 144.0;
                assert!((cam.offset[k] - e * phi.cos()).abs() <= 1e-13 * r, "{k}");
            }
            assert!((cam.face_width() - 2.0 * e).abs() <= 1e-13 * r);
        }
    }
    Ok(())
}

/// The rocking follower of `DiscFlatRocker` every `360 / (n - 1)` degrees, its point on the arm,
/// with the mechanism's contact offset `w` and arm angle `gamma`.
fn rocker_samples(m: &DiscFlatRocker, n: usize) -> Result<(Vec<FollowerSample>, Vec<f64>), Error> {
    let start = m.solve(0.0)?;
    let (mut samples, mut w) = (Vec::new(), Vec::new());
    for s in m.sweep(0.0, TAU, n, &start.q)? {
        let s = s?;
        let p = [s.out.arm.x, s.out.arm.y];
        samples.push(FollowerSample {
            cam: [s.input.phi, 1.0, 0.0],
            point: [p, [s.dout.arm.x, s.dout.arm.y], [s.d2out.arm.x, s.d2out.arm.y]],
            direction: [-(p[1] - m.a_y), p[0] - m.a_x],
        });
        w.push(s.q.w);
    }
    Ok((samples, w))
}

#[test]
fn an_eccentric_disc_is_recovered_under_a_rocking_face() -> Result<(), Error> {
    let m = DiscFlatRocker::default();
    let (samples, w) = rocker_samples(&m, 145)?;
    // The face `d` on the arm's right: at the signed offset -d (positive on the left).
    let face = FlatFace::Rocking { pivot: [m.a_x, m.a_y], offset: -m.d, tilt: 0.0 };
    let cam = flat_face_profile(&samples, [0.0, 0.0], face)?;
    for (k, &w) in w.iter().enumerate() {
        let [x, y] = cam.profile[k];
        assert!(((x - m.e).hypot(y) - m.r).abs() <= 1e-13 * m.r, "{k}: {:?}", cam.profile[k]);
        // A circle's radius of curvature, from the arm's second analogs.
        assert!((cam.radius[k] - m.r).abs() <= 1e-12 * m.r, "{k}: {}", cam.radius[k]);
        // The contact where the mechanism's loop puts it along the face, and the pressure angle
        // of a rocking flat face, tan = d / w.
        assert!((cam.offset[k] - w).abs() <= 1e-13 * m.r, "{k}: {} vs {w}", cam.offset[k]);
        let alpha = m.d.atan2(w.abs());
        assert!((cam.pressure_angle[k] - alpha).abs() <= 1e-14, "{k}: {} vs {alpha}", cam.pressure_angle[k]);
    }
    // The same follower described from another point of its arm, 30 degrees off it: the face
    // parallel to the arm is then tilted by -30 degrees from the line pivot -> point.
    let off: Vec<FollowerSample> = samples
        .iter()
        .map(|s| {
            let turn = |v: [f64; 2]| {
                let (sn, cs) = (PI / 6.0).sin_cos();
                [cs * v[0] - sn * v[1], sn * v[0] + cs * v[1]]
            };
            let arm = turn([s.point[0][0] - m.a_x, s.point[0][1] - m.a_y]);
            FollowerSample { point: [[m.a_x + arm[0], m.a_y + arm[1]], turn(s.point[1]), turn(s.point[2])], ..*s }
        })
        .collect();
    let tilted = FlatFace::Rocking { pivot: [m.a_x, m.a_y], offset: -m.d, tilt: -PI / 6.0 };
    let tilted = flat_face_profile(&off, [0.0, 0.0], tilted)?;
    for k in 0..samples.len() {
        for c in 0..2 {
            assert!((tilted.profile[k][c] - cam.profile[k][c]).abs() <= 1e-12 * m.r, "{k}");
        }
        assert!((tilted.offset[k] - cam.offset[k]).abs() <= 1e-12 * m.r, "{k}");
    }
    Ok(())
}

/// The arm's angle of a rocking follower moved by a law, `gamma = g0 + a (1 - cos phi) / 2`, and
/// its first two derivatives.
fn swing(phi: f64) -> [f64; 3] {
    let (g0, a) = (-0.25, 0.2);
    [g0 + a * (1.0 - phi.cos()) / 2.0, a * phi.sin() / 2.0, a * phi.cos() / 2.0]
}

#[test]
fn a_rocking_face_s_envelope_is_where_neighbouring_faces_meet() -> Result<(), Error> {
    let (pivot, offset) = ([-60.0, 60.0], -5.0);
    let unit = |g: f64| [g.cos(), g.sin()];
    let samples: Vec<FollowerSample> = (0..73)
        .map(|k| {
            let phi = TAU * k as f64 / 72.0;
            let [g, dg, d2g] = swing(phi);
            let (u, ju) = (unit(g), unit(g + FRAC_PI_2));
            // The samples' point anywhere on the arm's line, only its direction from the pivot
            // counts: here sliding along it, `l = 100 + 10 sin phi` from the pivot.
            let [l, dl, d2l] = [100.0 + 10.0 * phi.sin(), 10.0 * phi.cos(), -10.0 * phi.sin()];
            let along = |a: f64, b: f64| [a * u[0] + b * ju[0], a * u[1] + b * ju[1]];
            let point = [
                [pivot[0] + l * u[0], pivot[1] + l * u[1]],
                along(dl, l * dg),
                along(d2l - l * dg * dg, 2.0 * dl * dg + l * d2g),
            ];
            FollowerSample { cam: [phi, 1.0, 0.0], point, direction: ju }
        })
        .collect();
    let cam = flat_face_profile(&samples, [0.0, 0.0], FlatFace::Rocking { pivot, offset, tilt: 0.0 })?;
    // The face at cam angle phi, in the cam's frame: its point at the pivot's foot and direction.
    let line = |phi: f64| {
        let g = swing(phi)[0];
        let (t, jt) = (unit(g), unit(g + FRAC_PI_2));
        let back = |v: [f64; 2]| [phi.cos() * v[0] + phi.sin() * v[1], -phi.sin() * v[0] + phi.cos() * v[1]];
        (back([pivot[0] + offset * jt[0], pivot[1] + offset * jt[1]]), back(t))
    };
    // Where the faces at phi - delta and phi + delta meet: the envelope's point to O(delta^2).
    let meet = |phi: f64, delta: f64| {
        let ((p1, t1), (p2, t2)) = (line(phi - delta), line(phi + delta));
        let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
        let lambda = cross([p2[0] - p1[0], p2[1] - p1[1]], t2) / cross(t1, t2);
        [p1[0] + lambda * t1[0], p1[1] + lambda * t1[1]]
    };
    for (k, sample) in samples.iter().enumerate() {
        let phi = sample.cam[0];
        // delta = 1e-5: the truncation, ~delta^2 times the profile's size (1e-8 mm), and the
        // rounding of two lines 2e-5 rad apart, ~1e-16 * 100 / 2e-5 (5e-10 mm), both below 1e-7.
        let x = meet(phi, 1e-5);
        for c in 0..2 {
            assert!((cam.profile[k][c] - x[c]).abs() <= 1e-7, "{k}: {:?} vs {x:?}", cam.profile[k]);
        }
        // Its place along the face from the pivot's foot, and the pressure angle tan = |d| / |l|.
        let (foot, t) = line(phi);
        let along = (x[0] - foot[0]) * t[0] + (x[1] - foot[1]) * t[1];
        assert!((cam.offset[k] - along).abs() <= 1e-7, "{k}: {} vs {along}", cam.offset[k]);
        let alpha = offset.abs().atan2(along.abs());
        assert!((cam.pressure_angle[k] - alpha).abs() <= 1e-10, "{k}");
        // The radius of curvature, ds/dpsi along J n: the brute-force points 2e-3 rad of the cam
        // apart over the turn of the face's normal between them (psi = gamma - phi), n the
        // outward normal (the cam's centre behind it). Truncation ~(1e-3)^2 of the radius, the
        // points' error (~3e-9 mm) over 2e-3 rad ~2e-6 mm: 1e-5 of the radius (45 mm) holds both.
        let (a, b) = (meet(phi - 1e-3, 1e-5), meet(phi + 1e-3, 1e-5));
        let dpsi = (swing(phi + 1e-3)[0] - swing(phi - 1e-3)[0]) - 2e-3;
        let jt = [-t[1], t[0]];
        let outward = if jt[0] * foot[0] + jt[1] * foot[1] > 0.0 { jt } else { [-jt[0], -jt[1]] };
        let jn = [-outward[1], outward[0]];
        let rho = ((b[0] - a[0]) * jn[0] + (b[1] - a[1]) * jn[1]) / dpsi;
        assert!((cam.radius[k] - rho).abs() <= 1e-5 * rho.abs(), "{k}: {} vs {rho}", cam.radius[k]);
    }
    Ok(())
}

/// Every length of `samples`, and of the rocker's pivot and offset, times `k`.
fn scaled(samples: &[FollowerSample], k: f64) -> Vec<FollowerSample> {
    samples.iter().map(|s| FollowerSample { point: s.point.map(|p| p.map(|v| v * k)), ..*s }).collect()
}

/// The same cams in micrometres and at the ends of the f64 range: the same angles, the lengths
/// scaled.
#[test]
fn the_same_cams_at_any_scale_have_the_same_angles() -> Result<(), Error> {
    let mm = DiscFlatRocker::default();
    let (rocking, _) = rocker_samples(&mm, 73)?;
    let translating = disc_under_a_tilted_face(10.0, 40.0, 0.3, 73);
    let rocker = |k: f64| FlatFace::Rocking { pivot: [k * mm.a_x, k * mm.a_y], offset: -k * mm.d, tilt: 0.0 };
    let tilted = FlatFace::Translating { tilt: 0.3 };
    let plain =
        [flat_face_profile(&rocking, [0.0, 0.0], rocker(1.0))?, flat_face_profile(&translating, [0.0, 0.0], tilted)?];
    // Micrometres from the mechanism itself (its lengths times 1000), then the samples scaled.
    let k = 1000.0;
    let um = DiscFlatRocker { e: k * mm.e, r: k * mm.r, a_x: k * mm.a_x, a_y: k * mm.a_y, d: k * mm.d, l: k * mm.l };
    let check = |a: &FlatFaceProfile, b: &FlatFaceProfile, k: f64, what: &str| {
        for j in 0..a.radius.len() {
            assert!(
                (a.pressure_angle[j] - b.pressure_angle[j]).abs() <= 1e-14,
                "{what} {j}: {} vs {}",
                a.pressure_angle[j],
                b.pressure_angle[j]
            );
            assert!((k * a.radius[j] - b.radius[j]).abs() <= 1e-12 * k * 40.0, "{what} {j}");
            assert!(
                (k * a.offset[j] - b.offset[j]).abs() <= 1e-12 * k * 40.0,
                "{what} {j}: {} vs {}",
                k * a.offset[j],
                b.offset[j]
            );
            for c in 0..2 {
                assert!((k * a.profile[j][c] - b.profile[j][c]).abs() <= 1e-12 * k * 40.0, "{what} {j}");
            }
        }
    };
    check(&plain[0], &flat_face_profile(&rocker_samples(&um, 73)?.0, [0.0, 0.0], rocker(k))?, k, "um");
    for k in [1e-3, 1e300, 1e-300] {
        check(&plain[0], &flat_face_profile(&scaled(&rocking, k), [0.0, 0.0], rocker(k))?, k, &format!("{k:e}"));
        check(&plain[1], &flat_face_profile(&scaled(&translating, k), [0.0, 0.0], tilted)?, k, &format!("{k:e}"));
    }
    Ok(())
}

#[test]
fn bad_samples_and_faces_are_refused_naming_what_is_wrong() -> Result<(), Error> {
    let m = DwellCamRocker::default();
    let good = translating(13, m.y0, [0.0, 1.0], 1.0, |phi| m.law_by_hand(phi));
    let square = FlatFace::Translating { tilt: 0.0 };
    let refused = |samples: &[FollowerSample], pivot: [f64; 2], face: FlatFace, says: &str| {
        let e = flat_face_profile(samples, pivot, face).unwrap_err();
        assert!(matches!(e, Error::InvalidArgument(_)) && e.to_string().contains(says), "{says}: {e}");
    };
    let o = [0.0, 0.0];
    refused(&[], o, square, "no samples");
    refused(&good, [f64::NAN, 0.0], square, "the pivot");
    refused(&good, o, FlatFace::Translating { tilt: FRAC_PI_2 }, "less than a quarter turn");
    refused(&good, o, FlatFace::Translating { tilt: f64::INFINITY }, "less than a quarter turn");
    refused(&good, o, FlatFace::Rocking { pivot: [0.0, 0.0], offset: f64::NAN, tilt: 0.0 }, "must be finite");
    let mut nan = good.clone();
    nan[4].point[2][1] = f64::NAN;
    refused(&nan, o, square, "sample 4 has a value that is not finite");
    let mut still = good.clone();
    still[2].direction = [0.0, 0.0];
    refused(&still, o, square, "sample 2's direction (the guide)");
    let mut bent = good.clone();
    bent[3].direction = [1e-6, 1.0];
    refused(&bent, o, square, "sample 3's guide");
    // The cam's pivot 15 above the face at sample 0, which has risen by 17.9 at sample 4 (the
    // 3-4-5 law at u = 3/4): the face has passed the pivot.
    refused(&good, [0.0, 75.0], square, "at sample 4 the face passes through the cam's pivot or beyond it");
    // A cam that stands still under a translating face: the face does not turn relative to it.
    let mut parked = good.clone();
    parked[5].cam = [parked[5].cam[0], 0.0, 0.0];
    refused(&parked, o, square, "at sample 5 the face does not turn relative to the cam");
    let mut reversed = good.clone();
    reversed[7].cam[1] = -1.0;
    refused(&reversed, o, square, "at sample 7 the face turns relative to the cam the other way");
    // A rocker whose point is its pivot has no arm (at sample 3, the mid-rise).
    let mid = good[3].point[0];
    refused(&good, o, FlatFace::Rocking { pivot: mid, offset: 5.0, tilt: 0.0 }, "at sample 3 the follower's point");
    // An offset 1e300 beside an arm of about 60: the arm's square underflows in the offset's
    // unit. Said as such, not as a point at the pivot (it was).
    let far = FlatFace::Rocking { pivot: [0.0, 0.0], offset: 1e300, tilt: 0.0 };
    let e = flat_face_profile(&good, o, far).unwrap_err().to_string();
    assert!(e.contains("at sample 0 the arm from the rocker's pivot") && e.contains("too short"), "{e}");
    assert!(!e.contains("is at the rocker's pivot"), "{e}");
    // A rocker swinging with the cam at sample 0: the face turns with it.
    let mut spun = vec![good[0]; 3];
    for (k, s) in spun.iter_mut().enumerate() {
        let g = 0.1 * k as f64;
        *s = FollowerSample {
            cam: [g, 1.0, 0.0],
            point: [[g.cos(), 60.0 + g.sin()], [-g.sin(), g.cos()], [-g.cos(), -g.sin()]],
            direction: [0.0, 1.0],
        };
    }
    refused(
        &spun,
        o,
        FlatFace::Rocking { pivot: [0.0, 60.0], offset: -20.0, tilt: 0.0 },
        "at sample 0 the face does not turn",
    );
    Ok(())
}
