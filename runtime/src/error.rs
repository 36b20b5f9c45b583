//! Typed errors. Every failure carries where it happened (a [`Location`]): the mechanism, the
//! input values, and (for solver failures) the block of the decomposition with its unknowns and
//! equations.

use crate::events::EventKind;
use crate::number::{Count, Number};
use std::borrow::Cow;
use std::fmt;

use crate::events::Location;

mod computed;
pub use computed::Computed;

/// What kind of value was not finite.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Quantity {
    /// A design parameter.
    Parameter,
    /// An input (generalized coordinate).
    Input,
    /// An initial guess of an unknown.
    Guess,
    /// An input speed or acceleration given to `motion`.
    Motion,
    /// A sweep's range or step.
    Range,
    /// An unknown of a position given to `kinematics_at` (not solved: the caller's).
    Position,
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Quantity::Parameter => "parameter",
            Quantity::Input => "input",
            Quantity::Guess => "initial guess of",
            Quantity::Motion => "input speed or acceleration",
            Quantity::Range => "sweep range value",
            Quantity::Position => "given position of",
        })
    }
}

/// Errors of kinloop's solvers and analyses. Never a panic, never a silent NaN.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter, input, guess or given position is NaN or infinite.
    #[error("{what} `{name}` is not finite ({value}) {at}")]
    NonFinite {
        /// Which kind of value.
        what: Quantity,
        /// Its declared name.
        name: Cow<'static, str>,
        /// The value given.
        value: f64,
        /// Where.
        at: Box<Location>,
    },
    /// Newton's method reached its iteration limit.
    #[error(
        "Newton's method did not converge in {} {at}: residual {residual:e} in equation `{equation}`; give a \
         closer initial guess or raise `max_iterations`",
        Count(*iterations as usize, "iteration")
    )]
    NoConvergence {
        /// Iterations performed.
        iterations: u32,
        /// Largest scaled residual at the end.
        residual: f64,
        /// The equation with the largest residual.
        equation: Cow<'static, str>,
        /// Where.
        at: Box<Location>,
    },
    /// The loops cannot close: the residual stalls at a non-zero minimum where the Jacobian
    /// degenerates (links fully stretched or folded). Typical of link lengths that cannot
    /// assemble at this input.
    #[error(
        "the mechanism cannot be assembled {at}: the loop residual stalls at {residual:e} of the \
         equation's terms in equation `{equation}` (the links cannot reach; check the lengths or the \
         input range)"
    )]
    NoAssembly {
        /// The residual where it stalled, relative to the magnitude of the equation's terms
        /// (Newton's); for a closed form, the least residual of its equation relative to the
        /// magnitude of its terms (a slider-crank's rod angle: the sum of the lengths in its
        /// projection), a dyad's the gap of its links over the sum of its lengths.
        /// A pure number: the same for the mechanism at every size.
        residual: f64,
        /// The equation with the largest residual.
        equation: Cow<'static, str>,
        /// Where.
        at: Box<Location>,
    },
    /// The Jacobian of a block is singular or too ill-conditioned at the solved position: a dead
    /// centre, a limit position of the input, or a change point. Velocity analogs do not exist.
    #[error("singular position {at}: {}; this is a dead centre or a limit position", singular_cause(*pivot_ratio, *tolerance))]
    Singular {
        /// Smallest equilibrated pivot ratio of the block's Jacobian where the solve ended (see
        /// `NewtonConfig::singular_tol`).
        pivot_ratio: f64,
        /// The singular tolerance (`NewtonConfig::singular_tol`). The pivot ratio is below it,
        /// or Newton reached the position only linearly, as at a root where the Jacobian is
        /// singular (its pivot ratio then shrinks with every step, not yet below the tolerance).
        tolerance: f64,
        /// Where.
        at: Box<Location>,
    },
    /// An expression evaluated to NaN or infinity although every parameter and input is finite:
    /// it left its domain (square root of a negative number, `asin` beyond ±1, division by zero,
    /// the derivative of `norm` or `atan2` at a zero vector)
    /// or its result left the range of `f64` (`exp` of an argument above 709.78, a product
    /// beyond 1.8e308): the value alone, NaN or infinite, does not tell which.
    #[error(
        "the {what} `{name}` is not finite {at}: an expression left its domain or the range of \
         f64 (e.g. sqrt of a negative number, asin/acos beyond ±1, a division by zero, the rate of a \
         norm or of a vector's angle where the vector is zero, or exp of an argument above 709.78)"
    )]
    Domain {
        /// Which kind of value: an equation, a position, an analog, an output, ...
        what: Computed,
        /// Name of the equation, unknown or output column.
        name: Cow<'static, str>,
        /// Where.
        at: Box<Location>,
    },
    /// An equation's terms are too small for `f64`: the magnitude its residual is judged in
    /// (the size of its terms, see `NewtonConfig::residual_tol`) is below `least`, or
    /// underflowed to zero where its terms do not vanish. Below `2^-1022` doubles are
    /// subnormal, `2^-1074` (4.9e-324) apart whatever their size, so a residual there is known
    /// no finer than `4.9e-324 / magnitude` of its magnitude; below `least` that is coarser
    /// than the residual tolerance (at least 16 eps), and a root judged there could be off by
    /// far more than the tolerance says; or, where the equation's derivatives are subnormal too
    /// (a mechanism whose lengths are below about `1e-308`), neither has a finite reciprocal
    /// to judge it in. Typical of an equation of squared lengths (a rod length written
    /// `(x - a)^2 + ... == l^2`) with lengths below about `1e-156`, and of any mechanism whose
    /// lengths are subnormal: the mechanism in a smaller unit (larger numbers) solves.
    #[error(
        "the terms of the equation `{equation}` are too small to be evaluated in f64 {at}: {}, where doubles \
         are 4.9e-324 apart, too coarse to judge its residual to the tolerance; give the lengths in a smaller \
         unit (larger numbers)",
        underflow_cause(*magnitude, *least)
    )]
    Underflow {
        /// The equation.
        equation: Cow<'static, str>,
        /// Its magnitude where the solve ended (`0` where it underflowed to zero).
        magnitude: f64,
        /// The smallest magnitude a residual can be judged in with the configuration's
        /// residual tolerance, `2^-1074 / max(residual_tol, 16 eps)` (`4.9e-312` by default);
        /// or `2^-1024` (`5.6e-309`), where a magnitude's reciprocal overflows, for an equation
        /// whose derivatives are as small (its lengths subnormal): it can be equilibrated by
        /// neither.
        least: f64,
        /// Where.
        at: Box<Location>,
    },
    /// A result overflowed although every value given was finite: accelerations for input
    /// speeds near the largest `f64`, or (`what` is [`Computed::Equation`]) the terms of an equation, too
    /// large to be evaluated in `f64`, the counterpart of [`Error::Underflow`]. An equation's
    /// magnitude (the size of its terms, see `NewtonConfig::residual_tol`) overflowed to
    /// infinity, so its residual cannot be judged relative to it; where the residual overflowed
    /// too (squared lengths each beyond `f64::MAX`, whose difference is `inf - inf`), the terms
    /// in its unknowns do (an unknown times its derivative), which tells it from an expression
    /// outside its domain ([`Error::Domain`]). Typical of an equation of squared lengths (a rod
    /// length written `(x - a)^2 + ... == l^2`) with lengths beyond about `1e153`: the
    /// mechanism in a larger unit (smaller numbers) solves.
    #[error("the {what} `{name}` overflows {at}: {}", overflow_cause(*what))]
    Overflow {
        /// [`Computed::Equation`], or a true motion: [`Computed::Velocity`],
        /// [`Computed::Acceleration`], [`Computed::OutputVelocity`] or
        /// [`Computed::OutputAcceleration`].
        what: Computed,
        /// Name of the equation, unknown or output column.
        name: Cow<'static, str>,
        /// Where.
        at: Box<Location>,
    },
    /// A sweep stopped at a singular position it cannot (or is configured not to) pass on its
    /// branch: a limit position of the input, or a singular crossing. The event, with the
    /// located input value, is in the sweep's `events()`. The message says what goes on from
    /// there: `trace_curve` past a limit position, and past a crossing `AtSingular::Continue`,
    /// `trace_curve`, or a lower `SweepConfig::singular_pivot` where two assembly modes only
    /// pass close.
    #[error("the sweep stopped at a {kind} {at}{}", stopped_advice(*kind))]
    SweepStopped {
        /// What was met.
        kind: EventKind,
        /// Where (the located input value).
        at: Box<Location>,
    },
    /// A sweep starts at a singular position (its first sample's smallest pivot ratio below
    /// `SweepConfig::singular_pivot`, or below `NewtonConfig::singular_tol`, where the first
    /// state does not solve: the point solve's [`Error::Singular`]; or within a hundred times
    /// `singular_pivot` where no first step however small is accepted: a hair inside a limit
    /// position, nearer it than the sweep's smallest step): a limit position (the end
    /// of a reachable range, where a sweep that stopped there put it) or a change point, where
    /// the input alone does not say which branch leads on. Start inside the range, or trace the
    /// curve from there (`trace_curve` starts at a limit position).
    #[error(
        "the sweep starts at a singular position ({}): a limit position or a change point, where the input \
         alone does not say which branch leads on and the analogs are the rounding's; start the sweep inside the \
         range (a reachable range ends at limit positions), or trace the curve from it (`trace_curve`) {at}",
        start_cause(*pivot_ratio, *singular_pivot)
    )]
    SingularStart {
        /// The first sample's smallest pivot ratio ([`Health::min_pivot`](crate::Health), of the
        /// analogs' factorisations); where the first state's point solve finds it singular, that
        /// of the analogs at its positions solved alone (0 where those are not determined
        /// either), not the point solve's own measure.
        pivot_ratio: f64,
        /// The configured `SweepConfig::singular_pivot`.
        singular_pivot: f64,
        /// Where (the sweep's start).
        at: Box<Location>,
    },
    /// A sweep's steps pass so near a singular position (a pivot ratio below
    /// `SweepConfig::singular_pivot`) that the residual tolerance no longer pins the branch, and
    /// no limit position or crossing is found there. A mechanism meant to pass this close (a
    /// slide brushing its pivot) sweeps with a lower `singular_pivot`.
    #[error(
        "the sweep passes within a pivot ratio of {pivot_ratio:.2e} of a singular position, below \
         `SweepConfig::singular_pivot` ({singular_pivot:e}), where the residual tolerance no longer pins the branch, \
         and finds no limit position or crossing there; if the mechanism is meant to pass this close (e.g. a \
         slide brushing its pivot), lower `singular_pivot` {at}"
    )]
    NearSingular {
        /// The smallest pivot ratio of the step that failed.
        pivot_ratio: f64,
        /// The configured `SweepConfig::singular_pivot`.
        singular_pivot: f64,
        /// Where.
        at: Box<Location>,
    },
    /// A sweep could not stay on its assembly branch (see the sweep's events).
    #[error("{message} {at}")]
    Branch {
        /// What went wrong.
        message: String,
        /// Where.
        at: Box<Location>,
    },
    /// A sweep's or a trace's steps cannot be taken where an input's doubles are farther apart
    /// than a millionth of the steps' change in it (an input near `1e17` is a double 16 apart):
    /// the steps' inputs round away from where they are predicted. The arguments' fault (a range
    /// far out, or too finely sampled for where it is), not the mechanism's.
    #[error(
        "the {walk} cannot take its steps: input `{name}` is a double {} apart from the next here, coarser than \
         a millionth of {} in it ({}), so the steps' inputs round away from where they are predicted; reduce a \
         periodic input by whole turns, or {} {at}",
        Number(*.apart),
        if *.walk == "sweep" { "the samples' spacing" } else { "a step's length" },
        Number(*.step),
        if *.walk == "sweep" { "sample a longer range" } else { "take longer steps" }
    )]
    InputTooCoarse {
        /// What walks the path: `"sweep"` or `"trace"`.
        walk: &'static str,
        /// The input's index among the mechanism's inputs.
        input: usize,
        /// The input's name.
        name: String,
        /// The distance from its value to the next double, in its unit.
        apart: f64,
        /// Its change over a sample spacing (a sweep) or a step (a trace), in its unit.
        step: f64,
        /// Where.
        at: Box<Location>,
    },
    /// An angle's guess is so many turns out that on its turn the angle cannot be solved to the
    /// tolerance: the spacing of doubles there (about `|value| * 2.2e-16`) is coarser than the
    /// residual tolerance accepts. Solved on its guess's turn (as every angle is), it would be a
    /// wrong answer by that much. Typical of an angle carried over millions of turns; reduce it
    /// by whole turns.
    #[error(
        "the angle `{name}` is {value:e} rad, {} turns out, where doubles are \
         {spacing:e} rad apart: too coarse for the residual tolerance {at}; give its guess on a \
         nearer turn (whole turns off, e.g. `q.rem_euclid(TAU)`)",
        whole_turns(*turns)
    )]
    TooManyTurns {
        /// The unknown.
        name: Cow<'static, str>,
        /// Its guess (or the closed form's root on the guess's turn).
        value: f64,
        /// `value` in whole turns.
        turns: f64,
        /// The spacing of doubles at `value`.
        spacing: f64,
        /// Where.
        at: Box<Location>,
    },
    /// A sweep's or a trace's range is longer than a sweep follows: more than `max_turns` turns of its inputs
    /// (measured in the inputs' units: radians for an angle, the mechanism's size for a length).
    /// A sweep steps at most a fraction of a radian of its inputs at a time, whatever the number
    /// of samples asked for, so that no step passes a gap where the loops cannot close; a longer
    /// range would take more steps than a sweep makes, and far out the inputs' doubles are too
    /// coarse for such steps (see [`paths::sweep`](crate::paths::sweep), "Range", and
    /// [`MAX_TURNS`](crate::paths::sweep::MAX_TURNS)). Split the range, or reduce a periodic
    /// input by whole turns.
    #[error(
        "the range is {turns:e} turns of its inputs (a turn: 2 pi of their units, radians for an \
         angle), more than the {max_turns:e} turns a sweep or a trace follows {at}; split the range, \
         or reduce a periodic input by whole turns"
    )]
    RangeTooLong {
        /// The range's length in turns (`2 pi` input units).
        turns: f64,
        /// The most turns a sweep follows.
        max_turns: f64,
        /// Where (the start of the range).
        at: Box<Location>,
    },
    /// An argument outside its valid range (e.g. a sweep with zero samples).
    #[error("invalid argument: {0}")]
    InvalidArgument(String),
    /// A dynamic analysis failed for a reason of its own: the
    /// [`DynamicsError`](crate::dynamics::DynamicsError), kept whole (`e.downcast_ref()`). A
    /// kinematic failure inside a dynamic analysis is its own variant of this enum instead.
    #[error(transparent)]
    Dynamics(Source),
    /// A chart or a drawing could not be made: the error of `kinloop::plot` or `kinloop::draw`
    /// (`PlotError`, `DrawError`), kept whole (`e.downcast_ref()`).
    #[error(transparent)]
    Figure(Source),
}

/// What a configuration's `validate` returns: `Ok` when `field` (its first one out of range, as
/// its `invalid_field` finds it) is `None`, otherwise the `InvalidArgument` naming
/// `owner::field`, stating the field's valid range (`range`, in the words of its documentation)
/// and showing the whole configuration `cfg`, the field's value among the others. One wording
/// for every configuration of the solvers, sweeps and optimisers.
pub(crate) fn check_fields(
    owner: &str,
    field: Option<(impl fmt::Display, &str)>,
    cfg: &impl fmt::Debug,
) -> Result<(), Error> {
    match field {
        None => Ok(()),
        Some((field, range)) => {
            Err(Error::InvalidArgument(format!("{owner}::{field} is out of its valid range, {range}: {cfg:?}")))
        }
    }
}

/// An error of another part of kinloop carried inside [`Error`] (see [`Error::Dynamics`] and
/// [`Error::Figure`]), so that one error type goes through `?` everywhere. The original is kept:
/// [`Source::downcast_ref`] gives it back typed, and `std::error::Error::source` follows its
/// chain. Two are equal when their messages are.
#[derive(Clone, Debug)]
pub struct Source(std::sync::Arc<dyn std::error::Error + Send + Sync + 'static>);

impl Source {
    /// Wraps `e`.
    pub fn new(e: impl std::error::Error + Send + Sync + 'static) -> Self {
        Source(std::sync::Arc::new(e))
    }

    /// The original error, if it is a `T`.
    ///
    /// ```
    /// use kinloop_runtime::Error;
    /// use kinloop_runtime::dynamics::DynamicsError;
    /// let e = Error::from(DynamicsError::Overflow { what: "total mass", x: Vec::new(), names: Vec::new() });
    /// let Error::Dynamics(source) = &e else { panic!("{e:?}") };
    /// assert!(matches!(source.downcast_ref::<DynamicsError>(), Some(DynamicsError::Overflow { .. })));
    /// ```
    pub fn downcast_ref<T: std::error::Error + 'static>(&self) -> Option<&T> {
        self.0.downcast_ref::<T>()
    }
}

impl fmt::Display for Source {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

impl std::error::Error for Source {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.0.source()
    }
}

impl PartialEq for Source {
    fn eq(&self, other: &Self) -> bool {
        std::sync::Arc::ptr_eq(&self.0, &other.0) || self.0.to_string() == other.0.to_string()
    }
}

impl Error {
    /// The location carried by the error, if any.
    pub fn location(&self) -> Option<&Location> {
        match self {
            Error::NonFinite { at, .. }
            | Error::NoConvergence { at, .. }
            | Error::NoAssembly { at, .. }
            | Error::Singular { at, .. }
            | Error::Domain { at, .. }
            | Error::Overflow { at, .. }
            | Error::Underflow { at, .. }
            | Error::SweepStopped { at, .. }
            | Error::Branch { at, .. }
            | Error::SingularStart { at, .. }
            | Error::NearSingular { at, .. }
            | Error::InputTooCoarse { at, .. }
            | Error::TooManyTurns { at, .. }
            | Error::RangeTooLong { at, .. } => Some(at),
            Error::InvalidArgument(_) | Error::Dynamics(_) | Error::Figure(_) => None,
        }
    }

    /// The location carried by the error, to be changed: e.g. its inputs written in the units
    /// a program reads them in (a command line's degrees).
    pub fn location_mut(&mut self) -> Option<&mut Location> {
        match self {
            Error::NonFinite { at, .. }
            | Error::NoConvergence { at, .. }
            | Error::NoAssembly { at, .. }
            | Error::Singular { at, .. }
            | Error::Domain { at, .. }
            | Error::Overflow { at, .. }
            | Error::Underflow { at, .. }
            | Error::SweepStopped { at, .. }
            | Error::Branch { at, .. }
            | Error::SingularStart { at, .. }
            | Error::NearSingular { at, .. }
            | Error::InputTooCoarse { at, .. }
            | Error::TooManyTurns { at, .. }
            | Error::RangeTooLong { at, .. } => Some(at),
            Error::InvalidArgument(_) | Error::Dynamics(_) | Error::Figure(_) => None,
        }
    }
}

/// Why a result overflowed, by what it is: an equation's terms (see [`Error::Overflow`]), or a
/// state's velocities and accelerations.
fn overflow_cause(what: Computed) -> &'static str {
    if what == Computed::Equation {
        "its terms are too large to be evaluated in f64 (their magnitude is beyond 1.8e308, the largest \
         double, as squared lengths beyond about 1.3e154 are), so its residual cannot be judged; give the \
         lengths in a larger unit (smaller numbers)"
    } else {
        "the given speeds or accelerations are too large"
    }
}

/// The magnitude of an equation too small to be judged, as it is (a subnormal number, or zero
/// where it underflowed), against the least one judged.
fn underflow_cause(magnitude: f64, least: f64) -> String {
    if magnitude == 0.0 {
        format!("their magnitude underflows to zero (it must be at least {least:.2e})")
    } else {
        format!("their magnitude {magnitude:.2e} is below {least:.2e}")
    }
}

/// A count of turns in a message: whole, in digits up to 1e15 (`159154943` turns out), in `e`
/// notation beyond (`{turns:.0}` wrote a guess of 1e308 rad as 308 digits of turns).
fn whole_turns(turns: f64) -> String {
    if turns.abs() < 1e15 { format!("{turns:.0}") } else { format!("{turns:.3e}") }
}

/// What goes on from where a sweep stopped ([`Error::SweepStopped`]), in the library's names (the
/// command line names its own options and commands in notes under the message). The input turns
/// back at a limit position, so no sweep passes it and a trace does; at a crossing the sweep
/// cannot tell which branch the mechanism takes, so it goes on when told which (the smooth
/// continuation), and a trace keeps to its curve. A crossing met where two assembly modes only
/// pass nearer than the residual tolerance tells apart (a crank-rocker a hair from a change
/// point, see [`EventKind::SingularCrossing`]) is passed with a lower `singular_pivot`. A kink
/// stops no sweep; it has none.
fn stopped_advice(kind: EventKind) -> &'static str {
    match kind {
        EventKind::LimitPosition => {
            ": the input cannot go on past a limit position on this branch; `trace_curve` follows the curve \
             through it (the input turning back), and can start from it"
        }
        EventKind::SingularCrossing => {
            ": two branches of the motion cross there (a change point), and the input alone does not say which \
             one the mechanism follows on; `AtSingular::Continue` (`SweepConfig::with_at_singular`) goes on along \
             the smooth continuation, and `trace_curve` keeps to the curve it is on through it (where two assembly \
             modes only pass close, a mechanism meant to pass there sweeps with a lower \
             `SweepConfig::singular_pivot`)"
        }
        _ => "",
    }
}

/// Why a sweep's start is singular ([`Error::SingularStart`]): its pivot ratio below the sweep's
/// `singular_pivot`, or else the solve of its first state found it singular (below
/// `NewtonConfig::singular_tol`, or reached only linearly), whatever `singular_pivot` is (with
/// `singular_pivot` 0 the message said a ratio of 0 was "below" 0), or no first step was
/// accepted from it (a hair inside a limit position).
fn start_cause(pivot_ratio: f64, singular_pivot: f64) -> String {
    if pivot_ratio < singular_pivot {
        format!("a pivot ratio of {pivot_ratio:.2e}, below `SweepConfig::singular_pivot`, {singular_pivot:e}")
    } else {
        format!(
            "a pivot ratio of {pivot_ratio:.2e}, where the solve of its first state finds the Jacobian singular \
             (`NewtonConfig::singular_tol`), or no step however small leaves it on one branch (it lies within the \
             sweep's smallest step of a singular position)"
        )
    }
}

/// Why a position is singular, with the numbers as they are: a pivot ratio below the tolerance,
/// or a root that Newton reaches only linearly (each step about half the last, as where the
/// Jacobian is singular at the root) while the ratio has not yet fallen below the tolerance.
fn singular_cause(pivot_ratio: f64, tolerance: f64) -> String {
    if pivot_ratio < tolerance {
        format!("the Jacobian's pivot ratio is {pivot_ratio:e} (below the tolerance {tolerance:e})")
    } else {
        format!(
            "Newton reaches the position only linearly, as a root where the Jacobian is singular (its pivot \
             ratio falls with every step, {pivot_ratio:e} at the last, the tolerance being {tolerance:e})"
        )
    }
}
