//! The lean harness of the instruction counts: one loop for every variant, reference and
//! candidate alike. Each step's twelve numbers (the positions, velocity and acceleration analogs
//! of the unknowns, and of the output point where the mechanism has one) are added into one
//! accumulator, so every variant must compute all of them and none is made to store them: a
//! hand closed form keeps them in registers, kinloop's `Sweep` is read where it keeps its state.
//! The step functions are inlined into the loop, which is a function of its own per variant.

use kinloop::{Kin, Mechanism};

use crate::hand_sweep::HandSweep;
use crate::kernel_lane::kernel_lane_fold;
use crate::kinloop_variants::{KinloopSweep, state_sum};
use std::f64::consts::TAU;

use crate::sweep::{Failed, Step, Stepper, WarmStart, next_input, step_sum};

/// `steps` steps of `s` over turns of `turn` equally spaced inputs, each warm-started from the
/// previous step by `policy` (a closed form ignores it): the sum of every step's numbers (see
/// the module documentation).
pub fn stepper_turns<S: Stepper<N>, const N: usize>(
    s: &S,
    policy: WarmStart,
    turn: usize,
    guess: [f64; N],
    steps: usize,
) -> Result<f64, Failed> {
    match policy {
        WarmStart::Previous => previous_turns(s, turn, guess, steps),
        WarmStart::Taylor => taylor_turns(s, turn, guess, steps),
    }
}

/// The first step, at input 0: out of the loops' functions, so that the step has one call site
/// there, in the loop (with two, the compiler may inline it in neither).
#[inline(never)]
fn first_step<S: Stepper<N>, const N: usize>(s: &S, guess: &[f64; N]) -> Result<Step<N>, Failed> {
    s.step(0.0, guess)
}

/// [`stepper_turns`] from the previous position: only the positions are kept between steps.
#[inline(never)]
fn previous_turns<S: Stepper<N>, const N: usize>(
    s: &S,
    turn: usize,
    guess: [f64; N],
    steps: usize,
) -> Result<f64, Failed> {
    let (h, mut k) = (TAU / turn as f64, 0usize);
    let mut q = first_step(s, &guess)?.q;
    let mut acc = 0.0;
    for _ in 0..steps {
        let (step, out) = s.step_summed(next_input(&mut k, turn, h), &q)?;
        q = step.q;
        acc += step_sum(&step) + out;
    }
    Ok(acc)
}

/// [`stepper_turns`] from the second-order prediction (a closed form is given the previous
/// position instead: it computes no prediction).
#[inline(never)]
fn taylor_turns<S: Stepper<N>, const N: usize>(
    s: &S,
    turn: usize,
    guess: [f64; N],
    steps: usize,
) -> Result<f64, Failed> {
    let (h, mut k) = (TAU / turn as f64, 0usize);
    let mut prev = first_step(s, &guess)?;
    let mut acc = 0.0;
    for _ in 0..steps {
        let g = if S::WARM {
            std::array::from_fn(|u| prev.q[u] + h * (prev.dq[u] + 0.5 * h * prev.d2q[u]))
        } else {
            prev.q
        };
        let (step, out) = s.step_summed(next_input(&mut k, turn, h), &g)?;
        prev = step;
        acc += step_sum(&step) + out;
    }
    Ok(acc)
}

/// `steps` samples of kinloop's own `Sweep` of `m` over turns of `turn` samples (a new sweep
/// per turn, from the last position): the sum of every sample's numbers, as
/// [`stepper_turns`] sums its steps'.
#[inline(never)]
pub fn sweep_turns<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize>(
    m: &M,
    turn: usize,
    guess: [f64; N],
    steps: usize,
) -> Result<f64, Failed> {
    let mut sweep = KinloopSweep::start(m, turn, guess)?;
    let mut acc = 0.0;
    for _ in 0..steps {
        acc += sweep.advance_sum()?;
    }
    Ok(acc)
}

/// [`sweep_turns`] as a program usually writes it: a `for` loop over the sweep's items (each
/// sample's state a copy, `Result<Kin, Error>`), a new sweep per turn from the last position,
/// the last one shortened to the samples left (at the same spacing). The sweep's `next` is
/// inlined into the loop as `next_ref` is into [`sweep_turns`]'s, so both cost the same.
#[inline(never)]
pub fn sweep_for_turns<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize>(
    m: &M,
    turn: usize,
    guess: [f64; N],
    steps: usize,
) -> Result<f64, Failed> {
    let h = TAU / turn as f64;
    let (mut acc, mut q, mut left) = (0.0, guess, steps);
    while left > 0 {
        let n = left.min(turn);
        let sweep = kinloop::Sweep::<M, Kin<N, 1, NO>, N, 1, NO>::new(m, [0.0], [h * (n - 1) as f64], n, q)
            .map_err(Failed::new)?;
        for k in sweep {
            let k = k.map_err(Failed::new)?;
            acc += state_sum(&k);
            q = k.q;
        }
        left -= n;
    }
    Ok(acc)
}

/// The sum of an output point's coordinates and analogs (0 without a point), added as the hand
/// closed forms' `step_summed` adds them.
#[inline(always)]
pub fn point_sum<const NP: usize>(p: &[f64; NP]) -> f64 {
    match NP {
        6 => ((p[0] + p[1]) + (p[2] + p[3])) + (p[4] + p[5]),
        _ => p.iter().fold(-0.0, |acc, v| acc + v),
    }
}

/// Each of `steps` samples of the hand-written sweep `s` after its first (at input 0), with
/// its input: `f(acc, x, step, point)` folds them (see [`HandSweepCursor`]). The tests compare
/// the samples with the closed form's through it, so they check what the counts measure.
#[inline(always)]
pub fn hand_sweep_fold<S: HandSweep<N, NP>, A, const N: usize, const NP: usize>(
    mut s: S,
    steps: usize,
    init: A,
    mut f: impl FnMut(A, f64, &Step<N>, &[f64; NP]) -> A,
) -> Result<A, Failed> {
    first_sync(&mut s)?;
    let mut cursor = HandSweepCursor::new(&s);
    let mut acc = init;
    for _ in 0..steps {
        let (x, step, point) = cursor.next(&mut s)?;
        acc = f(acc, x, &step, &point);
    }
    Ok(acc)
}

/// Where a hand-written sweep is along its turns of `turn` samples: the index `k` of its last
/// sample in the turn (input `h k`, advanced as `next_input` advances the other rows') and the
/// samples since the last re-synchronisation.
#[derive(Clone, Copy, Debug)]
pub struct HandSweepCursor {
    turn: usize,
    period: usize,
    h: f64,
    k: usize,
    since_sync: usize,
}

impl HandSweepCursor {
    /// The cursor of `s` at the first sample of a turn (input 0).
    #[inline(always)]
    pub fn new<S: HandSweep<N, NP>, const N: usize, const NP: usize>(s: &S) -> Self {
        HandSweepCursor { turn: s.turn(), period: s.period(), h: TAU / s.turn() as f64, k: 0, since_sync: 0 }
    }

    /// The next sample of `s` and its input: re-synchronised with libm ([`HandSweep::sync`])
    /// every `s.period()` samples, at the first of every turn (input 0) and where the sweep
    /// asks for it ([`HandSweep::exact_next`]), advanced by rotation ([`HandSweep::advance`])
    /// otherwise.
    #[inline(always)]
    pub fn next<S: HandSweep<N, NP>, const N: usize, const NP: usize>(
        &mut self,
        s: &mut S,
    ) -> Result<(f64, Step<N>, [f64; NP]), Failed> {
        let x = next_input(&mut self.k, self.turn, self.h);
        self.since_sync += 1;
        let (step, point) = if self.k == 0 || self.since_sync == self.period || s.exact_next() {
            self.since_sync = 0;
            s.sync(x)?
        } else {
            s.advance()?
        };
        Ok((x, step, point))
    }
}

/// The first sample of a hand-written sweep, at input 0 (out of the loop, as [`first_step`]).
#[inline(never)]
fn first_sync<S: HandSweep<N, NP>, const N: usize, const NP: usize>(s: &mut S) -> Result<(), Failed> {
    s.start(0.0).map(|_| ())
}

/// `steps` samples of the hand-written sweep `s` (see [`hand_sweep_fold`]): the sum of every
/// sample's numbers, as [`stepper_turns`] sums its steps'. The sweep is taken by value: its
/// carried values are the loop's own locals, as a sweep written by hand keeps them (through a
/// reference to the caller's, the compiler stores them back every sample; the counts moved by
/// -10 to +5 instructions a sample between the two, with the register allocation).
#[inline(never)]
pub fn hand_sweep_turns<S: HandSweep<N, NP>, const N: usize, const NP: usize>(
    s: S,
    steps: usize,
) -> Result<f64, Failed> {
    hand_sweep_fold(s, steps, 0.0, |acc, _, step, point| acc + (step_sum(step) + point_sum(point)))
}

/// `steps` samples of kinloop's kernel driven by the hand sweep's trigonometry
/// ([`crate::kernel_lane`]): the sum of every sample's numbers, as [`sweep_turns`] sums a
/// `Sweep`'s.
#[inline(never)]
pub fn kernel_lane_turns<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize, const TERMS: usize>(
    m: &M,
    turn: usize,
    guess: [f64; N],
    steps: usize,
) -> Result<f64, Failed> {
    kernel_lane_fold::<M, f64, N, NO, TERMS>(m, turn, guess, steps, 0.0, |acc, k| acc + state_sum(k))
}

/// Samples of each design's sweep in [`scan_designs`]: a turn from 0 to `2 pi`, both ends
/// included (the sweep's spacing is that of a turn of `SCAN_SAMPLES - 1` steps).
pub const SCAN_SAMPLES: usize = 100;

/// A design-space scan (`kinloop::scan`) over `steps / SCAN_SAMPLES` designs made by `design`
/// from their index, each swept over a turn in [`SCAN_SAMPLES`] samples from its declared
/// guess, every sample's numbers added into one accumulator by the scan's fold: the sum over
/// the designs. Its cost per sample against [`sweep_turns`] at `SCAN_SAMPLES - 1` steps a turn
/// is the scan's cost per design (a new sweep and its first solve from the guess; the fold reads
/// each state in place) spread over its samples.
pub fn scan_designs<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize>(
    design: impl Fn(usize) -> M,
    steps: usize,
) -> Result<f64, Failed> {
    let designs: Vec<M> = (0..steps / SCAN_SAMPLES).map(design).collect();
    let spec = kinloop::ScanConfig::new([0.0], [TAU], SCAN_SAMPLES);
    let sums = kinloop::scan(&designs, &spec, |_| 0.0, |acc, _, k| acc + crate::kinloop_variants::state_sum(k));
    sums.into_iter().try_fold(0.0, |acc, s| Ok(acc + s.map_err(Failed::new)?))
}
