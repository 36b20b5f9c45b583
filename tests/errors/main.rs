//! Typed errors and the regression tests of the point solver and of sweeps: every `Ok` is
//! accurate, every error names what happened.
//!
//! One test binary per subject: each module below was a binary of its own, and every binary
//! links the whole library. A new test file of this subject goes into this folder with a
//! `mod` line here; `support` (`tests/support/`) is shared by every binary.

#[allow(dead_code, unused_macros)] // not every binary uses every helper
#[macro_use]
#[path = "../support/mod.rs"]
mod support;

mod assert_close;
mod auto_traits;
mod errors;
mod limit_of_one_angle;
mod limit_within_tolerance;
mod newton_near_limits;
mod no_silent_wrong_answer;
mod no_silent_wrong_answer_sweeps;
