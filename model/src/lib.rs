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
//! Newton by the runtime's `newton` (`dense`, the block's program in `newton`; its
//! evaluation's sines and cosines rotated from the solve's previous evaluation by the runtime's
//! `NearSlot`, as the emitted block's `NearTrig` rotates them: `near`), the factorisations by
//! the runtime's `Lu`, `Inverse2` and `Fixed`, chosen by the emitter's rules (`factor`),
//! dispatched over the block size once per call. A large block the plan solves by sparse
//! Newton keeps the plan's pattern
//! and elimination order as tables and runs the runtime's `newton_with` over its non-zeros,
//! its numeric steps the loops the compiled tables run (`sparse`), the weak-pivot dense
//! fallback included; it is solved at a compiled size padded with unknowns that stay zero,
//! which changes no value and no test. A step ([`Model::kinematics`]) computes what the compiled mechanism's
//! `kinematics_flat` computes, with the same operations in the same order, and allocates
//! nothing; [`Model::positions`] solves the positions alone, as `position_flat` (the drawings'
//! reference state). Through the runtime's `Kernel` ([`ModelKernel`]), a failed step is the
//! compiled mechanism's error, field for field and named alike (`tests/errors.rs`).
//!
//! Not evaluated yet: dense blocks of more than [`MAX_DENSE`] unknowns
//! ([`ReadError::Unsupported`]; sparse blocks are, up to [`MAX_SPARSE`], the language's limit of
//! unknowns). Parameter sensitivities are ([`Model::sensitivities`]), and so are the dynamics
//! items (below).
//!
//! # Dynamics
//!
//! The declared bodies, loads and gravity are evaluated as the compiled mechanism's
//! `mass_model` evaluates them: masses, moments of inertia, constant coordinates and gravity
//! are nodes of the parameters, read from their registers into the runtime's
//! `dynamics::MassModelBuf` ([`Model::mass_model`]); the force and torque expressions are a
//! segment of their own over the inputs and unknowns of a state ([`Model::load_values`], no
//! allocation). The runtime's dynamics is written once over any state (`AnalogState`: the
//! compiled `Kin` or a run-time `KinBuf`) and any `Kernel`, so a model's dynamics at a state
//! ([`Model::dynamics`], [`Model::shaking`]), its inverse cycle over a turn of the input and the
//! flywheel sizing ([`Model::inverse_cycle`]) are the compiled mechanism's, computed by the same
//! code: they equal the compiled ones to 1e-14 of each quantity's magnitude
//! (`tests/dynamics.rs`). So is the forward simulation ([`Model::simulation`]: the runtime's
//! `dynamics::simulate_of`, the compiled `Simulation`'s integration, over the model's kernel,
//! each evaluation the model's step written in place and the declared loads' segment, no
//! allocation but the trajectory's, none at all when [`ModelSimulation::run_steps`] hands each
//! step over as it is made): the same trajectory to the last bit on the engine and
//! Stirling fixtures, and a free slider-crank's energy and time of a turn as the closed forms
//! give them.
//!
//! # Speed
//!
//! A step is an interpreted tape (nodes of the parameters alone computed when they are set, a
//! sine and cosine of one argument as one instruction, consecutive arithmetic operations
//! sharing a dispatch) and, per closed-form block, a small program compiled when the model is
//! built (the emitter's folds of the graph's constants decided once), the blocks'
//! factorisations written in place: on the gallery's rhombic drive it executes about 3.7 times
//! the compiled step's instructions, on the four-bar 2.6 times, on a Newton-dominated class IV
//! block 1.7 times, on the ring of 64 four-bar loops (one sparse block of 128 unknowns) 2.6
//! times. What remains is the interpretation's dispatch per operation and the per-block
//! bookkeeping of small blocks. Reading and planning a declaration takes 0.6 to 3.0
//! milliseconds (`BENCHMARKS.md`, "The run: mechanisms read at run time").
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
//! same inputs). Its step is [`Model::kinematics`] (libm's sines and cosines of the inputs: a
//! run-time model has no sweep's trigonometry cache, nor deferred checks; its Newton blocks
//! rotate theirs as a point solve of the compiled mechanism does), copied into the sweep's slot:
//! no allocation per step.
//!
//! Served to run-time models: the sweep and what it uses (the event location by
//! pseudo-arclength continuation, the equilibrated determinants, the table), and the analyses
//! of sampled sweeps ([`Model::sampled`], the runtime's `SampledOf`: extremes located as roots
//! of the velocity analog, ranges, dwells, harmonics, unbalance, time ratio, transmission angle;
//! columns by name) and the limit report ([`Model::limits`]), each the one implementation a
//! compiled mechanism runs (`tests/analysis.rs`: equal bit for bit to the compiled
//! mechanism's where the sweeps' sines are the same, and to the closed forms).
//!
//! The runtime's other path algorithms are written once over `Kernel` too, and serve a model
//! through the same kernel (the compiled mechanisms' public functions call them through
//! `Compiled`):
//!
//! * [`Model::trace_curve`]: the whole solution curve through limit positions
//!   (`trace_curve_of`; its result [`ModelTraced`] is the generic `TracedOf` over boxed slices);
//! * [`Model::reachable`]: how far the input goes on one assembly mode (`reachable_of`);
//! * [`Model::sweep_at`]: the states at given inputs, stretch by stretch (`sweep_at_of`);
//! * [`Model::assembly_modes`]: the distinct assembly modes at an input (`assembly_modes_of`,
//!   multi-start Newton from the declared guess, `Kernel::guess`);
//! * [`Model::scan`]: a design-space scan over parameter sets ([`ParamScanConfig`]), each set's
//!   sweep folded into one value (`fold_sweep_of`, the compiled `scan`'s fold);
//! * `Model::par_scan` (cargo feature `rayon`): the same on all cores (the compiled
//!   `par_scan`'s distribution over rayon's pool), a clone of the model per rayon job, the
//!   results bitwise [`Model::scan`]'s.
//!
//! They equal the compiled mechanism's to the last bit where the operations are the same (curve
//! tracing and the assembly modes call the same kernels; the others, whose sweep steps take
//! libm's sines and cosines here where a compiled sweep rotates them, against a compiled
//! mechanism stepping with libm's), and its own to the sweeps' rounding otherwise
//! (`tests/paths.rs`, with the four-bar's and slider-crank's closed forms as independent checks).
//! Each lends the model with its solver configuration (`Model::sweep_config`, the defaults until
//! `Model::set_sweep_config`); the generic functions take
//! any kernel, `m.kernel(config)`.
//!
//! Synthesis is served too: the runtime's `synthesis` is written once over `SensKernel` (a
//! `Kernel` with parameters to set and the sensitivities of its states), which the model's
//! kernel implements; [`Model::synthesis_problem`] gives the problem ([`ModelProblem`]) that
//! `Search::run` solves with the compiled mechanism's code, to the same candidates bit for bit
//! (`tests/synthesis.rs`). That problem lends the model, one evaluation after the other (a
//! model is one workspace); [`Model::shared_synthesis_problem`] gives one that threads can share
//! ([`SharedModelProblem`], over a [`SharedModelKernel`]: each evaluation checks a clone of the
//! model out of a pool, with the parameters of its point, and gives it back), which
//! `Search::par_run` runs on all cores with `Search::run`'s report, bit for bit, and the compiled
//! mechanism's `par_run`'s (a step's result depends on its parameters, inputs, guess and
//! configuration alone, not on what the clone ran before).
//!
//! The objectives with parameter gradients (`extremum_with_gradient`, `integral_with_gradient`)
//! are written once over `SampledOf` for any `SensKernel` too: a [`ModelSampled`] of a model
//! declared with `#[kinloop(sensitivities)]` gives them with gradients as vectors, equal bit for
//! bit to the compiled ones with the same sines (`tests/objectives.rs`).
//!
//! A run-time model's errors and events name the model, its inputs and the failed or singular
//! block's unknowns and equations as the compiled mechanism's do, with owned strings (the names
//! of `Location`, `BlockInfo` and the errors are `Cow<'static, str>`: borrowed constants for a
//! compiled mechanism).
//!
//! # Drawings
//!
//! A model carries the default drawing's description of its declaration
//! ([`Model::drawing_text`]: the compiled `Mechanism::DRAWING`, from the same function of the
//! pipeline) and is the runtime's `drawing::Drawable`: [`Model::drawing`] and
//! [`Model::motion`] give `kinloop_viz`'s `DefaultDrawing` and `Motion`, whose SVG animations,
//! exposures and interactive pages (`kinloop_viz::html::html_of`) are the compiled mechanism's
//! code; over the same states they are the same bytes (`tests/drawings.rs`), grids of several
//! inputs ([`Model::grid`], for `html_grid_of`) too.
//!
//! Besides these a run-time model offers single-point solves with their analogs and
//! sensitivities ([`Model::kinematics`], [`Model::sensitivities`], [`Model::solve`]) and the
//! structure report.

#![warn(missing_docs)]

mod analysis;
mod at;
mod blocks;
mod closed;
#[cfg(test)]
mod compiled_reference;
mod confusables;
mod count;
mod dense;
mod drawing;
mod dynamics;
mod dynamics_prog;
mod extra;
mod factor;
mod finite;
mod gather;
mod levers;
mod mechanism;
mod model;
mod near;
mod newton;
mod paths;
mod scale;
mod sens_kernel;
mod sensitivities;
mod shared;
pub mod source;
mod sparse;
mod synthesis;
mod tape;

pub use analysis::ModelSampled;
pub use at::Jacobian;
pub use blocks::StepFailure;
pub use confusables::latin_lookalike;
pub use count::Count;
pub use dynamics::{ModelCycle, ModelSimulation};
pub use factor::MAX_DENSE;
pub use mechanism::ModelKernel;
pub use model::{Model, ReadError, State, StepError};
pub use paths::{ModelTraced, ParamScanConfig, ParamScanStart};
pub use sens_kernel::ModelSens;
pub use sensitivities::Sensitivities;
pub use shared::SharedModelKernel;
pub use source::{Diagnostic, Diagnostics, Level};
pub use sparse::MAX_SPARSE;
pub use synthesis::{ModelProblem, SharedModelProblem};
