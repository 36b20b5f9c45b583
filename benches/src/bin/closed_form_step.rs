//! Kinematic steps for instruction counts under callgrind: `closed_form_step VARIANT STEPS [TURN]`
//! runs `STEPS` steps of turns of `TURN` steps (default 720: 0.5 degree) with one of
//! * rhombic drive: `hand` (the paper's closed form written by hand, `gamma`'s sine and cosine
//!   precomputed), `hand-libm-sum` (the same with `sin_cos(phi1 + gamma)` from libm), `point` (kinloop's
//!   `kinematics_flat` from the previous position: closed-form blocks), `newton` (the same with
//!   `#[kinloop(newton)]`), `newton-taylor` (that, warm-started by the benchmarks' second-order
//!   predictor), `sweep` (kinloop's own `Sweep`, each sample read where the sweep keeps it),
//!   `sweep-for` (the same sweep consumed by a `for` loop over its items), `newton-sweep`;
//! * four-bar with its coupler point, gear-lever rocker: `four-bar-hand`, `four-bar-point`,
//!   `four-bar-sweep`, `four-bar-sweep-for`, `gear-lever-hand`, `gear-lever-point`,
//!   `gear-lever-sweep`, `gear-lever-sweep-for` (the hand closed forms of `kinloop_bench::hand`);
//! * the sweep recipe written by hand (`kinloop_bench::hand_sweep`: inputs' sines and cosines
//!   rotated, angles advanced by increments, libm only to re-synchronise): `hand-sweep`,
//!   `four-bar-hand-sweep`, `gear-lever-hand-sweep`; the same with kinloop's per-sample checks
//!   (`kinloop_bench::hand_check`: prediction, determinant signs, pivot ratio, slopes, angles,
//!   the gear-lever's positions): `hand-sweep-checked`, `four-bar-hand-sweep-checked`,
//!   `gear-lever-hand-sweep-checked`;
//! * kinloop's kernel (the one its `Sweep` runs) driven by the hand sweep's trigonometry, with
//!   no check and no judgment (`kinloop_bench::kernel_lane`): `kernel-lane`,
//!   `four-bar-kernel-lane`, `gear-lever-kernel-lane`;
//! * the four-bar's sweep loop sketched as the macro would emit it, with the sweep's checks
//!   (`kinloop_bench::lane_sketch`): `four-bar-lane-sketch`, and `four-bar-lane-lean` with the
//!   branch flag carried, the plain root formula and the analogs by the dyad's own determinant;
//! * class IV block (Newton): `class-four-hand` (the hand-written Newton),
//!   `class-four-hand-near` (the same with each iterate's sines and cosines rotated from the
//!   previous iterate's, as kinloop's Newton blocks do), `class-four-point`,
//!   `class-four-sweep`, and `class-four-hand-taylor`, `class-four-point-taylor` warm-started by
//!   the benchmarks' second-order predictor instead of the previous position;
//! * design-space scan: `four-bar-scan` (`kinloop::scan` over four-bars whose cranks differ
//!   by 0.1 %, each swept over a turn in 100 samples; against `four-bar-sweep@99`, the same
//!   spacing in one long sweep);
//! * sensitivities: `four-bar-sens` (the four-bar's `sensitivities_flat`: positions, analogs and
//!   outputs with their sensitivities to its four parameters) and `four-bar-sens-point` (the
//!   same declaration's `kinematics_flat`);
//! * ring of 64 four-bar loops closed through a differential (one Newton block of 128
//!   unknowns): `ring-point` (sparse factorisation), `ring-dense-point` (its `#[kinloop(dense)]`
//!   twin), against `series-point`, the same 64 loops in series (closed-form dyads).
//!
//! Every variant runs in the same lean harness ([`kinloop_bench::lean`]): the step inlined into
//! a loop of its own, its twelve numbers added into one accumulator.
//!
//! Instructions per step = difference of the totals of two runs with different `STEPS`, divided
//! by the difference of the steps (the setup cancels).

use kinloop_bench::class_four::{self, HandNewton, HandNewtonNear};
use kinloop_bench::decls::{ClassFour, FourBarSens, RhombicDrive, four_sens};
use kinloop_bench::hand::{FOUR_BAR, FourBarClosed, GearLeverClosed, gear_lever};
use kinloop_bench::hand_check::Checked;
use kinloop_bench::hand_sweep::{
    FOUR_BAR_TERMS, FourBarSweep, GEAR_LEVER_TERMS, GearLeverSweep, HandSweep, PERIOD, RHOMBIC_TERMS, RhombicSweep,
};
use kinloop_bench::kinloop_variants::{Kinloop, KinloopSens};
use kinloop_bench::lane_sketch::FourBarLaneSketch;
use kinloop_bench::lean;
use kinloop_bench::rhombic::{ClosedForm, ClosedFormLibmSum, PARAMS, initial_guess};
use kinloop_bench::ring::{Ring, RingDense, Series};
use kinloop_bench::sweep::{Stepper, WarmStart};
use kinloop_fixtures::FourBar;
use kinloop_fixtures::gear_lever::GearLever;

kinloop::mechanism! {
    /// The rhombic drive of the benchmarks, solved by Newton in every block.
    #[kinloop(newton)]
    pub struct RhombicNewton {
        params r_p = 1.0, r_b = 1.2, l_p = 3.0, l_b = 3.5, e_p = 0.5, de = 0.9, gamma = 0.7;
        input phi1;
        unknowns phi2 = 0, phi4 = pi, x_c = -l_p, x_f = l_b;
        loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
        loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
    }
}

/// Steps per turn unless a third argument gives another number (the criterion benchmarks use
/// 1000000, where a Taylor prediction already meets Newton's tolerance).
const TURN: usize = 720;

/// The steps per turn: the third argument, or [`TURN`].
fn turn() -> usize {
    std::env::args().nth(3).and_then(|s| s.parse().ok()).unwrap_or(TURN)
}

// Every variant runs in the lean harness (`kinloop_bench::lean`): one loop per variant, the
// step inlined into it, the step's twelve numbers added into one accumulator.
fn steps_of<S: Stepper<N>, const N: usize>(s: &S, guess: [f64; N], steps: usize) -> f64 {
    policy_steps(s, WarmStart::Previous, guess, steps)
}

fn policy_steps<S: Stepper<N>, const N: usize>(s: &S, policy: WarmStart, guess: [f64; N], steps: usize) -> f64 {
    lean::stepper_turns(s, policy, turn(), guess, steps).expect("step")
}

fn sweep_of<M: kinloop::Mechanism<N, 1, NO>, const N: usize, const NO: usize>(
    m: &M,
    guess: [f64; N],
    steps: usize,
) -> f64 {
    lean::sweep_turns(m, turn(), guess, steps).expect("sample")
}

fn sweep_for_of<M: kinloop::Mechanism<N, 1, NO>, const N: usize, const NO: usize>(
    m: &M,
    guess: [f64; N],
    steps: usize,
) -> f64 {
    lean::sweep_for_turns(m, turn(), guess, steps).expect("sample")
}

fn lane_of<M: kinloop::Mechanism<N, 1, NO>, const N: usize, const NO: usize, const TERMS: usize>(
    m: &M,
    guess: [f64; N],
    steps: usize,
) -> f64 {
    lean::kernel_lane_turns::<M, N, NO, TERMS>(m, turn(), guess, steps).expect("sample")
}

fn hand_sweep_of<S: HandSweep<N, NP>, const N: usize, const NP: usize>(s: S, steps: usize) -> f64 {
    lean::hand_sweep_turns(s, steps).expect("sample")
}

/// The ring's position at input 0.
fn ring_guess() -> [f64; 128] {
    Ring::default().solve(0.0).expect("the ring assembles").q.into()
}

/// The series' position at input 0.
fn series_guess() -> [f64; 128] {
    Series::default().solve(0.0).expect("the series assembles").q.into()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let variant = args.get(1).map_or("point", String::as_str);
    let steps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(10_000);
    let m = PARAMS.kinloop();
    let g = initial_guess(&PARAMS);
    let four = FOUR_BAR;
    let four_hand = FourBarClosed::of(&four);
    let gear = gear_lever();
    let gear_hand = GearLeverClosed::of(&gear);
    let gf: [f64; 2] = four.solve(0.0).expect("four-bar assembles").q.into();
    let gg: [f64; 2] = gear.solve(0.0).expect("gear lever assembles").q.into();
    let (c4, g4) = (class_four::PARAMS, class_four::INITIAL_GUESS);
    let acc = match variant {
        "hand" => steps_of(&ClosedForm::new(&PARAMS), g, steps),
        "hand-libm-sum" => steps_of(&ClosedFormLibmSum(ClosedForm::new(&PARAMS)), g, steps),
        "hand-sweep" => hand_sweep_of(RhombicSweep::<RHOMBIC_TERMS>::new(&PARAMS, turn(), PERIOD), steps),
        "hand-sweep-checked" => {
            hand_sweep_of(Checked::new(RhombicSweep::<RHOMBIC_TERMS>::new(&PARAMS, turn(), PERIOD)), steps)
        }
        "point" => steps_of(&Kinloop::<RhombicDrive, 0>::new(m), g, steps),
        "newton" => steps_of(&Kinloop::<RhombicNewton, 0>::new(RhombicNewton::default()), g, steps),
        "sweep" => sweep_of(&m, g, steps),
        "sweep-for" => sweep_for_of(&m, g, steps),
        "kernel-lane" => lane_of::<_, 4, 0, RHOMBIC_TERMS>(&m, g, steps),
        "newton-taylor" => {
            policy_steps(&Kinloop::<RhombicNewton, 0>::new(RhombicNewton::default()), WarmStart::Taylor, g, steps)
        }
        "newton-sweep" => sweep_of(&RhombicNewton::default(), g, steps),
        "four-bar-hand" => steps_of(&four_hand, gf, steps),
        "four-bar-hand-sweep" => {
            hand_sweep_of(FourBarSweep::<FOUR_BAR_TERMS>::new(four_hand, turn(), PERIOD, gf), steps)
        }
        "four-bar-hand-sweep-checked" => {
            hand_sweep_of(Checked::new(FourBarSweep::<FOUR_BAR_TERMS>::new(four_hand, turn(), PERIOD, gf)), steps)
        }
        "four-bar-point" => steps_of(&Kinloop::<FourBar, 2>::new(four), gf, steps),
        "four-bar-sweep" => sweep_of(&four, gf, steps),
        "four-bar-sweep-for" => sweep_for_of(&four, gf, steps),
        "four-bar-lane-sketch" => {
            hand_sweep_of(Checked::new(FourBarLaneSketch::<FOUR_BAR_TERMS>::new(four, turn(), PERIOD, gf)), steps)
        }
        "four-bar-lane-lean" => {
            hand_sweep_of(Checked::new(FourBarLaneSketch::<FOUR_BAR_TERMS, true>::new(four, turn(), PERIOD, gf)), steps)
        }
        "four-bar-kernel-lane" => lane_of::<_, 2, 2, FOUR_BAR_TERMS>(&four, gf, steps),
        "four-bar-scan" => lean::scan_designs(
            // Designs 0.1 % apart in the crank: every one a crank-rocker like the four-bar.
            |i| FourBar { a: four.a * (1.0 + 1e-3 * (i % 100) as f64), ..four },
            steps,
        )
        .expect("scan"),
        "four-bar-sens" => steps_of(&KinloopSens::<FourBarSens, 2, 4>::new(four_sens(&four)), gf, steps),
        "four-bar-sens-point" => steps_of(&Kinloop::<FourBarSens, 2>::new(four_sens(&four)), gf, steps),
        "gear-lever-hand" => steps_of(&gear_hand, gg, steps),
        "gear-lever-hand-sweep" => {
            hand_sweep_of(GearLeverSweep::<GEAR_LEVER_TERMS>::new(gear_hand, turn(), PERIOD, gg), steps)
        }
        "gear-lever-hand-sweep-checked" => {
            hand_sweep_of(Checked::new(GearLeverSweep::<GEAR_LEVER_TERMS>::new(gear_hand, turn(), PERIOD, gg)), steps)
        }
        "gear-lever-point" => steps_of(&Kinloop::<GearLever, 2>::new(gear), gg, steps),
        "gear-lever-sweep" => sweep_of(&gear, gg, steps),
        "gear-lever-sweep-for" => sweep_for_of(&gear, gg, steps),
        "gear-lever-kernel-lane" => lane_of::<_, 2, 2, GEAR_LEVER_TERMS>(&gear, gg, steps),
        "class-four-hand" => steps_of(&HandNewton { p: c4 }, g4, steps),
        "class-four-hand-near" => steps_of(&HandNewtonNear { p: c4 }, g4, steps),
        "class-four-point" => steps_of(&Kinloop::<ClassFour, 0>::new(c4.kinloop()), g4, steps),
        "class-four-hand-taylor" => policy_steps(&HandNewton { p: c4 }, WarmStart::Taylor, g4, steps),
        "class-four-point-taylor" => {
            policy_steps(&Kinloop::<ClassFour, 0>::new(c4.kinloop()), WarmStart::Taylor, g4, steps)
        }
        "class-four-sweep" => sweep_of(&c4.kinloop(), g4, steps),
        "ring-point" => steps_of(&Kinloop::<Ring, 0>::new(Ring::default()), ring_guess(), steps),
        "ring-dense-point" => steps_of(&Kinloop::<RingDense, 0>::new(RingDense::default()), ring_guess(), steps),
        "series-point" => steps_of(&Kinloop::<Series, 0>::new(Series::default()), series_guess(), steps),
        other => panic!("unknown variant {other} (see the module documentation)"),
    };
    println!("{variant}: {steps} steps, checksum {acc}");
}
