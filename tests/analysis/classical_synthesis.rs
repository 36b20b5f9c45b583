//! The classical closed forms' designs analysed by kinloop's own Newton solver, independent of
//! the circle intersections and compatibility equations they were synthesised with: the log10
//! function generator reaches its precision points, and a four-bar built from two Burmester
//! dyads takes its body through all five poses.

use kinloop::deg;
use kinloop::synthesis::classical::{
    BurmesterConfig, Dyad, FunctionMap, Pose, burmester_points, chebyshev_points, freudenstein, structural_error,
};

kinloop::mechanism! {
    /// A four-bar in the frame of Freudenstein's equation: input pivot at the origin, output
    /// pivot at `(d, 0)`, both angles from the X axis.
    #[kinloop(newton)]
    pub struct FunctionFourBar {
        params a, b, c, d;
        input phi;
        unknowns theta = 0.5, psi = 1.5;
        loop abcd: a @ phi + b @ theta == (d, 0) + c @ psi;
    }
}

kinloop::mechanism! {
    /// A four-bar anywhere in the plane: a crank of length `a` about `(ax, ay)`, a rocker of
    /// length `c` about `(dx, dy)`, a coupler `b` between them carrying a point `p` from the
    /// crank's end at `gamma` from the coupler's line.
    #[kinloop(newton)]
    pub struct PoseFourBar {
        params ax, ay, dx, dy, a, b, c, p, gamma;
        input phi;
        unknowns theta = 0, psi = 0;
        loop abcd: (ax, ay) + a @ phi + b @ theta == (dx, dy) + c @ psi;
        point tip = (ax, ay) + a @ phi + p @ (theta + gamma);
    }
}

/// Newton's residual tolerance is relative to the mechanism's size; the angles it settles on
/// are then good to a few roundings of a radian (the Jacobian is well-conditioned away from
/// dead centres, which these positions are not).
const ANGLE: f64 = 1e-12;

#[test]
fn the_log10_generator_reaches_its_precision_points_under_newtons_method() {
    let map = FunctionMap::new(f64::log10, 1.0, 2.0, deg(60.0), deg(90.0), deg(90.0), deg(90.0)).unwrap();
    let xs = chebyshev_points(3, 1.0, 2.0).unwrap();
    let g = freudenstein(&map.precision_points(f64::log10, &xs).unwrap()).unwrap();
    // In millimetres, a ground of 100.
    let l = g.scaled(100.0);
    let m = FunctionFourBar { a: l.input, b: l.coupler, c: l.output, d: l.ground };
    for &x in &xs {
        let (phi, psi) = (map.phi(x), map.psi(x.log10()));
        // Start Newton a few degrees off the answer, on the design's closure.
        let guess = FunctionFourBarUnknowns { theta: coupler_angle(&m, phi, psi) + 0.05, psi: psi - 0.05 };
        let (q, _) = m.position(phi, &guess).unwrap();
        let e = wrap(q.psi - psi);
        assert!(e.abs() < ANGLE, "x = {x}: psi {} vs {psi}, {e:e}", q.psi);
    }
    // A branch-safe sweep over the range: the structural error it sees is the one the library
    // reports (the same samples, analysed by Newton here, by intersecting circles there).
    let (phi0, psi0) = (map.phi(1.0), map.psi(0.0));
    let guess = FunctionFourBarUnknowns { theta: coupler_angle(&m, phi0, psi0), psi: psi0 };
    let run = m.sweep(phi0, map.phi(2.0), 101, &guess).unwrap().run();
    assert_eq!(run.states.len(), 101, "{:?}", run.stop);
    let worst = run.states.iter().map(|s| wrap(s.q.psi - psi_of(&map, s.input.phi)).abs()).fold(0.0, f64::max);
    let report = structural_error(&g, &map, f64::log10, 101).unwrap();
    assert!((worst - report.max).abs() < 1e-11, "sweep {worst} vs report {}", report.max);
}

/// An angle wrapped into `[-pi, pi)`.
fn wrap(angle: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    (angle + PI).rem_euclid(TAU) - PI
}

/// The ideal output angle at the input angle `phi`.
fn psi_of(map: &FunctionMap, phi: f64) -> f64 {
    let x = map.x0 + (phi - map.phi0) / map.dphi * (map.x1 - map.x0);
    map.psi(x.log10())
}

/// The coupler's angle when the input is at `phi` and the output at `psi`.
fn coupler_angle(m: &FunctionFourBar, phi: f64, psi: f64) -> f64 {
    let (bx, by) = (m.a * phi.cos(), m.a * phi.sin());
    let (cx, cy) = (m.d + m.c * psi.cos(), m.c * psi.sin());
    (cy - by).atan2(cx - bx)
}

/// Five poses of a body (its point and angle); not made by any known linkage.
fn poses() -> [Pose; 5] {
    [
        Pose::new(0.0, 0.0, 0.0),
        Pose::new(1.0, 0.2, 0.4),
        Pose::new(1.6, 1.0, 0.9),
        Pose::new(1.1, 2.0, 1.5),
        Pose::new(0.3, 2.4, 2.0),
    ]
}

#[test]
fn a_four_bar_of_two_burmester_dyads_takes_every_pose_under_newtons_method() {
    let poses = poses();
    let found = burmester_points(&poses, &BurmesterConfig::default()).unwrap();
    assert!(found.dyads.len() >= 2, "{found:?}");
    let (crank, rocker) = (&found.dyads[0], &found.dyads[1]);
    let m = pose_four_bar(crank, rocker, &poses[0]);
    for (j, pose) in poses.iter().enumerate() {
        let (k1, k2) = (crank.circle_point_in(&poses[0], pose), rocker.circle_point_in(&poses[0], pose));
        let phi = (k1 - crank.center).angle();
        // Guesses a little off the pose, so that Newton has work to do.
        let guess = PoseFourBarUnknowns { theta: (k2 - k1).angle() + 0.03, psi: (k2 - rocker.center).angle() - 0.03 };
        let s = m.kinematics(phi, &m.position(phi, &guess).unwrap().0).unwrap();
        let tip = s.out.tip;
        assert!((tip.x - pose.point.x).hypot(tip.y - pose.point.y) < 1e-10 * found.size, "pose {j}: {tip:?}");
        // The body's angle: the coupler's, plus the fixed offset of the first pose.
        let offset = pose_angle_offset(crank, rocker, &poses);
        let e = wrap(s.q.theta + offset - pose.angle);
        assert!(e.abs() < ANGLE, "pose {j}: angle off by {e:e}");
    }
}

/// The four-bar whose input is `crank` and whose output is `rocker`, carrying the first pose's
/// point.
fn pose_four_bar(crank: &Dyad, rocker: &Dyad, first: &Pose) -> PoseFourBar {
    let coupler = rocker.circle - crank.circle;
    let to_point = first.point - crank.circle;
    PoseFourBar {
        ax: crank.center.x,
        ay: crank.center.y,
        dx: rocker.center.x,
        dy: rocker.center.y,
        a: crank.radius(),
        b: coupler.norm(),
        c: rocker.radius(),
        p: to_point.norm(),
        gamma: to_point.angle() - coupler.angle(),
    }
}

/// The body's angle minus the coupler line's angle (constant: both turn with the body).
fn pose_angle_offset(crank: &Dyad, rocker: &Dyad, poses: &[Pose]) -> f64 {
    poses[0].angle - (rocker.circle - crank.circle).angle()
}
