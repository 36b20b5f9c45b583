//! The expression graph ([`dag`]: hash-consed nodes with local simplification) and its
//! symbolic differentiation and substitution ([`diff`]).

pub mod dag;
pub mod diff;
