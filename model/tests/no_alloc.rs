//! A run-time step (with its parameter sensitivities) allocates nothing once the model is built:
//! a counting allocator sees no allocation over a sweep of steps (closed forms, linear blocks,
//! Newton blocks, sparse Newton blocks and their dense fallback).

use kinloop::NewtonConfig;
use kinloop_fixtures as fx;
use kinloop_model::Model;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to the system allocator, only counting.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: the caller's layout is passed on unchanged.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` was allocated by `System` with `layout`.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// The tests count allocations of the whole process: one at a time.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

#[test]
fn steps_do_not_allocate() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let dense = format!(
        "#[kinloop(dense)] {}",
        fx::RHOMBIC_DRIVE_TEXT.replacen("struct RhombicDrive ", "struct RhombicDriveDense ", 1)
    );
    // A ring of nine four-bar loops closed through a differential (one sparse block), at link
    // lengths where some static pivots of the turn are weak (the dense fallback).
    let unknowns: Vec<String> = (0..9).map(|i| format!("u{i} = 0.6, v{i} = 1.9")).collect();
    let mut loops = vec!["loop l0: a @ (0.5 * (phi + v8)) + b @ u0 == (d, 0) + c @ v0;".to_string()];
    loops.extend((1..9).map(|i| format!("loop l{i}: a @ v{} + b @ u{i} == (d, 0) + c @ v{i};", i - 1)));
    let ring = format!(
        "pub struct Ring9 {{ params a = 2.0, b = 2.0, c = 4.0, d = 2.0; input phi; unknowns {}; {} }}",
        unknowns.join(", "),
        loops.join(" ")
    );
    let texts = [fx::RHOMBIC_DRIVE_TEXT, dense.as_str(), fx::CLASS_FOUR_TEXT, kinloop_bench::ring::RING, ring.as_str()];
    for text in texts {
        let mut m = Model::read("m.kl", text).expect("valid");
        let cfg = NewtonConfig::default();
        let mut q = vec![0.0; m.unknowns().len()];
        let mut x = [0.0];
        m.guess(&x, &mut q).expect("guess");
        let before = ALLOCATIONS.load(Ordering::Relaxed);
        let mut dense = 0;
        for k in 0..200 {
            x[0] = k as f64 * 0.03;
            let (s, _) = m.sensitivities(&x, &q, &cfg).expect("step");
            q.copy_from_slice(&s.q);
            dense += usize::from(m.dense_fallback(0) == Some(true));
        }
        if text == ring {
            assert!(dense > 0, "the dense fallback was not exercised");
        }
        let during = ALLOCATIONS.load(Ordering::Relaxed) - before;
        assert_eq!(during, 0, "{}: {during} allocations in 200 steps", m.name());
    }
}

/// A run-time model's sweep allocates its workspace once (states, prediction, input: boxed
/// slices of the model's sizes) and nothing per sample: samples 2 to 200 of a whole turn cost
/// no allocation, read in place with `next_ref`.
#[test]
fn sweep_steps_do_not_allocate() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    for text in [fx::RHOMBIC_DRIVE_TEXT, fx::CLASS_FOUR_TEXT] {
        let mut m = Model::read("m.kl", text).expect("valid");
        let mut g = vec![0.0; m.unknowns().len()];
        m.guess(&[0.0], &mut g).expect("guess");
        let mut sweep = m.sweep(&[0.0], &[std::f64::consts::TAU], 200, &g).expect("sweep");
        sweep.next_ref().expect("a first sample").expect("solved");
        let before = ALLOCATIONS.load(Ordering::Relaxed);
        let mut samples = 1;
        while let Some(k) = sweep.next_ref() {
            k.expect("solved");
            samples += 1;
        }
        let during = ALLOCATIONS.load(Ordering::Relaxed) - before;
        assert_eq!(samples, 200);
        assert_eq!(during, 0, "{during} allocations in 199 samples");
    }
}
