//! One kinematic step (positions + velocity analogs + acceleration analogs of the unknowns)
//! at the next of equally spaced crank angles per turn, warm-started from the previous step.
//! Every variant of a group runs in this one binary, one after the other, in the same loop
//! ([`time_lean`]); each is first checked over a whole turn against the reference (the closed form for the rhombic drive, the
//! hand-written Newton for the class IV block) with the same warm-start policy. `kinloop_sweep`
//! (in the taylor groups and the closed-form rows) is kinloop's own `Sweep`: see
//! [`bench_kinloop_sweep`].
//!
//! * `rhombic_*`, `class_four_*`: 1,000,000 steps a turn, both warm-start policies;
//! * `closed_form_rhombic`, `closed_form_four_bar`, `closed_form_gear_lever`: the closed-form
//!   rows of the callgrind harness `closed_form_step` (720 steps a turn, previous position, the
//!   hand closed forms, kinloop's point step, kinloop's own `Sweep` and the sweep recipe
//!   written by hand, `hand_sweep`), see
//!   [`closed_form_row`]; `class_four_720_previous`: the class IV block on that turn;
//! * `ring_720_previous`: the ring of 64 four-bar loops (one sparse block) and the same loops in
//!   series; `sensitivities_four_bar`: the four-bar's sensitivity solve and its kinematic step
//!   (`ring-point`, `series-point`, `four-bar-sens`, `four-bar-sens-point` of
//!   `closed_form_step`).
//!
//! `cargo bench -p kinloop-bench --bench step`; `cargo run --release -p kinloop-bench --bin
//! report` then prints the table of medians and ratios.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, criterion_group, criterion_main};
use kinloop::Mechanism;
use kinloop_bench::class_four::{self, HandNewton};
use kinloop_bench::decls::{FourBarSens, four_sens};
use kinloop_bench::hand::{FOUR_BAR, FourBarClosed};
use kinloop_bench::hand_sweep::HandSweep;
use kinloop_bench::kinloop_variants::{Kinloop, KinloopNamed, KinloopSens, KinloopSweep, check_kinloop_sweep};
use kinloop_bench::lean::{HandSweepCursor, point_sum};
use kinloop_bench::rhombic::{self, ClosedForm, DenseFiniteDifference, DenseHandJacobian, DenseNumDual, TwoLoopNewton};
use kinloop_bench::ring::{Ring, RingDense, Series};
use kinloop_bench::rows::{RowVisitor, TURN_720, closed_form_rows};
use kinloop_bench::sweep::step_sum;
use kinloop_bench::sweep::{
    DIFFERENCED, EXACT, Failed, STEPS, Step, Stepper, Sweep, SweepCheck, WarmStart, check_sweep, check_turn,
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

/// Hands a step to the optimiser as used.
#[inline(always)]
fn consume<const N: usize>(step: &Step<N>) {
    black_box(step);
}

/// Hands a step's sum (the lean harness's twelve numbers) to the optimiser as used.
#[inline(always)]
fn consume_sum(sum: f64) {
    black_box(sum);
}

/// Checks `s` over a whole turn of `steps` steps against `reference`, then times one step of
/// such turns.
#[allow(clippy::too_many_arguments)]
fn bench<S: Stepper<N>, R: Stepper<N>, const N: usize>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    s: &S,
    reference: &R,
    policy: WarmStart,
    guess0: [f64; N],
    tol: [f64; 3],
    steps: usize,
) {
    assert_check(name, policy, check_sweep(s, reference, steps, policy, guess0), tol);
    let sweep = Sweep::start(s, steps, policy, guess0).unwrap();
    time_lean(g, name, s, || sweep.clone(), |s, sweep| sweep.advance(s).map(consume));
}

/// kinloop's own sweep (`kinloop::Sweep`, default `SweepConfig`), in the taylor group since it
/// predicts with its own second-order Taylor predictor. It is checked over a whole turn against
/// `reference` at the angles it samples, with the same tolerances as `kinloop`; then one step is
/// timed like every other variant: one `KinloopSweep::advance`, i.e. one `next_ref()` of the
/// runtime sweep (prediction, the full solve of positions and analogs, and the sweep's
/// branch-safety checks of every step). The runtime sweep ends after a turn of `steps` samples;
/// the new sweep for the next turn is created inside the timed loop, so its cost is counted
/// (amortised over the `steps` steps of a turn; see [`KinloopSweep`]).
fn bench_kinloop_sweep<M: Mechanism<N, 1, NO>, R: Stepper<N>, const N: usize, const NO: usize>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    m: &M,
    reference: &R,
    guess0: [f64; N],
    steps: usize,
) {
    let name = "kinloop_sweep";
    assert_check(name, WarmStart::Taylor, check_kinloop_sweep(m, reference, steps, guess0), EXACT);
    time_lean(g, name, &(), || KinloopSweep::start(m, steps, guess0).unwrap(), |_, sweep| sweep.advance().map(consume));
}

/// [`bench`] in the lean harness of the callgrind counts (`kinloop_bench::lean`): the step's
/// twelve numbers summed, the sum passed to `black_box`.
fn bench_lean<S: Stepper<N>, R: Stepper<N>, const N: usize>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    s: &S,
    reference: &R,
    guess0: [f64; N],
    steps: usize,
) {
    let policy = WarmStart::Previous;
    assert_check(name, policy, check_sweep(s, reference, steps, policy, guess0), EXACT);
    let sweep = Sweep::start(s, steps, policy, guess0).unwrap();
    time_lean(g, name, s, || sweep.clone(), |s, sweep| sweep.advance_summed(s).map(consume_sum));
}

/// Times one step as the lean harness of the callgrind counts runs it: `advance` steps a state
/// of its own (made by `make` before the clock starts) given `s` and passes what it computed to
/// `black_box`, in a loop of its own with `s` behind a shared reference ([`lean_loop`]).
fn time_lean<S, T>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    s: &S,
    make: impl Fn() -> T,
    advance: impl Fn(&S, &mut T) -> Result<(), Failed>,
) {
    g.bench_function(name, |b| {
        b.iter_custom(|iters| {
            let mut state = make();
            lean_loop(name, s, &mut state, iters, &advance)
        })
    });
}

/// `iters` steps of `advance` and the time they took. Out of line and given the stepper `s` by
/// a shared reference, as the lean harness's loops are (`kinloop_bench::lean`): the compiler
/// may then take `s`'s fields as unchanged through the loop and compute what depends on them
/// alone once (the rhombic drive's `sin gamma` and `cos gamma`), as it does in any loop over
/// one mechanism's inputs. A stepper in the loop's own mutable state, or reached through a
/// closure's captures, is read again after every `black_box` (which may write any memory
/// whose address was taken), and such values recomputed at every step; the hand closed forms
/// keep them in their structs, so only kinloop's step would pay.
#[inline(never)]
fn lean_loop<S, T>(
    name: &str,
    s: &S,
    state: &mut T,
    iters: u64,
    advance: &impl Fn(&S, &mut T) -> Result<(), Failed>,
) -> Duration {
    let start = Instant::now();
    for _ in 0..iters {
        if let Err(e) = advance(s, state) {
            panic!("{name}: {e}")
        }
    }
    start.elapsed()
}

/// The sweep recipe written by hand (`kinloop_bench::hand_sweep`), checked over a whole turn
/// against the hand closed form `reference`, then timed one sample at a time in the lean
/// harness of the callgrind counts (its twelve numbers summed, the sum passed to `black_box`).
fn bench_hand_sweep<S: HandSweep<N, NP>, R: Stepper<N>, const N: usize, const NP: usize>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    mut s: S,
    reference: &R,
    guess0: [f64; N],
) {
    let name = "hand_sweep";
    let steps = s.turn();
    let (first, _) = s.sync(0.0).unwrap();
    let mut cursor = HandSweepCursor::new(&s);
    let mut checked = s.clone();
    let check = check_turn(reference, steps, WarmStart::Previous, guess0, (0.0, first), || {
        cursor.next(&mut checked).map(|(x, step, _)| (x, step))
    });
    assert_check(name, WarmStart::Previous, check, EXACT);
    let cursor = HandSweepCursor::new(&s);
    time_lean(
        g,
        name,
        &(),
        || (cursor, s.clone()),
        |_, (cursor, s)| {
            let (_, step, point) = cursor.next(s)?;
            consume_sum(step_sum(&step) + point_sum(&point));
            Ok(())
        },
    );
}

/// [`bench_kinloop_sweep`] in the lean harness of the callgrind counts: the sample's twelve
/// numbers summed where the sweep keeps them, the sum passed to `black_box`.
fn bench_kinloop_sweep_lean<M: Mechanism<N, 1, NO>, R: Stepper<N>, const N: usize, const NO: usize>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    m: &M,
    reference: &R,
    guess0: [f64; N],
    steps: usize,
) {
    let name = "kinloop_sweep";
    assert_check(name, WarmStart::Taylor, check_kinloop_sweep(m, reference, steps, guess0), EXACT);
    time_lean(
        g,
        name,
        &(),
        || KinloopSweep::start(m, steps, guess0).unwrap(),
        |_, sweep| sweep.advance_sum().map(consume_sum),
    );
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
        bench(&mut g, "closed_form", &closed, &closed, policy, guess0, EXACT, STEPS);
        bench(&mut g, "kinloop", &kl, &closed, policy, guess0, EXACT, STEPS);
        bench(&mut g, "kinloop_named", &named, &closed, policy, guess0, EXACT, STEPS);
        if policy == WarmStart::Taylor {
            bench_kinloop_sweep::<_, _, 4, 0>(&mut g, &kl.m, &closed, guess0, STEPS);
        }
        bench(&mut g, "two_loop_newton", &TwoLoopNewton { p }, &closed, policy, guess0, EXACT, STEPS);
        bench(&mut g, "dense_hand_jacobian", &DenseHandJacobian { p }, &closed, policy, guess0, EXACT, STEPS);
        bench(&mut g, "dense_num_dual", &DenseNumDual { p }, &closed, policy, guess0, EXACT, STEPS);
        bench(
            &mut g,
            "dense_finite_difference",
            &DenseFiniteDifference { p },
            &closed,
            policy,
            guess0,
            DIFFERENCED,
            STEPS,
        );
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
        bench(&mut g, "hand_newton", &hand, &hand, policy, guess0, EXACT, STEPS);
        bench(&mut g, "kinloop", &kl, &hand, policy, guess0, EXACT, STEPS);
        bench(&mut g, "kinloop_named", &named, &hand, policy, guess0, EXACT, STEPS);
        if policy == WarmStart::Taylor {
            bench_kinloop_sweep::<_, _, 4, 0>(&mut g, &kl.m, &hand, guess0, STEPS);
        }
        g.finish();
    }
}

/// The criterion groups of the closed-form rows ([`closed_form_rows`]), one a row
/// (`closed_form_rhombic`, ...), each variant checked over a whole turn against the hand closed
/// form first: `closed_form` (the hand closed form, which ignores the guess), `kinloop` (the
/// generated point step `kinematics_flat` from the previous position), `kinloop_sweep` (one
/// sample of kinloop's own `Sweep`) and `hand_sweep` (the sweep recipe written by hand), all in
/// the lean harness of the callgrind counts, at [`TURN_720`] steps a turn.
struct CriterionRows<'c>(&'c mut Criterion);

impl RowVisitor for CriterionRows<'_> {
    fn row<
        M: Mechanism<N, 1, NO>,
        H: Stepper<N>,
        S: HandSweep<N, NP>,
        const N: usize,
        const NO: usize,
        const NP: usize,
    >(
        &mut self,
        name: &str,
        _title: &str,
        m: M,
        hand: &H,
        sweep: S,
        guess0: [f64; N],
    ) {
        let mut g = self.0.benchmark_group(format!("closed_form_{name}"));
        let kl = Kinloop::<M, NO>::new(m);
        bench_lean(&mut g, "closed_form", hand, hand, guess0, TURN_720);
        bench_lean(&mut g, "kinloop", &kl, hand, guess0, TURN_720);
        bench_kinloop_sweep_lean(&mut g, &kl.m, hand, guess0, TURN_720);
        bench_hand_sweep(&mut g, sweep, hand, guess0);
        g.finish();
    }
}

/// The closed-form rows: the rhombic drive, the four-bar with its coupler point and the
/// gear-lever rocker against their closed forms written by hand.
fn closed_form_blocks(c: &mut Criterion) {
    closed_form_rows(&mut CriterionRows(c));
}

/// The class IV block (Newton) at [`TURN_720`] steps a turn from the previous position: the
/// hand-written Newton and kinloop's point step, as `class-four-hand` and `class-four-point` of
/// `closed_form_step`.
fn class_four_720(c: &mut Criterion) {
    let p = black_box(class_four::PARAMS);
    let guess0 = class_four::INITIAL_GUESS;
    let hand = HandNewton { p };
    let policy = WarmStart::Previous;
    let mut g = c.benchmark_group("class_four_720_previous");
    bench(&mut g, "hand_newton", &hand, &hand, policy, guess0, EXACT, TURN_720);
    bench(&mut g, "kinloop", &Kinloop::<_, 0>::new(p.kinloop()), &hand, policy, guess0, EXACT, TURN_720);
    g.finish();
}

/// The ring of 64 four-bar loops (one sparse Newton block of 128 unknowns) and the same loops
/// in series, 720 steps a turn from the previous position: the ring checked against its dense
/// twin (`RingDense`: the dense partial-pivoting factorisation); the series, a different
/// mechanism with no peer here, only timed (its check against itself asserts that it solves
/// every step).
fn ring_720(c: &mut Criterion) {
    let (ring, dense, series) = (
        Kinloop::<Ring, 0>::new(Ring::default()),
        Kinloop::<RingDense, 0>::new(RingDense::default()),
        Kinloop::<Series, 0>::new(Series::default()),
    );
    let ring_guess: [f64; 128] = Ring::default().solve(0.0).expect("the ring assembles").q.into();
    let series_guess: [f64; 128] = Series::default().solve(0.0).expect("the series assembles").q.into();
    let mut g = c.benchmark_group("ring_720_previous");
    bench_lean(&mut g, "ring", &ring, &dense, ring_guess, TURN_720);
    bench_lean(&mut g, "series", &series, &series, series_guess, TURN_720);
    g.finish();
}

/// The four-bar's sensitivity solve (`sensitivities_flat`) and the same declaration's kinematic
/// step, 720 steps a turn from the previous position, checked against the hand closed form.
fn sensitivities_four_bar(c: &mut Criterion) {
    let four = black_box(FOUR_BAR);
    let hand = FourBarClosed::of(&four);
    let g0: [f64; 2] = four.solve(0.0).expect("the four-bar assembles").q.into();
    let mut g = c.benchmark_group("sensitivities_four_bar");
    bench_lean(&mut g, "kinematics", &Kinloop::<FourBarSens, 2>::new(four_sens(&four)), &hand, g0, TURN_720);
    bench_lean(&mut g, "sensitivities", &KinloopSens::<FourBarSens, 2, 4>::new(four_sens(&four)), &hand, g0, TURN_720);
    g.finish();
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
    targets = rhombic_drive, class_four_block, closed_form_blocks, class_four_720, ring_720, sensitivities_four_bar
}
criterion_main!(step);
