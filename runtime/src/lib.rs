//! Runtime of [kinloop](https://docs.rs/kinloop): Newton solvers, the flat kinematic state,
//! errors, and the interface generated mechanisms implement.
//!
//! Most users depend on the `kinloop` facade crate, which re-exports everything here next to
//! the `mechanism!` macro.

// Index loops over small fixed-size arrays read like the formulas they implement (matrix rows,
// unknowns, inputs); iterator chains would obscure them.
#![allow(clippy::needless_range_loop)]
#![warn(missing_docs)]

pub mod analysis;
mod angles;
pub mod dynamics;
mod error;
pub mod events;
#[doc(hidden)]
pub mod generated;
mod kin;
#[cfg(feature = "serde")]
mod kin_serde;
mod kinds;
mod mechanism;
pub mod metrics;
pub mod paths;
mod solvers;
mod table;
mod table_units;
mod vec2;

// Short paths inside the crate for the modules every part uses.
use solvers::{lu, newton};

pub use analysis::objective::{Extreme, Extremum, extremum, integral};
pub use angles::{deg, to_deg};
pub use error::{Error, Quantity};
pub use events::{BlockInfo, Event, EventKind, Location};
pub use kin::{DetSigns, FlatMotion, Health, Jac, Kin, Sens};
pub use kinds::{LENGTH_UNIT, QuantityKind};
pub use mechanism::{Mechanism, Named, NamedSensitivities, Sensitivities};
pub use newton::{NewtonConfig, SolveReport, Termination};
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
