//! Paper 002 (SEEDS.md), as declared and printed by `examples/roller_edger.rs`: the roller
//! edger driven by time (`S1 = V1 t`), all four link angles with their angular velocities and
//! accelerations against the example's closed forms derived by hand (law of cosines for contour
//! 1; the triangle O2 B A and its differentiated loop equation for contour 2), and against the
//! numbers the example prints.

use kinloop_fixtures::roller_edger::{RollerEdger, closed, solved};

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
                assert!(
                    (got[l][o] - c[l][o]).abs() < 1e-12,
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

#[test]
fn numbers_printed_by_the_example() {
    let m = RollerEdger::default();
    // t, phi1, phi3, phi2, phi4 [deg, 4 decimals], w1, w3, w2, w4 [rad/s, 6 decimals].
    let rows = [
        (0.0, 40.4142, -35.1083, 101.4674, 31.3026, 0.014344, -0.086066, -0.045736, 0.053908),
        (3.0, 41.4539, -49.5693, 92.6673, 40.4947, -0.000850, -0.083347, -0.057557, 0.055389),
        (6.0, 40.4142, -64.0633, 80.8384, 51.8208, -0.010758, -0.086066, -0.087070, 0.087444),
    ];
    for (t, a1, a3, a2, a4, w1, w3, w2, w4) in rows {
        let c = closed(&m, t);
        let deg = [c[0][0], c[1][0], c[2][0], c[3][0]].map(f64::to_degrees);
        for (got, want) in deg.iter().zip([a1, a3, a2, a4]) {
            assert!((got - want).abs() < 5.1e-5, "t = {t}: {got} vs {want}");
        }
        for (got, want) in [c[0][1], c[1][1], c[2][1], c[3][1]].iter().zip([w1, w3, w2, w4]) {
            assert!((got - want).abs() < 5.1e-7, "t = {t}: {got} vs {want}");
        }
    }
    // Cylinder 1 stops turning and turns back when it is perpendicular to link 3 (right angle
    // at A: s^2 = l5^2 - l3^2), i.e. at t* = (sqrt(l5^2 - l3^2) - l1) / V1; since
    // 0.9 * 1.2 = l5^2 - l3^2 its angle is the same at both ends of the stroke. The example
    // locates t* as the maximum of phi1 (root of its angular velocity).
    let run = kinloop::analysis::Sampled::sweep(&m, 0.0, 6.0, 61, m.guess(0.0).into()).unwrap();
    let top = run.range("phi1").unwrap().max;
    let t_star = ((m.l5 * m.l5 - m.l3 * m.l3).sqrt() - m.l1) / m.v1;
    assert!((top.x - t_star).abs() < 1e-9, "{} vs {t_star}", top.x);
    let apex = closed(&m, t_star)[0][0];
    assert!((top.value - apex).abs() < 1e-12);
    assert!(
        (t_star - 2.784610).abs() < 5e-7 && (apex.to_degrees() - 41.459156).abs() < 5e-7,
        "{t_star} {}",
        apex.to_degrees()
    );
    assert!((m.solve(6.0).unwrap().q.phi1 - m.solve(0.0).unwrap().q.phi1).abs() < 1e-12);
}
