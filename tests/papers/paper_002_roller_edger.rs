//! Paper 002 (`docs/papers.md`), the roller edger of `examples/roller_edger.rs` driven by time
//! (`S1 = V1 t`): all four link angles with their angular velocities and accelerations against
//! the closed forms derived by hand (law of cosines for contour 1; the triangle O2 B A and its
//! differentiated loop equation for contour 2), and both against a plain geometric construction
//! (circle intersections) differentiated numerically in time.

use kinloop_fixtures::roller_edger::{RollerEdger, closed, solved};

use crate::support::{circle_point, richardson, stationary, tol};

#[test]
fn all_links_match_the_closed_forms_over_the_stroke() {
    let m = RollerEdger::default();
    let mut n = 0;
    for s in m.sweep(0.0, 6.0, 601, &m.guess(0.0)).unwrap() {
        let s = s.unwrap();
        let (c, got) = (closed(&m, s.input.t), solved(&s));
        for l in 0..4 {
            // Positions within the Newton tolerance (1e-12, well conditioned); the analogs come
            // from the same factorisation, to the same tolerance; contour 2 inherits contour 1's
            // error.
            for o in 0..3 {
                assert_close!(
                    got[l][o],
                    c[l][o],
                    tol::SOLVE,
                    "link {l}, order {o} at t = {}: {} vs {}",
                    s.input.t,
                    got[l][o],
                    c[l][o]
                );
            }
        }
        // With time as the input the analogs are the true angular velocities and accelerations.
        let mo = s.motion(1.0, 0.0).unwrap();
        assert_eq!((mo.qdot.phi4, mo.qddot.phi2), (s.dq.phi4, s.d2q.phi2));
        n += 1;
    }
    assert_eq!(n, 601);
}

/// The four link angles `[phi1, phi3, phi2, phi4]` at time `t` by plain geometry, independent of
/// the closed forms: the joint A from the circles (O1, S1 + l1) and (O3, l3), then B from the
/// circles (O2, s2 + l2) and (A, l4), both on the left of the line between the centres (the
/// declared assembly mode). Contour 1 has its origin at O1, contour 2 at O2.
fn construction(m: &RollerEdger, t: f64) -> [f64; 4] {
    let (o3x, o3y) = (m.l5 * m.alpha.cos(), m.l5 * m.alpha.sin());
    let (ax, ay) = circle_point(0.0, 0.0, m.v1 * t + m.l1, o3x, o3y, m.l3, 1.0);
    let phi3 = (o3y - ay).atan2(o3x - ax);
    // A seen from O2: O2O3 - AO3.
    let (px, py) = (m.l6 * m.beta.cos() - m.l3 * phi3.cos(), m.l6 * m.beta.sin() - m.l3 * phi3.sin());
    let (bx, by) = circle_point(0.0, 0.0, m.s2 + m.l2, px, py, m.l4, 1.0);
    [ay.atan2(ax), phi3, by.atan2(bx), (py - by).atan2(px - bx)]
}

#[test]
fn all_links_match_a_construction_with_differentiated_time() {
    // The solved and the closed-form angles against the construction; the angular velocities and
    // accelerations against its Richardson-extrapolated central differences in time (h = 0.02 s:
    // truncation ~h^4 / 480 |phi^(5)| <= 1e-11 (h = 0.05 leaves 1.2e-10 on phi4'), rounding
    // ~5e-16 / h^2 ~ 1e-12 on the second derivative).
    let m = RollerEdger::default();
    for s in m.sweep(0.0, 6.0, 61, &m.guess(0.0)).unwrap() {
        let s = s.unwrap();
        let t = s.input.t;
        let (c, got, geo) = (closed(&m, t), solved(&s), construction(&m, t));
        for l in 0..4 {
            let (w, e) = richardson(|t| construction(&m, t)[l], t, 0.02);
            for (order, want) in [geo[l], w, e].into_iter().enumerate() {
                // The construction's own rounding (square roots of differences) is ~1e-14; the
                // Newton tolerance 1e-12 bounds the solved angles.
                let tol = [1e-11, 1e-10, 1e-9][order];
                assert_close!(got[l][order], want, tol, "link {l} order {order} at {t}: {} vs {want}", got[l][order]);
                assert_close!(c[l][order], want, tol, "closed form, link {l} order {order} at {t}");
            }
        }
    }
}

#[test]
fn cylinder_one_turns_back_where_it_is_perpendicular_to_link_three() {
    let m = RollerEdger::default();
    // Cylinder 1 stops turning and turns back when it is perpendicular to link 3 (right angle
    // at A: s^2 = l5^2 - l3^2), i.e. at t* = (sqrt(l5^2 - l3^2) - l1) / V1; since
    // 0.9 * 1.2 = l5^2 - l3^2 its angle is the same at both ends of the stroke. The example
    // locates t* as the maximum of phi1 (root of its angular velocity).
    let run = m.sampled(0.0, 6.0, 61, &m.guess(0.0)).unwrap();
    let top = run.range(RollerEdger::COL.phi1).unwrap().max;
    let t_star = ((m.l5 * m.l5 - m.l3 * m.l3).sqrt() - m.l1) / m.v1;
    assert_close!(top.x, t_star, 1e-9, "{} vs {t_star}", top.x);
    let apex = closed(&m, t_star)[0][0];
    assert_close!(top.value, apex, tol::SOLVE);
    // Independently: the construction's phi1 is stationary at t* (located to ~1e-13 / |phi1''|
    // ~ 1e-10 s), and there the cylinder is perpendicular to link 3.
    let geo = construction(&m, t_star);
    assert_close!(stationary(|t| construction(&m, t)[0], 1.0, 5.0), t_star, 1e-8);
    assert!((geo[0] - apex).abs() < 1e-12 && (geo[0] - geo[1]).cos().abs() < 1e-12);
    assert_close!(m.solve(6.0).unwrap().q.phi1, m.solve(0.0).unwrap().q.phi1, tol::SOLVE);
}
