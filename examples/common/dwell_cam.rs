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

/// The largest pressure angle of the cam over the cam angles from `from` to `to`, located
/// between the samples of `states` (the turn the cam was found from): Brent's search between the
/// best sample's neighbours, each trial a solve at that cam angle from the best sample's
/// position, inverted on its own. `(cam angle, pressure angle)`.
pub fn peak_pressure(
    m: &DwellCamRocker,
    states: &[DwellCamRockerState],
    profile: &CamProfile,
    from: f64,
    to: f64,
) -> Result<(f64, f64)> {
    let inside = |k: &usize| (from..=to).contains(&states[*k].input.phi);
    let best = (0..states.len())
        .filter(inside)
        .max_by(|&a, &b| profile.pressure_angle[a].total_cmp(&profile.pressure_angle[b]));
    let Some(k) = best else {
        return Err(kinloop::Error::InvalidArgument(format!("no sample between {from} and {to}")));
    };
    let lo = states[k.saturating_sub(1)].input.phi.max(from);
    let hi = states[(k + 1).min(states.len() - 1)].input.phi.min(to);
    let guess = states[k].q;
    kinloop::analysis::maximize(lo, hi, |phi| {
        let s = m.kinematics(phi, &guess)?;
        Ok(cam(std::slice::from_ref(&s))?.pressure_angle[0])
    })
}
