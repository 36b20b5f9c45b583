//! Solvers of one square block: damped Newton's method with scale-free tests and its
//! diagnostics ([`newton`]), and the equilibrated LU factorisation of small fixed-size blocks
//! that Newton, the analogs and the sensitivities share ([`lu`]); large sparse blocks factorise
//! along an elimination order fixed at compile time ([`sparse_lu`]), by the numeric steps of
//! [`sparse_steps`]; a sparse block read at run time, along its owned tables ([`sparse_lu_dyn`]).
//! Angles stay on their guesses' turns by [`turns`]; the closed forms' steps are [`closed`].
//!
//! The bottom layer of the runtime: nothing here knows a mechanism, its states or its sweeps.
//! The solvers use each other and the small leaves `error` and `events` only, so each can be
//! read and tested alone; `runtime/tests/layering.rs` fails when an import from above creeps in.

pub mod closed;
pub mod deferred;
pub mod inverse2;
pub mod jacobian;
pub mod lu;
pub mod newton;
pub mod sparse_lu;
pub mod sparse_lu_dyn;
pub mod sparse_steps;
pub mod turns;
