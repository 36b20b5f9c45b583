//! Structural analysis of the equation/unknown incidence.
//!
//! * A maximum matching (augmenting paths) pairs each equation with an unknown it can be
//!   solved for. A perfect matching is necessary for the system to be regular.
//! * When it is not perfect, the Dulmage–Mendelsohn decomposition names the over-determined
//!   part (equations reachable from an unmatched equation by alternating paths: they cannot all
//!   hold) and the under-determined part (unknowns reachable from an unmatched unknown: they are
//!   left free), so diagnostics point at the offending loops and unknowns.
//! * Tarjan's strongly connected components of the matched dependency graph give the
//!   block-lower-triangular (BLT) order: blocks are solved one after another, each with its own
//!   small Newton, feeding solved unknowns forward. Dyads become small blocks; an Assur group of
//!   class IV stays one coupled block.

use crate::dag::{Leaf, NodeId};
use crate::model::Model;
use std::collections::BTreeSet;

/// One block of the BLT decomposition.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Block {
    /// Unknown indices, in declaration order.
    pub unknowns: Vec<usize>,
    /// Equation indices, in declaration order.
    pub equations: Vec<usize>,
}

/// The incidence: for each equation, the unknowns its residual depends on.
pub fn incidence(model: &Model) -> Vec<BTreeSet<usize>> {
    model.equations.iter().map(|e| unknowns_of(model, e.residual)).collect()
}

pub fn unknowns_of(model: &Model, node: NodeId) -> BTreeSet<usize> {
    model
        .graph
        .leaves_of(&[node])
        .into_iter()
        .filter_map(|l| match l {
            Leaf::Unknown(u) => Some(u as usize),
            _ => None,
        })
        .collect()
}

/// A maximum matching: `eq_to_unknown[e]` and `unknown_to_eq[u]`.
pub struct Matching {
    pub eq_to_unknown: Vec<Option<usize>>,
    pub unknown_to_eq: Vec<Option<usize>>,
}

impl Matching {
    pub fn is_perfect(&self) -> bool {
        self.eq_to_unknown.iter().all(Option::is_some) && self.unknown_to_eq.iter().all(Option::is_some)
    }
}

/// Maximum bipartite matching by augmenting paths (Kuhn), with an explicit stack.
pub fn maximum_matching(inc: &[BTreeSet<usize>], n_unknowns: usize) -> Matching {
    let adj: Vec<Vec<usize>> = inc.iter().map(|s| s.iter().copied().collect()).collect();
    let mut eq_to_unknown = vec![None; inc.len()];
    let mut unknown_to_eq: Vec<Option<usize>> = vec![None; n_unknowns];
    // Cheap greedy start, then augment.
    for (e, a) in adj.iter().enumerate() {
        if let Some(&u) = a.iter().find(|&&u| unknown_to_eq[u].is_none()) {
            eq_to_unknown[e] = Some(u);
            unknown_to_eq[u] = Some(e);
        }
    }
    for start in 0..adj.len() {
        if eq_to_unknown[start].is_some() {
            continue;
        }
        let mut visited = vec![false; n_unknowns];
        // Stack of (equation, next adjacency index); `via[e]` = unknown through which e was reached.
        let mut stack: Vec<(usize, usize)> = vec![(start, 0)];
        let mut via: Vec<Option<usize>> = vec![None; adj.len()];
        let mut found: Option<usize> = None;
        while let Some(&mut (e, ref mut k)) = stack.last_mut() {
            if *k >= adj[e].len() {
                stack.pop();
                continue;
            }
            let u = adj[e][*k];
            *k += 1;
            if visited[u] {
                continue;
            }
            visited[u] = true;
            match unknown_to_eq[u] {
                None => {
                    found = Some(u);
                    break;
                }
                Some(e2) => {
                    via[e2] = Some(u);
                    stack.push((e2, 0));
                }
            }
        }
        if let Some(mut u) = found {
            // Flip the alternating path along the stack, from its end back to `start`.
            while let Some((e, _)) = stack.pop() {
                let prev = eq_to_unknown[e];
                eq_to_unknown[e] = Some(u);
                unknown_to_eq[u] = Some(e);
                match (via[e], prev) {
                    (Some(_), Some(p)) => u = p,
                    _ => break,
                }
            }
        }
    }
    Matching { eq_to_unknown, unknown_to_eq }
}

/// The Dulmage–Mendelsohn coarse decomposition of a non-perfect matching.
pub struct Imbalance {
    /// Equations of the over-determined part.
    pub over_equations: BTreeSet<usize>,
    /// Unknowns appearing in the over-determined part.
    pub over_unknowns: BTreeSet<usize>,
    /// Unknowns of the under-determined part.
    pub under_unknowns: BTreeSet<usize>,
    /// Equations of the under-determined part.
    pub under_equations: BTreeSet<usize>,
}

pub fn dulmage_mendelsohn(inc: &[BTreeSet<usize>], n_unknowns: usize, m: &Matching) -> Imbalance {
    // Unknown -> equations containing it.
    let mut rev: Vec<Vec<usize>> = vec![Vec::new(); n_unknowns];
    for (e, s) in inc.iter().enumerate() {
        for &u in s {
            rev[u].push(e);
        }
    }
    // Over-determined: from unmatched equations, alternate (any edge to an unknown, matched edge
    // back to its equation).
    let mut over_equations = BTreeSet::new();
    let mut over_unknowns = BTreeSet::new();
    let mut stack: Vec<usize> = (0..inc.len()).filter(|&e| m.eq_to_unknown[e].is_none()).collect();
    while let Some(e) = stack.pop() {
        if !over_equations.insert(e) {
            continue;
        }
        for &u in &inc[e] {
            if over_unknowns.insert(u)
                && let Some(e2) = m.unknown_to_eq[u]
            {
                stack.push(e2);
            }
        }
    }
    // Under-determined: from unmatched unknowns, alternate (any edge to an equation, matched edge
    // back to its unknown).
    let mut under_unknowns = BTreeSet::new();
    let mut under_equations = BTreeSet::new();
    let mut stack: Vec<usize> = (0..n_unknowns).filter(|&u| m.unknown_to_eq[u].is_none()).collect();
    while let Some(u) = stack.pop() {
        if !under_unknowns.insert(u) {
            continue;
        }
        for &e in &rev[u] {
            if under_equations.insert(e)
                && let Some(u2) = m.eq_to_unknown[e]
            {
                stack.push(u2);
            }
        }
    }
    Imbalance { over_equations, over_unknowns, under_unknowns, under_equations }
}

/// Block-lower-triangular order from a perfect matching: Tarjan's SCC on "unknown u (via its
/// matched equation) depends on unknown v". Tarjan emits components dependencies-first, which is
/// the solve order.
pub fn blt(inc: &[BTreeSet<usize>], m: &Matching) -> Vec<Block> {
    let n = m.unknown_to_eq.len();
    let succ: Vec<Vec<usize>> = (0..n)
        .map(|u| match m.unknown_to_eq[u] {
            Some(e) => inc[e].iter().copied().filter(|&v| v != u).collect(),
            None => Vec::new(),
        })
        .collect();
    let mut index = vec![usize::MAX; n];
    let mut low = vec![0usize; n];
    let mut on_stack = vec![false; n];
    let mut stack: Vec<usize> = Vec::new();
    let mut next = 0usize;
    let mut blocks = Vec::new();
    for root in 0..n {
        if index[root] != usize::MAX {
            continue;
        }
        // Explicit DFS stack of (node, next successor position).
        let mut dfs: Vec<(usize, usize)> = vec![(root, 0)];
        index[root] = next;
        low[root] = next;
        next += 1;
        stack.push(root);
        on_stack[root] = true;
        while let Some(&mut (v, ref mut k)) = dfs.last_mut() {
            if *k < succ[v].len() {
                let w = succ[v][*k];
                *k += 1;
                if index[w] == usize::MAX {
                    index[w] = next;
                    low[w] = next;
                    next += 1;
                    stack.push(w);
                    on_stack[w] = true;
                    dfs.push((w, 0));
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            dfs.pop();
            if let Some(&(parent, _)) = dfs.last() {
                low[parent] = low[parent].min(low[v]);
            }
            if low[v] == index[v] {
                let mut comp = Vec::new();
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    comp.push(w);
                    if w == v {
                        break;
                    }
                }
                comp.sort_unstable();
                let mut equations: Vec<usize> = comp.iter().filter_map(|&u| m.unknown_to_eq[u]).collect();
                equations.sort_unstable();
                blocks.push(Block { unknowns: comp, equations });
            }
        }
    }
    blocks
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inc(rows: &[&[usize]]) -> Vec<BTreeSet<usize>> {
        rows.iter().map(|r| r.iter().copied().collect()).collect()
    }

    #[test]
    fn matching_needs_augmenting_paths() {
        // Greedy would match e0-u0 and leave e1 stuck; augmenting fixes it.
        let i = inc(&[&[0, 1], &[0]]);
        let m = maximum_matching(&i, 2);
        assert!(m.is_perfect());
        assert_eq!(m.eq_to_unknown, vec![Some(1), Some(0)]);
    }

    #[test]
    fn blt_orders_dependencies_first() {
        // e0: u0 (alone) ; e1: u0, u1 ; e2,e3: u2, u3 coupled, depending on u1.
        let i = inc(&[&[0], &[0, 1], &[1, 2, 3], &[2, 3]]);
        let m = maximum_matching(&i, 4);
        assert!(m.is_perfect());
        let b = blt(&i, &m);
        assert_eq!(
            b,
            vec![
                Block { unknowns: vec![0], equations: vec![0] },
                Block { unknowns: vec![1], equations: vec![1] },
                Block { unknowns: vec![2, 3], equations: vec![2, 3] },
            ]
        );
    }

    /// Size of a maximum matching by exhaustive search (small graphs only).
    fn brute_force(inc: &[BTreeSet<usize>], used: &mut Vec<bool>, e: usize) -> usize {
        if e == inc.len() {
            return 0;
        }
        let mut best = brute_force(inc, used, e + 1);
        for &u in &inc[e] {
            if !used[u] {
                used[u] = true;
                best = best.max(1 + brute_force(inc, used, e + 1));
                used[u] = false;
            }
        }
        best
    }

    #[test]
    fn matching_is_maximum_and_dm_parts_are_consistent_on_random_graphs() {
        let mut state = 0x5eed_u64;
        let mut next = move |n: u64| {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 33) % n
        };
        for _ in 0..2000 {
            let (n_eq, n_u) = (next(7) as usize, next(7) as usize);
            let i: Vec<BTreeSet<usize>> = (0..n_eq).map(|_| (0..n_u).filter(|_| next(3) == 0).collect()).collect();
            let m = maximum_matching(&i, n_u);
            let size = m.eq_to_unknown.iter().flatten().count();
            assert_eq!(size, brute_force(&i, &mut vec![false; n_u], 0), "{i:?}");
            // The two directions agree and every matched pair is an edge.
            for (e, u) in m.eq_to_unknown.iter().enumerate() {
                if let Some(u) = *u {
                    assert!(i[e].contains(&u));
                    assert_eq!(m.unknown_to_eq[u], Some(e));
                }
            }
            let d = dulmage_mendelsohn(&i, n_u, &m);
            // Over-determined: more equations than unknowns by exactly the unmatched equations.
            let free_eq = m.eq_to_unknown.iter().filter(|x| x.is_none()).count();
            let free_u = m.unknown_to_eq.iter().filter(|x| x.is_none()).count();
            assert_eq!(d.over_equations.len(), d.over_unknowns.len() + free_eq, "{i:?}");
            assert_eq!(d.under_unknowns.len(), d.under_equations.len() + free_u, "{i:?}");
            assert!(d.over_equations.is_disjoint(&d.under_equations), "{i:?}");
            assert!(d.over_unknowns.is_disjoint(&d.under_unknowns), "{i:?}");
            if m.is_perfect() {
                // The BLT blocks partition unknowns and equations, each block square.
                let blocks = blt(&i, &m);
                let mut seen_u: Vec<usize> = blocks.iter().flat_map(|b| b.unknowns.clone()).collect();
                seen_u.sort_unstable();
                assert_eq!(seen_u, (0..n_u).collect::<Vec<_>>());
                assert!(blocks.iter().all(|b| b.unknowns.len() == b.equations.len()));
            }
        }
    }

    #[test]
    fn dulmage_mendelsohn_finds_both_parts() {
        // e0, e1 both only in u0 (over-determined); u1, u2 only in e2 (under-determined).
        let i = inc(&[&[0], &[0], &[1, 2]]);
        let m = maximum_matching(&i, 3);
        assert!(!m.is_perfect());
        let d = dulmage_mendelsohn(&i, 3, &m);
        assert_eq!(d.over_equations, [0, 1].into_iter().collect());
        assert_eq!(d.over_unknowns, [0].into_iter().collect());
        assert_eq!(d.under_unknowns, [1, 2].into_iter().collect());
        assert_eq!(d.under_equations, [2].into_iter().collect());
    }
}
