//! The forward simulation written once, over any [`Kernel`] and any evaluation of a one-input
//! mass model at a state: a compiled mechanism's [`Simulation`](super::Simulation) (through
//! [`Compiled`](crate::mechanism::kernel::Compiled) and its [`MassModel`](super::MassModel)) and a run-time model's
//! (`kinloop_model::Model::simulation`, its `MassModelBuf` and its load expressions) run this
//! integration, with the same operations in the same order. Its settings ([`RunConfig`]) and
//! result ([`Trajectory`]) are every simulation's.

use super::error::DynamicsError;
use super::eval::Dynamics;
use super::ode::{DenseStep, OdeConfig, dopri5};
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

impl Trajectory {
    /// `[phi, omega]` at time `t` (clamped to the simulated interval), from the dense output.
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
/// `(J + J_fly) phi'' + 1/2 J' phi'^2 = M_drive + Q` by [`dopri5`], the kinematics solved at
/// every evaluation (the first from `guess`, every later one warm-started from the last
/// position, without restarts, so that the machine stays on its assembly branch).
///
/// `reduced(state, omega)` gives the one-input dynamics at a solved state and input speed (the
/// reduced inertia `J = mass[0][0]`, `1/2 J' = gamma[0][0][0]`, the generalised force `Q`: a
/// compiled `MassModel::dynamics`, a run-time `MassModelBuf::dynamics_into`); `drive(t, phi,
/// omega)` the driving torque; `stop(t, [phi, omega])`, asked after every step, ends the run
/// early. The errors of [`Simulation::run`](super::Simulation::run); besides, a kernel with
/// other than one input, or a guess of another size than its unknowns, is
/// [`DynamicsError::SizeMismatch`]. Besides the recorded trajectory (one entry per accepted
/// step, amortised growth), a step allocates nothing unless `reduced` does.
#[allow(clippy::too_many_arguments)]
pub fn simulate_of<K: Kernel>(
    m: K,
    mut reduced: impl FnMut(&<K::Dims as Dims>::Kin, f64) -> Result<Dynamics<1>, DynamicsError>,
    drive: impl Fn(f64, f64, f64) -> f64,
    start: [f64; 2],
    t_end: f64,
    guess: <K::Dims as Dims>::Q,
    cfg: &RunConfig,
    mut stop: impl FnMut(f64, &[f64; 2]) -> bool,
) -> Result<Trajectory, DynamicsError> {
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
    let mut steps = Vec::new();
    let mut reached = start;
    let run = dopri5(rhs, 0.0, start, t_end, &cfg.ode, |s, y| {
        steps.push(*s);
        reached = *y;
        Ok(stop(s.t1(), y))
    });
    match run {
        Ok((t, end)) => Ok(Trajectory { steps, t_end: t, end }),
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
