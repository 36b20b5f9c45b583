//! Synthesis: from the motion a designer needs to the dimensions of a declared mechanism that
//! makes it.
//!
//! [`classical`] holds the closed-form four-bar results of the theory (function generation by
//! Freudenstein's equation, Burmester's center-point and circle-point curves), used as exact
//! answers and as starts for the general search.

pub mod classical;
