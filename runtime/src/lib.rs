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
#[doc(hidden)]
pub mod generated;
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
pub use mechanism::{Mechanism, Named, NamedSensitivities, Sensitivities};
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
