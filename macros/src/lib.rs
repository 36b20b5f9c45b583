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

/// What a generated struct derives as `Serialize` when kinloop is built without its feature
/// `serde`: nothing. It accepts the struct's `serde` attributes, so that the expansion of
/// `mechanism!` is the same with and without the feature (see `kinloop::__gen`).
#[doc(hidden)]
#[proc_macro_derive(NoSerialize, attributes(serde))]
pub fn no_serialize(_item: TokenStream) -> TokenStream {
    TokenStream::new()
}

/// What a generated struct derives as `Deserialize` without kinloop's feature `serde`: nothing
/// (see `NoSerialize`).
#[doc(hidden)]
#[proc_macro_derive(NoDeserialize, attributes(serde))]
pub fn no_deserialize(_item: TokenStream) -> TokenStream {
    TokenStream::new()
}
