//! The forward simulation written once, over any [`Kernel`] and any evaluation of a one-input
//! mass model at a state: a compiled mechanism's [`Simulation`](super::Simulation) (through
//! [`Compiled`](crate::mechanism::kernel::Compiled) and its [`MassModel`](super::MassModel)) and a run-time model's
//! (`kinloop_model::Model::simulation`, its `MassModelBuf` and its load expressions) run this
//! integration, with the same operations in the same order. Its settings ([`RunConfig`]) and
//! result ([`Trajectory`]) are every simulation's. The integration hands each accepted step
//! to its caller as it is made ([`simulate_steps_of`]); recording them into the trajectory
//! ([`simulate_of`]) is one use of them.

use super::error::DynamicsError;
use super::eval::Dynamics;
use super::ode::{DenseStep, OdeConfig, dopri5_judged};
use crate::dims::{Dims, KinState};
use crate::mechanism::kernel::Kernel;
use crate::solvers::newton::NewtonConfig;
use crate::trig::Libm;

/// Settings of a simulation ([`Simulation`](super::Simulation), [`simulate_of`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct RunConfig {
    /// Integrator tolerances (the state is `[phi, omega]`).
    pub ode: OdeConfig,
    /// Newton settings of the kinematic solves.
    pub newton: NewtonConfig,
    /// Moment of inertia of a flywheel on the input shaft (added to `J`).
    pub flywheel: f64,
}

impl Default for RunConfig {
    fn default() -> Self {
        RunConfig { ode: OdeConfig::default(), newton: NewtonConfig::default(), flywheel: 0.0 }
    }
}

impl RunConfig {
    /// Sets [`RunConfig::ode`].
    pub fn with_ode(mut self, ode: OdeConfig) -> Self {
        self.ode = ode;
        self
    }
    /// Sets [`RunConfig::newton`].
    pub fn with_newton(mut self, newton: NewtonConfig) -> Self {
        self.newton = newton;
        self
    }
    /// Sets [`RunConfig::flywheel`].
    pub fn with_flywheel(mut self, inertia: f64) -> Self {
        self.flywheel = inertia;
        self
    }
}

/// The simulated motion: every accepted step with its dense output.
#[derive(Clone, Debug, PartialEq)]
pub struct Trajectory {
    /// The accepted steps in time order.
    pub steps: Vec<DenseStep<2>>,
    /// Time reached.
    pub t_end: f64,
    /// `[phi, omega]` reached.
    pub end: [f64; 2],
}

/// A [`Trajectory`] being recorded, one accepted step at a time, by a run whose step budget is
/// its configuration's [`OdeConfig::max_steps`] ([`simulate_of`], `Simulation::run`, a run-time
/// model's `run`): its steps' storage grows as a `Vec`'s does (doubling), but never past the
/// budget, which no run's accepted steps exceed.
///
/// Why not a plain `Vec`: at the default budget of ten million steps its doubling reserves room
/// for 16.8 million (1.6 GB at 96 bytes a step) once a run passes 8.4 million, where 0.96 GB
/// holds every step a run can make (a span far beyond the budget makes them all before its
/// [`DynamicsError::TooManySteps`]). The steps recorded, and so the trajectory, are the same.
///
/// Public for the run-time models' `run` (kinloop-model) alone, and hidden: a caller that wants
/// the trajectory calls `run`, one that wants each step as it is made `run_steps`, which keeps
/// none.
#[doc(hidden)]
#[derive(Debug)]
pub struct Recording {
    steps: Vec<DenseStep<2>>,
    budget: usize,
}

impl Recording {
    /// An empty recording of a run configured by `cfg` (its budget, `cfg.max_steps`).
    pub fn new(cfg: &OdeConfig) -> Self {
        Recording { steps: Vec::new(), budget: cfg.max_steps }
    }

    /// Records the accepted step `step`.
    pub fn push(&mut self, step: &DenseStep<2>) {
        if self.steps.len() == self.steps.capacity() {
            // At least one more, should a caller push past the budget (no run does).
            let room = self.budget.saturating_sub(self.steps.len()).max(1);
            self.steps.reserve_exact(self.steps.len().max(4).min(room));
        }
        self.steps.push(*step);
    }

    /// The steps recorded, in time order.
    pub fn steps(&self) -> &[DenseStep<2>] {
        &self.steps
    }

    /// The trajectory of the steps recorded, which reached `t_end` and the state `end` there.
    pub fn finish(self, t_end: f64, end: [f64; 2]) -> Trajectory {
        Trajectory { steps: self.steps, t_end, end }
    }
}

impl Trajectory {
    /// `[phi, omega]` at time `t` (clamped to the simulated interval), from the dense output;
    /// NaN at a time that is NaN.
    pub fn at(&self, t: f64) -> [f64; 2] {
        if self.steps.is_empty() {
            return self.end;
        }
        let i = self.steps.partition_point(|s| s.t1() < t).min(self.steps.len() - 1);
        let s = &self.steps[i];
        s.at(t.clamp(s.t0, s.t1()))
    }
}

/// Simulates the one-input machine `m` for `t_end` time units from `start = [phi0, omega0]`:
/// `(J + J_fly) phi'' + 1/2 J' phi'^2 = M_drive + Q` by [`dopri5`](super::ode::dopri5), the
/// kinematics solved at every evaluation (the first from `guess`, every later one warm-started
/// from the last position, without restarts, so that the machine stays on its assembly
/// branch; a trial state of a step that fails the kinematic solve is judged thrown off the
/// motion by its angle alone, see `dopri5_judged`), and records
/// the motion: [`simulate_steps_of`] with every accepted step pushed into the [`Trajectory`].
///
/// `reduced(state, omega)` gives the one-input dynamics at a solved state and input speed (the
/// reduced inertia `J = mass[0][0]`, `1/2 J' = gamma[0][0][0]`, the generalised force `Q`: a
/// compiled `MassModel::dynamics`, a run-time `MassModelBuf::dynamics_into`); `drive(t, phi,
/// omega)` the driving torque; `stop(t, [phi, omega])`, asked after every step, ends the run
/// early. The errors of [`Simulation::run`](super::Simulation::run); besides, a kernel with
/// other than one input, or a guess of another size than its unknowns, is
/// [`DynamicsError::SizeMismatch`]; an angle parameter beyond the `largest_precise_angle` of
/// `cfg.newton` ([`Kernel::check_param_angles`]) is refused before the first step. Besides the
/// recorded trajectory (one entry per accepted step, amortised growth up to the step budget,
/// [`OdeConfig::max_steps`]), a step allocates nothing unless `reduced` does.
#[allow(clippy::too_many_arguments)]
pub fn simulate_of<K: Kernel>(
    m: K,
    reduced: impl FnMut(&<K::Dims as Dims>::Kin, f64) -> Result<Dynamics<1>, DynamicsError>,
    drive: impl Fn(f64, f64, f64) -> f64,
    start: [f64; 2],
    t_end: f64,
    guess: <K::Dims as Dims>::Q,
    cfg: &RunConfig,
    mut stop: impl FnMut(f64, &[f64; 2]) -> bool,
) -> Result<Trajectory, DynamicsError> {
    let mut steps = Recording::new(&cfg.ode);
    let (t_end, end) = simulate_steps_of(m, reduced, drive, start, t_end, guess, cfg, |s, y| {
        steps.push(s);
        stop(s.t1(), y)
    })?;
    Ok(steps.finish(t_end, end))
}

/// The forward simulation of [`simulate_of`], keeping nothing: each accepted step is handed to
/// `on_step(step, [phi, omega])` as it is made (its dense output, which gives the state
/// anywhere in `step.t0 ..= step.t1()`, and the state at its end), and `on_step` returning
/// `true` ends the run there. Returns the time and the state `[phi, omega]` reached (`t_end`
/// unless `on_step` ended the run early), as [`dopri5`](super::ode::dopri5) does.
///
/// The steps are those [`simulate_of`] records, bit for bit (it is this function with each
/// step pushed into its trajectory), so a consumer that samples them as they pass sees what
/// [`Trajectory::at`] gives afterwards, in the memory of what it keeps. The arguments and
/// errors are [`simulate_of`]'s: an error (with its time, and the input and speed reached for
/// a collapsing step) ends the run after the steps before it were handed over. A step
/// allocates nothing unless `reduced` or `on_step` does.
///
/// ```
/// use kinloop_runtime::dynamics::{Dynamics, RunConfig, simulate_steps_of};
/// use kinloop_runtime::{Compiled, Kin};
/// # use kinloop_runtime::{BlockInfo, Error, Health, Jac, Mechanism, NewtonConfig, SolveReport};
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
/// // A wheel of reduced inertia 2 (`Wheel`: the input is its angle) under a torque of 1.
/// let reduced = |_: &Kin<0, 1, 0>, _omega: f64| Ok(Dynamics { mass: [[2.0]], gamma: [[[0.0]]], forces: [0.0] });
/// // The largest step, and the speed at each step's middle from its dense output: nothing kept.
/// let (mut longest, mut worst) = (0.0f64, 0.0f64);
/// let (t, [phi, omega]) = simulate_steps_of(
///     Compiled(&Wheel), reduced, |_t, _phi, _omega| 1.0, [0.0, 0.0], 2.0, [], &RunConfig::default(),
///     |step, _end| {
///         let mid = step.t0 + 0.5 * step.h;
///         longest = longest.max(step.h);
///         worst = worst.max((step.at(mid)[1] - mid / 2.0).abs());
///         false // never end the run early
///     },
/// )?;
/// // From rest: omega = t / 2, phi = t^2 / 4.
/// assert_eq!(t, 2.0);
/// assert!((omega - 1.0).abs() < 1e-9 && (phi - 1.0).abs() < 1e-9 && worst < 1e-9);
/// assert!(longest > 0.0 && longest <= 2.0);
/// # Ok::<(), kinloop_runtime::dynamics::DynamicsError>(())
/// ```
#[allow(clippy::too_many_arguments)]
pub fn simulate_steps_of<K: Kernel>(
    m: K,
    mut reduced: impl FnMut(&<K::Dims as Dims>::Kin, f64) -> Result<Dynamics<1>, DynamicsError>,
    drive: impl Fn(f64, f64, f64) -> f64,
    start: [f64; 2],
    t_end: f64,
    guess: <K::Dims as Dims>::Q,
    cfg: &RunConfig,
    mut on_step: impl FnMut(&DenseStep<2>, &[f64; 2]) -> bool,
) -> Result<(f64, [f64; 2]), DynamicsError> {
    let d = m.dims();
    if d.ni() != 1 {
        return Err(DynamicsError::SizeMismatch {
            what: "inputs of a one-input simulation",
            expected: 1,
            given: d.ni(),
        });
    }
    if guess.as_ref().len() != d.n() {
        return Err(DynamicsError::SizeMismatch {
            what: "unknowns of the guess",
            expected: d.n(),
            given: guess.as_ref().len(),
        });
    }
    if !(cfg.flywheel >= 0.0 && cfg.flywheel.is_finite()) {
        return Err(DynamicsError::BadValue {
            what: "flywheel inertia",
            value: cfg.flywheel,
            why: "must be finite, not negative",
        });
    }
    for v in start {
        if !v.is_finite() {
            return Err(DynamicsError::BadValue { what: "initial state", value: v, why: "must be finite" });
        }
    }
    // The kernel's step requires valid settings: checked once, as the first solve's error.
    cfg.newton.validate().map_err(|source| DynamicsError::Kinematics { t: Some(0.0), source })?;
    // An angle parameter too large to resolve: once, before the first evaluation.
    m.check_param_angles(&cfg.newton).map_err(DynamicsError::kin)?;
    // The workspace of every evaluation, made once: the input, the last position, the state.
    let (mut x, mut q, mut k) = (d.x(), guess, d.kin());
    // The first solve is from the caller's guess; every later one from the last position, where
    // a restart would find another branch.
    let mut newton = cfg.newton;
    // The input's name, for the errors of the mass model's evaluations (which see its value
    // only): copied into an error on its way out, never per evaluation.
    let input = [m.input_name(0)];
    let named = |e: DynamicsError| e.with_input_names(&input);
    let rhs = |t: f64, y: &[f64; 2]| -> Result<[f64; 2], DynamicsError> {
        let [phi, omega] = *y;
        x[0] = phi;
        // The kernel's step with libm's sines and cosines: the same result as its kinematics,
        // written in place (nothing built and copied per evaluation).
        m.step_into(&x, &q, &newton, &mut Libm, &mut k)
            .map_err(|source| DynamicsError::Kinematics { t: Some(t), source })?;
        q.as_mut().copy_from_slice(k.q());
        newton.restarts = false;
        let mut d = reduced(&k, omega).map_err(named)?;
        let tau = drive(t, phi, omega);
        if !tau.is_finite() {
            let e = DynamicsError::NonFiniteLoad { name: "drive".into(), value: tau, x: vec![phi], names: Vec::new() };
            return Err(named(e));
        }
        d.mass[0][0] += cfg.flywheel;
        let eps = d.accelerations(&[phi], &[omega], &[tau]).map_err(named)?;
        Ok([omega, eps[0]])
    };
    let mut reached = start;
    // A kinematic solve depends on the input's angle alone; any other failure (a load's law,
    // the drive) may depend on the speed as well.
    let depends = |e: &DynamicsError| [true, !matches!(e, DynamicsError::Kinematics { .. })];
    let run = dopri5_judged(rhs, depends, 0.0, start, t_end, &cfg.ode, |s, y| {
        reached = *y;
        Ok(on_step(s, y))
    });
    match run {
        Ok(end) => Ok(end),
        // Say where: the input and speed of the last accepted step.
        Err(DynamicsError::StepTooSmall { t, h }) => Err(named(DynamicsError::SingularMotion {
            t,
            h,
            x: vec![reached[0]],
            speed: vec![reached[1]],
            names: Vec::new(),
        })),
        Err(e) => Err(e),
    }
}
