//! The checked hand sweeps: the same numbers as the unchecked ones, bit for bit, with no check
//! failing along the benchmarks' regular turns; each check firing where it should (a mechanism
//! at a nearly singular position, a forced jump of the carried state); the judged unknowns and
//! units those of kinloop's declarations.

use std::f64::consts::TAU;

use kinloop::Mechanism;
use kinloop_fixtures::gear_lever::GearLever;

use super::*;
use crate::hand::{FOUR_BAR, FourBarClosed, GearLeverClosed, gear_lever};
use crate::hand_sweep::{FOUR_BAR_TERMS, GEAR_LEVER_TERMS, PERIOD, RHOMBIC_TERMS};
use crate::lean::{HandSweepCursor, hand_sweep_fold};
use crate::rhombic::PARAMS;

/// Every number of `steps` samples of `s` after its first, as bits.
fn bits<S: HandSweep<N, NP>, const N: usize, const NP: usize>(s: S, steps: usize) -> Result<Vec<u64>, Failed> {
    hand_sweep_fold(s, steps, Vec::with_capacity(steps * 12), |mut v, x, step, point| {
        v.push(x.to_bits());
        v.extend((0..N).flat_map(|u| [step.q[u], step.dq[u], step.d2q[u]]).map(f64::to_bits));
        v.extend(point.iter().map(|p| p.to_bits()));
        v
    })
}

/// A checked sweep against its unchecked twin: no check fails, and every number is the same.
fn same_numbers<S: Branch<N, NP>, const N: usize, const NP: usize>(name: &str, s: S, steps: usize) {
    let plain = bits(s.clone(), steps).unwrap();
    let checked = bits(Checked::new(s), steps).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(plain == checked, "{name}: the checked sweep's numbers differ");
}

fn four_bar_guess() -> [f64; 2] {
    FOUR_BAR.solve(0.0).unwrap().q.into()
}

fn gear_lever_guess(m: &GearLever) -> [f64; 2] {
    m.solve(0.0).unwrap().q.into()
}

/// 20 turns of 720 samples and one of 20,000, the three mechanisms of the benchmarks.
#[test]
fn checked_sweeps_give_the_same_numbers_and_pass_every_check() {
    let gear = gear_lever();
    for (turn, steps) in [(720, 20 * 720), (20_000, 20_000)] {
        same_numbers("rhombic", RhombicSweep::<RHOMBIC_TERMS>::new(&PARAMS, turn, PERIOD), steps);
        let four = FourBarSweep::<FOUR_BAR_TERMS>::new(FourBarClosed::of(&FOUR_BAR), turn, PERIOD, four_bar_guess());
        same_numbers("four-bar", four, steps);
        let lever =
            GearLeverSweep::<GEAR_LEVER_TERMS>::new(GearLeverClosed::of(&gear), turn, PERIOD, gear_lever_guess(&gear));
        same_numbers("gear-lever", lever, steps);
    }
}

/// The judged unknowns and closed-form angles of [`Branch`] are those kinloop's sweep judges in
/// the three declarations: the rhombic drive's sliders follow their rods (not judged), every
/// other unknown is judged, and all but the gear-lever's length are closed-form angles.
#[test]
fn the_judged_unknowns_are_kinloops() {
    fn flags<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize>(_: &M) -> ([bool; N], [bool; N]) {
        (M::FOLLOWERS, M::CLOSED_FORM_ANGLES)
    }
    let (follow, angles) = flags(&PARAMS.kinloop());
    assert_eq!(follow, [false, false, true, true]);
    assert_eq!(angles[..2], <RhombicSweep as Branch<4, 0>>::ANGLES);
    // kinloop's `positions_judged`: some judged unknown is not a closed-form angle.
    assert_eq!(!(angles[0] & angles[1]), <RhombicSweep as Branch<4, 0>>::POSITIONS_JUDGED);
    let (follow, angles) = flags(&FOUR_BAR);
    assert_eq!(follow, [false; 2]);
    assert_eq!(angles, <FourBarSweep as Branch<2, 6>>::ANGLES);
    assert_eq!(!(angles[0] & angles[1]), <FourBarSweep as Branch<2, 6>>::POSITIONS_JUDGED);
    let (follow, angles) = flags(&gear_lever());
    assert_eq!(follow, [false; 2]);
    assert_eq!(angles, <GearLeverSweep as Branch<2, 6>>::ANGLES);
    assert_eq!(!(angles[0] & angles[1]), <GearLeverSweep as Branch<2, 6>>::POSITIONS_JUDGED);
}

/// The gear-lever's length is judged in kinloop's unit of it at the sweep's start (its loop's
/// lengths, `l_c + l_p + s` with `s = l_c + l_p` at input 0), its rocker angle in radians.
#[test]
fn the_gear_levers_length_unit_is_kinloops() {
    let m = gear_lever();
    let jac = m.jacobian_flat(&[0.0], &gear_lever_guess(&m));
    let hand = GearLeverSweep::<GEAR_LEVER_TERMS>::new(GearLeverClosed::of(&m), 720, PERIOD, gear_lever_guess(&m));
    assert_eq!(jac.unit[1], 1.0, "the rocker angle's unit is a radian");
    // The same sum of lengths, up to its rounding.
    let units = hand.judged_units();
    assert!((jac.unit[0] - units[0]).abs() <= 1e-15 * jac.unit[0], "{} {units:?}", jac.unit[0]);
    assert_eq!(units[1], 1.0);
}

/// The hand pivot ratios (over the columns' norms) against kinloop's smallest pivot ratio (over
/// the columns' largest entries) along a turn of the rhombic drive and the four-bar: a column
/// of two entries has a 2-norm between 1 and `sqrt 2` times its largest, so the hand ratio is
/// `[1 / sqrt 2, 1]` times kinloop's for a rod (one angle column), `[1 / 2, 1]` for the dyad's
/// two: the same zeros and about the same size. The gear-lever's (`s` over `l_c + l_p`, where
/// kinloop's lever floor is the rows' magnitudes, which vary along the turn) is measured within
/// `[0.72, 1]` of kinloop's; the bound asserted is `[1 / 2, 1]`.
#[test]
fn the_pivot_ratios_are_kinloops_up_to_the_columns_scales() {
    let rhombic = PARAMS.kinloop();
    let mut guess = crate::rhombic::initial_guess(&PARAMS);
    let mut sweep = RhombicSweep::<RHOMBIC_TERMS>::new(&PARAMS, 72, PERIOD);
    for k in 0..72 {
        let x = TAU * k as f64 / 72.0;
        let (step, _) = sweep.sync(x).unwrap();
        let kin = rhombic.kinematics_flat(&[x], &guess, &Default::default()).unwrap();
        guess = kin.q;
        let (_, hand) = sweep.health(&step, sweep.pivot_unit());
        let ratio = hand / kin.health.min_pivot;
        assert!(
            (0.5f64.sqrt() - 1e-12..=1.0 + 1e-12).contains(&ratio),
            "rhombic at {x}: {hand} against {}",
            kin.health.min_pivot
        );
    }
    let mut guess = four_bar_guess();
    let mut sweep = FourBarSweep::<FOUR_BAR_TERMS>::new(FourBarClosed::of(&FOUR_BAR), 72, PERIOD, guess);
    for k in 0..72 {
        let x = TAU * k as f64 / 72.0;
        let (step, _) = sweep.sync(x).unwrap();
        let kin = FOUR_BAR.kinematics_flat(&[x], &guess, &Default::default()).unwrap();
        guess = kin.q;
        let (_, hand) = sweep.health(&step, sweep.pivot_unit());
        let ratio = hand / kin.health.min_pivot;
        assert!(
            (0.5 - 1e-12..=1.0 + 1e-12).contains(&ratio),
            "four-bar at {x}: {hand} against {}",
            kin.health.min_pivot
        );
    }
    let m = gear_lever();
    let mut guess = gear_lever_guess(&m);
    let mut sweep = GearLeverSweep::<GEAR_LEVER_TERMS>::new(GearLeverClosed::of(&m), 72, PERIOD, guess);
    for k in 0..72 {
        let x = TAU * k as f64 / 72.0;
        let (step, _) = sweep.sync(x).unwrap();
        let kin = m.kinematics_flat(&[x], &guess, &Default::default()).unwrap();
        guess = kin.q;
        let (_, hand) = sweep.health(&step, sweep.pivot_unit());
        let ratio = hand / kin.health.min_pivot;
        assert!((0.5..=1.0 + 1e-12).contains(&ratio), "gear-lever at {x}: {hand} against {}", kin.health.min_pivot);
    }
}

/// Runs `s` (checked) for up to `steps` samples after its first, calling `jump` on it before
/// sample `at`: the checks that fired (0 if none did) and the index of the failed sample.
fn fire<S: Branch<N, NP>, const N: usize, const NP: usize>(
    s: S,
    steps: usize,
    at: usize,
    jump: impl FnOnce(&mut S),
) -> (u8, Option<usize>) {
    let mut s = Checked::new(s);
    s.start(0.0).unwrap();
    let mut cursor = HandSweepCursor::new(&s);
    let mut jump = Some(jump);
    for i in 0..steps {
        if i == at {
            (jump.take().unwrap())(s.inner_mut());
        }
        if cursor.next(&mut s).is_err() {
            return (s.fired(), Some(i));
        }
    }
    (s.fired(), None)
}

fn four_bar_sweep(closed: FourBarClosed, turn: usize) -> FourBarSweep {
    let guess = FOUR_BAR.solve(0.0).unwrap().q.into();
    FourBarSweep::new(closed, turn, PERIOD, guess)
}

/// The four-bar's closed form switched to the other assembly mode mid-sweep (as a solve that
/// slid onto the mirror image): the determinant's sign flips (and the mirror image is more than
/// a radian away, its slopes far from the prediction: those checks fire with it).
#[test]
fn a_change_of_assembly_mode_flips_the_determinants_sign() {
    let (fired, at) = fire(four_bar_sweep(FourBarClosed::of(&FOUR_BAR), 720), 400, 100, |s| s.closed.left = false);
    assert_eq!(at, Some(100));
    assert!(fired & fired::FLIP != 0, "{fired:#b}");
}

/// The carried signs forced to the other assembly mode (the sweep's first sample on the mirror
/// image): the first judged sample, on the branch, fails the determinant's sign alone.
#[test]
fn carried_signs_of_the_other_mode_fail_the_sign_check_alone() {
    let mut s = Checked::new(four_bar_sweep(FourBarClosed::of(&FOUR_BAR), 720));
    s.start(0.0).unwrap();
    s.signs ^= 1;
    let mut cursor = HandSweepCursor::new(&s);
    assert!(cursor.next(&mut s).is_err());
    assert_eq!(s.fired(), fired::FLIP);
}

/// The carried coupler angle a turn off (an angle on the wrong turn): only the angle's cap
/// fires (the slopes and the signs are those of the branch).
#[test]
fn an_angle_a_turn_off_exceeds_the_angle_cap() {
    let (fired, at) = fire(four_bar_sweep(FourBarClosed::of(&FOUR_BAR), 720), 400, 100, |s| s.beta += TAU);
    assert_eq!((fired, at), (fired::TURN, Some(100)));
}

/// The crank 5 % longer mid-sweep: the angles move by a few hundredths of a radian (within the
/// cap, and the four-bar's positions are not judged), the slopes by 5 %, twice their bound's
/// relative part: only the slopes' check fires.
#[test]
fn a_jump_of_the_slopes_fails_the_slope_check() {
    let (fired, at) =
        fire(four_bar_sweep(FourBarClosed::of(&FOUR_BAR), 720), 400, 100, |s| s.closed.a = 1.05 * FOUR_BAR.a);
    assert_eq!((fired, at), (fired::SLOPE, Some(100)));
}

/// The gear-lever's carrier 2 % longer mid-sweep: the length `s` jumps by about 0.04, beyond
/// `max_dist` (a quarter of the predicted change, at most 0.014 along a turn of 720): only that
/// check fires.
#[test]
fn a_jump_of_the_length_fails_the_position_check() {
    let m = gear_lever();
    let s = GearLeverSweep::<GEAR_LEVER_TERMS>::new(GearLeverClosed::of(&m), 720, PERIOD, gear_lever_guess(&m));
    let (fired, at) = fire(s, 400, 100, |s| s.closed.l_c *= 1.02);
    assert_eq!(at, Some(100));
    assert_eq!(fired, fired::DIST, "{fired:#b}");
}

/// A four-bar whose dyad is within `1e-13` of folding at crank angle 0 (coupler minus rocker
/// `2.2 - 1e-13`, the frame minus the crank 2.2): its transmission angle's sine, the pivot
/// ratio, is 4.3e-7 there. Sampled finely enough (1e-8 rad) for every other check to hold,
/// only the pivot's fires, at the first judged sample.
#[test]
fn a_nearly_folded_dyad_fails_the_pivot_check() {
    let closed = FourBarClosed { a: 1.0, b: 3.0 - 1e-13, c: 0.8, d: 3.2, left: true };
    let turn = (TAU / 1e-8) as usize;
    let (fired, at) =
        fire(FourBarSweep::<FOUR_BAR_TERMS>::new(closed, turn, PERIOD, [0.0, 0.0]), 10, usize::MAX, |_| {});
    assert_eq!((fired, at), (fired::PIVOT, Some(0)));
}

/// The same dyad `1e-6` from folding (pivot ratio 1.4e-3, under [`ROTATE_MIN_PIVOT`]), sampled
/// at 3e-6 rad: every check holds, and every sample after the first comes from libm, the
/// rotation skipped; at the regular four-bar, none does.
#[test]
fn a_small_pivot_ratio_takes_the_next_sample_from_libm() {
    let closed = FourBarClosed { a: 1.0, b: 3.0 - 1e-6, c: 0.8, d: 3.2, left: true };
    let turn = (TAU / 3e-6) as usize;
    let mut s = Checked::new(FourBarSweep::<FOUR_BAR_TERMS>::new(closed, turn, PERIOD, [0.0, 0.0]));
    s.start(0.0).unwrap();
    let mut cursor = HandSweepCursor::new(&s);
    for _ in 0..50 {
        cursor.next(&mut s).unwrap();
    }
    assert_eq!(s.exact_samples(), 50);
    let mut s = Checked::new(four_bar_sweep(FourBarClosed::of(&FOUR_BAR), 720));
    s.start(0.0).unwrap();
    let mut cursor = HandSweepCursor::new(&s);
    for _ in 0..720 {
        cursor.next(&mut s).unwrap();
    }
    assert_eq!(s.exact_samples(), 0);
}

/// The gear-lever sampled 20 times a turn: its rocker's slope changes over the first step by
/// more than the slope-change bound allows (only that check fires; sampled more coarsely, the
/// slopes' test fires too, the rocker's slope being judged in radians beside the length's in
/// its unit).
#[test]
fn a_coarse_step_near_a_fast_passage_is_too_long() {
    let m = gear_lever();
    let s = GearLeverSweep::<GEAR_LEVER_TERMS>::new(GearLeverClosed::of(&m), 20, PERIOD, gear_lever_guess(&m));
    let (fired, at) = fire(s, 20, usize::MAX, |_| {});
    assert_eq!((fired, at), (fired::LONG, Some(0)), "{fired:#b}");
}

/// The rhombic drive's rods: a drive whose working rod's sine reaches `1 - 1e-14` at
/// `phi1 = pi / 2` (its cosine, the pivot ratio, 1.4e-7 there), swept at 720 a turn: the sweep
/// is stopped by the checks near there, never passes it.
#[test]
fn the_rhombic_drive_stops_at_its_rod_across_the_slide() {
    let p = crate::rhombic::Params { e_p: 3.0 * (1.0 - 1e-14) - 1.0, ..PARAMS };
    let (fired, at) = fire(RhombicSweep::<RHOMBIC_TERMS>::new(&p, 720, PERIOD), 720, usize::MAX, |_| {});
    let at = at.expect("the checks stop the sweep");
    // Sample `i` is at `(i + 1) h`: `pi / 2` is sample 179.
    assert!(fired != 0 && at <= 179, "{fired:#b} at {at}");
    eprintln!("rhombic rod across its slide: the checks {fired:#08b} at sample {at}");
}
