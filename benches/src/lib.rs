//! Benchmarks of kinloop: the rhombic drive of paper 000 against its
//! hand-written closed form, a hand-written two-loop Newton, and dense Newtons with a
//! hand-written, num-dual or finite-difference Jacobian; the class IV mechanism of paper 003
//! against a hand-written Newton for its coupled block; a ring of 64 four-bar loops (one sparse
//! block of 128 unknowns) against the same loops in series; and the macro's expansion time and code
//! size. See `BENCHMARKS.md` at the repository root for how to run them and the results.
//!
//! The peers live here (not in the bench targets) so the criterion benchmarks, the accuracy and
//! allocation tests and the report binary all use the same code.

#![warn(missing_docs)]

pub mod class_four;
pub mod decls;
pub mod expansion;
pub mod hand;
pub mod hand_check;
pub mod hand_sweep;
pub mod kernel_lane;
pub mod kinloop_variants;
pub mod lane_sketch;
pub mod lean;
pub mod libm;
pub mod linalg;
pub mod literature;
pub mod rhombic;
pub mod ring;
pub mod rows;
pub mod sweep;
