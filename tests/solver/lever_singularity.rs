//! A slotted rocker whose slide passes (close to) its pivot, and a cylinder collapsed (almost)
//! onto its pivot: the angle `theta` of `s @ theta` is undetermined where its lever `s` (an
//! unknown, an input) vanishes, and only known to about `eps * L / s` near there (`L` the loop's
//! other lengths). The health must say so: its pivot ratio is the one its definition gives in
//! closed form, every `Ok` is as accurate as that ratio promises, in every unit and on both
//! paths (closed form and Newton), a position-only solve refuses where the kinematics do, and a
//! sweep never passes such a position silently.
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

/// What one solve returned: `s`, `theta`, their analogs `ds/dphi`, `dtheta/dphi` and the
/// smallest pivot ratio, or the error.
type Outcome = Result<(f64, f64, f64, f64, f64), Error>;

/// Both paths at crank angle `phi`, from a guess on the slide's side of the pivot.
fn solve_both(scale: f64, phi: f64) -> [Outcome; 2] {
    let (h, r) = (scale, scale);
    let closed = SlottedRocker { h, r }
        .kinematics(phi, &SlottedRockerUnknowns { s: 0.1 * scale, theta: 0.1 })
        .map(|k| (k.q.s, k.q.theta, k.dq.s, k.dq.theta, k.health.min_pivot));
    let newton = SlottedRockerNewton { h, r }
        .kinematics(phi, &SlottedRockerNewtonUnknowns { s: 0.1 * scale, theta: 0.1 })
        .map(|k| (k.q.s, k.q.theta, k.dq.s, k.dq.theta, k.health.min_pivot));
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

/// The pivot ratio the health must report for the rocker at offset `e`, from the definition of
/// `Health::min_pivot`, not from the library. The block's Jacobian in its unknowns `(s, theta)`
/// has the columns `-(cos theta, sin theta)` and `s (sin theta, -cos theta)`. The slide's column
/// is divided by its largest entry, `cos theta` (`theta = e / 2` is below `pi / 4`); the angle's,
/// whose lever `s` is an unknown, by at least its lever floor, the loop's other lengths: the Y
/// projection's magnitude without the lever, `|h| + |r| = 2 r` (the X projection's `|r|` is a
/// term of it), larger than `s` here. Partial pivoting keeps the X row first (`cos theta >= sin
/// theta`): pivots `1` and `s cos theta / 2r + tan theta s sin theta / 2r = s / (2 r cos
/// theta)`. With `s = 2 r sin(e / 2)` the ratio is `tan(e / 2)`: the lever over the loop's other
/// lengths, `sin(e / 2)`, to a relative `e^2 / 8`.
fn rocker_pivot(e: f64) -> f64 {
    (e / 2.0).tan()
}

/// Whether a reported pivot ratio is the closed form's `want`. The reported one is computed
/// from the solved position: the slide's length is known to a few `eps` of the loop (the rounding
/// of its lengths), a relative `eps L / s`, about `eps / want`, and the angle's error (`eps /
/// want` too) moves the cosines by `eps` at most. So within `4 eps / want` (from 2e-14 at a
/// lever of a tenth of the loop to 2e-6 at 1e-9), where a pivot off by a constant factor, even
/// of 1 %, is not.
fn assert_pivot(at: &str, pivot: f64, want: f64) {
    let eps = f64::EPSILON;
    assert!((pivot / want - 1.0).abs() <= 4.0 * eps / want, "{at}: pivot ratio {pivot:e}, closed form {want:e}");
}

#[test]
fn a_slide_near_its_pivot_is_as_accurate_as_its_pivot_ratio_says() {
    let eps = f64::EPSILON;
    let mut analogs_checked = 0;
    for scale in SCALES {
        for k in 1..=12 {
            let phi = -FRAC_PI_2 + 10f64.powi(-k);
            let e = offset(phi);
            let pivot = rocker_pivot(e);
            for (path, got) in ["closed form", "Newton"].iter().zip(solve_both(scale, phi)) {
                let at = format!("{path}, scale {scale:e}, e = 1e-{k}");
                // Down to a lever of 1e-8 of the loop the position is regular to the default
                // tolerance (pivot ratio 1e-10).
                if let Some((s, theta, ds, dtheta, reported)) = ok_or_singular(&at, got, k, 9, 10) {
                    assert_pivot(&at, reported, pivot);
                    // The angle carries the rounding of the loop's lengths divided by the lever,
                    // `eps L / s`, and its analog that error once more over the lever: with the
                    // pivot ratio `s / L`, bounds of `eps / pivot` and `eps / pivot^2` (twice each
                    // for the other roundings). The angle's bound is one of a direction, against
                    // a turn (at most 9e-7 rad, at e = 1e-9): it still tells the slot from its
                    // reverse, although from e = 1e-8 on it exceeds `theta = e / 2` itself.
                    assert_close!(theta, e / 2.0, <= 2.0 * eps / pivot, "{at}: theta {theta:e}");
                    // The analog's bound exceeds the analog itself (1/2) from e = 1e-8 on, where
                    // the data no longer determine it (measured: off by all of it there): checked
                    // where it says something, down to e = 1e-7 (a bound of 18 % of it).
                    if eps / (pivot * pivot) < 0.5 {
                        assert_close!(dtheta, 0.5, <= eps / (pivot * pivot), "{at}: dtheta {dtheta}");
                        analogs_checked += 1;
                    }
                    // What the data do determine at every lever: the slide's length, as in the
                    // position-only solve (the rounding of the loop's lengths, a few `eps` of
                    // it), and its analog, the crank's velocity along the slide, `r cos(e /
                    // 2)`, which the angle's error moves by `r sin(e / 2)` times it, `2 eps r`
                    // at most (8 `eps` with the roundings of the projection).
                    let lever = 2.0 * (e / 2.0).sin();
                    assert_close!(s / scale, lever, <= 4.0 * eps, "{at}: s {s:e}");
                    assert_close!(ds / (scale * (e / 2.0).cos()), 1.0, <= 8.0 * eps, "{at}: ds {ds:e}");
                }
            }
        }
    }
    // Both paths at e = 1e-1 ..= 1e-7 in every unit.
    assert_eq!(analogs_checked, 2 * 7 * SCALES.len());
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

/// The pivot ratio the health must report for the cylinder drive with `d = r` at `c = len /
/// (2 r)`, from the definition of `Health::min_pivot` (as [`rocker_pivot`]). The block's
/// Jacobian in its unknowns `(theta, phi)` has the columns `len (-sin theta, cos theta)` and `r
/// (sin phi, -cos phi)`, with `phi = 2 theta`, `theta` near `pi / 2` (`sin theta >= cos
/// theta`). The cylinder's angle, whose lever `len` is an input, is divided by at least its lever
/// floor: the X projection's magnitude without the lever, `|d| + |r| = 2 r` (the Y projection's
/// `|r|` is a term of it), larger than `len` here; the crank's by its largest entry `r |cos
/// phi|`. Partial pivoting takes the X row first: pivot `len sin theta / 2r`. The second is the
/// equilibrated determinant over it: `|det| = len r |sin(phi - theta)| = len r sin theta`, so
/// `(len sin theta / (2 r * r |cos phi|)) / (len sin theta / 2r) = 1 / |cos phi| >= 1`. The ratio
/// is the first, `c sqrt(1 - c^2)`: the lever over the loop's other lengths, `c`, to a relative
/// `c^2 / 2`.
fn cylinder_pivot(c: f64) -> f64 {
    c * (1.0 - c * c).sqrt()
}

#[test]
fn a_cylinder_collapsed_onto_its_pivot_is_as_accurate_as_its_pivot_ratio_says() {
    // `d = r`: the crank pin passes the cylinder's pivot, where the cylinder's angle is
    // undetermined. On the branch above the axis `phi = 2 theta` and `cos(theta) = len / (2 r)`:
    // `theta = pi/2 - asin(len / (2 r))`, `dtheta/dlen = -1 / (2 r sqrt(1 - len^2 / (4 r^2)))`.
    let eps = f64::EPSILON;
    let mut analogs_checked = 0;
    for scale in SCALES {
        let (d, r) = (scale, scale);
        for k in 1..=14 {
            let len = scale * 10f64.powi(-k);
            let c = len / (2.0 * r);
            let pivot = cylinder_pivot(c);
            let theta = FRAC_PI_2 - c.asin();
            let dtheta = -1.0 / (2.0 * r * (1.0 - c * c).sqrt());
            // From the solution itself, as a sweep's prediction hands it: from a guess off by
            // more than the lever, Newton's steps in `theta` (its column is the lever) jump to
            // the other assembly mode, tens of turns away; its determinant sign tells.
            let guess = (theta, 2.0 * theta);
            let closed = CylinderCrank { d, r }
                .kinematics(len, &CylinderCrankUnknowns { theta: guess.0, phi: guess.1 })
                .map(|k| (k.q.theta, k.q.phi, k.dq.theta, k.dq.phi, k.health.min_pivot));
            let newton = CylinderCrankNewton { d, r }
                .kinematics(len, &CylinderCrankNewtonUnknowns { theta: guess.0, phi: guess.1 })
                .map(|k| (k.q.theta, k.q.phi, k.dq.theta, k.dq.phi, k.health.min_pivot));
            let placed = CylinderCrank { d, r }
                .position(len, &CylinderCrankUnknowns { theta: guess.0, phi: guess.1 })
                .map(|(q, _)| q.theta);
            for (path, got) in [("closed form", closed), ("Newton", newton)] {
                let at = format!("{path}, scale {scale:e}, len = 1e-{k} r");
                if let Some((th, ph, dth, dph, reported)) = ok_or_singular(&at, got, k, 10, 9) {
                    assert_pivot(&at, reported, pivot);
                    // As for the slotted rocker: `eps / pivot` and `eps / pivot^2` (the angle
                    // modulo whole turns, which the solution does not pick). The angle's bound
                    // stays below 1e-6 rad of an angle near `pi / 2`.
                    assert!(angle_apart(th, theta) <= 2.0 * eps / pivot, "{at}: theta {th} (pivot {pivot:e})");
                    // The analog's relative bound reaches one from len = 1e-8 r on, where the
                    // data no longer determine it (measured: off by 11 % to all of it there):
                    // checked where it says something, down to len = 1e-7 r (a bound of 9 %).
                    if eps / (pivot * pivot) < 1.0 {
                        let rel = ((dth - dtheta) / dtheta).abs();
                        assert!(rel <= eps / (pivot * pivot), "{at}: dtheta {dth:e} (pivot {pivot:e})");
                        analogs_checked += 1;
                    }
                    // What the data do determine at every length: the crank's angle, whose pin
                    // is at `2 r cos(phi / 2) = len` from the pivot (the rounding of the lengths
                    // moves it by a few `eps`, as does that of the reference near `pi`), and its
                    // analog `-1 / (r sin theta)`, which the angle's error moves by `cos theta`
                    // times it, `2 eps` at most (8 `eps` with the roundings).
                    assert!(angle_apart(ph, PI - 2.0 * c.asin()) <= 8.0 * eps, "{at}: phi {ph}");
                    assert_close!(dph / (2.0 * dtheta), 1.0, <= 8.0 * eps, "{at}: dphi {dph:e}");
                }
            }
            // The position-only solve refuses where the kinematics do.
            let at = format!("position, scale {scale:e}, len = 1e-{k} r");
            if let Some(th) = ok_or_singular(&at, placed, k, 10, 10) {
                assert_close!(th, theta, <= 4.0 * eps * scale / len, "{at}: theta {th}");
            }
        }
    }
    // Both paths at len = 1e-1 r ..= 1e-7 r in every unit.
    assert_eq!(analogs_checked, 2 * 7 * SCALES.len());
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
                assert!(matches!(e, Error::NearSingular { .. }) && e.to_string().contains("singular_pivot"), "{e}");
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
