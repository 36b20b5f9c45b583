//! Runtime of [kinloop](https://docs.rs/kinloop): Newton solvers, the flat kinematic state,
//! errors, and the interface generated mechanisms implement.
//!
//! Most users depend on the `kinloop` facade crate, which re-exports everything here next to
//! the `mechanism!` macro.

// Index loops over small fixed-size arrays read like the formulas they implement (matrix rows,
// unknowns, inputs); iterator chains would obscure them.
#![allow(clippy::needless_range_loop)]

pub mod analysis;
mod curve;
pub mod dynamics;
mod error;
mod kin;
mod lu;
mod mechanism;
pub mod metrics;
mod modes;
mod newton;
mod objective;
mod scan;
mod sweep;
mod table;
mod vec2;

pub use curve::{Traced, TracedPoint, trace_curve};
pub use error::{BlockInfo, Error, Location, Quantity};
pub use kin::{FlatMotion, Health, Jac, Kin, Sens};
pub use lu::{Factor, Fixed, Lu, max_abs};
pub use mechanism::{Mechanism, Sensitivities};
pub use modes::assembly_modes;
pub use newton::{BlockEval, BlockFailure, NewtonConfig, SolveReport, Solved, Termination, iterate, newton};
pub use objective::{Extreme, Extremum, LmConfig, LmResult, extremum, integral, levenberg_marquardt};
#[cfg(feature = "rayon")]
pub use scan::par_scan;
pub use scan::{ScanSpec, ScanStart, scan};
pub use sweep::{AtSingular, Event, EventKind, Reach, Sweep, SweepConfig, reachable};
pub use table::Table;
pub use vec2::Vec2;

/// Re-exported so generated code and users share one nalgebra version.
pub use nalgebra;

/// Builds the error for a failed block (called by generated code on the cold path).
#[doc(hidden)]
#[cold]
#[inline(never)]
pub fn block_error(fail: BlockFailure, at: Location) -> Error {
    let equations = at.block.map_or(&[][..], |(_, info)| info.equations);
    let name = |row: usize| equations.get(row).copied().unwrap_or("?");
    match fail {
        BlockFailure::NonFinite { row, .. } => Error::Domain { what: "equation", name: name(row), at: Box::new(at) },
        BlockFailure::NoConvergence { row, iterations, residual } => {
            Error::NoConvergence { iterations, residual, equation: name(row), at: Box::new(at) }
        }
        BlockFailure::NoAssembly { row, residual, .. } => {
            Error::NoAssembly { residual, equation: name(row), at: Box::new(at) }
        }
    }
}

/// The first row holding a non-finite value (cold-path diagnosis of a failed factorisation).
#[doc(hidden)]
#[cold]
pub fn first_bad_row<const M: usize, const R: usize>(rows: &[[f64; M]; R]) -> Option<usize> {
    rows.iter().position(|r| r.iter().any(|v| !v.is_finite()))
}

/// Finds the first non-finite value among named values (parameters, inputs, guesses).
#[doc(hidden)]
pub fn first_non_finite(names: &[&'static str], values: &[f64]) -> Option<(&'static str, f64)> {
    names.iter().zip(values).find(|(_, v)| !v.is_finite()).map(|(n, v)| (*n, *v))
}
