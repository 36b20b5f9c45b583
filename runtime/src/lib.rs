//! Runtime of [kinloop](https://docs.rs/kinloop): Newton solvers, the flat kinematic state,
//! errors, and the interface generated mechanisms implement.
//!
//! Most users depend on the `kinloop` facade crate, which re-exports everything here next to
//! the `mechanism!` macro.

// Index loops over small fixed-size arrays read like the formulas they implement (matrix rows,
// unknowns, inputs); iterator chains would obscure them.
#![allow(clippy::needless_range_loop)]

pub mod analysis;
pub mod dynamics;
mod error;
pub mod events;
mod kin;
mod mechanism;
pub mod metrics;
pub mod paths;
pub mod solvers;
mod table;
mod vec2;

// Short paths inside the crate for the modules every part uses.
use solvers::{lu, newton};

pub use analysis::objective::{Extreme, Extremum, extremum, integral};
pub use error::{Error, Quantity};
pub use events::{BlockInfo, Event, EventKind, Location};
pub use kin::{DetSigns, FlatMotion, Health, Jac, Kin, Sens};
pub use lu::{Factor, Fixed, Lu, max_abs};
pub use mechanism::{Mechanism, Sensitivities};
pub use newton::{BlockEval, BlockFailure, NewtonConfig, SolveReport, Solved, Termination, iterate, newton};
pub use paths::curve::{Traced, TracedPoint, trace_curve};
pub use paths::modes::assembly_modes;
#[cfg(feature = "rayon")]
pub use paths::scan::par_scan;
pub use paths::scan::{ScanSpec, ScanStart, scan};
pub use paths::sweep::{AtSingular, Reach, Sweep, SweepConfig, reachable};
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
        BlockFailure::Singular { pivot_ratio, tolerance, .. } => {
            Error::Singular { pivot_ratio, tolerance, at: Box::new(at) }
        }
        BlockFailure::InvalidConfig { field } => Error::InvalidArgument(format!(
            "NewtonConfig::{field} is out of its valid range (see its documentation), {at}"
        )),
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
