//! A run-time step (with its parameter sensitivities) allocates nothing once the model is built:
//! a counting allocator sees no allocation over a sweep of steps (closed forms, linear blocks,
//! Newton blocks, sparse Newton blocks and their dense fallback), nor a sweep's samples, nor the
//! dynamics of a model at a state.

use kinloop::NewtonConfig;
use kinloop::dims::{KinBuf, Sizes};
use kinloop::dynamics::DynamicsBuf;
use kinloop_fixtures as fx;
use kinloop_model::Model;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    /// Allocations made by this thread: the test harness's own, on the threads of other tests
    /// (a test that ends while another counts), are not the counted code's.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// The allocations this thread has made so far.
fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

// SAFETY: forwards to the system allocator, only counting.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // A const-initialised cell: no allocation of its own; none after the thread's end.
        let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
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

/// The tests run one at a time (each counts its own thread's allocations).
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
        let before = allocations();
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
        let during = allocations() - before;
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
        let before = allocations();
        let mut samples = 1;
        while let Some(k) = sweep.next_ref() {
            k.expect("solved");
            samples += 1;
        }
        let during = allocations() - before;
        assert_eq!(samples, 200);
        assert_eq!(during, 0, "{during} allocations in 199 samples");
    }
}

/// A run-time model's dynamics at a state allocates nothing once its mass model and buffers
/// are built: the loads' segment, the mass matrix, the generalised forces, the shaking and the
/// driving torque over a turn of steps.
#[test]
fn the_dynamics_of_a_step_does_not_allocate() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
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
    let before = allocations();
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
    let after = allocations();
    assert!(torque.is_finite());
    assert_eq!(after - before, 0, "allocations over 100 steps of the dynamics");
}

/// A run-time model's simulation allocates nothing per step: each evaluation of the right-hand
/// side (the model's step written in place, the loads' segment, the mass model) allocates
/// nothing, and the recorded trajectory grows by doubling. A run of over twenty times the steps of a
/// short one costs at most one allocation per doubling of the trajectory more.
#[test]
fn a_simulation_s_steps_do_not_allocate() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let mut m = Model::read("engine.kl", fx::ENGINE_MACHINE_TEXT).expect("valid");
    let cfg = kinloop::dynamics::RunConfig::default().with_flywheel(0.05);
    let mut run = |turns: f64| {
        let stop = move |_: f64, y: &[f64; 2]| y[0] > turns * std::f64::consts::TAU;
        let before = allocations();
        let run =
            m.simulation().start(0.3, 150.0).drive(|_, _, w| 4.0 - 0.01 * w).config(cfg).stop_when(stop).run(10.0);
        let during = allocations() - before;
        (during, run.expect("a run").steps.len())
    };
    let (short, short_steps) = run(0.5);
    let (long, long_steps) = run(15.0);
    assert!(long_steps > 20 * short_steps, "{long_steps} steps against {short_steps}");
    // Each step evaluates the right-hand side six times: thousands of evaluations more.
    let doublings = long_steps.ilog2() as usize + 1;
    assert!(long <= short + doublings, "{long} allocations in {long_steps} steps, {short} in {short_steps}");
    eprintln!("simulation: {short} allocations in {short_steps} steps, {long} in {long_steps}");
}

/// A simulation that hands each step over as it is made (`run_steps`) allocates nothing per
/// step, the run-time model's and the compiled mechanism's: a run of over twenty times the
/// steps of a short one makes exactly as many allocations (the setup's).
#[test]
fn a_streamed_simulation_allocates_nothing_per_step() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let mut m = Model::read("engine.kl", fx::ENGINE_MACHINE_TEXT).expect("valid");
    let engine = fx::EngineMachine::default();
    let mass = engine.mass_model().expect("a mass model");
    let cfg = kinloop::dynamics::RunConfig::default().with_flywheel(0.05);
    let motor = |_: f64, _: f64, w: f64| 4.0 - 0.01 * w;
    // The allocations of a run to `turns` turns and its steps, of the run-time model and of the
    // compiled mechanism.
    let mut run = |turns: f64| {
        let until = move |y: &[f64; 2]| y[0] > turns * std::f64::consts::TAU;
        let (mut model_steps, mut compiled_steps) = (0usize, 0usize);
        let before = allocations();
        let r = m.simulation().start(0.3, 150.0).drive(motor).config(cfg).run_steps(10.0, |_, y| {
            model_steps += 1;
            until(y)
        });
        let model = allocations() - before;
        r.expect("a run");
        let before = allocations();
        let r = kinloop::dynamics::Simulation::new(&engine, &mass)
            .start(0.3, 150.0)
            .drive(motor)
            .config(cfg)
            .run_steps(10.0, |_, y| {
                compiled_steps += 1;
                until(y)
            });
        let compiled = allocations() - before;
        r.expect("a run");
        ((model, model_steps), (compiled, compiled_steps))
    };
    let (short_model, short_compiled) = run(0.5);
    let (long_model, long_compiled) = run(15.0);
    for (what, short, long) in [("model", short_model, long_model), ("compiled", short_compiled, long_compiled)] {
        assert!(long.1 > 20 * short.1, "{what}: {} steps against {}", long.1, short.1);
        assert_eq!(long.0, short.0, "{what}: allocations in {} steps, in {}", long.1, short.1);
        eprintln!("streamed {what} simulation: {} allocations in {} steps, {} in {}", short.0, short.1, long.0, long.1);
    }
}

/// A column found by name on a run-time model's kernel (`ColumnOf<K> for &str`) allocates
/// nothing, and is the column the compiled mechanism's `Column::named` finds; a name that is no
/// column gives the compiled lookup's error, listing the columns.
#[test]
fn a_column_found_by_name_does_not_allocate() {
    use kinloop::analysis::{Column, ColumnOf};
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let mut m = Model::read("four_bar.kl", fx::FOUR_BAR_TEXT).expect("valid");
    for p in ["a", "b", "c", "d"] {
        m.set_param(p, 1.0);
    }
    let k = m.kernel(kinloop::SweepConfig::default()).expect("a kernel");
    let names = ["phi", "beta", "gamma", "pc.x", "pc.y"];
    let mut found = [None; 5];
    let before = allocations();
    for (slot, name) in found.iter_mut().zip(names) {
        *slot = Some(name.resolve(&k).expect("a column"));
    }
    let after = allocations();
    assert_eq!(after - before, 0, "allocations resolving {} names", names.len());
    for (index, name) in found.iter().zip(names) {
        assert_eq!(*index, Some(Column::<fx::FourBar>::named(name).expect("compiled").index()), "{name}");
    }
    // The error lists the columns: the counter sees its allocations.
    let before = allocations();
    let r_err = "delta".resolve(&k).unwrap_err();
    assert!(allocations() > before);
    assert_eq!(r_err, Column::<fx::FourBar>::named("delta").unwrap_err());
    assert_eq!(
        r_err.to_string(),
        "invalid argument: `delta` is no column of `FourBar`: inputs phi; unknowns beta, gamma; outputs pc.x, pc.y"
    );
}

/// The positions-only solve allocates nothing: closed forms with their lever tests (the rhombic
/// drive) and a Newton block (the class IV group), over a turn.
#[test]
fn positions_do_not_allocate() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    for text in [fx::RHOMBIC_DRIVE_TEXT, fx::CLASS_FOUR_TEXT] {
        let mut m = Model::read("m.kl", text).expect("valid");
        let cfg = NewtonConfig::default();
        let mut q = vec![0.0; m.unknowns().len()];
        m.guess(&[0.0], &mut q).expect("guess");
        let before = allocations();
        for step in 0..100 {
            let x = [std::f64::consts::TAU * step as f64 / 100.0];
            let p = m.positions(&x, &q, &cfg).expect("positions");
            q.copy_from_slice(p);
        }
        let after = allocations();
        assert_eq!(after - before, 0, "{}: allocations over 100 positions-only solves", m.name());
    }
}

/// The synthesis kernel's calls on a model (`SensKernel::sensitivities_into`, `position_into`,
/// `sensitivities_at_into`: a step with its sensitivities, a position with its outputs, the
/// sensitivities at a solved position, copied into the caller's buffers) allocate nothing.
#[test]
fn synthesis_kernel_calls_do_not_allocate() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let mut m = Model::read("m.kl", fx::RHOMBIC_DRIVE_TEXT).expect("valid");
    let k = m.kernel(kinloop::SweepConfig::default()).expect("parameters set");
    let during = synthesis_calls_allocations(&k);
    assert_eq!(during, 0, "{during} allocations in 100 steps");
}

/// The allocations of 100 steps of the synthesis kernel's calls on `k` (their buffers made
/// before), with a check that the sensitivities were written.
fn synthesis_calls_allocations<K>(k: &K) -> usize
where
    K: kinloop::SensKernel<Sens = kinloop_model::ModelSens, Dims = kinloop::dims::Sizes>,
{
    use kinloop::dims::Dims;
    let cfg = NewtonConfig::default();
    let mut x = k.dims().x();
    let mut q = k.guess(&x);
    let (mut kin, mut sens, mut out) = (k.dims().kin(), k.sens(), vec![0.0; k.dims().no()]);
    let mut at = k.dims().q();
    let before = allocations();
    for step in 0..100 {
        x.0[0] = step as f64 * 0.06;
        k.sensitivities_into(&x, &q, &cfg, &mut kin, &mut sens).expect("step");
        k.position_into(&x, &q, &cfg, &mut at, &mut out).expect("position");
        k.sensitivities_at_into(&x, &at, &cfg, &mut kin, &mut sens).expect("at a position");
        q.0.copy_from_slice(&kin.q);
    }
    let during = allocations() - before;
    assert!(sens.q.iter().any(|v| *v != 0.0), "sensitivities written");
    during
}

/// The same calls on a model's kernel that threads can share (`Model::shared_kernel`) allocate
/// nothing either: inside `with_params` on the clone checked out for it, and outside on a
/// clone of the pool that holds the kernel's parameters already (checked out and given back
/// per call, nothing loaded).
#[test]
fn shared_kernel_calls_do_not_allocate() {
    use kinloop::SensKernel;
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let m = Model::read("m.kl", fx::RHOMBIC_DRIVE_TEXT).expect("valid");
    let shared = m.shared_kernel(kinloop::SweepConfig::default()).expect("parameters set");
    let own: Vec<f64> = (0..shared.param_count()).map(|k| shared.param(k)).collect();
    let count = synthesis_calls_allocations::<kinloop_model::SharedModelKernel>;
    let inside = shared.with_params(&own, count).expect("as many values as parameters");
    assert_eq!(inside, 0, "{inside} allocations in 100 steps inside with_params");
    let outside = count(&shared);
    assert_eq!(outside, 0, "{outside} allocations in 100 steps outside with_params");
}
