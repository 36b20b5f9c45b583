//! Typed errors. Every failure carries where it happened (a [`Location`]): the mechanism, the
//! input values, and (for solver failures) the block of the decomposition with its unknowns and
//! equations.

use crate::events::EventKind;
use std::fmt;

use crate::events::Location;

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
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Quantity::Parameter => "parameter",
            Quantity::Input => "input",
            Quantity::Guess => "initial guess of",
            Quantity::Motion => "input speed or acceleration",
            Quantity::Range => "sweep range value",
        })
    }
}

/// Errors of kinloop's solvers and analyses. Never a panic, never a silent NaN.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter, input or guess is NaN or infinite.
    #[error("{what} `{name}` is not finite ({value}) {at}")]
    NonFinite {
        /// Which kind of value.
        what: Quantity,
        /// Its declared name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// Where.
        at: Box<Location>,
    },
    /// Newton's method reached its iteration limit.
    #[error(
        "Newton's method did not converge in {iterations} iterations {at}: residual {residual:e} \
         in equation `{equation}`; give a closer initial guess or raise `max_iterations`"
    )]
    NoConvergence {
        /// Iterations performed.
        iterations: u32,
        /// Largest scaled residual at the end.
        residual: f64,
        /// The equation with the largest residual.
        equation: &'static str,
        /// Where.
        at: Box<Location>,
    },
    /// The loops cannot close: the residual stalls at a non-zero minimum where the Jacobian
    /// degenerates (links fully stretched or folded). Typical of link lengths that cannot
    /// assemble at this input.
    #[error(
        "the mechanism cannot be assembled {at}: the loop residual stalls at {residual:e} in \
         equation `{equation}` (the links cannot reach; check the lengths or the input range)"
    )]
    NoAssembly {
        /// The scaled residual where it stalled.
        residual: f64,
        /// The equation with the largest residual.
        equation: &'static str,
        /// Where.
        at: Box<Location>,
    },
    /// The Jacobian of a block is singular or too ill-conditioned at the solved position: a dead
    /// centre, a limit position of the input, or a change point. Velocity analogs do not exist.
    #[error(
        "singular position {at}: the Jacobian's pivot ratio is {pivot_ratio:e} (below the \
         tolerance {tolerance:e}); this is a dead centre or a limit position"
    )]
    Singular {
        /// Smallest row-equilibrated pivot ratio of the block's Jacobian.
        pivot_ratio: f64,
        /// The tolerance it fell below (`NewtonConfig::singular_tol`).
        tolerance: f64,
        /// Where.
        at: Box<Location>,
    },
    /// An expression evaluated to NaN or infinity although every parameter and input is finite:
    /// it left its domain (square root of a negative number, `asin` beyond ±1, division by zero).
    #[error(
        "the {what} `{name}` is not finite {at}: an expression left its domain (e.g. sqrt of a \
         negative number, asin/acos beyond ±1, or a division by zero)"
    )]
    Domain {
        /// `"equation"`, `"position"`, `"velocity analog"`, `"output"`, ...
        what: &'static str,
        /// Name of the equation, unknown or output column.
        name: &'static str,
        /// Where.
        at: Box<Location>,
    },
    /// A result overflowed although every value given was finite (e.g. accelerations for input
    /// speeds near the largest `f64`).
    #[error("the {what} `{name}` overflows {at}: the given speeds or accelerations are too large")]
    Overflow {
        /// `"velocity"`, `"acceleration"`, `"output velocity"` or `"output acceleration"`.
        what: &'static str,
        /// Name of the unknown or output column.
        name: &'static str,
        /// Where.
        at: Box<Location>,
    },
    /// A sweep stopped at a singular position it cannot (or is configured not to) pass on its
    /// branch: a limit position of the input, or a singular crossing. The event, with the
    /// located input value, is in the sweep's `events()`.
    #[error("the sweep stopped at a {kind} {at}")]
    SweepStopped {
        /// What was met.
        kind: EventKind,
        /// Where (the located input value).
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
    /// An angle's guess is so many turns out that on its turn the angle cannot be solved to the
    /// tolerance: the spacing of doubles there (about `|value| * 2.2e-16`) is coarser than the
    /// residual tolerance accepts. Solved on its guess's turn (as every angle is), it would be a
    /// wrong answer by that much. Typical of an angle carried over millions of turns; reduce it
    /// by whole turns.
    #[error(
        "the angle `{name}` is {value:e} rad, {turns:.0} turns out, where doubles are \
         {spacing:e} rad apart: too coarse for the residual tolerance {at}; give its guess on a \
         nearer turn (whole turns off, e.g. `q.rem_euclid(TAU)`)"
    )]
    TooManyTurns {
        /// The unknown.
        name: &'static str,
        /// Its guess (or the closed form's root on the guess's turn).
        value: f64,
        /// `value` in whole turns.
        turns: f64,
        /// The spacing of doubles at `value`.
        spacing: f64,
        /// Where.
        at: Box<Location>,
    },
    /// A sweep's range is longer than a sweep follows: more than `max_turns` turns of its inputs
    /// (measured in the inputs' units: radians for an angle, the mechanism's size for a length).
    /// A sweep steps at most a fraction of a radian of its inputs at a time, whatever the number
    /// of samples asked for, so that no step passes a gap where the loops cannot close; a longer
    /// range would take more steps than a sweep makes, and far out the inputs' doubles are too
    /// coarse for such steps (see [`paths::sweep`](crate::paths::sweep), "Range", and
    /// [`MAX_TURNS`](crate::paths::sweep::MAX_TURNS)). Split the range, or reduce a periodic
    /// input by whole turns.
    #[error(
        "the sweep's range is {turns:e} turns of its inputs, more than the {max_turns:e} turns a \
         sweep follows {at}; split the range, or reduce a periodic input by whole turns"
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
            | Error::SweepStopped { at, .. }
            | Error::Branch { at, .. }
            | Error::TooManyTurns { at, .. }
            | Error::RangeTooLong { at, .. } => Some(at),
            Error::InvalidArgument(_) => None,
        }
    }
}
