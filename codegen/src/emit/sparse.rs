//! Emission for large sparse Newton blocks (see [`crate::plan::sparse`]): the block's symbolic
//! factorisation as one `static` table per kernel, and its Jacobian as the structural non-zeros
//! only, so that the generated code grows with the number of non-zeros, not with `n^2`.

use super::lit;
use super::names::Names;
use crate::graph::dag::{Graph, NodeId};
use crate::plan::sparse::Sparse;
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

/// The name of block `b`'s pattern table.
pub fn pattern_ident(b: usize) -> Ident {
    format_ident!("__SPARSE_PATTERN{}", b)
}

/// `static __SPARSE_PATTERNb: SparsePattern = ...;` for block `b`.
pub fn pattern_item(sp: &Sparse, b: usize, rt: &TokenStream) -> TokenStream {
    let id = pattern_ident(b);
    let col = sp.entries.iter().map(|&(_, c)| c as u16);
    let (row_ptr, slot, prow, pcol, diag) = (&sp.row_ptr, &sp.slot, &sp.prow, &sp.pcol, &sp.diag);
    let (l_ptr, l_slot, l_row, u_ptr, u_slot, u_col, upd) =
        (&sp.l_ptr, &sp.l_slot, &sp.l_row, &sp.u_ptr, &sp.u_slot, &sp.u_col, &sp.upd);
    let odd = sp.odd;
    quote! {
        static #id: #rt::SparsePattern = #rt::SparsePattern {
            row_ptr: &[#(#row_ptr),*],
            col: &[#(#col),*],
            slot: &[#(#slot),*],
            prow: &[#(#prow),*],
            pcol: &[#(#pcol),*],
            odd: #odd,
            diag: &[#(#diag),*],
            l_ptr: &[#(#l_ptr),*],
            l_slot: &[#(#l_slot),*],
            l_row: &[#(#l_row),*],
            u_ptr: &[#(#u_ptr),*],
            u_slot: &[#(#u_slot),*],
            u_col: &[#(#u_col),*],
            upd: &[#(#upd),*],
        };
    }
}

/// The type `SparseJac<n, nnz, nlu>` of the block's Jacobian.
pub fn jac_type(sp: &Sparse, n: usize, rt: &TokenStream) -> TokenStream {
    let (n, nnz, nlu) = (lit(n), lit(sp.entries.len()), lit(sp.nlu));
    quote!(#rt::SparseJac<#n, #nnz, #nlu>)
}

/// The block's Jacobian from the nodes of its dense rows `jac`: its structural non-zeros only.
pub fn jac_value(
    sp: &Sparse,
    b: usize,
    g: &Graph,
    names: &Names,
    jac: &[Vec<NodeId>],
    rt: &TokenStream,
) -> TokenStream {
    let values = sp.entries.iter().map(|&(r, c)| names.operand(g, jac[r][c]));
    let (ty, id) = (jac_type(sp, jac.len(), rt), pattern_ident(b));
    quote!(<#ty>::new([#(#values),*], &#id))
}
