//! Errors of the classical closed forms: input they cannot use, and problems whose answer does
//! not exist or is not a linkage. Each converts into [`crate::Error`] (as
//! [`Error::InvalidArgument`] with the same message), so `?`
//! works in code that returns kinloop's error.

use crate::error::Error;

/// Why a classical synthesis gave no answer; see the [module documentation](super).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ClassicalError {
    /// A value given is NaN or infinite.
    #[error("{what} is not finite ({value})")]
    NonFinite {
        /// Which value, e.g. `"the input angle of precision point 2"`.
        what: String,
        /// The value given.
        value: f64,
    },
    /// Fewer precision points or poses than the method needs (or more than it takes).
    #[error("{method} takes {needed} {what}, got {given}")]
    Count {
        /// The method, e.g. `"Freudenstein's equation"`.
        method: &'static str,
        /// What is counted, e.g. `"precision points"`.
        what: &'static str,
        /// How many it takes, e.g. `"at least 3"`.
        needed: &'static str,
        /// How many were given.
        given: usize,
    },
    /// Two precision points or poses are the same (to rounding), so they carry one condition
    /// where the method needs two.
    #[error("{what} {first} and {second} coincide: give distinct ones")]
    Coincident {
        /// `"precision points"` or `"poses"`.
        what: &'static str,
        /// Index of the first (from 0).
        first: usize,
        /// Index of the second.
        second: usize,
    },
    /// The linear system of the method is singular (or too ill-conditioned to trust): the
    /// points or poses do not determine an answer.
    #[error(
        "the {what} is singular: its reciprocal condition number is {rcond:e}, below {tolerance:e}; \
         spread the precision points or poses further apart"
    )]
    Singular {
        /// Which system, e.g. `"Freudenstein system"`.
        what: &'static str,
        /// Smallest over largest singular value of the (column-scaled) system.
        rcond: f64,
        /// The smallest accepted.
        tolerance: f64,
    },
    /// The answer is not a linkage: a link length comes out negative, zero or imaginary.
    #[error("the {link} length comes out {value} (relative to the ground): {hint}")]
    BadLength {
        /// `"input"`, `"coupler"` or `"output"`.
        link: &'static str,
        /// The length found (the square of the length for the coupler when it is imaginary).
        value: f64,
        /// What to change.
        hint: &'static str,
    },
    /// A range or a count given to a helper is unusable (empty, inverted or zero).
    #[error("invalid {what}: {why}")]
    BadRange {
        /// Which argument.
        what: &'static str,
        /// What is wrong with it.
        why: String,
    },
    /// The poses or precision points are a special case the general formulas do not cover (or
    /// the result is not a linkage they can describe).
    #[error("degenerate input: {0}")]
    Degenerate(String),
}

impl From<ClassicalError> for Error {
    fn from(e: ClassicalError) -> Error {
        Error::InvalidArgument(e.to_string())
    }
}

/// `Ok(value)` when finite, else [`ClassicalError::NonFinite`] naming it (`what` is built only
/// on failure).
pub(crate) fn finite(value: f64, what: impl FnOnce() -> String) -> Result<f64, ClassicalError> {
    if value.is_finite() { Ok(value) } else { Err(ClassicalError::NonFinite { what: what(), value }) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The conversion keeps the message, so a caller using kinloop's error loses nothing but the
    /// variant.
    #[test]
    fn converts_into_kinloop_error_with_its_message() {
        let e = ClassicalError::Coincident { what: "poses", first: 1, second: 3 };
        let message = e.to_string();
        assert_eq!(Error::from(e), Error::InvalidArgument(message));
    }

    #[test]
    fn finite_names_the_value_only_when_not_finite() {
        assert_eq!(finite(1.5, || unreachable!()), Ok(1.5));
        let e = finite(f64::NAN, || "x".into()).unwrap_err();
        assert!(matches!(e, ClassicalError::NonFinite { ref what, .. } if what == "x"), "{e:?}");
    }
}
