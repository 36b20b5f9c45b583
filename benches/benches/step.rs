//! One kinematic step (positions + velocity analogs + acceleration analogs of the 4 unknowns)
//! at the next of 1,000,000 equally spaced crank angles per turn, warm-started from the previous
//! step. Every variant of a group runs in this one binary, one after the other; each is first
//! checked over a whole turn against the reference (the closed form for the rhombic drive, the
//! hand-written Newton for the class IV block) with the same warm-start policy. `kinloop_sweep`
//! (in the taylor groups only) is kinloop's own `Sweep`: see [`bench_kinloop_sweep`].
//!
//! `cargo bench -p kinloop-bench --bench step`; `cargo run --release -p kinloop-bench --bin
//! report` then prints the table of medians and ratios.

use std::hint::black_box;
use std::time::Duration;

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, criterion_group, criterion_main};
use kinloop::Mechanism;
use kinloop_bench::class_four::{self, HandNewton};
use kinloop_bench::kinloop_variants::{Kinloop, KinloopNamed, KinloopSweep, check_kinloop_sweep};
use kinloop_bench::rhombic::{self, ClosedForm, DenseFiniteDifference, DenseHandJacobian, DenseNumDual, TwoLoopNewton};
use kinloop_bench::sweep::{
    DIFFERENCED, EXACT, Failed, STEPS, Step, Stepper, Sweep, SweepCheck, WarmStart, check_sweep,
};

/// Prints a variant's check over a whole turn and asserts its deviations are within `tol`.
fn assert_check(name: &str, policy: WarmStart, check: Result<SweepCheck, Failed>, tol: [f64; 3]) {
    let check = check.unwrap_or_else(|e| panic!("{name}: {e}"));
    eprintln!(
        "check {name} ({}): max deviation q {:.1e}, dq {:.1e}, d2q {:.1e}; Newton iterations per step {:.3} (max {})",
        policy.name(),
        check.max_dev[0],
        check.max_dev[1],
        check.max_dev[2],
        check.mean_iterations,
        check.max_iterations
    );
    assert!(
        check.max_dev.iter().zip(tol).all(|(d, t)| *d <= t),
        "{name}: deviation {:?} beyond {tol:?}",
        check.max_dev
    );
}

/// Times one step: one call of `advance` (which passes the step to `black_box`).
fn time_step(g: &mut BenchmarkGroup<'_, WallTime>, name: &str, mut advance: impl FnMut() -> Result<(), Failed>) {
    g.bench_function(name, |b| {
        b.iter(|| {
            if let Err(e) = advance() {
                panic!("{name}: {e}")
            }
        })
    });
}

/// Hands a step to the optimiser as used.
#[inline(always)]
fn consume(step: &Step<4>) {
    black_box(step);
}

/// Checks `s` over a whole turn against `reference`, then times one step.
#[allow(clippy::too_many_arguments)]
fn bench<S: Stepper<4>, R: Stepper<4>>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    s: &S,
    reference: &R,
    policy: WarmStart,
    guess0: [f64; 4],
    tol: [f64; 3],
) {
    assert_check(name, policy, check_sweep(s, reference, STEPS, policy, guess0), tol);
    let mut sweep = Sweep::start(s, STEPS, policy, guess0).unwrap();
    time_step(g, name, || sweep.advance(s).map(consume));
}

/// kinloop's own sweep (`kinloop::Sweep`, default `SweepConfig`), in the taylor group since it
/// predicts with its own second-order Taylor predictor. It is checked over a whole turn against
/// `reference` at the angles it samples, with the same tolerances as `kinloop`; then one step is
/// timed like every other variant: one `KinloopSweep::advance`, i.e. one `next_kin()` of the
/// runtime sweep (prediction, the full solve of positions and analogs, and the sweep's
/// branch-safety checks of every step). The runtime sweep ends after a turn of 1,000,000 samples;
/// the new sweep for the next turn is created inside the timed loop, so its cost is counted
/// (amortised over the 1,000,000 steps of a turn; see [`KinloopSweep`]).
fn bench_kinloop_sweep<M: Mechanism<4, 1, NO>, R: Stepper<4>, const NO: usize>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    m: &M,
    reference: &R,
    guess0: [f64; 4],
) {
    let name = "kinloop_sweep";
    assert_check(name, WarmStart::Taylor, check_kinloop_sweep(m, reference, STEPS, guess0), EXACT);
    let mut sweep = KinloopSweep::start(m, STEPS, guess0).unwrap();
    time_step(g, name, || sweep.advance().map(consume));
}

fn rhombic_drive(c: &mut Criterion) {
    // Opaque parameters: no variant may fold them into constants.
    let p = black_box(rhombic::PARAMS);
    let guess0 = rhombic::initial_guess(&p);
    let closed = ClosedForm::new(&p);
    let kl = Kinloop::<_, 0>::new(p.kinloop());
    let named = KinloopNamed::new(p.kinloop());
    for policy in WarmStart::ALL {
        let mut g = c.benchmark_group(format!("rhombic_{}", policy.name()));
        bench(&mut g, "closed_form", &closed, &closed, policy, guess0, EXACT);
        bench(&mut g, "kinloop", &kl, &closed, policy, guess0, EXACT);
        bench(&mut g, "kinloop_named", &named, &closed, policy, guess0, EXACT);
        if policy == WarmStart::Taylor {
            bench_kinloop_sweep::<_, _, 0>(&mut g, &kl.m, &closed, guess0);
        }
        bench(&mut g, "two_loop_newton", &TwoLoopNewton { p }, &closed, policy, guess0, EXACT);
        bench(&mut g, "dense_hand_jacobian", &DenseHandJacobian { p }, &closed, policy, guess0, EXACT);
        bench(&mut g, "dense_num_dual", &DenseNumDual { p }, &closed, policy, guess0, EXACT);
        bench(&mut g, "dense_finite_difference", &DenseFiniteDifference { p }, &closed, policy, guess0, DIFFERENCED);
        g.finish();
    }
}

fn class_four_block(c: &mut Criterion) {
    let p = black_box(class_four::PARAMS);
    let guess0 = class_four::INITIAL_GUESS;
    let hand = HandNewton { p };
    let kl = Kinloop::<_, 0>::new(p.kinloop());
    let named = KinloopNamed::new(p.kinloop());
    for policy in WarmStart::ALL {
        let mut g = c.benchmark_group(format!("class_four_{}", policy.name()));
        bench(&mut g, "hand_newton", &hand, &hand, policy, guess0, EXACT);
        bench(&mut g, "kinloop", &kl, &hand, policy, guess0, EXACT);
        bench(&mut g, "kinloop_named", &named, &hand, policy, guess0, EXACT);
        if policy == WarmStart::Taylor {
            bench_kinloop_sweep::<_, _, 0>(&mut g, &kl.m, &hand, guess0);
        }
        g.finish();
    }
}

fn config() -> Criterion {
    Criterion::default()
        .sample_size(100)
        .warm_up_time(Duration::from_secs(2))
        .measurement_time(Duration::from_secs(6))
        .noise_threshold(0.03)
}

criterion_group! {
    name = step;
    config = config();
    targets = rhombic_drive, class_four_block
}
criterion_main!(step);
