//! Forward simulation of a one-input machine:
//! `(J(phi) + J_fly) phi'' + 1/2 J'(phi) phi'^2 = M_drive(t, phi, phi') + Q(phi, phi')`,
//! integrated by [`dopri5`](super::dopri5) with the kinematics solved at every evaluation
//! (warm-started from the previous one, so the machine stays on its assembly branch). The
//! integration is written once over any kernel ([`simulate_of`](super::simulate_of::simulate_of)); a run-time model's
//! simulation is the same.

use super::error::DynamicsError;
use super::model::MassModel;
use super::ode::DenseStep;
use super::simulate_of::{Recording, RunConfig, Trajectory, simulate_steps_of};
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
/// [`Simulation::run`] keeps every accepted step (its [`Trajectory`]);
/// [`Simulation::run_steps`] hands each one to the caller as it is made and keeps nothing.
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

/// The mechanism by its type, the mass model, the start, the guess and the settings; the
/// drive and the stop, closures, elided.
impl<M, D, S, const N: usize, const NO: usize> std::fmt::Debug for Simulation<'_, M, D, S, N, NO> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Simulation")
            .field("mechanism", &std::any::type_name::<M>())
            .field("model", self.model)
            .field("start", &self.start)
            .field("guess", &self.guess)
            .field("config", &self.cfg)
            .finish_non_exhaustive()
    }
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
    /// [`DynamicsError::Kinematics`] with the time, at a trial state of the integrator's step
    /// (the motion heading there: a trial angle thrown far from where the motion heads is
    /// retried with a smaller step; at a loose tolerance, whose steps are long, one thrown not as
    /// far can stop a motion short of the failure, which tighter tolerances or
    /// [`OdeConfig::h_max`](super::OdeConfig::h_max) avoid); a step that collapses (approaching a limit
    /// position, where the reduced inertia grows without bound) as
    /// [`DynamicsError::SingularMotion`] with the input reached; a reduced inertia that is not positive as
    /// [`DynamicsError::SingularMass`]; a drive or load that is not finite as
    /// [`DynamicsError::NonFiniteLoad`]; a start so far out (an input of 1e300) that a step cannot
    /// change it as [`DynamicsError::CannotAdvance`]; results beyond the range of `f64` as
    /// [`DynamicsError::Overflow`]; a span that needs more steps than the budget
    /// ([`OdeConfig::max_steps`](super::OdeConfig::max_steps) of the configuration's `ode`) as
    /// [`DynamicsError::TooManySteps`]; an angle parameter too large to resolve (beyond the
    /// `largest_precise_angle` of the configuration's `newton`) as [`DynamicsError::Kinematics`]
    /// before any step; integrator failures. Besides the recorded trajectory (one entry per
    /// accepted step, 96 bytes, amortised growth up to the step budget: 0.96 GB at the default
    /// budget, see [`OdeConfig::max_steps`](super::OdeConfig::max_steps)), a step allocates
    /// nothing; a long run that needs only what passes keeps nothing with
    /// [`Simulation::run_steps`].
    pub fn run(self, t_end: f64) -> Result<Trajectory, DynamicsError>
    where
        D: Fn(f64, f64, f64) -> f64,
        S: FnMut(f64, &[f64; 2]) -> bool,
    {
        let mut steps = Recording::new(&self.cfg.ode);
        let (t_end, end) = self.run_steps(t_end, |s, _| {
            steps.push(s);
            false
        })?;
        Ok(steps.finish(t_end, end))
    }

    /// Simulates for `t_end` time units from the start, as [`Simulation::run`] does, keeping
    /// nothing: each accepted step is handed to `on_step(step, [phi, omega])` as it is made (its
    /// dense output, [`DenseStep::at`] anywhere in `step.t0 ..= step.t1()`, and the state at its
    /// end), and `on_step` returning `true` ends the run there, as
    /// [`Simulation::stop_when`]'s predicate does (asked after `on_step`, unless that ended the
    /// run). Returns the time and the state `[phi, omega]` reached.
    ///
    /// The steps are those of [`Simulation::run`]'s [`Trajectory`], bit for bit (that is this
    /// run with each step pushed), and so are the errors, which end the run after the steps
    /// before them were handed over. A step allocates nothing unless `on_step` does: a run of
    /// any length takes the memory of what `on_step` keeps.
    ///
    /// ```
    /// use kinloop_runtime::dynamics::{Body, Coord, MassModel, Rotation, Simulation};
    /// # use kinloop_runtime::{BlockInfo, Error, Health, Jac, Kin, Mechanism, NewtonConfig, SolveReport};
    /// # /// A wheel turning with its input: no unknowns, no outputs.
    /// # struct Wheel;
    /// # impl Mechanism<0, 1, 0> for Wheel {
    /// #     const NAME: &'static str = "Wheel";
    /// #     const PARAMS: &'static [&'static str] = &[];
    /// #     const INPUTS: [&'static str; 1] = ["phi"];
    /// #     const UNKNOWNS: [&'static str; 0] = [];
    /// #     const EQUATIONS: [&'static str; 0] = [];
    /// #     const OUTPUTS: [&'static str; 0] = [];
    /// #     const BLOCKS: &'static [BlockInfo] = &[];
    /// #     fn param_values(&self) -> Vec<f64> { Vec::new() }
    /// #     fn guess_flat(&self, _: &[f64; 1]) -> [f64; 0] { [] }
    /// #     fn position_flat(&self, _: &[f64; 1], _: &[f64; 0], _: &NewtonConfig) -> Result<([f64; 0], SolveReport), Error> {
    /// #         Ok(([], SolveReport::given(0.0)))
    /// #     }
    /// #     fn kinematics_flat(&self, x: &[f64; 1], q: &[f64; 0], cfg: &NewtonConfig) -> Result<Kin<0, 1, 0>, Error> {
    /// #         self.kinematics_at_flat(x, q, cfg)
    /// #     }
    /// #     fn kinematics_at_flat(&self, x: &[f64; 1], _: &[f64; 0], _: &NewtonConfig) -> Result<Kin<0, 1, 0>, Error> {
    /// #         let (q, dq, d2q, out, dout, d2out) = ([], [], [], [], [], []);
    /// #         Ok(Kin { x: *x, q, dq, d2q, out, dout, d2out, report: SolveReport::given(0.0), health: Health::default() })
    /// #     }
    /// #     fn outputs_flat(&self, _: &[f64; 1], _: &[f64; 0]) -> [f64; 0] { [] }
    /// #     fn jacobian_flat(&self, _: &[f64; 1], _: &[f64; 0]) -> Jac<0, 1> {
    /// #         Jac { f: [], j: [], fx: [], scale: [], unit: [], input_unit: [1.0] }
    /// #     }
    /// # }
    /// // A wheel of moment of inertia 2 turning with the input, driven by a torque of 1.
    /// let wheel = Body { name: "wheel".into(), mass: 0.0, com: [Coord::Fixed(0.0); 2], inertia: 2.0, rotation: Rotation::Input(0) };
    /// let model = MassModel::<0, 1, 0>::new().with_body(wheel)?;
    /// // The mean speed over the run, from each step's dense output at its middle: no
    /// // trajectory kept, the run ended once the wheel has turned 1 radian.
    /// let (mut angle, mut steps) = (0.0, 0);
    /// let (t, [phi, omega]) = Simulation::new(&Wheel, &model)
    ///     .drive(|_t, _phi, _omega| 1.0)
    ///     .run_steps(10.0, |step, &[phi, _omega]| {
    ///         angle += step.at(step.t0 + 0.5 * step.h)[1] * step.h;
    ///         steps += 1;
    ///         phi >= 1.0
    ///     })?;
    /// // From rest: omega = t / 2, phi = t^2 / 4, reached 1 at t = 2 (within the last step).
    /// assert!(t < 10.0 && phi >= 1.0 && (omega - t / 2.0).abs() < 1e-9);
    /// assert!(steps > 1 && (angle - phi).abs() < 1e-6, "{angle} against {phi}");
    /// # Ok::<(), kinloop_runtime::dynamics::DynamicsError>(())
    /// ```
    pub fn run_steps(
        mut self,
        t_end: f64,
        mut on_step: impl FnMut(&DenseStep<2>, &[f64; 2]) -> bool,
    ) -> Result<(f64, [f64; 2]), DynamicsError>
    where
        D: Fn(f64, f64, f64) -> f64,
        S: FnMut(f64, &[f64; 2]) -> bool,
    {
        // `simulate_steps_of` refuses an angle parameter too large to resolve, once at the
        // start, not at each step's solves.
        let guess = self.guess.unwrap_or_else(|| self.m.guess_flat(&[self.start[0]]));
        let model = self.model;
        let reduced = |k: &Kin<N, 1, NO>, omega: f64| model.dynamics(k, &[omega]);
        let stop = &mut self.stop;
        let each = |s: &DenseStep<2>, y: &[f64; 2]| on_step(s, y) || stop(s.t1(), y);
        simulate_steps_of(Compiled(self.m), reduced, &self.drive, self.start, t_end, guess, &self.cfg, each)
    }
}
