//! Scheduling graph nodes into the scopes of a generated function.
//!
//! A generated solver is a sequence of scopes: per block a *pre* scope (values that do not
//! depend on the block's own unknowns, computed once) and a *loop* scope (inside the Newton
//! evaluation closure), then the analog and output scopes. Each node is computed once, in the
//! first scope that needs it; values computed inside a Newton closure that later scopes need are
//! handed out through the evaluation's `keep` array instead of being recomputed.

use crate::graph::angle_sums::{AngleSum, angle_sum, sources};
use crate::graph::dag::{Func, Graph, NodeId, Op};
use std::collections::HashMap;

/// Where a scope's code runs.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum ScopeKind {
    /// Straight-line code.
    Plain,
    /// Inside the Newton closure of a block; nodes of lower level go to the scope just before.
    Loop(usize),
}

/// What one scope of a generated function must compute.
pub struct ScopeSpec {
    /// Where it runs.
    pub kind: ScopeKind,
    /// The nodes it needs (its results).
    pub roots: Vec<NodeId>,
}

/// The nodes of each scope, and what the scopes hand to each other.
pub struct Schedule {
    /// Nodes computed in each scope, in topological order.
    pub lets: Vec<Vec<NodeId>>,
    /// Nodes a loop scope must hand out to other scopes.
    pub exports: Vec<Vec<NodeId>>,
    /// A sine and the cosine of the same argument, both scheduled in the same scope: they are
    /// computed together by one `sin_cos()` (see [`schedule`]). Keyed by each of the two.
    pub sin_cos: HashMap<NodeId, (NodeId, NodeId)>,
    /// Sines and cosines computed by angle addition (`graph::angle_sums`), keyed by each: their
    /// `sin a` and `cos a` are scheduled no later than they are, and paired.
    pub sums: HashMap<NodeId, AngleSum>,
}

/// Places every node needed by `scopes` in the first scope that needs it (a node of a `Loop`
/// scope that does not depend on the block's unknowns moves to the scope before), pairs sines
/// with cosines, and lists what each loop scope must hand out. `level` is
/// [`Plan::level`](crate::plan::Plan::level):
/// the highest block whose unknowns each node depends on.
pub fn schedule(g: &Graph, level: &[i32], scopes: &[ScopeSpec]) -> Schedule {
    let mut assigned: HashMap<NodeId, usize> = HashMap::new();
    for (s, spec) in scopes.iter().enumerate() {
        let mut stack: Vec<NodeId> = spec.roots.clone();
        while let Some(n) = stack.pop() {
            if assigned.contains_key(&n) || matches!(g.op(n), Op::Const(_) | Op::Leaf(_)) {
                continue;
            }
            let target = match spec.kind {
                ScopeKind::Loop(b) if level[n.index()] < b as i32 && s > 0 => s - 1,
                _ => s,
            };
            assigned.insert(n, target);
            // An angle sum's sine or cosine is computed from `sin a`, `cos a` and `b`, which
            // land in its scope (or an earlier one), never later.
            stack.extend(sources(g, n));
        }
    }
    // A sine and a cosine of the same argument are computed together (one `sin_cos`) in the
    // earlier of their two scopes; the argument is available there, since one of them already is.
    let cos_of: HashMap<NodeId, NodeId> = assigned
        .keys()
        .filter_map(|&m| match g.op(m) {
            Op::Func(Func::Cos, a) => Some((a, m)),
            _ => None,
        })
        .collect();
    let pairs: Vec<(NodeId, NodeId)> = assigned
        .keys()
        .filter_map(|&n| match g.op(n) {
            Op::Func(Func::Sin, a) => cos_of.get(&a).map(|&m| (n, m)),
            _ => None,
        })
        .collect();
    let mut sin_cos = HashMap::new();
    for (sn, cn) in pairs {
        let first = assigned[&sn].min(assigned[&cn]);
        assigned.insert(sn, first);
        assigned.insert(cn, first);
        sin_cos.insert(sn, (sn, cn));
        sin_cos.insert(cn, (sn, cn));
    }
    let sums: HashMap<NodeId, AngleSum> = assigned.keys().filter_map(|&n| Some((n, angle_sum(g, n)?))).collect();
    let mut lets = vec![Vec::new(); scopes.len()];
    for (&n, &s) in &assigned {
        lets[s].push(n);
    }
    for l in &mut lets {
        l.sort_unstable();
    }
    let mut exports = vec![Vec::new(); scopes.len()];
    let mut export = |n: NodeId, user_scope: usize| {
        if let Some(&s) = assigned.get(&n)
            && s != user_scope
            && matches!(scopes[s].kind, ScopeKind::Loop(_))
            && !exports[s].contains(&n)
        {
            exports[s].push(n);
        }
    };
    for (&m, &t) in &assigned {
        for n in sources(g, m) {
            export(n, t);
        }
    }
    for (t, spec) in scopes.iter().enumerate() {
        for &r in &spec.roots {
            export(r, t);
        }
    }
    for e in &mut exports {
        e.sort_unstable();
    }
    Schedule { lets, exports, sin_cos, sums }
}
