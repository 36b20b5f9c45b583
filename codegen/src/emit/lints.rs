//! The lints the generated kernels allow.

use proc_macro2::TokenStream;
use quote::quote;

/// Lints allowed on the kernels, each because of what the generator writes: locals named after
/// the user's names (`q_X_C`), and the user's literals, which may look like an approximation of
/// a constant (`3.14`).
pub(crate) fn kernel_lints() -> TokenStream {
    quote!(#[allow(non_snake_case, clippy::approx_constant)])
}
