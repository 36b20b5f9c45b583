//! Straight-line evaluations outside the solver kernels, at a position the caller gives: some
//! roots of the graph (the outputs, the guesses), and the residuals with the full Jacobian.

use super::kernel::{bind_q, prologue};
use super::literals::lit;
use super::names::Names;
use super::runtime_path::runtime;
use super::schedule::{ScopeKind, ScopeSpec, schedule};
use crate::graph::dag::{Leaf, NodeId};
use crate::plan::Plan;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use std::collections::HashSet;

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
