//! Regression tests of sweeps and of everything around them: configurations and ranges
//! validated up front, no unbounded loop, no false event, finiteness of every `Ok`, and the
//! assembly mode of every block watched (beyond the 64th).

use kinloop::paths::sweep::MAX_TURNS;
use kinloop::{AtSingular, Error, EventKind, SweepConfig};
use kinloop_fixtures::{FourBar, FourBarState};
use std::f64::consts::TAU;

use crate::support::{four_bar_angles, tol};

const CRANK_ROCKER: FourBar = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };

// The sweeps below run on the test's own thread: a range too long to follow is refused before
// any step, so each returns at once, and a hang would be one of the test harness's to catch.

/// The items of a sweep over `0..=to` of the crank-rocker in `samples` samples, and its events.
fn sweep_to(to: f64, samples: usize) -> (Vec<Result<FourBarState, Error>>, Vec<EventKind>) {
    let m = CRANK_ROCKER;
    let mut s = m.sweep(0.0, to, samples, &m.guess(0.0)).unwrap();
    let items: Vec<_> = s.by_ref().collect();
    (items, s.events().iter().map(|e| e.kind).collect())
}

/// Whether `items` is the one refusal of a range of `to` radians, `to / 2 pi` turns.
fn refused_as_too_long(items: &[Result<FourBarState, Error>], to: f64) {
    match items {
        [Err(Error::RangeTooLong { turns, max_turns, .. })] => {
            assert_close!(*turns, to / TAU, rel = tol::ULPS);
            assert_eq!(*max_turns, MAX_TURNS);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_sweep_over_a_huge_range_is_refused_as_too_long() {
    // 1.6e299 turns: refused by the first `next`, and nothing after it.
    let (items, events) = sweep_to(1e300, 5);
    refused_as_too_long(&items, 1e300);
    assert!(events.is_empty(), "{events:?}");
}

#[test]
fn a_crank_rocker_has_no_limit_position_even_over_a_long_range() {
    // 1.6e14 turns, beyond the most a sweep follows: refused, with no event.
    let (items, events) = sweep_to(1e15, 3);
    refused_as_too_long(&items, 1e15);
    assert!(events.is_empty(), "{events:?}");
    // Ten thousand turns and a bit, within it, in three samples (more than three million degrees
    // apart): every sample on the assembly it started on (C left of B -> D, the closed form's
    // side +1), where its closed form puts it, and no event on the way.
    let to = TAU * (1e4 + 0.3);
    let (items, events) = sweep_to(to, 3);
    assert!(events.is_empty(), "{events:?}");
    assert_eq!(items.len(), 3, "{items:?}");
    let FourBar { a, b, c, d } = CRANK_ROCKER;
    for st in items {
        let st = st.unwrap();
        let [beta, gamma] = four_bar_angles(a, b, c, d, st.input.phi, 1.0).unwrap();
        assert_close!(st.q.beta, beta, tol::SOLVE, "beta at {}", st.input.phi);
        assert_close!(st.q.gamma, gamma, tol::SOLVE, "gamma at {}", st.input.phi);
    }
}

#[test]
fn invalid_sweep_configurations_are_named_up_front() {
    let m = CRANK_ROCKER;
    let g = m.guess(0.0);
    let d = SweepConfig::default();
    let mut newton_inf = d;
    newton_inf.newton.residual_tol = f64::INFINITY;
    for (cfg, field) in [
        (d.with_max_step(0.0), "max_step"),
        (d.with_max_step(f64::NAN), "max_step"),
        (d.with_corrector(f64::NAN, d.corrector_abs), "corrector_rel"),
        (d.with_max_halvings(0), "max_halvings"),
        (newton_inf, "newton.residual_tol"),
    ] {
        let first = m.sweep(0.0, 1.0, 3, &g).unwrap().with_config(cfg).next();
        match first {
            Some(Err(Error::InvalidArgument(msg))) => assert!(msg.contains(field), "{msg}"),
            other => panic!("{field}: {other:?}"),
        }
    }
}

#[test]
fn motion_with_huge_speeds_is_an_error_not_infinity() {
    let s = CRANK_ROCKER.solve(0.4).unwrap();
    assert!(s.motion(1.0, 0.0).is_ok());
    match s.motion(1e200, 0.0) {
        Err(Error::Overflow { what: kinloop::Computed::Acceleration, .. }) => {}
        other => panic!("{other:?}"),
    }
}

kinloop::mechanism! {
    /// Seventy-one independent scalar blocks; the last one, `s70^2 = phi^2`, has a singular
    /// crossing at `phi = 0` where its smooth continuation `s70 = phi` changes the sign of its
    /// Jacobian `2 s70`.
    pub struct ManyBlocks {
        input phi;
        unknowns s0 = 1, s1 = 1, s2 = 1, s3 = 1, s4 = 1, s5 = 1, s6 = 1, s7 = 1, s8 = 1, s9 = 1, s10 = 1, s11 = 1, s12 = 1, s13 = 1, s14 = 1, s15 = 1, s16 = 1, s17 = 1, s18 = 1, s19 = 1, s20 = 1, s21 = 1, s22 = 1, s23 = 1, s24 = 1, s25 = 1, s26 = 1, s27 = 1, s28 = 1, s29 = 1, s30 = 1, s31 = 1, s32 = 1, s33 = 1, s34 = 1, s35 = 1, s36 = 1, s37 = 1, s38 = 1, s39 = 1, s40 = 1, s41 = 1, s42 = 1, s43 = 1, s44 = 1, s45 = 1, s46 = 1, s47 = 1, s48 = 1, s49 = 1, s50 = 1, s51 = 1, s52 = 1, s53 = 1, s54 = 1, s55 = 1, s56 = 1, s57 = 1, s58 = 1, s59 = 1, s60 = 1, s61 = 1, s62 = 1, s63 = 1, s64 = 1, s65 = 1, s66 = 1, s67 = 1, s68 = 1, s69 = 1, s70 = 1;
        eq e0: s0 * s0 == phi + 2;
        eq e1: s1 * s1 == phi + 3;
        eq e2: s2 * s2 == phi + 4;
        eq e3: s3 * s3 == phi + 5;
        eq e4: s4 * s4 == phi + 6;
        eq e5: s5 * s5 == phi + 7;
        eq e6: s6 * s6 == phi + 8;
        eq e7: s7 * s7 == phi + 9;
        eq e8: s8 * s8 == phi + 10;
        eq e9: s9 * s9 == phi + 11;
        eq e10: s10 * s10 == phi + 12;
        eq e11: s11 * s11 == phi + 13;
        eq e12: s12 * s12 == phi + 14;
        eq e13: s13 * s13 == phi + 15;
        eq e14: s14 * s14 == phi + 16;
        eq e15: s15 * s15 == phi + 17;
        eq e16: s16 * s16 == phi + 18;
        eq e17: s17 * s17 == phi + 19;
        eq e18: s18 * s18 == phi + 20;
        eq e19: s19 * s19 == phi + 21;
        eq e20: s20 * s20 == phi + 22;
        eq e21: s21 * s21 == phi + 23;
        eq e22: s22 * s22 == phi + 24;
        eq e23: s23 * s23 == phi + 25;
        eq e24: s24 * s24 == phi + 26;
        eq e25: s25 * s25 == phi + 27;
        eq e26: s26 * s26 == phi + 28;
        eq e27: s27 * s27 == phi + 29;
        eq e28: s28 * s28 == phi + 30;
        eq e29: s29 * s29 == phi + 31;
        eq e30: s30 * s30 == phi + 32;
        eq e31: s31 * s31 == phi + 33;
        eq e32: s32 * s32 == phi + 34;
        eq e33: s33 * s33 == phi + 35;
        eq e34: s34 * s34 == phi + 36;
        eq e35: s35 * s35 == phi + 37;
        eq e36: s36 * s36 == phi + 38;
        eq e37: s37 * s37 == phi + 39;
        eq e38: s38 * s38 == phi + 40;
        eq e39: s39 * s39 == phi + 41;
        eq e40: s40 * s40 == phi + 42;
        eq e41: s41 * s41 == phi + 43;
        eq e42: s42 * s42 == phi + 44;
        eq e43: s43 * s43 == phi + 45;
        eq e44: s44 * s44 == phi + 46;
        eq e45: s45 * s45 == phi + 47;
        eq e46: s46 * s46 == phi + 48;
        eq e47: s47 * s47 == phi + 49;
        eq e48: s48 * s48 == phi + 50;
        eq e49: s49 * s49 == phi + 51;
        eq e50: s50 * s50 == phi + 52;
        eq e51: s51 * s51 == phi + 53;
        eq e52: s52 * s52 == phi + 54;
        eq e53: s53 * s53 == phi + 55;
        eq e54: s54 * s54 == phi + 56;
        eq e55: s55 * s55 == phi + 57;
        eq e56: s56 * s56 == phi + 58;
        eq e57: s57 * s57 == phi + 59;
        eq e58: s58 * s58 == phi + 60;
        eq e59: s59 * s59 == phi + 61;
        eq e60: s60 * s60 == phi + 62;
        eq e61: s61 * s61 == phi + 63;
        eq e62: s62 * s62 == phi + 64;
        eq e63: s63 * s63 == phi + 65;
        eq e64: s64 * s64 == phi + 66;
        eq e65: s65 * s65 == phi + 67;
        eq e66: s66 * s66 == phi + 68;
        eq e67: s67 * s67 == phi + 69;
        eq e68: s68 * s68 == phi + 70;
        eq e69: s69 * s69 == phi + 71;
        eq e70: s70 * s70 == phi * phi;
    }
}

#[test]
fn a_branch_flip_in_block_seventy_is_caught() {
    use kinloop::Mechanism;
    let m = ManyBlocks {};
    let g = m.guess(1.0);
    // Stopping at the crossing (the default) names the block.
    let mut s = m.sweep(1.0, -1.0, 5, &g).unwrap();
    let stop = s.by_ref().find_map(|r| r.err()).expect("the crossing must stop the sweep");
    assert!(matches!(stop, Error::SweepStopped { kind: EventKind::SingularCrossing, .. }), "{stop}");
    let ev = &s.events()[0];
    let (index, info) = ev.block.clone().expect("the flipped block is named");
    assert_eq!(info.unknowns, &["s70"][..]);
    assert!(index >= 64, "{index}");
    assert_close!(ev.x[0], 0.0, tol::LOCATED, "{:?}", ev.x);
    // Passing it, the mode of block 70 is seen to change.
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    let all: Vec<_> = m.sweep(1.0, -1.0, 5, &g).unwrap().with_config(cfg).collect::<Result<_, _>>().unwrap();
    let (first, last) = (all[0].health.det_signs, all[4].health.det_signs);
    assert_eq!(first.first_difference(&last), Some(index));
    assert_close!(all[4].q.s70, -1.0, tol::ULPS, "{}", all[4].q.s70);
    let _ = <ManyBlocks as Mechanism<71, 1, 0>>::BLOCKS;
}

/// Five-bar with equal cranks (`a = e = 1`) and equal links (`b = c = 2`): where the cranks'
/// joints B and D coincide (`cos th1 = d / 2`, `th2 = pi - th1`, from `|B - (d, 0)| = e`),
/// the Jacobian and `[J | dF/dx]` are both singular, and branches cross: the motion goes on.
/// The continuation used to leave that point on the crossing branch, whose input reverses, and
/// reported a limit position that `AtSingular::Continue` could not pass.
/// Sweeps of the five-bar `$m` (of type `$ty`) through, and 0.01 rad aside, the point where
/// its joints coincide.
macro_rules! five_bar_crossing {
    ($ty:ty, $m:expr) => {{
        use kinloop::{Kin, Mechanism};
        let m: $ty = $m;
        let th1 = (m.d / 2.0).acos();
        let star = [th1, std::f64::consts::PI - th1];
        let from = [2.0, 1.0];
        let sweep = |to: [f64; 2], at_singular: AtSingular, samples: usize, guess: [f64; 2]| {
            let cfg = SweepConfig::default().with_at_singular(at_singular);
            let mut s = kinloop::Sweep::<$ty, Kin<2, 2, 3>, 2, 2, 3>::new(&m, from, to, samples, guess)
                .unwrap()
                .with_config(cfg);
            let states: Vec<_> = s.by_ref().collect();
            (states, s.events().to_vec())
        };
        // The residual of a state relative to the loop's magnitude (the sum of its lengths).
        let size = m.a + m.b + m.c + m.d + m.e;
        let closes = |k: &Kin<2, 2, 3>| m.residual_flat(&k.x, &k.q).iter().all(|r| r.abs() <= tol::SOLVE * size);
        let through = [2.0 * star[0] - from[0], 2.0 * star[1] - from[1]];
        let modes = kinloop::Named::assembly_modes(&m, from).unwrap();
        assert_eq!(modes.len(), 2);
        for mode in &modes {
            let guess = [mode.q.phi2, mode.q.phi3];
            for samples in [2, 64] {
                let (states, events) = sweep(through, AtSingular::Stop, samples, guess);
                let stop = states.iter().find_map(|r| r.as_ref().err());
                assert!(
                    matches!(stop, Some(Error::SweepStopped { kind: EventKind::SingularCrossing, .. })),
                    "{stop:?}"
                );
                assert_eq!(events.len(), 1);
                // A branch point is located to about `sqrt(eps)` in the input (the determinant and
                // the path's rate both vanish there to first order only along some directions).
                assert_close!(events[0].x[0], star[0], 1e-7, "{events:?} vs {star:?}");
                assert_close!(events[0].x[1], star[1], 1e-7, "{events:?} vs {star:?}");
                let (states, events) = sweep(through, AtSingular::Continue, samples, guess);
                assert_eq!(states.len(), samples);
                assert!(states.iter().all(|r| r.as_ref().is_ok_and(closes)), "{states:?}");
                assert_eq!(events.iter().map(|e| e.kind).collect::<Vec<_>>(), [EventKind::SingularCrossing]);
            }
            // A path 0.01 rad aside passes near the point with no event.
            let (states, events) = sweep([through[0] + 0.01, through[1] + 0.01], AtSingular::Stop, 64, guess);
            assert!(states.iter().all(|r| r.as_ref().is_ok_and(closes)) && events.is_empty(), "{events:?}");
        }
    }};
}

#[test]
fn five_bar_coincident_joints_are_a_crossing_not_a_limit_position() {
    five_bar_crossing!(FiveBarNewton, FiveBarNewton { a: 1.0, b: 2.0, c: 2.0, d: 1.5, e: 1.0 });
}

/// The same through the closed-form dyad of the fixtures' five-bar. Where the joints coincide,
/// a whole circle of positions (`phi2 = phi3`, any angle) crosses both assembly modes; the
/// continuation locating the event used to land on that circle, along which the input does not
/// move, and reported a limit position (whether it did depended on the last digits of the
/// starting position, which the closed form and Newton round differently).
#[test]
fn five_bar_coincident_joints_are_a_crossing_through_the_closed_form_too() {
    use kinloop_fixtures::FiveBar;
    five_bar_crossing!(FiveBar, FiveBar { a: 1.0, b: 2.0, c: 2.0, d: 1.5, e: 1.0 });
}

/// Paths through the point where the joints coincide, in six directions, both assembly modes:
/// the closed-form dyad and Newton report the same single crossing at that point and the same
/// states at every sample, on both sides of it.
#[test]
fn five_bar_crossings_are_the_same_through_the_closed_form_and_newton() {
    use kinloop::{Kin, Named};
    use kinloop_fixtures::FiveBar;
    let closed = FiveBar { a: 1.0, b: 2.0, c: 2.0, d: 1.5, e: 1.0 };
    let newton = FiveBarNewton { a: 1.0, b: 2.0, c: 2.0, d: 1.5, e: 1.0 };
    let th1 = (closed.d / 2.0).acos();
    let star = [th1, std::f64::consts::PI - th1];
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    for k in 0..6 {
        let angle = 0.1 + k as f64 * std::f64::consts::PI / 6.0;
        let step = [1.2 * angle.cos(), 1.2 * angle.sin()];
        let (from, to) = ([star[0] - step[0], star[1] - step[1]], [star[0] + step[0], star[1] + step[1]]);
        for mode in Named::assembly_modes(&closed, from).unwrap() {
            let guess = [mode.q.phi2, mode.q.phi3];
            let mut a = kinloop::Sweep::<FiveBar, Kin<2, 2, 3>, 2, 2, 3>::new(&closed, from, to, 64, guess)
                .unwrap()
                .with_config(cfg);
            let mut b = kinloop::Sweep::<FiveBarNewton, Kin<2, 2, 3>, 2, 2, 3>::new(&newton, from, to, 64, guess)
                .unwrap()
                .with_config(cfg);
            let (sa, sb): (Vec<_>, Vec<_>) = (a.by_ref().collect(), b.by_ref().collect());
            assert_eq!(sa.len(), 64);
            assert_eq!(sb.len(), 64);
            for (x, y) in sa.iter().zip(&sb) {
                let (x, y) = (x.as_ref().unwrap(), y.as_ref().unwrap());
                // Samples stay at least 1/126 of the path from the singular point: well conditioned.
                assert!(x.q.iter().zip(&y.q).all(|(p, q)| (p - q).abs() < 1e-12), "{k}: {:?} vs {:?}", x.q, y.q);
            }
            for events in [a.events(), b.events()] {
                assert_eq!(events.len(), 1, "{k}: {events:?}");
                assert_eq!(events[0].kind, EventKind::SingularCrossing);
                // A branch point is located to a few `sqrt(eps)` in the input (measured: up to
                // 1.3e-7 over these paths): the residual grows only quadratically off it along the
                // circle of positions through it.
                let off = [events[0].x[0] - star[0], events[0].x[1] - star[1]];
                assert_close!(off[0], 0.0, 5e-7, "{k}: {off:?} {events:?}");
                assert_close!(off[1], 0.0, 5e-7, "{k}: {off:?} {events:?}");
            }
        }
    }
}

kinloop::mechanism! {
    /// The fixtures' five-bar solved by Newton (the fixture's dyad is solved in closed form).
    #[kinloop(newton)]
    pub struct FiveBarNewton {
        params a = 1.0, b = 2.5, c = 2.2, d = 1.5, e = 1.2;
        inputs th1, th2;
        unknowns phi2 = 1.0, phi3 = 2.0;
        loop abcde: a @ th1 + b @ phi2 == (d, 0) + e @ th2 + c @ phi3;
        point pc = a @ th1 + b @ phi2;
        output spread = phi3 - phi2;
    }
}
