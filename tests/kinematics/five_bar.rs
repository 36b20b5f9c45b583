//! A two-input mechanism: the five-bar linkage driven by two cranks. The analogs are partial
//! derivatives with respect to both cranks, checked against central finite differences, and the
//! positions against an independent circle-intersection construction.

use kinloop_fixtures::FiveBar;

use crate::support::{five_bar_joint, tol};

const M: FiveBar = FiveBar { a: 1.0, b: 2.5, c: 2.2, d: 1.5, e: 1.2 };

#[test]
fn five_bar_positions_match_circle_intersection() {
    for i in 0..40 {
        for j in 0..40 {
            let (t1, t2) = (1.2 + 0.6 * i as f64 / 40.0, 0.8 + 0.6 * j as f64 / 40.0);
            let st = M.solve([t1, t2]).unwrap();
            let (cx, cy, p2, p3) = five_bar_joint(&M, t1, t2, 1.0);
            // The construction's own rounding (a square root of a difference) is ~1e-12.
            assert_close!(st.out.pc.x, cx, 1e-10, "({t1}, {t2}): {:?} vs {cx}, {cy}; {:?}", st.out.pc, st.q);
            assert_close!(st.out.pc.y, cy, 1e-10, "({t1}, {t2}): {:?} vs {cx}, {cy}; {:?}", st.out.pc, st.q);
            assert_close!(st.q.phi2, p2, 1e-10);
            assert_close!(st.q.phi3, p3, 1e-10);
        }
    }
}

#[test]
fn five_bar_partial_analogs_match_finite_differences() {
    let h = 1e-4;
    for (t1, t2) in [(1.3, 0.9), (1.5, 1.1), (1.7, 1.3), (1.25, 1.35)] {
        let st = M.solve([t1, t2]).unwrap();
        let q = |a: f64, b: f64| {
            let s = M.kinematics([a, b], &st.q).unwrap();
            [s.q.phi2, s.q.phi3, s.out.pc.x, s.out.pc.y, s.out.spread]
        };
        // Quantity k: the unknowns phi2, phi3, then the outputs pc.x, pc.y, spread (flat order).
        let f = &st.flat;
        let first = |i: usize, k: usize| if k < 2 { f.dq[k][i] } else { f.dout[k - 2][i] };
        let second = |i: usize, j: usize, k: usize| if k < 2 { f.d2q[k][i][j] } else { f.d2out[k - 2][i][j] };
        // The flat layout is the named one.
        assert_eq!((first(1, 4), first(0, 1)), (st.dout.spread.th2, st.dq.phi3.th1));
        assert_eq!((second(0, 1, 2), second(1, 1, 0)), (st.d2out.pc.x.th1.th2, st.d2q.phi2.th2.th2));
        let c = q(t1, t2);
        let shift = |i: usize, s: f64| if i == 0 { (t1 + s, t2) } else { (t1, t2 + s) };
        for i in 0..2 {
            let (pa, pb) = shift(i, h);
            let (ma, mb) = shift(i, -h);
            let (p, m) = (q(pa, pb), q(ma, mb));
            for k in 0..5 {
                let fd = (p[k] - m[k]) / (2.0 * h);
                assert_close!(first(i, k), fd, 1e-6, "d/dth{} of #{k}: {} vs {fd}", i + 1, first(i, k));
                let fd2 = (p[k] - 2.0 * c[k] + m[k]) / (h * h);
                assert_close!(second(i, i, k), fd2, 1e-4, "d2/dth{}^2 of #{k}: {} vs {fd2}", i + 1, second(i, i, k));
            }
        }
        // Mixed partial by the four-point stencil.
        let (pp, pm, mp, mm) = (q(t1 + h, t2 + h), q(t1 + h, t2 - h), q(t1 - h, t2 + h), q(t1 - h, t2 - h));
        for k in 0..5 {
            let fd = (pp[k] - pm[k] - mp[k] + mm[k]) / (4.0 * h * h);
            assert_close!(second(0, 1, k), fd, 1e-4, "mixed #{k}: {} vs {fd}", second(0, 1, k));
            assert_eq!(second(0, 1, k), second(1, 0, k), "second analogs are symmetric");
        }
    }
}

#[test]
fn five_bar_true_motion_sums_over_inputs() {
    let st = M.solve([1.4, 1.0]).unwrap();
    let (w1, w2, e1, e2) = (2.0, -1.5, 0.3, 0.7);
    let mo = st.motion([w1, w2], [e1, e2]).unwrap();
    let d = st.dq.phi2;
    let dd = st.d2q.phi2;
    let v = d.th1 * w1 + d.th2 * w2;
    let a = dd.th1.th1 * w1 * w1 + 2.0 * dd.th1.th2 * w1 * w2 + dd.th2.th2 * w2 * w2 + d.th1 * e1 + d.th2 * e2;
    assert_close!(mo.qdot.phi2, v, tol::SOLVE);
    assert_close!(mo.qddot.phi2, a, tol::SOLVE);
}
