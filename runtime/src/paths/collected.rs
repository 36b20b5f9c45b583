//! The memory budget of what keeps one state (or row) per sample: a sweep's collecting methods
//! ([`SweepOf::run`](super::sweep::SweepOf::run) and [`SweepOf::table`](super::sweep::SweepOf::table)),
//! [`sweep_at_of`](super::sweep_at::sweep_at_of), a [`SampledOf`](crate::analysis::SampledOf)
//! with the analyses built on one (a limit search's columns), and the points of
//! [`trace_curve_of`](super::trace::trace_curve_of), where iterating a sweep keeps none.

use crate::error::Error;

/// The most bytes of states (or table rows) kept one per sample: 1 GiB, the order of a
/// simulation's recording at its default step budget (0.96 GB, see
/// [`OdeConfig::max_steps`](crate::dynamics::OdeConfig::max_steps)).
///
/// A sweep may have up to [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES) intervals, and a state
/// takes a few hundred bytes: `run()` of `10^8` samples would ask for tens of GB, and a failed
/// allocation aborts the process rather than returning an error. What would exceed this is
/// refused before any step (`sweep_at` of inputs whose count is not known, when its states reach
/// it), saying what to do instead: a sweep's `run` and `table` (iterate it, `for s in sweep`, or
/// a fold, which keeps only what the caller keeps and is not bounded by this, or take fewer
/// samples), `sweep_at` (its inputs in parts), a sampled sweep and the analyses that keep one
/// (fewer samples). The bound is on the states themselves; the vector holding them grows by
/// doubling, as a `Vec` does.
pub const MAX_COLLECTED_BYTES: usize = 1 << 30;

/// `Err(Error::InvalidArgument)` when `count` items of `bytes_each` bytes, kept by `what` (what
/// the caller called, in words: "the sweep's `run()`", "the limit search"), exceed
/// [`MAX_COLLECTED_BYTES`]; the message gives the numbers and `instead`, what to do instead.
pub(crate) fn check_collected(
    what: &str,
    kept: &str,
    count: usize,
    bytes_each: usize,
    instead: &str,
) -> Result<(), Error> {
    check_collected_within(what, kept, count, bytes_each, instead, MAX_COLLECTED_BYTES)
}

/// Whether `count` items of `bytes_each` bytes fit in `budget` bytes (a count whose total
/// overflows does not): the test of [`check_collected`], for a caller whose error is its own.
pub(crate) fn within(count: usize, bytes_each: usize, budget: usize) -> bool {
    count.checked_mul(bytes_each).is_some_and(|total| total <= budget)
}

/// [`check_collected`] against a `budget` of bytes (tested with a small one); the message names
/// [`MAX_COLLECTED_BYTES`], the budget of every caller but a test.
pub(crate) fn check_collected_within(
    what: &str,
    kept: &str,
    count: usize,
    bytes_each: usize,
    instead: &str,
    budget: usize,
) -> Result<(), Error> {
    if within(count, bytes_each, budget) {
        return Ok(());
    }
    let total = count.saturating_mul(bytes_each);
    Err(Error::InvalidArgument(format!(
        "{what} would keep {count} {kept} of {bytes_each} bytes ({:.1} GB), beyond the {} GiB kept in memory at \
         most (`paths::collected::MAX_COLLECTED_BYTES`): {instead}",
        total as f64 / 1e9,
        MAX_COLLECTED_BYTES >> 30,
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The budget itself passes, a byte more does not, and a product that overflows is refused
    /// rather than wrapped into a small one.
    #[test]
    fn the_budget_is_inclusive_and_overflow_is_refused() {
        let check = |count: usize, bytes_each: usize| check_collected("it", "states", count, bytes_each, "less");
        assert!(check(MAX_COLLECTED_BYTES / 8, 8).is_ok());
        let err = check(MAX_COLLECTED_BYTES / 8 + 1, 8).unwrap_err();
        assert!(err.to_string().contains("it would keep 134217729 states of 8 bytes"), "{err}");
        assert!(err.to_string().ends_with(": less"), "{err}");
        assert!(check(usize::MAX, 2).is_err());
    }
}
