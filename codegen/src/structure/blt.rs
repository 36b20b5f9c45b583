//! Block-lower-triangular ordering (Tarjan's strongly connected components).

use super::matching::Matching;
use std::collections::BTreeSet;

/// One block of the BLT decomposition.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Block {
    /// Indices of the block's unknowns in the model's unknowns, in declaration order.
    pub unknowns: Vec<usize>,
    /// Indices of the block's equations in the model's equations, in declaration order.
    pub equations: Vec<usize>,
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
