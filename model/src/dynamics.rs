//! The dynamics of a run-time model: its declared bodies, loads and gravity
//! ([`Model::mass_model`], [`Model::load_values`], from the model's program of them,
//! `crate::dynamics_prog`), and the runtime's dynamics over them.
//!
//! The mass model holds the values of the parameters' registers, its checks the compiled
//! `MassModel`'s ([`MassModelBuf`]); the loads at a state are the load expressions' segment run
//! over the model's registers: evaluating them allocates nothing. The formulas of the dynamics,
//! the inverse cycle ([`ModelCycle`]), the flywheel and the forward simulation
//! ([`ModelSimulation`], its steps recorded or handed over as they are made) are the runtime's, written once over any state ([`AnalogState`]) and
//! any `Kernel`.

use crate::count::Count;
use crate::dynamics_prog::DynamicsProg;
use crate::model::Model;
use kinloop_runtime::dims::{Heap, KinBuf, Sizes};
use kinloop_runtime::dynamics::{
    AnalogState, Cycle, CyclePoint, DenseStep, Dynamics, DynamicsBuf, DynamicsError, MassModelBuf, Recording,
    RunConfig, Shaking, SpeedLaw, Trajectory, simulate_steps_of,
};
use kinloop_runtime::{Error, Source};

/// The inverse dynamics of a run-time model over a turn of its input, set up by name and run by
/// [`ModelCycle::run`]: the compiled mechanism's
/// [`InverseCycle`](kinloop_runtime::dynamics::InverseCycle), with the same defaults (the turn
/// from angle 0, 360 samples, the declared guess at the start, moments about the origin).
#[must_use = "an inverse cycle does nothing until `run`"]
pub struct ModelCycle<'a, 'l> {
    model: &'a mut Model,
    law: SpeedLaw<'l>,
    phi0: f64,
    samples: usize,
    guess: Option<Vec<f64>>,
    about: [f64; 2],
}

impl ModelCycle<'_, '_> {
    /// The turn covers `[phi0, phi0 + 2 pi)`.
    pub fn start(mut self, phi0: f64) -> Self {
        self.phi0 = phi0;
        self
    }

    /// Equally spaced angles per turn (at least 8).
    pub fn samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    /// The positions that choose the assembly branch at the start.
    pub fn guess(mut self, guess: &[f64]) -> Self {
        self.guess = Some(guess.to_vec());
        self
    }

    /// The frame point the shaking moments are taken about.
    pub fn about(mut self, about: [f64; 2]) -> Self {
        self.about = about;
        self
    }

    /// Runs the inverse dynamics over the turn: the runtime's sweep of the turn over the model
    /// ([`turn_states`](kinloop_runtime::dynamics::turn_states)), at each state as the sweep makes it the mass model, the loads, the
    /// driving torque and the shaking ([`Cycle::over_turn`]: no state is kept). Errors: those of the compiled
    /// `InverseCycle::run` (as [`Error::Dynamics`] or the kinematic error), a guess of another
    /// length, a parameter without a value, a model without declared dynamics or with other
    /// than one input ([`Error::InvalidArgument`]).
    pub fn run(self) -> Result<Cycle, Error> {
        let m = self.model;
        let mass = m.mass_model()?;
        let guess = start_guess(m, self.phi0, self.guess)?;
        // The mass model's errors carry the input's value; the model knows its name, as the
        // compiled cycle knows its mechanism's.
        let input_names = m.inputs().to_vec();
        let kernel = m.kernel(m.sweep_config)?;
        let about = self.about;
        let mut d = DynamicsBuf::zeros(1);
        // The sweep borrows the kernel, and each state's loads are computed on the model it lends
        // between two of the sweep's steps.
        let cycle =
            Cycle::over_turn(&kernel, self.phi0, self.samples, Heap(guess.into()), self.law, |k, omega, eps| {
                kernel.lend(|m, _| {
                    let (regs, prog) = m.dynamics_parts();
                    let loads = prog.loads(regs, k);
                    mass.dynamics_into(k, &[omega], loads, &mut d)
                })?;
                let shaking = mass.shaking(k, &[omega], &[eps], about)?;
                CyclePoint::of(k.x[0], omega, eps, &d.mass, &d.gamma, &d.forces, shaking)
            })
            .map_err(|e| e.with_input_names(&input_names.iter().map(String::as_str).collect::<Vec<_>>()))?;
        Ok(cycle)
    }
}

/// The guess at input `phi0` that picks the assembly branch: `given`, or the declared one; a
/// guess of another length than the unknowns is [`Error::InvalidArgument`].
fn start_guess(m: &mut Model, phi0: f64, given: Option<Vec<f64>>) -> Result<Vec<f64>, Error> {
    let guess = match given {
        Some(g) => g,
        None => {
            let mut g = vec![0.0; m.unknowns().len()];
            m.guess(&[phi0], &mut g).map_err(|e| Error::InvalidArgument(format!("{e}, in `{}`", m.name())))?;
            g
        }
    };
    if guess.len() != m.unknowns().len() {
        let n = m.unknowns().len();
        return Err(Error::InvalidArgument(format!("a guess of {} given, {n} expected", Count(guess.len(), "value"))));
    }
    Ok(guess)
}

/// No driving torque.
type NoDrive = fn(f64, f64, f64) -> f64;
/// Never stop early.
type NoStop = fn(f64, &[f64; 2]) -> bool;

/// A forward simulation of a run-time model of one input, set up by name and run by
/// [`ModelSimulation::run`]: the compiled mechanism's
/// [`Simulation`](kinloop_runtime::dynamics::Simulation), with the same setters and defaults
/// (at rest at input 0, from the declared guess there, no driving torque, never stopped early,
/// the default [`RunConfig`]), its mass model the declared bodies, loads and gravity.
#[must_use = "a simulation does nothing until `run`"]
pub struct ModelSimulation<'a, D, S> {
    model: &'a mut Model,
    drive: D,
    stop: S,
    start: [f64; 2],
    guess: Option<Vec<f64>>,
    cfg: RunConfig,
}

impl<'a, D, S> ModelSimulation<'a, D, S> {
    /// Starts from input `phi0` at speed `omega0`.
    pub fn start(mut self, phi0: f64, omega0: f64) -> Self {
        self.start = [phi0, omega0];
        self
    }

    /// The positions that choose the assembly branch at the start (the unknowns in
    /// declaration order).
    pub fn guess(mut self, guess: &[f64]) -> Self {
        self.guess = Some(guess.to_vec());
        self
    }

    /// The integrator's, the solver's and the flywheel's settings.
    pub fn config(mut self, cfg: RunConfig) -> Self {
        self.cfg = cfg;
        self
    }

    /// The driving torque on the input, `drive(t, phi, omega)` (a motor characteristic).
    pub fn drive<D2: Fn(f64, f64, f64) -> f64>(self, drive: D2) -> ModelSimulation<'a, D2, S> {
        let ModelSimulation { model, stop, start, guess, cfg, .. } = self;
        ModelSimulation { model, drive, stop, start, guess, cfg }
    }

    /// Ends the run early when `stop(t, [phi, omega])`, asked after every step, returns `true`.
    pub fn stop_when<S2: FnMut(f64, &[f64; 2]) -> bool>(self, stop: S2) -> ModelSimulation<'a, D, S2> {
        let ModelSimulation { model, drive, start, guess, cfg, .. } = self;
        ModelSimulation { model, drive, stop, start, guess, cfg }
    }

    /// Simulates for `t_end` time units from the start: the runtime's integration
    /// ([`simulate_of`](kinloop_runtime::dynamics::simulate_of())) over this model's kernel,
    /// each evaluation the model's step written in place, its declared loads' segment and
    /// [`MassModelBuf::dynamics_into`] (no allocation but the trajectory's growth): every
    /// accepted step of [`ModelSimulation::run_steps`] recorded.
    ///
    /// Errors: those of the compiled `Simulation::run`, as [`Error::Dynamics`] (a kinematic
    /// failure as [`DynamicsError::Kinematics`] with its time, its source with the model's
    /// names and the input reached; a start that is not finite as [`DynamicsError::BadValue`]);
    /// a guess of another length, a parameter without a value, a model without declared
    /// dynamics ([`Error::InvalidArgument`]); a model of other than one input
    /// ([`DynamicsError::SizeMismatch`] in [`Error::Dynamics`]).
    pub fn run(self, t_end: f64) -> Result<Trajectory, Error>
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

    /// Simulates for `t_end` time units from the start, as [`ModelSimulation::run`] does,
    /// keeping nothing: the runtime's [`simulate_steps_of`] over this model's kernel (the
    /// compiled `Simulation::run_steps`). Each accepted step is handed to `on_step(step, [phi,
    /// omega])` as it is made (its dense output, [`DenseStep::at`] anywhere in `step.t0 ..=
    /// step.t1()`, and the state at its end); `on_step` returning `true` ends the run there, as
    /// the [`ModelSimulation::stop_when`] predicate does (asked after `on_step`, unless that
    /// ended the run). Returns the time and the state `[phi, omega]` reached.
    ///
    /// The steps are those of [`ModelSimulation::run`]'s trajectory, bit for bit, and so are
    /// the errors, which end the run after the steps before them were handed over. Besides
    /// the setup (the mass model, a copy of the registers), a step allocates nothing unless
    /// `on_step` does.
    ///
    /// ```
    /// use kinloop_model::Model;
    /// let text = "pub struct Crank {
    ///     params r = 0.1, l = 0.4, m = 2.0, j = 0.01;
    ///     input phi;
    ///     unknowns beta = 0, x = 0.5;
    ///     loop abc: r @ phi + l @ beta == (x, 0);
    ///     body crank: mass 0, com (0, 0), inertia j, turns phi;
    ///     body piston: mass m, com (x, 0);
    /// }";
    /// let mut model = Model::read("crank.kl", text).unwrap();
    /// // The slowest speed over the run, read from each step's end and middle: no trajectory
    /// // kept; the run ends after the first turn.
    /// let mut slowest = f64::INFINITY;
    /// let (t, [phi, _]) = model
    ///     .simulation()
    ///     .start(0.0, 10.0)
    ///     .run_steps(2.0, |step, &[phi, omega]| {
    ///         slowest = slowest.min(omega).min(step.at(step.t0 + 0.5 * step.h)[1]);
    ///         phi >= std::f64::consts::TAU
    ///     })
    ///     .unwrap();
    /// assert!(t < 2.0 && phi >= std::f64::consts::TAU);
    /// // Free: J = j + m x'^2 >= j, so the crank slows down where the piston moves fast.
    /// assert!(slowest > 0.0 && slowest < 10.0);
    /// ```
    pub fn run_steps(
        self,
        t_end: f64,
        mut on_step: impl FnMut(&DenseStep<2>, &[f64; 2]) -> bool,
    ) -> Result<(f64, [f64; 2]), Error>
    where
        D: Fn(f64, f64, f64) -> f64,
        S: FnMut(f64, &[f64; 2]) -> bool,
    {
        let m = self.model;
        // The compiled simulation's errors for what its types rule out there, before the
        // declared guess is asked at the start: one input, a finite start.
        if m.inputs().len() != 1 {
            let given = m.inputs().len();
            return Err(
                DynamicsError::SizeMismatch { what: "inputs of a one-input simulation", expected: 1, given }.into()
            );
        }
        if let Some(&value) = self.start.iter().find(|v| !v.is_finite()) {
            return Err(DynamicsError::BadValue { what: "initial state", value, why: "must be finite" }.into());
        }
        let mass = m.mass_model()?;
        let guess = start_guess(m, self.start[0], self.guess)?;
        // The loads are evaluated over a copy of the registers (the parameters' values with
        // them): the kernel lends the model itself to the kinematics.
        let mut prog = m.dynamics_ready()?.clone();
        let mut regs = m.registers_view().to_vec();
        let mut d = DynamicsBuf::zeros(1);
        let reduced = |k: &KinBuf, omega: f64| -> Result<Dynamics<1>, DynamicsError> {
            let loads = prog.loads(&mut regs, k);
            mass.dynamics_into(k, &[omega], loads, &mut d)?;
            Ok(Dynamics { mass: [[d.mass[0]]], gamma: [[[d.gamma[0]]]], forces: [d.forces[0]] })
        };
        let kernel = m.kernel(m.sweep_config)?;
        let (start, cfg, mut stop) = (self.start, self.cfg, self.stop);
        let each = |s: &DenseStep<2>, y: &[f64; 2]| on_step(s, y) || stop(s.t1(), y);
        simulate_steps_of(kernel, reduced, self.drive, start, t_end, Heap(guess.into()), &cfg, each).map_err(
            |e| match e {
                // A kinematic failure keeps the time it happened at, as the compiled simulation's.
                e @ DynamicsError::Kinematics { t: Some(_), .. } => Error::Dynamics(Source::new(e)),
                e => e.into(),
            },
        )
    }
}

impl Model {
    /// A forward simulation of this one-input model under its declared bodies, loads and
    /// gravity: see [`ModelSimulation`] (the compiled `Simulation`).
    ///
    /// ```
    /// use kinloop_model::Model;
    /// let text = "pub struct Crank {
    ///     params r = 0.1, l = 0.4, m = 2.0, j = 0.01;
    ///     input phi;
    ///     unknowns beta = 0, x = 0.5;
    ///     loop abc: r @ phi + l @ beta == (x, 0);
    ///     body crank: mass 0, com (0, 0), inertia j, turns phi;
    ///     body piston: mass m, com (x, 0);
    /// }";
    /// let mut model = Model::read("crank.kl", text).unwrap();
    /// // Free: the kinetic energy 1/2 J(phi) omega^2 is kept, with J = j + m x'^2.
    /// let run = model.simulation().start(0.0, 10.0).run(2.0).unwrap();
    /// let [phi, omega] = run.end;
    /// // J >= j everywhere: the crank never turns faster than at the start.
    /// assert!(phi > 6.3 && omega > 0.0 && omega < 10.0 + 1e-6);
    /// ```
    pub fn simulation(&mut self) -> ModelSimulation<'_, NoDrive, NoStop> {
        ModelSimulation {
            model: self,
            drive: |_, _, _| 0.0,
            stop: |_, _| false,
            start: [0.0, 0.0],
            guess: None,
            cfg: RunConfig::default(),
        }
    }

    /// Whether the declaration has dynamics items (bodies, forces, torques, gravity): then
    /// [`Model::mass_model`] exists (the compiled mechanism's `mass_model`).
    pub fn has_dynamics(&self) -> bool {
        self.dynamics.is_some()
    }

    /// The registers and the dynamics program (present: checked by
    /// [`Model::dynamics_ready`]).
    fn dynamics_parts(&mut self) -> (&mut [f64], &mut DynamicsProg) {
        let (regs, prog) = self.regs_and_dynamics();
        (regs, prog.expect("checked by dynamics_ready"))
    }

    /// The declared bodies, loads and gravity with the current parameter values, as the
    /// runtime's [`MassModelBuf`] (the compiled mechanism's `mass_model`: the same checks, a
    /// negative or non-finite mass a [`DynamicsError`] naming the body). A declaration without
    /// dynamics items or a parameter without a value is [`Error::InvalidArgument`].
    pub fn mass_model(&self) -> Result<MassModelBuf, Error> {
        let prog = self.dynamics_ready()?;
        let sizes = Sizes { n: self.unknowns().len(), ni: self.inputs().len(), no: self.outputs().len() };
        Ok(prog.mass_model(self.registers_view(), sizes)?)
    }

    /// The values of the declared loads at state `k` (forces two values each, then torques: the
    /// order of [`MassModelBuf::load_values`]), computed by the load expressions' segment over
    /// the model's registers: no allocation. A state of other sizes is
    /// [`Error::InvalidArgument`].
    pub fn load_values<S: AnalogState + ?Sized>(&mut self, k: &S) -> Result<&[f64], Error> {
        self.dynamics_ready()?;
        let (n, ni) = (self.unknowns().len(), self.inputs().len());
        if k.inputs().len() != ni || k.unknowns().len() != n {
            return Err(Error::InvalidArgument(format!(
                "a state of {} and {} given, {ni} and {n} expected",
                Count(k.inputs().len(), "input"),
                Count(k.unknowns().len(), "unknown")
            )));
        }
        let (regs, prog) = self.dynamics_parts();
        Ok(prog.loads(regs, k))
    }

    /// The dynamics at state `k` (from [`Model::kinematics`] or a sweep) and input speeds `w`:
    /// mass matrix, velocity-product coefficients and generalised forces of the declared items
    /// (the compiled `mass_model()?.dynamics(k, w)`). It builds the mass model on each call;
    /// to evaluate many states without allocating, keep [`Model::mass_model`] and a
    /// `DynamicsBuf`, and call [`Model::load_values`] and `MassModelBuf::dynamics_into`.
    pub fn dynamics<S: AnalogState + ?Sized>(&mut self, k: &S, w: &[f64]) -> Result<DynamicsBuf, Error> {
        let mass = self.mass_model()?;
        let loads = self.load_values(k)?;
        Ok(mass.dynamics(k, w, loads)?)
    }

    /// The shaking force and moment of the declared bodies at state `k`, input speeds `w` and
    /// accelerations `eps`, about the frame point `about`.
    pub fn shaking<S: AnalogState + ?Sized>(
        &mut self,
        k: &S,
        w: &[f64],
        eps: &[f64],
        about: [f64; 2],
    ) -> Result<Shaking, Error> {
        Ok(self.mass_model()?.shaking(k, w, eps, about)?)
    }

    /// The inverse dynamics over a turn of the input at the speed law `law`: see
    /// [`ModelCycle`].
    ///
    /// ```
    /// use kinloop_model::Model;
    /// use kinloop_runtime::dynamics::SpeedLaw;
    /// let text = "pub struct Crank {
    ///     params r = 0.1, l = 0.4, m = 2.0;
    ///     input phi;
    ///     unknowns beta = 0, x = 0.5;
    ///     loop abc: r @ phi + l @ beta == (x, 0);
    ///     body piston: mass m, com (x, 0);
    /// }";
    /// let mut model = Model::read("crank.kl", text).unwrap();
    /// let cycle = model.inverse_cycle(SpeedLaw::Constant(10.0)).samples(72).run().unwrap();
    /// // At a constant speed and without loads, the mean driving torque vanishes.
    /// assert!(cycle.mean_torque().unwrap().abs() < 1e-12);
    /// ```
    pub fn inverse_cycle<'l>(&mut self, law: SpeedLaw<'l>) -> ModelCycle<'_, 'l> {
        ModelCycle { model: self, law, phi0: 0.0, samples: 360, guess: None, about: [0.0, 0.0] }
    }

    /// The declaration has dynamics items and every parameter a value, else
    /// [`Error::InvalidArgument`] saying what is missing.
    fn dynamics_ready(&self) -> Result<&DynamicsProg, Error> {
        let Some(prog) = &self.dynamics else {
            return Err(Error::InvalidArgument(format!(
                "`{}` declares no bodies, loads or gravity: declare them (`body`, `force`, `torque`, `gravity`) for its dynamics",
                self.name()
            )));
        };
        if let Some(k) = self.first_unset() {
            return Err(Error::InvalidArgument(format!(
                "parameter `{}` has no value (it has no default: give one), in `{}`",
                self.params()[k],
                self.name()
            )));
        }
        Ok(prog)
    }
}

/// A run-time model's flat state, read by the runtime's dynamics.
impl AnalogState for crate::model::State {
    fn inputs(&self) -> &[f64] {
        &self.x
    }
    fn unknowns(&self) -> &[f64] {
        &self.q
    }
    fn outputs(&self) -> &[f64] {
        &self.out
    }
    fn unknown_d1(&self, u: usize, i: usize) -> f64 {
        self.dq[u * self.x.len() + i]
    }
    fn unknown_d2(&self, u: usize, i: usize, j: usize) -> f64 {
        let ni = self.x.len();
        self.d2q[(u * ni + i) * ni + j]
    }
    fn output_d1(&self, o: usize, i: usize) -> f64 {
        self.dout[o * self.x.len() + i]
    }
    fn output_d2(&self, o: usize, i: usize, j: usize) -> f64 {
        let ni = self.x.len();
        self.d2out[(o * ni + i) * ni + j]
    }
    fn non_finite(&self) -> Option<f64> {
        [&self.x, &self.q, &self.dq, &self.d2q, &self.out, &self.dout, &self.d2out]
            .into_iter()
            .flat_map(|v| v.iter().copied())
            .find(|v| !v.is_finite())
    }
}
