//! The cam-linkage drive (eccentric disc cam, roller follower on a bell-crank rocker, rod and
//! slider) over a full turn against its closed form written here by hand: the equivalent
//! four-bar's joint as the intersection of two circles, the slider from the rod's length; the
//! analogs against central differences (one Richardson step) of that closed form; the rocker's
//! swing and the slider's stroke against the four-bar's limit positions. The drive with a
//! prescribed law (double-harmonic rise and return moving a translating follower that swings a
//! rocker) against the law's own derivatives and the rocker's circle intersection; the same with
//! a piecewise rise-dwell-return-dwell law (`clamp`), sampled at and beside its segments' ends,
//! and over four turns against the law of `phi mod 2 pi` (the declaration's `wrap`).

use crate::support::richardson;
use kinloop_fixtures::cam_linkage::{CamLinkage, DwellCamRocker, DwellCamRockerState, HarmonicCamRocker};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// The closed form's pose at cam angle `phi`: `[beta, psi, gamma, x]`.
///
/// The roller centre P is where the circle about the cam centre C = e (cos phi, sin phi) of
/// radius `r_cam + r_roller` (the contact condition) meets the circle about the pivot A of
/// radius `l_arm`, on the left of A -> C (the declared assembly mode: the roller to the right of
/// the cam, below the pivot). The rocker pin Q = A + l_out (cos(psi + delta), sin(psi + delta));
/// the slider S = (x, h) is at the rod's length from Q, to the right of Q.
fn closed_form(m: &CamLinkage, phi: f64) -> [f64; 4] {
    let (cx, cy) = (m.e * phi.cos(), m.e * phi.sin());
    let (px, py) = left_intersection(m.a_x, m.a_y, m.l_arm, cx, cy, m.r_cam + m.r_roller);
    let psi = (py - m.a_y).atan2(px - m.a_x);
    let beta = (py - cy).atan2(px - cx);
    let x = slider(m, psi);
    let (qx, qy) = pin(m, psi);
    [beta, psi, (m.h - qy).atan2(x - qx), x]
}

/// The point at distance `ra` from (ax, ay) and `rb` from (bx, by), on the left of the
/// direction from the first centre to the second.
fn left_intersection(ax: f64, ay: f64, ra: f64, bx: f64, by: f64, rb: f64) -> (f64, f64) {
    let (ux, uy) = (bx - ax, by - ay);
    let d = ux.hypot(uy);
    // Along the line of centres from the first, and across it to the left.
    let along = (ra * ra - rb * rb + d * d) / (2.0 * d);
    let across = (ra * ra - along * along).sqrt();
    (ax + (along * ux - across * uy) / d, ay + (along * uy + across * ux) / d)
}

/// The rocker pin Q at rocker angle `psi`.
fn pin(m: &CamLinkage, psi: f64) -> (f64, f64) {
    (m.a_x + m.l_out * (psi + m.delta).cos(), m.a_y + m.l_out * (psi + m.delta).sin())
}

/// The slider's position on its guide at rocker angle `psi`.
fn slider(m: &CamLinkage, psi: f64) -> f64 {
    let (qx, qy) = pin(m, psi);
    qx + (m.l_rod * m.l_rod - (m.h - qy).powi(2)).sqrt()
}

/// `a - b` for angles, in (-pi, pi].
fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    if d > PI { d - TAU } else { d }
}

#[test]
fn positions_and_analogs_over_a_turn_match_the_closed_form() -> Result<(), kinloop::Error> {
    let m = CamLinkage::default();
    // Lengths are compared relative to the longest link, angles in radians (scale-free).
    let scale = m.l_rod;
    // Central differences with one Richardson step of h = 0.01 rad: truncation about
    // h^4/480 |f^(5)| (about 1e-10 of the link lengths here, the derivatives of a cam's motion
    // being of the order of the eccentricity) and rounding of the closed form (1e-16 relative)
    // amplified to about 1e-14/h and 5e-14/h^2 relative: at most 1e-9 relative for the
    // velocity analogs and 1e-8 for the acceleration analogs, with a margin of ten.
    let h = 1e-2;
    let (tol_q, tol_d1, tol_d2) = (1e-12, 1e-9, 1e-8);
    let mut guess = m.guess(0.0);
    let mut worst = [0.0f64; 3];
    for k in 0..=360 {
        let phi = f64::from(k).to_radians();
        let s = m.kinematics(phi, &guess)?;
        guess = s.q;
        let reference = closed_form(&m, phi);
        let solved = [s.q.beta, s.q.psi, s.q.gamma, s.q.x];
        let (d1, d2) = ([s.dq.beta, s.dq.psi, s.dq.gamma, s.dq.x], [s.d2q.beta, s.d2q.psi, s.d2q.gamma, s.d2q.x]);
        for i in 0..4 {
            // The slider's position is a length; the rest are angles.
            let (unit, q_err) = if i == 3 {
                (scale, (solved[i] - reference[i]).abs() / scale)
            } else {
                (1.0, angle_diff(solved[i], reference[i]).abs())
            };
            let (fd1, fd2) = richardson(|p| closed_form(&m, p)[i], phi, h);
            let (e1, e2) = ((d1[i] - fd1).abs() / unit, (d2[i] - fd2).abs() / unit);
            assert!(q_err <= tol_q, "position {i} at {k}°: {} vs {} (error {q_err:.1e})", solved[i], reference[i]);
            assert!(e1 <= tol_d1, "velocity analog {i} at {k}°: {} vs {fd1} (error {e1:.1e})", d1[i]);
            assert!(e2 <= tol_d2, "acceleration analog {i} at {k}°: {} vs {fd2} (error {e2:.1e})", d2[i]);
            worst = [worst[0].max(q_err), worst[1].max(e1), worst[2].max(e2)];
        }
        // The pressure angle and the declared points, from the same closed form.
        let [beta, psi, _, x] = reference;
        assert!(angle_diff(s.out.pressure, beta - psi - FRAC_PI_2).abs() <= tol_q);
        let (qx, qy) = pin(&m, psi);
        let roller = (m.a_x + m.l_arm * psi.cos(), m.a_y + m.l_arm * psi.sin());
        assert!((s.out.rocker_pin.x - qx).hypot(s.out.rocker_pin.y - qy) <= tol_q * scale);
        assert!((s.out.roller.x - roller.0).hypot(s.out.roller.y - roller.1) <= tol_q * scale);
        // The contact condition: the roller centre stays at r_cam + r_roller from the cam centre.
        let gap = (s.out.roller - s.out.cam_centre).norm() - (m.r_cam + m.r_roller);
        assert!(gap.abs() <= tol_q * scale, "contact lost at {k}°: {gap:.1e}");
        // The slider stays at the rod's length from the pin.
        assert!(((x - qx).hypot(m.h - qy) - m.l_rod).abs() <= tol_q * scale);
    }
    println!(
        "max errors: positions {:.1e}, velocity analogs {:.1e}, acceleration analogs {:.1e}",
        worst[0], worst[1], worst[2]
    );
    Ok(())
}

#[test]
fn swing_and_stroke_match_the_limit_positions() -> Result<(), kinloop::Error> {
    let m = CamLinkage::default();
    let b = m.r_cam + m.r_roller;
    // The rocker's limit positions: cam crank and roller line stretched (|OP| = b + e) or folded
    // (|OP| = b - e); P on the circle about A, on the left of A -> O (the side of A -> C then,
    // C lying on the line OP), the cam angle along O -> P (stretched) or opposite (folded).
    let limit = |radius: f64, turn: f64| {
        let (px, py) = left_intersection(m.a_x, m.a_y, m.l_arm, 0.0, 0.0, radius);
        ((py - m.a_y).atan2(px - m.a_x), (py.atan2(px) + turn).rem_euclid(TAU))
    };
    let (psi_out, at_out) = limit(b + m.e, 0.0);
    let (psi_in, at_in) = limit(b - m.e, PI);
    let (psi_max, psi_min, at_max, at_min) =
        if psi_out > psi_in { (psi_out, psi_in, at_out, at_in) } else { (psi_in, psi_out, at_in, at_out) };
    let turn = m.sampled(0.0, TAU, 361, &m.guess(0.0))?;
    let swing = turn.range(CamLinkage::COL.psi)?;
    let stroke = turn.range(CamLinkage::COL.x)?;
    // The extremes are roots of the velocity analog refined to rounding (Sampled's bracketed
    // root), located where the analog's rounding (about 1e-16) divided by the acceleration
    // analog (about 0.1 here) puts them: values and cam angles both to rounding, with a margin.
    let (tol_value, tol_at) = (1e-12, 1e-10);
    let near = |a: f64, b: f64, tol: f64| angle_diff(a, b).abs() <= tol;
    assert_eq!(swing.extremes.len(), 2, "one swing each way: {:?}", swing.extremes);
    assert!(near(swing.max.value, psi_max, tol_value), "{} vs {psi_max}", swing.max.value);
    assert!(near(swing.min.value, psi_min, tol_value), "{} vs {psi_min}", swing.min.value);
    assert!(near(swing.max.x, at_max, tol_at), "{} vs {at_max}", swing.max.x);
    assert!(near(swing.min.x, at_min, tol_at), "{} vs {at_min}", swing.min.x);
    assert!((swing.span() - (psi_max - psi_min)).abs() <= tol_value);
    // The slider follows the rocker monotonically here (the rod never lines up with the pin's
    // path), so its dead centres are at the rocker's limit positions.
    let (x_hi, x_lo) = (slider(&m, psi_max), slider(&m, psi_min));
    let (x_max, x_min, at_x_max, at_x_min) =
        if x_hi > x_lo { (x_hi, x_lo, at_max, at_min) } else { (x_lo, x_hi, at_min, at_max) };
    let tol_len = tol_value * m.l_rod;
    assert_eq!(stroke.extremes.len(), 2, "one stroke each way: {:?}", stroke.extremes);
    assert!((stroke.max.value - x_max).abs() <= tol_len, "{} vs {x_max}", stroke.max.value);
    assert!((stroke.min.value - x_min).abs() <= tol_len, "{} vs {x_min}", stroke.min.value);
    assert!(near(stroke.max.x, at_x_max, tol_at) && near(stroke.min.x, at_x_min, tol_at));
    assert!((stroke.span() - (x_max - x_min)).abs() <= tol_len);
    println!(
        "swing {:.9}° (error {:.1e} rad), stroke {:.9} (error {:.1e} of l_rod); cam angles of the extremes off by at most {:.1e} rad",
        swing.span().to_degrees(),
        (swing.span() - (psi_max - psi_min)).abs(),
        stroke.span(),
        (stroke.span() - (x_max - x_min)).abs() / m.l_rod,
        [(swing.max.x, at_max), (swing.min.x, at_min), (stroke.max.x, at_x_max), (stroke.min.x, at_x_min)]
            .iter()
            .map(|&(a, b)| angle_diff(a, b).abs())
            .fold(0.0, f64::max)
    );
    Ok(())
}

/// The double-harmonic law and its first two derivatives by hand: `[s, ds/dphi, d2s/dphi2]`.
fn law(m: &HarmonicCamRocker, phi: f64) -> [f64; 3] {
    let k = m.lift / 2.0;
    [
        k * ((1.0 - phi.cos()) - (1.0 - (2.0 * phi).cos()) / 4.0),
        k * (phi.sin() - (2.0 * phi).sin() / 2.0),
        k * (phi.cos() - (2.0 * phi).cos()),
    ]
}

/// The rocker's angle at follower lift `s`: its pin where the circle about D (radius `c`) meets
/// the circle about the follower's pin F (radius `l_rod`), on the left of D -> F (the rocker to
/// the right of its pivot, the rod above the follower).
fn rocker(m: &HarmonicCamRocker, s: f64) -> f64 {
    let (rx, ry) = left_intersection(m.d_x, m.d_y, m.c, 0.0, m.y0 + s, m.l_rod);
    (ry - m.d_y).atan2(rx - m.d_x)
}

#[test]
fn harmonic_cam_follows_its_law_and_swings_the_rocker() -> Result<(), kinloop::Error> {
    let m = HarmonicCamRocker::default();
    // Positions to rounding; the follower's analogs are the law's own derivatives (rounding of
    // the lift's size); the rocker's against Richardson differences of its closed form with
    // h = 0.01 (errors as estimated for the first drive).
    let (tol_q, tol_d1, tol_d2) = (1e-12, 1e-9, 1e-8);
    let mut guess = m.guess(0.0);
    let mut worst = [0.0f64; 4];
    for k in 0..=360 {
        let phi = f64::from(k).to_radians();
        let s = m.kinematics(phi, &guess)?;
        guess = s.q;
        let [lift, v, a] = law(&m, phi);
        let follower = [s.out.follower.y - (m.y0 + lift), s.dout.follower.y - v, s.d2out.follower.y - a];
        let e_follower = follower.iter().map(|e| e.abs() / m.l_rod).fold(s.out.follower.x.abs() / m.l_rod, f64::max);
        assert!(e_follower <= tol_q, "follower at {k}°: {follower:?}");
        let psi = |p: f64| rocker(&m, law(&m, p)[0]);
        let (fd1, fd2) = richardson(psi, phi, 1e-2);
        let errors = [angle_diff(s.q.psi, psi(phi)).abs(), (s.dq.psi - fd1).abs(), (s.d2q.psi - fd2).abs()];
        assert!(errors[0] <= tol_q, "rocker at {k}°: {} vs {}", s.q.psi, psi(phi));
        assert!(errors[1] <= tol_d1, "rocker's velocity analog at {k}°: {} vs {fd1}", s.dq.psi);
        assert!(errors[2] <= tol_d2, "rocker's acceleration analog at {k}°: {} vs {fd2}", s.d2q.psi);
        worst = [worst[0].max(e_follower), worst[1].max(errors[0]), worst[2].max(errors[1]), worst[3].max(errors[2])];
    }
    // The rest at the bottom: follower and rocker stand still with zero acceleration.
    let bottom = m.solve(0.0)?;
    for v in [bottom.dout.follower.y / m.lift, bottom.d2out.follower.y / m.lift, bottom.dq.psi, bottom.d2q.psi] {
        assert!(v.abs() <= tol_q, "not at rest at the bottom: {v:e}");
    }
    // Rise to the top at half a turn: the follower's range is the lift, the rocker's swing is
    // between its angles at the bottom and at the top (the rocker follows the lift monotonically).
    let turn = m.sampled(0.0, TAU, 361, &m.guess(0.0))?;
    let rise = turn.range(HarmonicCamRocker::COL.follower.y)?;
    let swing = turn.range(HarmonicCamRocker::COL.psi)?;
    assert!((rise.span() - m.lift).abs() <= tol_q * m.lift, "rise {}", rise.span());
    assert!(angle_diff(rise.max.x, PI).abs() <= 1e-10, "the top at {}", rise.max.x);
    let (top, low) = (rocker(&m, m.lift), rocker(&m, 0.0));
    let (hi, lo) = if top > low { (swing.max, swing.min) } else { (swing.min, swing.max) };
    assert!(angle_diff(hi.value, top).abs() <= tol_q && angle_diff(lo.value, low).abs() <= tol_q);
    assert!(angle_diff(hi.x, PI).abs() <= 1e-10, "the rocker's top at {}", hi.x);
    assert!((swing.span() - (top - low).abs()).abs() <= tol_q);
    println!(
        "harmonic cam: max errors follower {:.1e}, rocker {:.1e} / {:.1e} / {:.1e}; swing {:.9}° (error {:.1e})",
        worst[0],
        worst[1],
        worst[2],
        worst[3],
        swing.span().to_degrees(),
        (swing.span() - (top - low).abs()).abs()
    );
    Ok(())
}

/// The rocker's angle at follower lift `s` (the circle intersection of the harmonic drive, the
/// same geometry).
fn dwell_rocker(m: &DwellCamRocker, s: f64) -> f64 {
    let (rx, ry) = left_intersection(m.d_x, m.d_y, m.c, 0.0, m.y0 + s, m.l_rod);
    (ry - m.d_y).atan2(rx - m.d_x)
}

/// The cam angles of a turn: every degree, and each segment's ends exactly and 1e-9, 1e-6 and
/// 1e-3 rad to either side.
fn dwell_samples(m: &DwellCamRocker) -> Vec<f64> {
    let mut phis: Vec<f64> = (0..360).map(|k| f64::from(k).to_radians()).collect();
    for end in [m.phi0, m.phi0 + m.rise, m.phi1, m.phi1 + m.fall] {
        phis.push(end);
        for d in [1e-9, 1e-6, 1e-3] {
            phis.extend([end - d, end + d]);
        }
    }
    phis.sort_by(f64::total_cmp);
    phis
}

#[test]
fn dwell_cam_follows_its_piecewise_law_and_swings_the_rocker() -> Result<(), kinloop::Error> {
    let m = DwellCamRocker::default();
    // The follower's values against the law to rounding (relative to the lift); the rocker's
    // position against the circle intersection, its analogs against the chain rule through the
    // law: psi(s(phi))' = psi'(s) s', '' = psi''(s) s'^2 + psi'(s) s'', with psi' and psi'' as
    // Richardson differences in the lift with h = 0.1 mm (smooth there, unlike the law at its
    // segments' ends).
    let (tol_q, tol_d1, tol_d2) = (1e-12, 1e-11, 1e-9);
    let mut guess = m.guess(0.0);
    let mut worst = [0.0f64; 4];
    let samples = dwell_samples(&m);
    for &phi in &samples {
        let s = m.kinematics(phi, &guess)?;
        guess = s.q;
        let [lift, v, a] = m.law_by_hand(phi);
        let follower = [s.out.follower.y - (m.y0 + lift), s.dout.follower.y - v, s.d2out.follower.y - a];
        let e_follower = follower.iter().map(|e| e.abs() / m.lift).fold(s.out.follower.x.abs(), f64::max);
        assert!(e_follower <= tol_q, "follower at {phi}: {follower:?}");
        // A step of 0.1 mm: the rounding of the second difference, magnified by s'^2 (up to
        // about 320), stays near 1e-10; the truncation (h^4) is below it.
        let (d1s, d2s) = richardson(|x| dwell_rocker(&m, x), lift, 0.1);
        let (fd1, fd2) = (d1s * v, d2s * v * v + d1s * a);
        let errors =
            [angle_diff(s.q.psi, dwell_rocker(&m, lift)).abs(), (s.dq.psi - fd1).abs(), (s.d2q.psi - fd2).abs()];
        assert!(errors[0] <= tol_q, "rocker at {phi}: {} vs {}", s.q.psi, dwell_rocker(&m, lift));
        assert!(errors[1] <= tol_d1, "rocker's velocity analog at {phi}: {} vs {fd1}", s.dq.psi);
        assert!(errors[2] <= tol_d2, "rocker's acceleration analog at {phi}: {} vs {fd2}", s.d2q.psi);
        worst = [worst[0].max(e_follower), worst[1].max(errors[0]), worst[2].max(errors[1]), worst[3].max(errors[2])];
    }
    // The dwells: exactly at rest, at the bottom (zero lift) and at the top (the full lift).
    for phi in [0.0, m.phi0 / 2.0, m.phi1 + m.fall + 0.1, TAU - 1e-3] {
        let s = m.solve(phi)?;
        assert_eq!([s.out.follower.y, s.dout.follower.y, s.d2out.follower.y], [m.y0, 0.0, 0.0], "at {phi}");
        assert_eq!([s.dq.psi, s.d2q.psi], [0.0, 0.0]);
    }
    let top = m.solve((m.phi0 + m.rise + m.phi1) / 2.0)?;
    assert_eq!([top.out.follower.y, top.dout.follower.y, top.d2out.follower.y], [m.y0 + m.lift, 0.0, 0.0]);
    // Mid-rise: the fastest point, 15/8 lift / rise.
    let mid = m.solve(m.phi0 + m.rise / 2.0)?;
    assert!((mid.dout.follower.y - 1.875 * m.lift / m.rise).abs() <= 1e-12 * m.lift);
    println!(
        "dwell cam ({} samples): max errors follower {:.1e} (of the lift), rocker {:.1e} / {:.1e} / {:.1e}",
        samples.len(),
        worst[0],
        worst[1],
        worst[2],
        worst[3]
    );
    Ok(())
}

/// A NaN in the law is reported, not hidden by `clamp`: with `fall = 0` the return is a jump,
/// and exactly at it `(phi - phi1) / fall` is 0 / 0.
#[test]
fn dwell_cam_reports_a_nan_in_its_law() {
    let m = DwellCamRocker { fall: 0.0, ..DwellCamRocker::default() };
    let err = m.solve(m.phi1);
    assert!(err.is_err(), "a NaN lift went unnoticed: {err:?}");
    // Beside the jump the law is defined: the follower is down again, or still up.
    let after = m.solve(m.phi1 + 0.1).expect("after the jump");
    assert_eq!(after.out.follower.y, m.y0);
    let before = m.solve(m.phi1 - 0.1).expect("before the jump");
    assert_eq!(before.out.follower.y, m.y0 + m.lift);
}

/// The default drawing reads the law's `clamp` and `wrap` from its description (`select` and
/// `floor` entries) and draws the follower's pin where the law puts it, in the rise and in both
/// dwells, in the first turn and in others.
#[test]
fn dwell_cam_drawing_follows_the_law() -> Result<(), kinloop::Error> {
    use kinloop::Mechanism;
    use kinloop::drawing::Description;
    let m = DwellCamRocker::default();
    let text = <DwellCamRocker as Mechanism<2, 1, 4>>::DRAWING;
    assert!(text.contains(" floor:") && text.contains(" select:"), "{text}");
    let d = Description::of::<DwellCamRocker, 2, 1, 4>()?;
    let first = [0.1, m.phi0 + 0.4 * m.rise, m.phi1 - 0.1, TAU - 0.1];
    let others = [-TAU, TAU, 2.0 * TAU, 5.0 * TAU].into_iter().flat_map(|turn| first.map(|p| turn + p));
    for phi in first.into_iter().chain(others) {
        let s = m.solve(phi)?;
        let at = d.evaluate(&m.param_values(), &[phi], &[s.q.gamma, s.q.psi])?;
        let pin = [0.0, m.y0 + m.law_by_hand(phi)[0]];
        let nearest = at.joints.iter().map(|j| (j[0] - pin[0]).hypot(j[1] - pin[1])).fold(f64::INFINITY, f64::min);
        assert!(nearest <= 1e-12 * m.y0, "at {phi}: no joint at the follower's pin {pin:?}: {:?}", at.joints);
    }
    Ok(())
}

/// Compares one state with the law of `phi mod 2 pi` (follower, to rounding of the lift) and
/// the rocker's circle intersection and chain rule: the errors of the follower, then of the
/// rocker's angle and its two analogs.
fn dwell_errors(m: &DwellCamRocker, phi: f64, s: &DwellCamRockerState) -> [f64; 4] {
    let [lift, v, a] = m.law_by_hand(phi);
    let follower = [s.out.follower.y - (m.y0 + lift), s.dout.follower.y - v, s.d2out.follower.y - a];
    let e_follower = follower.iter().map(|e| e.abs() / m.lift).fold(s.out.follower.x.abs(), f64::max);
    let (d1s, d2s) = richardson(|x| dwell_rocker(m, x), lift, 0.1);
    let (fd1, fd2) = (d1s * v, d2s * v * v + d1s * a);
    [e_follower, angle_diff(s.q.psi, dwell_rocker(m, lift)).abs(), (s.dq.psi - fd1).abs(), (s.d2q.psi - fd2).abs()]
}

/// The law repeats every turn (`wrap(phi, 2 pi)` in the declaration): over four turns, from
/// `-2 pi` to `6 pi`, the follower and the rocker follow the law of `phi mod 2 pi`, both in
/// point solves at each turn's samples (the segments' ends and the turn's own boundary, exactly
/// and beside them) and along one sweep, which passes the turns' boundaries (in the dwell, at
/// rest) without an event.
#[test]
fn dwell_cam_repeats_its_law_every_turn() -> Result<(), kinloop::Error> {
    let m = DwellCamRocker::default();
    let tol = [1e-12, 1e-12, 1e-11, 1e-9];
    let check = |phi: f64, s: &DwellCamRockerState, worst: &mut [f64; 4]| {
        let e = dwell_errors(&m, phi, s);
        for (k, what) in
            ["follower", "rocker", "rocker's velocity analog", "rocker's acceleration analog"].into_iter().enumerate()
        {
            assert!(e[k] <= tol[k], "{what} at {phi} (turn {}): error {:e}", (phi / TAU).floor(), e[k]);
            worst[k] = worst[k].max(e[k]);
        }
    };
    // Point solves: each turn's samples, and the boundaries between turns.
    let mut worst_points = [0.0f64; 4];
    let mut points = 0;
    let mut guess = m.guess(0.0);
    for turn in -1..3 {
        let base = f64::from(turn) * TAU;
        let mut phis: Vec<f64> = dwell_samples(&m).into_iter().map(|p| base + p).collect();
        for d in [0.0, 1e-12, 1e-9, 1e-6, 1e-3] {
            phis.extend([base - d, base + d]);
        }
        for phi in phis {
            let s = m.kinematics(phi, &guess)?;
            guess = s.q;
            check(phi, &s, &mut worst_points);
            points += 1;
        }
    }
    // At rest at every boundary, and the same state as at 0 (to rounding of the turns).
    let zero = m.solve(0.0)?;
    for turn in [-1.0, 1.0, 2.0, 3.0] {
        let s = m.solve(turn * TAU)?;
        assert_eq!([s.dout.follower.y, s.d2out.follower.y, s.dq.psi, s.d2q.psi], [0.0; 4], "turn {turn}");
        assert_eq!((s.out.follower.y, s.q.psi), (zero.out.follower.y, zero.q.psi), "turn {turn}");
    }
    // Mid-rise in the fourth turn: the fastest point, as in the first.
    let mid = m.solve(3.0 * TAU + m.phi0 + m.rise / 2.0)?;
    assert!((mid.dout.follower.y - 1.875 * m.lift / m.rise).abs() <= 1e-12 * m.lift);
    // One sweep over four turns, every half degree.
    let samples = 4 * 720 + 1;
    let start = m.solve(-TAU)?;
    let mut sweep = m.sweep(-TAU, 3.0 * TAU, samples, &start.q)?;
    let mut worst_sweep = [0.0f64; 4];
    let mut seen = 0;
    for s in sweep.by_ref() {
        let s = s?;
        check(s.input.phi, &s, &mut worst_sweep);
        seen += 1;
    }
    assert_eq!(seen, samples);
    assert!(sweep.events().is_empty(), "events at the turns' boundaries: {:?}", sweep.events());
    println!(
        "dwell cam over four turns: {points} point solves, max errors follower {:.1e} (of the lift), rocker \
         {:.1e} / {:.1e} / {:.1e}; sweep of {seen} samples {:.1e}, {:.1e} / {:.1e} / {:.1e}, no events",
        worst_points[0],
        worst_points[1],
        worst_points[2],
        worst_points[3],
        worst_sweep[0],
        worst_sweep[1],
        worst_sweep[2],
        worst_sweep[3]
    );
    Ok(())
}
