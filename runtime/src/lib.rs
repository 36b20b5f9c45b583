//! Runtime of [kinloop](https://docs.rs/kinloop): the interface generated mechanisms implement
//! ([`Mechanism`], the flat kernels, and [`Named`], the typed API on top of them), and the
//! generic code every mechanism shares:
//!
//! * the flat kinematic state [`Kin`] and the typed [`Error`]s;
//! * the position solves, configured by [`NewtonConfig`] and reported by [`SolveReport`] (the
//!   block solvers themselves are private: generated code reaches them through a hidden
//!   module);
//! * branch-safe sweeps, continuation through limit positions, assembly modes and scans
//!   ([`paths`], with [`Sweep`] and [`scan`] re-exported; a mechanism's own methods
//!   [`Named::reachable`], [`Named::trace_curve`] and [`Named::assembly_modes`] reach the
//!   rest), and the [`Event`]s they locate;
//! * [`Table`]s with units and CSV, [`Vec2`], angle conversions ([`deg`], [`to_deg`]);
//! * [`analysis`] of sweeps, design [`metrics`], machine [`dynamics`].
//!
//! Most users depend on the `kinloop` facade crate, which re-exports everything here next to
//! the `mechanism!` macro.

// Index loops over small fixed-size arrays read like the formulas they implement (matrix rows,
// unknowns, inputs); iterator chains would obscure them.
#![allow(clippy::needless_range_loop)]
#![warn(missing_docs)]

pub mod analysis;
mod angles;
mod configured;
pub mod dims;
pub mod drawing;
pub mod dynamics;
mod error;
pub mod events;
#[cfg(feature = "serde")]
mod floats_serde;
#[doc(hidden)]
pub mod generated;
mod kin;
#[cfg(feature = "serde")]
mod kin_serde;
mod kinds;
mod mechanism;
pub mod metrics;
mod named;
mod number;
pub mod paths;
mod solvers;
pub mod synthesis;
mod table;
mod table_units;
#[cfg(test)]
mod test_rng;
mod trig;
mod vec2;

pub use analysis::Extreme;
pub use analysis::objective::{Extremum, ExtremumOf};
pub use angles::{deg, to_deg};
pub use configured::Configured;
pub use error::{Computed, Error, Quantity, Source};
pub use events::{BlockInfo, BlockNames, Event, EventKind, Location};
pub use kin::{DetSigns, FlatMotion, Health, Jac, Kin, Sens};
pub use kinds::{LENGTH_UNIT, QuantityKind};
pub use mechanism::kernel::{Compiled, CompiledSens, Kernel, SensKernel, SensState};
pub use mechanism::{Mechanism, Sensitivities};
pub use named::{Named, NamedSensitivities};
pub use number::{Count, Number};
pub use paths::assembles::{Assembly, PathEntry};
pub use paths::config::{AtSingular, SweepConfig};
pub use paths::outcome::{SweepResult, SweepStop};
pub use paths::reach::Reach;
#[cfg(feature = "rayon")]
pub use paths::scan::par_scan;
pub use paths::scan::{ScanConfig, ScanStart, scan};
pub use paths::sweep::{Sweep, SweepOf};
pub use paths::trace::{TraceConfig, Traced, TracedOf, TracedPoint, TracedPointOf};
pub use solvers::newton::{NewtonConfig, NewtonStop, SolveReport};
pub use table::{ColumnKey, Table};
pub use vec2::Vec2;

/// Re-exported so generated code and users share one nalgebra version. Hidden from the item
/// lists, which its items would swamp: the facade shows it as one re-export line.
#[doc(hidden)]
pub use nalgebra;
