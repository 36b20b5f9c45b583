//! The `mechanism!` procedural macro of [kinloop](https://docs.rs/kinloop). The logic lives in
//! `kinloop-codegen` so it can be tested and benchmarked as plain functions; this crate only
//! adapts it to the compiler.

#![warn(missing_docs)]

use proc_macro::TokenStream;

/// Declares a mechanism by its closed vector loops: the grammar, an example and what is
/// generated are on `kinloop::mechanism`, the complete reference in `kinloop::language`.
///
/// It is called through `kinloop::mechanism!`, a `macro_rules!` wrapper that begins the input
/// with `#![crate = $crate]`: the expansion reaches kinloop by that path, which holds however
/// the user's crate names kinloop. Without the marker it names `::kinloop`.
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

/// What a generated struct derives as `Serialize` with kinloop's feature `serde`: serde's
/// `Serialize`, with every `f64` within written as kinloop writes numbers (a non-finite one as
/// `"NaN"`, `"inf"` or `"-inf"` in JSON, not `null`), alone as inside a state (see
/// `kinloop::__gen`).
#[doc(hidden)]
#[proc_macro_derive(FloatsSerialize, attributes(serde))]
pub fn floats_serialize(item: TokenStream) -> TokenStream {
    kinloop_codegen::derive_serialize(item.into()).into()
}

/// What a generated struct derives as `Deserialize` with kinloop's feature `serde`: serde's
/// `Deserialize`, reading every `f64` within as kinloop reads numbers (a number, `"NaN"`,
/// `"inf"`, `"-inf"`, or `null` as NaN; see `FloatsSerialize`).
#[doc(hidden)]
#[proc_macro_derive(FloatsDeserialize, attributes(serde))]
pub fn floats_deserialize(item: TokenStream) -> TokenStream {
    kinloop_codegen::derive_deserialize(item.into()).into()
}
