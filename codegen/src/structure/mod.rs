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

pub mod analysis;
mod blt;
pub mod diag;
mod dm;
mod imbalance;
mod matching;

pub use blt::{Block, blt};
pub use dm::{Imbalance, dulmage_mendelsohn};
pub use matching::maximum_matching;

use crate::graph::dag::{Leaf, NodeId};
use crate::semantics::model::Model;
use std::collections::BTreeSet;

/// The incidence: for each equation, the unknowns its residual depends on.
pub fn incidence(model: &Model) -> Vec<BTreeSet<usize>> {
    model.equations.iter().map(|e| unknowns_of(model, e.residual)).collect()
}

/// The unknowns a node of the graph depends on.
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
