//! Paper 003 (`docs/papers.md`), the mechanism of `examples/class_four.rs`: a class IV mechanism (crank OA,
//! ternary links CAE and DBF, binary links CD and EF). The coupled group is one block; the loops
//! close over a full turn; the analogs agree with finite differences; and the positions agree
//! with the paper's own method, solved independently: track the free angle of link DBF until
//! the two four-bars close together (here by bisection on the closure of EF).

use std::f64::consts::TAU;

use kinloop_fixtures::ClassFour;

use crate::support::{bisect, newton_to_default_step, richardson, tol, wrap};

/// The paper's way, independently: for a trial angle `th2` of link DBF, D and F are known; C is
/// the intersection of the circles (A, AC) and (D, CD) on the side `side` of A->D; then E
/// follows from the ternary link CAE, and the trial is right when |EF| = ef. Returns
/// `(th1, psi1, psi2, |EF| - ef)`.
fn close_with(m: &ClassFour, phi: f64, th2: f64, side: f64) -> (f64, f64, f64, f64) {
    let (ax, ay) = (m.oa * phi.cos(), m.oa * phi.sin());
    let (dx, dy) = (m.xb + m.bd * th2.cos(), m.yb + m.bd * th2.sin());
    let (ux, uy) = (dx - ax, dy - ay);
    let dist = ux.hypot(uy);
    let along = (m.ac * m.ac - m.cd * m.cd + dist * dist) / (2.0 * dist);
    let h = (m.ac * m.ac - along * along).sqrt();
    let (cx, cy) = (ax + (along * ux - side * h * uy) / dist, ay + (along * uy + side * h * ux) / dist);
    let th1 = (cy - ay).atan2(cx - ax);
    let psi1 = (dy - cy).atan2(dx - cx);
    let (ex, ey) = (ax + m.ae * (th1 + m.alpha_a).cos(), ay + m.ae * (th1 + m.alpha_a).sin());
    let (fx, fy) = (m.xb + m.bf * (th2 + m.alpha_b).cos(), m.yb + m.bf * (th2 + m.alpha_b).sin());
    (th1, psi1, (fy - ey).atan2(fx - ex), (fx - ex).hypot(fy - ey) - m.ef)
}

#[test]
fn the_class_four_group_is_one_block() {
    let b = ClassFour::BLOCKS;
    assert_eq!(b.len(), 1, "{b:?}");
    assert_eq!(b[0].unknowns, &["th1", "th2", "psi1", "psi2"][..]);
    assert!(!b[0].linear);
}

#[test]
fn full_turn_against_the_tracking_solution() {
    let m = ClassFour::default();
    let states: Vec<_> = m.sweep(0.0, TAU, 721, &m.guess(0.0)).unwrap().collect::<Result<_, _>>().unwrap();
    // Which intersection of the circles is this assembly: the side of C from A->D, at the start.
    let s0 = &states[0];
    let (ax, ay) = (1.0, 0.0);
    let cross = (s0.out.d.x - ax) * (s0.out.c.y - ay) - (s0.out.d.y - ay) * (s0.out.c.x - ax);
    let side = cross.signum();
    let mut th2 = s0.q.th2 + 0.02; // the tracker's own start, off the solution
    for s in &states {
        let phi = s.input.phi;
        assert!(m.residual(phi, &s.q).iter().all(|r| r.abs() < tol::SOLVE), "loops open at {phi}");
        // Track: bracket the root of the EF closure near the previous angle, then bisect.
        let g = |t: f64| close_with(&m, phi, t, side).3;
        let (lo, hi) = (th2 - 0.05, th2 + 0.05);
        assert!(g(lo) * g(hi) < 0.0, "no bracket at {phi}");
        th2 = bisect(g, lo, hi);
        let (th1, psi1, psi2, _) = close_with(&m, phi, th2, side);
        // The solution's sensitivity to the loop residual is ~1 (well conditioned).
        for (got, want, name) in
            [(s.q.th1, th1, "th1"), (s.q.th2, th2, "th2"), (s.q.psi1, psi1, "psi1"), (s.q.psi2, psi2, "psi2")]
        {
            assert!(wrap(got - want).abs() < 1e-11, "{name} at phi = {phi}: {got} vs {want}");
        }
    }
    // A full turn brings the group back (a crank-driven, fully rotatable linkage).
    let (a, b) = (states[0].q, states[720].q);
    assert_close!(a.th1, b.th1, 1e-11);
    assert_close!(a.psi2, b.psi2, 1e-11);
    // Well conditioned throughout.
    assert!(states.iter().all(|s| s.health.min_pivot > 0.5));
}

#[test]
fn analogs_match_finite_differences() {
    let m = ClassFour::default();
    // Positions solved until the Newton step is below 1e-13 (1 + |q|); Richardson-extrapolated
    // central differences with h = 1e-2: truncation ~1e-10, position errors give ~5e-11 and
    // ~3e-8 on the first and second derivatives.
    let step = newton_to_default_step();
    let h = 1e-2;
    for i in 0..36 {
        let phi = 0.05 + TAU * i as f64 / 36.0;
        let s = m.solve(phi).unwrap();
        let q = |x: f64| -> [f64; 4] { m.position_with(x, &s.q, &step).unwrap().0.into() };
        let (dq, d2q): ([f64; 4], [f64; 4]) = (s.dq.into(), s.d2q.into());
        for u in 0..4 {
            let (f1, f2) = richardson(|x| q(x)[u], phi, h);
            let name = ClassFour::UNKNOWNS[u];
            assert_close!(dq[u], f1, tol::FD_FIRST * dq[u].abs().max(1.0), "d{name} at {phi}: {} vs {f1}", dq[u]);
            assert_close!(d2q[u], f2, tol::FD_SECOND * d2q[u].abs().max(1.0), "d2{name} at {phi}: {} vs {f2}", d2q[u]);
        }
    }
}

#[test]
fn rows_printed_by_the_example_against_the_tracking_solution() {
    let m = ClassFour::default();
    // The example's sweep: 721 samples over a turn, every half degree; it prints every 30th
    // degree. The rows against the paper's method (bisection on the EF closure, bracketed about
    // the solved th2), the velocity analogs against its Richardson-extrapolated differences
    // (h = 1e-2: truncation ~1e-10; the bisection is exact to rounding, ~1e-15 / h noise).
    let states: Vec<_> = m.sweep(0.0, TAU, 721, &m.guess(0.0)).unwrap().collect::<Result<_, _>>().unwrap();
    let s0 = &states[0];
    let side = ((s0.out.d.x - 1.0) * s0.out.c.y - s0.out.d.y * (s0.out.c.x - 1.0)).signum();
    for s in states.iter().step_by(60) {
        let phi = s.input.phi;
        let track = |phi: f64| {
            let th2 = bisect(|t| close_with(&m, phi, t, side).3, s.q.th2 - 0.05, s.q.th2 + 0.05);
            let (th1, psi1, psi2, _) = close_with(&m, phi, th2, side);
            [th1, th2, psi1, psi2]
        };
        let want = track(phi);
        let got: [f64; 4] = s.q.into();
        let dq: [f64; 4] = s.dq.into();
        for u in 0..4 {
            assert!(wrap(got[u] - want[u]).abs() < 1e-11, "{} at {phi}", ClassFour::UNKNOWNS[u]);
            let (fd, _) = richardson(|x| track(x)[u], phi, 1e-2);
            assert_close!(dq[u], fd, tol::FD_FIRST * dq[u].abs().max(1.0), "d{} at {phi}", ClassFour::UNKNOWNS[u]);
        }
    }
}
