//! The name-agnostic cores of a failed step's diagnosis: which value given by the caller is not
//! finite, and which angle was guessed too many turns out (which value of a state is not finite
//! is the state's own, `kin::first_non_finite_state`), and the error of a failed block at a
//! known location. A compiled mechanism names what they find by its constants; a mechanism read
//! at run time (`kinloop_model`) by the names it read, so that its errors are the compiled
//! ones.

use crate::error::{Computed, Error, Quantity};
use crate::events::Location;
use crate::kinds::QuantityKind;
use crate::solvers::closed::largest_precise_angle;
use crate::solvers::newton::{BlockFailure, NewtonConfig};
use std::borrow::Cow;

/// The first non-finite parameter, input or guess, in that order, as its kind, index and
/// value: a bad value given by the caller explains a failure better than the failure itself.
#[cold]
#[inline(never)]
pub fn first_bad_value(
    params: impl IntoIterator<Item = f64>,
    x: &[f64],
    guess: Option<&[f64]>,
) -> Option<(Quantity, usize, f64)> {
    let first = |values: &mut dyn Iterator<Item = f64>| values.enumerate().find(|(_, v)| !v.is_finite());
    first(&mut params.into_iter())
        .map(|(i, v)| (Quantity::Parameter, i, v))
        .or_else(|| first(&mut x.iter().copied()).map(|(i, v)| (Quantity::Input, i, v)))
        .or_else(|| guess.and_then(|g| first(&mut g.iter().copied())).map(|(i, v)| (Quantity::Guess, i, v)))
}

/// The angle of a block guessed too many turns out to be solved to the tolerance of `cfg`
/// (see [`Error::TooManyTurns`](crate::Error::TooManyTurns)) and its value, when that explains
/// the failure `fail`: a closed form's own finding (its root on the guess's turn; the angle
/// `None` when the block has none), or any failure but an invalid configuration, an underflow
/// or an overflow from such a guess (Newton's residual stalls at the angle's rounding; a
/// closed form's sum of its guesses may overflow). `unknowns` are the block's, `kinds` and `guess` all
/// the mechanism's; the angle is the block's with the largest guess.
pub fn turns_culprit(
    unknowns: impl IntoIterator<Item = usize>,
    kinds: &[QuantityKind],
    fail: BlockFailure,
    guess: &[f64],
    cfg: &NewtonConfig,
) -> Option<(Option<usize>, f64)> {
    let largest = unknowns
        .into_iter()
        .filter(|&u| kinds[u] == QuantityKind::Angle)
        .max_by(|&a, &b| guess[a].abs().total_cmp(&guess[b].abs()));
    match (fail, largest) {
        (BlockFailure::TooManyTurns { value }, u) => Some((u, value)),
        // An equation too small or too large for `f64` explains a failure whatever the guesses.
        // A value not finite does not: the closed forms' check of their guesses' sum finds finite
        // guesses "not finite" where the sum overflows, which takes an angle's guess of about
        // `1e292` rad or more (a length's is at most `f64::MAX`), far beyond the bound.
        // Nor do lengths that are all zero.
        (
            BlockFailure::InvalidConfig { .. }
            | BlockFailure::Underflow { .. }
            | BlockFailure::Overflow { .. }
            | BlockFailure::Vanished { .. },
            _,
        ) => None,
        (_, Some(u)) if guess[u].abs() > largest_precise_angle(cfg) => Some((Some(u), guess[u])),
        _ => None,
    }
}

/// Builds the error for a failed block at a known location: equations the location's block
/// does not name are `?`. Public for a mechanism read at run time (`kinloop_model`), whose
/// failed steps must be the compiled mechanism's variants.
#[doc(hidden)]
#[cold]
#[inline(never)]
pub fn block_error(fail: BlockFailure, at: Location) -> Error {
    let equations = at.block.as_ref().map_or(&[][..], |(_, info)| &info.equations);
    let name = |row: usize| equations.get(row).cloned().unwrap_or(Cow::Borrowed("?"));
    match fail {
        BlockFailure::NonFinite { row, .. } => {
            Error::Domain { what: Computed::Equation, name: name(row), at: Box::new(at) }
        }
        BlockFailure::NoConvergence { row, iterations, residual } => {
            Error::NoConvergence { iterations, residual, equation: name(row), at: Box::new(at) }
        }
        BlockFailure::NoAssembly { row, residual, .. } => {
            Error::NoAssembly { residual, equation: name(row), at: Box::new(at) }
        }
        BlockFailure::Singular { pivot_ratio, tolerance, .. } => {
            Error::Singular { pivot_ratio, tolerance, at: Box::new(at) }
        }
        BlockFailure::InvalidConfig { field } => Error::InvalidArgument(format!(
            "NewtonConfig::{field} is out of its valid range, {}, {at}",
            NewtonConfig::valid_range(field)
        )),
        BlockFailure::Underflow { row, magnitude, least } => {
            Error::Underflow { equation: name(row), magnitude, least, at: Box::new(at) }
        }
        BlockFailure::Overflow { row } => {
            Error::Overflow { what: Computed::Equation, name: name(row), at: Box::new(at) }
        }
        BlockFailure::Vanished { row } => vanished_error(&name(row), &at),
        // Named by `block_failure` (`mechanism`), which knows the guesses.
        BlockFailure::TooManyTurns { value } => turns_error(Cow::Borrowed("?"), value, at),
    }
}

/// The error of a block whose equation `equation` vanishes at every position
/// ([`BlockFailure::Vanished`]): the parameters given are the fault, not the position, so an
/// [`Error::InvalidArgument`] naming the loop (the equation `abcd.x` is a projection of the loop
/// `abcd`) or the equation, where it is, and what to write instead. It was the block's singular
/// position ("a dead centre or a limit position"). A projection of a loop vanishes where every
/// link of the loop has length zero (each contributes its length to the magnitude of both
/// projections) and so does every offset along it: the loop's lengths all zero, or its links
/// all zero beside an offset across (`(0, e)`), which the message does not call zero.
fn vanished_error(equation: &str, at: &Location) -> Error {
    let what = match equation.strip_suffix(".x").or_else(|| equation.strip_suffix(".y")) {
        Some(name) => format!(
            "the links of loop `{name}` all have length zero {at}: its equation `{equation}` holds at every position \
             (each of its terms is zero), so no position of the loop is determined; give the loop's lengths their \
             values (a parameter left at 0 is one not set)"
        ),
        None => format!(
            "every term of equation `{equation}` is zero {at}: it holds at every position, so it determines none; \
             give the lengths in it their values (a parameter left at 0 is one not set), or, where they are below \
             about 1e-162 and their products underflow to zero, give them in a smaller unit (larger numbers)"
        ),
    };
    Error::InvalidArgument(what)
}

/// [`Error::TooManyTurns`] of the angle `name` at `value`. Public for a mechanism read at run
/// time (`kinloop_model`), which names the angle [`turns_culprit`] finds.
#[cold]
#[inline(never)]
pub fn turns_error(name: Cow<'static, str>, value: f64, at: Location) -> Error {
    // The distance to the next double away from zero.
    let spacing = f64::from_bits(value.abs().to_bits() + 1) - value.abs();
    Error::TooManyTurns { name, value, turns: value / core::f64::consts::TAU, spacing, at: Box::new(at) }
}

/// The error of the angle parameter `name` of `mechanism` at `value`, beyond `bound` (the
/// configuration's `largest_precise_angle`): an angle added to it is lost to rounding, so the
/// equations are not the declared ones. Public for a mechanism read at run time
/// (`kinloop_model`), whose error must be the compiled one.
#[cold]
#[inline(never)]
pub fn imprecise_param(mechanism: &str, name: &str, value: f64, bound: f64) -> Error {
    // The distance to the next double away from zero: what an angle added to it is rounded to.
    let spacing = f64::from_bits(value.abs().to_bits() + 1) - value.abs();
    Error::InvalidArgument(format!(
        "parameter `{name}` of `{mechanism}` is an angle of {value:e} rad, beyond {bound:e} rad, the \
         largest angle solved to the residual tolerance: doubles there are {spacing:e} rad apart, so an \
         angle added to it is rounded to that spacing (lost where the spacing passes a turn) and the \
         equations are not the declared ones; reduce it by whole turns (e.g. `{name}.rem_euclid(TAU)`, TAU = 2 pi)"
    ))
}
