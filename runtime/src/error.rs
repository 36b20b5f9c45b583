//! Typed errors. Every failure carries where it happened: the mechanism, the input values, and
//! (for solver failures) the block of the decomposition with its unknowns and equations.

use std::fmt;

/// Static description of one block of a mechanism's block-triangular decomposition.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BlockInfo {
    /// Unknowns solved in this block (declaration order).
    pub unknowns: &'static [&'static str],
    /// Scalar equations of this block (`loop.x`, `loop.y` or an `eq` name).
    pub equations: &'static [&'static str],
    /// The block's unknowns appear linearly: it is solved in closed form, without iteration.
    pub linear: bool,
}

/// Where an error happened.
#[derive(Clone, Debug, PartialEq)]
pub struct Location {
    /// Name of the mechanism type.
    pub mechanism: &'static str,
    /// Values of the inputs (generalized coordinates) when it happened.
    pub inputs: Vec<(&'static str, f64)>,
    /// The block being solved, with its index in solve order, if the error concerns one.
    pub block: Option<(usize, BlockInfo)>,
}

impl Location {
    /// A boxed location of mechanism `mechanism` at the inputs `names = x` (for errors raised
    /// by generic code: sweeps, continuation).
    pub(crate) fn boxed(
        mechanism: &'static str,
        names: &[&'static str],
        x: &[f64],
        block: Option<(usize, BlockInfo)>,
    ) -> Box<Location> {
        Box::new(Location { mechanism, inputs: names.iter().copied().zip(x.iter().copied()).collect(), block })
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "in `{}`", self.mechanism)?;
        if !self.inputs.is_empty() {
            write!(f, " at ")?;
            for (k, (name, value)) in self.inputs.iter().enumerate() {
                if k > 0 {
                    write!(f, ", ")?;
                }
                write!(f, "{name} = {value}")?;
            }
        }
        if let Some((index, info)) = &self.block {
            write!(
                f,
                " (block {index}: unknowns {}; equations {})",
                info.unknowns.join(", "),
                info.equations.join(", ")
            )?;
        }
        Ok(())
    }
}

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
    NonFinite { what: Quantity, name: &'static str, value: f64, at: Box<Location> },
    /// Newton's method reached its iteration limit.
    #[error(
        "Newton's method did not converge in {iterations} iterations {at}: residual {residual:e} \
         in equation `{equation}`; give a closer initial guess or raise `max_iterations`"
    )]
    NoConvergence { iterations: u32, residual: f64, equation: &'static str, at: Box<Location> },
    /// The loops cannot close: the residual stalls at a non-zero minimum where the Jacobian
    /// degenerates (links fully stretched or folded). Typical of link lengths that cannot
    /// assemble at this input.
    #[error(
        "the mechanism cannot be assembled {at}: the loop residual stalls at {residual:e} in \
         equation `{equation}` (the links cannot reach; check the lengths or the input range)"
    )]
    NoAssembly { residual: f64, equation: &'static str, at: Box<Location> },
    /// The Jacobian of a block is singular or too ill-conditioned at the solved position: a dead
    /// centre, a limit position of the input, or a change point. Velocity analogs do not exist.
    #[error(
        "singular position {at}: the Jacobian's pivot ratio is {pivot_ratio:e} (below the \
         tolerance {tolerance:e}); this is a dead centre or a limit position"
    )]
    Singular { pivot_ratio: f64, tolerance: f64, at: Box<Location> },
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
        at: Box<Location>,
    },
    /// A sweep stopped at a singular position it cannot (or is configured not to) pass on its
    /// branch: a limit position of the input, or a singular crossing. The event, with the
    /// located input value, is in the sweep's `events()`.
    #[error("the sweep stopped at a {kind} {at}")]
    SweepStopped { kind: crate::sweep::EventKind, at: Box<Location> },
    /// A sweep could not stay on its assembly branch (see the sweep's events).
    #[error("{message} {at}")]
    Branch { message: String, at: Box<Location> },
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
            | Error::SweepStopped { at, .. }
            | Error::Branch { at, .. } => Some(at),
            Error::InvalidArgument(_) => None,
        }
    }
}
