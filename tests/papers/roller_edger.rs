//! The roller edger of paper 002 (`docs/papers.md`), the gallery's mechanism, driven by time:
//! hydraulic cylinder 1 extends at constant speed, `S1 = V1 t`. Contour 1 against the closed
//! forms (law of cosines and its time derivatives derived by hand; the paper
//! prints `phi1 = alpha - acos(d)` next to `phi3 = alpha - acos(c)`, signs of two different
//! assembly modes: the consistent pair is used), contour 2 against a triangle construction.

use kinloop_fixtures::roller_edger::{RollerEdger, closed, solved};

use crate::support::tol;

const M: RollerEdger =
    RollerEdger { l1: 0.9, l3: 0.6, l5: 1.2, alpha: 0.2, v1: 0.05, l2: 1.0, s2: 0.1, l4: 0.7, l6: 1.4, beta: 0.9 };

#[test]
fn roller_edger_matches_closed_forms_in_time() {
    let mut guess = M.guess(0.0);
    guess.phi1 = M.alpha + 1.0;
    guess.phi3 = M.alpha - 1.0;
    for i in 0..=400 {
        let t = 6.0 * i as f64 / 400.0;
        let st = M.kinematics(t, &guess).unwrap_or_else(|e| panic!("t = {t}: {e}"));
        guess = st.q;
        let ([c1, c3, _, _], [got1, got3, _, _]) = (closed(&M, t), solved(&st));
        for o in 0..3 {
            let tol = if o == 0 { tol::SOLVE } else { 1e-9 };
            assert_close!(got1[o], c1[o], <= tol * c1[o].abs().max(1.0), "phi1 order {o} at t = {t}: {} vs {}", got1[o], c1[o]);
            assert_close!(got3[o], c3[o], <= tol * c3[o].abs().max(1.0), "phi3 order {o} at t = {t}: {} vs {}", got3[o], c3[o]);
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
        assert_close!(st.q.phi2, phi2, 1e-10, "phi2 at {t}");
        assert_close!(st.q.phi4, phi4, 1e-10, "phi4 at {t}: {} vs {phi4}", st.q.phi4);
    }
}

#[test]
fn roller_edger_solves_contour_one_before_contour_two() {
    let b = RollerEdger::BLOCKS;
    assert_eq!(b.len(), 2);
    assert_eq!(b[0].unknowns, &["phi1", "phi3"][..]);
    assert_eq!(b[1].unknowns, &["phi2", "phi4"][..]);
}
