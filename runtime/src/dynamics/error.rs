//! Errors of the dynamics layer: a bad mass model, a load that is not finite, a mass matrix that
//! is not positive definite, a kinematic solve that fails on the way (limit or singular position),
//! and integrator failures. Each converts into [`crate::Error`].

use crate::error::Error;
use crate::kinds::QuantityKind;
use crate::number::{Count, Number};
use std::borrow::Cow;

/// What went wrong in a dynamic analysis; see the [module documentation](self).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DynamicsError {
    /// A mass or a moment of inertia is negative, NaN or infinite.
    #[error("the {quantity} of body `{body}` is {}: it must be finite and not negative", Number(*.value))]
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
    #[error("invalid {what}: {} ({why})", Number(*.value))]
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
    #[error("the load `{name}` is not finite ({value}){}", at_inputs(names, x))]
    NonFiniteLoad {
        /// The load's name (`"drive"` for a drive torque law).
        name: Cow<'static, str>,
        /// The value returned.
        value: f64,
        /// The inputs where it happened.
        x: Vec<f64>,
        /// The inputs' names, in the order of `x`; empty where the error does not know them
        /// (a mass model's evaluation sees values only; a simulation and an inverse cycle name
        /// them).
        names: Vec<Cow<'static, str>>,
    },
    /// The mass matrix (the reduced moment of inertia for one input) is not positive definite:
    /// the machine has no inertia in some direction of motion at this position.
    #[error(
        "the mass matrix is not positive definite{} (pivot {}); give the machine mass",
        at_inputs(names, x),
        Number(*.pivot)
    )]
    SingularMass {
        /// The inputs where it happened.
        x: Vec<f64>,
        /// The smallest pivot of its Cholesky factorisation.
        pivot: f64,
        /// The inputs' names, in the order of `x`; empty where the error does not know them
        /// (a mass model's evaluation sees values only; a simulation and an inverse cycle name
        /// them).
        names: Vec<Cow<'static, str>>,
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
    #[error("the integration step fell to {h:e} at t = {}: the motion is singular here", Number(*.t))]
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
        "the motion is singular{}, {} (t = {}): the integration step fell to {h:e}; is this a limit position?",
        at_inputs(names, x),
        speeds(speed),
        Number(*.t)
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
        /// The inputs' names, in the order of `x`; empty where the error does not know them
        /// (a mass model's evaluation sees values only; a simulation and an inverse cycle name
        /// them).
        names: Vec<Cow<'static, str>>,
    },
    /// A result of the dynamics is beyond the range of `f64` (masses, speeds or loads so large
    /// that a product or a sum of them overflows), though every input is finite.
    #[error(
        "the {what}{} {} beyond the range of f64: express the model in other units (larger units of mass, length \
         or time)",
        at_inputs(names, x),
        is_or_are(what)
    )]
    Overflow {
        /// Which result (`"total mass"`, `"input accelerations"`, `"driving torque"`, ...): a
        /// noun phrase whose last word is plural when it ends in a single `s`.
        what: &'static str,
        /// The inputs where it happened (empty when it does not depend on them).
        x: Vec<f64>,
        /// The inputs' names, in the order of `x`; empty where the error does not know them
        /// (a mass model's evaluation sees values only; a simulation and an inverse cycle name
        /// them).
        names: Vec<Cow<'static, str>>,
    },
    /// A Fourier series asked for more harmonics than its samples resolve: `n` samples of a
    /// period determine harmonics below `n / 2` only.
    #[error(
        "{} asked of {} per period: they resolve at most {} (fewer than half the samples); take fewer \
         harmonics or more samples",
        Count(*harmonics, "harmonic"),
        Count(*samples, "sample"),
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
        "the integration cannot advance at t = {}: a step changes state component {component} (= {value:e}) \
         by {change:e}, less than half the spacing of f64 numbers there ({:e}), so the change is lost; \
         start from a smaller value (an angle modulo a turn)",
        Number(*.t),
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
    /// A cycle, which turns its input through one full turn of `2 pi` radians, was asked of a
    /// mechanism whose input is known not to be an angle (a length: a piston's position, a
    /// slider's): its "turn" would be `2 pi` of the input's unit, another stretch of motion in
    /// each unit of length, and no period of the machine.
    #[error(
        "a cycle turns its input through a full turn (2 pi rad), but `{input}` is {}, not an angle: give the \
         machine a crank angle as its input, or simulate it over time (`Simulation`, `kinloop simulate`)",
        kind_name(*.kind)
    )]
    InputNotAngle {
        /// The input's name.
        input: Cow<'static, str>,
        /// What the input is ([`QuantityKind::Length`] or [`QuantityKind::Dimensionless`]).
        kind: QuantityKind,
    },
    /// The integrator made its maximum number of steps (its budget,
    /// [`OdeConfig::max_steps`](super::OdeConfig::max_steps)) before the end time: the span
    /// asks for more steps than the budget allows at the step size the tolerances need.
    #[error(
        "the integration made its budget of {} and reached only t = {} of {}: simulate a shorter span (on \
         the command line, a smaller `--time`), or raise the budget (`OdeConfig::max_steps`) or loosen the \
         tolerances",
        Count(*steps, "step"),
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

/// A kind of quantity as a noun phrase: `a length`, `a pure number`.
fn kind_name(kind: QuantityKind) -> &'static str {
    match kind {
        QuantityKind::Angle => "an angle",
        QuantityKind::Length => "a length",
        QuantityKind::Dimensionless => "a pure number",
        QuantityKind::Other => "a quantity of its own unit",
    }
}

/// `" at t = .."` for a time, nothing outside a simulation.
fn at_time(t: Option<f64>) -> String {
    t.map_or_else(String::new, |t| format!(" at t = {}", Number(t)))
}

/// Where the inputs were, as a person reads it: `" at phi = 0"`, `" at phi = 0, psi = 1.5"`
/// with their names; `" at input 0"`, `" at inputs 0, 1.5"` without (names of another count
/// than the values are none); nothing for a result independent of the inputs.
fn at_inputs(names: &[Cow<'static, str>], x: &[f64]) -> String {
    if x.is_empty() {
        String::new()
    } else if names.len() == x.len() {
        let named: Vec<String> = names.iter().zip(x).map(|(n, &v)| format!("{n} = {}", Number(v))).collect();
        format!(" at {}", named.join(", "))
    } else {
        format!(" at {} {}", if x.len() == 1 { "input" } else { "inputs" }, list(x))
    }
}

/// `"speed 150"`, `"speeds 150, 2.5"`.
fn speeds(speed: &[f64]) -> String {
    format!("{} {}", if speed.len() == 1 { "speed" } else { "speeds" }, list(speed))
}

/// The values, comma-separated, each as [`Number`] writes it.
fn list(values: &[f64]) -> String {
    values.iter().map(|&v| Number(v).to_string()).collect::<Vec<_>>().join(", ")
}

/// The verb that agrees with `what`, a noun phrase of this module's (`"total mass"`, `"input
/// accelerations"`, `"shaking force or moment"`): `are` when its last word ends in a single `s`
/// (a plural; with `or`, the nearer noun decides), `is` otherwise (`mass` ends in `ss`).
fn is_or_are(what: &str) -> &'static str {
    let last = what.rsplit(' ').next().unwrap_or(what);
    if last.ends_with('s') && !last.ends_with("ss") { "are" } else { "is" }
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

    /// The error with the names of the inputs it was raised at, for an error raised where only
    /// their values were known (a mass model's evaluation), passed up through code that knows
    /// the mechanism. Names already given, and names of another count than the values, are
    /// left as they are. Called on the way out of an error only: the names are copied then. A
    /// mechanism read at run time names its inputs with it as a compiled one does.
    ///
    /// ```
    /// use kinloop_runtime::dynamics::DynamicsError;
    /// let e = DynamicsError::NonFiniteLoad { name: "gas".into(), value: f64::NAN, x: vec![0.5], names: vec![] };
    /// assert_eq!(e.with_input_names(&["phi"]).to_string(), "the load `gas` is not finite (NaN) at phi = 0.5");
    /// ```
    pub fn with_input_names(mut self, input_names: &[&str]) -> Self {
        if let DynamicsError::NonFiniteLoad { x, names, .. }
        | DynamicsError::SingularMass { x, names, .. }
        | DynamicsError::SingularMotion { x, names, .. }
        | DynamicsError::Overflow { x, names, .. } = &mut self
            && names.is_empty()
            && input_names.len() == x.len()
        {
            *names = input_names.iter().map(|n| Cow::Owned(n.to_string())).collect();
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(n: &[&'static str]) -> Vec<Cow<'static, str>> {
        n.iter().map(|&n| Cow::Borrowed(n)).collect()
    }

    #[test]
    fn inputs_and_speeds_are_written_as_a_person_reads_them() {
        let motion = |x: Vec<f64>, speed: Vec<f64>, n: &[&'static str]| {
            DynamicsError::SingularMotion { t: 0.0, h: 1e-300, x, speed, names: names(n) }.to_string()
        };
        assert_eq!(
            motion(vec![0.0], vec![150.0], &["phi"]),
            "the motion is singular at phi = 0, speed 150 (t = 0): the integration step fell to 1e-300; is this a \
             limit position?"
        );
        assert!(
            motion(vec![0.0, 1.5], vec![150.0, -2.5], &["phi", "s"])
                .starts_with("the motion is singular at phi = 0, s = 1.5, speeds 150, -2.5 (t = 0)")
        );
        // Without names (or with names of another count): the values alone.
        assert!(motion(vec![0.25], vec![1e300], &[]).starts_with("the motion is singular at input 0.25, speed 1e300 "));
        assert!(
            motion(vec![0.25, 2.0], vec![1.0, 0.0], &["phi"])
                .starts_with("the motion is singular at inputs 0.25, 2, speeds 1, 0 ")
        );
        let load =
            DynamicsError::NonFiniteLoad { name: "gas".into(), value: f64::NAN, x: vec![0.5], names: names(&["phi"]) };
        assert_eq!(load.to_string(), "the load `gas` is not finite (NaN) at phi = 0.5");
        let mass = DynamicsError::SingularMass { x: vec![0.0, 1.5], pivot: -0.25, names: Vec::new() };
        assert_eq!(
            mass.to_string(),
            "the mass matrix is not positive definite at inputs 0, 1.5 (pivot -0.25); give the machine mass"
        );
        // No Rust debug text in any of them.
        for e in [load, mass] {
            assert!(!e.to_string().contains('['), "{e}");
        }
    }

    #[test]
    fn an_overflow_agrees_with_what_overflows() {
        let overflow = |what, x: Vec<f64>| DynamicsError::Overflow { what, x, names: names(&["phi"]) }.to_string();
        assert!(
            overflow("input accelerations", vec![0.0]).starts_with("the input accelerations at phi = 0 are beyond")
        );
        assert!(overflow("total mass", Vec::new()).starts_with("the total mass is beyond the range of f64:"));
        // Every quantity the dynamics names, with its verb.
        for (what, verb) in [
            ("total mass", "is"),
            ("input accelerations", "are"),
            ("driving force", "is"),
            ("generalised forces", "are"),
            ("mass matrix or velocity-product coefficients", "are"),
            ("shaking force or moment", "is"),
            ("Fourier coefficients", "are"),
            ("work of the loads over the cycle", "is"),
            ("exact flywheel inertia", "is"),
            ("flywheel sizing", "is"),
        ] {
            assert_eq!(is_or_are(what), verb, "{what}");
        }
    }

    #[test]
    fn names_are_added_where_the_values_were_known_alone() {
        let mass = || DynamicsError::SingularMass { x: vec![0.5], pivot: 0.0, names: Vec::new() };
        assert!(mass().with_input_names(&["phi"]).to_string().contains(" at phi = 0.5 "));
        // Names of another count, or names already there, stay as they are.
        assert!(mass().with_input_names(&["phi", "s"]).to_string().contains(" at input 0.5 "));
        let named = DynamicsError::SingularMass { x: vec![0.5], pivot: 0.0, names: names(&["theta"]) };
        assert!(named.with_input_names(&["phi"]).to_string().contains(" at theta = 0.5 "));
        // An error without inputs is unchanged.
        let total = DynamicsError::Overflow { what: "total mass", x: Vec::new(), names: Vec::new() };
        assert_eq!(total.clone().with_input_names(&["phi"]), total);
    }

    #[test]
    fn times_and_values_far_out_are_written_in_exponent_notation() {
        let bad = DynamicsError::BadValue { what: "end time", value: 1e300, why: "must be finite" };
        assert_eq!(bad.to_string(), "invalid end time: 1e300 (must be finite)");
        let step = DynamicsError::StepTooSmall { t: 1e20, h: 1e3 };
        assert_eq!(step.to_string(), "the integration step fell to 1e3 at t = 1e20: the motion is singular here");
    }
}
