//! Emission for large sparse Newton blocks (see [`crate::plan::sparse`]), once per mechanism
//! beside its types: the block's symbolic factorisation as one `static` table, its numeric
//! steps (load, elimination, substitution) as straight-line code over the factor's slots, and
//! its Jacobian as the structural non-zeros only, so that the generated code grows with the
//! number of non-zeros and fill, not with `n^2`.

use super::literals::lit;
use super::names::Names;
use crate::graph::dag::{Graph, NodeId};
use crate::plan::Plan;
use crate::plan::solve::Solve;
use crate::plan::sparse::Sparse;
use proc_macro2::{Ident, TokenStream};
use quote::{ToTokens, format_ident, quote};

/// The name of mechanism `m`'s block `b`'s pattern table, `__mSparsePatternb`.
pub fn pattern_ident(m: &str, b: usize) -> Ident {
    format_ident!("__{}SparsePattern{}", m, b)
}

/// The name of mechanism `m`'s block `b`'s straight-line numeric steps, `__mSparseStepsb`.
pub fn steps_ident(m: &str, b: usize) -> Ident {
    format_ident!("__{}SparseSteps{}", m, b)
}

/// The most updates a block's factorisation may have for its numeric steps to be emitted as
/// straight-line code (one statement each). Beyond, the runtime's loops over the pattern's
/// tables (`Tables`, the same arithmetic) factorise it, so that a large, strongly coupled
/// declaration cannot turn its fill into code without bound. The ring of 64 four-bar loops of
/// the benchmarks has a few thousand.
pub const MAX_STRAIGHT_LINE_UPDATES: usize = 1 << 16;

/// Whether block `sp`'s numeric steps are emitted as straight-line code.
fn straight_line(sp: &Sparse) -> bool {
    sp.upd.len() <= MAX_STRAIGHT_LINE_UPDATES
}

/// The name of the type of mechanism `m`'s block `b`'s Jacobian, `__mSparseJacb`.
pub fn jac_ident(m: &str, b: usize) -> Ident {
    format_ident!("__{}SparseJac{}", m, b)
}

/// The items of every sparse block of a mechanism named `m` (see [`pattern_item`]).
pub fn items(plan: &Plan, m: &str, rt: &TokenStream) -> TokenStream {
    let mut out = TokenStream::new();
    for (b, bp) in plan.blocks.iter().enumerate() {
        if let Solve::NewtonSparse(sp) = &bp.solve {
            out.extend(pattern_item(sp, m, b, bp.unknowns.len(), rt));
        }
    }
    out
}

/// `static __mSparsePatternb: SparsePattern = ...;` for block `b` of mechanism `m`, its numeric
/// steps (see [`steps_item`]) and the type of its Jacobian: private items of the module that
/// declares the mechanism, once for all its kernels.
pub fn pattern_item(sp: &Sparse, m: &str, b: usize, n: usize, rt: &TokenStream) -> TokenStream {
    let steps = if straight_line(sp) { steps_item(sp, m, b, rt) } else { TokenStream::new() };
    let (jac, ty) = (jac_ident(m, b), jac_type(sp, m, b, n, rt));
    let id = pattern_ident(m, b);
    let col = sp.entries.iter().map(|&(_, c)| c as u16);
    let (row_ptr, slot, prow, pcol, diag) = (&sp.row_ptr, &sp.slot, &sp.prow, &sp.pcol, &sp.diag);
    let (l_ptr, l_slot, l_row, u_ptr, u_slot, u_col, upd) =
        (&sp.l_ptr, &sp.l_slot, &sp.l_row, &sp.u_ptr, &sp.u_slot, &sp.u_col, &sp.upd);
    let odd = sp.odd;
    quote! {
        #[doc(hidden)]
        #[allow(non_upper_case_globals)]
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
        #[doc(hidden)]
        #[allow(non_camel_case_types)]
        type #jac = #ty;
        #steps
    }
}

/// `struct __mSparseStepsb;` implementing `SparseSteps` for block `b`'s pattern as straight-line
/// code: every slot a constant index (no table read, no loop, no bounds check), one statement
/// per entry, pivot, multiplier and update, so its length is linear in the non-zeros and fill.
/// The arithmetic is the tables' (`kinloop_runtime`'s `Tables`), operation for operation: the
/// same factor bit for bit.
pub fn steps_item(sp: &Sparse, m: &str, b: usize, rt: &TokenStream) -> TokenStream {
    let (id, n, nlu, pattern) = (steps_ident(m, b), lit(sp.diag.len()), lit(sp.nlu), pattern_ident(m, b));
    // Load: the factor's slots in order, each written with an entry times its row's and
    // column's scale, or a zero of fill.
    let mut at: Vec<Option<usize>> = vec![None; sp.nlu];
    for (e, &s) in sp.slot.iter().enumerate() {
        at[s as usize] = Some(e);
    }
    let load = at.iter().enumerate().map(|(s, e)| {
        let s = lit(s);
        match *e {
            Some(e) => {
                let (r, c) = sp.entries[e];
                let (e, r, c) = (lit(e), lit(r), lit(c));
                quote!(__a[#s] = #rt::scaled(__v[#e], __r[#r], __c[#c]);)
            }
            None => quote!(__a[#s] = 0.0;),
        }
    });
    // Elimination: per pivot its test, its reciprocal, then per row below it the multiplier
    // and the updates of that row's entries right of the pivot.
    let mut elim = TokenStream::new();
    let mut upd = sp.upd.iter();
    for k in 0..sp.diag.len() {
        let (l, u) = (sp.l_ptr[k] as usize..sp.l_ptr[k + 1] as usize, sp.u_ptr[k] as usize..sp.u_ptr[k + 1] as usize);
        let (d, kl) = (lit(sp.diag[k] as usize), lit(k));
        let lower: Vec<_> = sp.l_slot[l.clone()].iter().map(|&s| lit(s as usize)).collect();
        elim.extend(quote!(let __i = __p.pivot(__a[#d], [#(__a[#lower]),*]); __d[#kl] = __i;));
        for s in &lower {
            let ups = sp.u_slot[u.clone()].iter().zip(upd.by_ref()).map(|(&u, &t)| {
                let (u, t) = (lit(u as usize), lit(t as usize));
                quote!(__a[#t] -= __m * __a[#u];)
            });
            elim.extend(quote!(let __m = __a[#s] * __i; __a[#s] = __m; #(#ups)*));
        }
    }
    // Substitution: forward through the columns of `L`, back through the rows of `U`.
    let mut subst = TokenStream::new();
    for k in 0..sp.diag.len() {
        let kl = lit(k);
        for (&s, &i) in
            sp.l_slot[sp.l_ptr[k] as usize..sp.l_ptr[k + 1] as usize].iter().zip(&sp.l_row[sp.l_ptr[k] as usize..])
        {
            let (s, i) = (lit(s as usize), lit(i as usize));
            subst.extend(quote!(__z[#i] -= __a[#s] * __z[#kl];));
        }
    }
    for k in (0..sp.diag.len()).rev() {
        let kl = lit(k);
        let u = sp.u_ptr[k] as usize..sp.u_ptr[k + 1] as usize;
        let terms: Vec<_> = sp.u_slot[u.clone()]
            .iter()
            .zip(&sp.u_col[u])
            .map(|(&s, &j)| {
                let (s, j) = (lit(s as usize), lit(j as usize));
                quote!(- __a[#s] * __z[#j])
            })
            .collect();
        subst.extend(if terms.is_empty() {
            quote!(__z[#kl] *= __d[#kl];)
        } else {
            quote!(__z[#kl] = (__z[#kl] #(#terms)*) * __d[#kl];)
        });
    }
    quote! {
        #[doc(hidden)]
        #[allow(non_camel_case_types)]
        struct #id;
        // `a -= m * b` as the tables write it, not `mul_add`: the same factor bit for bit.
        #[allow(clippy::suboptimal_flops)]
        impl #rt::SparseSteps<#n, #nlu> for #id {
            #[inline]
            fn load<const NNZ: ::core::primitive::usize>(
                __pattern: &#rt::SparsePattern,
                __v: &[::core::primitive::f64; NNZ],
                __r: &[::core::primitive::f64; #n],
                __c: &[::core::primitive::f64; #n],
                __a: &mut [::core::primitive::f64; #nlu],
            ) {
                // The code below is this block's pattern's: paired with another, it would be wrong.
                ::core::debug_assert!(::core::ptr::eq(__pattern, &#pattern));
                #(#load)*
            }
            #[inline]
            fn eliminate(
                _: &#rt::SparsePattern,
                __a: &mut [::core::primitive::f64; #nlu],
                __d: &mut [::core::primitive::f64; #n],
                __det: &mut ::core::primitive::f64,
                __negative: &mut ::core::primitive::bool,
            ) -> ::core::option::Option<::core::primitive::f64> {
                let mut __p = #rt::Pivots::new(*__det, *__negative);
                #elim
                __p.finish(__det, __negative)
            }
            #[inline]
            fn substitute(
                _: &#rt::SparsePattern,
                __a: &[::core::primitive::f64; #nlu],
                __d: &[::core::primitive::f64; #n],
                __z: &mut [::core::primitive::f64; #n],
            ) {
                #subst
            }
        }
    }
}

/// The type `SparseJac<n, nnz, nlu, __mSparseStepsb>` of block `b`'s Jacobian (`Tables` for
/// its steps beyond [`MAX_STRAIGHT_LINE_UPDATES`]).
fn jac_type(sp: &Sparse, m: &str, b: usize, n: usize, rt: &TokenStream) -> TokenStream {
    let (n, nnz, nlu) = (lit(n), lit(sp.entries.len()), lit(sp.nlu));
    let steps = if straight_line(sp) { steps_ident(m, b).into_token_stream() } else { quote!(#rt::Tables) };
    quote!(#rt::SparseJac<#n, #nnz, #nlu, #steps>)
}

/// The block's Jacobian from the nodes of its dense rows `jac`: its structural non-zeros only.
pub fn jac_value(sp: &Sparse, b: usize, g: &Graph, names: &Names, jac: &[Vec<NodeId>]) -> TokenStream {
    let values = sp.entries.iter().map(|&(r, c)| names.operand(g, jac[r][c]));
    let (ty, id) = (jac_ident(&names.mechanism, b), pattern_ident(&names.mechanism, b));
    quote!(#ty::new([#(#values),*], &#id))
}
