//! Positions and analogs of declared mechanisms against independent references: closed forms,
//! 50-digit references, finite differences, random linkages, units and quantity kinds, degrees,
//! parameter sensitivities.
//!
//! One test binary per subject: each module below was a binary of its own, and every binary
//! links the whole library. A new test file of this subject goes into this folder with a
//! `mod` line here; `support` (`tests/support/`) is shared by every binary.

#[allow(dead_code, unused_macros)] // not every binary uses every helper
#[macro_use]
#[path = "../support/mod.rs"]
mod support;

mod assembly_modes_extreme_scales;
mod cam_linkage;
mod chained_blocks_extreme_scales;
mod constants_named_like_declared_names;
mod degrees;
mod drawing;
mod extreme_scales;
mod five_bar;
mod later_equations;
mod limit_positions_extreme_scales;
mod mixed_units_extreme_scales;
mod near_singular;
mod pedantic_lints;
mod prop_linkages;
mod quantity_kinds;
mod readme_tour;
mod reference_mpmath;
mod sensitivities;
mod shadowed_primitives;
mod units;
mod without_the_prelude;
