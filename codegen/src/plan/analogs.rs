//! Velocity and acceleration analogs of a block: the right-hand sides of `J_bb q'_b = -T_i f_b`
//! and `J_bb q''_b = -T_j T_i f_b`.

use super::block_plan::BlockPlan;
use super::columns::rows_from_columns;
use super::seeds::Seeds;
use crate::graph::dag::{Graph, NodeId};

/// The full first and second total derivatives of a block's residuals (every analog a leaf),
/// which the sensitivities differentiate further.
pub type Derivatives = (Vec<Vec<NodeId>>, Vec<Vec<NodeId>>);

/// Fills in `vel` and `acc` of block `b`; returns its full derivatives.
pub fn block(g: &mut Graph, seeds: &Seeds, b: usize, bp: &mut BlockPlan) -> Derivatives {
    let rows = bp.f.len();
    let mut vel = Vec::new();
    let mut full_first = Vec::new();
    for i in 0..seeds.ni() {
        let own = seeds.first(g, &bp.f, i, Some(b));
        vel.push(negated(g, own));
        full_first.push(seeds.first(g, &bp.f, i, None));
    }
    let mut acc = Vec::new();
    let mut full_second = Vec::new();
    for (i, j) in seeds.pairs() {
        let own = seeds.second(g, &full_first[i], j, Some(b));
        acc.push(negated(g, own));
        full_second.push(seeds.second(g, &full_first[i], j, None));
    }
    bp.vel = rows_from_columns(rows, vel);
    bp.acc = rows_from_columns(rows, acc);
    (full_first, full_second)
}

/// Minus each node (right-hand sides are minus a derivative; the graph folds `-(-a)` to `a`).
pub fn negated(g: &mut Graph, nodes: Vec<NodeId>) -> Vec<NodeId> {
    nodes.into_iter().map(|x| g.neg(x)).collect()
}
