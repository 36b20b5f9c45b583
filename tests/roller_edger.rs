//! The roller edger of SEEDS.md (paper 002), driven by time: hydraulic cylinder 1 extends at
//! constant speed, `S1 = V1 t`. Both contours, against closed forms derived from the triangles
//! (law of cosines) and their time derivatives derived by hand.

kinloop::mechanism! {
    /// Lever-turning mode of the roller edger. Contour O1 A O3 O1: cylinder 1 (pivot O1, length
    /// `s1 + l1`) and link 3 (`l3`, turning about O3), frame O1O3 = `l5 @ alpha`. Contour
    /// O2 B A O3 O2: cylinder 2 (pivot O2, length `s2 + l2`), link 4 from B to A (`l4`), frame
    /// O2O3 = `l6 @ beta`.
    pub struct RollerEdger {
        params l1, l3, l5, alpha, v1, l2, s2, l4, l6, beta;
        input t;
        unknowns phi1 = 1.0, phi3 = -1.0, phi2 = 2.0, phi4 = 0.5;
        let s1 = v1 * t;
        loop o1ao3:  (s1 + l1) @ phi1 + l3 @ phi3 == l5 @ alpha;
        loop o2bao3: (s2 + l2) @ phi2 + l4 @ phi4 + l3 @ phi3 == l6 @ beta;
    }
}

const M: RollerEdger =
    RollerEdger { l1: 0.9, l3: 0.6, l5: 1.2, alpha: 0.2, v1: 0.05, l2: 1.0, s2: 0.1, l4: 0.7, l6: 1.4, beta: 0.9 };

/// phi3(t) = alpha - acos(c), phi1(t) = alpha + acos(d) with their first and second time
/// derivatives. (SEEDS.md prints phi1 = alpha - acos(d) next to phi3 = alpha - acos(c); those two
/// signs describe different assembly modes: with phi1 = alpha - acos(d) the link satisfies
/// phi3 = alpha + acos(c). The consistent pair is used here.)
fn contour1(m: &RollerEdger, t: f64) -> [[f64; 3]; 2] {
    let s = m.v1 * t + m.l1;
    let (l3, l5, v) = (m.l3, m.l5, m.v1);
    let c = (l5 * l5 + l3 * l3 - s * s) / (2.0 * l5 * l3);
    let dc = -s * v / (l5 * l3);
    let ddc = -v * v / (l5 * l3);
    let r = 1.0 - c * c;
    let phi3 = m.alpha - c.acos();
    let dphi3 = dc / r.sqrt();
    let ddphi3 = ddc / r.sqrt() + dc * dc * c / r.powf(1.5);
    let k = l5 * l5 - l3 * l3;
    let d = s / (2.0 * l5) + k / (2.0 * l5 * s);
    let dd = v / (2.0 * l5) - k * v / (2.0 * l5 * s * s);
    let ddd = k * v * v / (l5 * s * s * s);
    let r = 1.0 - d * d;
    let phi1 = m.alpha + d.acos();
    let dphi1 = -dd / r.sqrt();
    let ddphi1 = -ddd / r.sqrt() - dd * dd * d / r.powf(1.5);
    [[phi1, dphi1, ddphi1], [phi3, dphi3, ddphi3]]
}

#[test]
fn roller_edger_matches_closed_forms_in_time() {
    let mut guess = M.guess(0.0);
    guess.phi1 = M.alpha + 1.0;
    guess.phi3 = M.alpha - 1.0;
    for i in 0..=400 {
        let t = 6.0 * i as f64 / 400.0;
        let st = M.kinematics(t, &guess).unwrap_or_else(|e| panic!("t = {t}: {e}"));
        guess = st.q;
        let [c1, c3] = contour1(&M, t);
        let got1 = [st.q.phi1, st.dq.phi1, st.d2q.phi1];
        let got3 = [st.q.phi3, st.dq.phi3, st.d2q.phi3];
        for o in 0..3 {
            let tol = if o == 0 { 1e-12 } else { 1e-9 };
            assert!(
                (got1[o] - c1[o]).abs() <= tol * c1[o].abs().max(1.0),
                "phi1 order {o} at t = {t}: {} vs {}",
                got1[o],
                c1[o]
            );
            assert!(
                (got3[o] - c3[o]).abs() <= tol * c3[o].abs().max(1.0),
                "phi3 order {o} at t = {t}: {} vs {}",
                got3[o],
                c3[o]
            );
        }
        // Time is the input: true angular velocities are the analogs themselves.
        let mo = st.motion(1.0, 0.0).unwrap();
        assert_eq!(mo.qdot.phi3, st.dq.phi3);
        assert_eq!(mo.qddot.phi1, st.d2q.phi1);

        // Second contour: triangle O2 B A with O2A = O2O3 - A->O3 known from the first.
        let (ax, ay) = (M.l6 * M.beta.cos() - M.l3 * st.q.phi3.cos(), M.l6 * M.beta.sin() - M.l3 * st.q.phi3.sin());
        let dist = ax.hypot(ay);
        let sb = M.s2 + M.l2;
        let gamma = ((sb * sb + dist * dist - M.l4 * M.l4) / (2.0 * sb * dist)).acos();
        let base = ay.atan2(ax);
        let phi2 = if (st.q.phi2 - (base + gamma)).abs() < (st.q.phi2 - (base - gamma)).abs() {
            base + gamma
        } else {
            base - gamma
        };
        let (bx, by) = (sb * phi2.cos(), sb * phi2.sin());
        let phi4 = (ay - by).atan2(ax - bx);
        // The construction inherits phi3's error and its own rounding.
        assert!((st.q.phi2 - phi2).abs() < 1e-10, "phi2 at {t}");
        assert!((st.q.phi4 - phi4).abs() < 1e-10, "phi4 at {t}: {} vs {phi4}", st.q.phi4);
    }
}

#[test]
fn roller_edger_solves_contour_one_before_contour_two() {
    let b = RollerEdger::BLOCKS;
    assert_eq!(b.len(), 2);
    assert_eq!(b[0].unknowns, &["phi1", "phi3"]);
    assert_eq!(b[1].unknowns, &["phi2", "phi4"]);
}
