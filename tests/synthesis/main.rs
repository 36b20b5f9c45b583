//! Synthesis against independent references: known answers (dimensions hidden from closed-form
//! samples of a four-bar's coupler curve and of a slider-crank, recovered), the residuals'
//! Jacobian against central differences, the verification's defects on hand-made designs, bad
//! input, and the determinism of split and parallel searches.
//!
//! One test binary per subject; `support` (`tests/support/`) is shared by every binary.

#[allow(dead_code, unused_macros)] // not every binary uses every helper
#[macro_use]
#[path = "../support/mod.rs"]
mod support;

mod bad_input;
mod cognates;
mod convergence;
mod defects;
mod determinism;
mod docs_usage;
mod evolution;
mod grashof;
mod jacobian;
mod known_answers;
mod literature;
mod mechanisms;
mod report;
mod seeds;
