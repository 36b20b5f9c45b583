//! The inverse cycle evaluates each state as the sweep makes it and keeps none: the same points,
//! bit for bit, as the turn's states kept and evaluated after the sweep, and the same errors in
//! the same order of precedence.

use super::*;
use crate::analysis::demo::SliderCrank;
use crate::dynamics::{Body, Coord, Rotation};
use crate::kin::Kin;

/// A slider of mass 2 at the slider crank's unknown (its position along the slide), 0.5 off it.
fn slider_mass() -> MassModel<1, 1, 1> {
    let slider = Body {
        name: "slider".into(),
        mass: 2.0,
        com: [Coord::Unknown(0), Coord::Fixed(0.5)],
        inertia: 0.0,
        rotation: Rotation::None,
    };
    MassModel::new().with_body(slider).unwrap()
}

#[test]
fn the_streamed_cycle_is_the_cycle_of_the_kept_states() {
    let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
    let model = slider_mass();
    let speed = |phi: f64| (10.0 + phi.sin(), phi.cos());
    let law = SpeedLaw::Varying(&speed);
    let streamed = InverseCycle::new(&m, &model, law).start(0.3).samples(97).about([0.1, 0.2]).run().unwrap();
    let states = turn_states(Compiled(&m), 0.3, 97, m.guess_flat(&[0.3])).unwrap();
    let kept = Cycle::over_states(&states, law, |k, omega, eps| {
        let d = model.dynamics(k, &[omega])?;
        let shaking = model.shaking(k, &[omega], &[eps], [0.1, 0.2])?;
        let gamma = d.gamma.as_flattened().as_flattened();
        CyclePoint::of(k.x[0], omega, eps, d.mass.as_flattened(), gamma, &d.forces, shaking)
    })
    .unwrap();
    assert_eq!(streamed.points.len(), 97);
    assert!(streamed.points.iter().all(|p| p.torque != 0.0 && p.shaking.force[0] != 0.0));
    assert_eq!(streamed, kept);
    // The states visited one by one are the states kept.
    let mut visited = Vec::new();
    each_turn_state(Compiled(&m), 0.3, 97, m.guess_flat(&[0.3]), |k| visited.push(*k)).unwrap();
    assert_eq!(visited, states);
}

#[test]
fn a_kinematic_failure_anywhere_on_the_turn_comes_before_a_point_s_error() {
    // A rod shorter than the crank: the slider crank cannot turn past |sin phi| = 0.8, long after
    // the first sample, whose speed law is not a number.
    let m = SliderCrank { r: 1.0, l: 0.8, e: 0.0 };
    let model = slider_mass();
    let speed = |phi: f64| if phi == 0.0 { (f64::NAN, 0.0) } else { (1.0, 0.0) };
    let r = InverseCycle::new(&m, &model, SpeedLaw::Varying(&speed)).samples(36).run();
    assert!(matches!(r, Err(DynamicsError::Kinematics { .. })), "{r:?}");
    // On a turn the mechanism completes, the speed law's error is the first sample's.
    let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
    let r = InverseCycle::new(&m, &model, SpeedLaw::Varying(&speed)).samples(36).run();
    assert!(matches!(r, Err(DynamicsError::BadValue { what: "speed law", .. })), "{r:?}");
}

/// The harmonics, the mean torque and the flywheel take the points as one turn's samples. A
/// cycle of the states of a sweep over the closed turn `[0, 2 pi]` (96 intervals, 97 states, the
/// last repeating the first) was taken for 97 samples of a turn: the mean of its driving torque
/// (`a0` of its harmonics, and `mean_torque`, which checked nothing) came out -0.470, the first
/// sample's -45.6 counted twice over 97, where the turn's is 0 (1e-15), as `Ok`. It is refused,
/// naming the first angle out of place, as is a half turn; the turn's states without their end
/// give the turn's cycle, bit for bit.
#[test]
fn a_cycle_of_other_points_than_one_turn_has_no_harmonics_no_mean_torque_and_no_flywheel() {
    let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
    let model = slider_mass();
    let law = SpeedLaw::Constant(10.0);
    let evaluate = |k: &Kin<1, 1, 1>, omega: f64, eps: f64| {
        let d = model.dynamics(k, &[omega])?;
        let shaking = model.shaking(k, &[omega], &[eps], [0.0, 0.0])?;
        let gamma = d.gamma.as_flattened().as_flattened();
        CyclePoint::of(k.x[0], omega, eps, d.mass.as_flattened(), gamma, &d.forces, shaking)
    };
    let turn = InverseCycle::new(&m, &model, law).samples(96).run().unwrap();
    let closed = crate::analysis::Sampled::sweep(&m, 0.0, TAU, 97, m.guess_flat(&[0.0])).unwrap();
    let states = closed.states();
    assert_eq!(states.len(), 97);
    assert_eq!(states[96].x[0], TAU);
    let wrong = Cycle::over_states(states, law, evaluate).unwrap();
    for r in [
        wrong.torque_harmonics(2).map(|_| ()),
        wrong.shaking_harmonics(2).map(|_| ()),
        wrong.mean_torque().map(|_| ()),
        wrong.flywheel(0.05).map(|_| ()),
    ] {
        let said = r.as_ref().err().map(ToString::to_string).unwrap_or_default();
        assert!(matches!(&r, Err(DynamicsError::BadValue { what: "cycle angle", .. })), "{r:?}");
        assert!(said.contains("leave that state out"), "{said}");
    }
    let half = Cycle { points: turn.points[..48].to_vec() };
    assert!(matches!(half.torque_harmonics(2), Err(DynamicsError::BadValue { what: "cycle angle", .. })));
    assert!(matches!(half.flywheel(0.05), Err(DynamicsError::BadValue { what: "cycle angle", .. })));
    assert!(matches!(half.mean_torque(), Err(DynamicsError::BadValue { what: "cycle angle", .. })));
    // No points are no turn (their mean is 0 / 0), for the flywheel as before.
    let none = Cycle { points: Vec::new() };
    assert!(matches!(none.mean_torque(), Err(DynamicsError::BadValue { what: "cycle points", .. })));
    assert!(matches!(none.flywheel(0.05), Err(DynamicsError::BadValue { what: "cycle points", .. })));
    // Without the repeated end: the turn's cycle. Its mean torque is zero (at constant speed and
    // without loads, the mean of `1/2 J' omega^2` over a turn) up to the rounding of a sum of 96
    // torques, taken as 1e-12 of the largest: far below the -0.470 (1 % of it) of the closed turn.
    let open = Cycle::over_states(&states[..96], law, evaluate).unwrap();
    assert_eq!(open, turn);
    assert_eq!(open.torque_harmonics(2).unwrap(), turn.torque_harmonics(2).unwrap());
    let largest = turn.points.iter().fold(0.0f64, |m, p| m.max(p.torque.abs()));
    let mean = open.mean_torque().unwrap();
    assert!(mean.abs() <= 1e-12 * largest, "{mean} of torques up to {largest}");
    assert!(open.flywheel(0.05).is_ok());
}

/// A cycle or a turn's states beyond the memory budget are refused before the turn is swept,
/// as `samples`: a slider crank that cannot assemble at its start angle (its rod shorter than
/// the crank, the start at `pi / 2`) fails its first solve, so a refusal is the check's and
/// not the sweep's. At the budget the turn starts (and fails on that first solve).
#[test]
fn a_cycle_beyond_the_memory_budget_is_refused_before_the_turn() {
    let m = SliderCrank { r: 1.0, l: 0.8, e: 0.0 };
    let model = slider_mass();
    let start = std::f64::consts::FRAC_PI_2;
    let cycle =
        |samples: usize| InverseCycle::new(&m, &model, SpeedLaw::Constant(1.0)).start(start).samples(samples).run();
    let most = MAX_COLLECTED_BYTES / size_of::<CyclePoint>();
    assert!(most < crate::analysis::MAX_SAMPLES);
    let r = cycle(most + 1);
    assert!(matches!(r, Err(DynamicsError::BadValue { what: "samples", .. })), "{r:?}");
    assert!(r.unwrap_err().to_string().contains("take fewer samples"));
    assert!(matches!(cycle(most), Err(DynamicsError::Kinematics { .. })));

    let states = |samples: usize| turn_states(Compiled(&m), start, samples, m.guess_flat(&[start]));
    let most = MAX_COLLECTED_BYTES / size_of::<Kin<1, 1, 1>>();
    let r = states(most + 1);
    assert!(matches!(r, Err(DynamicsError::BadValue { what: "samples", .. })), "{r:?}");
    assert!(r.unwrap_err().to_string().contains("each_turn_state"));
    assert!(matches!(states(most), Err(DynamicsError::Kinematics { .. })));
}
