//! The straight-line solver kernels: flat arrays in, flat arrays out. Everything else a
//! mechanism offers is generic runtime code built on them.
//!
//! The solver kernels share one scheduler and differ by [`Mode`]:
//! * `Position`: blocks solved in BLT order, each as its plan's `Solve` says (Newton per
//!   nonlinear block, one linear solve per linear block, a closed form's straight-line solve);
//! * `Fused`: the same, then velocity and acceleration analogs with one factorisation per block
//!   (the Newton evaluation's Jacobian at the solution is reused, linear blocks reuse their
//!   position factorisation), then the outputs and their analogs;
//! * `At`: analogs and outputs at a position given by the caller.
//!
//! With `sens`, the parameter sensitivities follow on the same factorisations.
//!
//! A kernel is written in order: its scopes (which graph nodes each part computes,
//! [`scopes`]), its entry ([`entry`]), each block's position solve ([`position`], with the
//! factorisations of [`factor`]), the analogs and sensitivities ([`analogs`]) and its end, which
//! checks and returns the state ([`finish`]).

mod analogs;
mod entry;
mod factor;
mod finish;
mod position;
mod scopes;

pub use entry::closed_config_check;

use super::names::Names;
use super::runtime;
use super::schedule::{Schedule, ScopeSpec, schedule};
use crate::graph::dag::{Graph, Leaf, NodeId};
use crate::plan::{BlockPlan, Plan};
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use scopes::{Scopes, plan_scopes};
use std::collections::HashSet;

/// What a solver kernel computes (see the module documentation).
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// The positions only.
    Position,
    /// The positions, then their analogs and the outputs.
    Fused,
    /// The analogs and the outputs at a position the caller gives.
    At,
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
    /// The `sin`/`cos` nodes that closed-form solves define.
    closed_trig: HashSet<NodeId>,
}

/// The slot holding Newton block `b`'s evaluation (`__ev{b}`: residuals, Jacobian, kept
/// values), which the runtime's iteration updates in place.
fn evaluation_ident(b: usize) -> Ident {
    format_ident!("__ev{}", b)
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
    // The sines and cosines of closed-form angles come from their solve.
    let closed_trig =
        if mode == Mode::At { HashSet::new() } else { super::closed_form::take_trig(plan, &mut sched.lets) };
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

/// `let [a, _, c] = *from;` binding only the used elements; nothing when none is used.
fn bind_used(ids: &[Ident], used: impl Fn(usize) -> bool, from: TokenStream) -> TokenStream {
    if !(0..ids.len()).any(&used) {
        return TokenStream::new();
    }
    let pats = ids.iter().enumerate().map(|(k, id)| if used(k) { quote!(#id) } else { quote!(_) });
    quote!(let [#(#pats),*] = *#from;)
}

/// Binds the inputs the kernel reads to locals (parameters are read as `self.a`).
pub(super) fn prologue(names: &Names, used: &HashSet<Leaf>) -> TokenStream {
    bind_used(&names.inputs, |k| used.contains(&Leaf::Input(k as u16)), quote!(__x))
}

/// Binds the unknowns the kernel reads from `__q`.
pub(super) fn bind_q(names: &Names, used: &HashSet<Leaf>) -> TokenStream {
    bind_used(&names.unknowns, |k| used.contains(&Leaf::Unknown(k as u16)), quote!(__q))
}

impl Kernel<'_> {
    fn lets(&self, scope: usize) -> TokenStream {
        self.names.lets(self.g, &self.sched, &self.sched.lets[scope])
    }

    fn op(&self, n: NodeId) -> TokenStream {
        self.names.operand(self.g, n)
    }

    fn unknowns_of(&self, bp: &BlockPlan) -> Vec<&Ident> {
        bp.unknowns.iter().map(|&u| &self.names.unknowns[u]).collect()
    }

    fn guess_arg(&self) -> TokenStream {
        if self.mode == Mode::At { quote!(None) } else { quote!(Some(__guess)) }
    }
}
