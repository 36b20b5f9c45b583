//! The step budget of a sweep: a bound on the attempts that protects against a sweep that does
//! not advance, counted in windows that must each advance it by a stride (the sample spacing or
//! a quarter of the inputs' unit, the shorter), so that a sweep that advances is never stopped
//! for the length of its range between two samples, and one that crawls is stopped, saying so.

use kinloop_fixtures::cam_linkage::DwellCamRocker;

/// The dwell cam, whose law's corners (the 3-4-5 law's jerk jumps at each segment's ends) take
/// about thirteen times the natural steps a turn, swept over 10,000 radians between two
/// samples: it completes, at the state a point solve gives there. The budget per sample
/// interval stopped it at 6,826 rad, "no progress … (the solution curve is too rough here)",
/// where 10,000 samples over the same range completed.
#[test]
fn a_dwell_cam_sweeps_thousands_of_turns_between_two_samples() {
    let m = DwellCamRocker::default();
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let run = m.sweep(0.0, 1e4, 2, &g).unwrap().run();
    assert!(run.is_completed(), "{:?}", run.stop);
    assert_eq!(run.states.len(), 2);
    let end = &run.states[1];
    assert_eq!(end.input.phi, 1e4);
    let (q, _) = m.position(1e4, &g).unwrap();
    assert!((end.q.gamma - q.gamma).abs() < 1e-9 && (end.q.psi - q.psi).abs() < 1e-9, "{:?} against {q:?}", end.q);
}
