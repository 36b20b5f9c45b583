//! The inverse cycle evaluates each state as the sweep makes it and keeps none: the same points,
//! bit for bit, as the turn's states kept and evaluated after the sweep, and the same errors in
//! the same order of precedence.

use super::*;
use crate::analysis::demo::SliderCrank;
use crate::dynamics::{Body, Coord, Rotation};

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
