//! Zero heap allocations per step: a counting global allocator (this test binary only) proves
//! that kinloop's position + analog path (`kinematics_flat`, `kinematics_with`, `position_with`)
//! and sweep iteration never allocate on success: kinloop's own `Sweep` (`m.sweep(..)` through
//! `Iterator::next` and `Sweep::new` through `next_kin`, over a whole turn; creating a sweep may
//! allocate and is not counted), and warm-started steps along a turn with either warm-start
//! policy driven by this package's `Sweep`, which uses only the public step API. Error paths may
//! allocate (their `Location` is boxed); they are not exercised here.

use std::f64::consts::TAU;

use kinloop::{Kin, Mechanism, NewtonConfig};
use kinloop_bench::class_four;
use kinloop_bench::decls::ClassFourUnknowns;
use kinloop_bench::kinloop_variants::Kinloop;
use kinloop_bench::rhombic;
use kinloop_bench::ring::Ring;
use kinloop_bench::sweep::{Sweep, WarmStart};

/// Counts this thread's allocations; shared with the root package's `tests/scan.rs`.
#[path = "../../tests/support/counting_alloc.rs"]
mod counting_alloc;

use counting_alloc::allocations;

const STEPS: usize = 2_000;

#[test]
fn the_counter_counts() {
    let ((), n) = allocations(|| {
        let v: Vec<u64> = std::hint::black_box(vec![1, 2, 3]);
        assert_eq!(v.len(), 3);
    });
    assert_eq!(n, 1);
}

/// Allocations of `STEPS` steps of `m` along a turn from the named unknowns `q`, each step
/// through `kinematics_with`, `kinematics_flat` and `position_with`. (A macro: the named API's
/// types differ from mechanism to mechanism.)
macro_rules! step_allocations {
    ($m:expr, $q:expr) => {{
        let m = $m;
        let cfg = NewtonConfig::default();
        let mut q = $q;
        let h = TAU / STEPS as f64;
        allocations(|| {
            for k in 0..STEPS {
                let phi = h * k as f64;
                let s = m.kinematics_with(phi, &q, &cfg).expect("assembles");
                let flat = m.kinematics_flat(&[phi + 0.5 * h], &s.flat.q, &cfg).expect("assembles");
                let (p, _) = m.position_with(phi, &flat.q.into(), &cfg).expect("assembles");
                q = std::hint::black_box(p);
            }
        })
        .1
    }};
}

#[test]
fn rhombic_drive_steps_allocate_nothing() {
    let m = rhombic::PARAMS.kinloop();
    let n = step_allocations!(m, m.guess(0.0));
    assert_eq!(n, 0, "{n} allocations in {STEPS} steps");
}

#[test]
fn class_four_steps_allocate_nothing() {
    let n = step_allocations!(class_four::PARAMS.kinloop(), ClassFourUnknowns::from(class_four::INITIAL_GUESS));
    assert_eq!(n, 0, "{n} allocations in {STEPS} steps");
}

/// The ring of 64 loops: one sparse Newton block of 128 unknowns (its dense fallback, taken only
/// where a static pivot is weak, is never needed along the turn).
#[test]
fn sparse_ring_steps_allocate_nothing() {
    let m = Ring::default();
    let n = step_allocations!(m, m.guess(0.0));
    assert_eq!(n, 0, "{n} allocations in {STEPS} steps");
}

#[test]
fn warm_started_turns_allocate_nothing() {
    let p = rhombic::PARAMS;
    let kl = Kinloop::<_, 0>::new(p.kinloop());
    let c4 = Kinloop::<_, 0>::new(class_four::PARAMS.kinloop());
    for policy in WarmStart::ALL {
        // Starting a sweep solves its first step; iterating it must not allocate.
        let mut sweep = Sweep::start(&kl, STEPS, policy, rhombic::initial_guess(&p)).unwrap();
        let mut sweep4 = Sweep::start(&c4, STEPS, policy, class_four::INITIAL_GUESS).unwrap();
        let ((), n) = allocations(|| {
            for _ in 0..2 * STEPS {
                assert!(std::hint::black_box(sweep.advance(&kl)).is_ok());
                assert!(std::hint::black_box(sweep4.advance(&c4)).is_ok());
            }
        });
        assert_eq!(n, 0, "{policy:?}: {n} allocations");
    }
}

/// Allocations of iterating a whole sweep (every sample must be `Ok`).
fn sweep_allocations<T, E: std::fmt::Debug>(mut next: impl FnMut() -> Option<Result<T, E>>) -> usize {
    let mut samples = 0;
    let ((), n) = allocations(|| {
        while let Some(r) = next() {
            std::hint::black_box(r.expect("the sweep goes on"));
            samples += 1;
        }
    });
    assert_eq!(samples, STEPS);
    n
}

/// Allocations of iterating kinloop's own sweep of `m` over a whole turn from the named
/// unknowns `g`: `[m.sweep(..) through Iterator::next, Sweep::new(..) through next_kin]`.
/// Creating the sweeps is not counted.
macro_rules! kinloop_sweep_allocations {
    ($m:expr, $g:expr) => {{
        let m = $m;
        let g = $g;
        let mut named = m.sweep(0.0, TAU, STEPS, &g).unwrap();
        let mut flat = kinloop::Sweep::<_, Kin<4, 1, 0>, 4, 1, 0>::new(&m, [0.0], [TAU], STEPS, g.into()).unwrap();
        let n = [sweep_allocations(|| named.next()), sweep_allocations(|| flat.next_kin())];
        assert!(named.events().is_empty() && flat.events().is_empty());
        n
    }};
}

#[test]
fn kinloop_sweep_iteration_allocates_nothing() {
    let m = rhombic::PARAMS.kinloop();
    assert_eq!(kinloop_sweep_allocations!(m, m.guess(0.0)), [0, 0], "rhombic drive");
    let g = ClassFourUnknowns::from(class_four::INITIAL_GUESS);
    assert_eq!(kinloop_sweep_allocations!(class_four::PARAMS.kinloop(), g), [0, 0], "class IV");
}
