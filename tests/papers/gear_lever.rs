//! The intermittent-motion gear-lever drive of paper 001 (`docs/papers.md`): carrier + planet pin equals
//! the pin's position along the rocker, `s @ phi` with BOTH the length `s` and the angle `phi`
//! unknown. Checked against the paper's explicit formulas and against central finite
//! differences of the solved positions.

use kinloop_fixtures::gear_lever::GearLever;
use std::f64::consts::PI;

use crate::support::{gear_lever_explicit, tol, wrap};

#[test]
fn gear_lever_matches_explicit_formulas_for_all_k() {
    for k in [1.1, 1.2, 1.3, 1.4, 1.5] {
        let m = GearLever { l_c: 2.0, l_p: k, u: 3.0 };
        let mut guess = m.guess(0.0);
        for i in 0..=720 {
            let a = 2.0 * PI * i as f64 / 720.0;
            let st = m.kinematics(a, &guess).unwrap_or_else(|e| panic!("k = {k}, alpha = {a}: {e}"));
            guess = st.q;
            let [phi, om, eps, s, ds, x] = gear_lever_explicit(2.0, k, 3.0, a);
            // Newton stops at max|f| <= 1e-12, which bounds the position error by about 1e-12
            // times the inverse Jacobian's norm (about 1 here).
            assert!(wrap(st.q.phi - phi).abs() < 1e-11, "phi at {a}: {} vs {phi}", st.q.phi);
            assert_close!(st.q.s, s, 1e-11);
            assert_close!(st.dq.phi, om, <= 1e-9 * om.abs().max(1.0), "omega_r at {a}");
            assert_close!(st.d2q.phi, eps, <= 1e-9 * eps.abs().max(1.0), "eps_r at {a}: {} vs {eps}", st.d2q.phi);
            assert_close!(st.dq.s, ds, <= 1e-9 * ds.abs().max(1.0), "ds at {a}");
            assert_close!(st.out.b.x, x, tol::ULPS, "the pin is an explicit output");
        }
        // The rocker turns once per carrier turn: the continuous solution gains 2 pi.
        assert_close!(guess.phi, 2.0 * PI, 1e-9, "k = {k}: phi ends at {}", guess.phi);
    }
}

#[test]
fn gear_lever_analogs_match_central_finite_differences() {
    let m = GearLever { l_c: 2.0, l_p: 1.3, u: 3.0 };
    let h = 1e-4;
    for i in 0..50 {
        let a = 0.05 + 6.2 * i as f64 / 50.0;
        let st = m.solve(a).unwrap();
        let at = |x: f64| m.position(x, &st.q).unwrap().0;
        let (p, c, n) = (at(a + h), st.q, at(a - h));
        let fd1 = (p.phi - n.phi) / (2.0 * h);
        let fd2 = (p.phi - 2.0 * c.phi + n.phi) / (h * h);
        // Truncation error of the central differences is O(h^2 q''') and O(h^2 q'''').
        assert_close!(st.dq.phi, fd1, 1e-6 * st.dq.phi.abs().max(1.0), "at {a}");
        assert_close!(st.d2q.phi, fd2, 1e-4 * st.d2q.phi.abs().max(1.0), "at {a}: {} vs {fd2}", st.d2q.phi);
        let fds = (p.s - n.s) / (2.0 * h);
        assert_close!(st.dq.s, fds, 1e-6 * st.dq.s.abs().max(1.0));
    }
}

#[test]
fn gear_lever_is_one_coupled_block() {
    // s and phi appear together in both projections: one 2x2 nonlinear block.
    assert_eq!(GearLever::BLOCKS.len(), 1);
    assert_eq!(GearLever::BLOCKS[0].unknowns, &["s", "phi"][..]);
    assert!(!GearLever::BLOCKS[0].linear);
}
