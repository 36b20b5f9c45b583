//! Analysis on top of sweeps: cam profiles by inversion, design metrics, objectives with exact gradients, `Sampled` along
//! paths through the input space, and the synthesis example.
//!
//! One test binary per subject: each module below was a binary of its own, and every binary
//! links the whole library. A new test file of this subject goes into this folder with a
//! `mod` line here; `support` (`tests/support/`) is shared by every binary.

#[allow(dead_code, unused_macros)] // not every binary uses every helper
#[macro_use]
#[path = "../support/mod.rs"]
mod support;

mod cam_profile;
mod classical_synthesis;
mod classical_units;
mod coarse_samples;
mod far_from_origin;
mod flat_face;
mod limits_crossing;
mod limits_extreme_scales;
mod metrics_mechanisms;
mod objectives;
mod periodic_columns;
mod rests;
mod sampled_paths;
mod synthesis;
mod unbalance_crossing;
