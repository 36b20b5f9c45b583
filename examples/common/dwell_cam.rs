//! The dwell cam's disc cam, shared by its example and the gallery's drawing: one turn of the
//! drive, and the cam found from it by kinematic inversion for the roller the examples choose.

use kinloop::analysis::cam::{CamProfile, FollowerSample, cam_profile};
use kinloop_fixtures::cam_linkage::{DwellCamRocker, DwellCamRockerState};
use std::f64::consts::TAU;

type Result<T> = std::result::Result<T, kinloop::Error>;

/// One turn of the cam in `steps` equal steps (`steps + 1` states, both ends included), each
/// solve warm-started from the previous position so the rocker stays in the declared assembly
/// mode.
pub fn turn(m: &DwellCamRocker, steps: usize) -> Result<Vec<DwellCamRockerState>> {
    let mut guess = m.guess(0.0);
    let mut states = Vec::with_capacity(steps + 1);
    for k in 0..=steps {
        let state = m.kinematics(TAU * k as f64 / steps as f64, &guess)?;
        guess = state.q;
        states.push(state);
    }
    Ok(states)
}

/// The radius of the roller the cam is made for (mm): the designer's choice, not the law's.
pub const ROLLER: f64 = 10.0;

/// The disc cam that moves the follower by the law, found by kinematic inversion from the
/// follower pin's positions and analogs over `states`: the cam turns with the input shaft about
/// the origin, and the follower slides on the vertical line through it.
pub fn cam(states: &[DwellCamRockerState]) -> Result<CamProfile> {
    let follower: Vec<FollowerSample> = states
        .iter()
        .map(|s| FollowerSample {
            cam: [s.input.phi, 1.0, 0.0],
            point: [
                [s.out.follower.x, s.out.follower.y],
                [s.dout.follower.x, s.dout.follower.y],
                [s.d2out.follower.x, s.d2out.follower.y],
            ],
            direction: [0.0, 1.0],
        })
        .collect();
    cam_profile(&follower, [0.0, 0.0], ROLLER)
}
