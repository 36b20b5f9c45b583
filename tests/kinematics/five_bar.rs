//! A two-input mechanism: the five-bar linkage driven by two cranks. The analogs are partial
//! derivatives with respect to both cranks, checked against Richardson-extrapolated central
//! differences, and the positions against an independent circle-intersection construction.

use kinloop_fixtures::FiveBar;

use crate::support::{analogs_against_differences, five_bar_joint, tol};

const M: FiveBar = FiveBar { a: 1.0, b: 2.5, c: 2.2, d: 1.5, e: 1.2 };

#[test]
fn five_bar_positions_match_circle_intersection() {
    for i in 0..40 {
        for j in 0..40 {
            let (t1, t2) = (1.2 + 0.6 * i as f64 / 40.0, 0.8 + 0.6 * j as f64 / 40.0);
            let st = M.solve([t1, t2]).unwrap();
            let (cx, cy, p2, p3) = five_bar_joint(&M, t1, t2, 1.0);
            // Over this grid links b and c meet at C at 33 degrees or more from a line (the sine
            // of their angle is at least 0.55), far from both folds: the construction (a square
            // root of a difference) and the solve are well conditioned and round to a few ulps
            // of the links' size (measured: under 2e-15). `tol::SOLVE` admits the solve's own
            // tolerance; the 1e-10 this used to allow let a position 1e-11 off pass.
            assert_close!(st.out.pc.x, cx, tol::SOLVE, "({t1}, {t2}): {:?} vs {cx}, {cy}; {:?}", st.out.pc, st.q);
            assert_close!(st.out.pc.y, cy, tol::SOLVE, "({t1}, {t2}): {:?} vs {cx}, {cy}; {:?}", st.out.pc, st.q);
            assert_close!(st.q.phi2, p2, tol::SOLVE);
            assert_close!(st.q.phi3, p3, tol::SOLVE);
        }
    }
}

/// The partial analogs by both cranks, the second ones cross derivatives included, against
/// Richardson-extrapolated central differences of the positions and of the velocity analogs
/// (`analogs_against_differences`), to `tol::FD_FIRST` relative: the cross derivatives'
/// references are good to ~1e-12, where a four-point stencil of positions at h = 1e-4 (rounding
/// ~1e-16 / h^2 = 1e-8) held to 1e-4 let pass a cross derivative 1e-4 off.
#[test]
fn five_bar_partial_analogs_match_finite_differences() {
    for (t1, t2) in [(1.3, 0.9), (1.5, 1.1), (1.7, 1.3), (1.25, 1.35)] {
        let st = M.solve([t1, t2]).unwrap();
        // Quantity k: the unknowns phi2, phi3, then the outputs pc.x, pc.y, spread (flat order).
        let f = &st.flat;
        let first = |i: usize, k: usize| if k < 2 { f.dq[k][i] } else { f.dout[k - 2][i] };
        let second = |i: usize, j: usize, k: usize| if k < 2 { f.d2q[k][i][j] } else { f.d2out[k - 2][i][j] };
        // The flat layout is the named one.
        assert_eq!((first(1, 4), first(0, 1)), (st.dout.spread.th2, st.dq.phi3.th1));
        assert_eq!((second(0, 1, 2), second(1, 1, 0)), (st.d2out.pc.x.th1.th2, st.d2q.phi2.th2.th2));
        let checks = analogs_against_differences(&M, [t1, t2], &f.q, 1e-3);
        // Per input: 5 first analogs and 10 second ones.
        assert_eq!(checks.len(), 2 * 5 * 3);
        for (what, analog, reference) in checks {
            assert_close!(analog, reference, rel = tol::FD_FIRST, "{what} at ({t1}, {t2})");
        }
        for k in 0..5 {
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
