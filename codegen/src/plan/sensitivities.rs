//! Parameter sensitivities (only under `#[kinloop(sensitivities)]`): per block the right-hand
//! sides of `J_bb s = -d f / d p` for positions, first and second analogs (solved on the same
//! factorisations), and the outputs' sensitivities by the chain rule.

use super::analogs::negated;
use super::columns::rows_from_columns;
use super::seeds::Seeds;
use super::stages::Stages;
use crate::graph::dag::{Graph, NodeId};

/// One stage: every parameter's derivative of every column in `columns`, parameter innermost,
/// negated when `rhs` (a right-hand side rather than a value).
fn stage(
    g: &mut Graph,
    seeds: &Seeds,
    rows: usize,
    columns: &[Vec<NodeId>],
    own: Option<usize>,
    st: u8,
    rhs: bool,
) -> Vec<Vec<NodeId>> {
    let np = seeds.np();
    let mut cols = Vec::new();
    for col in columns {
        for k in 0..np {
            let d = seeds.param(g, col, k, own, st);
            cols.push(if rhs { negated(g, d) } else { d });
        }
    }
    rows_from_columns(rows, cols)
}

/// The right-hand sides of block `b` (residuals `f`, full derivatives `first` and `second`).
pub fn block(
    g: &mut Graph,
    seeds: &Seeds,
    b: usize,
    f: &[NodeId],
    first: &[Vec<NodeId>],
    second: &[Vec<NodeId>],
) -> Stages {
    let rows = f.len();
    Stages {
        q: stage(g, seeds, rows, &[f.to_vec()], Some(b), 0, true),
        v: stage(g, seeds, rows, first, Some(b), 1, true),
        a: stage(g, seeds, rows, second, Some(b), 2, true),
    }
}

/// The outputs' sensitivities (`first[i]`: first derivatives along input `i`; `d2[o][p]`).
pub fn outputs(g: &mut Graph, seeds: &Seeds, outputs: &[NodeId], first: &[Vec<NodeId>], d2: &[Vec<NodeId>]) -> Stages {
    let rows = outputs.len();
    let second: Vec<Vec<NodeId>> = (0..seeds.pairs().len()).map(|p| d2.iter().map(|row| row[p]).collect()).collect();
    Stages {
        q: stage(g, seeds, rows, &[outputs.to_vec()], None, 0, false),
        v: stage(g, seeds, rows, first, None, 0, false),
        a: stage(g, seeds, rows, &second, None, 0, false),
    }
}
