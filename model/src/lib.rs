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
//! size once per call. A large block the plan solves by sparse Newton keeps the plan's pattern
//! and elimination order as tables and runs the runtime's `newton_with` over its non-zeros,
//! its numeric steps the loops the compiled tables run (`sparse`), the weak-pivot dense
//! fallback included; it is solved at a compiled size padded with unknowns that stay zero,
//! which changes no value and no test. A step ([`Model::kinematics`]) computes what the compiled mechanism's
//! `kinematics_flat` computes, with the same operations in the same order, and allocates
//! nothing.
//!
//! Not evaluated yet: dense blocks of more than [`MAX_DENSE`] unknowns
//! ([`ReadError::Unsupported`]; sparse blocks are, up to [`MAX_SPARSE`], the language's limit of
//! unknowns); the dynamics items (bodies, loads: planned, not evaluated). Parameter sensitivities are ([`Model::sensitivities`]).
//!
//! # Speed
//!
//! A step is an interpreted tape (nodes of the parameters alone computed when they are set, a
//! sine and cosine of one argument as one instruction, consecutive arithmetic operations
//! sharing a dispatch): on the gallery's rhombic drive it executes about 5.4 times the compiled
//! step's instructions (about 2.5 times its time), on the four-bar 4.6 times, on a
//! Newton-dominated class IV block 2 times, on the ring of 64 four-bar loops (one sparse block
//! of 128 unknowns) 2.4 times; reading and planning a declaration takes one to
//! three milliseconds (`BENCHMARKS.md`, "Mechanisms read at run time").
//!
//! # Sweeps and the runtime's algorithms
//!
//! The runtime's sweep is written once, over its size-agnostic trait `Kernel`, whose storage
//! comes from a `Dims`: `Fixed<N, NI, NO>` (arrays, for compiled mechanisms through the
//! zero-cost wrapper `Compiled`) or `Sizes { n, ni, no }` (boxed slices, allocated once per
//! sweep). A [`Model`] is a `Kernel` ([`ModelKernel`], from [`Model::kernel`]), so
//! [`Model::sweep`] is that very sweep: branch-safe steps, events (limit positions, singular
//! crossings, located by the same continuation), `next_ref`/`next_kin`, `table()` with the
//! model's column names and units, `run`. It equals the compiled mechanism's sweep to rounding
//! (`tests/sweeps.rs`: the fixtures of the parity tests over a whole turn, the same events at the
//! same inputs). Its step is [`Model::kinematics`] (libm's sines and cosines: a run-time model has
//! no trigonometry cache, nor deferred checks), copied into the sweep's slot: no allocation per
//! step.
//!
//! Served to run-time models this round: the sweep and what it uses (the event location by
//! pseudo-arclength continuation, the equilibrated determinants, the table). Still on compiled
//! sizes (`Mechanism<N, NI, NO>` and `Kin<N, NI, NO>`): `trace_curve` (its result type
//! `Traced<N, NI>` holds arrays; its continuation is already the kernel-generic one), the
//! reachable ranges and `sweep_at` (stretches of sweeps: they need their result types generic),
//! the assembly modes (multi-start Newton over `position_flat`, which a model does not expose
//! as a kernel method), scans, the analyses of sampled sweeps (`Sampled` holds `Kin` arrays),
//! sensitivities-based synthesis (`Sensitivities<N, NI, NO, NP>`) and dynamics. Each needs its
//! state and result types over `Dims` as the sweep's are, and the kernel methods it calls
//! (`position`, `sensitivities`) added to `Kernel`.
//!
//! A run-time model's errors and events name the model, its inputs and the failed or singular
//! block's unknowns and equations as the compiled mechanism's do, with owned strings (the names
//! of `Location`, `BlockInfo` and the errors are `Cow<'static, str>`: borrowed constants for a
//! compiled mechanism).
//!
//! Besides sweeps a run-time model offers single-point solves with their analogs and
//! sensitivities ([`Model::kinematics`], [`Model::sensitivities`], [`Model::solve`]) and the
//! structure report.

#![warn(missing_docs)]

mod at;
mod blocks;
mod closed;
mod factor;
mod mechanism;
mod model;
mod newton;
mod sensitivities;
pub mod source;
mod sparse;
mod tape;

pub use at::Jacobian;
pub use blocks::StepFailure;
pub use factor::MAX_DENSE;
pub use mechanism::ModelKernel;
pub use model::{Model, ReadError, State, StepError};
pub use sensitivities::Sensitivities;
pub use source::{Diagnostic, Diagnostics, Level};
pub use sparse::MAX_SPARSE;
