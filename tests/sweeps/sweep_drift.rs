//! Drift of a sweep's positions from the libm path. A sweep advances the sines and cosines of
//! its inputs by rotation and its closed-form angles from anchors (libm only to
//! re-synchronise); a point solve at the same input computes every value with libm (an input
//! angle plus a parameter angle by angle addition from libm's values of both). Over many
//! turns and up to 10^6 samples the two must agree to rounding: nothing may accumulate.
//!
//! Measured, not timed: the largest deviation of every position (angles in radians, lengths in
//! units of the mechanism's links, of about 1 to 3.5; relative beyond 1) over the whole sweep. The 10^6-sample
//! check is `#[ignore]`d (about a minute in debug mode; `cargo test --release --test sweeps
//! drift -- --ignored` runs it in seconds); the shorter one runs always, with the same bound.

use kinloop::{Kin, Mechanism, NewtonConfig, Sweep};
use kinloop_fixtures::gear_lever::GearLever;
use kinloop_fixtures::{FourBar, RhombicDrive};
use std::f64::consts::TAU;

use crate::support::tol;

/// The largest deviation of a sweep's positions from libm's (relative beyond 1) over `turns` turns of the input
/// from 0, `samples` samples in all: at every sample the mechanism is solved again at the same
/// input by `kinematics_flat` (libm's sines, cosines and inverse functions), from the sweep's
/// position (which only picks the branch and the angles' turns: the closed forms ignore the
/// rest of the guess).
fn drift<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize>(
    m: &M,
    guess: [f64; N],
    turns: f64,
    samples: usize,
) -> f64 {
    let cfg = NewtonConfig::default();
    let mut sweep = Sweep::<_, Kin<N, 1, NO>, N, 1, NO>::new(m, [0.0], [TAU * turns], samples, guess).unwrap();
    let (mut worst, mut n) = (0.0f64, 0usize);
    while let Some(k) = sweep.next_ref() {
        let k = k.unwrap();
        let libm = m.kinematics_flat(&k.x, &k.q, &cfg).unwrap();
        for u in 0..N {
            // An angle that has turned many times (the gear-lever's rocker turns with its
            // carrier: about 125 rad after 20 turns) carries the rounding of its magnitude in any
            // computation, libm's too: the deviation is measured relative to it beyond 1.
            worst = worst.max((k.q[u] - libm.q[u]).abs() / libm.q[u].abs().max(1.0));
        }
        n += 1;
    }
    assert_eq!(n, samples);
    worst
}

/// The three closed-form mechanisms of the benchmarks: the rhombic drive (two `asin` rod
/// angles, the inputs `phi1` and `phi1 + gamma`), the four-bar with its coupler point (two
/// `atan2` angles) and the gear-lever rocker (an `atan2` angle and a length, two input
/// arguments `alpha` and `(1 - u) alpha`): their largest drifts.
fn drifts(turns: f64, samples: usize) -> [f64; 3] {
    let rhombic = RhombicDrive::default();
    let four = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let gear = GearLever::default();
    [
        drift(&rhombic, rhombic.guess(0.0).into(), turns, samples),
        drift(&four, four.guess(0.0).into(), turns, samples),
        drift(&gear, gear.guess(0.0).into(), turns, samples),
    ]
}

/// Positions within `tol::ULPS` (1e-14) of libm's: 20,000 samples over 20 turns (1,000 a turn).
#[test]
fn sweep_positions_stay_within_rounding_of_the_libm_path() {
    let d = drifts(20.0, 20_000);
    println!("drift over 20 turns, 20,000 samples (rhombic, four-bar, gear-lever): {d:?}");
    assert!(d.iter().all(|&d| d <= tol::ULPS), "{d:?}");
}

/// The same bound over 10^6 samples and 50 turns (20,000 a turn).
#[test]
#[ignore = "about a minute in debug mode; run with --release"]
fn sweep_positions_stay_within_rounding_of_the_libm_path_over_a_million_samples() {
    let d = drifts(50.0, 1_000_000);
    println!("drift over 50 turns, 10^6 samples (rhombic, four-bar, gear-lever): {d:?}");
    assert!(d.iter().all(|&d| d <= tol::ULPS), "{d:?}");
}
