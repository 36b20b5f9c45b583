//! The bound on `--samples`: a count taken from the command line sizes the tables the sweeps
//! allocate and the time they run, so an unbounded one aborts on allocation or never ends.

use crate::{Failed, exit};

/// The most samples `sweep`, `extremes`, `animate` and `dynamics` take: far more than a chart
/// or a table can show, and few enough for the states to fit in memory.
pub const MAX_SAMPLES: usize = 10_000_000;

/// `--samples` within [`MAX_SAMPLES`], or a usage error naming the limit.
pub fn check(samples: usize) -> Result<(), Failed> {
    if samples > MAX_SAMPLES {
        return Err(exit::usage(format!("--samples {samples} is too many: at most {MAX_SAMPLES}")));
    }
    Ok(())
}
