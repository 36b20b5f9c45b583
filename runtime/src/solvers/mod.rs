//! Solvers of one square block: damped Newton's method with scale-free tests and its
//! diagnostics ([`newton`]), and the equilibrated LU factorisation of small fixed-size blocks
//! that Newton, the analogs and the sensitivities share ([`lu`]); large sparse blocks factorise
//! along an elimination order fixed at compile time ([`sparse_lu`]).

pub mod closed;
pub mod deferred;
pub mod inverse2;
pub mod jacobian;
pub mod lu;
pub mod newton;
mod newton_config;
pub mod sparse_lu;
