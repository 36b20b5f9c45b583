//! Forward simulation of a one-input machine:
//! `(J(phi) + J_fly) phi'' + 1/2 J'(phi) phi'^2 = M_drive(t, phi, phi') + Q(phi, phi')`,
//! integrated by [`dopri5`](super::dopri5) with the kinematics solved at every evaluation
//! (warm-started from the previous one, so the machine stays on its assembly branch). The
//! integration is written once over any kernel ([`simulate_of`]); a run-time model's
//! simulation is the same.

use super::error::DynamicsError;
use super::model::MassModel;
use super::simulate_of::{RunConfig, Trajectory, simulate_of};
use crate::kin::Kin;
use crate::mechanism::Mechanism;
use crate::mechanism::kernel::Compiled;

/// A forward simulation of a one-input machine, set up by name and run by [`Simulation::run`]:
///
/// ```text
/// let run = Simulation::new(&engine, &engine.mass_model()?)
///     .start(0.0, 10.0)                         // phi0, omega0
///     .guess(engine.guess(0.0))                 // the assembly branch at phi0
///     .drive(|_t, _phi, omega| 5.0 - 0.1 * omega) // a motor characteristic
///     .config(RunConfig::default().with_flywheel(0.2))
///     .stop_when(|_t, [phi, _]| *phi > 20.0)
///     .run(3.0)?;                               // simulate 3 time units
/// let [phi, omega] = run.at(1.5);
/// ```
///
/// Without a call to each setter: at rest at input 0 (`start`), from the mechanism's declared
/// guess there (`guess`), no driving torque (`drive`), never stopped early (`stop_when`), the
/// default [`RunConfig`] (`config`).
#[must_use = "a simulation does nothing until `run`"]
pub struct Simulation<'a, M, D, S, const N: usize, const NO: usize> {
    m: &'a M,
    model: &'a MassModel<N, 1, NO>,
    drive: D,
    stop: S,
    start: [f64; 2],
    guess: Option<[f64; N]>,
    cfg: RunConfig,
}

/// No driving torque.
type NoDrive = fn(f64, f64, f64) -> f64;
/// Never stop early.
type NoStop = fn(f64, &[f64; 2]) -> bool;

impl<'a, M, const N: usize, const NO: usize> Simulation<'a, M, NoDrive, NoStop, N, NO>
where
    M: Mechanism<N, 1, NO>,
{
    /// A simulation of mechanism `m` with mass model `model` (see the type's documentation for
    /// what it starts with).
    pub fn new(m: &'a M, model: &'a MassModel<N, 1, NO>) -> Self {
        Simulation {
            m,
            model,
            drive: |_, _, _| 0.0,
            stop: |_, _| false,
            start: [0.0, 0.0],
            guess: None,
            cfg: RunConfig::default(),
        }
    }
}

impl<'a, M, D, S, const N: usize, const NO: usize> Simulation<'a, M, D, S, N, NO>
where
    M: Mechanism<N, 1, NO>,
{
    /// Starts from input `phi0` at speed `omega0`.
    pub fn start(mut self, phi0: f64, omega0: f64) -> Self {
        self.start = [phi0, omega0];
        self
    }

    /// The positions that choose the assembly branch at the start: the mechanism's named
    /// unknowns (`m.guess(phi0)`) or their array.
    pub fn guess(mut self, guess: impl Into<[f64; N]>) -> Self {
        self.guess = Some(guess.into());
        self
    }

    /// The integrator's, the solver's and the flywheel's settings.
    pub fn config(mut self, cfg: RunConfig) -> Self {
        self.cfg = cfg;
        self
    }

    /// The driving torque on the input, `drive(t, phi, omega)` (a motor characteristic).
    pub fn drive<D2: Fn(f64, f64, f64) -> f64>(self, drive: D2) -> Simulation<'a, M, D2, S, N, NO> {
        let Simulation { m, model, stop, start, guess, cfg, .. } = self;
        Simulation { m, model, drive, stop, start, guess, cfg }
    }

    /// Ends the run early when `stop(t, [phi, omega])`, asked after every step, returns `true`.
    pub fn stop_when<S2: FnMut(f64, &[f64; 2]) -> bool>(self, stop: S2) -> Simulation<'a, M, D, S2, N, NO> {
        let Simulation { m, model, drive, start, guess, cfg, .. } = self;
        Simulation { m, model, drive, stop, start, guess, cfg }
    }

    /// Simulates for `t_end` time units from the start.
    ///
    /// Errors: a kinematic failure (limit or singular position, no assembly) as
    /// [`DynamicsError::Kinematics`] with the time; a step that collapses (approaching a limit
    /// position, where the reduced inertia grows without bound) as
    /// [`DynamicsError::SingularMotion`] with the input reached; a reduced inertia that is not positive as
    /// [`DynamicsError::SingularMass`]; a drive or load that is not finite as
    /// [`DynamicsError::NonFiniteLoad`]; a start so far out (an input of 1e300) that a step cannot
    /// change it as [`DynamicsError::CannotAdvance`]; results beyond the range of `f64` as
    /// [`DynamicsError::Overflow`]; a span that needs more steps than the budget
    /// ([`OdeConfig::max_steps`](super::OdeConfig::max_steps) of the configuration's `ode`) as
    /// [`DynamicsError::TooManySteps`]; integrator failures. Besides the recorded trajectory (one
    /// entry per accepted step, amortised growth), a step allocates nothing.
    pub fn run(mut self, t_end: f64) -> Result<Trajectory, DynamicsError>
    where
        D: Fn(f64, f64, f64) -> f64,
        S: FnMut(f64, &[f64; 2]) -> bool,
    {
        let guess = self.guess.unwrap_or_else(|| self.m.guess_flat(&[self.start[0]]));
        let model = self.model;
        let reduced = |k: &Kin<N, 1, NO>, omega: f64| model.dynamics(k, &[omega]);
        simulate_of(Compiled(self.m), reduced, &self.drive, self.start, t_end, guess, &self.cfg, &mut self.stop)
    }
}
