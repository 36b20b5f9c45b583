//! The straight-line kernels: flat arrays in, flat arrays out. Everything else a mechanism
//! offers is generic runtime code built on them.
//!
//! The solver kernels share one scheduler and differ by [`Mode`]:
//! * `Position`: blocks solved in BLT order (Newton per nonlinear block, one linear solve per
//!   linear block);
//! * `Fused`: the same, then velocity and acceleration analogs with one factorisation per block
//!   (the Newton evaluation's Jacobian at the solution is reused, linear blocks reuse their
//!   position factorisation), then the outputs and their analogs;
//! * `At`: analogs and outputs at a position given by the caller.
//!
//! With `sens`, the parameter sensitivities follow on the same factorisations.

use super::names::{Names, float_arg};
use super::schedule::{Schedule, ScopeKind, ScopeSpec, schedule};
use super::sparse;
use super::{lit, runtime};
use crate::dag::{Graph, Leaf, NodeId};
use crate::plan::finite::{self, Term};
use crate::plan::{BlockPlan, Plan, Stages, pair_index, pairs};
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashSet;

#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Position,
    Fused,
    At,
}

/// Scope indices of a solver kernel, per block.
#[derive(Default)]
struct Scopes {
    specs: Vec<ScopeSpec>,
    residual: Option<usize>,
    pre: Vec<usize>,
    newton: Vec<usize>,
    vel: Vec<usize>,
    acc: Vec<usize>,
    sens: [Vec<usize>; 3],
    out: usize,
}

impl Scopes {
    fn push(&mut self, kind: ScopeKind, roots: Vec<NodeId>) -> usize {
        self.specs.push(ScopeSpec { kind, roots });
        self.specs.len() - 1
    }
}

/// The pieces of a solver kernel being generated.
struct Kernel<'a> {
    plan: &'a Plan,
    g: &'a Graph,
    names: &'a Names,
    mode: Mode,
    sched: Schedule,
    scopes: Scopes,
    rt: TokenStream,
    /// Checks switched by the kernel's constant `__CHECKED`, deferred to its end when it is
    /// false (see [`deferred_body`]).
    deferred: bool,
    /// The leaves the kernel reads.
    used: HashSet<Leaf>,
    /// Closed-form hook: the `sin`/`cos` nodes that closed-form solves define.
    closed_trig: HashSet<NodeId>,
}

/// The slot holding Newton block `b`'s evaluation (`__ev{b}`: residuals, Jacobian, kept
/// values), which the runtime's iteration updates in place.
fn evaluation_ident(b: usize) -> Ident {
    format_ident!("__ev{}", b)
}

/// Whether a dense Newton block's analogs (the fused kernel's) reuse the factorisation of
/// its final correction: when every non-zero entry of its unknowns' Jacobian columns is one
/// of the block's own entries, the column magnitudes the analogs equilibrate by are known
/// inside the block's evaluation, so the runtime can factorise exactly as the analogs
/// would (a later block's entry in such a column would not be known yet). Not a sparse
/// block: the ring of coupled loops ends every solve with a final correction above the
/// rounding level, which is evaluated again, so a kept factorisation was made again there,
/// and moving a sparse one cost more than it saved (measured on the ring).
fn keeps_lu(mode: Mode, bp: &BlockPlan) -> bool {
    mode == Mode::Fused
        && bp.sparse.is_none()
        && !bp.linear
        && bp.closed.is_none()
        && bp.lever_floor.iter().all(Vec::is_empty)
        && bp
            .col_scale
            .iter()
            .enumerate()
            .all(|(c, col)| col.iter().all(|e| bp.jac.iter().any(|row| row.get(c) == Some(e))))
}

/// A sensitivity stage's right-hand sides per row.
fn stage_rows(s: &Stages, stage: usize) -> &Vec<Vec<NodeId>> {
    [&s.q, &s.v, &s.a][stage]
}

fn plan_scopes(plan: &Plan, mode: Mode, sens: bool) -> Scopes {
    let mut s = Scopes::default();
    if mode == Mode::At {
        s.residual = Some(s.push(ScopeKind::Plain, plan.residuals.clone()));
    } else {
        for (b, bp) in plan.blocks.iter().enumerate() {
            let (pre, newton) = if let Some(c) = &bp.closed {
                // Closed-form hook: the coefficients before the solve, no Newton closure; a
                // position-only solve also tests its levers against their floors (see
                // `closed_block`).
                let mut pre = c.form.coefficients();
                if mode == Mode::Position {
                    pre.extend(bp.lever_floor.concat());
                }
                (pre, vec![])
            } else if bp.linear {
                (
                    bp.jac
                        .concat()
                        .into_iter()
                        .chain(bp.rhs0.iter().copied())
                        .chain(bp.col_scale.concat())
                        .chain(bp.lever_floor.concat())
                        .collect(),
                    vec![],
                )
            } else {
                let scales = bp.scale.iter().chain(&bp.unit).copied();
                (Vec::new(), bp.f.iter().copied().chain(bp.jac.concat()).chain(scales).collect())
            };
            let p = s.push(ScopeKind::Plain, pre);
            s.pre.push(p);
            let l = s.push(ScopeKind::Loop(b), newton);
            s.newton.push(l);
        }
    }
    if mode == Mode::Position {
        return s;
    }
    for bp in &plan.blocks {
        let mut roots = bp.vel.concat();
        // A block that keeps its factorisation needs no column magnitudes of its own.
        if !keeps_lu(mode, bp) {
            roots.extend(bp.col_scale.concat());
            roots.extend(bp.lever_floor.concat());
        }
        // Closed-form hook: no Newton evaluation to reuse, the Jacobian is computed here.
        if mode == Mode::At || bp.closed.is_some() {
            roots.extend(bp.jac.concat());
        }
        let v = s.push(ScopeKind::Plain, roots);
        s.vel.push(v);
    }
    for bp in &plan.blocks {
        let a = s.push(ScopeKind::Plain, bp.acc.concat());
        s.acc.push(a);
    }
    let mut out: Vec<NodeId> =
        plan.outputs.iter().copied().chain(plan.out_d1.concat()).chain(plan.out_d2.concat()).collect();
    if sens {
        for stage in 0..3 {
            for bp in &plan.blocks {
                let roots = bp.sens.as_ref().map(|st| stage_rows(st, stage).concat()).unwrap_or_default();
                let k = s.push(ScopeKind::Plain, roots);
                s.sens[stage].push(k);
            }
        }
        if let Some(os) = &plan.out_sens {
            out.extend(os.q.concat().into_iter().chain(os.v.concat()).chain(os.a.concat()));
        }
    }
    s.out = s.push(ScopeKind::Plain, out);
    s
}

/// The body of a solver kernel with arguments `__x`, `__guess` (or `__q` in mode `At`) and
/// `__cfg`, returning a `Kin` (or `(Kin, Sens)` with `sens`).
pub fn solver_body(plan: &Plan, names: &Names, mode: Mode, sens: bool) -> TokenStream {
    body(plan, names, mode, sens, false)
}

/// The body of a sweep's kernel (`names` with the sweep's trigonometry: arguments `__x`,
/// `__guess`, `__cfg`, `__trig`, `__sink`) whose checks are switched by a constant `__CHECKED`.
/// With it true, the body is the checked kernel's ([`solver_body`] in mode `Fused`): every check
/// on the way. With it false the checks are deferred to the end: the closed-form blocks and the
/// analog blocks test nothing on the way, and one test at the end accepts the state exactly where
/// every check would have passed; otherwise (and where a Newton block fails) the kernel returns
/// what the checked one (`Mechanism::kinematics_step_checked`, this body with `__CHECKED` true)
/// returns from the same arguments. See the runtime's `solvers::deferred`.
pub fn deferred_body(plan: &Plan, names: &Names) -> TokenStream {
    body(plan, names, Mode::Fused, false, true)
}

fn body(plan: &Plan, names: &Names, mode: Mode, sens: bool, deferred: bool) -> TokenStream {
    let scopes = plan_scopes(plan, mode, sens);
    let g = &plan.graph;
    let mut sched = schedule(g, &plan.level, &scopes.specs);
    // Closed-form hook: the sines and cosines of closed-form angles come from their solve.
    let closed_trig =
        if mode == Mode::At { HashSet::new() } else { crate::closed_form::emit::take_trig(plan, &mut sched.lets) };
    let used = used_leaves(g, &scopes.specs);
    let mut body = prologue(names, &used);
    let k = Kernel { plan, g, names, mode, sched, scopes, rt: runtime(), deferred, used, closed_trig };
    body.extend(k.start());
    if deferred {
        body.extend(k.deferred_entry());
    }
    if mode != Mode::At {
        for b in 0..plan.blocks.len() {
            body.extend(k.position_block(b));
        }
        if mode == Mode::Position {
            let q = &names.unknowns;
            body.extend(quote!(::core::result::Result::Ok(([#(#q),*], __report))));
            return body;
        }
    }
    let rt = &k.rt;
    body.extend(quote!(let mut __health = #rt::Health::default();));
    for b in 0..plan.blocks.len() {
        body.extend(k.velocity_block(b));
    }
    for b in 0..plan.blocks.len() {
        body.extend(k.acceleration_block(b));
    }
    if sens {
        for stage in 0..3 {
            for b in 0..plan.blocks.len() {
                body.extend(k.sensitivity_block(stage, b));
            }
        }
    }
    body.extend(names.lets(g, &k.sched, &k.sched.lets[k.scopes.out]));
    body.extend(if sens { k.finish_sensitivities() } else { k.finish() });
    body
}

/// The leaves a kernel reads, from the roots of all its scopes.
fn used_leaves(g: &Graph, specs: &[ScopeSpec]) -> HashSet<Leaf> {
    let roots: Vec<NodeId> = specs.iter().flat_map(|s| s.roots.iter().copied()).collect();
    g.leaves_of(&roots).into_iter().collect()
}

/// `let [a, _, c] = *from;` binding only the used elements.
fn bind_used(ids: &[Ident], used: impl Fn(usize) -> bool, from: TokenStream) -> TokenStream {
    let pats = ids.iter().enumerate().map(|(k, id)| if used(k) { quote!(#id) } else { quote!(_) });
    quote!(let [#(#pats),*] = *#from;)
}

/// Binds the inputs the kernel reads to locals (parameters are read as `self.a`).
fn prologue(names: &Names, used: &HashSet<Leaf>) -> TokenStream {
    bind_used(&names.inputs, |k| used.contains(&Leaf::Input(k as u16)), quote!(__x))
}

/// Binds the unknowns the kernel reads from `__q`.
fn bind_q(names: &Names, used: &HashSet<Leaf>) -> TokenStream {
    bind_used(&names.unknowns, |k| used.contains(&Leaf::Unknown(k as u16)), quote!(__q))
}

/// Closed-form hook: without a Newton block nothing else reads the configuration, which is
/// still checked (an invalid one is an error whichever way the blocks are solved). Empty when a
/// Newton block checks it.
pub fn closed_config_check(plan: &Plan) -> TokenStream {
    let rt = runtime();
    if !plan.blocks.iter().all(|b| b.linear || b.closed.is_some()) {
        return TokenStream::new();
    }
    match plan.blocks.iter().position(|b| b.closed.is_some()) {
        Some(b) => {
            let b = lit(b);
            quote! {
                if let Some(field) = __cfg.invalid_field() {
                    return Err(#rt::config_failure(self, #b, field, __x, __guess));
                }
            }
        }
        None => TokenStream::new(),
    }
}

impl Kernel<'_> {
    fn lets(&self, scope: usize) -> TokenStream {
        self.names.lets(self.g, &self.sched, &self.sched.lets[scope])
    }

    fn op(&self, n: NodeId) -> TokenStream {
        self.names.operand(self.g, n)
    }

    /// The solve report: the caller's position's residual (mode `At`), or filled by the blocks.
    fn start(&self) -> TokenStream {
        let rt = &self.rt;
        match self.scopes.residual {
            Some(r) => {
                let (q, lets) = (bind_q(self.names, &self.used), self.lets(r));
                let res = self.names.operands(self.g, &self.plan.residuals);
                quote! {
                    #q
                    #lets
                    let __report = #rt::SolveReport::given(#rt::max_abs([#(#res),*]));
                }
            }
            // Only Newton blocks add to the report.
            None if self.plan.blocks.iter().all(|b| b.linear || b.closed.is_some()) => {
                // A sweep's kernel is given the configuration the sweep checked once.
                let mut out =
                    if self.names.sweep_kernel() { TokenStream::new() } else { closed_config_check(self.plan) };
                out.extend(quote!(let __report = #rt::SolveReport::direct();));
                out
            }
            None => quote!(let mut __report = #rt::SolveReport::direct();),
        }
    }

    /// A 1x1 linear block with a constant, non-zero, finite coefficient.
    fn fixed(&self, bp: &BlockPlan) -> Option<f64> {
        if !bp.linear || bp.unknowns.len() != 1 {
            return None;
        }
        self.g.as_const(bp.jac[0][0]).filter(|c| *c != 0.0 && c.is_finite())
    }

    /// Each column's magnitude: the largest of its entries and of its lever floors.
    fn col_scales(&self, bp: &BlockPlan) -> Vec<TokenStream> {
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
    fn floor_value(&self, bp: &BlockPlan, c: usize) -> TokenStream {
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
    fn factor(&self, bp: &BlockPlan, jrows: &TokenStream, scale: &[TokenStream]) -> TokenStream {
        let (rt, n) = (&self.rt, lit(bp.unknowns.len()));
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
            _ => quote!(#rt::Lu::<#n>::factor_cols(&#jrows, [#(#scale),*])),
        }
    }

    fn unknowns_of(&self, bp: &BlockPlan) -> Vec<&Ident> {
        bp.unknowns.iter().map(|&u| &self.names.unknowns[u]).collect()
    }

    fn position_block(&self, b: usize) -> TokenStream {
        let bp = &self.plan.blocks[b];
        let mut out = self.lets(self.scopes.pre[b]);
        let qs = self.unknowns_of(bp);
        let (rt, lu) = (&self.rt, format_ident!("__lu{}", b));
        if let Some(c) = self.fixed(bp) {
            // A constant, non-zero coefficient: one division, never singular.
            let (c, rhs) = (float_arg(c), self.op(bp.rhs0[0]));
            out.extend(quote! {
                let #lu = #rt::Fixed(#c);
                let [#(#qs),*] = #lu.solve([#rhs]);
            });
        } else if bp.linear {
            out.extend(self.linear_block(b, bp, &qs));
        } else if let Some(c) = &bp.closed {
            // Closed-form hook: the block's closed-form solve instead of Newton.
            out.extend(self.closed_block(b, c));
        } else {
            out.extend(self.newton_block(b, bp, &qs));
        }
        out
    }

    fn linear_block(&self, b: usize, bp: &BlockPlan, qs: &[&Ident]) -> TokenStream {
        let rt = &self.rt;
        let (bl, lu) = (lit(b), format_ident!("__lu{}", b));
        let scale = self.col_scales(bp);
        let jrows = self.names.rows(self.g, &bp.jac);
        let aug: Vec<Vec<NodeId>> =
            bp.jac.iter().zip(&bp.rhs0).map(|(row, &r)| row.iter().copied().chain([r]).collect()).collect();
        let aug = self.names.rows(self.g, &aug);
        let rhs = self.names.operands(self.g, &bp.rhs0);
        let factor = self.factor(bp, &jrows, &scale);
        quote! {
            let #lu = #factor;
            if !(#lu.pivot_ratio() >= __cfg.singular_tol) {
                return Err(#rt::singular(self, #bl, #lu.pivot_ratio(), __cfg, __x, #rt::first_bad_row(&#aug)));
            }
            let [#(#qs),*] = #lu.solve([#(#rhs),*]);
        }
    }

    fn newton_block(&self, b: usize, bp: &BlockPlan, qs: &[&Ident]) -> TokenStream {
        let rt = &self.rt;
        let (n, bl) = (lit(bp.unknowns.len()), lit(b));
        let l = self.scopes.newton[b];
        let inner = self.lets(l);
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
        let (from_j, kept) = self.exports_of(b, l);
        let exports: Vec<Ident> = kept.iter().map(|&x| self.names.temp(x)).collect();
        let k = lit(exports.len() + kept_mags.len());
        let guess = bp.unknowns.iter().map(|&u| {
            let u = lit(u);
            quote!(__guess[#u])
        });
        let f = self.names.operands(self.g, &bp.f);
        let (s, ev, r) = (format_ident!("__s{}", b), format_ident!("__eval{}", b), format_ident!("__r{}", b));
        let at = evaluation_ident(b);
        // A large sparse block: its non-zeros only, and Newton over its sparse factorisation.
        let (pattern, ty, jrows, newton) = match &bp.sparse {
            Some(sp) => (
                sparse::pattern_item(sp, b, rt),
                sparse::jac_type(sp, bp.unknowns.len(), rt),
                sparse::jac_value(sp, b, self.g, self.names, &bp.jac, rt),
                quote!(#rt::newton_with),
            ),
            None => (TokenStream::new(), quote!(), self.names.rows(self.g, &bp.jac), quote!(#rt::newton::<#n, #k>)),
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
        } else {
            (TokenStream::new(), newton, TokenStream::new())
        };
        let ty = if bp.sparse.is_some() { quote!(#rt::BlockEval<#n, #k, #ty>) } else { quote!(#rt::BlockEval<#n, #k>) };
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
        let failure = quote!(return Err(#rt::block_failure(self, #bl, *e, __x, __guess, __cfg)));
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
        // The block's evaluation is one closure handed to the runtime's Newton, which checks
        // the guess, corrects it at least once and always checks the final residual.
        quote! {
            #pattern
            let #ev = |__z: &[f64; #n]| -> #ty {
                let [#(#qs),*] = *__z;
                #inner
                #rt::BlockEval { f: [#(#f),*], j: #jrows, keep: [#(#exports,)* #(#kept_mags),*] }
            };
            #mags_once
            let __z0: [f64; #n] = [#(#guess),*];
            // The guess evaluated here, into the slot the iteration updates in place: the
            // block's evaluation is never copied into or out of the solver.
            let mut #at = #ev(&__z0);
            #slot
            let #r = #newton(__z0, &mut #at, __cfg, #ev, #mags #lu_arg);
            let #s = match &#r {
                Ok(s) => s,
                Err(e) => #fail,
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
    fn exports_of(&self, b: usize, l: usize) -> (Vec<TokenStream>, Vec<NodeId>) {
        let (bp, at) = (&self.plan.blocks[b], evaluation_ident(b));
        let mut from_j = Vec::new();
        let mut kept = Vec::new();
        for &x in &self.sched.exports[l] {
            let entry = bp.jac.iter().enumerate().find_map(|(r, row)| row.iter().position(|&e| e == x).map(|c| (r, c)));
            match entry {
                Some((r, c)) if bp.sparse.is_none() => {
                    let (id, r, c) = (self.names.temp(x), lit(r), lit(c));
                    from_j.push(quote!(let #id: f64 = #at.j[#r][#c];));
                }
                _ => kept.push(x),
            }
        }
        (from_j, kept)
    }

    /// Closed-form hook: the straight-line solve of a recognised block.
    fn closed_block(&self, b: usize, c: &crate::closed_form::Recognised) -> TokenStream {
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
        let cx = crate::closed_form::emit::Context {
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
        };
        crate::closed_form::emit::solve(c, &cx)
    }

    /// Velocity analogs of block `b`, factorising its Jacobian when the position solve did not
    /// (the factorisation is reused for accelerations and sensitivities).
    fn velocity_block(&self, b: usize) -> TokenStream {
        let bp = &self.plan.blocks[b];
        let rt = &self.rt;
        let (n, ni, bl) = (lit(bp.unknowns.len()), lit(self.plan.ni), lit(b));
        let (lu, rv) = (format_ident!("__lu{}", b), format_ident!("__rv{}", b));
        let mut out = self.lets(self.scopes.vel[b]);
        let rows = self.names.rows(self.g, &bp.vel);
        out.extend(quote!(let #rv: [[f64; #ni]; #n] = #rows;));
        let fixed = self.fixed(bp);
        if let (Mode::At, Some(c)) = (self.mode, fixed) {
            let c = float_arg(c);
            out.extend(quote!(let #lu = #rt::Fixed(#c);));
        }
        if let Some(sp) = &bp.sparse {
            out.extend(self.sparse_factor(b, sp, &rv));
        } else if (self.mode == Mode::At || !bp.linear) && fixed.is_none() {
            // Closed-form hook: a closed-form block has no Newton evaluation to read.
            let from_graph = self.mode == Mode::At || bp.closed.is_some();
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
                quote!(let #lu = #rt::Lu::<#n>::factor_cols(&__j, [#(#scale),*]);)
            };
            // Deferred, the end tests the smallest pivot ratio `__health` records.
            let checked = self.deferred.then(|| quote!(__CHECKED &&));
            out.extend(quote! {
                let __j: [[f64; #n]; #n] = #j;
                #factor
                if #checked !(#lu.pivot_ratio() >= __cfg.singular_tol) {
                    let bad = #rt::first_bad_row(&__j).or(#rt::first_bad_row(&#rv));
                    return Err(#rt::singular(self, #bl, #lu.pivot_ratio(), __cfg, __x, bad));
                }
            });
        }
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

    /// The factorisation of a sparse block for its analogs: the Newton evaluation's Jacobian,
    /// or (mode `At`) its non-zeros at the given position.
    fn sparse_factor(&self, b: usize, sp: &crate::plan::sparse::Sparse, rv: &Ident) -> TokenStream {
        let (bp, rt, bl) = (&self.plan.blocks[b], &self.rt, lit(b));
        let (lu, scale) = (format_ident!("__lu{}", b), self.col_scales(bp));
        let (pattern, j) = if self.mode == Mode::At {
            (sparse::pattern_item(sp, b, rt), sparse::jac_value(sp, b, self.g, self.names, &bp.jac, rt))
        } else {
            let at = evaluation_ident(b);
            (TokenStream::new(), quote!(#at.j))
        };
        quote! {
            #pattern
            let __j = #j;
            let #lu = __j.factor_cols([#(#scale),*]);
            if !(#lu.pivot_ratio() >= __cfg.singular_tol) {
                let bad = __j.first_bad_row().or(#rt::first_bad_row(&#rv));
                return Err(#rt::singular(self, #bl, #lu.pivot_ratio(), __cfg, __x, bad));
            }
        }
    }

    fn acceleration_block(&self, b: usize) -> TokenStream {
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
            let __ra: [[f64; #npl]; #n] = #rows;
            let [#(#ws),*] = #lu.solve_cols(__ra);
        });
        out
    }

    /// Parameter sensitivities of block `b` at `stage` (positions, first or second analogs):
    /// the same factorisation, one more set of right-hand sides.
    fn sensitivity_block(&self, stage: usize, b: usize) -> TokenStream {
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
            let __rs: [[f64; #width]; #n] = #rows;
            let [#(#binds),*] = #lu.solve_cols(__rs);
        });
        out
    }

    /// The `Kin` value from the locals.
    fn kin(&self) -> TokenStream {
        let (plan, names, rt, ni) = (self.plan, self.names, &self.rt, self.plan.ni);
        let q = &names.unknowns;
        let dq = (0..plan.n).map(|u| {
            let v = (0..ni).map(|i| names.tan(u, i));
            quote!([#(#v),*])
        });
        let d2q = (0..plan.n).map(|u| {
            let rows = (0..ni).map(|i| {
                let w = (0..ni).map(|j| names.tan2(u, i, j));
                quote!([#(#w),*])
            });
            quote!([#(#rows),*])
        });
        let out = names.operands(self.g, &plan.outputs);
        let dout = names.rows(self.g, &plan.out_d1);
        let d2: Vec<TokenStream> = plan.out_d2.iter().map(|row| self.by_pairs(row, 1, 0)).collect();
        quote! {
            #rt::Kin {
                x: *__x,
                q: [#(#q),*],
                dq: [#(#dq),*],
                d2q: [#(#d2q),*],
                out: [#(#out),*],
                dout: #dout,
                d2out: [#(#d2),*],
                report: __report,
                health: __health,
            }
        }
    }

    /// `[[row[p(i, j) * stride + k]]]` over input pairs, as an `ni x ni` array.
    fn by_pairs(&self, row: &[NodeId], stride: usize, k: usize) -> TokenStream {
        let ni = self.plan.ni;
        let rows = (0..ni).map(|i| {
            let r = (0..ni).map(|j| self.op(row[pair_index(ni, i, j) * stride + k]));
            quote!([#(#r),*])
        });
        quote!([#(#rows),*])
    }

    fn guess_arg(&self) -> TokenStream {
        if self.mode == Mode::At { quote!(None) } else { quote!(Some(__guess)) }
    }

    /// Returns the state; one sum tells whether every value is finite (NaN and infinity
    /// propagate), and the state is examined value by value only on the cold path (in the
    /// runtime's `checked`). The usual path returns the state itself (passed through `checked`,
    /// the ~200-byte state was copied once more).
    fn finish(&self) -> TokenStream {
        let (sum, checks) = self.finite_sum();
        if self.deferred {
            return self.finish_deferred(sum, checks);
        }
        let (kin, rt, guess) = (self.kin(), &self.rt, self.guess_arg());
        // The state is built where it goes on the hot path: in the returned value, or in a
        // sweep's slot (`__sink`). A state built once and passed to the check is copied into the
        // result: a memcpy per step.
        let sink = if self.names.sweep_kernel() { quote!(__sink) } else { quote!(#rt::ByValue) };
        quote! {
            let __sum: f64 = #sum;
            #rt::checked_with(self, __sum, #guess, #sink, || #kin)
        }
    }

    /// The sum of the state's values whose finiteness the kernel tests, and (deferred) the
    /// closed-form blocks' check sums it tests too. In the fused kernel, only the values whose
    /// finiteness the others' does not imply (see `plan::finite`); a sum of the whole state
    /// elsewhere.
    fn finite_sum(&self) -> (TokenStream, Vec<TokenStream>) {
        let (plan, names, g) = (self.plan, self.names, self.g);
        let ni = plan.ni;
        let leaf = |l: Leaf| g.find(crate::dag::Op::Leaf(l)).map(Term::Node);
        let mut terms: Vec<(Option<Term>, TokenStream)> = Vec::new();
        for (u, q) in names.unknowns.iter().enumerate() {
            terms.push((leaf(Leaf::Unknown(u as u16)), quote!(#q)));
        }
        for u in 0..plan.n {
            for i in 0..ni {
                let v = names.tan(u, i);
                terms.push((leaf(Leaf::Tan { unknown: u as u16, input: i as u16 }), quote!(#v)));
                for j in 0..ni {
                    let (a, b) = (i.min(j) as u16, i.max(j) as u16);
                    let w = names.tan2(u, i, j);
                    terms.push((leaf(Leaf::Tan2 { unknown: u as u16, i: a, j: b }), quote!(#w)));
                }
            }
        }
        for (o, &node) in plan.outputs.iter().enumerate() {
            for n in std::iter::once(node).chain(plan.out_d1[o].iter().copied()).chain(plan.out_d2[o].iter().copied()) {
                terms.push((Some(Term::Node(n)), self.op(n)));
            }
        }
        let first_check = terms.len();
        if self.deferred {
            for b in (0..plan.blocks.len()).filter(|&b| plan.blocks[b].closed.is_some()) {
                let check = format_ident!("__check{}", b);
                terms.push((Some(Term::Check(b)), quote!(#check)));
            }
        }
        let keep = self.kept_terms(&terms);
        let (mut sum, mut checks) = (Vec::new(), Vec::new());
        for (k, ((_, t), kept)) in terms.into_iter().zip(keep).enumerate() {
            if kept {
                if k < first_check { sum.push(t) } else { checks.push(t) }
            }
        }
        (balanced_sum(sum), checks)
    }

    /// Per term of [`Kernel::finite_sum`], whether the sum includes it: in the fused kernel
    /// each value once, and only when the others' finiteness does not imply its own; elsewhere
    /// all.
    fn kept_terms(&self, terms: &[(Option<Term>, TokenStream)]) -> Vec<bool> {
        if self.mode != Mode::Fused {
            return vec![true; terms.len()];
        }
        let ids: Vec<Term> = terms.iter().filter_map(|(t, _)| *t).collect();
        let mut summed = finite::summed(self.plan, &ids).into_iter();
        // A term with no graph node (a leaf the graph does not hold) is always summed.
        terms.iter().map(|(t, _)| t.is_none() || summed.next() != Some(false)).collect()
    }

    /// The end of a kernel whose checks are switched by `__CHECKED`: with it, the checked
    /// kernel's end (`sum` is [`Kernel::finite_sum`]'s). Otherwise the state is accepted
    /// when `sum` and the closed-form blocks' check sums `checks` are finite and the smallest
    /// pivot ratio is at least `singular_tol`; else the checked kernel answers.
    fn finish_deferred(&self, sum: TokenStream, mut checks: Vec<TokenStream>) -> TokenStream {
        let kin = self.kin();
        checks.push(quote!(__sum));
        let all = balanced_sum(checks);
        quote! {
            let __sum: f64 = #sum;
            let __accept: bool = (#all).is_finite() && __health.min_pivot >= __cfg.singular_tol;
            __mode.finish((__accept, __sum), (self, __x, __guess, __cfg, __trig), __sink, || #kin)
        }
    }

    /// The entry of a deferred kernel: its mode `__mode`, and the test of the closed-form
    /// angles' guesses (`Checks::far`), where the checked kernel answers instead. A closed-form
    /// angle lies within `π` of its guess, so the test bounds the angles themselves by values
    /// known on entry: tested at the end, on the angles, the same test made the gear-lever's
    /// sweep take up to 40 % longer (160 against 115 ns a step, 5 instructions more).
    fn deferred_entry(&self) -> TokenStream {
        let rt = &self.rt;
        let mode = quote!(let __mode = #rt::Checks::<__CHECKED>;);
        let angles: Vec<TokenStream> = self
            .plan
            .blocks
            .iter()
            .filter_map(|bp| bp.closed.as_ref())
            .flat_map(|c| c.form.angles())
            .map(|u| {
                let u = lit(u);
                quote!(__guess[#u].abs())
            })
            .collect();
        if angles.is_empty() {
            return mode;
        }
        let magnitudes = balanced_sum(angles);
        quote! {
            #mode
            if __mode.far(#magnitudes) {
                return __mode.rerun((self, __x, __guess, __cfg, __trig), __sink);
            }
        }
    }

    /// Returns the state and its sensitivities, checked.
    fn finish_sensitivities(&self) -> TokenStream {
        let (plan, names, rt) = (self.plan, self.names, &self.rt);
        let (ni, npar) = (plan.ni, plan.np);
        let params = |f: &dyn Fn(usize) -> Ident| {
            let v = (0..npar).map(f);
            quote!([#(#v),*])
        };
        let sq = (0..plan.n).map(|u| params(&|k| names.sens_q(u, k)));
        let sv = (0..plan.n).map(|u| {
            let rows = (0..ni).map(|i| params(&|k| names.sens_v(u, i, k)));
            quote!([#(#rows),*])
        });
        let sa = (0..plan.n).map(|u| {
            let rows = (0..ni).map(|i| {
                let cols = (0..ni).map(|j| params(&|k| names.sens_a(u, i, j, k)));
                quote!([#(#cols),*])
            });
            quote!([#(#rows),*])
        });
        let empty = Stages { q: Vec::new(), v: Vec::new(), a: Vec::new() };
        let os = plan.out_sens.as_ref().unwrap_or(&empty);
        let osq = names.rows(self.g, &os.q);
        let osv = os.v.iter().map(|row| {
            let rows = (0..ni).map(|i| {
                let v = names.operands(self.g, &row[i * npar..(i + 1) * npar]);
                quote!([#(#v),*])
            });
            quote!([#(#rows),*])
        });
        let osa = os.a.iter().map(|row| {
            let rows = (0..ni).map(|i| {
                let cols = (0..ni).map(|j| {
                    let p = pair_index(ni, i, j);
                    let v = names.operands(self.g, &row[p * npar..(p + 1) * npar]);
                    quote!([#(#v),*])
                });
                quote!([#(#cols),*])
            });
            quote!([#(#rows),*])
        });
        let (kin, guess) = (self.kin(), self.guess_arg());
        quote! {
            let __sens = #rt::Sens { q: [#(#sq),*], dq: [#(#sv),*], d2q: [#(#sa),*], out: #osq, dout: [#(#osv),*], d2out: [#(#osa),*] };
            #rt::checked_sensitivities(self, #kin, __sens, #guess)
        }
    }
}

/// `a + b + ...` as a balanced tree: its depth (the latency of the dependent additions) grows
/// like the logarithm of the number of terms instead of linearly.
fn balanced_sum(mut terms: Vec<TokenStream>) -> TokenStream {
    if terms.is_empty() {
        return quote!(0.0);
    }
    while terms.len() > 1 {
        let mut next = Vec::with_capacity(terms.len().div_ceil(2));
        let mut it = terms.into_iter();
        while let Some(a) = it.next() {
            next.push(match it.next() {
                Some(b) => quote!((#a + #b)),
                None => a,
            });
        }
        terms = next;
    }
    terms.pop().unwrap_or_else(|| quote!(0.0))
}

/// Straight-line evaluation of some roots (residual, outputs, guesses), returning an array;
/// `with_q` binds the unknowns from `__q`.
pub fn straight_line(plan: &Plan, names: &Names, roots: &[NodeId], with_q: bool) -> TokenStream {
    let g = &plan.graph;
    let sched = schedule(g, &plan.level, &[ScopeSpec { kind: ScopeKind::Plain, roots: roots.to_vec() }]);
    let lets = names.lets(g, &sched, &sched.lets[0]);
    let used: HashSet<Leaf> = g.leaves_of(roots).into_iter().collect();
    let bind = if with_q { bind_q(names, &used) } else { quote!() };
    let vals = names.operands(g, roots);
    let mut body = prologue(names, &used);
    body.extend(quote! {
        #bind
        #lets
        [#(#vals),*]
    });
    body
}

/// Residuals, full Jacobian and input derivatives at `(x, q)`, as a `Jac`.
pub fn jacobian_body(plan: &Plan, names: &Names) -> TokenStream {
    let g = &plan.graph;
    let roots = plan.residuals.iter().copied().chain(plan.jac_full.concat()).chain(plan.fx_full.concat());
    let units = plan.unit_full.iter().chain(&plan.input_unit).copied();
    let roots: Vec<NodeId> = roots.chain(plan.scale_full.iter().copied()).chain(units).collect();
    let used: HashSet<Leaf> = g.leaves_of(&roots).into_iter().collect();
    let sched = schedule(g, &plan.level, &[ScopeSpec { kind: ScopeKind::Plain, roots }]);
    let lets = names.lets(g, &sched, &sched.lets[0]);
    let (q, rt) = (bind_q(names, &used), runtime());
    let (f, scale) = (names.operands(g, &plan.residuals), names.operands(g, &plan.scale_full));
    let (unit, input_unit) = (names.operands(g, &plan.unit_full), names.operands(g, &plan.input_unit));
    let (n, ni) = (lit(plan.n), lit(plan.ni));
    let (j, fx) = (sparse_entries(plan, names, &plan.jac_full, "j"), sparse_entries(plan, names, &plan.fx_full, "fx"));
    let mut body = prologue(names, &used);
    body.extend(quote! {
        #q
        #lets
        let mut __jac = #rt::Jac {
            f: [#(#f),*],
            j: [[0.0; #n]; #n],
            fx: [[0.0; #ni]; #n],
            scale: [#(#scale),*],
            unit: [#(#unit),*],
            input_unit: [#(#input_unit),*],
        };
        #j
        #fx
        __jac
    });
    body
}

/// `__jac.field[r][c] = value;` for the structurally non-zero entries of a matrix only: a
/// Jacobian is sparse (a few entries per row), and writing all `n^2` of them would make the
/// generated code, and its compile time, grow with the square of the size.
fn sparse_entries(plan: &Plan, names: &Names, rows: &[Vec<NodeId>], field: &str) -> TokenStream {
    let g = &plan.graph;
    let field = format_ident!("{}", field);
    let mut out = TokenStream::new();
    for (r, row) in rows.iter().enumerate() {
        for (c, &node) in row.iter().enumerate().filter(|&(_, &node)| !g.is_zero(node)) {
            let (r, c, v) = (lit(r), lit(c), names.operand(g, node));
            out.extend(quote!(__jac.#field[#r][#c] = #v;));
        }
    }
    out
}
