//! The outputs' analogs, by the chain rule through the unknowns' analog leaves.

use super::columns::rows_from_columns;
use super::seeds::Seeds;
use crate::graph::dag::{Graph, NodeId};

/// `(out_d1[o][i], out_d2[o][p], first)` where `first[i]` is the column of first derivatives
/// along input `i` (the sensitivities differentiate it further).
#[allow(clippy::type_complexity)]
pub fn analogs(
    g: &mut Graph,
    seeds: &Seeds,
    outputs: &[NodeId],
) -> (Vec<Vec<NodeId>>, Vec<Vec<NodeId>>, Vec<Vec<NodeId>>) {
    let first: Vec<Vec<NodeId>> = (0..seeds.ni()).map(|i| seeds.first(g, outputs, i, None)).collect();
    let second: Vec<Vec<NodeId>> =
        seeds.pairs().into_iter().map(|(i, j)| seeds.second(g, &first[i], j, None)).collect();
    (rows_from_columns(outputs.len(), first.clone()), rows_from_columns(outputs.len(), second), first)
}
