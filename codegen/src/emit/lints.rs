//! The lints the generated kernels allow.

use proc_macro2::TokenStream;
use quote::quote;

/// Lints allowed on the kernels, each because of what the generator writes: locals named after
/// the user's names (`q_X_C`), and the user's literals, which may look like an approximation of
/// a constant (`3.14`). And `clippy::suboptimal_flops` (of `clippy::nursery`, which a user may
/// turn on in their crate): the kernels are sums of products as the declaration and its
/// derivatives write them, and `mul_add` is no better there. Without the target feature `fma` it
/// is a call to libm's software `fma`, many times slower than a multiply and an add, in every
/// kernel; and it rounds once where the run-time model (`kinloop-model`), which evaluates the
/// same graph, rounds twice, and the two agree bit for bit (`model/tests/cross_scope_pairs.rs`).
pub(crate) fn kernel_lints() -> TokenStream {
    quote!(#[allow(non_snake_case, clippy::approx_constant, clippy::suboptimal_flops)])
}
