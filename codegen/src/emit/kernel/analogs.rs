//! The analogs of each block (velocity, acceleration) and its parameter sensitivities, all on
//! one factorisation of its Jacobian: the position solve's where it made one, otherwise made
//! with the velocity analogs.

use super::evaluation_slot::evaluation_ident;
use super::generator::Kernel;
use super::mode::Mode;
use super::scopes::{keeps_lu, stage_rows};
use crate::emit::literals::lit;
use crate::emit::names::float_arg;
use crate::emit::sparse;
use crate::plan::pairs;
use crate::plan::solve::Solve;
use crate::plan::sparse::Sparse;
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

impl Kernel<'_> {
    /// Velocity analogs of block `b`, factorising its Jacobian when the position solve did not
    /// (the factorisation is reused for accelerations and sensitivities).
    pub(super) fn velocity_block(&self, b: usize) -> TokenStream {
        let bp = &self.plan.blocks[b];
        let rt = &self.rt;
        let (n, ni, bl) = (lit(bp.unknowns.len()), lit(self.plan.ni), lit(b));
        let (lu, rv) = (format_ident!("__lu{}", b), format_ident!("__rv{}", b));
        let mut out = self.lets(self.scopes.vel[b]);
        let rows = self.names.rows(self.g, &bp.vel);
        out.extend(quote!(let #rv: [[::core::primitive::f64; #ni]; #n] = #rows;));
        let at = self.mode == Mode::At;
        // The factorisation the analogs solve with: the position solve's where it made one
        // (linear blocks) or kept Newton's, otherwise made here.
        out.extend(match &bp.solve {
            Solve::Fixed { coefficient, .. } if at => {
                let c = float_arg(*coefficient);
                quote!(let #lu = #rt::Fixed(#c);)
            }
            Solve::Fixed { .. } => TokenStream::new(),
            Solve::Linear { .. } if at => self.dense_factor(b, true, &rv),
            Solve::Linear { .. } => TokenStream::new(),
            // No Newton evaluation to read.
            Solve::ClosedForm(_) => self.dense_factor(b, true, &rv),
            Solve::Newton => self.dense_factor(b, at, &rv),
            Solve::NewtonSparse(sp) => self.sparse_factor(b, sp, &rv),
        });
        let vs = bp.unknowns.iter().map(|&u| {
            let v = (0..self.plan.ni).map(|i| self.names.tan(u, i));
            quote!([#(#v),*])
        });
        out.extend(quote! {
            __health.note(#bl, &#lu);
            let [#(#vs),*] = #lu.solve_cols(#rv);
        });
        out
    }

    /// The factorisation of a dense block for its analogs, checked: of its Jacobian evaluated
    /// from the graph (`from_graph`), or of the Newton evaluation's, where the runtime may have
    /// kept the factorisation of the final correction.
    fn dense_factor(&self, b: usize, from_graph: bool, rv: &Ident) -> TokenStream {
        let (bp, rt, bl) = (&self.plan.blocks[b], &self.rt, lit(b));
        let (n, lu) = (lit(bp.unknowns.len()), format_ident!("__lu{}", b));
        let j = if from_graph {
            self.names.rows(self.g, &bp.jac)
        } else {
            let at = evaluation_ident(b);
            quote!(#at.j)
        };
        let scale = self.col_scales(bp);
        // The factorisation the runtime made at the block's final evaluation, when it kept
        // it; otherwise made here.
        let factor = if from_graph {
            let f = self.factor(bp, &quote!(__j), &scale);
            quote!(let #lu = #f;)
        } else if keeps_lu(self.mode, bp) {
            TokenStream::new()
        } else {
            let f = self.factor_general(bp, &quote!(__j), &scale);
            quote!(let #lu = #f;)
        };
        // Deferred, the end tests the smallest pivot ratio `__health` records.
        let checked = self.deferred.then(|| quote!(__CHECKED &&));
        quote! {
            let __j: [[::core::primitive::f64; #n]; #n] = #j;
            #factor
            if #checked !(#lu.pivot_ratio() >= __cfg.singular_tol) {
                let __r = #rt::first_bad_row(__j).or(#rt::first_bad_row(#rv));
                return ::core::result::Result::Err(#rt::singular(self, #bl, #lu.pivot_ratio(), __cfg, __x, __r));
            }
        }
    }

    /// The factorisation of a sparse block for its analogs: the Newton evaluation's Jacobian,
    /// written over the slot its Newton steps factorised into, or (mode `At`) its non-zeros at
    /// the given position, into a slot made here.
    fn sparse_factor(&self, b: usize, sp: &Sparse, rv: &Ident) -> TokenStream {
        let (bp, rt, bl) = (&self.plan.blocks[b], &self.rt, lit(b));
        let (lu, scale) = (format_ident!("__lu{}", b), self.col_scales(bp));
        let factor = if bp.row_scale.is_empty() {
            quote!(__j.factor_cols_into(&mut #lu, &[#(#scale),*]);)
        } else {
            let rows = self.names.operands(self.g, &bp.row_scale);
            quote!(__j.factor_scaled_into(&mut #lu, &[#(#rows),*], &[#(#scale),*]);)
        };
        let (j, slot) = if self.mode == Mode::At {
            (
                sparse::jac_value(sp, b, self.g, self.names, &bp.jac),
                quote!(let mut #lu = #rt::BlockJacobian::work(&__j);),
            )
        } else {
            // Borrowed: the Jacobian of a large block is kilobytes.
            let at = evaluation_ident(b);
            (quote!(&#at.j), TokenStream::new())
        };
        quote! {
            let __j = #j;
            #slot
            #factor
            if !(#lu.pivot_ratio() >= __cfg.singular_tol) {
                let __r = __j.first_bad_row().or(#rt::first_bad_row(#rv));
                return ::core::result::Result::Err(#rt::singular(self, #bl, #lu.pivot_ratio(), __cfg, __x, __r));
            }
        }
    }

    pub(super) fn acceleration_block(&self, b: usize) -> TokenStream {
        let bp = &self.plan.blocks[b];
        let np = pairs(self.plan.ni);
        let (n, npl, lu) = (lit(bp.unknowns.len()), lit(np.len()), format_ident!("__lu{}", b));
        let mut out = self.lets(self.scopes.acc[b]);
        let rows = self.names.rows(self.g, &bp.acc);
        let ws = bp.unknowns.iter().map(|&u| {
            let w = np.iter().map(|&(i, j)| self.names.tan2(u, i, j));
            quote!([#(#w),*])
        });
        out.extend(quote! {
            let __ra: [[::core::primitive::f64; #npl]; #n] = #rows;
            let [#(#ws),*] = #lu.solve_cols(__ra);
        });
        out
    }

    /// Parameter sensitivities of block `b` at `stage` (positions, first or second analogs):
    /// the same factorisation, one more set of right-hand sides.
    pub(super) fn sensitivity_block(&self, stage: usize, b: usize) -> TokenStream {
        let bp = &self.plan.blocks[b];
        let Some(st) = &bp.sens else { return TokenStream::new() };
        let (ni, npar) = (self.plan.ni, self.plan.np);
        let slots: Vec<(usize, usize)> = match stage {
            0 => vec![(0, 0)],
            1 => (0..ni).map(|i| (i, 0)).collect(),
            _ => pairs(ni),
        };
        let (n, width, lu) = (lit(bp.unknowns.len()), lit(slots.len() * npar), format_ident!("__lu{}", b));
        let mut out = self.lets(self.scopes.sens[stage][b]);
        let rows = self.names.rows(self.g, stage_rows(st, stage));
        let binds = bp.unknowns.iter().map(|&u| {
            let ids = slots.iter().flat_map(|&(i, j)| {
                (0..npar).map(move |k| match stage {
                    0 => self.names.sens_q(u, k),
                    1 => self.names.sens_v(u, i, k),
                    _ => self.names.sens_a(u, i, j, k),
                })
            });
            quote!([#(#ids),*])
        });
        out.extend(quote! {
            let __rs: [[::core::primitive::f64; #width]; #n] = #rows;
            let [#(#binds),*] = #lu.solve_cols(__rs);
        });
        out
    }
}
