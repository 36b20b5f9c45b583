//! A sweep over a given, unevenly spaced list of inputs, checked against the four-bar's closed
//! form (intersection of two circles) on one assembly branch throughout.

use kinloop_fixtures::FourBar;
use std::f64::consts::TAU;

use crate::support::{four_bar_joint, tol};

#[test]
fn uneven_inputs_stay_on_one_branch() {
    // A crank-rocker: the crank turns fully, no limit position of the input.
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.0 };
    // Quadratically spaced over two turns, with a repeat and a long jump back.
    let mut inputs: Vec<f64> = (0..=40).map(|k| 2.0 * TAU * (k as f64 / 40.0).powi(2)).collect();
    inputs.insert(5, inputs[5]);
    inputs.push(0.25);
    let g = m.guess(inputs[0]);
    let run = m.sweep_at(inputs.iter().copied(), &g);
    assert!(run.is_completed() && run.events.is_empty(), "{:?}", run.stop);
    let states = run.into_result().unwrap();
    assert_eq!(states.len(), inputs.len());
    let first = states[0].out.pc;
    let side =
        if (four_bar_joint(m.a, m.b, m.c, m.d, inputs[0], 1.0).unwrap().1 - first.y).abs() < 1e-9 { 1.0 } else { -1.0 };
    for (s, &phi) in states.iter().zip(&inputs) {
        assert_eq!(s.input.phi, phi);
        let (cx, cy) = four_bar_joint(m.a, m.b, m.c, m.d, phi, side).unwrap();
        // Lengths of order 3: a few ulps of the closed form's rounding.
        assert_close!(s.out.pc.x, cx, tol::SOLVE, "phi = {phi}");
        assert_close!(s.out.pc.y, cy, tol::SOLVE, "phi = {phi}");
    }
}

#[test]
fn a_limit_position_between_inputs_is_a_typed_error() {
    // A double rocker: the crank cannot pass phi where |BD| = b + c.
    let m = FourBar { a: 2.0, b: 1.0, c: 1.5, d: 3.0 };
    let g = m.position(0.3, &m.guess(0.3)).unwrap().0;
    let run = m.sweep_at([0.3, 0.5, 3.0], &g);
    // The two inputs before the limit position are kept; the stop says where it is: where
    // |BD| = b + c, by the law of cosines.
    assert_eq!(run.states.len(), 2);
    let (a, b, c, d) = (m.a, m.b, m.c, m.d);
    let limit = ((a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d)).acos();
    match &run.stop {
        kinloop::SweepStop::LimitPosition(ev) => assert!((ev.x[0] - limit).abs() < 1e-9, "{ev:?} vs {limit}"),
        other => panic!("{other:?}"),
    }
    assert_eq!(run.events.len(), 1);
    let err = run.into_result().unwrap_err();
    assert!(matches!(err, kinloop::Error::SweepStopped { .. }), "{err}");
    // No inputs, no states.
    assert!(m.sweep_at(Vec::<f64>::new(), &g).into_result().unwrap().is_empty());
}

/// An input of the list that is not finite stops the run there as an input not finite, named
/// as the input (not as the end `to` of a stretch, which the caller never gave), the states
/// before it kept.
#[test]
fn an_input_of_the_list_not_finite_is_named_as_the_input() {
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.0 };
    let g = m.guess(0.0);
    for bad in [f64::NAN, f64::INFINITY] {
        let run = m.sweep_at([0.0, 0.5, bad, 1.0], &g);
        assert_eq!(run.states.len(), 2);
        match &run.stop {
            kinloop::SweepStop::Failed(kinloop::Error::NonFinite { what, name, value, .. }) => {
                assert_eq!((*what, name.as_ref()), (kinloop::Quantity::Input, "phi"));
                assert!(value.is_nan() == bad.is_nan(), "{value}");
            }
            other => panic!("{other:?}"),
        }
        let message = run.into_result().unwrap_err().to_string();
        assert!(message.starts_with("input `phi` is not finite"), "{message}");
    }
}

/// Every state of `sweep_at` is at the input asked for, bit for bit, however far apart the
/// inputs lie: a stretch's sweep ends at `from + 1 * (to - from)`, which from `1e6` to `1e-10`
/// is `1.164e-10` (the state there was returned for `1e-10`; from `1e4`, `1.0004e-10`), and
/// `1e-300` came out 0. The
/// states there against the closed form. (A `Sweep`'s own last sample keeps that rounding, as
/// documented: a test of it costs every sample five instructions.)
#[test]
fn every_state_is_at_the_input_asked_for() {
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let inputs = [1e4, 1e-10, 0.1, 0.7, 1e4 + 0.3, -3.3, 1e-300, 1e4, 1e4];
    let g = m.position(inputs[0], &m.guess(inputs[0])).unwrap().0;
    let side = |phi: f64, y: f64| (four_bar_joint(m.a, m.b, m.c, m.d, phi, 1.0).unwrap().1 - y).abs() < 1e-9;
    let side = if side(inputs[0], m.solve(inputs[0]).unwrap().out.pc.y) { 1.0 } else { -1.0 };
    let states = m.sweep_at(inputs, &g).into_result().unwrap();
    assert_eq!(states.len(), inputs.len());
    for (s, &phi) in states.iter().zip(&inputs) {
        assert_eq!(s.input.phi, phi);
        let (cx, cy) = four_bar_joint(m.a, m.b, m.c, m.d, phi, side).unwrap();
        // Lengths of order 3 at angles up to 1e4 rad, whose doubles are 1.8e-12 apart.
        assert_close!(s.out.pc.x, cx, 1e-11, "phi = {phi}");
        assert_close!(s.out.pc.y, cy, 1e-11, "phi = {phi}");
    }
    // Ranges whose end `from + (to - from)` rounds off `to` (each of these does).
    for (from, to) in [(5.2755, -4.8986), (-9.4911, 0.8282), (1e4, 0.7), (0.3, 1e-300)] {
        assert_ne!(from + (to - from), to);
        let g = m.position(from, &m.guess(from)).unwrap().0;
        let states = m.sweep_at([from, to], &g).into_result().unwrap();
        assert_eq!(states[1].input.phi, to, "{from} to {to}");
    }
}
