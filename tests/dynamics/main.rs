//! Machine dynamics: declared mass models, reduced inertia, inverse dynamics, shaking force and
//! moment, forward simulation, and the dynamics layer's typed errors.
//!
//! One test binary per subject: each module below was a binary of its own, and every binary
//! links the whole library. A new test file of this subject goes into this folder with a
//! `mod` line here; `support` (`tests/support/`) is shared by every binary.

#[allow(dead_code, unused_macros)] // not every binary uses every helper
#[macro_use]
#[path = "../support/mod.rs"]
mod support;

#[allow(dead_code)] // not every module uses every fixture
mod fixtures;

mod declared;
mod errors;
mod inertia;
mod inverse;
mod robust_inputs;
mod shaking;
mod simulation;
