//! Errors of synthesis: a problem that is not well posed (a variable that is no parameter,
//! bounds that hold no value, targets that are missing or not finite, fewer equations than
//! unknowns) is refused when it is built, with a message that names what is wrong.

use crate::error::Error;
use crate::number::{Count, Number};
use std::borrow::Cow;

/// What is wrong with a synthesis problem or its search: a problem that is not well posed is
/// refused when it is built, with a message that names what is wrong.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SynthesisError {
    /// A design variable is not a parameter of the mechanism.
    #[error("`{name}` is no parameter of `{mechanism}`: its parameters are {params}")]
    UnknownVariable {
        /// The name given.
        name: String,
        /// The mechanism's name (a compiled mechanism's type name).
        mechanism: Cow<'static, str>,
        /// Its parameters, comma-separated.
        params: String,
    },
    /// A parameter is named twice among the design variables (or the link-ratio constraint).
    #[error("the parameter `{name}` is named twice")]
    DuplicateVariable {
        /// The parameter.
        name: String,
    },
    /// A variable's (or the timing's, or the placement's) bounds hold no value: not finite, or
    /// the lower above the upper.
    #[error(
        "the bounds of `{name}` are [{}, {}]: they must be finite with lo <= hi, at most the largest double \
         (1.7976931348623157e308) apart",
        Number(*.lo),
        Number(*.hi)
    )]
    BadBounds {
        /// The variable.
        name: String,
        /// Lower bound.
        lo: f64,
        /// Upper bound.
        hi: f64,
    },
    /// A task or constraint names a column that is no unknown or output of the mechanism.
    #[error("`{name}` is no unknown or output column of `{mechanism}`: {columns}")]
    UnknownColumn {
        /// The name given.
        name: String,
        /// The mechanism's name (a compiled mechanism's type name).
        mechanism: Cow<'static, str>,
        /// Its unknowns and outputs, comma-separated.
        columns: String,
    },
    /// No design variable was named.
    #[error("no design variable: name at least one parameter to vary")]
    NoVariables,
    /// The task has no target.
    #[error("the task has no target")]
    NoTargets,
    /// A target value, prescribed input or weight is NaN or infinite.
    #[error("{what} of target {target} is not finite ({value})")]
    NonFinite {
        /// What the value is (`"a value"`, `"the input"`, `"a weight"`).
        what: &'static str,
        /// The target's index.
        target: usize,
        /// The value.
        value: f64,
    },
    /// The targets give fewer scalar equations than there are unknowns (design variables, free
    /// input values, placement): the solution is not determined.
    #[error(
        "{} from the targets for {} (design variables, free inputs, placement): give at least {}, \
         fewer variables, or accept a family of designs with `Design::underdetermined()`",
        Count(*residuals, "equation"),
        Count(*variables, "unknown"),
        Count(*variables, "target value")
    )]
    TooFewTargets {
        /// Scalar equations (target components).
        residuals: usize,
        /// Unknowns of the search.
        variables: usize,
    },
    /// The targets and the values attached to them do not match in number or size.
    #[error("{0}")]
    Mismatch(String),
    /// The task needs something the mechanism does not have (free timing, or full rotation, of
    /// a mechanism with several inputs).
    #[error("{0}")]
    Unsupported(String),
    /// A configuration value is out of its range (the message names the field).
    #[error("invalid configuration: {0}")]
    InvalidConfig(String),
    /// A design variable is named as a column of its own of the report's table
    /// ([`SynthesisReport::table`](super::SynthesisReport::table)): the table would name two
    /// columns alike.
    #[error(
        "the design variable `{name}` is named as a column of the report's table of its own: the table would \
         name two columns `{name}`; rename the parameter to tabulate the report"
    )]
    ReportColumn {
        /// The variable.
        name: String,
    },
    /// A kinematic analysis failed where the problem needs it to succeed.
    #[error("kinematics failed: {0}")]
    Kinematics(#[from] Error),
}
