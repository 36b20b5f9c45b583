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
//! checks and returns the state ([`finish`]). They are all methods of one [`Kernel`]
//! ([`generator`]: the plan, the names, the schedule and the scopes it is written from), with the
//! `let`s binding what it reads ([`bindings`]) and the slots of the Newton evaluations
//! ([`evaluation_slot`]).

mod analogs;
mod bindings;
mod entry;
mod evaluation_slot;
mod factor;
mod finish;
mod generator;
mod mode;
mod position;
mod scopes;

pub(super) use bindings::{bind_q, prologue};
pub use entry::closed_config_check;
pub use mode::Mode;

use super::names::Names;
use super::runtime_path::runtime;
use super::schedule::{ScopeSpec, schedule};
use crate::graph::dag::{Graph, Leaf, NodeId};
use crate::plan::Plan;
use generator::Kernel;
use proc_macro2::TokenStream;
use quote::quote;
use scopes::plan_scopes;
use std::collections::HashSet;

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
    body.extend(quote!(let mut __health = <#rt::Health as ::core::default::Default>::default();));
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
