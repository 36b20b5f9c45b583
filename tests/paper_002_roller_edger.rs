//! Paper 002 (SEEDS.md), as printed by `examples/roller_edger.rs`: the roller edger driven by
//! time (`S1 = V1 t`), all four link angles with their angular velocities and accelerations
//! against closed forms derived by hand (law of cosines for contour 1; the triangle O2 B A and
//! its differentiated loop equation for contour 2), and against the numbers the example prints.

kinloop::mechanism! {
    /// Lever-turning mode of the roller edger (as in the example).
    pub struct RollerEdger {
        params l1 = 0.9, l3 = 0.6, l5 = 1.2, alpha = 0.2, v1 = 0.05,
               l2 = 1.0, s2 = 0.1, l4 = 0.7, l6 = 1.4, beta = 0.9;
        input t;
        unknowns phi1 = 1.2, phi3 = -0.8, phi2 = 2.0, phi4 = 0.5;
        let s1 = v1 * t;
        loop o1ao3:  (s1 + l1) @ phi1 + l3 @ phi3 == l5 @ alpha;
        loop o2bao3: (s2 + l2) @ phi2 + l4 @ phi4 + l3 @ phi3 == l6 @ beta;
    }
}

/// Closed forms: `[phi1, phi3, phi2, phi4]`, each with its first and second time derivatives.
fn closed(m: &RollerEdger, t: f64) -> [[f64; 3]; 4] {
    // Contour 1, law of cosines in the triangle O1 A O3.
    let s = m.v1 * t + m.l1;
    let (l3, l5, v) = (m.l3, m.l5, m.v1);
    let c = (l5 * l5 + l3 * l3 - s * s) / (2.0 * l5 * l3);
    let (dc, ddc) = (-s * v / (l5 * l3), -v * v / (l5 * l3));
    let r = 1.0 - c * c;
    let phi3 = [m.alpha - c.acos(), dc / r.sqrt(), ddc / r.sqrt() + dc * dc * c / r.powf(1.5)];
    let k = l5 * l5 - l3 * l3;
    let d = s / (2.0 * l5) + k / (2.0 * l5 * s);
    let dd = v / (2.0 * l5) - k * v / (2.0 * l5 * s * s);
    let ddd = k * v * v / (l5 * s * s * s);
    let r = 1.0 - d * d;
    let phi1 = [m.alpha + d.acos(), -dd / r.sqrt(), -ddd / r.sqrt() - dd * dd * d / r.powf(1.5)];

    // Contour 2: P = O2A = l6 @ beta - l3 @ phi3 is known with its derivatives; the triangle
    // O2 B A gives phi2 (on the branch with B on the left of O2->A), then phi4 points from B
    // to A. Differentiating a @ phi2 + l4 @ phi4 = P (a = s2 + l2) and dotting with the
    // directions e2, e4 of the two links gives the velocities and accelerations.
    let (p3, w3, e3) = (phi3[0], phi3[1], phi3[2]);
    let (s3, c3) = p3.sin_cos();
    let p = [m.l6 * m.beta.cos() - m.l3 * c3, m.l6 * m.beta.sin() - m.l3 * s3];
    let dp = [m.l3 * w3 * s3, -m.l3 * w3 * c3];
    let ddp = [m.l3 * (e3 * s3 + w3 * w3 * c3), m.l3 * (-e3 * c3 + w3 * w3 * s3)];
    let a = m.s2 + m.l2;
    let dist = p[0].hypot(p[1]);
    let gamma = ((a * a + dist * dist - m.l4 * m.l4) / (2.0 * a * dist)).acos();
    let phi2 = p[1].atan2(p[0]) + gamma;
    let phi4 = (p[1] - a * phi2.sin()).atan2(p[0] - a * phi2.cos());
    let (e2, e4) = ([phi2.cos(), phi2.sin()], [phi4.cos(), phi4.sin()]);
    let dot = |u: [f64; 2], v: [f64; 2]| u[0] * v[0] + u[1] * v[1];
    let sin42 = (phi4 - phi2).sin();
    let w2 = dot(dp, e4) / (a * sin42);
    let w4 = -dot(dp, e2) / (m.l4 * sin42);
    let rhs =
        [ddp[0] + a * w2 * w2 * e2[0] + m.l4 * w4 * w4 * e4[0], ddp[1] + a * w2 * w2 * e2[1] + m.l4 * w4 * w4 * e4[1]];
    let acc2 = dot(rhs, e4) / (a * sin42);
    let acc4 = -dot(rhs, e2) / (m.l4 * sin42);
    [phi1, phi3, [phi2, w2, acc2], [phi4, w4, acc4]]
}

#[test]
fn all_links_match_the_closed_forms_over_the_stroke() {
    let m = RollerEdger::default();
    let mut n = 0;
    for s in m.sweep(0.0, 6.0, 601, &m.guess(0.0)).unwrap() {
        let s = s.unwrap();
        let c = closed(&m, s.input.t);
        let got = [
            [s.q.phi1, s.dq.phi1, s.d2q.phi1],
            [s.q.phi3, s.dq.phi3, s.d2q.phi3],
            [s.q.phi2, s.dq.phi2, s.d2q.phi2],
            [s.q.phi4, s.dq.phi4, s.d2q.phi4],
        ];
        for l in 0..4 {
            // Positions within the Newton tolerance (1e-12, well conditioned); the analogs come
            // from the same factorisation; contour 2 inherits contour 1's error.
            for (o, tol) in [1e-12, 1e-12, 1e-12].into_iter().enumerate() {
                assert!(
                    (got[l][o] - c[l][o]).abs() < tol,
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
