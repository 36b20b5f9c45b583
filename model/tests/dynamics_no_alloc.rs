//! A run-time model's dynamics at a state allocates nothing once its mass model and buffers
//! are built: the loads' segment, the mass matrix, the generalised forces, the shaking and the
//! driving torque over a turn of steps, under a counting allocator.

use kinloop::NewtonConfig;
use kinloop::dims::{KinBuf, Sizes};
use kinloop::dynamics::DynamicsBuf;
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

#[test]
fn the_dynamics_of_a_step_does_not_allocate() {
    let mut m = Model::read("engine.kl", fx::ENGINE_MACHINE_TEXT).expect("valid");
    let mass = m.mass_model().expect("a mass model");
    let sizes = Sizes { n: m.unknowns().len(), ni: 1, no: m.outputs().len() };
    let mut k = KinBuf::zeros(sizes);
    let mut d = DynamicsBuf::zeros(1);
    let mut tau = [0.0];
    let cfg = NewtonConfig::default();
    let mut guess = vec![0.0; sizes.n];
    m.guess(&[0.0], &mut guess).expect("guess");
    let (w, eps) = ([150.0], [3.0]);
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    let mut torque = 0.0;
    for step in 0..100 {
        let x = [std::f64::consts::TAU * step as f64 / 100.0];
        let st = m.kinematics(&x, &guess, &cfg).expect("a step");
        guess.copy_from_slice(&st.q);
        for (to, from) in [(&mut k.x, &st.x), (&mut k.q, &st.q), (&mut k.dq, &st.dq), (&mut k.d2q, &st.d2q)] {
            to.copy_from_slice(from);
        }
        for (to, from) in [(&mut k.out, &st.out), (&mut k.dout, &st.dout), (&mut k.d2out, &st.d2out)] {
            to.copy_from_slice(from);
        }
        let loads = m.load_values(&k).expect("loads");
        mass.dynamics_into(&k, &w, loads, &mut d).expect("dynamics");
        let s = mass.shaking(&k, &w, &eps, [0.0, 0.0]).expect("shaking");
        d.checked_drive_into(&x, &w, &eps, &mut tau).expect("torque");
        torque += tau[0] + s.moment;
    }
    let after = ALLOCATIONS.load(Ordering::Relaxed);
    assert!(torque.is_finite());
    assert_eq!(after - before, 0, "allocations over 100 steps of the dynamics");
}
