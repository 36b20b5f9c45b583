//! One step of a sweep: the common interface of kinloop and of every peer, and the warm-start
//! policies that drive them along a turn of the crank, with what every harness counts with (the
//! sum of a step's numbers, [`step_sum`], and the input of the next step of a turn,
//! `next_input`).
//!
//! This is the vocabulary of the benchmarks: the peers and kinloop's variants implement it and
//! the lean harness ([`crate::lean`]) drives them with it, and it imports none of them.

use std::f64::consts::TAU;

/// Crank angles per turn in the benchmarks (1,000,000 equally spaced angles).
pub const STEPS: usize = 1_000_000;

/// Positions, velocity analogs and acceleration analogs of the unknowns at one input value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Step<const N: usize> {
    /// Positions of the unknowns.
    pub q: [f64; N],
    /// Velocity analogs `dq/dphi`.
    pub dq: [f64; N],
    /// Acceleration analogs `d2q/dphi2`.
    pub d2q: [f64; N],
    /// Newton iterations spent on this step (0 when the warm start already met the tolerance).
    pub iterations: u32,
}

/// The sum of a step's positions and analogs.
#[inline(always)]
pub fn step_sum<const N: usize>(s: &Step<N>) -> f64 {
    (0..N).fold(-0.0, |acc, u| acc + ((s.q[u] + s.dq[u]) + s.d2q[u]))
}

/// A failed step (never expected along the benchmark sweeps).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Failed(pub String);

impl Failed {
    /// A failure that says why; cold, so building it costs the steps that succeed nothing.
    #[cold]
    #[inline(never)]
    pub fn new(why: impl ToString) -> Self {
        Failed(why.to_string())
    }
}

impl std::fmt::Display for Failed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// One kinematic step: positions (solved from `guess`), velocity and acceleration analogs.
pub trait Stepper<const N: usize> {
    /// Whether the step uses the warm start (a closed form does not, and then the sweep
    /// computes none: the closed form is timed without the predictor's cost).
    const WARM: bool = true;
    /// Positions at input `phi`, solved from `guess`, with their velocity and acceleration
    /// analogs.
    fn step(&self, phi: f64, guess: &[f64; N]) -> Result<Step<N>, Failed>;

    /// [`Stepper::step`] and the sum of the output points' coordinates and their analogs (0
    /// without outputs): what the lean harness of the closed-form rows adds up (see
    /// [`crate::lean`]), where `step` hands the outputs to `black_box`.
    #[inline(always)]
    fn step_summed(&self, phi: f64, guess: &[f64; N]) -> Result<(Step<N>, f64), Failed> {
        self.step(phi, guess).map(|s| (s, 0.0))
    }
}

/// How the guess of the next step is made from the previous step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WarmStart {
    /// The previous position `q(phi - h)`.
    Previous,
    /// The second-order Taylor predictor `q + q' h + q'' h^2 / 2` from the previous step's
    /// position and analogs (which every step computes anyway).
    Taylor,
}

impl WarmStart {
    /// Both policies, in the report's order.
    pub const ALL: [WarmStart; 2] = [WarmStart::Taylor, WarmStart::Previous];

    /// The policy's name in benchmark ids and the report.
    pub fn name(self) -> &'static str {
        match self {
            WarmStart::Previous => "previous",
            WarmStart::Taylor => "taylor",
        }
    }
}

/// Walks the crank through `steps` equally spaced angles per turn, turn after turn, each step
/// warm-started from the previous one.
#[derive(Clone, Debug)]
pub struct Sweep<const N: usize> {
    steps: usize,
    k: usize,
    h: f64,
    policy: WarmStart,
    prev: Step<N>,
}

impl<const N: usize> Sweep<N> {
    /// Solves the first step at `phi = 0` from `guess0` (the assembly mode).
    pub fn start<S: Stepper<N>>(s: &S, steps: usize, policy: WarmStart, guess0: [f64; N]) -> Result<Self, Failed> {
        let first = s.step(0.0, &guess0)?;
        Ok(Sweep { steps, k: 0, h: TAU / steps as f64, policy, prev: first })
    }

    /// The step size `h` (radians).
    pub fn h(&self) -> f64 {
        self.h
    }

    /// Index of the current step within the turn.
    pub fn index(&self) -> usize {
        self.k
    }

    /// The current input value.
    pub fn phi(&self) -> f64 {
        self.h * self.k as f64
    }

    /// The current step.
    pub fn current(&self) -> &Step<N> {
        &self.prev
    }

    /// The guess for the next step.
    #[inline(always)]
    pub fn guess(&self) -> [f64; N] {
        let p = &self.prev;
        match self.policy {
            WarmStart::Previous => p.q,
            WarmStart::Taylor => {
                let h = self.h;
                std::array::from_fn(|u| p.q[u] + h * (p.dq[u] + 0.5 * h * p.d2q[u]))
            }
        }
    }

    /// Solves the next step (after the last angle of a turn comes the first angle again).
    #[inline(always)]
    pub fn advance<S: Stepper<N>>(&mut self, s: &S) -> Result<&Step<N>, Failed> {
        self.k += 1;
        if self.k == self.steps {
            self.k = 0;
        }
        self.solve_at(s, self.h * self.k as f64)
    }

    /// Like [`Sweep::advance`], but solves the next step at `phi` instead of at the next angle
    /// of the turn (to follow another sweep's angles, which may differ from these by rounding).
    pub fn advance_to<S: Stepper<N>>(&mut self, s: &S, phi: f64) -> Result<&Step<N>, Failed> {
        self.k = (self.k + 1) % self.steps;
        self.solve_at(s, phi)
    }

    /// Like [`Sweep::advance`], but returns the sum of the step's numbers and its outputs (see
    /// [`Stepper::step_summed`]), added up from the step as computed, before it is stored, as
    /// the lean harness adds them ([`crate::lean`]). Summed from the stored step instead, the
    /// sum's 16-byte loads span the step's 8-byte stores where a step stores its numbers one at
    /// a time (kinloop's state, converted field by field), and wait for them to retire (no
    /// store-to-load forwarding): a harness cost one variant pays and another not.
    #[inline(always)]
    pub fn advance_summed<S: Stepper<N>>(&mut self, s: &S) -> Result<f64, Failed> {
        self.k += 1;
        if self.k == self.steps {
            self.k = 0;
        }
        let phi = self.h * self.k as i64 as f64;
        let (step, out) = if S::WARM && self.policy == WarmStart::Taylor {
            s.step_summed(phi, &self.guess())?
        } else {
            // The last positions read where they lie, as the lean harness passes its own: a copy
            // would load them in pairs across the 8-byte stores a step may have written them
            // with, and wait for those (no store-to-load forwarding), a cost of the harness that
            // only a step which reads its guess would pay.
            s.step_summed(phi, &self.prev.q)?
        };
        let sum = step_sum(&step) + out;
        self.prev = step;
        Ok(sum)
    }

    #[inline(always)]
    fn solve_at<S: Stepper<N>>(&mut self, s: &S, phi: f64) -> Result<&Step<N>, Failed> {
        let guess = if S::WARM { self.guess() } else { self.prev.q };
        self.prev = s.step(phi, &guess)?;
        Ok(&self.prev)
    }
}

/// The input of the step after the `k`-th of a turn of `turn` steps of `h`, `k` advanced.
#[inline(always)]
pub(crate) fn next_input(k: &mut usize, turn: usize, h: f64) -> f64 {
    *k += 1;
    if *k == turn {
        *k = 0;
    }
    h * *k as i64 as f64
}

/// Relative difference, absolute near zero: `|a - b| / max(|b|, 1)`.
pub fn rel_err(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1.0)
}

/// Largest deviations of one step from a reference step: (positions, velocity analogs,
/// acceleration analogs), each as [`rel_err`].
pub fn deviation<const N: usize>(got: &Step<N>, want: &Step<N>) -> [f64; 3] {
    let mut d = [0.0f64; 3];
    for u in 0..N {
        d[0] = d[0].max(rel_err(got.q[u], want.q[u]));
        d[1] = d[1].max(rel_err(got.dq[u], want.dq[u]));
        d[2] = d[2].max(rel_err(got.d2q[u], want.d2q[u]));
    }
    // NaN must not pass as "small".
    d.map(|v| if v.is_nan() { f64::INFINITY } else { v })
}

/// Statistics of a checked sweep: a whole turn of `steps` angles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepCheck {
    /// Largest deviations from the reference over the turn (see [`deviation`]).
    pub max_dev: [f64; 3],
    /// Mean Newton iterations per step.
    pub mean_iterations: f64,
    /// Largest Newton iteration count of any step.
    pub max_iterations: u32,
}

/// Tolerances of [`SweepCheck::max_dev`] for exact derivatives: positions to the residual
/// tolerance, analogs to rounding.
pub const EXACT: [f64; 3] = [1e-11, 1e-9, 1e-9];
/// Tolerances of [`SweepCheck::max_dev`] for finite differences: the analogs carry the
/// differencing error.
pub const DIFFERENCED: [f64; 3] = [1e-11, 1e-6, 1e-5];

/// Runs `s` over one whole turn with `policy` from `guess0` and compares every step with
/// `reference` (a stepper that ignores the guess, e.g. a closed form, or another solver run
/// side by side with the same policy).
pub fn check_sweep<const N: usize, S: Stepper<N>, R: Stepper<N>>(
    s: &S,
    reference: &R,
    steps: usize,
    policy: WarmStart,
    guess0: [f64; N],
) -> Result<SweepCheck, Failed> {
    let mut sweep = Sweep::start(s, steps, policy, guess0)?;
    let first = (sweep.phi(), *sweep.current());
    check_turn(reference, steps, policy, guess0, first, || {
        let got = *sweep.advance(s)?;
        Ok((sweep.phi(), got))
    })
}

/// Compares one whole turn of `steps` steps, each `(phi, step)` — `first` at `phi = 0`, then
/// `steps - 1` from `next` — with `reference` solved at the same angles (warm-started with
/// `policy` from `guess0`, unless it ignores the guess).
pub fn check_turn<const N: usize, R: Stepper<N>>(
    reference: &R,
    steps: usize,
    policy: WarmStart,
    guess0: [f64; N],
    first: (f64, Step<N>),
    mut next: impl FnMut() -> Result<(f64, Step<N>), Failed>,
) -> Result<SweepCheck, Failed> {
    if first.0 != 0.0 {
        return Err(Failed::new(format!("the turn starts at {} instead of 0", first.0)));
    }
    let mut ref_sweep = Sweep::start(reference, steps, policy, guess0)?;
    let mut max_dev = deviation(&first.1, ref_sweep.current());
    let mut total = 0u64;
    let mut max_iterations = 0;
    for _ in 1..steps {
        let (phi, got) = next()?;
        let want = *ref_sweep.advance_to(reference, phi)?;
        if (phi - ref_sweep.phi()).abs() > 1e-12 {
            return Err(Failed::new(format!("step {} is at {phi} instead of {}", ref_sweep.index(), ref_sweep.phi())));
        }
        let d = deviation(&got, &want);
        for (m, d) in max_dev.iter_mut().zip(d) {
            *m = m.max(d);
        }
        total += u64::from(got.iterations);
        max_iterations = max_iterations.max(got.iterations);
    }
    Ok(SweepCheck { max_dev, mean_iterations: total as f64 / (steps - 1) as f64, max_iterations })
}
