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
//! The runtime's sweeps, events, reachable ranges, curve tracing, scans and analyses are written
//! over the const-generic trait `Mechanism<N, NI, NO>` (sizes known when the mechanism is
//! compiled) and its `Kin<N, NI, NO>` states. They are not repeated here (one implementation of
//! each algorithm): serving a run-time model needs them generic over how sizes are known. What
//! that takes, from `runtime/src/paths/sweep.rs`, `curve.rs` and `mechanism.rs`:
//!
//! * **Sizes.** A trait `Dims` with associated storage types, one per shape the algorithms hold
//!   (`Q` for `[f64; N]`, `X` for `[f64; NI]`, `XX` for `[[f64; NI]; NI]`, the state `Kin`, the
//!   Jacobian `Jac`), implemented by a zero-sized `Fixed<N, NI, NO>` with the arrays of today
//!   (compiled mechanisms keep their code and speed) and by a run-time `Sized { n, ni, no }` with
//!   boxed slices, allocated once per sweep. `Mechanism` gains `type Dims` and its flat kernels
//!   (`kinematics_flat`, `kinematics_at_flat`, `jacobian_flat`, `guess_flat`, `outputs_flat`,
//!   `kinematics_step_sink`) take and write `Dims`' types. The sweep's fields (`guess`,
//!   `first_q`, `states: [Kin; 2]`, `delta2`, `Path<NI>`), its `Prediction<N>`, and
//!   `curve.rs`'s `CurvePoint<N>`, `Metric<N>` and stack temporaries become `Dims`' types or
//!   fields of the sweep's workspace.
//! * **Constants.** `NAME`, `PARAMS`, `INPUTS`, `UNKNOWNS`, `EQUATIONS`, `OUTPUTS`, `BLOCKS`,
//!   the kinds, `FOLLOWERS` and `CLOSED_FORM_ANGLES` are associated constants; a run-time model
//!   knows them only when read. They become methods whose defaults return the constants
//!   (nothing changes for compiled mechanisms after inlining), and what the sweep computes from
//!   them at compile time (`const JUDGED: Judged<N> = Judged::of(M::FOLLOWERS)`) becomes a field
//!   made in `Sweep::new`.
//! * **Names in errors.** `Location` and `Error` hold `&'static str` names (`M::NAME`,
//!   `M::INPUTS`); a run-time model's names are owned strings. Either the names become
//!   `Cow<'static, str>` (or `Arc<str>`) in `Location` (a public type: a CHANGELOG entry), or a
//!   read model leaks its few names once (`Box::leak`, bounded by the number of models read;
//!   not acceptable for a long-running service reading untrusted files).
//! * **The flat kernels** a run-time model provides already, equal to the compiled ones:
//!   `kinematics_flat` ([`Model::kinematics`]), `kinematics_at_flat` ([`Model::kinematics_at`]),
//!   `jacobian_flat` ([`Model::jacobian`]), `outputs_flat` ([`Model::outputs_at`]),
//!   `residual_flat` ([`Model::residual`]), `guess_flat` ([`Model::guess`]) and
//!   `sensitivities_flat` ([`Model::sensitivities`]). The sweep's fast path
//!   (`kinematics_step_sink` with the input trigonometry cache and deferred checks) keeps its
//!   default, `kinematics_flat`, for a run-time model.
//!
//! Until then a run-time model offers single-point solves with their analogs and sensitivities
//! ([`Model::kinematics`], [`Model::sensitivities`], [`Model::solve`]) and the structure report.

#![warn(missing_docs)]

mod at;
mod blocks;
mod closed;
mod factor;
mod model;
mod newton;
mod sensitivities;
pub mod source;
mod sparse;
mod tape;

pub use at::Jacobian;
pub use blocks::StepFailure;
pub use factor::MAX_DENSE;
pub use model::{Model, ReadError, State, StepError};
pub use sensitivities::Sensitivities;
pub use source::{Diagnostic, Diagnostics, Level};
pub use sparse::MAX_SPARSE;
