//! A run-time model's kinematic step beside the compiled step of the same declaration, and the
//! time to read and plan the gallery's declarations (`Model::read`).
//!
//! Both steps run in the same harness: one point step per iteration along turns of 720 steps,
//! each warm-started from the previous position, the sum of the outputs and the first analog
//! into `black_box`, in a loop out of line as `benches/src/bin/step_count.rs` runs them under
//! callgrind.
//!
//! ```text
//! cargo bench -p kinloop-model --bench step
//! ```

use criterion::{BenchmarkGroup, Criterion, criterion_group, criterion_main, measurement::WallTime};
use kinloop::{Mechanism, NewtonConfig};
use kinloop_fixtures as fx;
use kinloop_model::Model;
use std::f64::consts::TAU;
use std::hint::black_box;
use std::time::{Duration, Instant};

const TURN: usize = 720;

/// Input 0 at step `k` of a turn.
fn input(k: usize) -> f64 {
    TAU * (k % TURN) as f64 / TURN as f64
}

fn compiled<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    m: &M,
) {
    // Opaque: the generated `kinematics_flat` is `#[inline]`, and a local constant configuration
    // would let the compiled kernel fold its tolerances where the run-time step reads them.
    let cfg = black_box(NewtonConfig::default());
    let q0 = m.guess_flat(&[0.0; NI]);
    g.bench_function(format!("{name}/compiled"), |b| b.iter_custom(|iters| compiled_steps(m, &cfg, q0, iters)));
}

/// `iters` compiled steps from input 0 and the time they took: the loop of
/// `benches/src/bin/step_count.rs`, out of line with the mechanism borrowed shared, so that
/// what depends on its parameters alone (the rhombic drive's sines and cosines of `gamma` and
/// `psi_s1`) is computed once, as the run-time model computes it when its parameters are set.
/// (In criterion's `iter` closure the mechanism was read again after every `black_box`, and
/// the compiled step paid two `sincos` a step the model does not.)
#[inline(never)]
fn compiled_steps<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    cfg: &NewtonConfig,
    mut q: [f64; N],
    iters: u64,
) -> Duration {
    let start = Instant::now();
    for k in 0..iters as usize {
        let mut x = [0.0; NI];
        x[0] = input(k);
        let s = m.kinematics_flat(black_box(&x), &q, cfg).expect("solve");
        q = s.q;
        black_box(s.out.iter().sum::<f64>() + s.dq[0][0]);
    }
    start.elapsed()
}

fn runtime(g: &mut BenchmarkGroup<'_, WallTime>, name: &str, m: &mut Model) {
    // Opaque, as for the compiled step: both read the configuration at run time.
    let cfg = black_box(NewtonConfig::default());
    let ni = m.inputs().len();
    let mut q0 = vec![0.0; m.unknowns().len()];
    m.guess(&vec![0.0; ni], &mut q0).expect("guess");
    g.bench_function(format!("{name}/runtime"), |b| b.iter_custom(|iters| runtime_steps(m, &cfg, &q0, iters)));
}

/// [`compiled_steps`] of a run-time model.
#[inline(never)]
fn runtime_steps(m: &mut Model, cfg: &NewtonConfig, q0: &[f64], iters: u64) -> Duration {
    let mut q = q0.to_vec();
    let mut x = vec![0.0; m.inputs().len()];
    let start = Instant::now();
    for k in 0..iters as usize {
        x[0] = input(k);
        let s = m.kinematics(black_box(&x), &q, cfg).expect("solve");
        q.copy_from_slice(&s.q);
        black_box(s.out.iter().sum::<f64>() + s.dq[0]);
    }
    start.elapsed()
}

fn model(text: &str, params: &[(&str, f64)]) -> Model {
    let mut m = Model::read("bench.kl", text).expect("valid declaration");
    for (p, v) in params {
        m.set_param(p, *v);
    }
    m
}

fn steps(c: &mut Criterion) {
    let mut g = c.benchmark_group("step");
    compiled(&mut g, "rhombic", &fx::RhombicDrive::default());
    runtime(&mut g, "rhombic", &mut model(fx::RHOMBIC_DRIVE_TEXT, &[]));
    compiled(&mut g, "four-bar", &fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 });
    runtime(&mut g, "four-bar", &mut model(fx::FOUR_BAR_TEXT, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]));
    compiled(&mut g, "class-four", &fx::ClassFour::default());
    runtime(&mut g, "class-four", &mut model(fx::CLASS_FOUR_TEXT, &[]));
    g.finish();
}

fn read(c: &mut Criterion) {
    let mut g = c.benchmark_group("read");
    for (name, text) in [
        ("rhombic", fx::RHOMBIC_DRIVE_TEXT),
        ("displacer-rod-drive", fx::DISPLACER_ROD_DRIVE_TEXT),
        ("working-rod-drive", fx::WORKING_ROD_DRIVE_TEXT),
        ("five-bar", fx::FIVE_BAR_TEXT),
        ("class-four", fx::CLASS_FOUR_TEXT),
        ("gear-lever", fx::gear_lever::GEAR_LEVER_TEXT),
        ("roller-edger", fx::roller_edger::ROLLER_EDGER_TEXT),
    ] {
        g.bench_function(name, |b| b.iter(|| Model::read("bench.kl", black_box(text)).expect("valid declaration")));
    }
    g.finish();
}

criterion_group!(benches, steps, read);
criterion_main!(benches);
