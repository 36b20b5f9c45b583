//! The `let`s that bind the inputs and unknowns a kernel reads.

use crate::emit::names::Names;
use crate::graph::dag::Leaf;
use proc_macro2::{Ident, TokenStream};
use quote::quote;
use std::collections::HashSet;

/// `let [a, _, c] = *from;` binding only the used elements; nothing when none is used.
fn bind_used(ids: &[Ident], used: impl Fn(usize) -> bool, from: TokenStream) -> TokenStream {
    if !(0..ids.len()).any(&used) {
        return TokenStream::new();
    }
    let pats = ids.iter().enumerate().map(|(k, id)| if used(k) { quote!(#id) } else { quote!(_) });
    quote!(let [#(#pats),*] = *#from;)
}

/// Binds the inputs the kernel reads to locals (parameters are read as `self.a`).
pub fn prologue(names: &Names, used: &HashSet<Leaf>) -> TokenStream {
    bind_used(&names.inputs, |k| used.contains(&Leaf::Input(k as u16)), quote!(__x))
}

/// Binds the unknowns the kernel reads from `__q`.
pub fn bind_q(names: &Names, used: &HashSet<Leaf>) -> TokenStream {
    bind_used(&names.unknowns, |k| used.contains(&Leaf::Unknown(k as u16)), quote!(__q))
}
