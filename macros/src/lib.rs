//! The `mechanism!` procedural macro of [kinloop](https://docs.rs/kinloop). The logic lives in
//! `kinloop-codegen` so it can be tested and benchmarked as plain functions; this crate only
//! adapts it to the compiler.

#![warn(missing_docs)]

use proc_macro::TokenStream;

/// Declares a mechanism by its closed vector loops: the grammar, an example and what is
/// generated are on `kinloop::mechanism`, the complete reference in `kinloop::language`.
#[proc_macro]
pub fn mechanism(input: TokenStream) -> TokenStream {
    kinloop_codegen::expand(input.into()).into()
}
