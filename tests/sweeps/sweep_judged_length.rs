//! A sweep never jumps a gap in the input, in any unit, when the unknowns it judges include a
//! length: the sweep's prediction and judge compare every judged unknown against one bound,
//! so a long slide could dilute the bound of an angle.
//!
//! The trap: a slotted rocker, whose slide `s` is judged beside its angle, and beside it a
//! four-bar whose crank cannot pass a gap of 0.33 rad around `phi = pi` (`a + d` exceeds
//! `b + c` by 0.01). Each sweep takes two to four samples, one step straddling the gap, from
//! both assembly modes, with the rocker's crank at twelve phases, at scales 1e-3 to 1e6. The
//! rocker's slide moves smoothly across the gap, and the four-bar assembles on the far side in
//! the same assembly mode: with the prediction and the judge taken out of the sweep (an
//! experiment), 576 of these 768 sweeps complete across the gap. Every sweep must stop at the
//! limit position, at the input the law of cosines gives (`|crank tip - rocker pivot| = b + c`),
//! whatever the unit, on both paths (closed form and Newton).

use kinloop::{Kin, Mechanism, NewtonConfig, Sweep, SweepStop};
use std::f64::consts::TAU;

use crate::support::{four_bar_limit, tol};

kinloop::mechanism! {
    /// A crank `r` at phase `o` driving a block in a slot pivoted at `(h, 0)`, and a four-bar
    /// `a`, `b`, `c`, `d` on the same crank angle.
    pub struct RockerBesideFourBar {
        params a, b, c, d, r, h, o;
        input phi;
        unknowns s = 1, psi = 3, beta = 1, gamma = 2;
        loop slot: r @ (phi + o) == (h, 0) + s @ psi;
        loop four_bar: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

kinloop::mechanism! {
    /// The same, solved by Newton.
    #[kinloop(newton)]
    pub struct RockerBesideFourBarNewton {
        params a, b, c, d, r, h, o;
        input phi;
        unknowns s = 1, psi = 3, beta = 1, gamma = 2;
        loop slot: r @ (phi + o) == (h, 0) + s @ psi;
        loop four_bar: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

/// The trap at scale `k` (every length times `k`) with the rocker's crank at phase `o`.
fn trap(k: f64, o: f64) -> RockerBesideFourBar {
    RockerBesideFourBar { a: k, b: 2.5 * k, c: 1.49 * k, d: 3.0 * k, r: k, h: 2.0 * k, o }
}

/// The trap solved by Newton.
fn trap_newton(k: f64, o: f64) -> RockerBesideFourBarNewton {
    let t = trap(k, o);
    RockerBesideFourBarNewton { a: t.a, b: t.b, c: t.c, d: t.d, r: t.r, h: t.h, o }
}

/// The crank angle where the four-bar's coupler and rocker stretch out: the crank's tip is
/// `b + c` from the rocker's pivot (law of cosines; the same at every scale).
fn limit() -> f64 {
    let (a, b, c, d) = (1.0f64, 2.5, 1.49, 3.0);
    four_bar_limit(a, d, b + c)
}

/// Every sweep of the trap, built by `build(k, o)`, stops at the limit position.
fn check<M: Mechanism<4, 1, 0>>(build: impl Fn(f64, f64) -> M) {
    let cfg = NewtonConfig::default();
    let limit = limit();
    assert_close!(limit, 2.978_213_783_015_119, tol::ULPS);
    let mut sweeps = 0;
    for k in [1e-3, 1.0, 1e3, 1e6] {
        for phase in 0..12 {
            let o = f64::from(phase) * TAU / 12.0;
            let m = build(k, o);
            // Both assembly modes of the four-bar (coupler and rocker above or below the line
            // of centres); the rocker's slide positive, as guessed.
            for mode in [1.0, -1.0] {
                for (from, samples) in [(2.0, 2), (2.3, 2), (2.5, 2), (2.7, 2), (2.9, 2), (2.0, 3), (1.5, 3), (2.2, 4)]
                {
                    let guess = [2.0 * k, 3.0 + o, mode, 2.0 * mode];
                    let start = m.kinematics_flat(&[from], &guess, &cfg).unwrap();
                    let to = TAU - from;
                    let run = Sweep::<_, Kin<4, 1, 0>, 4, 1, 0>::new(&m, [from], [to], samples, start.q).unwrap().run();
                    let at = format!("k = {k:e}, o = {o:.3}, mode {mode}, from {from} in {samples} samples");
                    let SweepStop::LimitPosition(event) = &run.stop else {
                        panic!("{at}: the sweep did not stop at the limit position: {:?}", run.stop);
                    };
                    assert_close!(
                        event.x[0],
                        limit,
                        tol::LOCATED,
                        "{at}: limit at {} (law of cosines {limit})",
                        event.x[0]
                    );
                    assert!(run.states.iter().all(|st| st.x[0] < limit), "{at}: a sample past the limit");
                    sweeps += 1;
                }
            }
        }
    }
    assert_eq!(sweeps, 4 * 12 * 2 * 8);
}

#[test]
fn a_judged_length_never_lets_a_sweep_jump_a_gap_in_any_unit() {
    check(trap);
}

#[test]
fn nor_by_newton() {
    check(trap_newton);
}
