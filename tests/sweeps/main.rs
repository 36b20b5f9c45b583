//! Sweeps: branch safety, limit positions and change points, the sweep's results and stop
//! reasons, sweeps over given inputs, and judged lengths.
//!
//! One test binary per subject: each module below was a binary of its own, and every binary
//! links the whole library. A new test file of this subject goes into this folder with a
//! `mod` line here; `support` (`tests/support/`) is shared by every binary.

#[allow(dead_code, unused_macros)] // not every binary uses every helper
#[macro_use]
#[path = "../support/mod.rs"]
mod support;

mod assembly_near;
mod assur_groups;
mod change_point_samples;
mod events_extreme_scales;
mod sweep_any_step;
mod sweep_api;
mod sweep_at;
mod sweep_budget;
mod sweep_dense;
mod sweep_drift;
mod sweep_judged_length;
mod sweep_kinks;
mod sweeps;
mod trace_branch_points;
mod trace_from_limits;
mod trace_kinks;
mod trace_length_input_scales;
