//! Each block's position solve, as its plan's `Solve` says: one division, one linear solve,
//! the straight-line solve of a closed form, or Newton over the block's evaluation.

use super::evaluation_slot::evaluation_ident;
use super::generator::Kernel;
use super::mode::Mode;
use super::scopes::keeps_lu;
use crate::emit::literals::lit;
use crate::emit::names::{NearCall, float_arg};
use crate::emit::{closed_form, sparse};
use crate::graph::dag::NodeId;
use crate::plan::BlockPlan;
use crate::plan::closed_form::Recognised;
use crate::plan::solve::Solve;
use crate::plan::sparse::Sparse;
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

impl Kernel<'_> {
    /// The position solve of block `b`, after the values computed before it.
    pub(super) fn position_block(&self, b: usize) -> TokenStream {
        let bp = &self.plan.blocks[b];
        let mut out = self.lets(self.scopes.pre[b]);
        let qs = self.unknowns_of(bp);
        out.extend(match &bp.solve {
            Solve::Fixed { coefficient, rhs } => {
                // A constant, non-zero coefficient: one division, never singular.
                let (rt, lu) = (&self.rt, format_ident!("__lu{}", b));
                let (c, rhs) = (float_arg(*coefficient), self.op(*rhs));
                quote! {
                    let #lu = #rt::Fixed(#c);
                    let [#(#qs),*] = #lu.solve([#rhs]);
                }
            }
            Solve::Linear { rhs } => self.linear_block(b, bp, rhs, &qs),
            Solve::ClosedForm(c) => self.closed_block(b, c),
            Solve::Newton => self.newton_block(b, bp, None, &qs),
            Solve::NewtonSparse(sp) => self.newton_block(b, bp, Some(sp), &qs),
        });
        out
    }

    /// One linear solve, `J q = rhs`, failing where `J` is singular.
    fn linear_block(&self, b: usize, bp: &BlockPlan, rhs: &[NodeId], qs: &[&Ident]) -> TokenStream {
        let rt = &self.rt;
        let (bl, lu) = (lit(b), format_ident!("__lu{}", b));
        let scale = self.col_scales(bp);
        let jrows = self.names.rows(self.g, &bp.jac);
        let aug: Vec<Vec<NodeId>> =
            bp.jac.iter().zip(rhs).map(|(row, &r)| row.iter().copied().chain([r]).collect()).collect();
        let aug = self.names.rows(self.g, &aug);
        let rhs = self.names.operands(self.g, rhs);
        let factor = self.factor(bp, &jrows, &scale);
        quote! {
            let #lu = #factor;
            if !(#lu.pivot_ratio() >= __cfg.singular_tol) {
                let __row = #rt::first_bad_row(#aug);
                return ::core::result::Result::Err(#rt::singular(self, #bl, #lu.pivot_ratio(), __cfg, __x, __row));
            }
            let [#(#qs),*] = #lu.solve([#(#rhs),*]);
        }
    }

    /// Newton over the block's evaluation, dense or (with `sparse`) over its sparse
    /// factorisation.
    fn newton_block(&self, b: usize, bp: &BlockPlan, sparse: Option<&Sparse>, qs: &[&Ident]) -> TokenStream {
        let rt = &self.rt;
        let (n, bl) = (lit(bp.unknowns.len()), lit(b));
        let l = self.scopes.newton[b];
        // The evaluation's sines and cosines from the solve's own cache: the guess's from libm
        // (evaluated in place, once, so the compiler inlines it: no closure call), kept in the
        // cache; each later evaluation's rotated from the one before where the argument moved
        // little (Newton's corrections), at a fraction of a libm call.
        let near = format_ident!("__near{}", b);
        let lets = &self.sched.lets[l];
        let (inner, slots) = self.names.lets_near(self.g, &self.sched, lets, &near, NearCall::Rotate);
        // The same nodes: the guess's evaluation seeds every slot the later ones rotate.
        let (inner_guess, _) = self.names.lets_near(self.g, &self.sched, lets, &near, NearCall::Seed);
        let (scale, unit) = (self.names.operands(self.g, &bp.scale), self.names.operands(self.g, &bp.unit));
        let (scale, unit): (Vec<TokenStream>, Vec<TokenStream>) = (scale.collect(), unit.collect());
        // The magnitudes the tests judge in: made once for the solve when they do not depend on
        // the block's unknowns (link lengths), otherwise kept from every evaluation after the
        // values later scopes read.
        let fixed =
            bp.scale.iter().chain(&bp.unit).all(|m| self.plan.level.get(m.index()).is_some_and(|&l| l < b as i32));
        let kept_mags: Vec<&TokenStream> = if fixed { Vec::new() } else { scale.iter().chain(&unit).collect() };
        // What later scopes read from the evaluation: a dense Jacobian entry from `j`, where the
        // evaluation holds it anyway; the rest through `keep` (each kept value is a store per
        // evaluation).
        let (from_j, kept) = self.exports_of(b, l, sparse.is_none());
        let exports: Vec<Ident> = kept.iter().map(|&x| self.names.temp(x)).collect();
        let k = lit(exports.len() + kept_mags.len());
        let guess = bp.unknowns.iter().map(|&u| {
            let u = lit(u);
            quote!(__guess[#u])
        });
        let f: Vec<TokenStream> = self.names.operands(self.g, &bp.f).collect();
        let (s, ev, r) = (format_ident!("__s{}", b), format_ident!("__eval{}", b), format_ident!("__r{}", b));
        let at = evaluation_ident(b);
        // A large sparse block: its non-zeros only, and Newton over its sparse factorisation.
        let (ty, jrows, newton) = match sparse {
            Some(sp) => {
                let ty = sparse::jac_ident(&self.names.mechanism, b);
                (quote!(#ty), sparse::jac_value(sp, b, self.g, self.names, &bp.jac), quote!(#rt::newton_with_work))
            }
            None => (quote!(), self.names.rows(self.g, &bp.jac), quote!(#rt::newton::<#n, #k>)),
        };
        // A block that keeps the final factorisation for its analogs: the runtime writes it
        // into the analogs' `__lu{b}`.
        let lu = format_ident!("__lu{}", b);
        let (slot, newton, lu_arg) = if keeps_lu(self.mode, bp) {
            (
                quote!(let mut #lu = #rt::Lu::<#n>::unfactored();),
                quote!(#rt::newton_keeping_lu::<#n, #k>),
                quote!(, &mut #lu),
            )
        } else if sparse.is_some() {
            // A sparse block: one factorisation slot (kilobytes) for the solve's steps and
            // then its analogs, each factorisation written over it.
            (quote!(let mut #lu = #rt::BlockJacobian::work(&#at.j);), newton, quote!(, &mut #lu))
        } else {
            (TokenStream::new(), newton, TokenStream::new())
        };
        let ty = if sparse.is_some() { quote!(#rt::BlockEval<#n, #k, #ty>) } else { quote!(#rt::BlockEval<#n, #k>) };
        let mag = format_ident!("__mag{}", b);
        // The unknowns Newton may return on their guess's turn (see `plan::turns`).
        let turns = if bp.turns.contains(&true) {
            let t = &bp.turns;
            quote!(.with_turns([#(#t),*]))
        } else {
            TokenStream::new()
        };
        let (mags_once, mags) = if fixed {
            (quote!(let #mag = #rt::Magnitudes::new([#(#scale),*], [#(#unit),*])#turns;), quote!(&#mag))
        } else {
            let nb = bp.unknowns.len();
            let at = |k: usize| {
                let k = lit(exports.len() + k);
                quote!(__e.keep[#k])
            };
            let (s, u) = ((0..nb).map(at), (nb..2 * nb).map(at));
            (TokenStream::new(), quote!(&|__e: &#ty| #rt::Magnitudes::new([#(#s),*], [#(#u),*])#turns))
        };
        // The kept magnitudes are not read after the solve.
        let take_keep = if exports.is_empty() {
            TokenStream::new()
        } else {
            let unkept = kept_mags.iter().map(|_| quote!(_));
            quote!(let [#(#exports,)* #(#unkept),*] = #at.keep;)
        };
        // Deferred, an earlier block may have failed unchecked (its outputs NaN): the checked
        // kernel tells which failure it is.
        let failure =
            quote!(return ::core::result::Result::Err(#rt::block_failure(self, #bl, *__e, __x, __guess, __cfg)));
        let fail = if self.deferred {
            quote!({
                if __CHECKED {
                    #failure
                }
                return __mode.rerun((self, __x, __guess, __cfg, __trig), __sink);
            })
        } else {
            failure
        };
        // The guess's evaluation is made here as the value of the slot the iteration updates in
        // place: the slot must exist before the closure can write into it, and made as a value
        // it needs no zeroing first (9.6 KB for the ring's block); with sines and cosines it is
        // also no closure call, which the rotations make too large to inline. The solver's
        // closure writes every field of that slot (a block's evaluation is hundreds of bytes, a
        // large sparse block's kilobytes: one returned by value from the closure, which owns
        // the sine and cosine cache, was made in a temporary and copied into the slot).
        let kept_values = quote!([#(#exports,)* #(#kept_mags),*]);
        let value = quote!(#rt::BlockEval { f: [#(#f),*], j: #jrows, keep: #kept_values });
        let keep_field = if exports.is_empty() && kept_mags.is_empty() {
            TokenStream::new()
        } else {
            quote!(__e.keep = #kept_values;)
        };
        let closure = quote! {
            |__z: &[::core::primitive::f64; #n], __e: &mut #ty| {
                let [#(#qs),*] = *__z;
                #inner
                __e.f = [#(#f),*];
                __e.j = #jrows;
                #keep_field
            }
        };
        let z0 = quote!(let __z0: [::core::primitive::f64; #n] = [#(#guess),*];);
        let guess_eval = quote! {
            let mut #at = {
                let [#(#qs),*] = __z0;
                #inner_guess
                #value
            };
        };
        // With sines and cosines, the guess's are libm's, seeding the cache, and the closure
        // then owns the cache (`move`: measured, 57 instructions fewer a class IV step from the
        // predictor than borrowing it).
        let (cache, owns) = if slots == 0 {
            (TokenStream::new(), TokenStream::new())
        } else {
            let slots = lit(slots);
            (quote!(let #near = #rt::NearTrig::<#slots>::new();), quote!(move))
        };
        let evaluations = quote! {
            #cache
            #mags_once
            #z0
            #guess_eval
            let #ev = #owns #closure;
        };
        // The block's evaluation is one closure handed to the runtime's Newton, which checks
        // the guess, corrects it at least once and always checks the final residual.
        quote! {
            #evaluations
            #slot
            let #r = #newton(__z0, &mut #at, __cfg, #ev, #mags #lu_arg);
            let #s = match &#r {
                ::core::result::Result::Ok(__s) => __s,
                ::core::result::Result::Err(__e) => #fail,
            };
            __report.absorb(#s);
            let [#(#qs),*] = #s.z;
            #take_keep
            #(#from_j)*
        }
    }

    /// The values Newton block `b`'s loop scope `l` hands to later scopes: bindings read from
    /// the final evaluation's dense Jacobian `j` for those that are entries of it, and the
    /// nodes of the rest, which go through `keep`.
    fn exports_of(&self, b: usize, l: usize, dense: bool) -> (Vec<TokenStream>, Vec<NodeId>) {
        let (bp, at) = (&self.plan.blocks[b], evaluation_ident(b));
        let mut from_j = Vec::new();
        let mut kept = Vec::new();
        for &x in &self.sched.exports[l] {
            let entry = bp.jac.iter().enumerate().find_map(|(r, row)| row.iter().position(|&e| e == x).map(|c| (r, c)));
            match entry {
                Some((r, c)) if dense => {
                    let (id, r, c) = (self.names.temp(x), lit(r), lit(c));
                    from_j.push(quote!(let #id: ::core::primitive::f64 = #at.j[#r][#c];));
                }
                _ => kept.push(x),
            }
        }
        (from_j, kept)
    }

    /// The straight-line solve of a block recognised as a closed form.
    fn closed_block(&self, b: usize, c: &Recognised) -> TokenStream {
        let op = |n: NodeId| self.op(n);
        let bind = |n: NodeId| self.closed_trig.contains(&n).then(|| self.names.temp(n));
        // A position-only solve has no analogs, whose pivot ratio would report a position the
        // data do not determine (a lever short against its floor, a dyad on coincident
        // centres): the solve tests for it itself.
        let bp = &self.plan.blocks[b];
        let lever_floor = |u: usize| {
            let c = bp.unknowns.iter().position(|&v| v == u)?;
            (!bp.lever_floor[c].is_empty()).then(|| self.floor_value(bp, c))
        };
        let cx = closed_form::Context {
            position_only: self.mode == Mode::Position,
            lever_floor: &lever_floor,
            graph: self.g,
            op: &op,
            unknowns: &self.names.unknowns,
            bind: &bind,
            block: b,
            rt: &self.rt,
            trig: self.names.sweep_kernel(),
            deferred: self.deferred,
            // A `move` closure: it holds `self` and the leaves it reads, passed on the cold
            // path alone.
            terms: bp.terms.map(|n| {
                let value = self.names.standalone(self.g, n);
                quote!(move || #value)
            }),
        };
        closed_form::solve(c, &cx)
    }
}
