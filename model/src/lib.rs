//! Mechanisms read at run time: the declaration language of `kinloop::mechanism!` read from
//! text (a `.kl` file), checked and planned by the macro's own pipeline (`kinloop-codegen`:
//! front end, checks, structure analysis, plan), then evaluated by an instruction tape over
//! `f64` registers instead of compiled.
//!
//! ```
//! use kinloop_model::Model;
//! let text = "pub struct FourBar {
//!     params a = 1, b = 3, c = 2.5, d = 3.2;
//!     input phi;
//!     unknowns psi = 0.6, theta = 1.9;
//!     loop abcd: a @ phi + b @ psi == (d, 0) + c @ theta;
//! }";
//! let mut m = Model::read("four_bar.kl", text).unwrap();
//! let state = m.solve(&[0.5]).unwrap();
//! assert_eq!(state.q.len(), 2);
//! ```
//!
//! # One pipeline, two back ends
//!
//! [`Model::read`] lexes the text with proc-macro2 (whose spans then carry lines and columns),
//! and hands the tokens to `kinloop_codegen::plan_declaration`: the very functions the macro
//! runs, so a declaration is accepted or rejected with the same messages ([`Diagnostics`],
//! rendered with a caret by `codespan-reporting`). The plan's expression graph becomes a tape
//! (`tape`): one register per graph node, one instruction per operation, each the operation the
//! emitted code performs for that node. Each block is solved as the plan decided, with the
//! runtime's own solvers: the closed forms by the emitter's formulas on values (`closed`),
//! Newton by the runtime's `newton` (`newton`), the factorisations by the runtime's `Lu`,
//! `Inverse2` and `Fixed`, chosen by the emitter's rules (`factor`), dispatched over the block
//! size once per call. A step ([`Model::kinematics`]) computes what the compiled mechanism's
//! `kinematics_flat` computes, with the same operations in the same order, and allocates
//! nothing.
//!
//! Not evaluated yet: blocks solved by sparse Newton and blocks of more than
//! [`MAX_DENSE`] unknowns ([`ReadError::Unsupported`]); the dynamics items (bodies, loads: planned,
//! not evaluated). Parameter sensitivities are ([`Model::sensitivities`]).
//!
//! # Speed
//!
//! A step is an interpreted tape: on the gallery's rhombic drive it executes about 6.9 times
//! the compiled step's instructions (4.2 times its time), on a Newton-dominated class IV block
//! 2.4 times; reading and planning a declaration takes a few milliseconds (`BENCHMARKS.md`,
//! "Mechanisms read at run time").
//!
//! # Sweeps and the runtime's algorithms
//!
//! The runtime's sweeps, events, reachable ranges, curve tracing and analyses are written over
//! the const-generic trait `Mechanism<N, NI, NO>` (sizes known when the mechanism is compiled)
//! and its `Kin<N, NI, NO>` states. They are not repeated here: making them serve a run-time
//! model needs them generic over how sizes are known. What that takes:
//!
//! * a size parameter: a trait `Dims` with associated array types (`type Q: AsRef<[f64]> +
//!   AsMut<[f64]> + Copy`, one per shape: unknowns, inputs, outputs, `dq`, ...) implemented
//!   by a zero-sized `Const<N, NI, NO>` (arrays: the compiled path keeps its code and speed)
//!   and by a run-time `Dyn` (boxed slices, allocated once per sweep);
//! * `Kin` and the sweep's state generic over `Dims` instead of three const parameters;
//!   `Mechanism` gains `type Dims` and its flat kernels take and return `Dims`' types; every
//!   `[f64; N]` in `paths/` (sweep, continuation, events, trace, reach) becomes `D::Q`, and
//!   the few stack arrays of temporaries (`[f64; N]` scratch in the event locator and the
//!   predictor) become fields of a per-sweep workspace;
//! * the sweep's kernel entry points that a compiled mechanism specialises (`kinematics_step_sink`
//!   with its trigonometry cache and deferred checks) keep default implementations in terms of
//!   `kinematics_flat`, which a run-time model implements with [`Model::kinematics`].
//!
//! Until then a run-time model offers single-point solves with their analogs
//! ([`Model::kinematics`], [`Model::solve`]) and the structure report.

#![warn(missing_docs)]

mod blocks;
mod closed;
mod factor;
mod model;
mod newton;
mod sensitivities;
pub mod source;
mod tape;

pub use blocks::StepFailure;
pub use factor::MAX_DENSE;
pub use model::{Model, ReadError, State, StepError};
pub use sensitivities::Sensitivities;
pub use source::{Diagnostic, Diagnostics, Level};
