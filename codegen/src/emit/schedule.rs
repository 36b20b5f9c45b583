//! Scheduling graph nodes into the scopes of a generated function.
//!
//! A generated solver is a sequence of scopes: per block a *pre* scope (values that do not
//! depend on the block's own unknowns, computed once) and a *loop* scope (inside the Newton
//! evaluation closure), then the analog and output scopes. Each node is computed once, in the
//! first scope that needs it; values computed inside a Newton closure that later scopes need are
//! handed out through the evaluation's `keep` array instead of being recomputed.

use crate::graph::dag::{Func, Graph, Leaf, NodeId, Op};
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
    /// Sums of angles: a sine's argument `a + b` free of the unknowns, with `b` a parameter
    /// angle or a constant and `a`'s sine and cosine also computed, keyed by the sine.
    /// `a`'s pair is scheduled no later than the sum's, so the sum's pair can be had from it by
    /// angle addition (see `Names::angle_sum`).
    pub sums: HashMap<NodeId, AngleSum>,
}

/// An argument `a + b` of a paired sine and cosine (see [`Schedule::sums`]).
#[derive(Clone, Copy, Debug)]
pub struct AngleSum {
    /// The argument `a + b`.
    pub sum: NodeId,
    /// The part that varies (an input's angle).
    pub a: NodeId,
    /// The parameter angle (or constant).
    pub b: NodeId,
    /// `a`'s paired sine and cosine.
    pub sin_cos_a: (NodeId, NodeId),
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
            stack.extend(g.op(n).operands());
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
    let sums = angle_sums(g, level, &sin_cos, &mut assigned);
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
        for n in g.op(m).operands() {
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

/// The paired arguments `a + b` free of the unknowns whose part `b` is a parameter angle and
/// whose `a` has its own pair; each such `a`'s pair moves to the sum's scope when that is earlier.
fn angle_sums(
    g: &Graph,
    level: &[i32],
    sin_cos: &HashMap<NodeId, (NodeId, NodeId)>,
    assigned: &mut HashMap<NodeId, usize>,
) -> HashMap<NodeId, AngleSum> {
    // Parameters and constants (`phi + gamma`, `phi + deg(30)`).
    let parameter = |n: NodeId| g.leaves_of(&[n]).iter().all(|l| matches!(l, Leaf::Param(_)));
    let mut sums = HashMap::new();
    let mut sines: Vec<NodeId> = sin_cos.values().map(|&(sn, _)| sn).collect();
    sines.sort_unstable();
    sines.dedup();
    for sn in sines {
        let Op::Func(_, arg) = g.op(sn) else { continue };
        let Op::Add(x, y) = g.op(arg) else { continue };
        let (a, b) = match (parameter(x), parameter(y)) {
            (false, true) => (x, y),
            (true, false) => (y, x),
            _ => continue,
        };
        let Some(&(sa, ca)) = g.find(Op::Func(Func::Sin, a)).and_then(|s| sin_cos.get(&s)) else { continue };
        // Every paired node is scheduled; `get` rather than indexing keeps the macro panic-free.
        let (Some(&at_a), Some(&at_sum)) = (assigned.get(&sa), assigned.get(&sn)) else { continue };
        if level[arg.index()] >= 0 {
            continue;
        }
        let first = at_a.min(at_sum);
        assigned.insert(sa, first);
        assigned.insert(ca, first);
        sums.insert(sn, AngleSum { sum: arg, a, b, sin_cos_a: (sa, ca) });
    }
    sums
}
