//! The kernel driven by the hand sweep's trigonometry (`kinloop_bench::kernel_lane`), and the
//! four-bar's sweep loop sketched as the macro would emit it (`kinloop_bench::lane_sketch`, with
//! the sweep's checks), against the kernel with libm's sines, cosines and angles at every sample
//! (`kinematics_flat` from the previous sample's positions): the counts `closed_form_step`
//! gives for them are those of the same numbers, not of a cheaper wrong computation.
//!
//! Tolerances, relative to `max(1, |value|)`, as in `tests/hand_sweep.rs` and for the same
//! reasons: positions (unknowns and outputs) 1e-14; analogs 1e-13, 3e-12 for the gear-lever,
//! whose analogs are defined only to the rounding of libm's arguments times third derivatives
//! up to 675.

use kinloop::{Kin, Mechanism, NewtonConfig};
use kinloop_bench::hand::{FOUR_BAR, gear_lever};
use kinloop_bench::hand_check::Checked;
use kinloop_bench::hand_sweep::PERIOD;
use kinloop_bench::hand_sweep::{FOUR_BAR_TERMS, GEAR_LEVER_TERMS, RHOMBIC_TERMS};
use kinloop_bench::kernel_lane::kernel_lane_fold;
use kinloop_bench::lane_sketch::FourBarLaneSketch;
use kinloop_bench::lean::hand_sweep_fold;
use kinloop_bench::rhombic::{PARAMS, initial_guess};
use kinloop_bench::sweep::rel_err;

const POSITION_TOL: f64 = 1e-14;
const ANALOG_TOL: f64 = 1e-13;
const GEAR_LEVER_ANALOG_TOL: f64 = 3e-12;

/// The largest deviations `[positions, analogs]` so far, `dev`, with a sample's (a NaN counts
/// as infinite).
fn widen(dev: [f64; 2], positions: impl IntoIterator<Item = f64>, analogs: impl IntoIterator<Item = f64>) -> [f64; 2] {
    let largest = |d: f64, e: f64| d.max(if e.is_nan() { f64::INFINITY } else { e });
    [positions.into_iter().fold(dev[0], largest), analogs.into_iter().fold(dev[1], largest)]
}

/// Largest deviations `[positions, analogs]` of the lane's samples from libm's over `steps`
/// samples of turns of `turn`.
fn deviation<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize, const TERMS: usize>(
    m: &M,
    guess: [f64; N],
    turn: usize,
    steps: usize,
) -> [f64; 2] {
    let cfg = NewtonConfig::default();
    let mut prev = m.kinematics_flat(&[0.0], &guess, &cfg).unwrap();
    let (h, mut k) = (std::f64::consts::TAU / turn as f64, 0usize);
    kernel_lane_fold::<M, _, N, NO, TERMS>(m, turn, guess, steps, [0.0f64; 2], |dev, got: &Kin<N, 1, NO>| {
        // The lane's input: the next of the turn's equally spaced inputs.
        k = (k + 1) % turn;
        assert_eq!(got.x, [h * k as f64]);
        let want = m.kinematics_flat(&got.x, &prev.q, &cfg).unwrap();
        let positions =
            (0..N).map(|u| rel_err(got.q[u], want.q[u])).chain((0..NO).map(|o| rel_err(got.out[o], want.out[o])));
        let analogs = (0..N)
            .flat_map(|u| [rel_err(got.dq[u][0], want.dq[u][0]), rel_err(got.d2q[u][0][0], want.d2q[u][0][0])])
            .chain((0..NO).flat_map(|o| {
                [rel_err(got.dout[o][0], want.dout[o][0]), rel_err(got.d2out[o][0][0], want.d2out[o][0][0])]
            }));
        prev = want;
        widen(dev, positions, analogs)
    })
    .unwrap()
}

fn check(name: &str, dev: [f64; 2], analog_tol: f64) {
    assert!(dev[0] <= POSITION_TOL, "{name}: positions deviate by {:e}", dev[0]);
    assert!(dev[1] <= analog_tol, "{name}: analogs deviate by {:e}", dev[1]);
}

#[test]
fn the_lane_computes_the_kernel_s_numbers() {
    // Three turns of 720 (each sample from the rotation but the re-synchronised ones) and part
    // of a turn of 20,000, where the increments are smaller.
    for (turn, steps) in [(720, 3 * 720), (20_000, 4000)] {
        let rhombic = deviation::<_, 4, 0, RHOMBIC_TERMS>(&PARAMS.kinloop(), initial_guess(&PARAMS), turn, steps);
        check(&format!("rhombic drive at {turn}"), rhombic, ANALOG_TOL);
        let four: [f64; 2] = FOUR_BAR.solve(0.0).unwrap().q.into();
        let four = deviation::<_, 2, 2, FOUR_BAR_TERMS>(&FOUR_BAR, four, turn, steps);
        check(&format!("four-bar at {turn}"), four, ANALOG_TOL);
        let gear = gear_lever();
        let g: [f64; 2] = gear.solve(0.0).unwrap().q.into();
        let gear = deviation::<_, 2, 2, GEAR_LEVER_TERMS>(&gear, g, turn, steps);
        check(&format!("gear-lever at {turn}"), gear, GEAR_LEVER_ANALOG_TOL);
    }
}

#[test]
fn the_four_bar_lane_sketch_computes_the_kernel_s_numbers() {
    lane_sketch_computes_the_kernel_s_numbers::<false>();
}

/// The lean sketch too (branch flag carried, the plain root formula, analogs by the dyad's
/// determinant): the same numbers to the rounding.
#[test]
fn the_lean_four_bar_lane_sketch_computes_the_kernel_s_numbers() {
    lane_sketch_computes_the_kernel_s_numbers::<true>();
}

fn lane_sketch_computes_the_kernel_s_numbers<const LEAN: bool>() {
    let cfg = NewtonConfig::default();
    for (turn, steps) in [(720, 3 * 720), (20_000, 4000)] {
        let guess: [f64; 2] = FOUR_BAR.solve(0.0).unwrap().q.into();
        let lane = Checked::new(FourBarLaneSketch::<FOUR_BAR_TERMS, LEAN>::new(FOUR_BAR, turn, PERIOD, guess));
        let mut prev = FOUR_BAR.kinematics_flat(&[0.0], &guess, &cfg).unwrap();
        let dev = hand_sweep_fold(lane, steps, [0.0f64; 2], |dev, x, got, point| {
            let want = FOUR_BAR.kinematics_flat(&[x], &prev.q, &cfg).unwrap();
            let positions = [
                rel_err(got.q[0], want.q[0]),
                rel_err(got.q[1], want.q[1]),
                rel_err(point[0], want.out[0]),
                rel_err(point[1], want.out[1]),
            ];
            let analogs = [
                rel_err(got.dq[0], want.dq[0][0]),
                rel_err(got.dq[1], want.dq[1][0]),
                rel_err(got.d2q[0], want.d2q[0][0][0]),
                rel_err(got.d2q[1], want.d2q[1][0][0]),
                rel_err(point[2], want.dout[0][0]),
                rel_err(point[3], want.dout[1][0]),
                rel_err(point[4], want.d2out[0][0][0]),
                rel_err(point[5], want.d2out[1][0][0]),
            ];
            prev = want;
            widen(dev, positions, analogs)
        })
        .unwrap();
        check(&format!("four-bar lane sketch (lean {LEAN}) at {turn}"), dev, ANALOG_TOL);
    }
}
