//! The mechanisms and numbers of the papers (`docs/papers.md`) and of the gallery's examples,
//! against the papers' closed forms and independent constructions.
//!
//! One test binary per subject: each module below was a binary of its own, and every binary
//! links the whole library. A new test file of this subject goes into this folder with a
//! `mod` line here; `support` (`tests/support/`) is shared by every binary.

#[allow(dead_code, unused_macros)] // not every binary uses every helper
#[macro_use]
#[path = "../support/mod.rs"]
mod support;

mod gear_lever;
mod paper_000_extremes;
mod paper_000_variants;
mod paper_001_dwell;
mod paper_002_roller_edger;
mod paper_003_class_four;
mod paper_004_balancing;
mod rhombic_drive;
mod roller_edger;
