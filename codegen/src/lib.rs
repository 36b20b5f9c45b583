//! Everything behind kinloop's `mechanism!` macro, as plain functions over
//! `proc_macro2::TokenStream` so they can be tested, fuzzed and benchmarked outside a compiler.
//! The folders are the pipeline's stages:
//!
//! 1. [`front`] parses the declaration ([`syntax`], with a Pratt parser for expressions,
//!    [`expr`]) after checking its size and nesting without recursion;
//! 2. [`semantics`] resolves names, checks vector/scalar types against one table of built-in
//!    functions and lowers everything into one hash-consed expression graph ([`graph`]);
//! 3. [`structure`] checks the structure (counts, mobility, Dulmage–Mendelsohn diagnosis) and
//!    orders the equations into blocks (block-lower-triangular form);
//! 4. [`plan`] differentiates the graph symbolically (compile-time forward-mode AD), one small
//!    pass per kind of derivative;
//! 5. [`emit`] writes what depends on the declaration: the named types, the straight-line
//!    kernels and the constants (everything else is generic code in the runtime).
//!
//! [`expand`] never panics: every mistake becomes a `compile_error!` at the user's span.

pub mod closed_form;
pub mod emit;
pub mod fallback;
pub mod front;
pub mod graph;
pub mod plan;
pub mod semantics;
pub mod structure;

// The first stages under their former paths (`crate::syntax`, `crate::dag`, ...).
pub use front::{expr, syntax};
pub use graph::dag;
pub use semantics::model;
pub use structure::{analysis, diag};

use proc_macro2::TokenStream;

/// What analysis produced, for tests and tools.
pub struct Analyzed {
    pub model: model::Model,
    pub blocks: Vec<structure::Block>,
    /// Warnings (unused parameters); they do not stop code generation.
    pub warnings: Vec<diag::Warning>,
}

/// Parses and checks a declaration without generating code. Never panics.
pub fn analyze(input: TokenStream) -> Result<Analyzed, syn::Error> {
    let def = syntax::parse(input)?;
    let model = model::build(def)?;
    let blocks = analysis::analyze(&model)?;
    let warnings = analysis::warnings(&model);
    Ok(Analyzed { model, blocks, warnings })
}

/// Expands a `mechanism!` invocation. Never panics. Errors come back as `compile_error!`
/// invocations, all of them together; once the mechanism's name is known they come with the
/// fallback items of [`fallback`], so code that uses the mechanism's types adds no secondary
/// errors.
pub fn expand(input: TokenStream) -> TokenStream {
    let (def, syntax_errors) = syntax::parse_recover(input);
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
