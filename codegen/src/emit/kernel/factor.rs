//! The factorisation of a block's Jacobian evaluated from the graph, and the column magnitudes
//! (entries and lever floors) it is equilibrated by.

use super::generator::Kernel;
use crate::emit::literals::lit;
use crate::graph::dag::NodeId;
use crate::plan::BlockPlan;
use proc_macro2::TokenStream;
use quote::quote;

impl Kernel<'_> {
    /// Each column's magnitude: the largest of its entries and of its lever floors.
    pub(super) fn col_scales(&self, bp: &BlockPlan) -> Vec<TokenStream> {
        let rt = &self.rt;
        (0..bp.col_scale.len())
            .map(|c| {
                let c = self.scale_operands(bp, c);
                quote!(#rt::max_abs([#(#c),*]))
            })
            .collect()
    }

    /// Column `c`'s entries, then its lever floors (a floor is never an entry: it is placed after
    /// them, so an entry's position in the list is its position among the entries).
    fn scale_operands(&self, bp: &BlockPlan, c: usize) -> Vec<TokenStream> {
        let all: Vec<NodeId> = bp.col_scale[c].iter().chain(&bp.lever_floor[c]).copied().collect();
        self.names.operands(self.g, &all).collect()
    }

    /// Column `c`'s lever floor as one optional value: `None`, the floor, or the largest of
    /// several.
    fn floor_of(&self, bp: &BlockPlan, c: usize) -> TokenStream {
        if bp.lever_floor[c].is_empty() {
            return quote!(::core::option::Option::None);
        }
        let f = self.floor_value(bp, c);
        quote!(::core::option::Option::Some(#f))
    }

    /// Column `c`'s lever floor, which it has: the floor, or the largest of several.
    pub(super) fn floor_value(&self, bp: &BlockPlan, c: usize) -> TokenStream {
        let rt = &self.rt;
        match bp.lever_floor[c].as_slice() {
            [one] => self.op(*one),
            many => {
                let f = self.names.operands(self.g, many);
                quote!(#rt::max_abs([#(#f),*]))
            }
        }
    }

    /// The factorisation of a block whose Jacobian `jrows` is evaluated from the graph, read off
    /// the Jacobian columns its entries belong to (the runtime's `Lu::factor_in_col` for a
    /// scalar block whose entry is among the column's non-zero entries: the general
    /// factorisation with fewer checks; `Inverse2::in_cols` for a 2x2 block: its explicit
    /// inverse, with the LU's pivot ratio); otherwise the general `factor_cols` with `scale`.
    pub(super) fn factor(&self, bp: &BlockPlan, jrows: &TokenStream, scale: &[TokenStream]) -> TokenStream {
        if !bp.row_scale.is_empty() {
            return self.factor_general(bp, jrows, scale);
        }
        let rt = &self.rt;
        let k = (bp.unknowns.len() == 1).then(|| bp.col_scale[0].iter().position(|&e| e == bp.jac[0][0])).flatten();
        match (bp.unknowns.len(), k) {
            (1, Some(k)) => {
                let (col, k) = (self.scale_operands(bp, 0), lit(k));
                quote!(#rt::Lu::<1>::factor_in_col([#(#col),*], #k))
            }
            (2, _) => {
                // Each column's entries beyond the block (the rows of later blocks), both padded
                // with zeros to one length (a zero changes no maximum and no sum).
                let beyond: Vec<Vec<TokenStream>> = bp
                    .col_scale
                    .iter()
                    .enumerate()
                    .map(|(c, col)| {
                        let own = [bp.jac[0][c], bp.jac[1][c]];
                        let rest: Vec<NodeId> = col.iter().copied().filter(|e| !own.contains(e)).collect();
                        self.names.operands(self.g, &rest).collect()
                    })
                    .collect();
                let len = beyond.iter().map(Vec::len).max().unwrap_or(0);
                let cols = beyond.into_iter().map(|mut v| {
                    v.resize(len, quote!(0.0));
                    quote!([#(#v),*])
                });
                if bp.lever_floor.iter().all(Vec::is_empty) {
                    quote!(#rt::Inverse2::in_cols(&#jrows, [#(#cols),*]))
                } else {
                    let floors = (0..2).map(|c| self.floor_of(bp, c));
                    quote!(#rt::Inverse2::in_cols_floored(&#jrows, [#(#cols),*], [#(#floors),*]))
                }
            }
            _ => self.factor_general(bp, jrows, scale),
        }
    }

    /// The general factorisation of `jrows`: its columns divided by `scale`, and its rows by the
    /// block's row scales first where it has them (rows of several units, see
    /// `plan::column_units`).
    pub(super) fn factor_general(&self, bp: &BlockPlan, jrows: &TokenStream, scale: &[TokenStream]) -> TokenStream {
        let (rt, n) = (&self.rt, lit(bp.unknowns.len()));
        if bp.row_scale.is_empty() {
            return quote!(#rt::Lu::<#n>::factor_cols(&#jrows, [#(#scale),*]));
        }
        let rows = self.names.operands(self.g, &bp.row_scale);
        quote!(#rt::Lu::<#n>::factor_scaled(&#jrows, [#(#rows),*], [#(#scale),*]))
    }
}
