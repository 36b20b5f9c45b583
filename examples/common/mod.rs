//! Helpers shared by the examples (the library of the `kinloop-examples` package): where their
//! data and figures go, and the dwell cam's profile ([`dwell_cam`]). The examples draw with `kinloop::plot`, giving each series its quantity
//! kind.

pub mod dwell_cam;

use kinloop::plot;
use std::path::PathBuf;

/// Output folder of an example: `$KINLOOP_OUT/<example>` (default `out/<example>`).
///
/// # Panics
/// When the folder cannot be created (`kinloop::plot::out_dir` returns the error instead).
pub fn out_dir(example: &str) -> PathBuf {
    plot::out_dir(example).unwrap_or_else(|e| panic!("{e}"))
}

/// Folder for an example's figures: `$KINLOOP_FIGURES/<example>` when that variable is set
/// (`KINLOOP_FIGURES=docs/figures` regenerates the README gallery), else [`out_dir`].
///
/// # Panics
/// When the folder cannot be created (`kinloop::plot::figure_dir` returns the error instead).
pub fn figure_dir(example: &str) -> PathBuf {
    plot::figure_dir(example).unwrap_or_else(|e| panic!("{e}"))
}
