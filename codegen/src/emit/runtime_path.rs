//! The path generated code reaches the runtime by.

use proc_macro2::TokenStream;
use quote::quote;

/// The path generated code uses to reach the runtime.
pub fn runtime() -> TokenStream {
    quote!(::kinloop::__gen)
}
