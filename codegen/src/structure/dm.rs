//! The Dulmage–Mendelsohn decomposition: which part of a structurally singular system is
//! over-determined and which is under-determined.

use super::matching::Matching;
use std::collections::BTreeSet;

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

/// The Dulmage–Mendelsohn decomposition of the incidence `inc` (per equation, its unknowns)
/// from a maximum matching `m`: the over- and under-determined parts.
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
