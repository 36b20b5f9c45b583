//! The point solver and the code `mechanism!` generates: closed-form blocks against their
//! Newton twins, the block decomposition, deferred checks, Newton's restarts, singular levers,
//! the order of generated sines and cosines, and the step whose cost callgrind measures.
//!
//! One test binary per subject: each module below was a binary of its own, and every binary
//! links the whole library. A new test file of this subject goes into this folder with a
//! `mod` line here; `support` (`tests/support/`) is shared by every binary.

#[allow(dead_code, unused_macros)] // not every binary uses every helper
#[macro_use]
#[path = "../support/mod.rs"]
mod support;

mod accepted_guess;
mod closed_form;
mod closed_form_constructions;
mod closed_form_prop;
mod decomposition;
mod deferred_checks;
mod deferred_entry_bound;
mod degenerate_dyad_links;
mod lever_singularity;
mod mechanism_named_like_prelude;
mod newton_restarts;
mod overflowed_magnitudes;
mod sin_cos_order;
mod sparse_steps;
mod step_cost;
mod underflowed_magnitudes;
mod zero_lengths;
