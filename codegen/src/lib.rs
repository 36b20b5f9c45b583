//! Everything behind kinloop's `mechanism!` macro, as plain functions over
//! `proc_macro2::TokenStream` so they can be tested, fuzzed and benchmarked outside a compiler:
//!
//! 1. [`syntax`] parses the declaration (with a Pratt parser for expressions, [`expr`]);
//! 2. [`model`] resolves names, checks vector/scalar types and lowers everything into one
//!    hash-consed expression graph ([`dag`]);
//! 3. [`analysis`] checks the structure (counts, mobility, Dulmage–Mendelsohn diagnosis) and
//!    orders the equations into blocks ([`structure`]);
//! 4. [`plan`] differentiates the graph symbolically (compile-time forward-mode AD);
//! 5. [`items`] and [`solver`] emit straight-line Rust.
//!
//! [`expand`] never panics: every mistake becomes a `compile_error!` at the user's span.

pub mod analysis;
pub mod dag;
pub mod emit;
pub mod expr;
pub mod items;
pub mod model;
pub mod plan;
pub mod solver;
pub mod structure;
pub mod syntax;

use proc_macro2::TokenStream;

/// What analysis produced, for tests and tools.
pub struct Analyzed {
    pub model: model::Model,
    pub blocks: Vec<structure::Block>,
}

/// Parses and checks a declaration without generating code.
pub fn analyze(input: TokenStream) -> Result<Analyzed, syn::Error> {
    let def = syntax::parse(input)?;
    let model = model::build(def)?;
    let blocks = analysis::analyze(&model)?;
    Ok(Analyzed { model, blocks })
}

/// Expands a `mechanism!` invocation. Errors come back as `compile_error!` invocations.
pub fn expand(input: TokenStream) -> TokenStream {
    match analyze(input) {
        Ok(Analyzed { mut model, blocks }) => {
            let plan = plan::build(&mut model, &blocks);
            items::generate(&model, &plan)
        }
        Err(e) => e.to_compile_error(),
    }
}
