//! The slot of a Newton block's evaluation.

use proc_macro2::Ident;
use quote::format_ident;

/// The slot holding Newton block `b`'s evaluation (`__ev{b}`: residuals, Jacobian, kept
/// values), which the runtime's iteration updates in place.
pub(super) fn evaluation_ident(b: usize) -> Ident {
    format_ident!("__ev{}", b)
}
