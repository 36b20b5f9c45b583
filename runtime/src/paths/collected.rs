//! The memory budget of a sweep's collecting methods ([`SweepOf::run`](super::sweep::SweepOf::run)
//! and [`SweepOf::table`](super::sweep::SweepOf::table)), which keep every state, where iterating
//! the sweep keeps none.

use crate::error::Error;

/// The most bytes of states (or table rows) a sweep's collecting methods keep: 1 GiB, the order
/// of a simulation's recording at its default step budget (0.96 GB, see
/// [`OdeConfig::max_steps`](crate::dynamics::OdeConfig::max_steps)).
///
/// A sweep may have up to [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES) intervals, and a state
/// takes a few hundred bytes: `run()` of `10^8` samples would ask for tens of GB, and a failed
/// allocation aborts the process rather than returning an error. A sweep whose states would
/// exceed this is refused by `run` and `table` before any step, saying what to do instead:
/// iterate it (`for s in sweep`, or a fold), which keeps only what the caller keeps and is not
/// bounded by this, or take fewer samples. The bound is on the states themselves; the vector
/// holding them grows by doubling, as a `Vec` does.
pub const MAX_COLLECTED_BYTES: usize = 1 << 30;

/// `Err(Error::InvalidArgument)` when `count` items of `bytes_each` bytes, kept by `what` (a
/// method's name, such as "`run()`"), exceed [`MAX_COLLECTED_BYTES`]; the message gives the
/// numbers and the alternatives.
pub(crate) fn check_collected(what: &str, kept: &str, count: usize, bytes_each: usize) -> Result<(), Error> {
    let total = count.saturating_mul(bytes_each);
    if total <= MAX_COLLECTED_BYTES {
        return Ok(());
    }
    Err(Error::InvalidArgument(format!(
        "the sweep's {what} would keep {count} {kept} of {bytes_each} bytes ({:.1} GB), beyond the {} GiB a \
         collected sweep may keep (`paths::collected::MAX_COLLECTED_BYTES`): iterate the sweep instead (`for s in \
         sweep`, or a fold, keeps only what you keep), or take fewer samples",
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
        assert!(check_collected("`run()`", "states", MAX_COLLECTED_BYTES / 8, 8).is_ok());
        let err = check_collected("`run()`", "states", MAX_COLLECTED_BYTES / 8 + 1, 8).unwrap_err();
        assert!(err.to_string().contains("134217729 states of 8 bytes"), "{err}");
        assert!(check_collected("`run()`", "states", usize::MAX, 2).is_err());
    }
}
