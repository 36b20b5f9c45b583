//! The bound on `--samples`: a count taken from the command line sizes the tables the sweeps
//! allocate and the time they run, so an unbounded one aborts on allocation or never ends.

use crate::{Failed, exit};

/// The most samples `sweep`, `extremes`, `dynamics` and `simulate` take: far more than a chart
/// or a table can show, and few enough for the states to fit in memory.
pub const MAX_SAMPLES: usize = 10_000_000;

/// The most samples `animate` takes: each is a pose recorded in full (a few kilobytes: every
/// point drawn, every column), where a row of a table takes a hundred bytes, so that
/// [`MAX_SAMPLES`] of them would take some twenty gigabytes. As many as a grid has cells at most
/// (`MAX_GRID_CELLS`), and far more than the frames written.
pub const MAX_ANIMATION_SAMPLES: usize = kinloop_viz::draw::MAX_GRID_CELLS;

/// `--samples` within [`MAX_SAMPLES`], or a usage error naming the limit.
pub fn check(samples: usize) -> Result<(), Failed> {
    check_at_most(samples, MAX_SAMPLES)
}

/// `--samples` within `max`, or a usage error naming the limit.
pub fn check_at_most(samples: usize, max: usize) -> Result<(), Failed> {
    if samples > max {
        return Err(exit::usage(format!("--samples {samples} is too many: at most {max}")));
    }
    Ok(())
}
