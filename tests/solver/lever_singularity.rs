//! A slotted rocker whose slide passes (close to) its pivot, and a cylinder collapsed (almost)
//! onto its pivot: the angle `theta` of `s @ theta` is undetermined where its lever `s` (an
//! unknown, an input) vanishes, and only known to about `eps * L / s` near there (`L` the loop's
//! other lengths). The health must say so: every `Ok` is as accurate as its reported pivot ratio
//! promises, in every unit and on both paths (closed form and Newton), a position-only solve
//! refuses where the kinematics do, and a sweep never passes such a position silently.
//!
//! The rocker's reference is exact: with the pivot at the origin, the crank centre at `(0, h)` and `h =
//! r`, the slide at crank angle `phi = -pi/2 + e` is `r (sin e, 1 - cos e)`, whose direction is
//! `theta = e / 2` and length `s = 2 r sin(e / 2)`, for every `e`: `dtheta/dphi = 1/2`.

use kinloop::{Error, EventKind, SweepConfig};
use std::f64::consts::{FRAC_PI_2, PI};

use crate::support::{angle_apart, tol};

kinloop::mechanism! {
    /// A crank `r` about `(0, h)` driving a block in a rocker slot pivoted at the origin.
    pub struct SlottedRocker {
        params h, r;
        input phi;
        unknowns s = 1, theta = 0.5;
        loop slot: (0, h) + r @ phi == s @ theta;
    }
}

kinloop::mechanism! {
    /// The same rocker solved by Newton.
    #[kinloop(newton)]
    pub struct SlottedRockerNewton {
        params h, r;
        input phi;
        unknowns s = 1, theta = 0.5;
        loop slot: (0, h) + r @ phi == s @ theta;
    }
}

kinloop::mechanism! {
    /// A crank `r` about `(d, 0)` whose pin is driven by a cylinder of length `len` from the
    /// origin: the cylinder's angle has an input for its lever.
    pub struct CylinderCrank {
        params d, r;
        input len;
        unknowns theta = 1.5, phi = 3.0;
        loop cyl: len @ theta == (d, 0) + r @ phi;
    }
}

kinloop::mechanism! {
    /// The same drive solved by Newton.
    #[kinloop(newton)]
    pub struct CylinderCrankNewton {
        params d, r;
        input len;
        unknowns theta = 1.5, phi = 3.0;
        loop cyl: len @ theta == (d, 0) + r @ phi;
    }
}

/// The units the solves are made in: lengths from a micrometre to a megametre of the metre's.
const SCALES: [f64; 5] = [1e-6, 1e-3, 1.0, 1e3, 1e6];

/// What one solve returned: `theta`, `dtheta/dphi` and the smallest pivot ratio, or the error.
type Outcome = Result<(f64, f64, f64), Error>;

/// Both paths at crank angle `phi`, from a guess on the slide's side of the pivot.
fn solve_both(scale: f64, phi: f64) -> [Outcome; 2] {
    let (h, r) = (scale, scale);
    let closed = SlottedRocker { h, r }
        .kinematics(phi, &SlottedRockerUnknowns { s: 0.1 * scale, theta: 0.1 })
        .map(|k| (k.q.theta, k.dq.theta, k.health.min_pivot));
    let newton = SlottedRockerNewton { h, r }
        .kinematics(phi, &SlottedRockerNewtonUnknowns { s: 0.1 * scale, theta: 0.1 })
        .map(|k| (k.q.theta, k.dq.theta, k.health.min_pivot));
    [closed, newton]
}

/// The exact offset `e = phi + pi/2` of a crank angle in floating point: `phi + FRAC_PI_2` is
/// exact (the two are within a factor two), and `FRAC_PI_2` lies below `pi/2` by the constant
/// added.
fn offset(phi: f64) -> f64 {
    (phi + FRAC_PI_2) + 6.123_233_995_736_766e-17
}

/// The value of a solve at an offset of `1e-k`: when `Ok`, which the data must still determine
/// there (`k <= last_ok`), the value to check; an error must be `Singular`, and only from
/// `k >= first_singular` on.
fn ok_or_singular<T: std::fmt::Debug>(
    at: &str,
    got: Result<T, Error>,
    k: i32,
    last_ok: i32,
    first_singular: i32,
) -> Option<T> {
    match got {
        Ok(v) => {
            assert!(k <= last_ok, "{at}: Ok {v:?}");
            Some(v)
        }
        Err(err) => {
            assert!(matches!(err, Error::Singular { .. }), "{at}: {err}");
            assert!(k >= first_singular, "{at}: {err}");
            None
        }
    }
}

#[test]
fn a_slide_near_its_pivot_is_as_accurate_as_its_pivot_ratio_says() {
    let eps = f64::EPSILON;
    for scale in SCALES {
        for k in 1..=12 {
            let phi = -FRAC_PI_2 + 10f64.powi(-k);
            let e = offset(phi);
            for (path, got) in ["closed form", "Newton"].iter().zip(solve_both(scale, phi)) {
                let at = format!("{path}, scale {scale:e}, e = 1e-{k}");
                // Down to a lever of 1e-8 of the loop the position is regular to the default
                // tolerance (pivot ratio 1e-10).
                if let Some((theta, dtheta, pivot)) = ok_or_singular(&at, got, k, 9, 10) {
                    // The angle carries the rounding of the loop's lengths divided by the lever,
                    // `eps L / s`, and its analog that error once more over the lever: with the
                    // pivot ratio `s / L`, bounds of `eps / pivot` and `eps / pivot^2` (twice each
                    // for the other roundings).
                    assert_close!(theta, e / 2.0, <= 2.0 * eps / pivot, "{at}: theta {theta:e} (pivot {pivot:e})");
                    assert_close!(dtheta, 0.5, <= eps / (pivot * pivot), "{at}: dtheta {dtheta} (pivot {pivot:e})");
                }
            }
        }
    }
}

#[test]
fn a_position_solve_refuses_the_lever_the_kinematics_refuse() {
    // Without analogs there is no pivot ratio to report: a position-only solve tests the lever
    // itself, on both paths, and agrees with the kinematics (`Singular` from a lever of 1e-11
    // of the loop on; Newton's own test, on its Jacobian equilibrated by the rows' magnitudes
    // and the unknowns' units, may already refuse or
    // still accept at 1e-10, the edge of the tolerance).
    let eps = f64::EPSILON;
    for scale in SCALES {
        let (h, r) = (scale, scale);
        for k in 1..=16 {
            let phi = -FRAC_PI_2 + 10f64.powi(-k);
            let e = offset(phi);
            let closed = SlottedRocker { h, r }
                .position(phi, &SlottedRockerUnknowns { s: 0.1 * scale, theta: 0.1 })
                .map(|(q, _)| (q.s, q.theta));
            let newton = SlottedRockerNewton { h, r }
                .position(phi, &SlottedRockerNewtonUnknowns { s: 0.1 * scale, theta: 0.1 })
                .map(|(q, _)| (q.s, q.theta));
            for (path, got) in [("closed form", closed), ("Newton", newton)] {
                let at = format!("{path}, scale {scale:e}, e = 1e-{k}");
                if let Some((s, theta)) = ok_or_singular(&at, got, k, 10, 10) {
                    // The angle to the rounding of the loop's lengths over the lever.
                    let lever = 2.0 * (e / 2.0).sin();
                    assert_close!(theta, e / 2.0, <= 4.0 * eps / lever, "{at}: theta {theta:e}");
                    assert_close!(s / scale, lever, <= 4.0 * eps, "{at}: s {s:e}");
                }
            }
        }
    }
}

#[test]
fn a_cylinder_collapsed_onto_its_pivot_is_as_accurate_as_its_pivot_ratio_says() {
    // `d = r`: the crank pin passes the cylinder's pivot, where the cylinder's angle is
    // undetermined. On the branch above the axis `phi = 2 theta` and `cos(theta) = len / (2 r)`:
    // `theta = pi/2 - asin(len / (2 r))`, `dtheta/dlen = -1 / (2 r sqrt(1 - len^2 / (4 r^2)))`.
    let eps = f64::EPSILON;
    for scale in SCALES {
        let (d, r) = (scale, scale);
        for k in 1..=14 {
            let len = scale * 10f64.powi(-k);
            let theta = FRAC_PI_2 - (len / (2.0 * r)).asin();
            let dtheta = -1.0 / (2.0 * r * (1.0 - len * len / (4.0 * r * r)).sqrt());
            // From the solution itself, as a sweep's prediction hands it: from a guess off by
            // more than the lever, Newton's steps in `theta` (its column is the lever) jump to
            // the other assembly mode, tens of turns away; its determinant sign tells.
            let guess = (theta, 2.0 * theta);
            let closed = CylinderCrank { d, r }
                .kinematics(len, &CylinderCrankUnknowns { theta: guess.0, phi: guess.1 })
                .map(|k| (k.q.theta, k.dq.theta, k.health.min_pivot));
            let newton = CylinderCrankNewton { d, r }
                .kinematics(len, &CylinderCrankNewtonUnknowns { theta: guess.0, phi: guess.1 })
                .map(|k| (k.q.theta, k.dq.theta, k.health.min_pivot));
            let placed = CylinderCrank { d, r }
                .position(len, &CylinderCrankUnknowns { theta: guess.0, phi: guess.1 })
                .map(|(q, _)| q.theta);
            for (path, got) in [("closed form", closed), ("Newton", newton)] {
                let at = format!("{path}, scale {scale:e}, len = 1e-{k} r");
                if let Some((th, dth, pivot)) = ok_or_singular(&at, got, k, 10, 9) {
                    // As for the slotted rocker: `eps / pivot` and `eps / pivot^2` (the angle
                    // modulo whole turns, which the solution does not pick).
                    assert!(angle_apart(th, theta) <= 2.0 * eps / pivot, "{at}: theta {th} (pivot {pivot:e})");
                    let rel = ((dth - dtheta) / dtheta).abs();
                    assert!(rel <= eps / (pivot * pivot), "{at}: dtheta {dth:e} (pivot {pivot:e})");
                }
            }
            // The position-only solve refuses where the kinematics do.
            let at = format!("position, scale {scale:e}, len = 1e-{k} r");
            if let Some(th) = ok_or_singular(&at, placed, k, 10, 10) {
                assert_close!(th, theta, <= 4.0 * eps * scale / len, "{at}: theta {th}");
            }
        }
    }
}

/// The rocker angle from its closed form, on the side of the slide the sweep started on.
fn exact_theta(h: f64, r: f64, phi: f64) -> f64 {
    (h + r * phi.sin()).atan2(r * phi.cos())
}

#[test]
fn a_sweep_never_passes_a_slide_near_its_pivot_silently() {
    for scale in [1e-3, 1.0, 1e3] {
        for d in [1e-3, 1e-8] {
            let (h, r) = (scale * (1.0 + d), scale);
            let m = SlottedRocker { h, r };
            let g = m.position(0.0, &SlottedRockerUnknowns { s: 1.4 * scale, theta: 0.7 }).unwrap().0;
            let check = |cfg: SweepConfig| -> Result<(), Error> {
                for st in m.sweep(0.0, 2.0 * PI, 73, &g).unwrap().with_config(cfg) {
                    let st = st?;
                    let want = exact_theta(h, r, st.input.phi);
                    assert!(angle_apart(st.q.theta, want) < 1e-9, "scale {scale:e}, d {d:e}, at {}", st.input.phi);
                    assert!(st.q.s > 0.0);
                }
                Ok(())
            };
            // By default: every sample right, or a stop that says how to pass.
            if let Err(e) = check(SweepConfig::default()) {
                assert!(d < 1e-6, "scale {scale:e}, d {d:e}: {e}");
                assert!(matches!(e, Error::Branch { .. }) && e.to_string().contains("singular_pivot"), "{e}");
            }
            // Told that it may pass this close, it passes, on the right side of the pivot.
            check(SweepConfig::default().with_singular_pivot(1e-12)).unwrap();
        }
    }
}

/// The sample counts the crossings are swept with: a step of a whole sample spacing (at most a
/// quarter radian) down to a hundredth of a radian.
const SAMPLES: [usize; 3] = [13, 73, 721];

/// Where the sweep of `sweep` stops, with the event it records there.
fn stop_at<I: Iterator<Item = Result<T, Error>>, T>(sweep: &mut I) -> Error {
    sweep.by_ref().find_map(Result::err).expect("the sweep stops at the crossing")
}

#[test]
fn a_slide_through_its_pivot_is_a_located_singular_crossing() {
    // `h = r`: the slide passes exactly through the pivot at `phi = 3 pi / 2`, where `s = 0`
    // and the smooth continuation turns `s` negative (the determinant `s` changes sign).
    //
    // Located from positions solved on both sides, well away from the pivot: the determinant
    // along the branch is the lever over the loop's size, `2 sin(e / 2) r / L` with the offset
    // `e` from the crossing, rounded to a few `eps` and of slope about one per radian there. Its
    // interpolant passes that rounding on about doubled (its Lebesgue constant between the
    // nearest samples) and the input path rounds the crossing to a few ulps of `3 pi / 2`: ten
    // to twenty `eps` of a radian in all, within `tol::ULPS` (45 `eps`). Before, the crossing
    // was read off the continuation's points, whose angle the residual tolerance pins only to
    // `tol L / s`: about `sqrt(tol)` off (up to 8.3e-7 rad).
    for scale in SCALES {
        for samples in SAMPLES {
            let closed = SlottedRocker { h: scale, r: scale };
            let g = closed.position(0.0, &SlottedRockerUnknowns { s: 1.4 * scale, theta: 0.7 }).unwrap().0;
            let mut sweep = closed.sweep(0.0, 2.0 * PI, samples, &g).unwrap();
            let stop = stop_at(&mut sweep);
            let closed_events = sweep.events().to_vec();
            let newton = SlottedRockerNewton { h: scale, r: scale };
            let g = newton.position(0.0, &SlottedRockerNewtonUnknowns { s: 1.4 * scale, theta: 0.7 }).unwrap().0;
            let mut sweep = newton.sweep(0.0, 2.0 * PI, samples, &g).unwrap();
            let newton_stop = stop_at(&mut sweep);
            for (path, stop, events) in
                [("closed form", stop, closed_events), ("Newton", newton_stop, sweep.events().to_vec())]
            {
                let at = format!("{path}, scale {scale:e}, {samples} samples");
                assert!(matches!(stop, Error::SweepStopped { kind: EventKind::SingularCrossing, .. }), "{at}: {stop}");
                assert_eq!(events.len(), 1, "{at}: {events:?}");
                let ev = &events[0];
                assert_close!(ev.x[0], 1.5 * PI, <= tol::ULPS, "{at}: crossing at {}", ev.x[0]);
                // The position there from the samples' positions, whose angles are pinned to
                // `eps L / s` with a lever of at least a thousandth of the loop (the samples' smallest
                // pivot ratio), passed on about doubled: the slide on the pivot, `theta = pi`.
                assert_close!(ev.q[0] / scale, 0.0, <= tol::ULPS, "{at}: s {:e}", ev.q[0]);
                assert!(angle_apart(ev.q[1], PI) <= 1e-12, "{at}: theta {}", ev.q[1]);
            }
        }
    }
}

#[test]
fn a_crank_pin_through_its_cylinders_pivot_is_a_located_singular_crossing() {
    // `d = r`: shortening the cylinder to `len = 0` brings the crank pin onto its pivot, where
    // the cylinder's angle is undetermined; on the branch above the axis `cos(theta) = len /
    // (2 r)` goes on smoothly to negative lengths, and the determinant `-len r sin(theta)`
    // changes sign. Located as the slotted rocker's crossing is, in the length's unit: its
    // determinant is exact in the input and rounded to a few `eps` in the angles, and the
    // input path `r - 2 r tau` rounds `len = 0` to an ulp of `r`, so within `tol::ULPS` of the
    // mechanism's size (before: up to 8.4e-7 of it).
    for scale in SCALES {
        for samples in SAMPLES {
            let (d, r) = (scale, scale);
            let start = CylinderCrankUnknowns { theta: PI / 3.0, phi: 2.0 * PI / 3.0 };
            let closed = CylinderCrank { d, r };
            let g = closed.position(r, &start).unwrap().0;
            let mut sweep = closed.sweep(r, -r, samples, &g).unwrap();
            let stop = stop_at(&mut sweep);
            let closed_events = sweep.events().to_vec();
            let newton = CylinderCrankNewton { d, r };
            let g = newton.position(r, &CylinderCrankNewtonUnknowns { theta: start.theta, phi: start.phi }).unwrap().0;
            let mut sweep = newton.sweep(r, -r, samples, &g).unwrap();
            let newton_stop = stop_at(&mut sweep);
            for (path, stop, events) in
                [("closed form", stop, closed_events), ("Newton", newton_stop, sweep.events().to_vec())]
            {
                let at = format!("{path}, scale {scale:e}, {samples} samples");
                assert!(matches!(stop, Error::SweepStopped { kind: EventKind::SingularCrossing, .. }), "{at}: {stop}");
                assert_eq!(events.len(), 1, "{at}: {events:?}");
                let ev = &events[0];
                assert_close!(ev.x[0] / scale, 0.0, <= tol::ULPS, "{at}: crossing at {}", ev.x[0]);
                // The position as the rocker's: the cylinder across, the crank pointing back.
                assert!(angle_apart(ev.q[0], FRAC_PI_2) <= 1e-12, "{at}: theta {}", ev.q[0]);
                assert!(angle_apart(ev.q[1], PI) <= 1e-12, "{at}: phi {}", ev.q[1]);
            }
        }
    }
}
