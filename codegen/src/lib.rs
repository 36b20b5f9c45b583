//! Everything behind kinloop's `mechanism!` macro, as plain functions over
//! `proc_macro2::TokenStream` so they can be tested, fuzzed and benchmarked outside a compiler:
//! [`expand`] is what the macro runs; [`analyze`] stops after the checks and returns the checked
//! [`model`], the solve order in [`Block`]s and the warnings ([`diag`]).
//!
//! The pipeline's stages are the crate's private folders:
//!
//! 1. `front` parses the declaration (`declaration`) into its syntax tree (`syntax`), with a
//!    Pratt parser for expressions (`expr`), after checking its size and nesting without
//!    recursion;
//! 2. `semantics` resolves names, checks vector/scalar types against one table of built-in
//!    functions and lowers everything into one hash-consed expression graph (`graph`);
//! 3. `structure` checks the structure (counts, mobility, Dulmage–Mendelsohn diagnosis) and
//!    orders the equations into blocks (block-lower-triangular form);
//! 4. `plan` differentiates the graph symbolically (compile-time forward-mode AD), one small
//!    pass per kind of derivative, and decides once how each block is solved (`solve`: directly,
//!    in closed form for the classical Assur groups, `closed_form`, or by Newton);
//! 5. `emit` writes what depends on the declaration: the named types, the straight-line
//!    kernels and the constants (everything else is generic code in the runtime).
//!
//! [`expand`] never panics: every mistake becomes a `compile_error!` at the user's span, with
//! the named types of the mechanism still declared (`fallback`) so that the user's code around
//! it adds no secondary errors.

#![warn(missing_docs)]

// The crate's interface is `expand` (what the macro runs), `analyze` (for tests and tools) and
// `plan_declaration` (for back ends other than the emitter: the run-time evaluator of
// `kinloop-model`). The plan it returns and the expression graph the plan owns are reachable,
// hidden from the documentation: an interface between the workspace's crates, not a stable one,
// so the pipeline can change without breaking anyone outside it. The other stages are private.
pub(crate) mod emit;
pub(crate) mod fallback;
pub(crate) mod front;
#[doc(hidden)]
pub mod graph;
#[doc(hidden)]
pub mod plan;
pub(crate) mod semantics;
pub(crate) mod serde_derive;
pub(crate) mod structure;

// What `analyze` returns is public: the checked model, the blocks and the warnings.
/// The declared dynamics items (bodies, loads, gravity) of a checked model, which a run-time
/// back end evaluates as the emitted `mass_model` does.
#[doc(hidden)]
pub use semantics::dynamics;
pub use semantics::model;
/// The serde derives of the structs `mechanism!` generates (kinloop's feature `serde`): serde's
/// impls with every number written and read as kinloop writes and reads numbers.
#[doc(hidden)]
pub use serde_derive::{derive_deserialize, derive_serialize};
pub use structure::{Block, diag};

/// The message for a binary or octal number with a digit its base does not have (`0b102`), which
/// the run-time reader's lexer refuses: the one `mechanism!` gives.
#[doc(hidden)]
pub use front::expr::digit_outside_its_base;

use front::declaration;
use proc_macro2::TokenStream;
use structure::analysis;

/// What analysis produced, for tests and tools.
pub struct Analyzed {
    /// The checked model: names resolved, equations and outputs lowered to one graph.
    pub model: model::Model,
    /// The blocks in solve order (block-lower-triangular form): each block's unknowns are
    /// solved together from its equations, once the blocks before it are solved.
    pub blocks: Vec<Block>,
    /// Warnings (unused parameters); they do not stop code generation.
    pub warnings: Vec<diag::Warning>,
}

/// Parses and checks a declaration without generating code. Never panics.
pub fn analyze(input: TokenStream) -> Result<Analyzed, syn::Error> {
    let def = declaration::parse(input)?;
    let model = model::build(def)?;
    let blocks = analysis::analyze(&model)?;
    let warnings = analysis::warnings(&model);
    Ok(Analyzed { model, blocks, warnings })
}

/// What planning produced: the checked declaration and the plan the emitter writes Rust from,
/// for back ends that evaluate the plan instead (see `kinloop-model`).
pub struct Planned {
    /// The checked model (its graph is moved into the plan: read expressions from `plan.graph`).
    pub model: model::Model,
    /// The blocks in solve order.
    pub blocks: Vec<Block>,
    /// The computation plan: every derivative, and how each block is solved.
    pub plan: plan::Plan,
    /// Warnings (unused parameters).
    pub warnings: Vec<diag::Warning>,
}

/// Parses, checks and plans a declaration exactly as [`expand`] does before it emits code: the
/// same front end, checks, structure analysis and plan. Never panics; the first error comes back
/// as the macro would report it (message and span).
pub fn plan_declaration(input: TokenStream) -> Result<Planned, syn::Error> {
    let Analyzed { mut model, blocks, warnings } = analyze(input)?;
    let sensitivities = model.options.sensitivities.is_some();
    let plan = plan::build(&mut model, &blocks, sensitivities);
    Ok(Planned { model, blocks, plan, warnings })
}

/// The decomposition of a planned declaration in words, as the generated constant
/// `Name::DECOMPOSITION` has it: counts, mobility, and per block how it is solved, its unknowns
/// and its equations.
pub fn decomposition(planned: &Planned) -> String {
    emit::describe::decomposition(&planned.model, &planned.plan)
}

/// The default drawing's description of a planned declaration, in the runtime's text format
/// (`kinloop_runtime::drawing`): the text the generated constant `Mechanism::DRAWING` holds,
/// from the same function.
pub fn drawing(planned: &Planned) -> String {
    emit::drawing::description(&planned.model)
}

/// Expands a `mechanism!` invocation. Never panics. Errors come back as `compile_error!`
/// invocations, all of them together; once the mechanism's name is known they come with the
/// mechanism's named types, declared from the syntax alone, so code that uses those types adds
/// no secondary errors.
///
/// The facade's wrapper begins the invocation with the marker `#![crate = $crate]`: the
/// expansion then reaches the runtime through that path, which names kinloop however the user's
/// crate depends on it (renamed, or through a crate that re-exports it). Without the marker it
/// names `::kinloop`.
pub fn expand(input: TokenStream) -> TokenStream {
    let (root, declaration) = emit::runtime_path::split_root(input);
    emit::runtime_path::with_root(root, || expand_declaration(declaration))
}

/// [`expand`] once the facade's path is set.
fn expand_declaration(input: TokenStream) -> TokenStream {
    let (def, syntax_errors) = declaration::parse_recover(input);
    let Some(def) = def else {
        return syntax_errors.map(|e| e.to_compile_error()).unwrap_or_default();
    };
    let shape = fallback::Shape::of(&def);
    if let Some(e) = syntax_errors {
        // Names are not resolved after a syntax error: an item that failed to parse may define
        // a name that the others use, and every such use would be a misleading error.
        let mut out = e.to_compile_error();
        out.extend(shape.items(None));
        return out;
    }
    let mut model = match model::build(def) {
        Ok(m) => m,
        Err(e) => {
            let mut out = e.to_compile_error();
            out.extend(shape.items(None));
            return out;
        }
    };
    let warnings = diag::to_tokens(&analysis::warnings(&model), &model.name);
    match analysis::analyze(&model) {
        Ok(blocks) => {
            let sensitivities = model.options.sensitivities.is_some();
            let plan = plan::build(&mut model, &blocks, sensitivities);
            let mut out = emit::generate(&model, &plan);
            out.extend(warnings);
            out
        }
        Err(e) => {
            let mut out = e.to_compile_error();
            out.extend(shape.items(plan::model_defaults(&model)));
            out.extend(warnings);
            out
        }
    }
}
