//! Maximum bipartite matching of equations to unknowns.

use std::collections::BTreeSet;

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
