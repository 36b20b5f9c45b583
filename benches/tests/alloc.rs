//! Zero heap allocations per step: a counting global allocator (this test binary only) proves
//! that kinloop's position + analog path (`kinematics_flat`, `kinematics_with`, `position_with`)
//! and sweep iteration (warm-started steps along a turn, with either warm-start policy, driven
//! by this package's `Sweep`, which uses only the public step API) never allocate on success. Error paths may allocate (their `Location` is boxed); they are not
//! exercised here.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use kinloop::{Mechanism, NewtonConfig};
use kinloop_bench::class_four;
use kinloop_bench::decls::{ClassFourUnknowns, RhombicDriveUnknowns};
use kinloop_bench::rhombic::{self, Kinloop};
use kinloop_bench::sweep::{Sweep, WarmStart};

/// Counts the allocations made by the current thread while counting is switched on (tests run
/// on several threads; each counts only its own).
struct Counting;

thread_local! {
    static ON: Cell<bool> = const { Cell::new(false) };
    static COUNT: Cell<usize> = const { Cell::new(0) };
}

fn note() {
    // `try_with`: the allocator may run while a thread's locals are being torn down.
    let _ = ON.try_with(|on| {
        if on.get() {
            let _ = COUNT.try_with(|c| c.set(c.get() + 1));
        }
    });
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note();
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note();
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Allocations made by `f` on this thread.
fn allocations(f: impl FnOnce()) -> usize {
    COUNT.with(|c| c.set(0));
    ON.with(|on| on.set(true));
    f();
    ON.with(|on| on.set(false));
    COUNT.with(|c| c.get())
}

const STEPS: usize = 2_000;

#[test]
fn the_counter_counts() {
    let n = allocations(|| {
        let v: Vec<u64> = std::hint::black_box(vec![1, 2, 3]);
        assert_eq!(v.len(), 3);
    });
    assert_eq!(n, 1);
}

#[test]
fn rhombic_drive_steps_allocate_nothing() {
    let m = rhombic::PARAMS.kinloop();
    let cfg = NewtonConfig::default();
    let mut q = m.guess(0.0);
    let h = std::f64::consts::TAU / STEPS as f64;
    let n = allocations(|| {
        for k in 0..STEPS {
            let phi = h * k as f64;
            let s = m.kinematics_with(phi, &q, &cfg).expect("assembles");
            let flat = m.kinematics_flat(&[phi + 0.5 * h], &s.flat.q, &cfg).expect("assembles");
            let (p, _) = m.position_with(phi, &RhombicDriveUnknowns::from(flat.q), &cfg).expect("assembles");
            q = std::hint::black_box(p);
        }
    });
    assert_eq!(n, 0, "{n} allocations in {STEPS} steps");
}

#[test]
fn class_four_steps_allocate_nothing() {
    let m = class_four::PARAMS.kinloop();
    let cfg = NewtonConfig::default();
    let mut q = ClassFourUnknowns::from(class_four::INITIAL_GUESS);
    let h = std::f64::consts::TAU / STEPS as f64;
    let n = allocations(|| {
        for k in 0..STEPS {
            let phi = h * k as f64;
            let s = m.kinematics_with(phi, &q, &cfg).expect("assembles");
            let flat = m.kinematics_flat(&[phi + 0.5 * h], &s.flat.q, &cfg).expect("assembles");
            q = std::hint::black_box(flat.q.into());
        }
    });
    assert_eq!(n, 0, "{n} allocations in {STEPS} steps");
}

#[test]
fn sweep_iteration_allocates_nothing() {
    let p = rhombic::PARAMS;
    let kl = Kinloop::<_, 0>::new(p.kinloop());
    let c4 = Kinloop::<_, 0>::new(class_four::PARAMS.kinloop());
    for policy in WarmStart::ALL {
        // Starting a sweep solves its first step; iterating it must not allocate.
        let mut sweep = Sweep::start(&kl, STEPS, policy, rhombic::initial_guess(&p)).unwrap();
        let mut sweep4 = Sweep::start(&c4, STEPS, policy, class_four::INITIAL_GUESS).unwrap();
        let n = allocations(|| {
            for _ in 0..2 * STEPS {
                assert!(std::hint::black_box(sweep.advance(&kl)).is_ok());
                assert!(std::hint::black_box(sweep4.advance(&c4)).is_ok());
            }
        });
        assert_eq!(n, 0, "{policy:?}: {n} allocations");
    }
}
