//! Forward simulation of a one-input machine:
//! `(J(phi) + J_fly) phi'' + 1/2 J'(phi) phi'^2 = M_drive(t, phi, phi') + Q(phi, phi')`,
//! integrated by [`dopri5`] with the kinematics solved at every evaluation (warm-started from
//! the previous one, so the machine stays on its assembly branch).

use super::error::DynamicsError;
use super::model::MassModel;
use super::ode::{DenseStep, OdeConfig, dopri5};
use crate::mechanism::Mechanism;
use crate::solvers::newton::NewtonConfig;

/// Settings of [`simulate`].
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

/// Simulates from `phi0` at speed `omega0` for `t_end` time units, `guess` choosing the
/// assembly branch at `phi0`. `drive(t, phi, omega)` is the driving torque on the input (a motor
/// characteristic; `|_, _, _| 0.0` for none). `stop(t, [phi, omega])` is asked after every step
/// and ends the run early when it returns `true`.
///
/// Errors: a kinematic failure (limit or singular position, no assembly) as
/// [`DynamicsError::Kinematics`] with the time; a step that collapses (approaching a limit
/// position, where the reduced inertia grows without bound) as
/// [`DynamicsError::SingularMotion`] with the input reached; a reduced inertia that is not positive as
/// [`DynamicsError::SingularMass`]; a drive or load that is not finite as
/// [`DynamicsError::NonFiniteLoad`]; a start so far out (an input of 1e300) that a step cannot
/// change it as [`DynamicsError::CannotAdvance`]; results beyond the range of `f64` as
/// [`DynamicsError::Overflow`]; integrator failures. Besides the recorded trajectory (one
/// entry per accepted step, amortised growth), a step allocates nothing.
#[allow(clippy::too_many_arguments)]
pub fn simulate<M, const N: usize, const NO: usize>(
    m: &M,
    model: &MassModel<N, 1, NO>,
    drive: impl Fn(f64, f64, f64) -> f64,
    start: [f64; 2],
    t_end: f64,
    guess: [f64; N],
    cfg: &RunConfig,
    mut stop: impl FnMut(f64, &[f64; 2]) -> bool,
) -> Result<Trajectory, DynamicsError>
where
    M: Mechanism<N, 1, NO>,
{
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
    let mut q = guess;
    // The first solve is from the caller's guess; every later one from the last position, where
    // a restart would find another branch.
    let mut newton = cfg.newton;
    let rhs = |t: f64, y: &[f64; 2]| -> Result<[f64; 2], DynamicsError> {
        let [phi, omega] = *y;
        let k = m.kinematics_flat(&[phi], &q, &newton).map_err(|source| DynamicsError::Kinematics { t, source })?;
        q = k.q;
        newton.restarts = false;
        let d = model.dynamics(&k, &[omega])?;
        let tau = drive(t, phi, omega);
        if !tau.is_finite() {
            return Err(DynamicsError::NonFiniteLoad { name: "drive", value: tau, x: vec![phi] });
        }
        let mut d = d;
        d.mass[0][0] += cfg.flywheel;
        let eps = d.accelerations(&[phi], &[omega], &[tau])?;
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
        Err(DynamicsError::StepTooSmall { t, h }) => {
            Err(DynamicsError::SingularMotion { t, h, x: vec![reached[0]], speed: vec![reached[1]] })
        }
        Err(e) => Err(e),
    }
}
