//! kinloop itself, for both mechanisms, through three of its APIs: the generic flat
//! [`Mechanism::kinematics_flat`] ([`Kinloop`]), the generated named `kinematics_with`
//! ([`KinloopNamed`]), and kinloop's own sweep `kinloop::Sweep` ([`KinloopSweep`]).

use std::f64::consts::TAU;

use kinloop::{Kin, Mechanism, NewtonConfig, Sensitivities};

use crate::decls::{ClassFour, ClassFourUnknowns, RhombicDrive, RhombicDriveUnknowns};
use crate::sweep::{Failed, Step, Stepper, SweepCheck, WarmStart, check_turn};

/// The step of kinloop's flat state (one input).
#[inline(always)]
fn step_of<const N: usize, const NO: usize>(k: &Kin<N, 1, NO>) -> Step<N> {
    Step { q: k.q, dq: k.dq.map(|r| r[0]), d2q: k.d2q.map(|r| r[0][0]), iterations: k.report.iterations }
}

/// kinloop through the generic [`Mechanism`] trait (`kinematics_flat`: flat arrays); `NO` is
/// the mechanism's number of output columns.
#[derive(Clone, Copy, Debug)]
pub struct Kinloop<M, const NO: usize> {
    /// The mechanism (its parameter values).
    pub m: M,
    /// The Newton settings of every solve.
    pub cfg: NewtonConfig,
}

impl<M, const NO: usize> Kinloop<M, NO> {
    /// `m` with the default Newton settings.
    pub fn new(m: M) -> Self {
        Kinloop { m, cfg: NewtonConfig::default() }
    }
}

/// `kinematics_flat` of `k` at `phi` from `guess`, inlined into the caller as the peers' steps
/// are: its configuration test, then the kernel it runs with libm's sines and cosines
/// (`kinematics_step_flat`, always inlined). Called through `kinematics_flat` itself, which the
/// benchmark's other uses instantiate too, the compiler keeps it out of line (about 90 more
/// instructions a step: the state returned through memory).
#[inline(always)]
fn kin_of<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize>(
    k: &Kinloop<M, NO>,
    phi: f64,
    guess: &[f64; N],
) -> Result<Kin<N, 1, NO>, Failed> {
    if let Some(field) = k.cfg.invalid_field() {
        return Err(Failed::new(format!("invalid configuration: {field}")));
    }
    k.m.kinematics_step_flat(&[phi], guess, &k.cfg, &mut kinloop::__gen::Libm).map_err(Failed::new)
}

impl<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize> Stepper<N> for Kinloop<M, NO> {
    #[inline(always)]
    fn step(&self, phi: f64, guess: &[f64; N]) -> Result<Step<N>, Failed> {
        kin_of(self, phi, guess).map(|k| step_of(&k))
    }

    #[inline(always)]
    fn step_summed(&self, phi: f64, guess: &[f64; N]) -> Result<(Step<N>, f64), Failed> {
        kin_of(self, phi, guess).map(|k| (step_of(&k), outputs_sum(&k)))
    }
}

/// kinloop's parameter sensitivities (`Sensitivities::sensitivities_flat`): the kinematic solve
/// and the sensitivities of positions, analogs and outputs to every parameter on the same
/// factorisations, for the cost of a sensitivity solve against a kinematic step
/// ([`Kinloop`] of the same mechanism). `NP` is the mechanism's number of parameters.
#[derive(Clone, Copy, Debug)]
pub struct KinloopSens<M, const NO: usize, const NP: usize> {
    /// The mechanism (its parameter values).
    pub m: M,
    /// The Newton settings of every solve.
    pub cfg: NewtonConfig,
}

impl<M, const NO: usize, const NP: usize> KinloopSens<M, NO, NP> {
    /// `m` with the default Newton settings.
    pub fn new(m: M) -> Self {
        KinloopSens { m, cfg: NewtonConfig::default() }
    }
}

impl<M: Sensitivities<N, 1, NO, NP>, const N: usize, const NO: usize, const NP: usize> Stepper<N>
    for KinloopSens<M, NO, NP>
{
    #[inline(always)]
    fn step(&self, phi: f64, guess: &[f64; N]) -> Result<Step<N>, Failed> {
        self.step_summed(phi, guess).map(|(s, _)| s)
    }

    /// The outputs and every sensitivity are added up (a sensitivity not read would be a
    /// computation the compiler may drop).
    #[inline(always)]
    fn step_summed(&self, phi: f64, guess: &[f64; N]) -> Result<(Step<N>, f64), Failed> {
        let (k, s) = self.m.sensitivities_flat(&[phi], guess, &self.cfg).map_err(Failed::new)?;
        let mut sum = outputs_sum(&k);
        for p in 0..NP {
            for u in 0..N {
                sum += (s.q[u][p] + s.dq[u][0][p]) + s.d2q[u][0][0][p];
            }
            for o in 0..NO {
                sum += (s.out[o][p] + s.dout[o][0][p]) + s.d2out[o][0][0][p];
            }
        }
        Ok((step_of(&k), sum))
    }
}

/// The sum of a state's outputs and their analogs (one input).
#[inline(always)]
pub fn outputs_sum<const N: usize, const NO: usize>(k: &Kin<N, 1, NO>) -> f64 {
    (0..NO).fold(-0.0, |s, o| s + ((k.out[o] + k.dout[o][0]) + k.d2out[o][0][0]))
}

/// The sum of a state's positions, analogs, outputs and their analogs (one input): the
/// numbers the lean harness adds up per step (see [`crate::lean`]).
#[inline(always)]
pub fn state_sum<const N: usize, const NO: usize>(k: &Kin<N, 1, NO>) -> f64 {
    let q = (0..N).fold(-0.0, |s, u| s + ((k.q[u] + k.dq[u][0]) + k.d2q[u][0][0]));
    q + outputs_sum(k)
}

/// The generated named API of a mechanism of the benchmarks: `kinematics_with` taking the
/// named unknowns and returning the named state (`RhombicDriveState`, `ClassFourState`).
pub trait NamedKinematics {
    /// One kinematic solve at input `phi` from `guess` through `kinematics_with`, converted
    /// from and to flat arrays outside the timed kinematics.
    fn named_step(&self, phi: f64, guess: &[f64; 4], cfg: &NewtonConfig) -> Result<Step<4>, kinloop::Error>;
}

macro_rules! named_kinematics {
    ($($m:ty => $unknowns:ty),* $(,)?) => {$(
        impl NamedKinematics for $m {
            #[inline(always)]
            fn named_step(&self, phi: f64, guess: &[f64; 4], cfg: &NewtonConfig) -> Result<Step<4>, kinloop::Error> {
                let s = self.kinematics_with(phi, &<$unknowns>::from(*guess), cfg)?;
                Ok(Step { q: s.q.into(), dq: s.dq.into(), d2q: s.d2q.into(), iterations: s.report.iterations })
            }
        }
    )*};
}

named_kinematics!(RhombicDrive => RhombicDriveUnknowns, ClassFour => ClassFourUnknowns);

/// kinloop through the named API (`kinematics_with` returning `RhombicDriveState` or
/// `ClassFourState`).
#[derive(Clone, Copy, Debug)]
pub struct KinloopNamed<M> {
    /// The mechanism (its parameter values).
    pub m: M,
    /// The Newton settings of every solve.
    pub cfg: NewtonConfig,
}

impl<M> KinloopNamed<M> {
    /// `m` with the default Newton settings.
    pub fn new(m: M) -> Self {
        KinloopNamed { m, cfg: NewtonConfig::default() }
    }
}

impl<M: NamedKinematics> Stepper<4> for KinloopNamed<M> {
    #[inline]
    fn step(&self, phi: f64, guess: &[f64; 4]) -> Result<Step<4>, Failed> {
        self.m.named_step(phi, guess, &self.cfg).map_err(Failed::new)
    }
}

/// kinloop's own sweep (`kinloop::Sweep`, `runtime/src/paths/sweep.rs`, default `SweepConfig`) over
/// the same turns as the benchmark's [`crate::sweep::Sweep`]: `steps` samples per turn at the
/// angles `k 2 pi / steps`, `k = 0 .. steps - 1`.
///
/// One step is one `next_ref()` of the runtime sweep (the state read where the sweep keeps it):
/// its own second-order Taylor predictor, the full kinematic solve from that guess (positions,
/// velocity and acceleration analogs, as `kinematics_flat`), and the sweep's **branch-safety checks** on the result (determinant signs
/// of every block, the smallest pivot ratio, the distance of the corrected position and of its
/// velocity analogs from their predictions) with the bookkeeping of its adaptive step size. When
/// a step is not accepted the sweep halves it, so a sample may cost more than one solve
/// ([`Step::iterations`] counts the Newton iterations of the accepted solve only).
///
/// A runtime sweep covers one turn and then ends; the next turn is a new sweep, started from the
/// last position of the turn. That restart is counted in the step that makes it: `Sweep::new`
/// plus the first sample of the new turn, which the runtime solves from the previous position
/// (without a predictor) — once per `steps` steps.
pub struct KinloopSweep<'m, M: Mechanism<N, 1, NO>, const N: usize, const NO: usize> {
    m: &'m M,
    steps: usize,
    sweep: kinloop::Sweep<'m, M, Kin<N, 1, NO>, N, 1, NO>,
    phi: f64,
    current: Step<N>,
}

impl<'m, M: Mechanism<N, 1, NO>, const N: usize, const NO: usize> KinloopSweep<'m, M, N, NO> {
    /// Starts the first turn from `guess0` (the assembly mode) and takes its first sample, at
    /// `phi = 0`.
    pub fn start(m: &'m M, steps: usize, guess0: [f64; N]) -> Result<Self, Failed> {
        let mut sweep = Self::turn(m, steps, guess0)?;
        let k = sweep.next_kin().ok_or_else(|| Failed::new("kinloop sweep: no sample"))?.map_err(Failed::new)?;
        Ok(KinloopSweep { m, steps, sweep, phi: k.x[0], current: step_of(&k) })
    }

    /// One turn: `steps` samples from `0` to `(steps - 1) 2 pi / steps`.
    fn turn(m: &'m M, steps: usize, guess: [f64; N]) -> Result<kinloop::Sweep<'m, M, Kin<N, 1, NO>, N, 1, NO>, Failed> {
        let last = TAU * (steps - 1) as f64 / steps as f64;
        kinloop::Sweep::new(m, [0.0], [last], steps, guess).map_err(Failed::new)
    }

    /// The input value of the current step.
    pub fn phi(&self) -> f64 {
        self.phi
    }

    /// The current step.
    pub fn current(&self) -> &Step<N> {
        &self.current
    }

    /// The next sample (after the last angle of a turn comes the first angle of a new sweep).
    #[inline(always)]
    pub fn advance(&mut self) -> Result<&Step<N>, Failed> {
        // The sample is read where the sweep keeps it (no copy of the state).
        match self.sweep.next_ref() {
            Some(Ok(k)) => {
                self.phi = k.x[0];
                self.current = step_of(k);
            }
            Some(Err(e)) => return Err(Failed::new(e)),
            None => {
                let k = self.restart()?;
                self.phi = k.x[0];
                self.current = step_of(&k);
            }
        }
        Ok(&self.current)
    }

    /// The next sample's [`state_sum`], read where the sweep keeps the state (the lean harness,
    /// [`crate::lean`]): nothing is copied out of the sweep.
    #[inline(always)]
    pub fn advance_sum(&mut self) -> Result<f64, Failed> {
        match self.sweep.next_ref() {
            Some(Ok(k)) => Ok(state_sum(k)),
            Some(Err(e)) => Err(Failed::new(e)),
            None => self.restart_sum(),
        }
    }

    /// [`KinloopSweep::restart`] from the sweep's last position, and the first sample's sum.
    #[cold]
    #[inline(never)]
    fn restart_sum(&mut self) -> Result<f64, Failed> {
        if let Some(k) = self.sweep.last_accepted() {
            self.current.q = k.q;
        }
        let k = self.restart()?;
        Ok(state_sum(&k))
    }

    /// A new turn from the last position, and its first sample.
    #[cold]
    #[inline(never)]
    fn restart(&mut self) -> Result<Kin<N, 1, NO>, Failed> {
        self.sweep = Self::turn(self.m, self.steps, self.current.q)?;
        self.sweep.next_kin().ok_or_else(|| Failed::new("kinloop sweep: no sample"))?.map_err(Failed::new)
    }
}

/// Runs kinloop's sweep of `m` over one whole turn from `guess0` and compares every sample with
/// `reference` at the same angle (warm-started by the Taylor predictor, as the runtime sweep is).
pub fn check_kinloop_sweep<M: Mechanism<N, 1, NO>, R: Stepper<N>, const N: usize, const NO: usize>(
    m: &M,
    reference: &R,
    steps: usize,
    guess0: [f64; N],
) -> Result<SweepCheck, Failed> {
    let mut sweep = KinloopSweep::start(m, steps, guess0)?;
    let first = (sweep.phi(), *sweep.current());
    check_turn(reference, steps, WarmStart::Taylor, guess0, first, || {
        let got = *sweep.advance()?;
        Ok((sweep.phi(), got))
    })
}
