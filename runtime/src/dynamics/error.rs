//! Errors of the dynamics layer: a bad mass model, a load that is not finite, a mass matrix that
//! is not positive definite, a kinematic solve that fails on the way (limit or singular position),
//! and integrator failures. Each converts into [`crate::Error`].

use crate::error::Error;
use crate::number::Number;
use std::borrow::Cow;

/// What went wrong in a dynamic analysis; see the [module documentation](self).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DynamicsError {
    /// A mass or a moment of inertia is negative, NaN or infinite.
    #[error("the {quantity} of body `{body}` is {value}: it must be finite and not negative")]
    BadMass {
        /// The body's name.
        body: Cow<'static, str>,
        /// `"mass"` or `"moment of inertia"`.
        quantity: &'static str,
        /// The offending value.
        value: f64,
    },
    /// An index of the kinematic state is out of range.
    #[error("{owner} `{name}` refers to {what} {index}, but the mechanism has only {len}")]
    IndexOutOfRange {
        /// `"body"` or `"load"`.
        owner: &'static str,
        /// The body's or the load's name.
        name: Cow<'static, str>,
        /// `"output column"`, `"unknown"` or `"input"`.
        what: &'static str,
        /// The offending index.
        index: usize,
        /// How many there are.
        len: usize,
    },
    /// A constant of the model (gravity, a load, a speed, a tolerance) is not finite or out of
    /// its range.
    #[error("invalid {what}: {value} ({why})")]
    BadValue {
        /// What the value is.
        what: &'static str,
        /// The value.
        value: f64,
        /// What it must be.
        why: &'static str,
    },
    /// A torque is applied to a body that does not rotate (a slider).
    #[error("the torque `{name}` acts on no angle: give it an unknown or an input to act on")]
    TorqueOnSlider {
        /// The load's name.
        name: Cow<'static, str>,
    },
    /// A force or torque law returned NaN or infinity.
    #[error("the load `{name}` is not finite ({value}) at input {x:?}")]
    NonFiniteLoad {
        /// The load's name (`"drive"` for a drive torque law).
        name: Cow<'static, str>,
        /// The value returned.
        value: f64,
        /// The inputs where it happened.
        x: Vec<f64>,
    },
    /// The mass matrix (the reduced moment of inertia for one input) is not positive definite:
    /// the machine has no inertia in some direction of motion at this position.
    #[error("the mass matrix is not positive definite at input {x:?} (pivot {pivot:e}); give the machine mass")]
    SingularMass {
        /// The inputs where it happened.
        x: Vec<f64>,
        /// The smallest pivot of its Cholesky factorisation.
        pivot: f64,
    },
    /// The kinematic solve failed (a limit position, a singular position, no assembly), at
    /// time `t` of a simulation (`None` outside a simulation).
    #[error("kinematics failed{}: {source}", at_time(*.t))]
    Kinematics {
        /// Time of the simulation when it happened (`None` when not simulating).
        t: Option<f64>,
        /// The kinematic error, with its location.
        source: Error,
    },
    /// The integrator's step fell below the resolution of the time: the motion is singular
    /// (or the tolerance is unreachable).
    #[error("the integration step fell to {h:e} at t = {t}: the motion is singular here")]
    StepTooSmall {
        /// Time reached.
        t: f64,
        /// The step size.
        h: f64,
    },
    /// A simulation's step collapsed: the motion is singular at input `x`. Approaching a limit
    /// position, the reduced moment of inertia grows without bound (like `1 / (x_limit - x)`),
    /// the speed falls to zero in finite time and the input stops being a coordinate of the
    /// motion; the step collapses there before a kinematic solve fails.
    #[error(
        "the motion is singular at input {x:?}, speed {speed:?} (t = {t}): the integration step fell to {h:e}; \
         is this a limit position?"
    )]
    SingularMotion {
        /// Time reached.
        t: f64,
        /// The step size.
        h: f64,
        /// The inputs reached (the last accepted state).
        x: Vec<f64>,
        /// The input speeds there.
        speed: Vec<f64>,
    },
    /// A result of the dynamics is beyond the range of `f64` (masses, speeds or loads so large
    /// that a product or a sum of them overflows), though every input is finite.
    #[error(
        "the {what}{} is beyond the range of f64: express the model in other units (larger units of mass, length or time)",
        at_input(.x)
    )]
    Overflow {
        /// Which result (`"total mass"`, `"mass matrix"`, `"driving torque"`, ...).
        what: &'static str,
        /// The inputs where it happened (empty when it does not depend on them).
        x: Vec<f64>,
    },
    /// A Fourier series asked for more harmonics than its samples resolve: `n` samples of a
    /// period determine harmonics below `n / 2` only.
    #[error(
        "{harmonics} harmonics asked of {samples} samples per period: they resolve at most {} \
         (fewer than half the samples); take fewer harmonics or more samples",
        samples.saturating_sub(1) / 2
    )]
    TooManyHarmonics {
        /// Harmonics asked for.
        harmonics: usize,
        /// Samples per period.
        samples: usize,
    },
    /// An integration step cannot change a component of the state: the change it computes
    /// is below the spacing of `f64` numbers at the component's value, so the state stays
    /// where it is (e.g. a simulation started at an input angle of 1e300, whose spacing is
    /// about 1e284 rad).
    #[error(
        "the integration cannot advance at t = {t}: a step changes state component {component} (= {value:e}) \
         by {change:e}, less than half the spacing of f64 numbers there ({:e}), so the change is lost; \
         start from a smaller value (an angle modulo a turn)",
        spacing(*.value)
    )]
    CannotAdvance {
        /// Time reached.
        t: f64,
        /// Index of the state component (for a simulation, 0 the input, 1 its speed).
        component: usize,
        /// The component's value.
        value: f64,
        /// The change the step computed for it.
        change: f64,
    },
    /// A state, vector or list of values of a run-time mass model
    /// ([`MassModelBuf`](super::MassModelBuf)) has another size than the model's.
    #[error("{given} {what} given, {expected} expected")]
    SizeMismatch {
        /// What was given.
        what: &'static str,
        /// The size expected.
        expected: usize,
        /// The size given.
        given: usize,
    },
    /// The integrator made its maximum number of steps (its budget,
    /// [`OdeConfig::max_steps`](super::OdeConfig::max_steps)) before the end time: the span
    /// asks for more steps than the budget allows at the step size the tolerances need.
    #[error(
        "the integration made its budget of {steps} steps and reached only t = {} of {}: simulate a \
         shorter span (on the command line, a smaller `--time`), or raise the budget \
         (`OdeConfig::max_steps`) or loosen the tolerances",
        Number(*.t),
        Number(*.t_end)
    )]
    TooManySteps {
        /// Steps made.
        steps: usize,
        /// Time reached.
        t: f64,
        /// The end time asked for.
        t_end: f64,
    },
}

impl From<DynamicsError> for Error {
    fn from(e: DynamicsError) -> Error {
        match e {
            DynamicsError::Kinematics { source, .. } => source,
            other => Error::Dynamics(crate::error::Source::new(other)),
        }
    }
}

/// `" at t = .."` for a time, nothing outside a simulation.
fn at_time(t: Option<f64>) -> String {
    t.map_or_else(String::new, |t| format!(" at t = {t}"))
}

/// `" at input [..]"`, or nothing for a result independent of the inputs.
fn at_input(x: &[f64]) -> String {
    if x.is_empty() { String::new() } else { format!(" at input {x:?}") }
}

/// The spacing of `f64` numbers at `v` (one unit in the last place).
pub(crate) fn spacing(v: f64) -> f64 {
    let a = v.abs();
    if !a.is_finite() {
        return f64::NAN;
    }
    if a == f64::MAX { a - f64::from_bits(a.to_bits() - 1) } else { f64::from_bits(a.to_bits() + 1) - a }
}

impl DynamicsError {
    /// A kinematic failure outside a simulation.
    pub(crate) fn kin(source: Error) -> Self {
        DynamicsError::Kinematics { t: None, source }
    }
}
