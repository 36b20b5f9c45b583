//! Synthesis: from the motion a designer needs to the dimensions of a declared mechanism that
//! makes it, for any mechanism declared with `#[kinloop(sensitivities)]`.
//!
//! Written once over [`SensKernel`](crate::SensKernel) ([`ProblemOf`]): a compiled mechanism's
//! problem is [`Problem`] (over [`CompiledSens`](crate::CompiledSens)), a run-time model's
//! `kinloop_model::Model::synthesis_problem`; the search, the local solve and the verification
//! are the same code, and give the same candidates where the kernels give the same states.
//!
//! A [`Problem`] names the design variables (parameters, with bounds: [`Design`]), the
//! [`Task`] (path generation with or without prescribed timing, path fitting with a free
//! placement, function generation, motion generation) and optional [`Constraints`]. A
//! [`Search`] runs Levenberg–Marquardt from many starts spread over the box by a shifted Halton
//! sequence, on the residuals with their exact Jacobian (the generated parameter
//! sensitivities; the velocity analogs for free input values; closed forms for the placement),
//! verifies every result with a branch-safe sweep through the targets in order ([`Defect`]s:
//! branch, circuit, order, and the constraints), and ranks them in a [`SynthesisReport`].
//!
//! [`classical`] holds the closed-form four-bar results of the theory (function generation by
//! Freudenstein's equation, Burmester's center-point and circle-point curves), used as exact
//! answers and as starts for the general search.
//!
//! See `docs/synthesis.md` in the repository for the method and what is verified.

mod candidate;
pub mod classical;
mod constraints;
mod error;
mod evolution;
mod halton;
mod held;
mod local;
mod problem;
mod refusal;
mod report;
mod residuals;
mod resolve;
mod search;
mod task;
mod vars;
mod verify;

pub use candidate::{Candidate, Defect, FourBarClass, Origin};
pub use constraints::{Constraints, FourBarNames, LinkRatioBound, TransmissionBound};
pub use error::SynthesisError;
pub use evolution::{DeConfig, Global};
pub use halton::Halton;
pub use local::{LocalConfig, LocalReport};
pub use problem::{Problem, ProblemOf, default_newton};
pub use refusal::{RefusalKind, Refused};
pub use report::{Rejections, SynthesisReport, grashof_code};
pub use residuals::Residuals;
pub use search::Search;
pub use task::{Channel, PlacementBounds, Task, Timing, chebyshev};
pub use vars::{Design, Variable};
